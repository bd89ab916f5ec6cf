#include "alphaflex/model/sensor.hpp"

#include <algorithm>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/mesh_reconstruction.hpp"
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

/// r(q, v, q̈ = 0, t) of an element at load factor λ (1: as in a dynamic run), inertia left out;
/// at rest if `still`.
Eigen::VectorXd forces(const Element& e, LocalState ls, double load_factor, bool still = false) {
  ls.qdd.setZero();
  if (still) ls.v.setZero();
  ls.load_factor = load_factor;
  LocalResidual out;
  out.reset(static_cast<int>(ls.v.size()), false);
  e.evaluate(ls, out, false);
  return out.r;
}

/// Part `which` of an element's energy (J) or power (W): 0 kinetic, 1 strain, 2 potential of
/// gravity, 3 their total, 4 the power of its loads on the model, 5 the power it dissipates.
/// What exchanges which energy follows from the element's own residual, so that every element
/// type takes part without code of its own: an element with mass (M = ∂r/∂q̈ ≠ 0: bodies, beams,
/// shells) has kinetic energy ½ vᵀMv and, in the part of r that the load factor λ scales, gravity
/// f_g = r(λ = 0) − r(λ = 1), constant nodal forces whose potential is −Σ f_g·x over its nodes'
/// positions (the consistent weights of beams and shells integrate −∫ρ g·x exactly); an element
/// without mass is a load in the part λ scales (power −vᵀ(r(λ = 1) − r(λ = 0))) and a force
/// element in the rest, which dissipates vᵀ(r(q, v) − r(q, 0)) at λ = 0 (c L̇² for a linear
/// damper, ε̇ᵀCε̇ for a bushing). docs/theory/force_elements.md, energy balance.
double energy_part(const Model& model, const Element& e, const LocalState& ls, int which) {
  LocalResidual t;
  t.reset(static_cast<int>(ls.v.size()), true);
  e.evaluate(ls, t, true);
  const bool mass = t.M.cwiseAbs().maxCoeff() > 0.0;
  auto gravity = [&] {
    if (!mass) return 0.0;
    const Eigen::VectorXd fg = forces(e, ls, 0.0, true) - forces(e, ls, 1.0, true);
    double V = 0.0;
    int oc = 0, od = 0;  // the node's first configuration number and unknown in the local vectors
    for (int n : e.nodes()) {
      const Node& nd = model.node(n);
      // Positions: x of a frame (its first 3 unknowns translate it), all coordinates of a planar
      // node (θ takes no gravity force: the weight acts at the centre of mass).
      const int np = nd.spatial() ? 3 : nd.ndof;
      V -= fg.segment(od, np).dot(ls.q.segment(oc, np));
      oc += nd.nconf;
      od += nd.ndof;
    }
    return V;
  };
  switch (which) {
    case 0: return 0.5 * ls.v.dot(t.M * ls.v);
    case 1: return e.elastic_energy(ls.q);
    case 2: return gravity();
    case 3: return 0.5 * ls.v.dot(t.M * ls.v) + e.elastic_energy(ls.q) + gravity();
    case 4: return mass ? 0.0 : -ls.v.dot(forces(e, ls, 1.0) - forces(e, ls, 0.0));
    default: return mass ? 0.0 : ls.v.dot(forces(e, ls, 0.0) - forces(e, ls, 0.0, true));
  }
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
      // One element, or the sum over the element range [element, node2) when node2 > element (an
      // energy or work sensor `of` a block, a body or the model: io/types/energy_sensors.cpp; each
      // rank sums the range's elements it owns, partition/subdomain.cpp); element < 0: none here.
      if (element < 0) return 0.0;
      double sum = 0.0;
      for (int k = element; k < std::max(node2, element + 1); ++k) {
        const Element& e = *model.elements()[static_cast<size_t>(k)];
        sum += energy_part(model, e, model.local_state(e, s), component);
      }
      return sum;
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
      // A reduced body's rebuilt mesh (io/types/reduced_mesh_3d.cpp; the layout of
      // MeshReconstruction::output_index): a point's position or displacement rebuilds that point
      // alone, an element's result (a section force) that element alone. The whole output rebuilds
      // every point and recovers every element's section forces twice (the odd part), per sensor
      // and step — on a 170-element rod most of a reduced run's time.
      if (const MeshReconstruction* mesh = reconstruction_of(e)) {
        const int np = static_cast<int>(mesh->points());
        if (component >= 0 && component < 6 * np) {
          const size_t a = static_cast<size_t>((component % (3 * np)) / 3);
          const int c = component % 3;
          const Eigen::Vector3d x = mesh->point_position(model.local_state(e, s), a);
          return component < 3 * np ? x[c] : x[c] - mesh->point(a).initial[c];
        }
        size_t k = 0;
        int c = 0;
        if (mesh->output_cell(component, k, c)) {
          const Eigen::VectorXd cell = mesh->element_output(model.local_state(e, s), k);
          return c < cell.size() ? cell[c] : 0.0;
        }
      }
      Eigen::VectorXd values;
      e.output(model.local_state(e, s), values);
      return values[component];
    }
  }
  return 0.0;
}

}  // namespace alphaflex
