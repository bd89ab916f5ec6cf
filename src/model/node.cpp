#include "alphaflex/model/node.hpp"

#include "alphaflex/core/rotation.hpp"

namespace alphaflex {

const char* to_string(NodeKind kind) {
  switch (kind) {
    case NodeKind::RigidBody2D: return "rigid_body";
    case NodeKind::Particle2D: return "particle";
    case NodeKind::LineParticle2D: return "line_particle";
    case NodeKind::Frame3D: return "frame";
  }
  return "?";
}

int Node::dofs_of(NodeKind kind) {
  switch (kind) {
    case NodeKind::RigidBody2D: return 3;
    case NodeKind::Particle2D: return 2;
    case NodeKind::LineParticle2D: return 1;
    case NodeKind::Frame3D: return 6;
  }
  return 0;
}

int Node::confs_of(NodeKind kind) { return kind == NodeKind::Frame3D ? 7 : dofs_of(kind); }

bool is_lie_group(NodeKind kind) { return kind == NodeKind::Frame3D; }

void retract(NodeKind kind, const double* q, const double* dx, double* out) {
  if (kind != NodeKind::Frame3D) {
    for (int k = 0; k < Node::dofs_of(kind); ++k) out[k] = q[k] + dx[k];
    return;
  }
  for (int k = 0; k < 3; ++k) out[k] = q[k] + dx[k];
  const Eigen::Quaterniond r(q[3], q[4], q[5], q[6]);
  const Eigen::Quaterniond n = (r * quaternion_exp(Eigen::Vector3d(dx[3], dx[4], dx[5]))).normalized();
  out[3] = n.w();
  out[4] = n.x();
  out[5] = n.y();
  out[6] = n.z();
}

Eigen::MatrixXd tangent_operator(NodeKind kind, const double* x) {
  const int n = Node::dofs_of(kind);
  Eigen::MatrixXd T = Eigen::MatrixXd::Identity(n, n);
  if (kind == NodeKind::Frame3D) T.bottomRightCorner<3, 3>() = tangent_so3<double>(Eigen::Vector3d(x[3], x[4], x[5]));
  return T;
}

const char* coordinate_name(NodeKind kind, int k) {
  static const char* planar[] = {"x", "y", "theta"};
  static const char* spatial[] = {"x", "y", "z", "rotation x (body)", "rotation y (body)", "rotation z (body)"};
  if (kind == NodeKind::Frame3D) return spatial[k];
  return kind == NodeKind::LineParticle2D ? "s" : planar[k];
}



}  // namespace alphaflex
