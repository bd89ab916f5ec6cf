#pragma once
// Linear spring-damper between two points (bodies, particles or the ground).
//
// Point-to-point: with d = r1 − r2, L = |d|, e = d/L, the tension N = k (L − L0) + c L̇ acts as
// −N e on point 1 and +N e on point 2, so r = N Bᵀ e with B = ∂d/∂q.
// Along a fixed axis u (`direction`): δ = u·d replaces L and u replaces e; this is the linear
// spring of a slider on its rail and stays regular at zero length.
#include <optional>

#include "alphaflex/model/element.hpp"
#include "alphaflex/model/planar_marker.hpp"

namespace alphaflex {

class SpringDamper2D final : public Element {
 public:
  /// `nodes` are the non-ground nodes of the two markers, whose offsets refer to them.
  SpringDamper2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2, double stiffness,
                 double damping, double rest_length, std::optional<Eigen::Vector2d> axis);
  const char* type() const override { return "spring_damper"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<SpringDamper2D>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }
  /// ½ k (L − L0)².
  double elastic_energy(const Eigen::VectorXd& q) const override {
    const double e = length(q) - l0_;
    return 0.5 * k_ * e * e;
  }

  /// Current length (or elongation along the axis) for the given local coordinates.
  double length(const Eigen::VectorXd& q) const;

 private:
  PlanarMarker p1_, p2_;
  double k_, c_, l0_;
  std::optional<Eigen::Vector2d> axis_;
};

}  // namespace alphaflex
