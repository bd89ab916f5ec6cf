// Block low-rank factorization (solver.linear.low_rank, MUMPS' BLR: ICNTL(35), CNTL(7)) on a
// shell scene: it is really active — MUMPS' own count of entries in the compressed factors,
// INFOG(35), is below the full-rank count INFOG(29) — and the results stay those of the exact
// factorization. Bound: BLR at ε perturbs the Newton matrix by about ε relative per block, which
// changes only the Newton path (the residual is exact), so the converged step differs from the
// exact run's by what Newton leaves, the tolerance on the last correction (rtol 1e-9): 1e-9
// relative on the plate's centre deflection and corner moment (measured: 8e-13 and 2e-16).
//
// Size: MUMPS 5.5 compresses only fronts above its BLR size threshold, and the plate has none up
// to 3.4·10⁴ unknowns (n = 36); at n = 48 (58 758 unknowns) three fronts are compressed, 96 % of
// the factor entries remain at ε = 1e-8. So this test is large for the suite: one dynamic step
// (6 factorizations), about 6 s of CPU and 0.9 GB per run, two runs.
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

// The clamped plate under pressure (inputs/plate_pressure.yaml) on a 48 × 48 grid, one step of
// the dynamics (the pressure applied at rest). Full Newton: a new factorization every iteration, so
// that BLR's approximation of S_t shows in Newton's iterations (modified Newton, the default at
// this size, would use one factorization for the whole step).
const std::vector<std::string> kPlate{"mesh.parameters.n=48", "solver.analysis=dynamic", "solver.h=1e-5",
                                      "solver.t_end=1e-5", "solver.newton.modified=off"};

TEST(LowRankFactorization, CompressesTheFactorsAndKeepsTheResults) {
  const RunSummary exact = run_scene("plate_pressure", kPlate);
  std::vector<std::string> blr = kPlate;
  blr.push_back("solver.linear.low_rank=1e-8");
  const RunSummary low = run_scene("plate_pressure", blr);

  ASSERT_TRUE(exact.mumps.mumps);
  ASSERT_TRUE(low.mumps.mumps);
  EXPECT_EQ(exact.mumps.low_rank_tolerance, 0.0);   // off by default
  EXPECT_EQ(low.mumps.low_rank_tolerance, 1e-8);    // CNTL(7) as MUMPS holds it
  EXPECT_EQ(low.mumps.entries, exact.mumps.entries);  // INFOG(29): the full-rank count, the same pattern
  EXPECT_GT(low.mumps.low_rank_entries, 0.0);
  EXPECT_LT(low.mumps.low_rank_entries, 0.99 * low.mumps.entries) << "BLR compressed less than 1 % of the factors (measured: 3.9 %)";

  for (const char* s : {"w_centre", "m11_corner"}) {
    const double a = final_value(exact, s), b = final_value(low, s);
    EXPECT_NEAR(b, a, 1e-9 * std::fabs(a)) << s;
  }
  EXPECT_EQ(low.steps, exact.steps);
  EXPECT_EQ(low.newton_total, exact.newton_total);  // 3 and 3: BLR at 1e-8 leaves Newton's contraction as it is
}

}  // namespace
}  // namespace alphaflex::testing
