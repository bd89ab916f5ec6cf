#include "alphaflex/driver/step_controller.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace alphaflex {

StepController::StepController(double h, double t_end) : t_end_(t_end) {
  st_.h = h;
  st_.h_anchor = h;
  st_.t_anchor = 0.0;  // runs start at t = 0 (solver.t_end's doc)
}

StepPlan StepController::plan(double t) const {
  StepPlan p;
  p.t = t;
  p.h = st_.h;
  // The anchor's exact time while h is the anchor's; otherwise the sum.
  const bool anchored = st_.h == st_.h_anchor;
  p.t_next = anchored ? st_.t_anchor + static_cast<double>(st_.k + 1) * st_.h : t + st_.h;
  const double landing = landing_time(t);
  const double target = landing > t && landing < t_end_ ? landing : t_end_;
  // A step within 1e-9 of the run (or of h) of the target lands on it with its h (the fixed-step
  // rule of a t_end that is a multiple of h); beyond it, the step is shortened to land.
  const double tol = 1e-9 * std::max(st_.h, target - (anchored ? st_.t_anchor : t));
  if (p.t_next >= target - tol) {
    if (std::fabs(p.t_next - target) > tol) {
      p.h = target - t;
      p.resized = true;
    }
    p.t_next = target;
    p.last = target == t_end_;
    p.output = !p.last && target == output_time(t);
  } else if (splits_remainder()) {
    // Within kLandingSteps steps of the target: equal steps that end on it, so that h changes by
    // a ratio n/(n+1) near 1 rather than a last step cut to a sliver (a sudden change of h excites
    // the index-3 transient of q̈ and λ, docs/theory/adaptive_steps.md §2).
    const double rem = target - t;
    const double n = std::ceil(rem / st_.h - 1e-9);
    if (n <= kLandingSteps) {
      p.h = rem / n;
      p.t_next = t + p.h;
      p.resized = true;
    }
  }
  return p;
}

bool StepController::converged(const StepPlan& p, double error) {
  const double h_before = st_.h;
  if (!accept(p, error)) {
    ++st_.rejected;
    return false;
  }
  ++st_.accepted;
  if (!p.resized || st_.h_min == 0.0) {
    st_.h_min = st_.h_min == 0.0 ? p.h : std::min(st_.h_min, p.h);
    st_.h_max = std::max(st_.h_max, p.h);
  }
  if (!p.resized && p.h == st_.h_anchor && st_.h == h_before && st_.h == st_.h_anchor && p.t_next != landing_time(p.t)) {
    ++st_.k;  // same h: the next time is counted from the anchor
  } else {
    st_.t_anchor = p.t_next;
    st_.h_anchor = st_.h;
    st_.k = 0;
  }
  return true;
}

// ---- Fixed steps ---------------------------------------------------------------------------------

long FixedSteps::total_steps(long steps_done, double) const {
  const double ratio = (t_end_ - st_.t_anchor) / st_.h_anchor;
  long n = std::lround(ratio);
  if (std::fabs(ratio - std::round(ratio)) > 1e-9 * std::max(1.0, ratio)) n = static_cast<long>(std::ceil(ratio));
  return steps_done - static_cast<long>(st_.k) + n;
}

std::string FixedSteps::shortened_last_step(double t, bool restarted) const {
  const double ratio = (t_end_ - st_.t_anchor) / st_.h_anchor;
  if (std::fabs(ratio - std::round(ratio)) <= 1e-9 * std::max(1.0, ratio)) return "";
  const long n = static_cast<long>(std::ceil(ratio));
  (void)t;
  std::ostringstream os;
  os << "t_end = " << t_end_ << " s is not a multiple of h = " << st_.h_anchor << " s" << (restarted ? " after the restart time" : "")
     << ": the last step is shortened to " << t_end_ - st_.t_anchor - static_cast<double>(n - 1) * st_.h_anchor
     << " s (the order-2 condition, eq. 17, holds for constant h)";
  return os.str();
}

// ---- Cut-back --------------------------------------------------------------------------------------

// st_.cuts_in_row counts the halvings in force: a failure adds one, a doubling back takes one off.
// A converged step does not clear it (it used to: then a step that failed again after one converged
// step was halved N more times, and cycles of failure and success took h down without limit,
// 5e-3 s to 2e-89 s on the undamped slider-crank), so h ≥ h/2^N holds for the whole run.
bool CutBack::newton_failed(const StepPlan& p) {
  if (st_.cuts_in_row >= max_cuts_) return false;
  st_.h = 0.5 * p.h;
  ++st_.cuts_in_row;
  ++st_.newton_failures;
  st_.good_steps = 0;
  return true;
}

std::string CutBack::too_small(const StepPlan& p) const {
  if (st_.cuts_in_row < max_cuts_) return "";
  std::ostringstream os;
  os << "solver.step_cuts = " << max_cuts_ << ": the step failed at h = " << p.h << " s, solver.h = " << h0_ << " s halved "
     << st_.cuts_in_row << " times (the halvings in force: a doubling after 4 converged steps undoes one), the smallest h the key"
     << " allows; " << st_.newton_failures << " step cuts in the run so far. A larger solver.step_cuts allows smaller steps.";
  return os.str();
}

