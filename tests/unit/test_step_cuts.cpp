// Newton failure policy (solver.step_cuts): a dynamic step whose Newton iteration fails is retried
// from the saved state with h halved, and h grows back after good steps. Checked on the paper's
// slider-crank (inputs/slider_crank.yaml) with Newton limited to 3 iterations, which fails at a
// fast phase of the crank with the scene's h = 5e-3 s.
#include <gtest/gtest.h>

#include <cmath>

#include "alphaflex/core/error.hpp"
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

}  // namespace
}  // namespace alphaflex
