#include "alphaflex/elements/geometrically_exact_beam.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace alphaflex {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Throws unless R is a rotation matrix (orthonormal, det +1) to 1e-9.
void require_rotation(const Eigen::Matrix3d& R, const std::string& what) {
  const double orth = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!R.allFinite() || orth > 1e-9 || R.determinant() < 0.0) {
    std::ostringstream m;
    m << what << " is not a rotation matrix (|RᵀR − I| = " << orth << ", det = " << R.determinant() << ")";
    throw std::invalid_argument(m.str());
  }
}

/// The elastic energy W(q) = (L0/2) εᵀ C ε as a spatial kernel (spatial_kernel.hpp): its
/// kernel_jacobian is r = ∂W/∂δ, its kernel_second with weight 1 is K = ∂r/∂δ' (the reference).
struct ElasticEnergy {
  const GeometricallyExactBeam& beam;

  template <class S>
  void operator()(const Pose<S>* frames, const S& /*t*/, KernelVector<S>& out) const {
    const Vec6<S> e = beam.strain_of<S>(frames[0], frames[1]);
    const auto& c = beam.section().stiffness();
    S w = S(0);
    for (int k = 0; k < 6; ++k) w += S(c[k]) * e[k] * e[k];
    out.resize(1);
    out[0] = S(0.5 * beam.reference_length()) * w;
  }
};

/// The closed-form elastic residual as a spatial kernel: its kernel_jacobian is (r, K).
struct ElasticResidual {
  const GeometricallyExactBeam& beam;

  template <class S>
  void operator()(const Pose<S>* frames, const S& /*t*/, KernelVector<S>& out) const {
    out = beam.elastic_residual_of<S>(frames[0], frames[1]);
  }
};

/// The elastic and damping residual at the nodes' velocities v (constants of the kernel): its
/// kernel_jacobian is (r, K at fixed v).
struct ViscoelasticResidual {
  const GeometricallyExactBeam& beam;
  const double* v;

  template <class S>
  void operator()(const Pose<S>* frames, const S& /*t*/, KernelVector<S>& out) const {
    out = beam.section_residual_of<S>(frames[0], frames[1], v);
  }
};

/// m_ij = ∫ N_i N_j ds / L0 for linear shape functions.
constexpr double kMass[2][2] = {{1.0 / 3.0, 1.0 / 6.0}, {1.0 / 6.0, 1.0 / 3.0}};

}  // namespace

GeometricallyExactBeam::GeometricallyExactBeam(std::string name, int node_a, int node_b, const BeamSection& section,
                                               const Pose<double>& pose_a, const Pose<double>& pose_b,
                                               const Eigen::Matrix3d& section_a, const Eigen::Matrix3d& section_b,
                                               const Eigen::Vector3d& gravity, double damping)
    : Element(std::move(name), {node_a, node_b}), section_(section), eta_(damping), g_(gravity) {
  if (node_a == node_b) throw std::invalid_argument("a beam element needs two different nodes");
  if (!(std::isfinite(damping) && damping >= 0.0)) {
    std::ostringstream m;
    m << "the material damping eta must be zero or positive and finite, in s (got " << damping << ")";
    throw std::invalid_argument(m.str());
  }
  require_rotation(pose_a.R, "the rotation of node A");
  require_rotation(pose_b.R, "the rotation of node B");
  require_rotation(section_a, "the section frame at end A");
  require_rotation(section_b, "the section frame at end B");
  offset_[0] = pose_a.R.transpose() * section_a;
  offset_[1] = pose_b.R.transpose() * section_b;
  // The reference strain measure d0 with L0 = 1, then L0 = |U0|: the arc length of the reference
  // helix x(σ) = x_A + R_secA ∫₀^σ exp(τ θ0^) dτ U0, σ ∈ [0, 1], whose tangent has length |U0|.
  const Eigen::Matrix3d Rrel = section_a.transpose() * section_b;
  const Eigen::Vector3d th0 = log_so3<double>(Rrel);
  if (th0.norm() > kPi - 1e-6) {
    std::ostringstream m;
    m << "the end sections of the beam element turn by " << th0.norm()
      << " rad relative to each other; log SE(3) needs less than pi: use shorter elements";
    throw std::invalid_argument(m.str());
  }
  const Vector6d d0 = se3_log<double>(Rrel, section_a.transpose() * (pose_b.x - pose_a.x));
  L0_ = d0.head<3>().norm();
  const double scale = std::max({1.0, pose_a.x.norm(), pose_b.x.norm()});
  if (!(L0_ > 1e-12 * scale)) throw std::invalid_argument("the beam element has zero reference length");
  eps0_ = d0 / L0_;
}

