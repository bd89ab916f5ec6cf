#pragma once
// One linearization of the equations of motion (or of equilibrium): assemble S and r at a state,
// factor S with the linear solver, solve, and bring the solution back in model order — with the
// wall time split by phase, PETSc log events, and a named diagnosis (redundant joints, coordinates
// nothing acts on) instead of a bare factorization error. Shared by the time integrator and the
// quasi-static solver.
#include <string>
#include <vector>

#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/petsc_error.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {

struct NewtonOptions {
  int max_iterations = 20;
  double rtol = 1e-9;          ///< relative size of the last correction (q and λ)
  double atol = 1e-12;         ///< absolute, for coordinates (m, rad)
  double atol_lambda = 1e-9;   ///< absolute, for multipliers (N, N·m)
  /// Modified Newton (scene key solver.newton.modified): keep the factorization of S_t across
  /// iterations and steps, and refactorize only when the contraction rate θ = ‖Δ_k‖/‖Δ_{k−1}‖
  /// exceeds max_contraction, when h changes (in adaptive runs: beyond h_change_rate), or after a
  /// checkpoint (generalized_alpha.hpp).
  /// `automatic` (the default) chooses by the size of the system and its elements, see uses_modified.
  enum class Method { full, modified, automatic };
  Method method = Method::automatic;
  /// With Method::automatic: modified Newton from this many unknowns (coordinates and
  /// multipliers, all ranks together), full Newton below unless an element favours modified
  /// Newton. Measured on every scene of inputs/ (docs/performance.md, "Modified Newton by
  /// default"; dense LU by LAPACK): modified Newton gains 1.1–7× per step from 38 unknowns on but
  /// on two mechanisms whose residual is the costly part (0.69–0.91×), and loses (0.71–0.94×) on the
  /// 9–22-unknown rigid mechanisms, where a dense LU costs less than the extra residual
  /// evaluations of its linear convergence.
  long modified_from = 30;
  /// Whether a system of `global_unknowns` unknowns (the same number on every rank, so every
  /// rank decides alike) iterates with modified Newton; `favoured`: the model has an element for
  /// which modified Newton pays at any size (Element::favours_modified_newton; decided on the
  /// global model, the same on every rank).
  bool uses_modified(long global_unknowns, bool favoured = false) const {
    return method == Method::modified ||
           (method == Method::automatic && (global_unknowns >= modified_from || favoured));
  }
  double max_contraction = 0.5;  ///< θ above which S_t is assembled and factored afresh
  /// Adaptive steps with modified Newton: the scaled S_t factored for h_f serves a step of size h
  /// while |1 − ρ²|/(1 + ρ²) ≤ h_change_rate, ρ = h/h_f — the contraction rate that the change of h
  /// alone gives the stale iteration with its correction scaled by 2/(1 + ρ²). IDA's XRATE is 0.25
  /// (ρ² in [0.6, 1/0.6]; Hindmarsh et al., ACM TOMS 31 (2005) 363–396); 0.1 (ρ from 0.905 to 1.105)
  /// was faster on the hammer-struck beam, where Newton's rtol of 1e-9 makes every unit of rate cost
  /// iterations (docs/theory/adaptive_steps.md §6). 0: refactor at every change of h.
  double h_change_rate = 0.1;
  /// Adaptive steps: the coordinate correction must also be ≤ step_atol + step_rtol‖q‖∞ (not below
  /// the round-off level 10⁴ε‖q‖∞), a fraction of the step's local error tolerance, so that what
  /// Newton leaves stays out of the error estimate (docs/theory/adaptive_steps.md). < 0: off.
  double step_atol = -1.0, step_rtol = 0.0;
};

struct NewtonRecord {
  double residual_dynamic = 0.0;     ///< ‖r_q‖₂ as assembled (scaled by βh² when scaling is on)
  double residual_constraint = 0.0;  ///< ‖Φ‖₂ (m, rad)
  double correction_q = 0.0, correction_lambda = 0.0;  ///< ‖Δq‖∞, ‖Δλ‖∞
  /// max_i |Δq_i|/(atol + rtol S_i) and max_i |Δq_i|/floor_i over all ranks (NewtonScales::measure):
  /// ≤ 1 when the coordinates are converged, at round-off.
  double q_tolerance_ratio = 0.0, q_roundoff_ratio = 0.0;
};

