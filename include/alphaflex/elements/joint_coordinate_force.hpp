#pragma once
// A force on a joint's coordinate ψ (joints/joint_coordinate.hpp: the unwrapped angle of a revolute
// or cylindrical joint, the displacement of a prismatic or cylindrical one), a scalar node:
//   spring-damper:  r = f(ψ, ψ̇, t)       (ScalarForceLaw: k (ψ − ψ0) + c ψ̇ + preload, a table, an
//                                         expression of deflection, speed and t);
//   motor:          r = −λ_f T(ψ, ψ̇, t)   (a torque or force driving the coordinate, an applied load:
//                                         scaled by the load factor λ_f like every load).
// K = ∂r/∂ψ and C = ∂r/∂ψ̇ are the law's exact partial derivatives; the coupling to the bodies is
// the link's constraint, whose multiplier carries the torque or force.
#include "alphaflex/elements/spatial_force_elements.hpp"

namespace alphaflex {

class JointCoordinateForce final : public Element {
 public:
  enum class Role { spring_damper, motor };
  JointCoordinateForce(std::string name, int coordinate_node, ScalarForceLaw law, Role role);
  const char* type() const override { return role_ == Role::motor ? "joint_motor" : "joint_spring_damper"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<JointCoordinateForce>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }
  std::vector<CellField> cell_fields() const override;
  /// coordinate ψ (rad or m), speed ψ̇, and the torque or force on the coordinate (N·m or N,
  /// positive in the sense of ψ: −r).
  void output(const LocalState& s, Eigen::VectorXd& values) const override;
  double elastic_energy(const Eigen::VectorXd& q) const override;

 private:
  ScalarForceLaw law_;
  Role role_;
};

}  // namespace alphaflex
