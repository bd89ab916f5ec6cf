#include "alphaflex/driver/time_loop.hpp"

#include <mpi.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <type_traits>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/fault_injection.hpp"

namespace alphaflex {

namespace {

// The step controller's state and the error estimator's history as a checkpoint keeps them
// (io/checkpoint.hpp): one list of fields for both directions, `store` (state → position) when a
// checkpoint is written and `load` (position → state) on a restart, so the two cannot drift apart.
const auto store = [](auto& position_field, const auto& state_field) { position_field = state_field; };
const auto load = [](const auto& position_field, auto& state_field) {
  state_field = static_cast<std::decay_t<decltype(state_field)>>(position_field);
};

// Where the steps go on: the step size, its anchor and the PI controller's memory. A restart with
// another solver.h (fixed steps) starts a new anchor instead (TimeLoop::restore).
template <class Position, class State, class Copy>
void anchor_fields(Position& p, State& s, Copy copy) {
  copy(p.h, s.h), copy(p.t_anchor, s.t_anchor), copy(p.h_anchor, s.h_anchor);
  copy(p.k, s.k), copy(p.error_prev, s.error_prev), copy(p.h_max, s.h_max);
}

// What the steps so far were: the cut-back policy's counts and the accepted and rejected steps.
template <class Position, class State, class Copy>
void count_fields(Position& p, State& s, Copy copy) {
  copy(p.cuts_in_row, s.cuts_in_row), copy(p.good_steps, s.good_steps), copy(p.step_cuts, s.newton_failures);
  copy(p.h_min, s.h_min), copy(p.accepted, s.accepted), copy(p.rejected, s.rejected);
}

template <class Position, class History, class Copy>
void history_fields(Position& p, History& hist, Copy copy) {
  copy(p.history_count, hist.count), copy(p.history_h1, hist.h1), copy(p.history_h2, hist.h2);
  copy(p.history_m1, hist.m1), copy(p.history_m2, hist.m2);
}

}  // namespace

Checkpointer::Checkpointer(const Subdomain& sub, ResultsWriter* writer, std::string path, AlphaParameters parameters, double h,
                           int keep)
    : sub_(sub), writer_(writer), path_(std::move(path)), parameters_(std::move(parameters)), h_(h), keep_(keep), last_(MPI_Wtime()) {}

void Checkpointer::write(long n, long last_written, const MechanicalState& s, GeneralizedAlpha& integrator,
                         const StepController& c, const PositionErrorEstimator& estimator, LoopCounters& counters) {
  if (!writer_) return;
  const double t0 = MPI_Wtime();
  writer_->commit();
  const RunPosition pos = position(n, last_written, integrator, c, estimator, counters);
  counters.checkpoint_bytes = write_checkpoint(sub_, path_, s, integrator.auxiliary(), pos, parameters_, h_, keep_);
  counters.checkpoint = path_;
  ++counters.checkpoints;
  counters.checkpoint_time += MPI_Wtime() - t0;
  last_ = MPI_Wtime();
  // Modified Newton: a restart has no factorization to keep; refactor here too, so that the run
  // and its restart take the same iterations bit for bit.
  integrator.invalidate_factorization();
}

RunPosition Checkpointer::position(long n, long last_written, const GeneralizedAlpha& integrator, const StepController& c,
                                   const PositionErrorEstimator& estimator, const LoopCounters& counters) const {
  RunPosition pos;
  pos.step = n;
  pos.last_written = last_written;
  pos.newton_total = counters.newton_total;
  pos.newton_max = counters.newton_max;
  pos.results = writer_->position();
  pos.controller = true;
  pos.h_auxiliary = integrator.auxiliary_step();
  const StepControllerState& st = c.state();
  anchor_fields(pos, st, store);
  count_fields(pos, st, store);
  history_fields(pos, estimator.history(), store);
  if (accumulated_) pos.accumulated = accumulated_();
  return pos;
}

TimeLoop::TimeLoop(const Subdomain& sub, GeneralizedAlpha& integrator, StepController& controller, Checkpointer& checkpointer,
                   ResultsWriter* writer, TimeLoopSettings settings)
    : sub_(sub), integrator_(integrator), controller_(controller), checkpointer_(checkpointer), writer_(writer),
      settings_(std::move(settings)), estimator_(integrator.parameters().local_error_constant()) {
  integrator_.set_variable_steps(controller_.variable());
  // Adaptive runs keep S_t across changes of h (modified Newton; docs/theory/adaptive_steps.md §6);
  // fixed steps and the cut-back of Newton failures refactor at each, as before.
  integrator_.set_factorization_across_h(controller_.estimates_error());
  integrator_.set_error_estimate(controller_.estimates_error());
}

void TimeLoop::restore(const Checkpoint& ck, double h) {
  StepControllerState st = controller_.state();
  const bool same_h = std::fabs(ck.scene_h - h) <= 1e-14 * h;
  const RunPosition& cp = ck.position;
  if (cp.controller && (same_h || controller_.estimates_error())) {
    anchor_fields(cp, st, load);
  } else {
    st.h = controller_.variable() ? std::min(cp.h, h) : h;
    st.t_anchor = ck.state.t;
    st.h_anchor = st.h;
    st.k = 0;
  }
  count_fields(cp, st, load);
  // A checkpoint without the controller's state counts every step taken as accepted.
  if (!cp.controller) st.accepted = cp.step;
  controller_.set_state(st);
  integrator_.set_auxiliary(ck.auxiliary, cp.controller ? cp.h_auxiliary : cp.h);
  PositionErrorEstimator::History hist;
  history_fields(cp, hist, load);
  estimator_.set_history(hist);
}

void TimeLoop::observe(long step, const MechanicalState& s, bool fields) {
  const StepEvent e{step, s, fields, controller_};
  for (const auto& o : observers_) o(e);
}

void TimeLoop::run(MechanicalState& s, long first_step, long last_written, LoopCounters& counters) {
  const std::string& ck_path = checkpointer_.path();
  auto of_total = [&](long n) {
    const long total = controller_.total_steps(counters.steps, s.t);
    return total >= 0 ? "step " + std::to_string(n) + " of " + std::to_string(total) : "step " + std::to_string(n);
  };
  // After every step, the ranks agree whether to checkpoint (rank 0's wall clock, the step count)
  // and whether to stop (a signal on any rank): one small all-reduce.
  auto due = [&](long n) {
    int flags[2] = {settings_.stop_signal ? settings_.stop_signal() : 0, 0};
    if (settings_.checkpoint_steps > 0 && n % settings_.checkpoint_steps == 0) flags[1] = 1;
    if (sub_.rank() == 0 && settings_.checkpoint_wall > 0.0 && MPI_Wtime() - checkpointer_.last_wall() >= settings_.checkpoint_wall)
      flags[1] = 1;
    if (sub_.size() > 1) MPI_Allreduce(MPI_IN_PLACE, flags, 2, MPI_INT, MPI_MAX, sub_.comm());
    if (flags[1] || flags[0]) checkpointer_.write(n, last_written, s, integrator_, controller_, estimator_, counters);
    if (!flags[0]) return;
    // Stop on request: the checkpoint is written; the state reached goes to the results too.
    if (writer_) {
      if (last_written != n) writer_->write_fields(s);
      writer_->finish();
    }
    std::ostringstream os;
    os << "stopped by " << (settings_.signal_name ? settings_.signal_name(flags[0]) : "a signal") << " at t = " << s.t << " s ("
       << of_total(n) << ")";
    if (writer_)
      os << ": checkpoint " << ck_path << ", results in " << writer_->xdmf_path() << ".\n  Go on with: alphaflex run "
         << settings_.scene_file << " --restart " << ck_path << " -o " << std::filesystem::absolute(settings_.outdir).string()
         << " (and the same --set options)";
    else
      os << " (no output, no checkpoint)";
    throw Interrupted(os.str());
  };
  // A failed step: keep what was computed (a checkpoint of the last converged state, which goes to
  // the files too) and stop.
  auto stop = [&](long n, const std::string& what) {
    if (writer_) {
      checkpointer_.write(n - 1, last_written, s, integrator_, controller_, estimator_, counters);
      if (last_written != n - 1) writer_->write_fields(s);
      writer_->finish();
    }
    std::ostringstream os;
    os << of_total(n) << ": " << what << "\n  The last converged state (t = " << s.t << " s) is written"
       << (writer_ ? " to " + writer_->xdmf_path() + "; a checkpoint of it to " + ck_path : std::string(" nowhere (no output)"))
       << ".";
    throw SolverError(os.str());
  };

  // The state to go back to when a step is retried (variable policies only: the fixed-step scheme
  // stops at its first failure and keeps no copy).
  const bool retries = controller_.variable();
  if (first_step == 1 && controller_.estimates_error()) estimator_.start(s.v);
  MechanicalState saved;
  Eigen::VectorXd saved_a;
  long n = first_step - 1;
  bool last = false, fields_now = false;
  // The state at every commit of the results (a commit happens inside an observer, before
  // last_written moves on: an output step being written counts as written).
  struct CommitHook {
    ResultsWriter* writer;
    ~CommitHook() {
      if (writer) writer->on_commit(nullptr);  // the hook sees this function's locals only
    }
  } hook{writer_ && settings_.on_commit ? writer_ : nullptr};
  auto keep_committed = [&] {
    settings_.on_commit(s, integrator_.auxiliary(),
                        checkpointer_.position(n, fields_now ? n : last_written, integrator_, controller_, estimator_, counters));
  };
  if (hook.writer) {
    writer_->on_commit(keep_committed);
    keep_committed();
  }
  while (!last) {
    const StepPlan p = controller_.plan(s.t);
    // At a kink of a load or driver q⃛ jumps: the divided difference of the estimate must not take
    // its points from both sides, or the steps before (long ones, when nothing moved) smear q⃛ over
    // their length and a step across a sharp pulse passes (inputs/beam_impulse.yaml: a 2 ms step
    // over the rising half of the 4 ms pulse was accepted at any tolerance, docs/performance.md).
    // The history starts again as at t = 0, from the velocity reached (docs/theory/adaptive_steps.md §3).
    if (controller_.estimates_error() && controller_.at_breakpoint(s.t) && s.t > 0.0) estimator_.start(s.v);
    if (retries) {
      saved = s;
      saved_a = integrator_.auxiliary();
    }
    const double saved_h_aux = integrator_.auxiliary_step();
    StepReport rep;
    bool ok = true;
    const auto newton_tol = controller_.newton_tolerance(p.h);
    integrator_.set_step_newton_tolerance(newton_tol.first, newton_tol.second);
    try {
      rep = integrator_.step(s, p.h, p.t_next);
    } catch (const SolverError& e) {
      // No retry: the policy's limit of h is reached (too_small says which; fixed steps have none).
      if (!controller_.newton_failed(p)) {
        const std::string small = controller_.too_small(p);
        stop(n + 1, small.empty() ? std::string(e.what()) : std::string(e.what()) + "\n  " + small);
      }
      ok = false;
    }
    if (fault_injected("internal")) throw std::runtime_error("injected fault (-af_inject_fault internal) at step " + std::to_string(n + 1));
    if (ok) {
      counters.newton_total += rep.iterations;  // the work of rejected steps counts too
      counters.newton_max = std::max(counters.newton_max, rep.iterations);
    }
    const bool estimating = ok && controller_.estimates_error();
    double local_error = 0.0;
    if (estimating && settings_.filter) {
      // The first step has no history: its estimate is C h² (a_{n+1} − a_n) (E), with a_n the a the
      // step started from (StepReport::a_start): moved to its h by (A) and, at the start of a run,
      // the start value a_0 of solver.start — set inside the first step, so the a saved before it
      // is still q̈_0 from initialize(): with a corrected or smooth start that estimate was
      // C h² (a_1 − q̈_0), off by about Δ_α h q⃛_0 (docs/theory/adaptive_steps.md, (E)).
      Eigen::VectorXd from_a;
      if (estimator_.history().count < 2) {
        from_a = std::fabs(integrator_.parameters().local_error_constant()) * p.h * p.h * (integrator_.auxiliary() - rep.a_start);
      }
      const Eigen::VectorXd e = estimator_.error_vector(rep.increment, p.h, from_a);
      local_error = sub_.max_abs(settings_.filter->apply(s, e, p.h, rep.increment, ErrorFilter::applications(controller_.t_end(), p.h),
                                                         integrator_.times()));
    } else if (estimating) {
      local_error = estimator_.estimate(sub_, rep.increment, p.h, rep.local_error);
    }
    if (ok && !controller_.converged(p, controller_.scaled_error(local_error, rep.q_norm, p.h))) {
      const std::string small = controller_.too_small(p);
      if (!small.empty()) {
        s = saved;
        integrator_.set_auxiliary(saved_a, saved_h_aux);
        stop(n + 1, "the local error estimate exceeds solver.tolerance: " + small);
      }
      ok = false;
    }
    if (!ok) {
      // Retry from the saved state with the controller's smaller h.
      s = saved;
      integrator_.set_auxiliary(saved_a, saved_h_aux);
      continue;
    }
    if (estimating) estimator_.accept(rep.increment, p.h);
    ++n;
    ++counters.steps;
    last = p.last;
    const bool fields = (n % settings_.output_every == 0) || last || p.output;
    fields_now = fields;
    observe(n, s, fields);
    fields_now = false;
    if (fields) last_written = n;
    if (!last) due(n);
  }
  if (settings_.checkpoint_at_end)
    checkpointer_.write(n, last_written, s, integrator_, controller_, estimator_, counters);  // the end of a run leaves one
}

}  // namespace alphaflex
