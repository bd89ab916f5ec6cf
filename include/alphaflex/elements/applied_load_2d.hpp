#pragma once
// Applied loads: a force of fixed world direction at a point, and a torque on a rigid body, each
// component a function of time. Gravity is part of the inertia elements.
#include "alphaflex/core/time_function.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/planar_marker.hpp"

namespace alphaflex {

/// Dead force F(t) (world frame) at a point: g = Jᵀ F, so r = −Jᵀ F and K = −∂(Jᵀ F)/∂q.
class PointForce2D final : public Element {
 public:
  PointForce2D(std::string name, int node, PlanarMarker point, TimeFunctionPtr fx, TimeFunctionPtr fy);
  const char* type() const override { return "force"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<PointForce2D>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }

 private:
  PlanarMarker point_;
  TimeFunctionPtr fx_, fy_;
};

/// Torque T(t) about the plane's normal on a rigid body: r_θ = −T.
class Torque2D final : public Element {
 public:
  Torque2D(std::string name, int node, TimeFunctionPtr torque);
  const char* type() const override { return "torque"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<Torque2D>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }

 private:
  TimeFunctionPtr torque_;
};

}  // namespace alphaflex
