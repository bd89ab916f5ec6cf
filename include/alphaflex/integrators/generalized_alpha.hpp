#pragma once
// The generalized-α scheme for constrained mechanical systems, Algorithm 1 of Arnold & Brüls
// (2007): dynamic equilibrium (1)–(2) enforced exactly at t_{n+1}, the auxiliary variable a of
// eq. (3) in the Newmark formulae (4)–(5), Newton corrections q += Δq, q̇ += γ'Δq, q̈ += β'Δq
// with β', γ' of eq. (6), and the iteration matrix S_t of eq. (7).
//
// Scaling (Bottasso, Dopico & Trainelli 2006): the dynamic rows are multiplied by βh² and the
// unknown of the multiplier rows is βh²Δλ, so that every block of S_t is O(1) and its condition
// number no longer grows like h⁻⁴ (paper Sec. 3.3 and 5).
//
// Newton stopping: on the size of the last correction, |Δq_i| ≤ atol + rtol S_i (S_i the model's
// size for a length, 1 rad for an angle: docs/theory/starting_values.md §3) and
// ‖Δλ‖∞ ≤ atol_λ + rtol Λ, Λ = max(‖λ‖∞, ‖Δλ₁‖∞/(rtol ρ₁)) after a full Newton iteration (ρ₁ the
// first iteration's max_i |Δq_i|/(atol + rtol S_i): the change of λ that goes with q's tolerance),
// Λ = ‖λ‖∞ after one with an old S_t. A test on (scaled) residuals alone would stop earlier and earlier
// as h → 0 (the dynamic residual is multiplied by βh²), and the errors left in Φ(q_n) are
// amplified by 1/h² in λ (eq. 34), so the order would be lost at small h. The λ test is waived
// once Δq is at round-off level (NewtonScales::measure): λ then carries the round-off of q times
// β' ~ 1/(βh²), which no further iteration removes.
//
// Modified Newton (NewtonOptions::method; by default from NewtonOptions::modified_from unknowns
// on, or for a model with an element that favours it, decided once from the global model): S_t is kept factored across iterations and steps. The
// iteration then converges linearly with a rate θ_k = ‖Δ_k‖/‖Δ_{k−1}‖, and a small last correction
// no longer means a small error: the error left after Δ_k is about θ/(1−θ)‖Δ_k‖ (the estimate of
// simplified Newton in Hairer & Wanner, Solving ODEs II, Sec. IV.8, eq. 8.13), which is what the
// stopping rule tests instead of ‖Δ_k‖. S_t is assembled and factored afresh when θ exceeds
// max_contraction, when h changes (β', γ' and the scaling are in S_t) — except in adaptive runs
// (set_factorization_across_h), where the scaled S_t of an earlier h_f is kept while
// |1 − ρ²|/(1 + ρ²) ≤ NewtonOptions::h_change_rate (ρ = h/h_f) and its corrections are scaled by
// 2/(1 + ρ²), as IDA does (docs/theory/adaptive_steps.md §6) —, after the consistent start
// and after a checkpoint (so that a restart repeats the run bit for bit); a step that fails with an
// old S_t is repeated with full Newton before the failure is reported. Positions, velocities and
// multipliers converge to the same solution of the step's equations, so the scheme's order is kept
// (tests/unit/test_modified_newton.cpp).
#include <string>
#include <vector>

#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/integrators/linearized_system.hpp"