template <class S>
Vec6<S> GeometricallyExactBeam::strain_of(const Pose<S>& a, const Pose<S>& b) const {
  // Section frames R_i O_i; H_A⁻¹ H_B = (R_sAᵀ R_sB, R_sAᵀ (x_B − x_A)).
  const Mat3<S> RsA = a.R * offset_[0].cast<S>();
  const Mat3<S> RsB = b.R * offset_[1].cast<S>();
  const Vec6<S> d = se3_log<S>(Mat3<S>(RsA.transpose() * RsB), Vec3<S>(RsA.transpose() * (b.x - a.x)));
  return d / S(L0_) - eps0_.cast<S>();
}

template <class S>
Eigen::Matrix<S, 12, 1> GeometricallyExactBeam::section_residual_of(const Pose<S>& a, const Pose<S>& b,
                                                                    const double* v) const {
  // Section frames, relative motion H_AB = H_A⁻¹ H_B = (R_rel, p) and d = log H_AB (as strain_of).
  const Mat3<S> RsA = a.R * offset_[0];
  const Mat3<S> RsB = b.R * offset_[1];
  const Mat3<S> Rrel = RsA.transpose() * RsB;
  const Vec3<S> p = RsA.transpose() * (b.x - a.x);
  const Vec6<S> d = se3_log<S>(Rrel, p);
  // Section forces f = C ε, then g = T_SE(3)(d)⁻ᵀ f, so that r = Bᵀ f (header comment).
  const Vector6d& c = section_.stiffness();
  Vec6<S> f;
  for (int k = 0; k < 6; ++k) f[k] = c[k] * (d[k] / L0_ - eps0_[k]);
  if (v) {
    // Kelvin–Voigt: f += η C ε̇, ε̇ = T_SE(3)(d)⁻¹ w / L0 with w = ξ̇_B − Ad(H_AB⁻¹) ξ̇_A,
    // ξ̇_i = ((R_i O_i)ᵀ ẋ_i, O_iᵀ Ω_i) (header comment):
    // w = (R_sBᵀ (ẋ_B − ẋ_A) + R_relᵀ (p × O_Aᵀ Ω_A),  O_Bᵀ Ω_B − R_relᵀ O_Aᵀ Ω_A).
    const Eigen::Map<const Eigen::Matrix<double, 12, 1>> vel(v);
    const Vec3<S> dxdt = (vel.segment<3>(6) - vel.segment<3>(0)).template cast<S>();
    const Vec3<S> phiA = (offset_[0].transpose() * vel.segment<3>(3)).template cast<S>();
    const Vec3<S> phiB = (offset_[1].transpose() * vel.segment<3>(9)).template cast<S>();
    Vec6<S> w;
    w.template head<3>() = RsB.transpose() * dxdt + Rrel.transpose() * p.cross(phiA);
    w.template tail<3>() = phiB - Rrel.transpose() * phiA;
    const Vec6<S> rate = tangent_se3_inverse_times<S>(d, w);
    const double eta = eta_;
    for (int k = 0; k < 6; ++k) f[k] += S(eta * c[k] / L0_) * rate[k];
  }
  const Vec6<S> g = tangent_se3_inverse_transpose_times<S>(d, f);
  const Vec3<S> gU = g.template head<3>(), gth = g.template tail<3>();
  const Vec3<S> RgU = Rrel * gU;
  const Vec3<S> FB = RsB * gU;  // = R_sA R_rel g_U, the force on B (world components)
  Eigen::Matrix<S, 12, 1> r;
  r.template segment<3>(0) = -FB;
  r.template segment<3>(3) = -(offset_[0] * Vec3<S>(p.cross(RgU) + Rrel * gth));
  r.template segment<3>(6) = FB;
  r.template segment<3>(9) = offset_[1] * gth;
  return r;
}

template Vec6<double> GeometricallyExactBeam::strain_of<double>(const Pose<double>&, const Pose<double>&) const;
template Vec6<ad::FixedAD1<12>> GeometricallyExactBeam::strain_of<ad::FixedAD1<12>>(const Pose<ad::FixedAD1<12>>&,
                                                                                    const Pose<ad::FixedAD1<12>>&) const;
template Vec6<ad::FixedAD2<12>> GeometricallyExactBeam::strain_of<ad::FixedAD2<12>>(const Pose<ad::FixedAD2<12>>&,
                                                                                    const Pose<ad::FixedAD2<12>>&) const;
template Eigen::Matrix<double, 12, 1> GeometricallyExactBeam::section_residual_of<double>(const Pose<double>&,
                                                                                        const Pose<double>&,
                                                                                        const double*) const;
