#pragma once
// Exact derivatives of functions of spatial frames on R³×SO(3), for element and joint kernels.
//
// A kernel is a functor written once as a template on the scalar,
//     template <class S> void operator()(const Pose<S>* frames, const S& t, KernelVector<S>& out) const;
// of the poses of its nodes (in node order) and of time. The functions below evaluate it with
// automatic differentiation (core/autodiff.hpp) on the right-trivialized perturbations
// (x, R) ∘ exp(δ) = (x + δx, R exp(δθ^)) that the Lie-group integrator uses (node.hpp):
//   jacobian:      J = ∂f(q ∘ exp(δ))/∂δ |₀                              (Φ_q, or a gradient)
//   second:        H_ij = ∂/∂δ'_j [ ∂(wᵀf)(q ∘ exp(δ') ∘ exp(δ))/∂δ_i ] |₀  (K_Φ = ∂(Φ_qᵀλ)/∂δ', or K)
//   along_motion:  d/dτ and d²/dτ² of f(q ∘ exp(τ v), t + τ) at τ = 0     (Φ_q v + Φ_t, and
//                  (Φ_q v)_q v + 2Φ_qt v + Φ_tt, the acceleration term of the consistent start,
//                  since q(t + τ) = q ∘ exp(τ v + τ² v̇/2 + O(τ³)) on the group)
// The order in `second` matters on a group: the outer perturbation is applied first, so H is the
// derivative of the residual at a perturbed configuration, which is what S_t needs; it is not
// symmetric in general.
//
// How the perturbations are applied (exact, and cheap):
//  - jacobian and second take only first derivatives with respect to each perturbation: d/dδ_i,
//    and in second the mixed ∂²/∂δ'_j∂δ_i (never ∂²/∂δ_i∂δ_k). exp(δθ^) = I + δθ^ + O(|δθ|²), and
//    the O(|δθ|²) terms enter neither: with M(δ', δ) = R exp(δθ'^) exp(δθ^) or R(I + δθ'^)(I + δθ^)
//    alike, ∂M/∂δθ_k = R ê_k and ∂²M/∂δθ'_j∂δθ_k = R ê_j ê_k at 0, so f(M) has the same first and
//    mixed derivatives (chain rule on f as a function of the matrix entries; f(M) is only ever
//    differentiated at δ = 0, where M = R is a rotation). So the frames are R(I + δθ^), seeded
//    directly as AD numbers (value R, first derivatives R ê_k, mixed R ê_j ê_k: seeded_pose1/2) —
//    no AD through exp and its series.
//  - along_motion needs d²/dτ² along one direction, where exp's second-order term counts: there
//    the frames are R(I + τv̂ + τ²v̂²/2) = R exp(τv̂) + O(τ³), exact for d/dτ and d²/dτ² at 0.
//  - The derivative vectors have a fixed size, 6 per frame (ad::FixedAD1<6>, <12> and the nested
//    ad::FixedAD2<6>, <12>; FixedAD2<1> for along_motion): no run-time sizes, no resizing of the
//    zero derivative vectors of constants, loops unrolled. Kernels have one or two frames (the
//    capacity of core/autodiff.hpp's types as well).
// Measured (thread CPU time, revolute joint between two nodes with an angle driver): geometric
// stiffness 425 µs with AD2 through exp and dynamic-size derivatives → 145 µs with R(I + δθ^)
// (same bits of H) → 47–84 µs with fixed sizes and direct seeding (the range is from the kernel
// compiled in a scratch program and in the library); Φ_q 7.3 → 2.3 µs; acceleration term
// 42 → 0.5 µs. docs/theory/beam.md, Cost.
#include <Eigen/Dense>
#include <array>
#include <stdexcept>

#include "alphaflex/core/autodiff.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/core/time_function.hpp"

