#include "alphaflex/elements/planar_beam.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace alphaflex {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The strain measure depends on q through z = (Δx, Δy, ᾱ, Δθ) = T q + const, with
//   Δx = x_B − x_A, Δy = y_B − y_A, ᾱ = (θ_A + θ_B)/2 + (φ_A + φ_B)/2, Δθ = θ_B − θ_A + φ_B − φ_A:
// derivatives are taken in z (4 variables) and mapped by T.
//   T = [[−1, 0, 0, 1, 0, 0], [0, −1, 0, 0, 1, 0], [0, 0, ½, 0, 0, ½], [0, 0, −1, 0, 0, 1]].
using Matrix46 = Eigen::Matrix<double, 4, 6>;

Matrix46 make_T() {
  Matrix46 T = Matrix46::Zero();
  T(0, 0) = -1.0, T(0, 3) = 1.0;
  T(1, 1) = -1.0, T(1, 4) = 1.0;
  T(2, 2) = 0.5, T(2, 5) = 0.5;
  T(3, 2) = -1.0, T(3, 5) = 1.0;
  return T;
}

const Matrix46 kT = make_T();

void require_positive(double value, const std::string& beam, const char* what) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    std::ostringstream m;
    m << "planar beam '" << beam << "': " << what << " must be positive and finite (got " << value << ")";
    throw std::invalid_argument(m.str());
  }
}

}  // namespace

void PlanarBeam::lengthening(double a, double& g, double& dg, double& ddg) {
  // g(α) = G(h), h = α/2: g' = G'/2, g'' = G''/4.
  const double h = 0.5 * a;
  if (std::abs(a) < kSeriesBelow) {
    // G = Σ c_n x^n, G' = Σ 2n c_n h^{2n−1}, G'' = Σ 2n(2n − 1) c_n h^{2n−2}, x = h² (Horner).
    const double x = h * h;
    double G = 0.0, G1 = 0.0, G2 = 0.0;
    for (int n = kSeriesTerms - 1; n >= 0; --n) {
      G = kSeries[n] + x * G;
      if (n >= 1) {
        G1 = 2.0 * n * kSeries[n] + x * G1;
        G2 = 2.0 * n * (2.0 * n - 1.0) * kSeries[n] + x * G2;
      }
    }
    g = G;
    dg = 0.5 * h * G1;
    ddg = 0.25 * G2;
    return;
  }
  const double s = std::sin(h), c = std::cos(h);
  g = h / s;
  dg = 0.5 * (s - h * c) / (s * s);                              // G' = (sin h − h cos h)/sin²h
  ddg = 0.25 * (h * (1.0 + c * c) - 2.0 * s * c) / (s * s * s);  // G'' = (h(1 + cos²h) − sin 2h)/sin³h
}

PlanarBeam::PlanarBeam(std::string name, int node_a, int node_b, double EA, double GA, double EI, double rhoA,
                       double rhoI, const Eigen::Vector3d& state_a, const Eigen::Vector3d& state_b,
                       double section_angle_a, double section_angle_b, const Eigen::Vector2d& gravity,
                       double damping)
    : Element(std::move(name), {node_a, node_b}), c_(EA, GA, EI), rhoA_(rhoA), rhoI_(rhoI), eta_(damping), g_(gravity) {
  const std::string& n = this->name();
  if (!(std::isfinite(damping) && damping >= 0.0)) {
    std::ostringstream m;
    m << "planar beam '" << n << "': the material damping eta must be zero or positive and finite, in s (got " << damping
      << ")";
    throw std::invalid_argument(m.str());
  }
  require_positive(EA, n, "the axial stiffness EA");
  require_positive(GA, n, "the shear stiffness GA");
  require_positive(EI, n, "the bending stiffness EI");
  require_positive(rhoA, n, "the mass per length rhoA");
  require_positive(rhoI, n, "the rotary inertia per length rhoI");
  if (node_a == node_b) throw std::invalid_argument("planar beam '" + n + "' needs two different nodes");
  if (!state_a.allFinite() || !state_b.allFinite() || !std::isfinite(section_angle_a) ||
      !std::isfinite(section_angle_b) || !gravity.allFinite())
    throw std::invalid_argument("planar beam '" + n + "': node states, section angles and gravity must be finite");
  const double turn = section_angle_b - section_angle_a;
  if (std::abs(turn) >= kPi) {
    std::ostringstream m;
    m << "planar beam '" << n << "': its end sections turn by " << turn
      << " rad relative to each other in the reference; the element needs less than pi: use shorter elements";
    throw std::invalid_argument(m.str());
  }
  offset_ = {section_angle_a - state_a[2], section_angle_b - state_b[2]};
  // d0 with L0 = 1 and no reference strain, then L0 = |U0| (the arc length of the reference arc)
  // and ε0 = d0/L0.
  L0_ = 1.0;
  eps0_.setZero();
  Eigen::Matrix<double, 6, 1> q0;
  q0 << state_a, state_b;
  const Eigen::Vector3d d0 = strain_of<double>(q0.data());
  const double L0 = d0.head<2>().norm();
  const double scale = std::max({1.0, state_a.head<2>().norm(), state_b.head<2>().norm()});
  if (!(L0 > 1e-12 * scale)) {
    std::ostringstream m;
    m << "planar beam '" << n << "' has zero reference length (nodes at (" << state_a[0] << ", " << state_a[1]
      << ") and (" << state_b[0] << ", " << state_b[1] << "))";
    throw std::invalid_argument(m.str());
  }
  L0_ = L0;
  eps0_ = d0 / L0;
}

