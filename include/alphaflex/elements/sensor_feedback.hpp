#pragma once
// Elements whose law reads sensors (model/sensor_function.hpp), on the nodes of those sensors:
//   motor:       a joint motor whose torque or force T(ψ, ψ̇, t, sensors) names sensors (a PD or
//                PID controller): r_ψ = −λ_f T, on the coordinate node ψ (first in the node list);
//   integrator:  the state of an `integral` sensor: a scalar node w with r_w = ẅ − e(t, sensors),
//                so ẇ = ∫ e dt + ẇ(0) is the integral, advanced by the generalized-α's own velocity
//                update (the same scheme as every mechanical velocity; second order), and the
//                consistent start finds ẅ(0) = e(0) from M = 1 like any acceleration. Why a node
//                rather than a sensor with memory: the integral then lives in q̇, so step cuts,
//                checkpoints, restarts and the ranks' ghost copies carry it as they carry any
//                velocity, and its coupling to the loads that read it is in S_t.
//   probe:       an `expression` sensor's value (its output), on the nodes it reads: no force (r = 0),
//                an element so that the rank that evaluates the sensor has those nodes, as every
//                element has its own (partition/subdomain.hpp).
// Tangents: K and C of the row are the exact derivatives of the law through the sensors
// (∂T/∂s · ∂s/∂δ, ∂T/∂s · ∂s/∂v) plus, for a motor, ∂T/∂ψ and ∂T/∂ψ̇; M is 1 on the integrator's
// row. The rows are not symmetric (a controller is not a potential).
#include <memory>

#include "alphaflex/model/element.hpp"
#include "alphaflex/model/sensor_function.hpp"

namespace alphaflex {

class SensorFeedbackForce final : public Element {
 public:
  enum class Role { motor, integrator, probe };
  /// `nodes`: the acted-on scalar node first, then the nodes the sensors read; `layout` their
  /// offsets (slot_offsets). A motor's function has the leading variables (coordinate, speed), the
  /// others none. A probe's node list is the nodes its sensors read.
  SensorFeedbackForce(std::string name, std::vector<int> nodes, std::vector<SlotOffsets> layout,
                      std::shared_ptr<const SensorFunction> law, Role role);
  const char* type() const override {
    return role_ == Role::motor ? "joint_motor" : role_ == Role::integrator ? "sensor_integrator" : "sensor_expression";
  }
  std::unique_ptr<Element> clone() const override { return std::make_unique<SensorFeedbackForce>(*this); }
  /// A motor's tangent goes through the derivatives of every sensor its law reads; modified Newton
  /// gained on the pan-tilt head (15 unknowns) where full Newton wins on every other mechanism of its
  /// size (docs/performance.md, "Modified Newton by default").
  const char* favours_modified_newton() const override {
    return role_ == Role::motor ? "a joint motor whose law reads sensors (its tangent goes through their derivatives)" : nullptr;
  }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  /// Motor: coordinate, speed, drive (as a joint_motor); integrator: integral ẇ, integrand e; probe: value.
  std::vector<CellField> cell_fields() const override;
  void output(const LocalState& s, Eigen::VectorXd& values) const override;

 private:
  std::vector<SlotOffsets> layout_;
  std::shared_ptr<const SensorFunction> law_;
  Role role_;
};

}  // namespace alphaflex
