// Adaptive steps (solver.tolerance; driver/step_controller.hpp, docs/theory/adaptive_steps.md):
// the error at t_end follows the tolerance, the scheme stays second order in q, q̇ and λ across the
// changes of h, rejected steps and Newton failures are retried, steps land on the output times, and
// fixed-step times carry no drift. The slider-crank's reference is the independent DOP853 solution
// (tests/reference/slider_crank.csv, scripts/reference/slider_crank_reference.py; 2e-11 in θ1).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <utility>

#include "alphaflex/core/error.hpp"
#include "alphaflex/driver/step_controller.hpp"
#include "alphaflex/study/study_spec.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::at_time;
using testing::column;
using testing::final_value;
using testing::fitted_slope;
using testing::input_error_of;
using testing::read_csv;
using testing::run_scene;
using testing::source_path;

std::vector<std::string> tolerance(double tol) {
  return {"solver.tolerance.rtol=" + std::to_string(tol), "solver.tolerance.atol=" + std::to_string(tol)};
}

// Over three decades of tolerance on the slider-crank: θ1's error at t_end is proportional to the
// tolerance (least-squares slope 1 within 0.2, error / tol within a factor 10 over the sweep), and
// against the number of steps θ1 (q), ω1 (q̇) and the pivot force (λ) converge with order 2: the
// rescaled auxiliary vector keeps the order across changes of h (without it an adaptive run drops
// to order 1). Measured: slope 0.91, error/tol 6.0..11.8, orders 1.80 (q), 2.04 (v), 1.89 (λ).
TEST(AdaptiveSteps, ErrorFollowsTheToleranceWithOrderTwoInPositionsVelocitiesAndMultipliers) {
  const auto ref = read_csv(source_path("tests/reference/slider_crank.csv"));
  const std::vector<double> tols{1e-3, 1e-4, 1e-5, 1e-6};
  std::vector<double> steps, e_q, e_v, e_l;
  for (double tol : tols) {
    const RunSummary r = run_scene("slider_crank", tolerance(tol));
    ASSERT_NEAR(r.final_state.t, 1.0, 1e-14);
    steps.push_back(r.steps);
    e_q.push_back(std::fabs(r.final_sensors[column(r, "theta1")] - at_time(ref, "theta1", 1.0)));
    e_v.push_back(std::fabs(r.final_state.v[2] - at_time(ref, "omega1", 1.0)));  // the crank's θ̇ (node 0: x, y, θ)
    e_l.push_back(std::fabs(r.final_sensors[column(r, "pivot_fx")] - at_time(ref, "pivot_fx", 1.0)));
    std::printf("tol %.0e: %d steps, %lld rejected, h %.3g..%.3g s; errors theta1 %.3e omega1 %.3e pivot_fx %.3e\n", tol, r.steps,
                r.rejected_steps, r.h_min, r.h_max, e_q.back(), e_v.back(), e_l.back());
  }
  const double slope = fitted_slope(tols, e_q);
  double lo = 1e300, hi = 0.0;
  for (size_t k = 0; k < tols.size(); ++k) {
    lo = std::min(lo, e_q[k] / tols[k]);
    hi = std::max(hi, e_q[k] / tols[k]);
  }
  std::printf("theta1: slope in tol %.3f, error/tol %.3g..%.3g; orders in steps: q %.2f, v %.2f, lambda %.2f\n", slope, lo, hi,
              -fitted_slope(steps, e_q), -fitted_slope(steps, e_v), -fitted_slope(steps, e_l));
  EXPECT_NEAR(slope, 1.0, 0.2);
  EXPECT_LT(hi / lo, 10.0);
  EXPECT_GT(-fitted_slope(steps, e_q), 1.7);
  EXPECT_GT(-fitted_slope(steps, e_v), 1.7);
  EXPECT_GT(-fitted_slope(steps, e_l), 1.7);
}

// A first step far too large is rejected and retried with a smaller one; the run then reaches the
// accuracy of a run with a good first step.
TEST(AdaptiveSteps, RejectedStepsAreRetriedFromTheSameState) {
  const auto ref = read_csv(source_path("tests/reference/slider_crank.csv"));
  auto with_h = [](double tol, const std::string& h) {
    std::vector<std::string> o = tolerance(tol);
    o.push_back("solver.h=" + h);
    return o;
  };
  const RunSummary big = run_scene("slider_crank", with_h(1e-4, "0.2"));
  const RunSummary good = run_scene("slider_crank", with_h(1e-4, "1e-3"));
  EXPECT_GT(big.rejected_steps, 0);
  EXPECT_LT(big.h_min, 0.2);
  ASSERT_EQ(big.times_out.size(), static_cast<size_t>(big.steps) + 1);  // rejected steps leave no row
  for (size_t k = 1; k < big.times_out.size(); ++k) ASSERT_GT(big.times_out[k], big.times_out[k - 1]);
  const double e_big = std::fabs(final_value(big, "theta1") - at_time(ref, "theta1", 1.0));
  const double e_good = std::fabs(final_value(good, "theta1") - at_time(ref, "theta1", 1.0));
  std::printf("first h 0.2: %lld rejected, error %.3e; first h 1e-3: error %.3e\n", big.rejected_steps, e_big, e_good);
  EXPECT_LT(e_big, 3.0 * e_good);
}

