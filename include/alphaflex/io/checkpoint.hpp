#pragma once
// Checkpoints: the whole state of a run in one HDF5 file, OUTDIR/NAME.checkpoint.h5, from which
// `alphaflex run SCENE --restart FILE` goes on as if the run had not stopped.
//
// What is in it: the state q (positions and unit quaternions), q̇, q̈, λ and the integrator's
// auxiliary variable a of eq. (3), in model order; time, step, the step size in use and the state of
// the step-cut policy, the summary's counters, the position of the results (sensor rows, output
// steps, parts); the scheme (α_m, α_f, β, γ, h); and a fingerprint of the model (kinds and names of
// the nodes, sizes, types and names of the joints, types and names of the elements), so that a
// checkpoint of another model is refused with what differs; and per element the sums of |r|, |K|,
// |C|, |M| at the initial state, so that a restart with changed physics (a beam's EA) warns naming
// the element. Every dataset has a Fletcher32 checksum and the metadata is in HDF5's checksummed
// format (1.10): a corrupted checkpoint is refused naming the dataset or attribute, with every
// size checked against the model before any allocation. The state is written in model order
// with each rank's rows (parallel HDF5), so a checkpoint restarts on any number of ranks.
//
// Atomic: the file is written under a temporary name and renamed over the last one (with `keep` > 1
// the older ones are kept as NAME.checkpoint.1.h5, .2.h5, …), so a kill at any moment leaves the
// previous checkpoint whole.
#include <string>
#include <vector>

#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

/// Where a run stands besides its state: what a restart needs to go on as if uninterrupted.
struct RunPosition {
  long long step = 0;            ///< time steps taken
  double h = 0.0;                ///< step size in use (with step cuts: the current one)
  long long cuts_in_row = 0, good_steps = 0;  ///< state of the step-cut policy
  long long newton_total = 0, newton_max = 0, step_cuts = 0;
  double h_min = 0.0;
  long long last_written = 0;    ///< the step of the last output step
  /// The step controller's state (driver/step_controller.hpp) and the step size the auxiliary
  /// vector a belongs to; `controller` is false for a checkpoint written before they were kept.
  bool controller = false;
  double t_anchor = 0.0, h_anchor = 0.0, error_prev = 1.0, h_max = 0.0, h_auxiliary = 0.0;
  long long k = 0, accepted = 0, rejected = 0;
  /// The adaptive error estimator's history (driver/error_estimator.hpp): the mean velocities of
  /// the last `history_count` (≤ 2) accepted steps, local vectors, and their step sizes.
  long long history_count = 0;
  double history_h1 = 0.0, history_h2 = 0.0;
  Eigen::VectorXd history_m1, history_m2;
  ResultsPosition results;       ///< committed sensor rows, output steps and parts
  /// The accumulated sensors' state (`work`: app/sensor_integrals.hpp), the same on every rank;
  /// empty if the scene has none.
  std::vector<double> accumulated;
};

/// The checkpoints a run wrote: how many, the size of the last, the time they took, the last's path
/// ("" if none). Counted by the time loop (driver/time_loop.hpp), reported in the run's summary.
struct CheckpointStats {
  int checkpoints = 0;
  long long checkpoint_bytes = 0;
  double checkpoint_time = 0.0;
  std::string checkpoint;
};

struct Checkpoint {
  MechanicalState state;      ///< this rank's subdomain's state
  Eigen::VectorXd auxiliary;  ///< the auxiliary variable a, local
  RunPosition position;
  double scene_h = 0.0;       ///< solver.h of the run that wrote it
  /// Settings that differ from the checkpointed run's (the restart goes on, but its results will
  /// not be those of the uninterrupted run).
  std::vector<std::string> warnings;
};

/// Writes the checkpoint of this rank's part to `path` (collective): atomically, keeping `keep`
/// checkpoints. Returns its size in bytes. Throws OutputError on every rank if a write failed on
/// one (naming the file, the operation and errno's text).
long long write_checkpoint(const Subdomain& sub, const std::string& path, const MechanicalState& local,
                           const Eigen::VectorXd& auxiliary, const RunPosition& position,
                           const AlphaParameters& parameters, double h, int keep);

/// Reads the checkpoint `path` for this subdomain (collective). Throws InputError on every rank if
/// it cannot be read, is no checkpoint, or is of another model (saying what differs).
Checkpoint read_checkpoint(const Subdomain& sub, const std::string& path, const AlphaParameters& parameters, double h);

}  // namespace alphaflex
