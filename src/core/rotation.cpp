#include "alphaflex/core/rotation.hpp"

#include <algorithm>

namespace alphaflex {

bool frame_from(const Eigen::Vector3d& e1, const Eigen::Vector3d& ref2, Eigen::Matrix3d& R) {
  const double n1 = e1.norm();
  if (!(n1 > 0.0)) return false;
  const Eigen::Vector3d a = e1 / n1;
  Eigen::Vector3d b = ref2 - a.dot(ref2) * a;
  if (!(b.norm() > 1e-8 * std::max(1.0, ref2.norm()))) return false;
  b.normalize();
  // A second projection: one pass leaves b·a ~ ε/sin∠(e1, ref2) (1e-8 for nearly parallel input).
  b -= a.dot(b) * a;
  b.normalize();
  R.col(0) = a;
  R.col(1) = b;
  R.col(2) = a.cross(b);
  return true;
}

}  // namespace alphaflex