namespace alphaflex {

namespace ad {
/// Fixed-size first derivatives with respect to N variables (the kernels' scalars, see the header).
template <int N> using FixedAD1 = Eigen::AutoDiffScalar<Eigen::Matrix<double, N, 1>>;
/// Nested: second (mixed) derivatives with respect to N outer and N inner variables.
template <int N> using FixedAD2 = Eigen::AutoDiffScalar<Eigen::Matrix<FixedAD1<N>, N, 1>>;

/// Plain value of any (nested) Eigen::AutoDiffScalar (core/autodiff.hpp has AD1 and AD2).
template <class D>
double value(const Eigen::AutoDiffScalar<D>& x) {
  return value(x.value());
}
}  // namespace ad

/// Largest number of outputs of one kernel (a two-node beam's residual: 12).
constexpr int kMaxKernelOutputs = 16;
template <class S> using KernelVector = Eigen::Matrix<S, Eigen::Dynamic, 1, 0, kMaxKernelOutputs, 1>;
/// Fixed-capacity results of kernel_jacobian (at most kMaxKernelOutputs outputs, 12 variables).
using KernelValue = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxKernelOutputs, 1>;
using KernelJacobian = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxKernelOutputs, 12>;

/// Position and rotation of a frame.
template <class S>
struct Pose {
  Vec3<S> x;
  Mat3<S> R;
};

/// The pose stored in 7 configuration numbers (x, y, z, q_w, q_x, q_y, q_z).
inline Pose<double> pose_of(const double* q) {
  Pose<double> p;
  p.x = Eigen::Vector3d(q[0], q[1], q[2]);
  p.R = Eigen::Quaterniond(q[3], q[4], q[5], q[6]).normalized().toRotationMatrix();
  return p;
}

/// The 7 configuration numbers of a pose.
inline void store_pose(const Eigen::Vector3d& x, const Eigen::Matrix3d& R, double* q) {
  const Eigen::Quaterniond r(R);
  q[0] = x.x();
  q[1] = x.y();
  q[2] = x.z();
  q[3] = r.w();
  q[4] = r.x();
  q[5] = r.y();
  q[6] = r.z();
}

template <class S>
Pose<S> cast_pose(const Pose<double>& p) {
  return Pose<S>{p.x.template cast<S>(), p.R.template cast<S>()};
}

/// p ∘ exp(δ): (x + δx, R exp(δθ^)).
template <class S>
Pose<S> perturbed(const Pose<S>& p, const Vec3<S>& dx, const Vec3<S>& dth) {
  return Pose<S>{p.x + dx, p.R * exp_so3<S>(dth)};
}

/// A frame fixed to node `slot` of a joint or force element (0 or 1 in its node list; −1: the
/// ground), given by its position and rotation in the node's frame (world frame for the ground).
struct SpatialMarker {
  int slot = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();

