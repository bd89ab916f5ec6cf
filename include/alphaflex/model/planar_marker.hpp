#pragma once
// A point fixed to a planar node (or to the ground), and its kinematics as a function of the
// node's local coordinates. Joints and force elements are written once against this interface and
// work for rigid bodies, particles and line particles alike.
//
// For a rigid body with local point s:  r = x + R(θ) s,  J = ∂r/∂q = [I, R'(θ) s],
// ∂(Jᵀw)/∂q has the single entry −wᵀR(θ)s at (θ,θ), and (J v)_q v = −R(θ) s θ̇².
#include <Eigen/Dense>

#include "alphaflex/model/node.hpp"

namespace alphaflex {

class PlanarMarker {
 public:
  /// A point of the ground at world position `point`.
  static PlanarMarker ground(const Eigen::Vector2d& point);
  /// A point of `node` with body-frame coordinates `local` relative to its reference point (the
  /// centre of mass of a rigid body; must be zero for particles); `offset` is where the node's
  /// coordinates start in the owner's local vector.
  static PlanarMarker on_node(const Node& node, const Eigen::Vector2d& local, int offset);

  bool grounded() const { return ndof_ == 0; }
  bool has_angle() const { return kind_ == NodeKind::RigidBody2D && !grounded(); }
  int ndof() const { return ndof_; }
  int offset() const { return offset_; }
  const Eigen::Vector2d& local() const { return local_; }

  /// θ of the node (0 for the ground); only meaningful when has_angle() or grounded().
  double angle(const Eigen::VectorXd& q) const;
  Eigen::Vector2d position(const Eigen::VectorXd& q) const;
  Eigen::Vector2d velocity(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  /// (J v)_q v: the part of the point's acceleration that does not come from q̈.
  Eigen::Vector2d convective_acceleration(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;

  /// J(:, offset:offset+ndof) += sign · ∂r/∂q_node; J has 2 rows.
  void add_jacobian(const Eigen::VectorXd& q, double sign, Eigen::MatrixXd& J) const;
  /// H += sign · ∂(Jᵀ w)/∂q for a fixed world vector w.
  void add_hessian(const Eigen::VectorXd& q, const Eigen::Vector2d& w, double sign, Eigen::MatrixXd& H) const;
  /// D += sign · ∂(J v)/∂q (2 rows): the derivative of the point velocity w.r.t. coordinates.
  void add_velocity_jacobian(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double sign,
                             Eigen::MatrixXd& D) const;
  /// Column index of θ in the owner's local vector (has_angle() only).
  int angle_index() const { return offset_ + 2; }

 private:
  NodeKind kind_ = NodeKind::RigidBody2D;
  int ndof_ = 0;
  int offset_ = 0;
  Eigen::Vector2d local_{0.0, 0.0};
  Eigen::Vector2d origin_{0.0, 0.0}, direction_{1.0, 0.0};
};

/// R(θ) s and R'(θ) s = R(θ) [−s_y, s_x].
inline Eigen::Vector2d rotate(double theta, const Eigen::Vector2d& s) {
  const double c = std::cos(theta), sn = std::sin(theta);
  return {c * s.x() - sn * s.y(), sn * s.x() + c * s.y()};
}
inline Eigen::Vector2d perp(const Eigen::Vector2d& a) { return {-a.y(), a.x()}; }

}  // namespace alphaflex
