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
#include <Eigen/Dense>

#include "alphaflex/core/autodiff.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/core/time_function.hpp"

namespace alphaflex {

/// Largest number of outputs of one kernel (a two-node beam's residual: 12).
constexpr int kMaxKernelOutputs = 16;
template <class S> using KernelVector = Eigen::Matrix<S, Eigen::Dynamic, 1, 0, kMaxKernelOutputs, 1>;

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

/// f(t) for a plain or differentiated time, exact to second order: f + f' dt + f'' dt²/2 about the
/// plain value of t (so the derivatives carried by t get f' and f'').
template <class S>
S time_value(const TimeFunction& f, const S& t) {
  const double t0 = ad::value(t);
  const S dt = t - S(t0);
  return S(f.value(t0)) + S(f.derivative(t0)) * dt + S(0.5 * f.second_derivative(t0)) * dt * dt;
}

namespace kernel_detail {

inline int frames_in(const Eigen::VectorXd& q) { return static_cast<int>(q.size() / 7); }

inline std::vector<Pose<double>> poses(const Eigen::VectorXd& q) {
  std::vector<Pose<double>> p;
  for (int k = 0; k < frames_in(q); ++k) p.push_back(pose_of(q.data() + 7 * k));
  return p;
}

}  // namespace kernel_detail

/// f(q, t) in doubles.
template <class Fn>
void kernel_value(const Fn& f, const Eigen::VectorXd& q, double t, Eigen::VectorXd& out) {
  const auto p = kernel_detail::poses(q);
  KernelVector<double> r;
  f(p.data(), t, r);
  out = r;
}

/// f and J = ∂f(q ∘ exp(δ))/∂δ (rows: outputs, columns: 6 per frame).
template <class Fn>
void kernel_jacobian(const Fn& f, const Eigen::VectorXd& q, double t, Eigen::VectorXd& value, Eigen::MatrixXd& J) {
  using ad::AD1;
  const auto p = kernel_detail::poses(q);
  const int nf = static_cast<int>(p.size()), n = 6 * nf;
  std::vector<Pose<AD1>> ps;
  for (int k = 0; k < nf; ++k) {
    Vec3<AD1> dx, dth;
    for (int i = 0; i < 3; ++i) {
      dx[i] = ad::variable1(0.0, n, 6 * k + i);
      dth[i] = ad::variable1(0.0, n, 6 * k + 3 + i);
    }
    ps.push_back(perturbed<AD1>(cast_pose<AD1>(p[k]), dx, dth));
  }
  KernelVector<AD1> r;
  f(ps.data(), ad::constant1(t, n), r);
  value.resize(r.size());
  J.resize(r.size(), n);
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    value[i] = r[i].value();
    if (r[i].derivatives().size() == n) J.row(i) = r[i].derivatives().transpose();
    else J.row(i).setZero();  // an output that does not depend on the frames
  }
}

/// H_ij = ∂/∂δ'_j ∂(wᵀf)/∂δ_i at q ∘ exp(δ') ∘ exp(δ) (see the header comment).
template <class Fn>
void kernel_second(const Fn& f, const Eigen::VectorXd& q, double t, const Eigen::VectorXd& w, Eigen::MatrixXd& H) {
  using ad::AD2;
  const auto p = kernel_detail::poses(q);
  const int nf = static_cast<int>(p.size()), n = 6 * nf;
  std::vector<Pose<AD2>> ps;
  for (int k = 0; k < nf; ++k) {
    Vec3<AD2> ox, oth, ix, ith;
    for (int i = 0; i < 3; ++i) {
      ox[i] = ad::outer_variable(0.0, n, 6 * k + i, n);
      oth[i] = ad::outer_variable(0.0, n, 6 * k + 3 + i, n);
      ix[i] = ad::inner_variable(0.0, n, 6 * k + i, n);
      ith[i] = ad::inner_variable(0.0, n, 6 * k + 3 + i, n);
    }
    ps.push_back(perturbed<AD2>(perturbed<AD2>(cast_pose<AD2>(p[k]), ox, oth), ix, ith));
  }
  KernelVector<AD2> r;
  f(ps.data(), ad::constant2(t, n, n), r);
  H = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index m = 0; m < r.size(); ++m) {
    if (w[m] == 0.0 || r[m].derivatives().size() != n) continue;
    for (int j = 0; j < n; ++j) {
      const auto& d = r[m].derivatives()[j].derivatives();
      if (d.size() == n) H.col(j) += w[m] * d;
    }
  }
}

/// first = d/dτ f(q ∘ exp(τ v), t + τ s), second = d²/dτ² of the same, at τ = 0 (s = 1 moves
/// time along, s = 0 freezes it).
template <class Fn>
void kernel_along_motion(const Fn& f, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t, double s,
                         Eigen::VectorXd& first, Eigen::VectorXd& second) {
  using ad::AD1;
  using ad::AD2;
  const auto p = kernel_detail::poses(q);
  // τ as both the inner and the outer variable: the mixed derivative is d²/dτ².
  ad::Derivatives2 d(1);
  d[0] = ad::constant1(1.0, 1);
  const AD2 tau(ad::variable1(0.0, 1, 0), d);
  std::vector<Pose<AD2>> ps;
  for (size_t k = 0; k < p.size(); ++k) {
    Vec3<AD2> dx, dth;
    for (int i = 0; i < 3; ++i) {
      dx[i] = tau * AD2(v[6 * k + i]);
      dth[i] = tau * AD2(v[6 * k + 3 + i]);
    }
    ps.push_back(perturbed<AD2>(cast_pose<AD2>(p[k]), dx, dth));
  }
  KernelVector<AD2> r;
  const AD2 time = AD2(t) + AD2(s) * tau;
  f(ps.data(), time, r);
  first.resize(r.size());
  second.resize(r.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    first[i] = r[i].value().derivatives().size() ? r[i].value().derivatives()[0] : 0.0;
    second[i] = (r[i].derivatives().size() && r[i].derivatives()[0].derivatives().size())
                    ? r[i].derivatives()[0].derivatives()[0]
                    : 0.0;
  }
}

}  // namespace alphaflex
