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
// Newton stopping: on the size of the last correction, ‖Δq‖∞ ≤ atol + rtol‖q‖∞ and
// ‖Δλ‖∞ ≤ atol_λ + rtol‖λ‖∞. A test on (scaled) residuals alone would stop earlier and earlier
// as h → 0 (the dynamic residual is multiplied by βh²), and the errors left in Φ(q_n) are
// amplified by 1/h² in λ (eq. 34), so the order would be lost at small h. The λ test is waived
// once Δq is at round-off level (≤ 10⁴ ε ‖q‖): λ then carries the round-off of q times
// β' ~ 1/(βh²), which no further iteration removes.
#include <string>
#include <vector>

#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {

struct NewtonOptions {
  int max_iterations = 20;
  double rtol = 1e-9;          ///< relative size of the last correction (q and λ)
  double atol = 1e-12;         ///< absolute, for coordinates (m, rad)
  double atol_lambda = 1e-9;   ///< absolute, for multipliers (N, N·m)
};

struct IntegratorOptions {
  bool scaling = true;           ///< Bottasso et al. scaling of S_t
  bool consistent_start = true;  ///< project q0 and q̇0 onto the constraints
  NewtonOptions newton;
};

/// Wall time spent by phase (seconds, this rank).
struct PhaseTimes {
  double assembly = 0.0, factorization = 0.0, solve = 0.0, output = 0.0;
};

struct NewtonRecord {
  double residual_dynamic = 0.0;     ///< ‖r_q‖₂ as assembled (scaled by βh² when scaling is on)
  double residual_constraint = 0.0;  ///< ‖Φ‖₂ (m, rad)
  double correction_q = 0.0, correction_lambda = 0.0;  ///< ‖Δq‖∞, ‖Δλ‖∞
};

struct StepReport {
  int iterations = 0;
  std::vector<NewtonRecord> history;
};

class GeneralizedAlpha {
 public:
  GeneralizedAlpha(SaddlePointSystem& system, LinearSolver& solver, AlphaParameters params,
                   IntegratorOptions options);

  /// Consistent initial conditions (design §3): q0 projected onto Φ = 0, q̇0 onto Φ_q q̇ = −Φ_t,
  /// then [[M, Φ_qᵀ],[Φ_q, 0]] [q̈0; λ0] = [g; −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt] and a_0 = q̈0.
  /// Returns the largest change made to q0 by the projection.
  double initialize(MechanicalState& s);

  /// One step of size h (Algorithm 1). On Newton failure throws SolverError and leaves `s` as it
  /// was (the last converged state).
  StepReport step(MechanicalState& s, double h);

  const AlphaParameters& parameters() const { return p_; }
  const Eigen::VectorXd& auxiliary() const { return a_; }
  void set_auxiliary(const Eigen::VectorXd& a) { a_ = a; }
  const PhaseTimes& times() const { return times_; }
  PhaseTimes& times() { return times_; }

 private:
  /// Assemble, factor, solve S x = r; returns x in model order. Throws SolverError on failure.
  ModelVector solve_linear(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows,
                           ModelVector* residual);
  std::string describe_largest(const ModelVector& r) const;

  SaddlePointSystem& sys_;
  LinearSolver& solver_;
  AlphaParameters p_;
  IntegratorOptions opt_;
  Eigen::VectorXd a_;
  PhaseTimes times_;
  bool initializing_ = false;  ///< a singular matrix during initialize() is bad input
};

}  // namespace alphaflex
