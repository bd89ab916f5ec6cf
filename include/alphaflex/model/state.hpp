#pragma once
// The physical state of the whole model in model order (node unknowns, then multipliers).
#include <Eigen/Dense>

namespace alphaflex {

struct MechanicalState {
  double t = 0.0;
  /// Configuration (nconf per node: coordinates, or position + unit quaternion for spatial
  /// frames), velocities and accelerations (ndof per node: q̇, or (ẋ, Ω) in the Lie algebra).
  Eigen::VectorXd q, v, qdd;
  Eigen::VectorXd lambda;     ///< Lagrange multipliers
};

}  // namespace alphaflex
