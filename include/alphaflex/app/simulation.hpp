#pragma once
// One run of a scene: DofMap → assembly → MUMPS → generalized-α, with results written as it goes.
// Used by the `alphaflex run` command and by the tests (in-process runs of scenes).
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "alphaflex/integrators/arc_length.hpp"
#include "alphaflex/app/memory_estimate.hpp"
#include "alphaflex/io/checkpoint.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {

struct RunOptions {
  std::string outdir = ".";
  bool write_results = true;  ///< HDF5/XDMF/CSV (tests may switch them off)
  bool verbose = true;        ///< header and summary on rank 0
  bool keep_history = false;  ///< keep every step's sensors in RunSummary (tests; O(steps) memory)
  /// Where the ranks agree that an error is collective (app/exit_agreement.hpp): an error that only
  /// some ranks caught ends the job (MPI_Abort) after `exit_timeout` s. MPI_COMM_NULL: no check.
  MPI_Comm exit_comm = MPI_COMM_NULL;
  double exit_timeout = 5.0;
  /// A checkpoint to go on from (io/checkpoint.hpp); empty: start at t = 0.
  std::string restart;
  /// Called on every rank with the state (model order, as RunSummary::final_state) at t = 0 and
  /// after every converged step, load steps included; the study module uses it for histories
  /// of multipliers and strain energies. Empty: not called.
  std::function<void(const MechanicalState&)> on_step;
  /// Stop once the run is set up — partition, assembly structure, solver, and (dynamic runs) the
  /// consistent start of q0, q̇0, q̈0 — before the first time or load step and before any output
  /// file: everything a bad input can fail in before the run proper (the fuzz test, tests/fuzz).
  bool stop_after_start = false;
};

/// A run's figures; the checkpoints written (CheckpointStats, io/checkpoint.hpp) are the time loop's.
struct RunSummary : CheckpointStats {
  int steps = 0;              ///< time steps (load steps in a static analysis)
  int static_steps = 0, static_cuts = 0;  ///< load steps and step cuts of the quasi-static solve
  /// Arc-length statics (solver.static.method: arc_length, integrators/arc_length.hpp): the path's
  /// end, its limit points and bifurcation candidates, each with the sensors (scene order) at the
  /// converged step nearest to it.
  bool arc_length = false;
  ArcLengthReport path;
  std::vector<std::vector<double>> critical_sensors;
  int step_cuts = 0;          ///< halvings of h after failed dynamic steps (solver.step_cuts)
  double h_min = 0.0, h_max = 0.0;  ///< smallest and largest step taken (s; steps shortened to land on t_end or an output time aside)
  long long rejected_steps = 0;     ///< steps rejected by the local error test (solver.tolerance) and retried
  long newton_total = 0;
  int newton_max = 0;
  int unknowns = 0, coordinates = 0, multipliers = 0;
  int factorizations = 0, symbolic_analyses = 0;
  /// Modified Newton: iterations on a factorization kept from before, refactorizations forced by a
  /// contraction rate above solver.newton.max_contraction (-1: full Newton).
  long reused_iterations = -1, contraction_refreshes = 0;
  /// Dynamic runs: Newton's method and why (GeneralizedAlpha::newton_method); empty for statics.
  std::string newton_method;
  /// Modified Newton: steps begun on a fresh factorization because the last step begun on an old
  /// one had to refactor at its first rate test (GeneralizedAlpha::fresh_starts).
  long fresh_starts = 0;
  /// Modified Newton in adaptive runs: iterations on a factorization made for another h
  /// (docs/theory/adaptive_steps.md §6).
  long rescaled_iterations = 0;
  double wall = 0.0;
  double projection = 0.0;  ///< largest change of q0 by the consistent start
  PhaseTimes times;
  MechanicalState final_state;
  std::vector<std::string> sensor_names;  ///< in scene order (the CSV header after t)
  std::vector<double> final_sensors;  ///< sensor values at the final time, in scene order
  std::vector<double> times_out;      ///< t of every step (including 0), if keep_history
  std::vector<std::vector<double>> sensor_history;  ///< [step][sensor], if keep_history
  std::vector<std::string> warnings;  ///< found during the run (shortened last step, round-off floor, ...)
  // Parallel layout (METIS partition) and cost.
  int ranks = 1;
  int edge_cut = 0;                        ///< couplings (element/joint node pairs) cut by the partition
  std::vector<int> unknowns_per_rank, ghosts_per_rank;  ///< owned unknowns, ghost nodes
  FactorStatistics mumps;                  ///< of the last factorization
  int workspace_retries = 0, workspace_percent = 0;  ///< MUMPS refactorizations with more workspace, ICNTL(14) now
  std::string blas;  ///< the BLAS (and LAPACK) the dense kernels ran on, found at run time (core/blas_library.hpp)
  double peak_memory_mb = 0.0, peak_memory_max_mb = 0.0;  ///< peak resident set: sum, largest rank
  /// Resident memory that reading the scene (and its mesh) and building its whole model took on
  /// the largest rank: the part every rank holds whatever their number (set by the command).
  double scene_memory_mb = -1.0;
  /// The memory a rank needs, estimated after MUMPS' analysis (app/memory_estimate.hpp).
  MemoryEstimate memory_estimate;
  std::string restarted_from;  ///< the checkpoint the run restarted from
  double restart_time = 0.0;
  std::string h5, xdmf, csv;
};

/// Runs `scene` to its t_end. Throws InputError / SolverError (on every rank alike) on failure,
/// after writing the last converged state.
RunSummary run_simulation(Scene& scene, const RunOptions& options, MPI_Comm comm);

/// The summary as printed by `alphaflex run`.
std::string format_summary(const Scene& scene, const RunSummary& s);

}  // namespace alphaflex
