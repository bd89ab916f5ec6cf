#pragma once
// Nodes carry the unknowns of the model. A node's kind fixes how many coordinates it has and how a
// point attached to it moves; nothing else in the code may assume a number of unknowns per body.
// Planar kinds live on vector spaces (x, y, θ are additive); spatial kinds with rotations (later
// issues) add a configuration on R³×SO(3) and a retraction, without changing Element/Constraint.
#include <Eigen/Dense>
#include <string>

namespace alphaflex {

enum class NodeKind {
  RigidBody2D,     ///< (x, y, θ) of the centre of mass: 3 unknowns
  Particle2D,      ///< (x, y): a point mass or a massless point: 2 unknowns
  LineParticle2D,  ///< s along a fixed line p = origin + s·direction: 1 unknown
};

const char* to_string(NodeKind kind);
/// Name of coordinate k of a node of this kind ("x", "y", "theta", "s"), for messages.
const char* coordinate_name(NodeKind kind, int k);

struct Node {
  std::string name;
  NodeKind kind = NodeKind::RigidBody2D;
  int ndof = 3;
  int first_dof = -1;                       ///< index of its first unknown in model order
  Eigen::VectorXd q0, v0;                   ///< initial coordinates and velocities
  Eigen::Vector2d line_origin{0.0, 0.0};    ///< LineParticle2D only
  Eigen::Vector2d line_direction{1.0, 0.0}; ///< LineParticle2D only, unit length

  bool has_angle() const { return kind == NodeKind::RigidBody2D; }
  static int dofs_of(NodeKind kind);
};

}  // namespace alphaflex