double PlanarBeam::elastic_energy(const Eigen::VectorXd& q) const {
  const Eigen::Vector3d e = strain(q);
  return 0.5 * L0_ * e.dot(c_.cwiseProduct(e));
}

void PlanarBeam::evaluate(const LocalState& st, LocalResidual& out, bool tangent) const {
  const double* q = st.q.data();
  const double aA = q[2] + offset_[0], aB = q[5] + offset_[1];
  const double dth = aB - aA, mean = 0.5 * (aA + aB);
  const double dx = q[3] - q[0], dy = q[4] - q[1];
  const double c = std::cos(mean), s = std::sin(mean);
  double g, dg, ddg;
  lengthening(dth, g, dg, ddg);
  // P = R(ᾱ)ᵀ Δx (chord in the mean section frame), d = (g P, Δθ).
  const double P1 = c * dx + s * dy, P2 = c * dy - s * dx;
  const Eigen::Vector3d eps(g * P1 / L0_ - eps0_[0], g * P2 / L0_ - eps0_[1], dth / L0_ - eps0_[2]);
  Eigen::Vector3d f = c_.cwiseProduct(eps);  // (N, V, M)

  // Bz = ∂d/∂z (rows d1, d2, d3; columns Δx, Δy, ᾱ, Δθ); ∂P/∂ᾱ = (P2, −P1).
  Eigen::Matrix<double, 3, 4> Bz;
  Bz << g * c, g * s, g * P2, dg * P1,  //
      -g * s, g * c, -g * P1, dg * P2,  //
      0.0, 0.0, 0.0, 1.0;
  // Material damping: f += η C ε̇, ε̇ = Bz ż / L0 with ż = T q̇ (header comment).
  Eigen::Vector4d zdot = Eigen::Vector4d::Zero();
  if (eta_ > 0.0) {
    zdot = kT * st.v.head<6>();
    f += (eta_ / L0_) * c_.cwiseProduct(Bz * zdot);
  }
  const Eigen::Vector4d rz = Bz.transpose() * f;
  double* r = out.r.data();
  r[0] -= rz[0];
  r[1] -= rz[1];
  r[2] += 0.5 * rz[2] - rz[3];
  r[3] += rz[0];
  r[4] += rz[1];
  r[5] += 0.5 * rz[2] + rz[3];

  // Inertia (consistent mass of linear interpolation) and gravity.
  const double mt = rhoA_ * L0_ / 6.0, mr = rhoI_ * L0_ / 6.0;
  const double* a = st.qdd.data();
  for (int k = 0; k < 2; ++k) {
    r[k] += mt * (2.0 * a[k] + a[3 + k]);
    r[3 + k] += mt * (a[k] + 2.0 * a[3 + k]);
  }
  r[2] += mr * (2.0 * a[2] + a[5]);
  r[5] += mr * (a[2] + 2.0 * a[5]);
  const double w = st.load_factor * 0.5 * rhoA_ * L0_;
  r[0] -= w * g_.x();
  r[1] -= w * g_.y();
  r[3] -= w * g_.x();
  r[4] -= w * g_.y();
  if (!tangent) return;

  // K = Tᵀ (Bzᵀ C Bz / L0 + f1 ∂²d1/∂z² + f2 ∂²d2/∂z²) T.
  Eigen::Matrix4d Kz = Bz.transpose() * (c_ / L0_).asDiagonal() * Bz;
  const double fP = f[0] * P1 + f[1] * P2;
  Eigen::Matrix4d H = Eigen::Matrix4d::Zero();
  H(0, 2) = -g * (f[0] * s + f[1] * c);
  H(0, 3) = dg * (f[0] * c - f[1] * s);
  H(1, 2) = g * (f[0] * c - f[1] * s);
  H(1, 3) = dg * (f[0] * s + f[1] * c);
  H(2, 2) = -g * fP;
  H(2, 3) = dg * (f[0] * P2 - f[1] * P1);
  H(3, 3) = ddg * fP;
  Kz += H + H.transpose();
  Kz.diagonal() -= H.diagonal();
  if (eta_ > 0.0) {
    // ∂(η C ε̇)/∂z at fixed q̇: rows żᵀ ∂²d_k/∂z² (d3 = Δθ is linear), then Bzᵀ of it; and
    // C_t = Tᵀ η Bzᵀ C Bz T / L0.
    Eigen::Matrix<double, 3, 4> D = Eigen::Matrix<double, 3, 4>::Zero();
    const double zx = zdot[0], zy = zdot[1], za = zdot[2], zt = zdot[3];
    D.row(0) << -g * s * za + dg * c * zt, g * c * za + dg * s * zt, -g * s * zx + g * c * zy - g * P1 * za + dg * P2 * zt,
        dg * c * zx + dg * s * zy + dg * P2 * za + ddg * P1 * zt;
    D.row(1) << -g * c * za - dg * s * zt, -g * s * za + dg * c * zt, -g * c * zx - g * s * zy - g * P2 * za - dg * P1 * zt,
        -dg * s * zx + dg * c * zy - dg * P1 * za + ddg * P2 * zt;
    const Eigen::Matrix<double, 3, 4> CB = (eta_ / L0_) * c_.asDiagonal() * Bz;
    Kz.noalias() += CB.transpose() * D;
    out.C.topLeftCorner<6, 6>().noalias() += kT.transpose() * (Bz.transpose() * CB) * kT;
  }
  out.K.topLeftCorner<6, 6>().noalias() += kT.transpose() * Kz * kT;

  for (int k = 0; k < 2; ++k) {
    out.M(k, k) += 2.0 * mt;
    out.M(k, 3 + k) += mt;
    out.M(3 + k, k) += mt;
    out.M(3 + k, 3 + k) += 2.0 * mt;
  }
  out.M(2, 2) += 2.0 * mr;
  out.M(2, 5) += mr;
  out.M(5, 2) += mr;
  out.M(5, 5) += 2.0 * mr;
}

