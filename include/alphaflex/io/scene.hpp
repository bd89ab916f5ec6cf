#pragma once
// Scene files (YAML) → a validated Model and run settings. Every key is documented in
// docs/input.md; unknown keys, wrong types and dangling references raise InputError naming the
// file, line, key path and what was expected.
#include <mpi.h>

#include <memory>
#include <string>
#include <vector>

#include "alphaflex/integrators/generalized_alpha.hpp"
#include "alphaflex/integrators/quasi_static.hpp"
#include "alphaflex/model/model.hpp"

namespace alphaflex {

enum class Analysis { Dynamic, Static };

struct RunSettings {
  int dimension = 2;    ///< 2: planar bodies (x, y, θ); 3: spatial bodies and beams on R³×SO(3)
  Analysis analysis = Analysis::Dynamic;
  /// Load stepping of a static analysis (its target is the load factor), or of the static
  /// equilibrium that starts a dynamic run when `initial_static`.
  StaticOptions statics;
  bool initial_static = false;
  double load_factor = 1.0;  ///< multiplies every applied load (`load.factor`)
  AlphaParameters parameters = AlphaParameters::from_rho_inf(0.7);
  IntegratorOptions integrator;
  double h = 1e-3;      ///< step size (s)
  /// Newton failure policy: up to this many successive halvings of h when a step does not converge
  /// (0: off, the run stops at the first failure); h grows back by doubling after 4 good steps.
  int step_cuts = 0;
  /// solver.linear.low_rank: MUMPS' block low-rank dropping tolerance (0: exact factorization).
  double low_rank = 0.0;
  double t_end = 1.0;   ///< final time (s)
  /// Adaptive steps (solver.tolerance: rtol, atol; 0, 0: fixed steps), bounds of h (s; 0: defaults).
  double tolerance_rtol = 0.0, tolerance_atol = 0.0, h_min = 0.0, h_max = 0.0;
  double tolerance_hold = 1.0;  ///< solver.tolerance.hold (AdaptiveOptions::hold)
  /// solver.tolerance.estimate: filter the local error estimate by the iteration matrix (true)
  /// or take it unfiltered (false); docs/theory/adaptive_steps.md §3b.
  bool filtered_error_estimate = true;
  double output_dt = 0.0;  ///< fields at multiples of this time (s; 0: every `output_every` steps)
  /// Times where a load's or driver's time function has a kink (Reader::breakpoints), sorted:
  /// adaptive steps land on them.
  std::vector<double> breakpoints;
  int output_every = 1; ///< HDF5 output every N steps (sensors: every step)
  /// output.sensors: write NAME.csv; output.sensors_dt: a row at the first step at or after each
  /// multiple of this time (s; 0: every step).
  bool sensors = true;
  double sensors_dt = 0.0;
  double progress_interval = 30.0;  ///< s of wall time between progress lines in batch logs (0: none)
  bool hdf5 = true;
  /// s of wall time a results part stays open before it is committed (io/results_writer.hpp);
  /// 0: every output step.
  double commit_interval = 1.0;
  /// Checkpoints (io/checkpoint.hpp): every this many steps, or every this many s of wall time
  /// (0: only at the end of the run); keep this many of them.
  long checkpoint_steps = 0;
  double checkpoint_wall = 0.0;
  int checkpoint_keep = 1;
  bool checkpoint_at_end = true;  ///< output.checkpoint_at_end: a checkpoint when the run ends
  /// output.superelement_cache: reduced blocks kept in OUTDIR/NAME.superelements.h5 and read from
  /// there by a later run with the same key (io/superelement_cache.hpp).
  bool superelement_cache = true;
};

struct Scene {
  std::string file;
  std::string name;
  std::string description;
  RunSettings settings;
  std::unique_ptr<Model> model;
  std::vector<std::string> warnings;  ///< parameter checks (eq. 17, 18, 20)
  /// Per reduced block, where its superelement came from (read from the cache, or computed and
  /// its CPU time), for the summary; and the cache files that could not be read or written.
  std::vector<std::string> superelements, superelement_warnings;
};

/// Reads and validates a scene. `overrides` are "key.path=value" strings (from --set) applied to
/// the YAML tree before validation, so they are checked like the file itself. Collective over
/// `comm`: rank 0 reads the file and its mesh (gmsh) and sends them; every rank builds the same
/// model, and a failure is the same InputError on every rank. `outdir`: where the run writes its
/// results; its reduced blocks are then kept in OUTDIR/NAME.superelements.h5 and read from there
/// by the next run with the same key (io/superelement_cache.hpp; `output.superelement_cache: off`:
/// not). Empty: every reduced block is computed.
Scene read_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                 MPI_Comm comm = MPI_COMM_SELF, const std::string& outdir = "");

/// `text` of rank 0 on every rank of `comm` (collective).
std::string broadcast_text(const std::string& text, MPI_Comm comm);

/// Same, from YAML text (tests); `label` stands for the file name in messages.
Scene read_scene_text(const std::string& yaml, const std::string& label,
                      const std::vector<std::string>& overrides = {});

}  // namespace alphaflex
