#include "alphaflex/elements/joint_stop.hpp"

#include <stdexcept>

namespace alphaflex {

JointStop::JointStop(std::string name, int coordinate_node, double lower, double upper, double stiffness, double damping)
    : Element(std::move(name), {coordinate_node}), lower_(lower), upper_(upper), k_(stiffness), c_(damping) {
  if (!(lower < upper)) throw std::invalid_argument("joint stop: lower must be below upper");
  if (!(stiffness > 0.0) || !(damping >= 0.0)) throw std::invalid_argument("joint stop: stiffness > 0 and damping ≥ 0 expected");
}

double JointStop::penetration(double psi, double& sign) const {
  sign = 0.0;
  if (psi > upper_) {
    sign = 1.0;
    return psi - upper_;
  }
  if (psi < lower_) {
    sign = -1.0;
    return lower_ - psi;
  }
  return 0.0;
}

void JointStop::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  double sign;
  const double delta = penetration(s.q[0], sign);
  if (sign == 0.0) return;
  // f = k δ + c δ̇ resists δ; δ = sign (ψ − limit), so r = sign f = k (ψ − limit) + c ψ̇.
  const double rate = sign * s.v[0];
  out.r[0] += sign * (k_ * delta + c_ * rate);
  if (!tangent) return;
  out.K(0, 0) += k_;
  out.C(0, 0) += c_;
}

std::vector<CellField> JointStop::cell_fields() const {
  return {{"coordinate", 1}, {"speed", 1}, {"penetration", 1}, {"force", 1}};
}

void JointStop::output(const LocalState& s, Eigen::VectorXd& values) const {
  LocalResidual r;
  r.reset(1, false);
  evaluate(s, r, false);
  double sign;
  values.resize(4);
  values << s.q[0], s.v[0], penetration(s.q[0], sign), -r.r[0];
}

double JointStop::elastic_energy(const Eigen::VectorXd& q) const {
  double sign;
  const double delta = penetration(q[0], sign);
  return 0.5 * k_ * delta * delta;
}

}  // namespace alphaflex
