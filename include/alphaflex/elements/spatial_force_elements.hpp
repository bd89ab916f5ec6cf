#pragma once
// Spatial force elements between two markers (frames fixed to nodes of R³×SO(3), or the ground):
// spring-dampers along the line of their points, and bushings (6×6 stiffness and damping in a
// chosen frame). Both are coordinate forces (elements/coordinate_force.hpp): exact r, K, C.
// Theory and sources: docs/theory/force_elements.md.
#include <memory>

#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/time_function.hpp"
#include "alphaflex/elements/coordinate_force.hpp"

namespace alphaflex {

/// The force of a scalar coordinate x with rest value x0, rate ẋ and time t:
///   linear:     f = k (x − x0) + c ẋ + f0         (f0: the preload, the force at x = x0)
///   table:      f = F(x − x0) + c ẋ               (F piecewise linear through the given points)
///   expression: f = F(x − x0, ẋ, t)               (core/expression.hpp, with its exact gradient)
/// A positive f resists an increase of x (a spring's tension).
class ScalarForceLaw {
 public:
  static ScalarForceLaw linear(double stiffness, double damping, double rest, double preload);
  static ScalarForceLaw table(TimeFunctionPtr force_of_deflection, double damping, double rest);
  /// `f`'s variables are (deflection x − x0, rate ẋ, time t), in that order, whatever their names.
  static ScalarForceLaw expression(std::shared_ptr<const ExpressionFunction> f, double rest);

  /// f and its partial derivatives ∂f/∂x, ∂f/∂ẋ.
  void evaluate(double x, double rate, double t, double& f, double& f_x, double& f_rate) const;
  /// The stored energy at x: ∫ f dx from x0 at ẋ = 0 for the linear law (½k(x − x0)² + f0 (x − x0));
  /// 0 for the others (not part of the law's definition: an expression may depend on ẋ and t).
  double potential(double x) const;
  double rest() const { return rest_; }

 private:
  enum class Kind { linear, table, expression } kind_ = Kind::linear;
  double k_ = 0.0, c_ = 0.0, rest_ = 0.0, preload_ = 0.0;
  TimeFunctionPtr table_;
  std::shared_ptr<const ExpressionFunction> expression_;
};

/// A spring-damper between the points of two markers: ε = L = |p_B − p_A|, tension N = f(L, L̇, t)
/// (ScalarForceLaw, with x0 the rest length), acting as +N e on A and −N e on B (e = (p_B − p_A)/L).
/// Undefined where the points coincide (a ConfigurationError names the element).
class SpatialSpringDamper final : public Element {
 public:
  /// `nodes`: the markers' non-ground nodes, which their slots refer to.
  SpatialSpringDamper(std::string name, std::vector<int> nodes, SpatialMarker a, SpatialMarker b, ScalarForceLaw law);
  const char* type() const override { return "spring_damper"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<SpatialSpringDamper>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }
  std::vector<CellField> cell_fields() const override;
  /// length (m), elongation L − L0 (m), rate L̇ (m/s), tension N (N).
  void output(const LocalState& s, Eigen::VectorXd& values) const override;
  double elastic_energy(const Eigen::VectorXd& q) const override;
  double length(const Eigen::VectorXd& q) const;

 private:
  SpatialMarker a_, b_;
  ScalarForceLaw law_;
};

/// A bushing: markers A and B, which coincide at t = 0, held by a 6×6 stiffness K and damping C
/// acting on ε = (u, γ) in the frame of A:
///   u = R_Aᵀ (p_B − p_A),   γ = 2 vee(R − Rᵀ) / (1 + tr R) = 2 tan(φ/2) n,   R = R_Aᵀ R_B,
/// (γ: the rotation φ about n of B relative to A, as twice the Gibbs vector — smooth through φ = 0,
/// equal to φ n to O(φ³), defined up to half a turn), f = K ε + C ε̇, r = J_εᵀ f. With a
/// symmetric K the elastic part is conservative, V = ½ εᵀ K ε. K and C must be positive
/// semi-definite (the scene reader refuses others).
class Bushing final : public Element {
 public:
  using Matrix6 = Eigen::Matrix<double, 6, 6>;
  Bushing(std::string name, std::vector<int> nodes, SpatialMarker a, SpatialMarker b, const Matrix6& stiffness,
          const Matrix6& damping);
  const char* type() const override { return "bushing"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<Bushing>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }
  std::vector<CellField> cell_fields() const override;
  /// deflection ε (u in m, γ in rad) and generalized force f = K ε + C ε̇ (N, N·m).
  void output(const LocalState& s, Eigen::VectorXd& values) const override;
  double elastic_energy(const Eigen::VectorXd& q) const override;

  /// ε of two poses: the coordinates above (templated for the AD kernels).
  template <class S>
  void coordinates(const Pose<S>* frames, CoordinateValues<S>& eps) const {
    const Pose<S> A = a_.pose(frames), B = b_.pose(frames);
    const Vec3<S> u = A.R.transpose() * (B.x - A.x);
    const Mat3<S> R = A.R.transpose() * B.R;
    const S scale = S(2.0) / (S(1.0) + R.trace());
    eps.resize(6);
    eps.template head<3>() = u;
    eps[3] = scale * (R(2, 1) - R(1, 2));
    eps[4] = scale * (R(0, 2) - R(2, 0));
    eps[5] = scale * (R(1, 0) - R(0, 1));
  }

 private:
  SpatialMarker a_, b_;
  Matrix6 k_, c_;
};

}  // namespace alphaflex