  template <class S>
  Pose<S> pose(const Pose<S>* frames) const {
    if (slot < 0) return cast_pose<S>(Pose<double>{position, rotation});
    const Pose<S>& f = frames[slot];
    return Pose<S>{f.x + f.R * position.template cast<S>(), f.R * rotation.template cast<S>()};
  }
};

/// f(t) for a plain or differentiated time, exact to second order: f + f' dt + f'' dt²/2 about the
/// plain value of t (so the derivatives carried by t get f' and f'').
template <class S>
S time_value(const TimeFunction& f, const S& t) {
  const double t0 = ad::value(t);
  const S dt = t - S(t0);
  return S(f.value(t0)) + S(f.derivative(t0)) * dt + S(0.5 * f.second_derivative(t0)) * dt * dt;
}

namespace kernel_detail {

/// At most two frames (12 variables), as core/autodiff.hpp's kMaxVariables.
constexpr int kMaxFrames = 2;
using Poses = std::array<Pose<double>, kMaxFrames>;

inline int frames_in(const Eigen::VectorXd& q) {
  const int nf = static_cast<int>(q.size() / 7);
  if (nf < 1 || nf > kMaxFrames || q.size() != 7 * nf)
    throw std::invalid_argument("a spatial kernel takes one or two frames (7 or 14 configuration numbers)");
  return nf;
}

inline Poses poses(const Eigen::VectorXd& q, int nf) {
  Poses p;
  for (int k = 0; k < nf; ++k) p[static_cast<size_t>(k)] = pose_of(q.data() + 7 * k);
  return p;
}

/// R êₘ, m = 0, 1, 2: ∂/∂δθₘ of R(I + δθ^).
inline std::array<Eigen::Matrix3d, 3> rotation_directions(const Eigen::Matrix3d& R) {
  std::array<Eigen::Matrix3d, 3> E;
  for (int m = 0; m < 3; ++m) E[static_cast<size_t>(m)] = R * hat<double>(Eigen::Vector3d::Unit(m));
  return E;
}

/// (x + δx, R(I + δθ^)) as AD1<N>, δ = variables `first` … `first` + 5.
template <int N>
Pose<ad::FixedAD1<N>> seeded_pose1(const Pose<double>& p, int first) {
  using A = ad::FixedAD1<N>;
  using D = typename A::DerType;
  const auto E = rotation_directions(p.R);
  Pose<A> s;
  for (int i = 0; i < 3; ++i) s.x[i] = A(p.x[i], D::Unit(first + i));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      D d = D::Zero();
      for (int m = 0; m < 3; ++m) d[first + 3 + m] = E[static_cast<size_t>(m)](i, j);
      s.R(i, j) = A(p.R(i, j), d);
    }
  return s;
}

/// (x + δx' + δx, R(I + δθ'^)(I + δθ^)) as AD2<N>: outer δ', inner δ, both variables `first` … +5.
/// Value R, inner and outer derivatives R êₘ, mixed ∂²/∂δθ'ₐ∂δθ_b = R êₐ ê_b.
template <int N>
Pose<ad::FixedAD2<N>> seeded_pose2(const Pose<double>& p, int first) {
  using A1 = ad::FixedAD1<N>;
  using A2 = ad::FixedAD2<N>;
  using D1 = typename A1::DerType;
  using D2 = typename A2::DerType;
  const auto E = rotation_directions(p.R);
  std::array<std::array<Eigen::Matrix3d, 3>, 3> EE;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      EE[static_cast<size_t>(a)][static_cast<size_t>(b)] =
          E[static_cast<size_t>(a)] * hat<double>(Eigen::Vector3d::Unit(b));
  Pose<A2> s;
  for (int i = 0; i < 3; ++i) {
    D2 outer;
    for (int o = 0; o < N; ++o) outer[o] = A1(o == first + i ? 1.0 : 0.0, D1::Zero());
    s.x[i] = A2(A1(p.x[i], D1::Unit(first + i)), outer);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      D1 d = D1::Zero();
      for (int m = 0; m < 3; ++m) d[first + 3 + m] = E[static_cast<size_t>(m)](i, j);
      D2 outer;
      for (int o = 0; o < N; ++o) {
        const int a = o - first - 3;
        if (a < 0 || a > 2) {
          outer[o] = A1(0.0, D1::Zero());
          continue;
        }
        D1 mixed = D1::Zero();
        for (int b = 0; b < 3; ++b) mixed[first + 3 + b] = EE[static_cast<size_t>(a)][static_cast<size_t>(b)](i, j);
        outer[o] = A1(d[o], mixed);
      }
      s.R(i, j) = A2(A1(p.R(i, j), d), outer);
    }
  return s;
}

template <int N, class Fn, class Value, class Jacobian>
void jacobian_fixed(const Fn& f, const Poses& p, double t, Value& value, Jacobian& J) {
  using A = ad::FixedAD1<N>;
  std::array<Pose<A>, N / 6> ps;
  for (int k = 0; k < N / 6; ++k) ps[static_cast<size_t>(k)] = seeded_pose1<N>(p[static_cast<size_t>(k)], 6 * k);
  KernelVector<A> r;
  f(ps.data(), A(t), r);
  value.resize(r.size());
  J.resize(r.size(), N);
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    value[i] = r[i].value();
    J.row(i) = r[i].derivatives().transpose();
  }
}

template <int N, class Fn>
void second_fixed(const Fn& f, const Poses& p, double t, const Eigen::VectorXd& w, Eigen::MatrixXd& H) {
  using A = ad::FixedAD2<N>;
  std::array<Pose<A>, N / 6> ps;
  for (int k = 0; k < N / 6; ++k) ps[static_cast<size_t>(k)] = seeded_pose2<N>(p[static_cast<size_t>(k)], 6 * k);
  KernelVector<A> r;
  f(ps.data(), A(t), r);
  H = Eigen::MatrixXd::Zero(N, N);
  for (Eigen::Index m = 0; m < r.size(); ++m) {
    if (w[m] == 0.0) continue;
    for (int j = 0; j < N; ++j) H.col(j) += w[m] * r[m].derivatives()[j].derivatives();
  }
}

}  // namespace kernel_detail