template Eigen::Matrix<ad::FixedAD1<12>, 12, 1> GeometricallyExactBeam::section_residual_of<ad::FixedAD1<12>>(
    const Pose<ad::FixedAD1<12>>&, const Pose<ad::FixedAD1<12>>&, const double*) const;

Eigen::Matrix<double, 6, 12> GeometricallyExactBeam::strain_rate_operator(const Eigen::VectorXd& q) const {
  // B_ε = T_SE(3)(d)⁻¹ G / L0 with G v = w (section_residual_of):
  // G = [[−R_sBᵀ, R_relᵀ p̂ O_Aᵀ, R_sBᵀ, 0], [0, −R_relᵀ O_Aᵀ, 0, O_Bᵀ]].
  const Pose<double> a = pose_of(q.data()), b = pose_of(q.data() + 7);
  const Eigen::Matrix3d RsA = a.R * offset_[0], RsB = b.R * offset_[1];
  const Eigen::Matrix3d Rrel = RsA.transpose() * RsB;
  const Eigen::Vector3d p = RsA.transpose() * (b.x - a.x);
  Eigen::Matrix<double, 6, 12> G = Eigen::Matrix<double, 6, 12>::Zero();
  G.block<3, 3>(0, 0) = -RsB.transpose();
  G.block<3, 3>(0, 3) = Rrel.transpose() * hat<double>(p) * offset_[0].transpose();
  G.block<3, 3>(0, 6) = RsB.transpose();
  G.block<3, 3>(3, 3) = -Rrel.transpose() * offset_[0].transpose();
  G.block<3, 3>(3, 9) = offset_[1].transpose();
  return tangent_se3_inverse<double>(se3_log<double>(Rrel, p)) * G / L0_;
}

GeometricallyExactBeam::Vector6d GeometricallyExactBeam::strain(const Eigen::VectorXd& q) const {
  return strain_of<double>(pose_of(q.data()), pose_of(q.data() + 7));
}

double GeometricallyExactBeam::elastic_energy(const Eigen::VectorXd& q) const {
  const Vector6d e = strain(q);
  return 0.5 * L0_ * e.dot(section_.stiffness().cwiseProduct(e));
}

void GeometricallyExactBeam::elastic_forces(const Eigen::VectorXd& q, Eigen::VectorXd& r, Eigen::MatrixXd* K) const {
  if (K) {
    kernel_jacobian(ElasticResidual{*this}, q, 0.0, r, *K);
    return;
  }
  r = elastic_residual_of<double>(pose_of(q.data()), pose_of(q.data() + 7));
}

void GeometricallyExactBeam::elastic_forces_from_energy(const Eigen::VectorXd& q, Eigen::VectorXd& r,
                                                        Eigen::MatrixXd* K) const {
  const ElasticEnergy energy{*this};
  Eigen::VectorXd w;
  Eigen::MatrixXd dW;
  kernel_jacobian(energy, q, 0.0, w, dW);
  r = dW.row(0).transpose();
  if (K) kernel_second(energy, q, 0.0, Eigen::VectorXd::Ones(1), *K);
}

void GeometricallyExactBeam::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  if (eta_ > 0.0) {
    // Kelvin–Voigt: K at fixed v by AD of the same kernel, C_t = η L0 B_εᵀ C B_ε (header comment).
    if (tangent) {
      KernelValue r;
      KernelJacobian K;
      kernel_jacobian(ViscoelasticResidual{*this, s.v.data()}, s.q, s.t, r, K);
      out.r += r;
      out.K += K;
      const Eigen::Matrix<double, 6, 12> B = strain_rate_operator(s.q);
      out.C.topLeftCorner<12, 12>().noalias() +=
          (eta_ * L0_) * B.transpose() * section_.stiffness().asDiagonal() * B;
    } else {
      out.r += section_residual_of<double>(pose_of(s.q.data()), pose_of(s.q.data() + 7), s.v.data());
    }
  } else if (tangent) {
    KernelValue r;  // fixed capacity: no heap allocation per element
    KernelJacobian K;
    kernel_jacobian(ElasticResidual{*this}, s.q, s.t, r, K);
    out.r += r;
    out.K += K;
  } else {
    out.r += elastic_residual_of<double>(pose_of(s.q.data()), pose_of(s.q.data() + 7));
  }
  add_inertia(s, out, tangent);
  // Gravity, consistent for linear interpolation: ∫ N_i ρA g ds = ρA L0/2 g.
  const Eigen::Vector3d fg = s.load_factor * 0.5 * section_.rhoA() * L0_ * g_;
  out.r.segment<3>(0) -= fg;
  out.r.segment<3>(6) -= fg;
}

