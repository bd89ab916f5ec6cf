// Newton failure policy (solver.step_cuts): a dynamic step whose Newton iteration fails is retried
// from the saved state with h halved, and h grows back after good steps. Checked on the paper's
// slider-crank (inputs/slider_crank.yaml) with Newton limited to 3 iterations, which fails at a
// fast phase of the crank with the scene's h = 5e-3 s.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "alphaflex/core/error.hpp"
#include "alphaflex/driver/step_controller.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::column;
using testing::run_scene;

TEST(StepCuts, WithoutCutsTheRunStopsWithItsNewtonFailure) {
  EXPECT_THROW(run_scene("slider_crank", {"solver.newton.max_iter=3"}), SolverError);
}

// With cuts the run reaches t_end; the steps it halved are counted, h never drops below what the
// failures required, and it grows back. The variable steps cost accuracy (the scheme's order 2
// holds for constant h): printed against a converged run (h = 1.25e-4) next to the fixed-step error.
TEST(StepCuts, HalvedStepsCarryTheRunThroughAndGrowBack) {
  const RunSummary ref = run_scene("slider_crank", {});
  const RunSummary cut = run_scene("slider_crank", {"solver.newton.max_iter=3", "solver.step_cuts=4"});
  std::printf("step cuts: %d, steps %d (fixed: %d), smallest h %.3g s\n", cut.step_cuts, cut.steps, ref.steps, cut.h_min);
  EXPECT_GT(cut.step_cuts, 0);
  EXPECT_NEAR(cut.times_out.back(), 1.0, 1e-12);
  EXPECT_GE(cut.h_min, 5e-3 / 16);
  // Grown back: far fewer steps than if every step after the first cut had stayed halved.
  EXPECT_LT(cut.steps, ref.steps + 4 * cut.step_cuts);
  const RunSummary fine = run_scene("slider_crank", {"solver.h=1.25e-4"});
  const size_t c = column(ref, "u4");
  std::printf("u4 at t_end: error with cuts %.3e, with fixed h %.3e (converged %.6f)\n",
              cut.final_sensors[c] - fine.final_sensors[c], ref.final_sensors[c] - fine.final_sensors[c], fine.final_sensors[c]);
}

// Without failures the policy changes nothing: the same steps, bit for bit.
TEST(StepCuts, WithoutFailuresTheRunIsBitIdentical) {
  const RunSummary a = run_scene("slider_crank", {});
  const RunSummary b = run_scene("slider_crank", {"solver.step_cuts=4"});
  EXPECT_EQ(b.step_cuts, 0);
  ASSERT_EQ(a.sensor_history.size(), b.sensor_history.size());
  for (size_t k = 0; k < a.sensor_history.size(); ++k) EXPECT_EQ(a.sensor_history[k], b.sensor_history[k]) << "row " << k;
  EXPECT_TRUE((a.final_state.q.array() == b.final_state.q.array()).all());
}

// solver.step_cuts = N bounds the halvings in force, not the failures between two converged steps:
// h ≥ h/2^N over the whole run. The controller alone, with the failure pattern of a Newton iteration
// at its round-off floor (below): every step fails once and its halved retry converges. Before the
// fix each converged step cleared the count, so this pattern halved h without limit.
TEST(StepCuts, HalvingsInForceStayWithinTheLimitAcrossConvergedSteps) {
  const double h = 5e-3;
  CutBack c(h, 500.0, 4);
  double t = 0.0;
  for (int k = 1; k <= 4; ++k) {
    const StepPlan failed = c.plan(t);
    ASSERT_TRUE(c.newton_failed(failed)) << "halving " << k;
    const StepPlan retry = c.plan(t);
    EXPECT_EQ(retry.h, h / (1 << k));  // halving is exact in binary
    ASSERT_TRUE(c.converged(retry, 0.0));
    t = retry.t_next;
  }
  EXPECT_EQ(c.state().cuts_in_row, 4);
  // A fifth halving would go below h/16: refused, and the message names the h reached and the cuts.
  const StepPlan at_limit = c.plan(t);
  EXPECT_EQ(at_limit.h, h / 16);
  EXPECT_FALSE(c.newton_failed(at_limit));
  EXPECT_EQ(c.state().h, h / 16);
  const std::string why = c.too_small(at_limit);
  EXPECT_NE(why.find("solver.step_cuts = 4: the step failed at h = 0.0003125 s, solver.h = 0.005 s halved 4 times"), std::string::npos)
      << why;
  EXPECT_NE(why.find("4 step cuts in the run so far"), std::string::npos) << why;
  EXPECT_EQ(c.state().h_min, h / 16);

  // 4 converged steps double h and undo one halving: one cut is allowed again, not a fifth.
  auto converge = [&](int steps) {
    for (int k = 0; k < steps; ++k) {
      const StepPlan p = c.plan(t);
      ASSERT_TRUE(c.converged(p, 0.0));
      t = p.t_next;
    }
  };
  converge(4);
  EXPECT_EQ(c.state().h, h / 8);
  EXPECT_EQ(c.state().cuts_in_row, 3);
  EXPECT_TRUE(c.newton_failed(c.plan(t)));
  EXPECT_EQ(c.state().h, h / 16);
  EXPECT_FALSE(c.newton_failed(c.plan(t)));
  // Back at the scene's h after 4 × 4 converged steps: no halving in force, N cuts allowed again.
  converge(16);
  EXPECT_EQ(c.state().h, h);
  EXPECT_EQ(c.state().cuts_in_row, 0);
  EXPECT_TRUE(c.too_small(c.plan(t)).empty());
  EXPECT_EQ(c.state().newton_failures, 5);
}

// In a run: Newton limited to 2 iterations on the slider-crank at its h = 5e-3 s fails again and
// again, with converged steps in between. Measured before the fix with step_cuts = 2: the run went
// through with 386 cuts and h down to 3.125e-4 s = h/16, four times below the limit. Now it stops at
// the first failure at h/4 = 1.25e-3 s and says so; with step_cuts = 4 h/16 is allowed and the run
// goes through, never below it (386 cuts, as before: the steps are the same while the limit is not
// reached).
TEST(StepCuts, TheLimitHoldsInARunWithFailuresBetweenConvergedSteps) {
  const std::vector<std::string> two_iterations{"solver.newton.max_iter=2", "solver.newton.rtol=1e-9"};
  std::vector<std::string> o = two_iterations;
  o.push_back("solver.step_cuts=2");
  try {
    run_scene("slider_crank", o);
    ADD_FAILURE() << "the run did not stop at h/4";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("(h = 0.00125 s)"), std::string::npos) << what;
    EXPECT_NE(what.find("solver.step_cuts = 2: the step failed at h = 0.00125 s, solver.h = 0.005 s halved 2 times"),
              std::string::npos)
        << what;
  }
  o = two_iterations;
  o.push_back("solver.step_cuts=4");
  const RunSummary r = run_scene("slider_crank", o);
  std::printf("step_cuts = 4: %d cuts, smallest h %.4g s\n", r.step_cuts, r.h_min);
  EXPECT_EQ(r.final_state.t, 1.0);
  EXPECT_GT(r.step_cuts, 4);  // more cuts than the limit: the cut state outlives converged steps
  EXPECT_GE(r.h_min, 5e-3 / 16);
}

}  // namespace
}  // namespace alphaflex
