#include "alphaflex/driver/error_estimator.hpp"

namespace alphaflex {

Eigen::VectorXd PositionErrorEstimator::divided_difference(const Eigen::VectorXd& increment, double h, double& factor) const {
  // Mid-points of the three steps, relative to the start of this one: h/2, −h1/2, −h1 − h2/2.
  const double h1 = hist_.h1, h2 = hist_.h2;
  const Eigen::VectorXd d1 = (increment / h - hist_.m1) / (0.5 * (h + h1));
  const Eigen::VectorXd d0 = (hist_.m1 - hist_.m2) / (0.5 * (h1 + h2));
  // q⃛ ≈ 2 m[τ_{n−1}, τ_n, τ_{n+1}] = 2 (d1 − d0) / (τ_{n+1} − τ_{n−1}).
  const double third = 2.0 / (0.5 * h + h1 + 0.5 * h2);
  factor = c_ * h * h * h * third;
  return d1 - d0;
}

double PositionErrorEstimator::estimate(const Subdomain& sub, const Eigen::VectorXd& increment, double h, double fallback) const {
  if (hist_.count < 2) return fallback;
  double factor = 0.0;
  const Eigen::VectorXd d = divided_difference(increment, h, factor);
  return factor * sub.max_abs(d);
}

Eigen::VectorXd PositionErrorEstimator::error_vector(const Eigen::VectorXd& increment, double h,
                                                     const Eigen::VectorXd& fallback) const {
  if (hist_.count < 2) return fallback;
  double factor = 0.0;
  const Eigen::VectorXd d = divided_difference(increment, h, factor);
  return factor * d;
}

void PositionErrorEstimator::accept(const Eigen::VectorXd& increment, double h) {
  hist_.m2 = hist_.m1;
  hist_.h2 = hist_.h1;
  hist_.m1 = increment / h;
  hist_.h1 = h;
  hist_.count = std::min(hist_.count + 1, 2);
}

}  // namespace alphaflex
