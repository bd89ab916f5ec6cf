// The smooth start (solver.start: smooth, docs/theory/starting_values.md §5) on the ranks this binary
// runs with (ctest: 1, 2 and 3): on quick_return it removes the parasitic start-up transient of the
// reactions as on one rank (tests/unit/test_starting_values.cpp), and the run equals the one-rank run
// (PETSC_COMM_SELF, in the same process) to round-off — the start's three extra acceleration solves
// and its perturbed q̇_0, q̈_0 are distributed like the steps themselves.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "alphaflex/app/simulation.hpp"
#include "alphaflex/io/scene.hpp"
#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

int world_rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

RunSummary run_on(MPI_Comm comm, const std::vector<std::string>& overrides) {
  std::vector<std::string> all{"solver.t_end=0.05"};  // the first 50 steps at h = 1e-3
  all.insert(all.end(), overrides.begin(), overrides.end());
  Scene s = read_scene(source_path("inputs/quick_return.yaml"), all, comm);
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  opt.keep_history = true;
  return run_simulation(s, opt, comm);
}

// Reference: the same scene at h = 3.125e-5 (standard start, one rank), whose own errors are 1/1024 of
// those at h = 1e-3. The transient is the largest second difference e_{n+1} − 2e_n + e_{n−1} of the
// reactions' errors over the first 50 steps (the smooth error changes by O(h⁴) there). Measured at
// h = 1e-3, ρ∞ = 0.8 on one rank: 1.68e-2 N (smooth) against 0.247 N (standard).
TEST(SmoothStart, QuickReturnTransientRemovedOnAnyRanks) {
  const RunSummary ref = run_on(PETSC_COMM_SELF, {"solver.h=3.125e-5"});
  const RunSummary standard = run_on(PETSC_COMM_WORLD, {"solver.h=1e-3"});
  const std::vector<std::string> smooth{"solver.h=1e-3", "solver.start=smooth"};
  const RunSummary par = run_on(PETSC_COMM_WORLD, smooth);
  const RunSummary one = run_on(PETSC_COMM_SELF, smooth);
  ASSERT_EQ(standard.sensor_history.size(), 51u);
  ASSERT_EQ(par.sensor_history.size(), 51u);
  ASSERT_EQ(one.sensor_history.size(), 51u);
  auto transient = [&](const RunSummary& r) {
    double d2 = 0.0;
    for (const char* n : {"slot_fx", "slot_fy", "O_fx", "O_fy"}) {
      const size_t c = column(ref, n);
      auto e = [&](size_t i) { return r.sensor_history[i][c] - ref.sensor_history[32 * i][c]; };
      for (size_t i = 2; i < 50; ++i) d2 = std::max(d2, std::fabs(e(i + 1) - 2.0 * e(i) + e(i - 1)));
    }
    return d2;
  };
  double apart = 0.0;
  for (size_t i = 1; i <= 50; ++i)
    for (const char* n : {"slot_fx", "slot_fy", "O_fx", "O_fy"}) {
      const size_t c = column(ref, n);
      apart = std::max(apart, std::fabs(par.sensor_history[i][c] - one.sensor_history[i][c]));
    }
  const double t_standard = transient(standard), t_smooth = transient(par);
  if (world_rank() == 0)
    std::printf("h 1e-3: start-up transient %.3e N (standard), %.3e N (smooth); ranks vs one rank %.2e N\n",
                t_standard, t_smooth, apart);
  EXPECT_LT(t_smooth, 0.1 * t_standard);
  // The reactions are ~66 N; the index-3 multipliers carry Newton's tolerance times β' ~ 1/h²
  // (docs/theory/starting_values.md §3), which the ranks' different summation orders reach.
  EXPECT_LT(apart, 1e-6);
}

}  // namespace
}  // namespace alphaflex::testing
