#pragma once
// Planar force elements that act through a few coordinates ε(q) of two planar rigid bodies
// (x, y, θ), or of a body and the ground (docs/theory/force_elements.md, planar counterparts):
//
//   bushing:      ε = [R(θ_A + α)ᵀ (p_B − p_A); θ_B − θ_A − γ0],   f = K ε + C ε̇  (3×3, in the bushing
//                 frame, which turns with body A; p = x + R(θ) s, the markers coincide at t = 0);
//   rotation:     ε = θ_1 − θ_2                 (the relative angle of a planar revolute joint: θ is a
//                 coordinate of the bodies, so it is unwrapped without an extra unknown);
//   translation:  ε = R(θ_2) a_2 · (x_1 − x_2)  (the displacement along a planar prismatic joint's
//                 axis a_2, fixed in body 2; on the joint's manifold the relative rotation is fixed,
//                 so this differs from the markers' displacement by a constant only).
//
// The law is f(ε, ε̇, t) = what resists ε: the bushing's K ε + C ε̇, a joint spring-damper's
// ScalarForceLaw of ε − ε0, or a motor's −λ_f T(ε − ε0, ε̇, t) (a load). As in
// elements/coordinate_force.hpp, on the vector space of planar coordinates:
//   r = J_εᵀ f,  K = Σ_k f_k H_k + J_εᵀ (f_ε J_ε + f_ε̇ D),  C = J_εᵀ f_ε̇ J_ε,  D = ∂ε̇/∂q = H v,
// with J_ε and H_k = ∂²ε_k/∂q² from nested forward AD (core/autodiff.hpp): exact.
#include <optional>

#include "alphaflex/elements/spatial_force_elements.hpp"

namespace alphaflex {

class PlanarCoordinateForce final : public Element {
 public:
  enum class Coordinates { bushing, rotation, translation };
  /// What the coordinates are made of: which sides are bodies (a RigidBody2D node; the element's
  /// nodes are the bodies, A first), the markers' points (body frame; world points on the ground),
  /// the bushing frame's angle α on A and γ0, the prismatic axis a_2 (body-2 frame).
  struct Geometry {
    Coordinates coordinates = Coordinates::bushing;
    bool body_a = true, body_b = false;
    Eigen::Vector2d point_a = Eigen::Vector2d::Zero(), point_b = Eigen::Vector2d::Zero();
    double alpha = 0.0, gamma0 = 0.0;
    Eigen::Vector2d axis_b = Eigen::Vector2d::UnitX();
  };
  /// A bushing: K, C symmetric positive semi-definite (3×3: x, y of the frame, rotation).
  PlanarCoordinateForce(std::string name, std::vector<int> nodes, const Geometry& g, const Eigen::Matrix3d& K,
                        const Eigen::Matrix3d& C);
  /// A joint spring-damper (`motor` false) or a motor (`motor` true: f = −λ_f T) on one coordinate,
  /// with the law's variable ε − ε0 (ε0: the coordinate at t = 0).
  PlanarCoordinateForce(std::string name, std::vector<int> nodes, const Geometry& g, ScalarForceLaw law, bool motor,
                        double eps0);
  const char* type() const override;
  std::unique_ptr<Element> clone() const override { return std::make_unique<PlanarCoordinateForce>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }
  double elastic_energy(const Eigen::VectorXd& q) const override;
  std::vector<CellField> cell_fields() const override;
  /// bushing: deflection[0..2], force[0..2] (K ε + C ε̇); joint forces: coordinate (ε − ε0), speed,
  /// force (the spring's resisting force, or the motor's drive T).
  void output(const LocalState& s, Eigen::VectorXd& values) const override;

  /// ε (without ε0) and J_ε, H_k at the local coordinates q.
  void coordinates(const Eigen::VectorXd& q, Eigen::VectorXd& eps, Eigen::MatrixXd& J,
                   std::vector<Eigen::MatrixXd>* H) const;

 private:
  /// f, f_ε, f_ε̇ at ε (without ε0), ε̇, t and load factor.
  void law(const Eigen::VectorXd& eps, const Eigen::VectorXd& rate, double t, double load_factor, Eigen::VectorXd& f,
           Eigen::MatrixXd& f_eps, Eigen::MatrixXd& f_rate) const;
  Geometry g_;
  Eigen::Matrix3d K_ = Eigen::Matrix3d::Zero(), C_ = Eigen::Matrix3d::Zero();
  std::optional<ScalarForceLaw> law_;
  bool motor_ = false;
  double eps0_ = 0.0;
};

}  // namespace alphaflex
