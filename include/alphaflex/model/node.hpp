#pragma once
// Nodes carry the unknowns of the model. A node's kind fixes how many coordinates it has and how a
// point attached to it moves; nothing else in the code may assume a number of unknowns per body.
// Planar kinds live on vector spaces (x, y, θ are additive). A spatial frame (rigid body or beam
// node) lives on the Lie group R³×SO(3) (Brüls, Cardona & Arnold 2012): its configuration is stored
// as (x, y, z, q_w, q_x, q_y, q_z) — position and unit quaternion, no singular parameterization —
// and its 6 unknowns are the velocity (ẋ in the world frame, Ω in the body frame) and the
// increments δ = (δx, δθ) that act through  (x, R) ∘ exp(δ) = (x + δx, R exp(δθ^)).
// Hence a node has `nconf` stored configuration numbers and `ndof` unknowns (equal for vector
// spaces). Tangents K = ∂r/∂δ and Φ_q are taken with respect to these right-trivialized δ.
#include <Eigen/Dense>
#include <string>

namespace alphaflex {

enum class NodeKind {
  RigidBody2D,     ///< (x, y, θ) of the centre of mass: 3 unknowns
  Particle2D,      ///< (x, y): a point mass or a massless point: 2 unknowns
  LineParticle2D,  ///< s along a fixed line p = origin + s·direction: 1 unknown
  Frame3D,         ///< position and rotation on R³×SO(3): 7 stored numbers, 6 unknowns
};

const char* to_string(NodeKind kind);
/// Name of coordinate k of a node of this kind ("x", "y", "theta", "s"), for messages.
const char* coordinate_name(NodeKind kind, int k);
/// True for kinds whose configuration is not a vector space (composition through exp).
bool is_lie_group(NodeKind kind);

/// out = q ∘ exp(dx) for one node: q, out have `nconf` entries, dx has `ndof`. On vector spaces
/// out = q + dx; for Frame3D the quaternion is renormalized.
void retract(NodeKind kind, const double* q, const double* dx, double* out);
/// T(x), the tangent operator of exp at x (ndof × ndof; the identity on vector spaces).
Eigen::MatrixXd tangent_operator(NodeKind kind, const double* x);

struct Node {
  std::string name;
  NodeKind kind = NodeKind::RigidBody2D;
  int ndof = 3;
  int nconf = 3;                            ///< stored configuration numbers (7 for Frame3D)
  int first_dof = -1;                       ///< index of its first unknown in model order
  int first_conf = -1;                      ///< index of its first configuration number
  Eigen::VectorXd q0, v0;                   ///< initial configuration (nconf) and velocity (ndof)
  Eigen::Vector2d line_origin{0.0, 0.0};    ///< LineParticle2D only
  Eigen::Vector2d line_direction{1.0, 0.0}; ///< LineParticle2D only, unit length

  bool has_angle() const { return kind == NodeKind::RigidBody2D; }
  bool spatial() const { return kind == NodeKind::Frame3D; }
  static int dofs_of(NodeKind kind);
  static int confs_of(NodeKind kind);
};

}  // namespace alphaflex
