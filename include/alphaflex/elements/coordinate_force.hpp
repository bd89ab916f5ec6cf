#pragma once
// Forces that act through a few scalar coordinates ε(q) of one or two frames: a spring-damper's
// length, a bushing's relative displacement and rotation, a joint's angle. With the generalized
// force law f(ε, ε̇, t) (f = ∂V/∂ε + damping: what resists ε; a motor's −T),
//
//   r = J_εᵀ f,   ε̇ = J_ε v,   J_ε = ∂ε(q ∘ exp(δ))/∂δ,
//   K = ∂r/∂δ' = Σ_k f_k H_kᵀ + J_εᵀ (f_ε J_ε + f_ε̇ D),   C = J_εᵀ f_ε̇ J_ε,
//   H_k(j, i) = ∂²ε_k/∂δ'_j∂δ_i at q ∘ exp(δ') ∘ exp(δ),   D(l, j) = Σ_i H_l(j, i) v_i = ∂ε̇_l/∂δ'_j,
//
// on the right-trivialized increments of R³×SO(3) that the integrator uses (model/node.hpp), at
// fixed v (ẋ in the world frame, Ω in the body frame): the velocity-dependent part of K, D, is the
// derivative of the damping force's rate with respect to the positions, which a tangent at fixed
// ε̇ would miss. ε is written once as a template on the scalar; J_ε and every H_k come from one
// nested forward AD evaluation with the seeding of model/spatial_kernel.hpp (outer perturbation
// applied first, as S_t needs on the group), so r, K and C are exact and nothing is differentiated
// by hand or by finite differences.
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

/// Largest number of coordinates of one force element (a bushing: 3 displacements, 3 rotations).
constexpr int kMaxForceCoordinates = 6;
using CoordinateVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxForceCoordinates, 1>;
using CoordinateMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxForceCoordinates, kMaxForceCoordinates>;
template <class S> using CoordinateValues = Eigen::Matrix<S, Eigen::Dynamic, 1, 0, kMaxForceCoordinates, 1>;

/// The law's answer at (ε, ε̇, t): f, f_ε = ∂f/∂ε and f_ε̇ = ∂f/∂ε̇.
struct GeneralizedForce {
  CoordinateVector f;
  CoordinateMatrix f_eps, f_rate;
};

namespace coordinate_force_detail {

template <int N, class Coordinates, class Law>
void evaluate_fixed(const Coordinates& coordinates, const Law& law, const LocalState& s, LocalResidual& out,
                    bool tangent) {
  using A2 = ad::FixedAD2<N>;
  constexpr int nf = N / 6;
  const auto p = kernel_detail::poses(s.q, nf);
  std::array<Pose<A2>, nf> ps;
  for (int k = 0; k < nf; ++k) ps[static_cast<size_t>(k)] = kernel_detail::seeded_pose2<N>(p[static_cast<size_t>(k)], 6 * k);
  CoordinateValues<A2> e;
  coordinates(ps.data(), e);
  const Eigen::Index m = e.size();
  CoordinateVector eps(m);
  Eigen::Matrix<double, Eigen::Dynamic, N, 0, kMaxForceCoordinates, N> J(m, N);
  for (Eigen::Index k = 0; k < m; ++k) {
    eps[k] = e[k].value().value();
    J.row(k) = e[k].value().derivatives().transpose();
  }
  const Eigen::Matrix<double, N, 1> v = s.v;
  const CoordinateVector rate = J * v;
  GeneralizedForce g;
  law(eps, rate, s, g);
  out.r += J.transpose() * g.f;
  if (!tangent) return;
  Eigen::Matrix<double, N, N> K = Eigen::Matrix<double, N, N>::Zero();
  Eigen::Matrix<double, Eigen::Dynamic, N, 0, kMaxForceCoordinates, N> D(m, N);
  for (Eigen::Index k = 0; k < m; ++k) {
    Eigen::Matrix<double, N, N> H;  // H(j, i) = ∂²ε_k/∂δ'_j∂δ_i
    for (int j = 0; j < N; ++j) H.row(j) = e[k].derivatives()[j].derivatives().transpose();
    K += g.f[k] * H.transpose();
    D.row(k) = (H * v).transpose();
  }
  K += J.transpose() * (g.f_eps * J + g.f_rate * D);
  out.K += K;
  out.C += J.transpose() * g.f_rate * J;
}

}  // namespace coordinate_force_detail

/// Adds r, K, C of the coordinate force to `out`. `coordinates(const Pose<S>* frames,
/// CoordinateValues<S>& eps)` is a template on S giving ε of the element's one or two frames;
/// `law(eps, rate, state, GeneralizedForce&)` gives f and its derivatives.
template <class Coordinates, class Law>
void evaluate_coordinate_force(const Coordinates& coordinates, const Law& law, const LocalState& s,
                               LocalResidual& out, bool tangent) {
  if (kernel_detail::frames_in(s.q) == 1)
    coordinate_force_detail::evaluate_fixed<6>(coordinates, law, s, out, tangent);
  else
    coordinate_force_detail::evaluate_fixed<12>(coordinates, law, s, out, tangent);
}

/// ε in doubles (for outputs and energies).
template <class Coordinates>
CoordinateVector coordinate_values(const Coordinates& coordinates, const Eigen::VectorXd& q) {
  const auto p = kernel_detail::poses(q, kernel_detail::frames_in(q));
  CoordinateValues<double> e;
  coordinates(p.data(), e);
  return e;
}

}  // namespace alphaflex
