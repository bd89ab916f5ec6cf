#pragma once
// Inertia of a planar rigid body in absolute coordinates (x, y, θ) of its centre of mass:
// M = diag(m, m, J) is constant, so r = M q̈ − m g with g the gravity vector (no gyroscopic term
// in the plane).
#include "alphaflex/model/element.hpp"

namespace alphaflex {

class RigidBody2D final : public Element {
 public:
  RigidBody2D(std::string name, int node, double mass, double inertia, Eigen::Vector2d gravity);
  const char* type() const override { return "rigid_body"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<RigidBody2D>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override;

 private:
  double m_, j_;
  Eigen::Vector2d g_;
};

/// Inertia of a particle or a line particle: M = m JᵀJ with the constant point Jacobian J, and the
/// weight Jᵀ m g.
class PointMass final : public Element {
 public:
  PointMass(std::string name, int node, const struct Node& n, double mass, Eigen::Vector2d gravity);
  const char* type() const override { return "point_mass"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<PointMass>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override;

 private:
  Eigen::MatrixXd mass_matrix_;
  Eigen::VectorXd weight_;
};

}  // namespace alphaflex
