#include "alphaflex/model/sensor.hpp"

#include "alphaflex/model/model.hpp"

namespace alphaflex {

double Sensor::evaluate(const Model& model, const MechanicalState& s) const {
  auto angle_of = [&](int n) { return s.q[model.node(n).first_dof + 2]; };
  switch (kind) {
    case Kind::BodyAngle: return angle_of(node);
    case Kind::RelativeAngle: return angle_of(node) - angle_of(node2);
    case Kind::PointPosition:
    case Kind::PointDisplacement:
    case Kind::PointVelocity:
    case Kind::PointAcceleration: {
      const Node& nd = model.node(node);
      const PlanarMarker m = PlanarMarker::on_node(nd, local, 0);
      const Eigen::VectorXd q = s.q.segment(nd.first_dof, nd.ndof);
      const Eigen::VectorXd v = s.v.segment(nd.first_dof, nd.ndof);
      if (kind == Kind::PointVelocity) return m.velocity(q, v)[component];
      if (kind == Kind::PointAcceleration) {
        // r̈ = J q̈ + (J q̇)_q q̇
        Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, nd.ndof);
        m.add_jacobian(q, 1.0, J);
        return (J * s.qdd.segment(nd.first_dof, nd.ndof) + m.convective_acceleration(q, v))[component];
      }
      const Eigen::Vector2d p = m.position(q);
      return kind == Kind::PointPosition ? p[component] : p[component] - initial[component];
    }
    case Kind::JointReaction: {
      const Constraint& c = *model.constraints()[static_cast<size_t>(constraint)];
      const std::vector<int> dofs = model.dofs_of(c.nodes());
      const JointReaction r = c.reaction(gather(s.q, dofs), s.t,
                                         s.lambda.segment(model.first_multiplier(constraint), c.size()));
      if (component == 0) return r.force.x();
      if (component == 1) return r.force.y();
      return r.moment.z();
    }
  }
  return 0.0;
}

}  // namespace alphaflex
