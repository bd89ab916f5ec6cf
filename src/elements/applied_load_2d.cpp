#include "alphaflex/elements/applied_load_2d.hpp"

namespace alphaflex {

PointForce2D::PointForce2D(std::string name, int node, PlanarMarker point, TimeFunctionPtr fx, TimeFunctionPtr fy)
    : Element(std::move(name), {node}), point_(point), fx_(std::move(fx)), fy_(std::move(fy)) {}

void PointForce2D::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  const Eigen::Vector2d f = s.load_factor * Eigen::Vector2d(fx_->value(s.t), fy_->value(s.t));
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, s.q.size());
  point_.add_jacobian(s.q, 1.0, J);
  out.r -= J.transpose() * f;
  if (tangent) point_.add_hessian(s.q, f, -1.0, out.K);
}

Torque2D::Torque2D(std::string name, int node, TimeFunctionPtr torque)
    : Element(std::move(name), {node}), torque_(std::move(torque)) {}

void Torque2D::evaluate(const LocalState& s, LocalResidual& out, bool) const {
  out.r[2] -= s.load_factor * torque_->value(s.t);
}

}  // namespace alphaflex