namespace alphaflex {


/// How a_0 is chosen (scene key solver.start; docs/theory/starting_values.md).
enum class StartValues {
  Standard,   ///< a_0 = q̈_0 (Arnold & Brüls 2007, eq. 3)
  Corrected,  ///< a_0 = q̈_0 + Δ_α h q⃛_0, Δ_α = α_m − α_f (Arnold, Brüls & Cardona 2015)
  /// a_0, q̇_0 and q̈_0 of the first step on the smooth expansion of the numerical solution through
  /// the exact one: a_0 = q̈_0 + r₁h q⃛_0 + r₂h² q⁽⁴⁾_0, q̇_0 + s₂h² q⃛_0 + s₃h³ q⁽⁴⁾_0,
  /// q̈_0 + w₂h² q⁽⁴⁾_0 (docs/theory/starting_values.md §5): the multipliers' start-up transient
  /// falls from O(h²) to O(h³)
  Smooth,
};

/// The metric of the position projection of the consistent start (scene key solver.start_projection).
enum class StartProjection {
  MinimumNorm,  ///< min ½‖Δq‖² (every coordinate alike: metres and radians mixed)
  Mass,         ///< min ½ Δqᵀ(M + εI)Δq, ε = 1e-12 max diag M: massless coordinates move first
};

struct IntegratorOptions {
  bool scaling = true;           ///< Bottasso et al. scaling of S_t
  bool consistent_start = true;  ///< project q0 and q̇0 onto the constraints
  StartValues start = StartValues::Standard;
  StartProjection projection = StartProjection::Mass;
  double load_factor = 1.0;      ///< multiplies every applied load (scene key load.factor)
  NewtonOptions newton;
};



struct StepReport {
  int iterations = 0;
  std::vector<NewtonRecord> history;
  /// With set_error_estimate(true): ‖C h² (a_{n+1} − a_n)‖∞, the local error estimate of q
  /// (AlphaParameters::local_error_constant), and ‖q_{n+1}‖∞ (both over all ranks); else -1.
  double local_error = -1.0, q_norm = -1.0;
  /// With set_error_estimate(true): the step's increment x = hΔq_n (q_{n+1} = q_n ∘ exp(x); local).
  Eigen::VectorXd increment;
  /// With set_error_estimate(true): the auxiliary vector a_n the step started from — after the
  /// start values of solver.start (a_0 of a corrected or smooth start is set inside the first step,
  /// not by initialize()) and moved to this h by (A) — so that an estimate C h² (a_{n+1} − a_n)
  /// made by the caller takes the a_n the step used (docs/theory/adaptive_steps.md, (E)).
  Eigen::VectorXd a_start;
};

class GeneralizedAlpha {
 public:
  GeneralizedAlpha(SaddlePointSystem& system, LinearSolver& solver, AlphaParameters params,
                   IntegratorOptions options);

  /// Consistent initial conditions (design §3): q0 projected onto Φ = 0 (in the metric of
  /// IntegratorOptions::projection), q̇0 onto Φ_q q̇ = −Φ_t,
  /// then [[M, Φ_qᵀ],[Φ_q, 0]] [q̈0; λ0] = [g; −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt] and a_0 = q̈0
  /// (StartValues::Corrected: the first step sets a_0 = q̈_0 + Δ_α h q⃛_0 with its own h;
  /// StartValues::Smooth: the first step also perturbs q̇_0 and q̈_0, on a copy of the state).
  /// Returns the largest change made to q0 by the projection.
  double initialize(MechanicalState& s);

  /// One step of size h (Algorithm 1). On Newton failure throws SolverError and leaves `s` as it
  /// was (the last converged state).
  StepReport step(MechanicalState& s, double h);
  /// The same step, reaching the time `t_next` given by the caller (times without drift,
  /// driver/step_controller.hpp); the step size is h.
  StepReport step(MechanicalState& s, double h, double t_next);

  /// The coefficients of the step's residual and iteration matrix S_t for a step of size h: β′, γ′
  /// (eq. 6), the Bottasso scaling when on, the load factor, and on Lie groups the step's increment
  /// x (q_{n+1} = q_n ∘ exp(x), kept by address: it must outlive the coefficients). The one place
  /// they are formed: the step and the filtered error estimate (driver/error_filter.hpp) use it.
  AssemblyCoefficients step_coefficients(double h, const Eigen::VectorXd& increment) const;

