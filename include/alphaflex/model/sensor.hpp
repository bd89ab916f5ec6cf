#pragma once
// Named scalar outputs (sensors) evaluated from the state, written to the CSV every step.
#include <string>

#include "alphaflex/model/planar_marker.hpp"
#include "alphaflex/model/state.hpp"

namespace alphaflex {

class Model;

struct Sensor {
  enum class Kind { BodyAngle, RelativeAngle, PointPosition, PointDisplacement, PointVelocity,
                    PointAcceleration, JointReaction, BodyRotation, ElementOutput,
                    NodeCoordinate,  ///< q of a one-coordinate node (a joint coordinate, joints/joint_coordinate.hpp)
                    NodeSpeed,       ///< q̇ of the same
                    /// Of one element, or summed over the element range [element, node2) when node2 >
                    /// element (every rank sums the range's elements it owns): component 0 kinetic
                    /// ½ q̇ᵀ M q̇, 1 strain, 2 gravity potential, 3 their total (J); 4 power of the
                    /// loads, 5 power dissipated (W), which app/sensor_integrals.hpp integrates.
                    ElementEnergy,
                    JointViolation };  ///< |Φ| of one joint (its equations' units: m, or 1 for axis products)
  std::string name;
  Kind kind = Kind::BodyAngle;
  int node = -1, node2 = -1;          ///< bodies (angle sensors); node of the marker
  Eigen::Vector3d local = Eigen::Vector3d::Zero();  ///< marker point in the body frame (planar: x, y)
  /// Points: 0, 1, 2 = x, y, z. Joints: fx, fy, fz, mx, my, mz = 0…5 in the joint frame.
  /// Body rotation: rotation-vector component. Element outputs: index into output_names().
  int component = 0;
  int constraint = -1;                ///< joint index (JointReaction, JointViolation)
  int element = -1;                   ///< element index (ElementOutput, ElementEnergy)
  /// Spatial points: components in the frame of this node, relative to its origin (−1: world).
  int frame_node = -1;
  Eigen::Vector3d initial = Eigen::Vector3d::Zero();  ///< initial point position (PointDisplacement)

  double evaluate(const Model& model, const MechanicalState& s) const;
};

}  // namespace alphaflex
