#pragma once
// Private to src/io/types: the joint coordinates (joints/joint_coordinate.hpp) that joint springs,
// dampers, motors, stops and joint sensors act on or read (types/force_elements_3d.cpp defines
// these; types/joint_stops_3d.cpp and types/sensor_feedback_3d.cpp use them).
#include "alphaflex/joints/joint_coordinate.hpp"
#include "alphaflex/joints/spatial_joints.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {

using Coordinate = JointCoordinateLink::Coordinate;

/// The coordinate of the joint named by `joint` that the item acts on or reads: the `coordinate`
/// key (rotation, translation; 1 or 2 on a universal joint) or the joint's only one; `wanted` (if
/// given: "rotation" or "translation") is what the type needs. A joint without such a coordinate
/// (spherical, planar, …) is refused naming the joint and its type.
Coordinate joint_coordinate_kind(const Item& it, const SpatialJoint& joint, const char* wanted);

/// The scalar node ψ of a joint's coordinate and its kind; the node is made on first use with its
/// link to the joint, named JOINT.angle, JOINT.displacement, or JOINT.angle1 / JOINT.angle2.
struct JointCoordinateNode {
  int node;
  Coordinate coordinate;
  bool rotation() const { return coordinate != Coordinate::translation; }
  const char* variable() const { return rotation() ? "angle" : "displacement"; }
};
JointCoordinateNode joint_coordinate_node(const Item& it, const char* wanted = nullptr);

/// The `joint` and `coordinate` keys of the items on a joint coordinate.
Key joint_coordinate_joint_key();
Key joint_coordinate_key();

}  // namespace alphaflex::scene_detail
