#pragma once
// The physical state of the whole model in model order (node unknowns, then multipliers).
#include <Eigen/Dense>

namespace alphaflex {

struct MechanicalState {
  double t = 0.0;
  Eigen::VectorXd q, v, qdd;  ///< coordinates, velocities q̇, accelerations q̈
  Eigen::VectorXd lambda;     ///< Lagrange multipliers
};

}  // namespace alphaflex