bool CutBack::accept(const StepPlan&, double) {
  if (st_.h < h0_ && ++st_.good_steps >= 4) {
    st_.h = std::min(h0_, 2.0 * st_.h);
    st_.good_steps = 0;
    if (st_.cuts_in_row > 0) --st_.cuts_in_row;
  }
  // Back at the scene's h (also after a restart with a smaller solver.h): no halving in force.
  if (st_.h >= h0_) st_.cuts_in_row = 0;
  return true;
}

// ---- Adaptive --------------------------------------------------------------------------------------

Adaptive::Adaptive(double h0, double t_end, const AdaptiveOptions& o) : StepController(h0, t_end), o_(o) {
  if (o_.h_max <= 0.0) o_.h_max = t_end;
  st_.h = std::clamp(h0, std::min(o_.h_min, o_.h_max), o_.h_max);
  st_.h_anchor = st_.h;
}

double Adaptive::scaled_error(double local_error, double q_norm, double h) const {
  return local_error / (o_.atol + o_.rtol * q_norm) * (t_end_ / h);
}

std::pair<double, double> Adaptive::newton_tolerance(double h) const {
  const double f = kNewton * h / t_end_;
  return {f * o_.atol, f * o_.rtol};
}

bool Adaptive::newton_failed(const StepPlan& p) {
  ++st_.newton_failures;
  st_.h = 0.5 * p.h;
  st_.cuts_in_row = 1;  // the next accepted step does not grow h
  return st_.h >= o_.h_min;
}

std::string Adaptive::too_small(const StepPlan& p) const {
  if (st_.h >= o_.h_min) return "";
  std::ostringstream os;
  os << "the step size needed at t = " << p.t << " s fell below solver.h_min = " << o_.h_min << " s (last tried h = " << p.h
     << " s, " << st_.rejected << " steps rejected, " << st_.newton_failures
     << " Newton failures so far). Loosen solver.tolerance or lower solver.h_min.";
  return os.str();
}

bool Adaptive::accept(const StepPlan& p, double error) {
  const double e = std::max(error, 1e-10);
  if (e > 1.0) {
    // Rejected: the retry's h from the error alone (I control), at least a fifth of h.
    st_.h = p.h * std::max(kMinFactor, kSafety * std::pow(e, -1.0 / kOrder));
    st_.cuts_in_row = 1;
    return false;
  }
  // PI control (Gustafsson 1991): h_{n+1} = h_n (1/e_n)^{k_I} (e_{n−1}/e_n)^{k_P}, with a safety
  // factor; no growth right after a rejection or a Newton failure.
  const double f = kSafety * std::pow(e, -kI) * std::pow(st_.error_prev / e, kP);
  double h = p.h * std::clamp(f, kMinFactor, st_.cuts_in_row > 0 ? 1.0 : kMaxFactor);
  // A step shortened to land somewhere says little about the h the solution allows: keep the h
  // planned before it unless the error asks for less.
  if (p.resized) h = std::max(h, std::min(st_.h, p.h * f));
  // Hysteresis (AdaptiveOptions::hold): a growth by less than `hold` is not worth a new S_t; the
  // step is then smaller than the error allows, never larger.
  else if (o_.hold > 1.0 && h >= p.h && h < o_.hold * p.h) h = p.h;
  st_.h = std::clamp(h, o_.h_min, o_.h_max);
  st_.error_prev = e;
  st_.cuts_in_row = 0;
  return true;
}

double Adaptive::output_time(double t) const {
  if (o_.output_dt <= 0.0) return 0.0;
  // The first output time k·dt after t (by more than round-off).
  double k = std::floor(t / o_.output_dt) + 1.0;
  if (k * o_.output_dt - t <= 1e-9 * o_.output_dt) k += 1.0;
  return k * o_.output_dt;
}

double Adaptive::landing_time(double t) const {
  double next = output_time(t);  // 0: none
  // The first breakpoint after t (by more than round-off of the run's length).
  const auto b = std::upper_bound(o_.breakpoints.begin(), o_.breakpoints.end(), t + 1e-12 * t_end_);
  if (b != o_.breakpoints.end() && (next == 0.0 || *b < next)) next = *b;
  return next;
}

bool Adaptive::at_breakpoint(double t) const {
  // Within the round-off of the run's length, as landing_time decides that a step is past one.
  const double tol = 1e-12 * t_end_;
  const auto b = std::lower_bound(o_.breakpoints.begin(), o_.breakpoints.end(), t - tol);
  return b != o_.breakpoints.end() && *b <= t + tol;
}

std::unique_ptr<StepController> make_step_controller(double h, double t_end, int step_cuts, const AdaptiveOptions& adaptive) {
  if (adaptive.enabled()) return std::make_unique<Adaptive>(h, t_end, adaptive);
  if (step_cuts > 0) return std::make_unique<CutBack>(h, t_end, step_cuts);
  return std::make_unique<FixedSteps>(h, t_end);
}

}  // namespace alphaflex