// Newton failures (at most 2 iterations allowed, a first step of 0.1 s) are retried with h/2 by the
// same machinery and the run reaches t_end.
TEST(AdaptiveSteps, NewtonFailuresAreRetriedWithHalfTheStep) {
  std::vector<std::string> o = tolerance(1e-3);
  o.push_back("solver.h=0.1");
  o.push_back("solver.newton.max_iter=2");
  const RunSummary r = run_scene("slider_crank", o);
  std::printf("%d Newton failures, %lld rejected, %d steps\n", r.step_cuts, r.rejected_steps, r.steps);
  EXPECT_GT(r.step_cuts, 0);
  EXPECT_EQ(r.final_state.t, 1.0);
}

// Adaptive steps land exactly on the output times k·dt and on t_end (the heavy top: a rigid body on
// R³×SO(3)).
TEST(AdaptiveSteps, StepsLandOnTheOutputTimes) {
  std::vector<std::string> o = tolerance(1e-4);
  o.push_back("output.dt=0.05");
  o.push_back("solver.t_end=0.3");
  const RunSummary r = run_scene("heavy_top", o);
  int found = 0;
  for (int k = 1; k <= 5; ++k)
    for (double t : r.times_out)
      if (t == static_cast<double>(k) * 0.05) ++found;
  EXPECT_EQ(found, 5);
  EXPECT_EQ(r.times_out.back(), 0.3);  // t_end itself (6 · 0.05 is 0.30000000000000004)
}

// A 4 ms pulse at t = 0.1 s on a beam at rest (inputs/beam_impulse.yaml): before it nothing moves,
// the error estimate is zero and h grows; the steps land on the load's breakpoints (0.1, 0.102,
// 0.104 s) instead of stepping over the pulse, and the beam is set in motion. (tol = 1e-3: at 1e-2 the
// filtered estimate, which leaves out the bending modes the scheme damps, takes 32 steps for the 0.2 s
// and tip_y is 10 % off the fixed steps', beyond the 5 % of the comparison below.)
TEST(AdaptiveSteps, StepsLandOnTheLoadsBreakpoints) {
  std::vector<std::string> o = tolerance(1e-3);
  o.push_back("solver.t_end=0.2");
  const RunSummary r = run_scene("beam_impulse", o);
  for (double tb : {0.1, 0.102, 0.104}) {
    bool found = false;
    for (double t : r.times_out) found = found || t == tb;
    EXPECT_TRUE(found) << "no step ends at " << tb;
  }
  // The same motion as fixed steps of 1e-3 s that sample the pulse (within their error): a pulse
  // stepped over would leave the beam at rest.
  const RunSummary fixed = run_scene("beam_impulse", {"solver.t_end=0.2"});
  std::printf("tip_y at 0.2 s: %.4g m after %d adaptive steps, %.4g m after %d fixed steps\n", final_value(r, "tip_y"), r.steps,
              final_value(fixed, "tip_y"), fixed.steps);
  EXPECT_NEAR(final_value(r, "tip_y"), final_value(fixed, "tip_y"), 0.05 * std::fabs(final_value(fixed, "tip_y")));
}

// Fixed steps: the time of step k is k·h, computed, not summed (deal.II's DiscreteTime): no drift,
// so the step at 0.5 s prints 0.5; and a run without failures under step_cuts is the same run.
TEST(DriftFreeTimes, FixedStepTimesAreMultiplesOfTheStep) {
  const RunSummary r = run_scene("slider_crank", {});
  ASSERT_EQ(r.times_out.size(), 201u);
  for (size_t k = 0; k < r.times_out.size(); ++k) ASSERT_EQ(r.times_out[k], static_cast<double>(k) * 0.005) << "step " << k;
  EXPECT_EQ(r.times_out[100], 0.5);
  EXPECT_EQ(r.times_out.back(), 1.0);
}

// The controller's plan on its own: a fixed step lands on t_end (shortened when t_end is no
// multiple of h); an adaptive step lands on the output times with equal steps.
TEST(StepControllerPlan, FixedAndAdaptiveLanding) {
  FixedSteps fixed(0.3, 1.0);
  EXPECT_EQ(fixed.total_steps(0, 0.0), 4);
  StepPlan p = fixed.plan(0.0);
  EXPECT_EQ(p.t_next, 0.3);
  EXPECT_FALSE(p.last);
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(fixed.converged(p, 0.0));
    p = fixed.plan(p.t_next);
  }
  EXPECT_TRUE(p.last);
  EXPECT_EQ(p.t_next, 1.0);
  EXPECT_NEAR(p.h, 0.1, 1e-15);
  EXPECT_FALSE(fixed.shortened_last_step(0.0, false).empty());

  AdaptiveOptions o;
  o.rtol = 1e-3;
  o.output_dt = 0.25;
  o.h_min = 1e-12;
  Adaptive ad(0.1, 1.0, o);
  p = ad.plan(0.0);
  // 0.25 away at h = 0.1: three equal steps of 0.25/3 land on it.
  EXPECT_NEAR(p.h, 0.25 / 3.0, 1e-16);
  EXPECT_TRUE(p.resized);
  // An error above 1 rejects and shrinks h, at least to a fifth.
  EXPECT_FALSE(ad.converged(p, 4.0));
  EXPECT_NEAR(ad.state().h, p.h * 0.9 * 0.5, 1e-16);
  EXPECT_EQ(ad.state().rejected, 1);
  // A Newton failure halves h.
  const StepPlan q = ad.plan(0.0);
  EXPECT_TRUE(ad.newton_failed(q));
  EXPECT_EQ(ad.state().h, 0.5 * q.h);
}

