#pragma once
// Static path following by arc length: equilibrium r(q, Λ) = r_int(q) + Φ_qᵀλ − Λ f(q) = 0,
// Φ(q) = 0 traced through limit points, the load factor Λ an unknown beside q and λ.
//
// Each step: a predictor along the tangent (q, λ)' = −S⁻¹ ∂r/∂Λ at the last converged state, then
// Newton corrections constrained to Crisfield's cylinder ‖Δu‖²_w = Δℓ² (Crisfield 1981, "A fast
// incremental/iterative solution procedure that handles snap-through", Comput. Struct. 13:55–62):
// with x_r = S⁻¹r and x_f = S⁻¹∂r/∂Λ — two solves with one factorization of the bordered
// saddle-point matrix S = [[K + K_Φ, Φ_qᵀ], [Φ_q, 0]], so joints and constraints are included —
// the correction is δu = −x_r − δΛ x_f with δΛ a root of the quadratic ‖Δu + δu‖²_w = Δℓ², the
// root whose increment makes the smaller angle with the previous one (Crisfield 1981). Δu is the
// increment in the tangent space of the group, log(q_n⁻¹q) (Model::difference), so rotations enter
// as rotation vectors. The weight w = 1/‖u₀‖², u₀ the linear response to the loads at Λ = 1, makes
// Δℓ a load factor on the linear part of the path.
//
// The predictor's direction (the sign of ΔΛ) follows the previous converged increment:
// sign(Δu_{n−1}ᵀ t), t the tangent (Feng, Perić & Owen 1995, "A new criterion for determination
// of initial loading parameter in arc-length methods", Comput. Struct. 58:479–485): it passes limit
// points, where det S changes sign (the determinant rule of Crisfield 1981 fails at bifurcations).
//
// Line search (Crisfield 1983, "An arc-length method including line searches and accelerations",
// IJNME 19:1269–1289): the search function s(η) = δxᵀ r(x + ηδx) along the whole correction (q, λ, Λ);
// a correction with |s(1)| > 0.8|s(0)| is scaled by η from regula falsi, clamped to [0.1, 1].
//
// The arc length adapts to the Newton iterations of the last step: Δℓ ← Δℓ·√(target/iterations)
// (Crisfield 1981, eq. 27; Ramm 1981), within [min, max]; a step that fails (no convergence, or
// no real root) is repeated with Δℓ halved.
//
// Critical points: a limit point is where ΔΛ changes sign between two converged steps (its load
// factor is the vertex of the parabola through the three points around it, Λ against the path's
// arc length); a bifurcation candidate is a sign change of det S (MUMPS' ICNTL(33), the dense
// path's LU) without one of ΔΛ. The sign of det S is that of the stiffness reduced to the
// constraints' null space times (−1)^m, m the number of constraints, so its changes are the
// reduced stiffness's.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "alphaflex/integrators/quasi_static.hpp"

namespace alphaflex {

struct CriticalPoint {
  enum class Kind { LimitMaximum, LimitMinimum, Bifurcation } kind = Kind::LimitMaximum;
  double load_factor = 0.0;  ///< estimated load factor at the point
  int step = 0;              ///< the converged step nearest to it (0: the start)
  double lower = 0.0, upper = 0.0;  ///< load factors of the converged steps around it
  std::string kind_name() const;
};

struct ArcLengthReport : StaticReport {
  std::vector<CriticalPoint> critical_points;
  double load_factor = 0.0;     ///< at the last converged step
  double min_arc = 0.0, max_arc = 0.0;  ///< smallest and largest arc length of a converged step
  int line_searches = 0;        ///< corrections scaled by the line search
  std::string stop;             ///< why the path ended: "max_load_factor" or "max_steps"
};

class ArcLength {
 public:
  ArcLength(SaddlePointSystem& system, LinearSolver& solver, StaticOptions options);

  /// Follows the path from `s` at load factor 0 (velocities and accelerations set to zero) until
  /// |Λ| reaches max_load_factor (the last step lands on it) or max_steps steps. `on_step(state,
  /// Λ)` after each converged step (not the start: the caller has it); `critical` is called when a critical point is
  /// found (after the step that shows it). Throws SolverError with the Newton history when the arc
  /// length falls below its minimum; `s` then holds the last converged step.
  ArcLengthReport solve(MechanicalState& s, const std::function<void(const MechanicalState&, double)>& on_step = {},
                        const std::function<void(const CriticalPoint&)>& critical = {});

  PhaseTimes& times() { return lin_.times(); }

 private:
  struct Linearization {
    ModelVector xr, xf, r;  ///< S⁻¹r, S⁻¹∂r/∂Λ, r
    int det_sign = 0;
  };
  /// Assembles and factors S at (s, Λ), solves for x_r and x_f (the second solve reuses the factors).
  Linearization linearize(const MechanicalState& s, double load_factor);
  /// w·(a·b) over the owned coordinates of all ranks; `dots` several in one all-reduce.
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  std::vector<double> dots(const std::vector<std::pair<const Eigen::VectorXd*, const Eigen::VectorXd*>>& pairs) const;
  /// The line search's δxᵀr over the coordinates and multipliers of all ranks.
  double search_slope(const ModelVector& dx, const ModelVector& r) const;
  /// One step from the converged (sn, Λn): predictor with increment dlf along the tangent of `lin`,
  /// then corrections on the cylinder of radius dl (or at fixed Λ when `fixed_load`). On success
  /// `s`, `dlf` are the converged state and load increment.
  bool step(const MechanicalState& sn, double lfn, const Linearization& lin, double dl, bool fixed_load,
            MechanicalState& s, double& dlf, std::vector<NewtonRecord>& history, ModelVector& r, int& line_searches);

  LinearizedSystem lin_;
  const Subdomain& sub_;
  LinearSolver& solver_;
  StaticOptions opt_;
  double weight_ = 1.0;  ///< 1/‖u₀‖²
};

}  // namespace alphaflex
