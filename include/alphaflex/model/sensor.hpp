#pragma once
// Named scalar outputs (sensors) evaluated from the state, written to the CSV every step.
#include <string>

#include "alphaflex/model/planar_marker.hpp"
#include "alphaflex/model/state.hpp"

namespace alphaflex {

class Model;

struct Sensor {
  enum class Kind { BodyAngle, RelativeAngle, PointPosition, PointDisplacement, PointVelocity,
                    PointAcceleration, JointReaction };
  std::string name;
  Kind kind = Kind::BodyAngle;
  int node = -1, node2 = -1;          ///< bodies (angle sensors); node of the marker
  Eigen::Vector2d local{0.0, 0.0};    ///< marker point in the body frame
  int component = 0;                  ///< 0 = x, 1 = y (points); fx, fy, mz = 0, 1, 2 (joints)
  int constraint = -1;                ///< joint index (JointReaction)
  Eigen::Vector2d initial{0.0, 0.0};  ///< initial point position (PointDisplacement)

  double evaluate(const Model& model, const MechanicalState& s) const;
};

}  // namespace alphaflex
