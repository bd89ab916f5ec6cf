// A restart with another solver.h than the checkpoint's (allowed with a warning: the run goes on
// from the checkpoint's time with the scene's h). The fixed-step loop must count the steps left from
// the checkpoint's time, not from t = 0: once it took the old step count and ran past t_end with a
// negative last step.
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

RunSummary run_to(const std::string& outdir, const std::vector<std::string>& overrides, const std::string& restart) {
  Scene s = read_scene(source_path("inputs/slider_crank.yaml"), overrides);
  RunOptions opt;
  opt.outdir = outdir;
  opt.verbose = false;
  opt.restart = restart;
  return run_simulation(s, opt, PETSC_COMM_WORLD);
}

// The slider-crank to t = 0.2 s at h = 1e-3 (200 steps, a checkpoint at its end), restarted to
// t = 0.3 s at h = 5e-4: 200 more steps, ending at t_end. Its error is that of h = 1e-3 on
// [0, 0.2] carried on by h = 5e-4, so it differs from a run at h = 5e-4 throughout by no more
// than the h = 1e-3 run itself does (errors O(h²), Arnold & Brüls 2007, Sec. 4).
TEST(Restart, WithAnotherStepSizeCountsTheStepsLeftFromTheCheckpointTime) {
  const TestOutputDir out("restart_h");
  const std::string& dir = out.path();
  run_to(dir, {"solver.t_end=0.2", "solver.h=1e-3", "output.hdf5=off"}, "");
  const RunSummary restarted =
      run_to(dir, {"solver.t_end=0.3", "solver.h=5e-4", "output.hdf5=off"}, dir + "/slider_crank.checkpoint.h5");
  EXPECT_EQ(restarted.steps, 200 + 200);
  EXPECT_NEAR(restarted.final_state.t, 0.3, 1e-12);
  const RunSummary fine = run_scene("slider_crank", {"solver.t_end=0.3", "solver.h=5e-4"});
  const RunSummary coarse = run_scene("slider_crank", {"solver.t_end=0.3", "solver.h=1e-3"});
  const double d_restart = (restarted.final_state.q - fine.final_state.q).cwiseAbs().maxCoeff();
  const double d_coarse = (coarse.final_state.q - fine.final_state.q).cwiseAbs().maxCoeff();
  std::printf("|q - q(h = 5e-4)|: restarted %.3e, h = 1e-3 throughout %.3e\n", d_restart, d_coarse);
  EXPECT_GT(d_coarse, 0.0);
  EXPECT_LE(d_restart, d_coarse);
}

}  // namespace
}  // namespace alphaflex::testing
