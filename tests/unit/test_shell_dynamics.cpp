// Shells in multibody dynamics (inputs/shell_spinup.yaml: a plate clamped to a driven rigid hub):
// the Lie-group generalized-α converges with order 2 in positions, rotations (on the group),
// velocities and multipliers for ρ∞ = 0.7 (Brüls, Cardona & Arnold 2012; Arnold & Brüls 2007,
// Sec. 5), measured as differences of successive halvings of h at t = 0.3 s (spin-up under way).
// Full Newton: the differences at the smallest h (7e-7 m) must be the scheme's, and what modified
// Newton (the default at 228 unknowns) leaves within its tolerance reaches the velocities through
// γ' ~ 1/h (measured with it: order 1.43 in v).
#include <gtest/gtest.h>

#include <cmath>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::run_scene;

TEST(ShellDynamics, SpinUpConvergesWithOrderTwoInTimeForRhoPointSeven) {
  const std::vector<double> hs{4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4};
  std::vector<RunSummary> runs;
  for (double h : hs)
    runs.push_back(run_scene("shell_spinup", {"solver.t_end=0.3", "solver.rho_inf=0.7", "solver.h=" + std::to_string(h),
                                              "solver.newton.modified=off"}));
  const testing::GroupOrders o = testing::successive_difference_orders(hs, runs, "");
  EXPECT_NEAR(o.position, 2.0, 0.25);
  EXPECT_NEAR(o.rotation, 2.0, 0.25);
  EXPECT_NEAR(o.velocity, 2.0, 0.25);
  EXPECT_NEAR(o.multiplier, 2.0, 0.25);
}

}  // namespace
}  // namespace alphaflex