  const AlphaParameters& parameters() const { return p_; }
  const Eigen::VectorXd& auxiliary() const { return a_; }
  void set_auxiliary(const Eigen::VectorXd& a) { a_ = a; }
  /// The step size the auxiliary vector belongs to: a_n ≈ q̈(t_n + (α_m − α_f) h) (0: none, a = q̈_0).
  double auxiliary_step() const { return h_aux_; }
  void set_auxiliary(const Eigen::VectorXd& a, double h) {
    a_ = a;
    h_aux_ = h;
  }
  /// Variable steps: at a change of h the auxiliary vector is moved to the new shifted time,
  /// a ← q̈_n + (h_new/h_old)(a − q̈_n) (docs/theory/adaptive_steps.md), which keeps the local
  /// error O(h³) and the scheme second order across changes of h. Off: a is kept as it is (the
  /// fixed-step scheme, whose shortened last step stays bit for bit what it was).
  void set_variable_steps(bool on) { variable_ = on; }
  /// Compute StepReport::local_error (two all-reduces per step).
  void set_error_estimate(bool on) { estimate_ = on; }
  /// Modified Newton in adaptive runs: keep the factorization of S_t across changes of h within
  /// NewtonOptions::h_change_rate, the corrections scaled by 2/(1 + ρ²) (docs/theory/adaptive_steps.md
  /// §6). Off (fixed steps): every change of h refactors, so a fixed-step run stays bit for bit.
  void set_factorization_across_h(bool on) { across_h_ = on; }
  /// Iterations on a factorization made for another h (their corrections scaled by 2/(1 + ρ²)).
  long rescaled_iterations() const { return rescaled_; }
  /// The next steps' Newton iteration also stops only once the coordinate correction is
  /// ≤ atol + rtol‖q‖∞ (NewtonOptions::step_atol; atol < 0: off).
  void set_step_newton_tolerance(double atol, double rtol) {
    opt_.newton.step_atol = atol;
    opt_.newton.step_rtol = rtol;
  }
  /// The next step assembles and factors S_t afresh (modified Newton; e.g. after a checkpoint).
  void invalidate_factorization() {
    factored_h_ = 0.0;
    fresh_starts_left_ = 0;  // a restart knows neither: the run and its restart iterate alike
    fresh_run_ = 0;
  }
  /// Factorizations of S_t kept from an earlier iteration (modified Newton), and refactorizations
  /// forced by a slow contraction.
  long reused_iterations() const { return reused_; }
  /// Whether the steps iterate with modified Newton (NewtonOptions::uses_modified at this
  /// system's global size and elements: the same on every rank).
  bool modified_newton() const { return modified_; }
  /// The method and why (for the summary): "modified (auto: 41 unknowns >= …)", "full (…: off)".
  const std::string& newton_method() const { return newton_method_; }
  long contraction_refreshes() const { return refreshes_; }
  /// Steps begun on a fresh factorization because the last step begun on an old one had to
  /// refactor at its first rate test (modified Newton; see try_step).
  long fresh_starts() const { return fresh_starts_; }
  const PhaseTimes& times() const { return lin_.times(); }
  PhaseTimes& times() { return lin_.times(); }

 private:
  LinearizedSystem lin_;
  NewtonScales scales_;
  AlphaParameters p_;
  IntegratorOptions opt_;
  Eigen::VectorXd a_;
  bool modified_ = false;    ///< modified Newton (resolved from opt_.newton at construction)
  std::string newton_method_;  ///< newton_method()
  double factored_h_ = 0.0;  ///< h of the S_t now factored (0: none usable)
  double h_aux_ = 0.0;       ///< the h a_ belongs to
  bool variable_ = false, estimate_ = false, across_h_ = false;
  long reused_ = 0, refreshes_ = 0, rescaled_ = 0, fresh_starts_ = 0;
  /// Modified Newton: how many more steps begin on a fresh factorization, and how many the last
  /// failed probe of an old one granted (1, 2, 4, … 16; 0: the last probe passed).
  int fresh_starts_left_ = 0, fresh_run_ = 0;
  /// StartValues::Corrected: the start time, and the state q0, q̇0, q̈0 of the consistent start
  /// (the first step of size h from it sets a_0 = q̈_0 + Δ_α (q̈(t_0 + h) − q̈_0)).
  bool start_pending_ = false;
  double t_start_ = 0.0;

  /// q̈ and λ of the index-1 system [[M, Φ_qᵀ],[Φ_q, 0]] [q̈; λ] = [g; −c] at (q, q̇, t) of `s`.
  void consistent_accelerations(MechanicalState& s);
  /// The corrected a_0 for a first step of size h (StartValues::Corrected).
  Eigen::VectorXd corrected_start(const MechanicalState& s, double h);
  /// q̈ of the index-1 system at the Taylor state σ after the start, q_0 ∘ exp(σq̇_0 + ½σ²q̈_0 +
  /// σ³/6 q⃛), q̇_0 + σq̈_0 + ½σ²q⃛, t_0 + σ (q⃛ null: the terms in q⃛ left out).
  Eigen::VectorXd acceleration_ahead(const MechanicalState& s, double sigma, const Eigen::VectorXd* q3);
  /// StartValues::Smooth: sets a_ and perturbs s.v, s.qdd for a first step of size h.
  void smooth_start(MechanicalState& s, double h);
  /// The step after the start values are set: the auxiliary vector moved to a new h, the step,
  /// the local error estimate.
  StepReport advance(MechanicalState& s, double h, double t_next);
  /// W = M + εI of the mass-weighted projection: ε (0 when the model has no mass at all).
  double projection_regularisation(const MechanicalState& s);

  /// Whether the S_t factored for factored_h_ may serve a step of size h (across_h_ only).
  bool usable_across_h(double h) const;
  StepReport step_at(MechanicalState& s, double h, double t_next);
  StepReport try_step(MechanicalState& s, double h, double t_next, bool allow_reuse, bool& used_old_matrix);
};

}  // namespace alphaflex