// solver.tolerance.hold (RADAU5's hysteresis, Hairer & Wanner II, IV.8): a proposed growth below
// the factor keeps h exactly (so modified Newton keeps S_t); a larger growth and every decrease are
// taken as without it (hold = 1, the default, is the controller unchanged).
TEST(StepControllerPlan, HoldKeepsTheStepForASmallGrowthOnly) {
  AdaptiveOptions o;
  o.rtol = 1e-3;
  o.h_min = 1e-12;
  // The ratio of the h after a second accepted step (error e2, after e1 = 0.35) to that step's h.
  auto ratio = [&](double hold, double e2) {
    o.hold = hold;
    Adaptive ad(0.01, 1.0, o);
    StepPlan p = ad.plan(0.0);
    EXPECT_TRUE(ad.converged(p, 0.35));
    p = ad.plan(p.t_next);
    EXPECT_FALSE(p.resized);
    EXPECT_TRUE(ad.converged(p, e2));
    return ad.state().h / p.h;
  };
  // e2 = 0.35 after 0.35: the PI controller asks 0.9 · 0.35^(−0.15) = 1.054: held at 1.2, taken at 1.
  EXPECT_NEAR(ratio(1.0, 0.35), 0.9 * std::pow(0.35, -0.15), 1e-12);
  EXPECT_EQ(ratio(1.2, 0.35), 1.0);
  // A small error asks for more than 1.2 (the clamp, 2): taken in full, as without the hold.
  EXPECT_EQ(ratio(1.2, 1e-3), ratio(1.0, 1e-3));
  EXPECT_GT(ratio(1.2, 1e-3), 1.2);
  // A decrease is never held.
  EXPECT_EQ(ratio(1.2, 0.99), ratio(1.0, 0.99));
  EXPECT_LT(ratio(1.2, 0.99), 1.0);
}

TEST(AdaptiveSteps, BadKeysAreNamed) {
  const std::string base = "name: x\nbodies: [{name: b, type: particle, mass: 1, position: [0, 0]}]\n";
  // Each scene's tail and the message its error must contain.
  const std::pair<std::string, std::string> cases[] = {
      {"solver: {tolerance: {rtol: 0}}\n", "solver.tolerance: expected rtol > 0 or atol > 0"},
      {"solver: {h_min: 1e-6}\n", "solver.h_min: only with solver.tolerance"},
      {"solver: {tolerance: {rtol: 1e-4}, step_cuts: 3}\n", "solver.step_cuts: not together with solver.tolerance"},
      {"solver: {tolerance: {rtol: 1e-4}, h_min: 1e-2, h_max: 1e-3}\n", "solver.h_min: exceeds solver.h_max"},
      {"solver: {h: 1e-3}\noutput: {dt: 2.5e-3}\n", "output.dt: expected a multiple of solver.h"}};
  for (const auto& c : cases)
    EXPECT_NE(input_error_of([&] { read_scene_text(base + c.first, "x.yaml"); }).find(c.second), std::string::npos) << c.first;
}

// The study's tolerance axis (study.tol): read in mode convergence, refused elsewhere.
TEST(AdaptiveSteps, StudyToleranceAxis) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "alphaflex_study_tol";
  fs::create_directories(dir);
  const fs::path scene = dir / "pendulum.yaml", study = dir / "study.yaml";
  std::ofstream(scene) << "solver: {h: 1.0e-3, t_end: 0.01}\n"
                          "bodies: [{name: bar, type: rigid_body, mass: 1, inertia: 0.1, position: [0.5, 0]}]\n"
                          "joints: [{name: pin, type: revolute, body1: bar, point1: [-0.5, 0], body2: ground, point2: [0, 0]}]\n";
  std::ofstream(study) << "study:\n  h: [1e-3]\n  tol: [1e-3, 1e-4]\n  reference: {h: 1e-4}\n";
  const study::StudySpec spec = study::read_study(scene.string(), study.string());
  EXPECT_EQ(spec.tol, (std::vector<double>{1e-3, 1e-4}));
  std::ofstream(study) << "study:\n  mode: oscillation\n  h: [1e-3]\n  tol: [1e-3]\n";
  EXPECT_NE(input_error_of([&] { study::read_study(scene.string(), study.string()); }).find("study.tol: only in mode convergence"),
            std::string::npos);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace alphaflex
