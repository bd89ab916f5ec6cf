#pragma once
// Step-size control of a dynamic run (driver module), one interface for the three policies, in
// the manner of PETSc's TSAdapt: the controller proposes the next step (plan), and is told whether
// Newton converged and, for the adaptive policy, the step's local error estimate; it accepts the
// step or asks for a retry with a smaller h.
//
//  - FixedSteps: h from the scene, the last step shortened to land on t_end (the paper's scheme).
//  - CutBack (solver.step_cuts): a step whose Newton iteration fails is retried with h halved; h
//    doubles back (up to the scene's h) after 4 converged steps; at most N halvings are in force at
//    a time (a doubling undoes one), so h ≥ h/2^N over the whole run.
//  - Adaptive (solver.tolerance): PI control of the local error (Gustafsson 1991; Söderlind 2002),
//    rejection and retry, Newton failures halve h; steps land on t_end and on the output times.
//
// Times without drift (in the manner of deal.II's DiscreteTime): while h stays the same the time
// of a step is t_anchor + k·h, not a sum of k steps, so a fixed-step run prints 0.5, not
// 0.50000000000000033; a change of h moves the anchor to the time reached.
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace alphaflex {

/// What a checkpoint keeps of the controller, so that a restart takes the same steps bit for bit.
struct StepControllerState {
  double h = 0.0;            ///< the step size to try next (before landing on t_end or an output time)
  double t_anchor = 0.0;     ///< while h stays the same, the time after k more steps is t_anchor + k·h
  double h_anchor = 0.0;     ///< the h the anchor counts in
  long long k = 0;           ///< steps of h_anchor since the anchor
  double error_prev = 1.0;   ///< the last accepted step's scaled error (PI controller)
  /// Cut-back: the halvings of h in force (a doubling back undoes one) and the converged steps since
  /// the last change of h. Adaptive: cuts_in_row > 0 after a rejection or a Newton failure (no growth).
  long long cuts_in_row = 0, good_steps = 0;
  long long accepted = 0, rejected = 0, newton_failures = 0;  ///< since t = 0
  double h_min = 0.0, h_max = 0.0;  ///< smallest and largest accepted step (0: none yet)
};

/// One step to try: its size and the time it reaches (exact: an anchor time, t_end or an output time).
struct StepPlan {
  double t = 0.0, h = 0.0, t_next = 0.0;
  bool last = false;       ///< reaches t_end
  bool output = false;     ///< reaches an output time (output.dt)
  bool resized = false;    ///< h is not the anchor's (the step was shortened to land somewhere)
};

/// The adaptive policy's settings (solver.tolerance, solver.h_min, solver.h_max).
struct AdaptiveOptions {
  double rtol = 0.0, atol = 0.0;  ///< local error tolerance, relative and absolute (m, rad)
  double h_min = 0.0, h_max = 0.0;  ///< bounds of h (s); h_max 0: t_end
  double output_dt = 0.0;           ///< steps land on multiples of this (s); 0: no landing
  /// Times the steps land on besides (a load's or driver's kinks; sorted), so that a short pulse is
  /// not stepped over while nothing moves.
  std::vector<double> breakpoints;
  /// Hysteresis of the step size (solver.tolerance.hold): an accepted step whose controller asks
  /// for growth by less than this factor keeps its h, so that modified Newton keeps its
  /// factorization of S_t (which belongs to one h). Hairer & Wanner, Solving ODEs II, Sec. IV.8,
  /// RADAU5's WORK(5), WORK(6) = 1, 1.2. 1: off (every proposal taken).
  double hold = 1.0;
  bool enabled() const { return rtol > 0.0 || atol > 0.0; }
};

class StepController {
 public:
  virtual ~StepController() = default;

  /// The step to try from time t (the state's time; the anchor decides the exact t_next).
  StepPlan plan(double t) const;
  /// Newton failed on `p`: shrinks h and returns true, or false when the policy allows no retry.
  virtual bool newton_failed(const StepPlan& p) = 0;
  /// The step `p` converged; `error` is its scaled error estimate (≤ 1: within the tolerance; only
  /// the adaptive policy uses it). Returns whether the step is accepted; otherwise h was reduced
  /// and the step is to be retried from the same state.
  bool converged(const StepPlan& p, double error);
  /// Whether the integrator should compute the local error estimate.
  virtual bool estimates_error() const { return false; }
  /// The error measure `converged` takes, from the integrator's estimate (StepReport::local_error,
  /// q_norm) of a step of size h; 0 for the policies that do not use it.
  virtual double scaled_error(double local_error, double q_norm, double h) const {
    (void)local_error, (void)q_norm, (void)h;
    return 0.0;
  }
  /// A tolerance (atol, rtol) for Newton's coordinate correction in a step of size h, a fraction
  /// of the local error the step may make; atol < 0: none (the scene's Newton tolerances alone).
  virtual std::pair<double, double> newton_tolerance(double h) const {
    (void)h;
    return {-1.0, 0.0};
  }
  /// Whether the step size changes during a run (the integrator then carries the auxiliary vector
  /// over changes of h, integrators/generalized_alpha.hpp).
  virtual bool variable() const { return true; }
  /// A step smaller than the policy allows (after newton_failed returned false, or a rejection):
  /// the message of the failure, with the h reached ("" if none).
  virtual std::string too_small(const StepPlan&) const { return ""; }
  /// Whether t is a breakpoint of the scene's time functions (a kink of a load or driver, where q⃛
  /// jumps): the error estimate's history must not reach across it (driver/error_estimator.hpp).
  virtual bool at_breakpoint(double t) const { (void)t; return false; }
  /// Steps in all, if known in advance (progress line, messages); -1 if not.
  virtual long total_steps(long steps_done, double t) const { (void)steps_done, (void)t; return -1; }

  const StepControllerState& state() const { return st_; }
  void set_state(const StepControllerState& s) { st_ = s; }
  double t_end() const { return t_end_; }

 protected:
  StepController(double h, double t_end);
  /// The policy's new h after an accepted step with scaled error `error`; false rejects the step.
  virtual bool accept(const StepPlan& p, double error) = 0;
  /// Where the step may have to land besides t_end (output times, breakpoints): the first such
  /// time > t (0: none).
  virtual double landing_time(double t) const { (void)t; return 0.0; }
  /// The first output time > t (0: none); a step that lands there writes the fields.
  virtual double output_time(double t) const { (void)t; return 0.0; }
  /// Fixed steps take the shortened last step as it comes; the others end on a landing time with
  /// equal steps from kLandingSteps steps before it.
  virtual bool splits_remainder() const { return true; }

  StepControllerState st_;
  double t_end_;
  static constexpr double kLandingSteps = 10.0;
};

/// The scene's h, every step; the last one shortened to land on t_end.
class FixedSteps : public StepController {
 public:
  FixedSteps(double h, double t_end) : StepController(h, t_end) {}
  bool newton_failed(const StepPlan&) override { return false; }
  bool variable() const override { return false; }
  long total_steps(long steps_done, double t) const override;
  /// The warning of a last step shortened to land on t_end ("" if t_end − t is a multiple of h).
  std::string shortened_last_step(double t, bool restarted) const;

 protected:
  bool accept(const StepPlan&, double) override { return true; }
  bool splits_remainder() const override { return false; }
};

/// Newton failures halve h, h doubles back after 4 good steps; at most `max_cuts` halvings in force
/// (StepControllerState::cuts_in_row: failures add one, doublings take one off), so h ≥ h/2^max_cuts.
class CutBack : public StepController {
 public:
  CutBack(double h, double t_end, int max_cuts) : StepController(h, t_end), h0_(h), max_cuts_(max_cuts) {}
  bool newton_failed(const StepPlan& p) override;
  std::string too_small(const StepPlan& p) const override;
  long total_steps(long, double) const override { return -1; }

 protected:
  bool accept(const StepPlan& p, double error) override;
  bool splits_remainder() const override { return false; }

 private:
  double h0_;
  int max_cuts_;
};

/// PI control of the local error, rejection and retry, Newton failures halve h.
class Adaptive : public StepController {
 public:
  Adaptive(double h0, double t_end, const AdaptiveOptions& o);
  bool newton_failed(const StepPlan& p) override;
  bool estimates_error() const override { return true; }
  std::string too_small(const StepPlan& p) const override;
  /// The scaled error of a step: ‖e‖∞ / (atol + rtol‖q‖∞) · t_end / h — per unit step with the
  /// run's length as the unit (docs/theory/adaptive_steps.md), so that the errors the steps leave
  /// add up to about the tolerance at t_end, and the global error is proportional to it.
  double scaled_error(double local_error, double q_norm, double h) const override;
  /// kNewton times the local error allowed in a step of h: (atol + rtol‖q‖∞) h / t_end.
  std::pair<double, double> newton_tolerance(double h) const override;
  static constexpr double kNewton = 0.1;
  bool at_breakpoint(double t) const override;

  static constexpr double kSafety = 0.9, kMinFactor = 0.2, kMaxFactor = 2.0;
  /// Gustafsson's PI gains for an error ∝ h^k, k = 2 (error per unit step of a second-order scheme).
  static constexpr double kOrder = 2.0, kI = 0.3 / kOrder, kP = 0.4 / kOrder;

 protected:
  bool accept(const StepPlan& p, double error) override;
  double landing_time(double t) const override;
  double output_time(double t) const override;

 private:
  AdaptiveOptions o_;
};

/// The policy of a run: adaptive if a tolerance is given, cut-back if solver.step_cuts > 0, else fixed.
std::unique_ptr<StepController> make_step_controller(double h, double t_end, int step_cuts, const AdaptiveOptions& adaptive);

}  // namespace alphaflex
