#pragma once
// A friction-free stop on a joint's coordinate ψ (joints/joint_coordinate.hpp: the unwrapped angle
// of a revolute, cylindrical or universal joint, or the displacement of a prismatic or cylindrical
// one), as a penalty: a linear spring-dashpot (Kelvin–Voigt) that acts only while ψ is beyond a
// limit. With the penetration δ = ψ − upper (or lower − ψ) and its rate δ̇,
//     f = k δ + c δ̇   for δ > 0,   0 otherwise,
// f resisting the penetration (r = f on the coordinate past the upper limit, −f past the lower).
// Why this law: it is the penalty Chrono (SMC contact) and MBDyn users know, and its coefficient
// of restitution has a closed form, e = exp(−ζπ/√(1 − ζ²)), ζ = c / (2√(k J)) for a body of inertia
// J on the joint (the contact lasts half a damped period; e.g. Goldsmith, *Impact*, 1960, and the
// review of Gilardi & Sharf, Mech. Mach. Theory 37 (2002) 1213, §3.1). Its known artefacts, as
// Hunt & Crossley (J. Appl. Mech. 42 (1975) 440) pointed out: the damping force jumps to c δ̇ at
// impact and pulls briefly (f < 0) before separation; both are part of the closed form and so of
// the test. Newton sees a piecewise-linear r with exact one-sided derivatives (semismooth): K = k,
// C = c inside, 0 outside. No state: the stop is a function of (ψ, ψ̇), so checkpoints and step
// cuts need nothing.
#include "alphaflex/model/element.hpp"

namespace alphaflex {

class JointStop final : public Element {
 public:
  /// `lower` < `upper` (either may be ±∞), stiffness k > 0 and damping c ≥ 0 in the coordinate's
  /// units (N·m/rad and N·m·s/rad, or N/m and N·s/m).
  JointStop(std::string name, int coordinate_node, double lower, double upper, double stiffness, double damping);
  const char* type() const override { return "joint_stop"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<JointStop>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }
  std::vector<CellField> cell_fields() const override;
  /// coordinate ψ, speed ψ̇, penetration δ (≥ 0, m or rad) and the stop's torque or force on the
  /// coordinate (positive in the sense of ψ: −r).
  void output(const LocalState& s, Eigen::VectorXd& values) const override;
  /// ½ k δ² while penetrating.
  double elastic_energy(const Eigen::VectorXd& q) const override;

 private:
  /// The penetration δ ≥ 0 at ψ and the sign s with δ = s (ψ − limit) (0 where free).
  double penetration(double psi, double& sign) const;
  double lower_, upper_, k_, c_;
};

}  // namespace alphaflex
