#include "alphaflex/model/planar_marker.hpp"

#include <stdexcept>

namespace alphaflex {

PlanarMarker PlanarMarker::ground(const Eigen::Vector2d& point) {
  PlanarMarker m;
  m.ndof_ = 0;
  m.origin_ = point;
  return m;
}

PlanarMarker PlanarMarker::on_node(const Node& node, const Eigen::Vector2d& local, int offset) {
  if (node.spatial())
    throw std::invalid_argument("'" + node.name + "' is a spatial node; planar joints and forces need planar bodies");
  PlanarMarker m;
  m.kind_ = node.kind;
  m.ndof_ = node.ndof;
  m.offset_ = offset;
  m.local_ = local;
  m.origin_ = node.line_origin;
  m.direction_ = node.line_direction;
  if (node.kind != NodeKind::RigidBody2D && local.norm() != 0.0)
    throw std::invalid_argument("a " + std::string(to_string(node.kind)) +
                                " has no extent: its attachment point must be [0, 0]");
  return m;
}

double PlanarMarker::angle(const Eigen::VectorXd& q) const {
  return has_angle() ? q[offset_ + 2] : 0.0;
}

Eigen::Vector2d PlanarMarker::position(const Eigen::VectorXd& q) const {
  if (grounded()) return origin_;
  switch (kind_) {
    case NodeKind::RigidBody2D: return Eigen::Vector2d(q[offset_], q[offset_ + 1]) + rotate(q[offset_ + 2], local_);
    case NodeKind::Particle2D: return {q[offset_], q[offset_ + 1]};
    case NodeKind::LineParticle2D: return origin_ + q[offset_] * direction_;
    case NodeKind::Frame3D: break;
  }
  return origin_;
}

Eigen::Vector2d PlanarMarker::velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  if (grounded()) return Eigen::Vector2d::Zero();
  switch (kind_) {
    case NodeKind::RigidBody2D:
      return Eigen::Vector2d(v[offset_], v[offset_ + 1]) + v[offset_ + 2] * perp(rotate(q[offset_ + 2], local_));
    case NodeKind::Particle2D: return {v[offset_], v[offset_ + 1]};
    case NodeKind::LineParticle2D: return v[offset_] * direction_;
    case NodeKind::Frame3D: break;
  }
  return Eigen::Vector2d::Zero();
}

Eigen::Vector2d PlanarMarker::convective_acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const {
  if (kind_ != NodeKind::RigidBody2D || grounded()) return Eigen::Vector2d::Zero();
  const double w = v[offset_ + 2];
  return -w * w * rotate(q[offset_ + 2], local_);
}

void PlanarMarker::add_jacobian(const Eigen::VectorXd& q, double sign, Eigen::MatrixXd& J) const {
  if (grounded()) return;
  switch (kind_) {
    case NodeKind::RigidBody2D:
      J(0, offset_) += sign;
      J(1, offset_ + 1) += sign;
      J.col(offset_ + 2) += sign * perp(rotate(q[offset_ + 2], local_));
      break;
    case NodeKind::Particle2D:
      J(0, offset_) += sign;
      J(1, offset_ + 1) += sign;
      break;
    case NodeKind::LineParticle2D: J.col(offset_) += sign * direction_; break;
    case NodeKind::Frame3D: break;  // refused by on_node
  }
}

void PlanarMarker::add_hessian(const Eigen::VectorXd& q, const Eigen::Vector2d& w, double sign,
                               Eigen::MatrixXd& H) const {
  if (kind_ != NodeKind::RigidBody2D || grounded()) return;
  const int t = offset_ + 2;
  H(t, t) -= sign * w.dot(rotate(q[t], local_));
}

void PlanarMarker::add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double sign,
                                         Eigen::MatrixXd& D) const {
  if (kind_ != NodeKind::RigidBody2D || grounded()) return;
  const int t = offset_ + 2;
  D.col(t) -= sign * v[t] * rotate(q[t], local_);
}

}  // namespace alphaflex
