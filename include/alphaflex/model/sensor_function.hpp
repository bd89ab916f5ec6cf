#pragma once
// An expression of sensor values (and time, and optionally of a caller's own variables) as a
// function of the local state of a node list, with its exact first derivatives with respect to the
// positions (the right-trivialized increments δ of the Lie-group integrator) and the velocities.
// Loads that read sensors (a PID joint motor), the `integral` sensor's integrand and `expression`
// sensors are written with it (io/types/sensor_feedback_3d.cpp). Why derivatives in closed form:
// a load that reads a sensor of another body couples them in S_t, and Newton converges
// quadratically only if that coupling is in the tangent (docs/theory/force_elements.md, feedback).
//
// The sensors it can read are those whose derivative it knows exactly:
//   NodeCoordinate, NodeSpeed (joint_angle, joint_displacement, joint_speed, integral: ∂ = 1);
//   PointPosition, PointDisplacement: p = x + R s, ∂p/∂δx = I, ∂p/∂δθ = −R ŝ;
//   PointVelocity: ṗ = ẋ + R(Ω × s), ∂ṗ/∂ẋ = I, ∂ṗ/∂Ω = −R ŝ, ∂ṗ/∂δθ = −R (Ω × s)^;
//   and the same in a moving frame F (`relative_to`): y = R_Fᵀ(p − x_F) (positions) or R_Fᵀ ṗ,
//   ∂y/∂δx_F = −R_Fᵀ (positions), ∂y/∂δθ_F = ŷ (spatial nodes only);
//   an `expression` sensor: another SensorFunction (chain rule).
// Others (accelerations, reactions, which depend on λ, rotations, energies, element outputs) are
// refused by the scene reader.
#include <memory>
#include <string>
#include <vector>

#include "alphaflex/core/expression.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/sensor.hpp"

namespace alphaflex {

class Model;

/// Where node `slot` of a node list starts in a LocalState: configuration and velocity offsets.
struct SlotOffsets {
  int conf = 0, dof = 0;
};
/// The offsets of `nodes` of `model`, in order.
std::vector<SlotOffsets> slot_offsets(const Model& model, const std::vector<int>& nodes);

class SensorFunction {
 public:
  /// One sensor read by the expression, on slots of the node list.
  struct Input {
    Sensor::Kind kind = Sensor::Kind::NodeCoordinate;  ///< unless `expression`
    int slot = -1;        ///< the node it reads
    int frame_slot = -1;  ///< points: the frame node (`relative_to`), −1 for the world
    Eigen::Vector3d local = Eigen::Vector3d::Zero(), initial = Eigen::Vector3d::Zero();
    int component = 0;
    std::shared_ptr<const SensorFunction> expression;  ///< an `expression` sensor (chain rule)
  };
  /// What variable k of the expression is: input roles[k] (≥ 0), time (kTime) or the caller's
  /// leading variable j (leading(j)). Only the variables the text uses are variables
  /// (ExpressionFunction holds at most kMaxVariables).
  static constexpr int kTime = -1;
  static constexpr int leading(int j) { return -2 - j; }

  SensorFunction(std::shared_ptr<const ExpressionFunction> f, std::vector<int> roles, std::vector<Input> inputs);

  /// The value at the local state `s` of the node list with `layout`; if `dq` is not null, also
  /// ∂f/∂δ and ∂f/∂v (both of the list's size in unknowns, overwritten) and ∂f/∂(leading variable j)
  /// added into leading_gradient[j].
  double evaluate(const LocalState& s, const std::vector<SlotOffsets>& layout, const double* leading = nullptr,
                  Eigen::VectorXd* dq = nullptr, Eigen::VectorXd* dv = nullptr, double* leading_gradient = nullptr) const;

  /// The same function on another node list: slot k becomes slot_map[k].
  std::shared_ptr<const SensorFunction> rebased(const std::vector<int>& slot_map) const;

  const ExpressionFunction& expression() const { return *f_; }

 private:
  /// Input k's value and, if dq, its derivatives added (times `weight`) to dq, dv.
  double input(const Input& in, const LocalState& s, const std::vector<SlotOffsets>& layout, double weight,
               Eigen::VectorXd* dq, Eigen::VectorXd* dv) const;
  std::shared_ptr<const ExpressionFunction> f_;
  std::vector<int> roles_;
  std::vector<Input> inputs_;
};

}  // namespace alphaflex
