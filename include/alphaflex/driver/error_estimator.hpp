#pragma once
// Local error estimate of the adaptive steps from positions only (docs/theory/adaptive_steps.md §3).
//
// The local error of q in one step is C h³ q⃛ (C = AlphaParameters::local_error_constant). q⃛ is
// taken from the mean velocities m_k = x_k / h_k of this step and the two accepted before it
// (x_k the step's increment, q_k = q_{k−1} ∘ exp(x_k)), as twice their second divided difference
// at the steps' mid-points. Positions satisfy the constraints exactly at every step, so this sees no
// trace of the index-3 transients that velocities and accelerations carry after a change of h
// (a velocity off Φ_q q̇ + Φ_t = 0 by u gives accelerations ~u/h normal to the constraints, which an
// estimate C h² (a_{n+1} − a_n) would take for a local error ∝ h and chase h down to nothing).
// At t = 0 the history is the initial velocity q̇_0 (a mean velocity over a step of length 0, which
// the consistent start put on the velocity constraints), so the second step has its three points;
// the first step uses C h² (a_{n+1} − a_n), whose velocities are still consistent. (After one step
// they are not: on the heavy top the estimate from a stayed above the tolerance for any h at the
// second step.)
#include <Eigen/Dense>

#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

class PositionErrorEstimator {
 public:
  /// The last two accepted steps' mean velocities (local vectors) and sizes: a checkpoint keeps them.
  struct History {
    Eigen::VectorXd m1, m2;  ///< of the last and the one before
    double h1 = 0.0, h2 = 0.0;
    int count = 0;           ///< how many of them are set (0, 1, 2)
  };

  explicit PositionErrorEstimator(double error_constant) : c_(std::abs(error_constant)) {}

  /// ‖C h³ q⃛‖∞ over all ranks for a step of size h with increment x; `fallback` (the estimate
  /// from a) while fewer than two accepted steps precede. Collective.
  double estimate(const Subdomain& sub, const Eigen::VectorXd& increment, double h, double fallback) const;
  /// The same estimate as a vector, C h³ q⃛ (local coordinates), for the filtered estimate
  /// (driver/error_filter.hpp); `fallback` (C h² (a_{n+1} − a_n)) while fewer than two accepted steps
  /// precede.
  Eigen::VectorXd error_vector(const Eigen::VectorXd& increment, double h, const Eigen::VectorXd& fallback) const;
  /// The run starts at the state with velocity v0 (local): the first point of the history.
  void start(const Eigen::VectorXd& v0) {
    hist_ = History();
    hist_.m1 = v0;
    hist_.count = 1;
  }
  /// The step with increment x and size h is accepted.
  void accept(const Eigen::VectorXd& increment, double h);

  const History& history() const { return hist_; }
  void set_history(const History& h) { hist_ = h; }

 private:
  /// m[τ_n, τ_{n+1}] − m[τ_{n−1}, τ_n] (local), and `factor` that makes C h³ q⃛ of it.
  Eigen::VectorXd divided_difference(const Eigen::VectorXd& increment, double h, double& factor) const;

  double c_;
  History hist_;
};

}  // namespace alphaflex
