#include "alphaflex/elements/joint_coordinate_force.hpp"

namespace alphaflex {

JointCoordinateForce::JointCoordinateForce(std::string name, int coordinate_node, ScalarForceLaw law, Role role)
    : Element(std::move(name), {coordinate_node}), law_(std::move(law)), role_(role) {}

void JointCoordinateForce::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  double f, f_x, f_rate;
  law_.evaluate(s.q[0], s.v[0], s.t, f, f_x, f_rate);
  // A motor is a load (−T, scaled by the load factor); a spring-damper is part of the mechanism.
  const double sign = role_ == Role::motor ? -s.load_factor : 1.0;
  out.r[0] += sign * f;
  if (!tangent) return;
  out.K(0, 0) += sign * f_x;
  out.C(0, 0) += sign * f_rate;
}

std::vector<CellField> JointCoordinateForce::cell_fields() const {
  return {{"coordinate", 1}, {"speed", 1}, {role_ == Role::motor ? "drive" : "force", 1}};
}

void JointCoordinateForce::output(const LocalState& s, Eigen::VectorXd& values) const {
  LocalResidual r;
  r.reset(1, false);
  evaluate(s, r, false);
  values.resize(3);
  values << s.q[0], s.v[0], -r.r[0];
}

double JointCoordinateForce::elastic_energy(const Eigen::VectorXd& q) const {
  return role_ == Role::spring_damper ? law_.potential(q[0]) : 0.0;
}

}  // namespace alphaflex
