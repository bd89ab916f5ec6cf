#include "alphaflex/elements/sensor_feedback.hpp"

namespace alphaflex {

SensorFeedbackForce::SensorFeedbackForce(std::string name, std::vector<int> nodes, std::vector<SlotOffsets> layout,
                                         std::shared_ptr<const SensorFunction> law, Role role)
    : Element(std::move(name), std::move(nodes)), layout_(std::move(layout)), law_(std::move(law)), role_(role) {
  if (layout_.size() != this->nodes().size()) throw std::logic_error("SensorFeedbackForce: one offset per node expected");
}

void SensorFeedbackForce::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  const double own[2] = {s.q[0], s.v[0]};
  if (role_ == Role::motor) {
    // r_ψ = −λ_f T(ψ, ψ̇, t, sensors): a load, scaled by the load factor.
    if (!tangent) {
      out.r[0] -= s.load_factor * law_->evaluate(s, layout_, own);
      return;
    }
    Eigen::VectorXd dq, dv;
    double g[2] = {0.0, 0.0};
    out.r[0] -= s.load_factor * law_->evaluate(s, layout_, own, &dq, &dv, g);
    dq[0] += g[0];
    dv[0] += g[1];
    out.K.row(0) -= s.load_factor * dq.transpose();
    out.C.row(0) -= s.load_factor * dv.transpose();
    return;
  }
  if (role_ == Role::probe) return;  // no force: it only evaluates a sensor
  // r_w = ẅ − e: the integrand is the controller's, not a load (not scaled).
  if (!tangent) {
    out.r[0] += s.qdd[0] - law_->evaluate(s, layout_);
    return;
  }
  Eigen::VectorXd dq, dv;
  out.r[0] += s.qdd[0] - law_->evaluate(s, layout_, nullptr, &dq, &dv);
  out.K.row(0) -= dq.transpose();
  out.C.row(0) -= dv.transpose();
  out.M(0, 0) += 1.0;
}

std::vector<CellField> SensorFeedbackForce::cell_fields() const {
  if (role_ == Role::motor) return {{"coordinate", 1}, {"speed", 1}, {"drive", 1}};
  if (role_ == Role::probe) return {{"value", 1}};
  return {{"integral", 1}, {"integrand", 1}};
}

void SensorFeedbackForce::output(const LocalState& s, Eigen::VectorXd& values) const {
  values.resize(3);
  if (role_ == Role::motor) {
    const double own[2] = {s.q[0], s.v[0]};
    values << s.q[0], s.v[0], law_->evaluate(s, layout_, own);
    return;
  }
  if (role_ == Role::probe) {
    values.resize(1);
    values << law_->evaluate(s, layout_);
    return;
  }
  values.resize(2);
  values << s.v[0], law_->evaluate(s, layout_);
}

}  // namespace alphaflex