/// Per-unknown scales of Newton's test (docs/theory/starting_values.md §3), so that it neither mixes
/// metres and radians nor depends on where the origin is: S_i = L, the model's size (diagonal of
/// the bounding box of the nodes at t = 0; 1 m if they coincide), for a length, 1 rad for an angle.
struct NewtonScales {
  Eigen::VectorXd scale;       ///< S_i of every local unknown (m or rad)
  std::vector<int> position;   ///< the configuration number of unknown i if it is a position, else −1
  double model_size = 1.0;     ///< L (m)
  static NewtonScales of(const Subdomain& sub);
  /// Sets rec.q_tolerance_ratio and rec.q_roundoff_ratio for the correction dq at q (collective;
  /// the round-off floor is explained in linearized_system.cpp).
  void measure(NewtonRecord& rec, const Subdomain& sub, const NewtonOptions& options, const Eigen::VectorXd& q,
               const Eigen::VectorXd& dq) const;
};

/// The record of one Newton iteration from the local residual and corrections, with norms over
/// all ranks (collective): ‖r_q‖₂ over owned coordinates, ‖Φ‖₂, ‖Δq‖∞, ‖Δλ‖∞.
NewtonRecord newton_record(const Subdomain& sub, const ModelVector& residual, const Eigen::VectorXd& dq,
                           const Eigen::VectorXd& dlambda);
/// The Newton stopping rule on the last correction (generalized_alpha.hpp explains why), on the
/// scales of NewtonScales: |Δq_i| ≤ atol + rtol S_i for every unknown and ‖Δλ‖∞ ≤ atol_λ + rtol Λ
/// (Λ = `lambda_scale`, the multipliers' scale: ‖λ‖∞, or more, generalized_alpha.hpp), the λ test
/// waived once Δq is at round-off (NewtonScales::measure) after the first iteration.
bool newton_converged(const NewtonOptions& options, const NewtonRecord& last, int iteration, double lambda_scale);
/// The aligned table of a Newton history printed when it fails.
std::string format_newton_history(const std::vector<NewtonRecord>& history, bool scaled);

/// Wall time spent by phase (seconds, this rank).
struct PhaseTimes {
  double assembly = 0.0, factorization = 0.0, solve = 0.0, output = 0.0;
  /// Before the first step: partition, subdomain, preallocation, output files, the check for
  /// redundant joints (the consistent start's solves count as assembly, factorization, solve).
  double setup = 0.0;
};

class LinearizedSystem {
 public:
  LinearizedSystem(SaddlePointSystem& system, LinearSolver& solver);

  /// Assemble, factor, solve S x = r; returns x in model order (and r if asked). Throws
  /// SolverError on failure; InputError if `initializing` and the model itself is singular.
  ModelVector solve(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows,
                    ModelVector* residual);
  /// The same with the last factorization kept: only r is assembled (no tangents), then solved
  /// with the factors of an earlier S (modified Newton).
  ModelVector solve_with_last_factorization(const MechanicalState& s, const AssemblyCoefficients& c,
                                            ConstraintRows rows, ModelVector* residual);
  /// x = S⁻¹ (s_r c_m M(q) w; 0) with the factors of an earlier S (SaddlePointSystem::assemble_mass_action):
  /// one application of the filtered error estimate's W (driver/error_filter.hpp).
  ModelVector solve_mass_action_with_last_factorization(const MechanicalState& s, const AssemblyCoefficients& c,
                                                        const Eigen::VectorXd& w);
  /// "largest equilibrium residual … at node '…' (…); largest constraint violation … in joint '…'".
  std::string describe_largest(const ModelVector& r) const;

  SaddlePointSystem& system() { return sys_; }
  const Model& model() const { return sys_.model(); }
  PhaseTimes& times() { return times_; }
  const PhaseTimes& times() const { return times_; }
  bool initializing = false;  ///< a singular matrix is then bad input (the model as given)

 private:
  /// r (and S if `matrix`) at `s`, timed as assembly; r in model order if asked.
  void assemble(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows, bool matrix,
                ModelVector* residual);
  /// x = S⁻¹ r with the factors in place, in model order, timed as solve.
  ModelVector solve_factored();

  SaddlePointSystem& sys_;
  LinearSolver& solver_;
  PhaseTimes times_;
};

}  // namespace alphaflex