bool PlanarBeam::mass_action(const LocalState& /*s*/, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const {
  // The consistent mass of evaluate() (linear interpolation).
  const double mt = rhoA_ * L0_ / 6.0, mr = rhoI_ * L0_ / 6.0;
  Mw.resize(6);
  for (int k = 0; k < 2; ++k) {
    Mw[k] = mt * (2.0 * w[k] + w[3 + k]);
    Mw[3 + k] = mt * (w[k] + 2.0 * w[3 + k]);
  }
  Mw[2] = mr * (2.0 * w[2] + w[5]);
  Mw[5] = mr * (w[2] + 2.0 * w[5]);
  return true;
}

std::vector<CellField> PlanarBeam::cell_fields() const {
  return {{"N"}, {"V"}, {"M"}, {"axial_strain"}, {"shear_strain"}, {"curvature"}};
}

void PlanarBeam::output(const LocalState& s, Eigen::VectorXd& values) const {
  const Eigen::Vector3d e = strain(s.q);
  values.resize(6);
  values.head<3>() = c_.cwiseProduct(e);
  if (eta_ > 0.0) {
    // The whole section forces C (ε + η ε̇): ε̇ by the derivative of ε along q̇ (forward AD).
    std::array<ad::AD1, 6> q;
    for (int k = 0; k < 6; ++k) q[static_cast<size_t>(k)] = ad::AD1(s.q[k], ad::Derivatives1::Constant(1, s.v[k]));
    const Eigen::Matrix<ad::AD1, 3, 1> ea = strain_of<ad::AD1>(q.data());
    for (int k = 0; k < 3; ++k) values[k] += eta_ * c_[k] * ea[k].derivatives()[0];
  }
  values.tail<3>() = e;
}

}  // namespace alphaflex
