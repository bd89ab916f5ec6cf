#include "alphaflex/elements/rigid_body_2d.hpp"

#include "alphaflex/model/planar_marker.hpp"

namespace alphaflex {

RigidBody2D::RigidBody2D(std::string name, int node, double mass, double inertia, Eigen::Vector2d gravity)
    : Element(std::move(name), {node}), m_(mass), j_(inertia), g_(std::move(gravity)) {}

void RigidBody2D::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  out.r[0] += m_ * (s.qdd[0] - s.load_factor * g_.x());
  out.r[1] += m_ * (s.qdd[1] - s.load_factor * g_.y());
  out.r[2] += j_ * s.qdd[2];
  if (tangent) {
    out.M(0, 0) += m_;
    out.M(1, 1) += m_;
    out.M(2, 2) += j_;
  }
}

bool RigidBody2D::mass_action(const LocalState& /*s*/, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const {
  Mw.resize(3);
  Mw << m_ * w[0], m_ * w[1], j_ * w[2];
  return true;
}

PointMass::PointMass(std::string name, int node, const Node& n, double mass, Eigen::Vector2d gravity)
    : Element(std::move(name), {node}) {
  const PlanarMarker marker = PlanarMarker::on_node(n, Eigen::Vector2d::Zero(), 0);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, n.ndof);
  marker.add_jacobian(n.q0, 1.0, J);  // constant for particles and line particles
  mass_matrix_ = mass * J.transpose() * J;
  weight_ = J.transpose() * (mass * gravity);
}

void PointMass::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  out.r += mass_matrix_ * s.qdd - s.load_factor * weight_;
  if (tangent) out.M += mass_matrix_;
}

bool PointMass::mass_action(const LocalState& /*s*/, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const {
  Mw.noalias() = mass_matrix_ * w;
  return true;
}

}  // namespace alphaflex
