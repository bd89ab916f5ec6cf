// The tie of an interface node to a reduced flexible body (joints/reduced_interface_tie.hpp,
// docs/theory/reduced_bodies.md "Interface points").
#include "alphaflex/joints/reduced_interface_tie.hpp"

#include <array>
#include <stdexcept>

namespace alphaflex {
namespace {

// Kernel variables: δx_B, δθ_B (0–5), δx_f, δθ_f (6–11), z = [u; ψ] (12–17).
constexpr int kVars = 18;
using Z = Eigen::Matrix<double, 6, 1>;
using A1 = ad::FixedAD1<kVars>;
using Along = ad::FixedAD2<1>;

/// a + b τ + c τ²/2 with τ both the inner and the outer variable (the mixed derivative is d²/dτ²).
Along along(double a, double b, double c) {
  using D = ad::FixedAD1<1>;
  return Along(D(a, D::DerType(b)), Along::DerType(D(b, D::DerType(c))));
}

/// (x + τ v_x, R(I + τ v̂ + τ² v̂²/2)) = (x, R) ∘ exp(τ v) + O(τ³).
Pose<Along> moving(const Pose<double>& p, const Eigen::Vector3d& vx, const Eigen::Vector3d& vth) {
  const Eigen::Matrix3d Rv = p.R * hat<double>(vth), Rvv = Rv * hat<double>(vth);
  Pose<Along> out;
  for (int i = 0; i < 3; ++i) out.x[i] = along(p.x[i], vx[i], 0.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.R(i, j) = along(p.R(i, j), Rv(i, j), Rvv(i, j));
  return out;
}

/// ∂Φ/∂(δ_B, δ_f, z) (6 × 18) in closed form, for any scalar: d = x_B − x_f − R_f(X_a + u) and
/// aᵢ·bⱼ, aᵢ = R_a eᵢ, R_a = R_f C, C = R̄_a exp(ψ̂), bⱼ = R_B eⱼ. With δx in world axes and
/// R → R exp(δθ̂) (so δ(R w) = −R ŵ δθ) and exp(ψ + δψ) = exp(ψ) exp((T(ψ)δψ)^):
///   ∂d/∂(δx_B, δx_f, δθ_f, u) = (I, −I, R_f (X_a + u)^, −R_f),
///   ∂(aᵢ·bⱼ)/∂δθ_B = (eⱼ × R_Bᵀaᵢ)ᵀ, ∂/∂δθ_f = (Ceᵢ × R_fᵀbⱼ)ᵀ, ∂/∂ψ = (eᵢ × R_aᵀbⱼ)ᵀ T(ψ)
/// (−vᵀŵ = (w × v)ᵀ). None of these formulas uses RᵀR = I, so they hold at the frames
/// R(I + δθ'^) that `tie_second` differentiates them at. The AD1 Jacobian of the equations it
/// replaces cost ~25 % of a reduced slider-crank's run (docs/benchmarks/reduced.md);
/// test_reduced_interface_tie.cpp compares the two.
///
/// With the offset (p, R_o) (the tied node welded at p, turned by R_o, in the block node's frame):
/// x_A = x_f + R_f (X_a + u + C p), a_i = R_f C R_o e_i, so ∂d/∂δθ_f = R_f (X_a + u + C p)^,
/// ∂d/∂ψ = R_a p̂ T(ψ) (δ(R_a p) = −R_a p̂ T δψ), and the rotation rows take oᵢ = R_o eᵢ for eᵢ
/// (∂/∂δθ_f: (C oᵢ × R_fᵀbⱼ)ᵀ, ∂/∂ψ: (oᵢ × R_aᵀbⱼ)ᵀ T(ψ)); p = 0, R_o = I is the plain tie.
template <class S>
Eigen::Matrix<S, 6, kVars> jacobian(const ReducedInterfaceTie& tie, const Pose<S>& b, const Pose<S>& f, const Vec3<S>& u,
                                    const Vec3<S>& psi) {
  const Mat3<S> C = tie.rotation().template cast<S>() * exp_so3<S>(psi), Ra = f.R * C, Tpsi = tangent_so3<S>(psi);
  const Vec3<S> p = tie.offset_position().template cast<S>();
  const Mat3<S> Ro = tie.offset_rotation().template cast<S>();
  const Mat3<S> CRo = C * Ro, RaRo = Ra * Ro;
  Eigen::Matrix<S, 6, kVars> J = Eigen::Matrix<S, 6, kVars>::Zero();
  J.template block<3, 3>(0, 0).setIdentity();
  J.template block<3, 3>(0, 6) = -Mat3<S>::Identity();
  J.template block<3, 3>(0, 9) = f.R * hat<S>(Vec3<S>(tie.position().template cast<S>() + u + C * p));
  J.template block<3, 3>(0, 12) = -f.R;
  J.template block<3, 3>(0, 15) = Ra * hat<S>(p) * Tpsi;
  const int pair[3][2] = {{1, 2}, {2, 0}, {0, 1}};  // rows 3–5: a₂·b₃, a₃·b₁, a₁·b₂
  for (int r = 0; r < 3; ++r) {
    const int i = pair[r][0], j = pair[r][1];
    const Vec3<S> oi = Ro.col(i), ej = Vec3<S>::Unit(j);
    J.template block<1, 3>(3 + r, 3) = ej.cross(Vec3<S>(b.R.transpose() * RaRo.col(i))).transpose();
    J.template block<1, 3>(3 + r, 9) = Vec3<S>(CRo.col(i)).cross(Vec3<S>(f.R.transpose() * b.R.col(j))).transpose();
    J.template block<1, 3>(3 + r, 15) = oi.cross(Vec3<S>(Ra.transpose() * b.R.col(j))).transpose() * Tpsi;
  }
  return J;
}

/// Φ (by the scalar-generic `equations` in double: the AD path's value part to a few ulps) and
/// ∂Φ/∂(δ_B, δ_f, z).
void tie_first(const ReducedInterfaceTie& tie, const Pose<double>& b, const Pose<double>& f, const Z& z, Eigen::VectorXd& phi,
           Eigen::Matrix<double, 6, kVars>& J) {
  const Eigen::Vector3d u = z.head<3>(), psi = z.tail<3>();
  phi.resize(6);
  tie.equations<double>(b, f, u, psi, phi.data());
  J = jacobian<double>(tie, b, f, u, psi);
}

/// H(i, j) = ∂/∂δ'_j ∂(λᵀΦ)/∂δ_i over the 18 kernel variables (outer perturbation first, as
/// model/spatial_kernel.hpp's `second`): forward AD1 of the closed-form gradient Jᵀλ at the
/// perturbed frames (x + δx', R(I + δθ'^)) and amplitudes z + δz'. Exact: `jacobian` holds at any
/// frame matrix, and only first derivatives in δ' are taken, which R(I + δθ'^) and R exp(δθ'^)
/// share (spatial_kernel.hpp's header). Nested AD2 of the equations, which it replaces, cost
/// ~18 times as much (test_reduced_interface_tie.cpp compares the two to round-off).
Eigen::Matrix<double, kVars, kVars> tie_second(const ReducedInterfaceTie& tie, const Pose<double>& b, const Pose<double>& f, const Z& z,
                                           const Eigen::VectorXd& lambda) {
  const Pose<A1> bs = kernel_detail::seeded_pose1<kVars>(b, 0), fs = kernel_detail::seeded_pose1<kVars>(f, 6);
  Vec3<A1> u, psi;
  for (int i = 0; i < 3; ++i) {
    u[i] = A1(z[i], A1::DerType::Unit(12 + i));
    psi[i] = A1(z[3 + i], A1::DerType::Unit(15 + i));
  }
  const Eigen::Matrix<A1, 6, kVars> J = jacobian<A1>(tie, bs, fs, u, psi);
  Eigen::Matrix<double, kVars, kVars> H = Eigen::Matrix<double, kVars, kVars>::Zero();
  for (int r = 0; r < 6; ++r) {
    if (lambda[r] == 0.0) continue;
    for (int i = 0; i < kVars; ++i) H.row(i) += lambda[r] * J(r, i).derivatives().transpose();
  }
  return H;
}

}  // namespace

ReducedInterfaceTie::ReducedInterfaceTie(std::string name, int tied, int frame, const std::vector<int>& amplitudes,
                                         const Eigen::Vector3d& position, const Eigen::Matrix3d& rotation, Eigen::MatrixXd shape,
                                         const Eigen::Vector3d& offset_position, const Eigen::Matrix3d& offset_rotation)
    : Constraint(std::move(name), [&] {
        std::vector<int> n{tied, frame};
        n.insert(n.end(), amplitudes.begin(), amplitudes.end());
        return n;
      }()),
      position_(position),
      rotation_(rotation),
      shape_(std::move(shape)),
      offset_position_(offset_position),
      offset_rotation_(offset_rotation) {
  if (shape_.rows() != 6 || shape_.cols() != static_cast<Eigen::Index>(amplitudes.size()))
    throw std::invalid_argument("reduced interface tie '" + this->name() + "': the shape must have 6 rows and one column per amplitude (" +
                                std::to_string(amplitudes.size()) + ")");
}

std::string ReducedInterfaceTie::equation_name(int k) const {
  static const char* names[6] = {"x", "y", "z", "a2·b3", "a3·b1", "a1·b2"};
  return k >= 0 && k < 6 ? names[k] : "";
}

Eigen::Matrix<double, 6, 1> ReducedInterfaceTie::z_of(const Eigen::VectorXd& q) const {
  const Eigen::Index m = shape_.cols();
  if (q.size() != 14 + m)
    throw std::invalid_argument("reduced interface tie '" + name() + "': expected the configuration of two frames and " +
                                std::to_string(m) + " amplitudes");
  return shape_ * q.tail(m);
}

void ReducedInterfaceTie::evaluate(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  const Z z = z_of(q);
  Eigen::Matrix<double, 6, kVars> J;
  tie_first(*this, pose_of(q.data()), pose_of(q.data() + 7), z, phi, J);
  // Φ_ξ = Φ_z Φ_a: z is linear in ξ.
  phi_q.resize(6, 12 + shape_.cols());
  phi_q.leftCols<12>() = J.leftCols<12>();
  phi_q.rightCols(shape_.cols()) = J.rightCols<6>() * shape_;
}

void ReducedInterfaceTie::geometric_stiffness(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda,
                                              Eigen::MatrixXd& k) const {
  const Eigen::Index m = shape_.cols();
  const Eigen::Matrix<double, kVars, kVars> H = tie_second(*this, pose_of(q.data()), pose_of(q.data() + 7), z_of(q), lambda);
  // Pᵀ H P with P = diag(I₁₂, Φ_a): exact, z being linear in ξ (no second derivative of z).
  k.resize(12 + m, 12 + m);
  k.topLeftCorner<12, 12>() = H.topLeftCorner<12, 12>();
  k.topRightCorner(12, m) = H.topRightCorner<12, 6>() * shape_;
  k.bottomLeftCorner(m, 12) = shape_.transpose() * H.bottomLeftCorner<6, 12>();
  k.bottomRightCorner(m, m) = shape_.transpose() * H.bottomRightCorner<6, 6>() * shape_;
}

void ReducedInterfaceTie::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double,
                                            Eigen::VectorXd& c) const {
  // d²/dτ² Φ(q ∘ exp(τ v)) at τ = 0: the frames along R(I + τv̂ + τ²v̂²/2), z + τ Φ_a ξ̇ (scleronomic).
  const Z z = z_of(q), zdot = shape_ * v.tail(shape_.cols());
  const Pose<Along> b = moving(pose_of(q.data()), v.segment<3>(0), v.segment<3>(3));
  const Pose<Along> f = moving(pose_of(q.data() + 7), v.segment<3>(6), v.segment<3>(9));
  Vec3<Along> u, psi;
  for (int i = 0; i < 3; ++i) {
    u[i] = along(z[i], zdot[i], 0.0);
    psi[i] = along(z[3 + i], zdot[3 + i], 0.0);
  }
  std::array<Along, 6> out;
  equations(b, f, u, psi, out.data());
  c.resize(6);
  for (int i = 0; i < 6; ++i) c[i] = out[static_cast<size_t>(i)].derivatives()[0].derivatives()[0];
}

JointReaction ReducedInterfaceTie::reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const {
  Eigen::VectorXd phi;
  Eigen::MatrixXd J;
  evaluate(q, t, phi, J);
  const Eigen::VectorXd g = -J.transpose() * lambda;  // generalized force of the tie on its nodes
  const Pose<double> b = pose_of(q.data());
  JointReaction r;
  r.location = b.x;
  r.force = g.segment<3>(0);
  r.moment = b.R * g.segment<3>(3);
  r.frame = b.R;
  return r;
}

}  // namespace alphaflex