/// f(q, t) in doubles.
template <class Fn, class Value>
void kernel_value(const Fn& f, const Eigen::VectorXd& q, double t, Value& out) {
  const auto p = kernel_detail::poses(q, kernel_detail::frames_in(q));
  KernelVector<double> r;
  f(p.data(), t, r);
  out = r;
}

/// f and J = ∂f(q ∘ exp(δ))/∂δ (rows: outputs, columns: 6 per frame).
/// Value and J may be fixed-capacity Eigen types (KernelValue, KernelJacobian below): no heap
/// allocation in element kernels.
template <class Fn, class Value, class Jacobian>
void kernel_jacobian(const Fn& f, const Eigen::VectorXd& q, double t, Value& value, Jacobian& J) {
  const int nf = kernel_detail::frames_in(q);
  const auto p = kernel_detail::poses(q, nf);
  if (nf == 1) kernel_detail::jacobian_fixed<6>(f, p, t, value, J);
  else kernel_detail::jacobian_fixed<12>(f, p, t, value, J);
}

/// H_ij = ∂/∂δ'_j ∂(wᵀf)/∂δ_i at q ∘ exp(δ') ∘ exp(δ) (see the header comment).
template <class Fn>
void kernel_second(const Fn& f, const Eigen::VectorXd& q, double t, const Eigen::VectorXd& w, Eigen::MatrixXd& H) {
  const int nf = kernel_detail::frames_in(q);
  const auto p = kernel_detail::poses(q, nf);
  if (nf == 1) kernel_detail::second_fixed<6>(f, p, t, w, H);
  else kernel_detail::second_fixed<12>(f, p, t, w, H);
}

/// first = d/dτ f(q ∘ exp(τ v), t + τ s), second = d²/dτ² of the same, at τ = 0 (s = 1 moves
/// time along, s = 0 freezes it).
template <class Fn>
void kernel_along_motion(const Fn& f, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t, double s,
                         Eigen::VectorXd& first, Eigen::VectorXd& second) {
  using A1 = ad::FixedAD1<1>;
  using A2 = ad::FixedAD2<1>;
  using D1 = A1::DerType;
  using D2 = A2::DerType;
  // τ as both the inner and the outer variable: the mixed derivative is d²/dτ². A number
  // a + b τ + c τ²/2 is A2(A1(a, b), (A1(b, c))).
  auto number = [](double a, double b, double c) { return A2(A1(a, D1(b)), D2(A1(b, D1(c)))); };
  const int nf = kernel_detail::frames_in(q);
  const auto p = kernel_detail::poses(q, nf);
  std::array<Pose<A2>, kernel_detail::kMaxFrames> ps;
  for (int k = 0; k < nf; ++k) {
    const Pose<double>& pk = p[static_cast<size_t>(k)];
    // x + τ v_x, R(I + τ v̂ + τ² v̂²/2): R exp(τ v̂) to second order.
    const Eigen::Vector3d vx = v.segment<3>(6 * k), vth = v.segment<3>(6 * k + 3);
    const Eigen::Matrix3d Rv = pk.R * hat<double>(vth), Rvv = Rv * hat<double>(vth);
    Pose<A2>& out = ps[static_cast<size_t>(k)];
    for (int i = 0; i < 3; ++i) out.x[i] = number(pk.x[i], vx[i], 0.0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) out.R(i, j) = number(pk.R(i, j), Rv(i, j), Rvv(i, j));
  }
  KernelVector<A2> r;
  f(ps.data(), number(t, s, 0.0), r);
  first.resize(r.size());
  second.resize(r.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    first[i] = r[i].value().derivatives()[0];
    second[i] = r[i].derivatives()[0].derivatives()[0];
  }
}

}  // namespace alphaflex
