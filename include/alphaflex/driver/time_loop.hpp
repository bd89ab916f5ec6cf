#pragma once
// The one step loop of a dynamic run (driver module, below study and app): the step controller
// (driver/step_controller.hpp) plans each step, the integrator takes it, the controller accepts it
// or asks for a retry from the saved state (q, q̇, q̈, λ and the auxiliary a with its step size);
// accepted steps go to the observers (sensors, fields, progress: in the manner of PETSc's
// TSMonitor), and the checkpointer writes the run's state every so many steps or s of wall time,
// at the end, after a failure and on a stop signal.
#include <functional>
#include <string>
#include <vector>

#include "alphaflex/driver/error_estimator.hpp"
#include "alphaflex/driver/error_filter.hpp"
#include "alphaflex/driver/step_controller.hpp"
#include "alphaflex/integrators/generalized_alpha.hpp"
#include "alphaflex/io/checkpoint.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

/// What the loop counts (the run's summary copies them).
struct LoopCounters : CheckpointStats {
  long steps = 0;  ///< accepted time steps
  long newton_total = 0;
  int newton_max = 0;
};

/// An accepted step (or the initial state, step 0), as the observers see it.
struct StepEvent {
  long step = 0;
  const MechanicalState& state;
  bool fields = false;  ///< an output step: the fields go to the results
  const StepController& controller;
};

/// Writes checkpoints (io/checkpoint.hpp): the results are committed first, so the position of the
/// results the checkpoint records is on disk.
class Checkpointer {
 public:
  /// `writer` null: no checkpoints (no output). `h`: the scene's step size (kept in the file).
  Checkpointer(const Subdomain& sub, ResultsWriter* writer, std::string path, AlphaParameters parameters, double h, int keep);
  /// Writes the checkpoint of `s` after step `n` (collective); then drops the integrator's kept
  /// factorization (modified Newton), as a restart has none, so run and restart stay bit-identical.
  void write(long n, long last_written, const MechanicalState& s, GeneralizedAlpha& integrator, const StepController& c,
             const PositionErrorEstimator& estimator, LoopCounters& counters);
  /// The position a checkpoint after step `n` records (the controller's state, the estimator's
  /// history, the results as committed so far).
  RunPosition position(long n, long last_written, const GeneralizedAlpha& integrator, const StepController& c,
                       const PositionErrorEstimator& estimator, const LoopCounters& counters) const;
  bool active() const { return writer_ != nullptr; }
  const std::string& path() const { return path_; }
  double last_wall() const { return last_; }
  /// State kept beside the mechanical state that the loop does not know (the accumulated
  /// sensors: RunPosition::accumulated), asked for at every checkpoint and commit.
  void set_accumulated(std::function<std::vector<double>()> accumulated) { accumulated_ = std::move(accumulated); }

 private:
  const Subdomain& sub_;
  ResultsWriter* writer_;
  std::string path_;
  AlphaParameters parameters_;
  double h_;
  int keep_;
  double last_;
  std::function<std::vector<double>()> accumulated_;
};

struct TimeLoopSettings {
  int output_every = 1;          ///< fields every N steps (and at the last step, and at output times)
  /// Adaptive steps: the filter of the local error estimate (driver/error_filter.hpp); null: the
  /// estimate from positions as it is.
  ErrorFilter* filter = nullptr;
  long checkpoint_steps = 0;     ///< every N steps (0: not by count)
  double checkpoint_wall = 0.0;  ///< every so many s of wall time (0: not by time)
  bool checkpoint_at_end = true; ///< a checkpoint when the last step is taken (output.checkpoint_at_end)
  /// For the messages of a stop: `alphaflex run FILE --restart CHECKPOINT -o OUTDIR`.
  std::string scene_file, outdir;
  /// The stop signal received on this rank (0: none) and its name (app/stop_signals.hpp).
  std::function<int()> stop_signal;
  std::function<const char*(int)> signal_name;
  /// Called after every commit of the results that succeeded, with the state the results end at and
  /// the position of its checkpoint: what a run keeps, to checkpoint it if a later write fails (a
  /// full disk, issue 24; app/simulation.cpp).
  std::function<void(const MechanicalState&, const Eigen::VectorXd& auxiliary, const RunPosition&)> on_commit;
};

class TimeLoop {
 public:
  TimeLoop(const Subdomain& sub, GeneralizedAlpha& integrator, StepController& controller, Checkpointer& checkpointer,
           ResultsWriter* writer, TimeLoopSettings settings);
  /// Called with every accepted step (and with step 0 by the caller's choice, see observe()).
  void add_observer(std::function<void(const StepEvent&)> observer) { observers_.push_back(std::move(observer)); }
  /// A restart: the controller's state, the h of a and the error estimator's history as the
  /// checkpoint has them, so that the steps are those of the uninterrupted run. A scene whose h
  /// differs from the checkpoint's (`h`: the scene's; a warning says so) goes on with its own h from
  /// the checkpoint's time (the cut-back policy with the smaller of that and the step in use).
  void restore(const Checkpoint& ck, double h);
  /// Calls the observers with a state (the initial state, step 0).
  void observe(long step, const MechanicalState& s, bool fields);

  /// Steps `s` from its time to t_end, from step `first_step` on (1, or a checkpoint's step + 1);
  /// `last_written` is the step of the last output step. Ends with a checkpoint (unless `checkpoint_at_end` is off). Throws SolverError
  /// (a failed step the policy cannot retry; the last converged state is written and checkpointed)
  /// or Interrupted (stop signal; the state is checkpointed and written).
  void run(MechanicalState& s, long first_step, long last_written, LoopCounters& counters);
  /// The adaptive policy's error estimator (its history goes to checkpoints and comes back on a restart).
  PositionErrorEstimator& estimator() { return estimator_; }

 private:
  const Subdomain& sub_;
  GeneralizedAlpha& integrator_;
  StepController& controller_;
  Checkpointer& checkpointer_;
  ResultsWriter* writer_;
  TimeLoopSettings settings_;
  std::vector<std::function<void(const StepEvent&)>> observers_;
  PositionErrorEstimator estimator_;
};

}  // namespace alphaflex
