#pragma once
// Quasi-static analysis: equilibrium Σ_e r_e(q; λ_load) + Φ_qᵀ λ = 0, Φ(q, t) = 0 with no inertia,
// the applied loads (forces, moments, gravity) multiplied by a load factor stepped from 0 to its
// target. Same elements, joints, assembly and linear solver as the dynamics: S = [[K + K_Φ, Φ_qᵀ],
// [Φ_q, 0]], Newton increments applied through the retraction q ← q ∘ exp(−Δ) on the group.
// A load step whose Newton iteration fails is halved (adaptive step cut), down to a limit; the
// step grows again (×1.5) after an easy step. Each load step starts from the secant predictor,
// the last converged state moved on along the path of the two before (q_k ∘ exp(s·log(q_{k−1}⁻¹q_k)),
// s the ratio of the load increments), which saves Newton iterations on smooth load paths. Used for static benchmarks and for the pre-loaded
// starting state of a dynamic run.
#include <functional>

#include "alphaflex/integrators/linearized_system.hpp"

namespace alphaflex {

/// Path following by arc length (integrators/arc_length.hpp; `solver.static.arc_length`). Arc
/// lengths are in load-factor units: the increment's coordinates are measured against the linear
/// response u₀ = K₀⁻¹f to the loads at load factor 1 at the start, so that a step of arc length
/// Δℓ on the initial, linear part of a path is a load step Δλ = Δℓ.
struct ArcLengthOptions {
  double initial = 0.1;          ///< first arc length
  double min = 1e-5;             ///< smallest arc length before giving up
  double max = 1.0;              ///< largest arc length
  int target_iterations = 5;     ///< Newton iterations per step the arc length is adapted to
  double max_load_factor = 0.0;  ///< stop when |λ| reaches it (λ lands on it); 0: |target|
  int max_steps = 200;           ///< stop after this many steps
  bool line_search = true;       ///< Crisfield's (1983) line search on the corrections
};

struct StaticOptions {
  enum class Method { LoadControl, ArcLength } method = Method::LoadControl;
  ArcLengthOptions arc_length;
  int steps = 10;          ///< initial number of equal load steps from 0 to the target
  int max_cuts = 12;       ///< halvings of one load step before giving up (2⁻¹² of the first step)
  double target = 1.0;     ///< final load factor
  NewtonOptions newton;
};

struct StaticReport {
  int load_steps = 0;      ///< converged load steps
  int cuts = 0;            ///< step halvings after a Newton failure
  long iterations = 0;     ///< Newton iterations in all
  int max_iterations = 0;  ///< most Newton iterations in one load step
};

class QuasiStatic {
 public:
  QuasiStatic(SaddlePointSystem& system, LinearSolver& solver, StaticOptions options);

  /// Brings `s` (velocities and accelerations set to zero) to equilibrium at the target load
  /// factor, at the fixed time s.t. `on_step(state, load factor)` is called after each converged
  /// load step. Throws SolverError with the Newton history if a step cannot be completed; `s` then
  /// holds the last converged load step.
  StaticReport solve(MechanicalState& s, const std::function<void(const MechanicalState&, double)>& on_step = {});

  PhaseTimes& times() { return lin_.times(); }

 private:
  /// Newton at load factor `lf` from the start `trial`; on convergence `s` = the result. Returns
  /// false (s unchanged) if it does not converge.
  bool equilibrium(MechanicalState& s, MechanicalState trial, double lf, std::vector<NewtonRecord>& history,
                   ModelVector& r);

  LinearizedSystem lin_;
  StaticOptions opt_;
};

}  // namespace alphaflex