void GeometricallyExactBeam::add_inertia(const LocalState& s, LocalResidual& out, bool tangent) const {
  const double mA = section_.rhoA() * L0_;
  const Eigen::Matrix3d J = section_.rotary_inertia();
  // Section angular velocities and accelerations Ω̄_i = O_iᵀ Ω_i, Ω̄̇_i = O_iᵀ Ω̇_i.
  std::array<Eigen::Vector3d, 2> W, Wd;
  for (int i = 0; i < 2; ++i) {
    W[i] = offset_[i].transpose() * s.v.segment<3>(6 * i + 3);
    Wd[i] = offset_[i].transpose() * s.qdd.segment<3>(6 * i + 3);
  }
  std::array<Eigen::Vector3d, 2> rbar{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  std::array<std::array<Eigen::Matrix3d, 2>, 2> cbar;
  for (auto& row : cbar)
    for (auto& c : row) c.setZero();
  // Linear in the accelerations: ∫ N_i N_j ds J̄ Ω̄̇_j.
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      out.r.segment<3>(6 * i) += mA * kMass[i][j] * s.qdd.segment<3>(6 * j);
      rbar[i] += L0_ * kMass[i][j] * (J * Wd[j]);
    }
  // Gyroscopic: ∫ N_i Ω̄(s) × J̄ Ω̄(s) ds, a cubic in s, and its derivative
  // ∂/∂Ω̄_j = ∫ N_i N_j (Ω̄^ J̄ − (J̄ Ω̄)^) ds, a cubic as well: 2-point Gauss is exact.
  const double gp = 0.5 / std::sqrt(3.0);
  for (const double xi : {0.5 - gp, 0.5 + gp}) {
    const double N[2] = {1.0 - xi, xi}, weight = 0.5 * L0_;
    const Eigen::Vector3d Ws = N[0] * W[0] + N[1] * W[1], JW = J * Ws;
    const Eigen::Vector3d gyro = Ws.cross(JW);
    const Eigen::Matrix3d dgyro = hat<double>(Ws) * J - hat<double>(JW);
    for (int i = 0; i < 2; ++i) {
      rbar[i] += weight * N[i] * gyro;
      for (int j = 0; j < 2; ++j) cbar[i][j] += weight * N[i] * N[j] * dgyro;
    }
  }
  for (int i = 0; i < 2; ++i) out.r.segment<3>(6 * i + 3) += offset_[i] * rbar[i];
  if (!tangent) return;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      out.M.block<3, 3>(6 * i, 6 * j) += mA * kMass[i][j] * Eigen::Matrix3d::Identity();
      out.M.block<3, 3>(6 * i + 3, 6 * j + 3) += L0_ * kMass[i][j] * offset_[i] * J * offset_[j].transpose();
      out.C.block<3, 3>(6 * i + 3, 6 * j + 3) += offset_[i] * cbar[i][j] * offset_[j].transpose();
    }
}

bool GeometricallyExactBeam::mass_action(const LocalState& /*s*/, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const {
  // The q̈-linear part of add_inertia with q̈ = w: ∫ N_i N_j ds (ρA w_j, O_i J̄ O_jᵀ w_j).
  const double mA = section_.rhoA() * L0_;
  const Eigen::Matrix3d J = section_.rotary_inertia();
  Mw.setZero(12);
  std::array<Eigen::Vector3d, 2> Jw;
  for (int j = 0; j < 2; ++j) Jw[j] = J * (offset_[j].transpose() * w.segment<3>(6 * j + 3));
  for (int i = 0; i < 2; ++i) {
    Eigen::Vector3d rbar = Eigen::Vector3d::Zero();
    for (int j = 0; j < 2; ++j) {
      Mw.segment<3>(6 * i) += mA * kMass[i][j] * w.segment<3>(6 * j);
      rbar += L0_ * kMass[i][j] * Jw[j];
    }
    Mw.segment<3>(6 * i + 3) = offset_[i] * rbar;
  }
  return true;
}

std::vector<CellField> GeometricallyExactBeam::cell_fields() const {
  return {{"N"}, {"V2"}, {"V3"}, {"T"}, {"M2"}, {"M3"}, {"axial_strain"}, {"shear_strain_2"}, {"shear_strain_3"},
          {"twist"}, {"curvature_2"}, {"curvature_3"}};
}

void GeometricallyExactBeam::output(const LocalState& s, Eigen::VectorXd& values) const {
  const Vector6d e = strain(s.q);
  values.resize(12);
  values.head<6>() = section_.stiffness().cwiseProduct(e);
  // With material damping the section forces are the whole C (ε + η ε̇).
  if (eta_ > 0.0)
    values.head<6>() += eta_ * section_.stiffness().cwiseProduct(strain_rate_operator(s.q) * s.v);
  values.tail<6>() = e;
}

}  // namespace alphaflex
