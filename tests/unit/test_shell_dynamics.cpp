// Shells in multibody dynamics (inputs/shell_spinup.yaml: a plate clamped to a driven rigid hub):
// the Lie-group generalized-α converges with order 2 in positions, rotations (on the group),
// velocities and multipliers for ρ∞ = 0.7 (Brüls, Cardona & Arnold 2012; Arnold & Brüls 2007,
// Sec. 5), measured as differences of successive halvings of h at t = 0.3 s (spin-up under way).
#include <gtest/gtest.h>

#include <cmath>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::fitted_slope;
using testing::run_scene;

TEST(ShellDynamics, SpinUpConvergesWithOrderTwoInTimeForRhoPointSeven) {
  const std::vector<double> hs{4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4};
  std::vector<RunSummary> runs;
  for (double h : hs)
    runs.push_back(run_scene("shell_spinup", {"solver.t_end=0.3", "solver.rho_inf=0.7", "solver.h=" + std::to_string(h)}));
  std::vector<double> ex, er, ev, el;
  for (size_t k = 0; k + 1 < runs.size(); ++k) {
    const auto d = testing::spatial_difference(runs[k].final_state, runs[k + 1].final_state);
    ex.push_back(d.position);
    er.push_back(d.rotation);
    ev.push_back(d.velocity);
    el.push_back(d.multiplier);
    std::printf("h %.1e: |dx| %.3e m, |dR| %.3e rad, |dv| %.3e, |dlambda| %.3e\n", hs[k], d.position, d.rotation,
                d.velocity, d.multiplier);
  }
  const std::vector<double> h_fit(hs.begin(), hs.end() - 1);
  std::printf("slopes: position %.2f, rotation %.2f, velocity %.2f, multiplier %.2f\n", fitted_slope(h_fit, ex),
              fitted_slope(h_fit, er), fitted_slope(h_fit, ev), fitted_slope(h_fit, el));
  EXPECT_NEAR(fitted_slope(h_fit, ex), 2.0, 0.25);
  EXPECT_NEAR(fitted_slope(h_fit, er), 2.0, 0.25);
  EXPECT_NEAR(fitted_slope(h_fit, ev), 2.0, 0.25);
  EXPECT_NEAR(fitted_slope(h_fit, el), 2.0, 0.25);
}

}  // namespace
}  // namespace alphaflex
