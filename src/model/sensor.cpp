#include "alphaflex/model/sensor.hpp"

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {
namespace {

/// Position, velocity or acceleration (which = 0, 1, 2) of point s of a spatial frame:
/// p = x + R s, ṗ = ẋ + R (Ω × s), p̈ = ẍ + R (Ω̇ × s + Ω × (Ω × s)).
Eigen::Vector3d spatial_point(const Model& m, const MechanicalState& st, int node, const Eigen::Vector3d& s, int which) {
  const Node& nd = m.node(node);
  const Pose<double> p = pose_of(st.q.data() + nd.first_conf);
  const Eigen::Vector3d W = st.v.segment<3>(nd.first_dof + 3);
  if (which == 0) return p.x + p.R * s;
  if (which == 1) return st.v.segment<3>(nd.first_dof) + p.R * W.cross(s);
  const Eigen::Vector3d Wd = st.qdd.segment<3>(nd.first_dof + 3);
  return st.qdd.segment<3>(nd.first_dof) + p.R * (Wd.cross(s) + W.cross(W.cross(s)));
}

}  // namespace

double Sensor::evaluate(const Model& model, const MechanicalState& s) const {
  auto angle_of = [&](int n) { return s.q[model.node(n).first_conf + 2]; };
  switch (kind) {
    case Kind::BodyAngle: return angle_of(node);
    case Kind::RelativeAngle: return angle_of(node) - angle_of(node2);
    case Kind::PointPosition:
    case Kind::PointDisplacement:
    case Kind::PointVelocity:
    case Kind::PointAcceleration: {
      const Node& nd = model.node(node);
      if (nd.spatial()) {
        const int which = kind == Kind::PointVelocity ? 1 : kind == Kind::PointAcceleration ? 2 : 0;
        Eigen::Vector3d p = spatial_point(model, s, node, local, which);
        if (kind == Kind::PointDisplacement) p -= initial;
        if (frame_node >= 0) {
          // Components in a moving frame (e.g. tip deflection seen from a spinning hub).
          const Node& fn = model.node(frame_node);
          const Pose<double> f = pose_of(s.q.data() + fn.first_conf);
          if (kind == Kind::PointPosition) p = f.R.transpose() * (p - f.x);
          else if (kind == Kind::PointDisplacement) p = f.R.transpose() * (p + initial - f.x) - initial;
          else p = f.R.transpose() * p;
        }
        return p[component];
      }
      const PlanarMarker m = PlanarMarker::on_node(nd, local.head<2>(), 0);
      const Eigen::VectorXd q = s.q.segment(nd.first_conf, nd.nconf);
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
    case Kind::BodyRotation: {
      const Node& nd = model.node(node);
      const Pose<double> p = pose_of(s.q.data() + nd.first_conf);
      return log_so3<double>(p.R)[component];
    }
    case Kind::JointReaction: {
      const Constraint& c = *model.constraints()[static_cast<size_t>(constraint)];
      const JointReaction r = c.reaction(gather(s.q, model.confs_of(c.nodes())), s.t,
                                         s.lambda.segment(model.first_multiplier(constraint), c.size()));
      const Eigen::Vector3d v = r.frame.transpose() * (component < 3 ? r.force : r.moment);
      return v[component % 3];
    }
    case Kind::NodeCoordinate: return s.q[model.node(node).first_conf];
    case Kind::NodeSpeed: return s.v[model.node(node).first_dof];
    case Kind::ElementEnergy: {
      const Element& e = *model.elements()[static_cast<size_t>(element)];
      const LocalState ls = model.local_state(e, s);
      if (component == 1) return e.elastic_energy(ls.q);
      // ½ q̇ᵀ M q̇ with the element's own mass matrix M = ∂r/∂q̈ (rigid bodies: ½ m ẋ² + ½ Ωᵀ J Ω).
      LocalResidual out;
      out.reset(static_cast<int>(ls.v.size()), true);
      e.evaluate(ls, out, true);
      return 0.5 * ls.v.dot(out.M * ls.v);
    }
    case Kind::JointViolation: {
      const Constraint& c = *model.constraints()[static_cast<size_t>(constraint)];
      Eigen::VectorXd phi;
      Eigen::MatrixXd phi_q;
      c.evaluate(gather(s.q, model.confs_of(c.nodes())), s.t, phi, phi_q);
      return phi.norm();
    }
    case Kind::ElementOutput: {
      const Element& e = *model.elements()[static_cast<size_t>(element)];
      Eigen::VectorXd values;
      e.output(model.local_state(e, s), values);
      return values[component];
    }
  }
  return 0.0;
}

}  // namespace alphaflex
