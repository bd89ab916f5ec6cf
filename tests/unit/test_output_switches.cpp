// Output that costs nothing when it is not wanted (issue 22): which steps write a sensor row
// (output.sensors_dt, io/sensor_schedule.hpp), and the round-off warning of small steps
// (integrators/round_off_floor.hpp) checked against what it claims. The files themselves
// (no CSV, no checkpoint, restarts) are checked through the executable: tests/cli/output_switches.py.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "alphaflex/integrators/round_off_floor.hpp"
#include "alphaflex/io/sensor_schedule.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

/// The steps (indices into `times`, 0 = the initial state) that get a row.
std::vector<int> rows(SensorSchedule sch, const std::vector<double>& times, int first = 0) {
  std::vector<int> r;
  for (size_t k = static_cast<size_t>(first); k < times.size(); ++k)
    if (sch.due(times[k], k + 1 == times.size())) r.push_back(static_cast<int>(k));
  return r;
}

TEST(SensorSchedule, EveryStepOffAndAtMultiplesOfDt) {
  // Fixed steps as the loop makes them: t = k·h (h = 1e-3 is not exact in binary).
  std::vector<double> t;
  for (int k = 0; k <= 23; ++k) t.push_back(k * 1e-3);
  EXPECT_EQ(rows(SensorSchedule(true, 0.0, 0.0, true), t).size(), t.size());
  EXPECT_TRUE(rows(SensorSchedule(false, 0.0, 0.0, true), t).empty());
  EXPECT_TRUE(rows(SensorSchedule(false, 5e-3, 0.0, true), t).empty());
  // dt = 5h: rows at 0, 5h, 10h, 15h, 20h and the last step (23h).
  EXPECT_EQ(rows(SensorSchedule(true, 5e-3, 0.0, true), t), (std::vector<int>{0, 5, 10, 15, 20, 23}));
}

TEST(SensorSchedule, VariableStepsGetTheFirstStepAtOrAfterEachMultiple) {
  // Steps of irregular length: 0.004 passes 0.003; 0.0118 passes both 0.006 and 0.009 (one row);
  // 0.012 lands on a multiple up to round-off (0.1 + 0.2 - 0.3 style: 0.012 - 1e-18).
  const std::vector<double> t{0.0, 0.001, 0.004, 0.005, 0.0118, 0.012 - 1e-18, 0.013, 0.0149};
  EXPECT_EQ(rows(SensorSchedule(true, 3e-3, 0.0, true), t), (std::vector<int>{0, 2, 4, 5, 7}));
}

TEST(SensorSchedule, ARestartWritesTheRowsOfTheUninterruptedRun) {
  std::vector<double> t;
  for (int k = 0; k <= 17; ++k) t.push_back(k * 2.5e-4);
  const std::vector<int> whole = rows(SensorSchedule(true, 1e-3, 0.0, true), t);
  for (int at : {3, 4, 5, 9}) {
    // From a checkpoint after step `at`: no initial row, the steps after it.
    const std::vector<int> rest = rows(SensorSchedule(true, 1e-3, t[static_cast<size_t>(at)], false), t, at + 1);
    std::vector<int> expected;
    for (int k : whole)
      if (k > at) expected.push_back(k);
    EXPECT_EQ(rest, expected) << "restart after step " << at;
  }
}

TEST(RoundOffFloor, IsEpsilonTimesQOverBetaHSquared) {
  const AlphaParameters p = AlphaParameters::from_rho_inf(0.7);
  const double h = 1e-4, q = 10.0;
  const double expected = std::numeric_limits<double>::epsilon() * q * (1.0 - p.alpha_m) / (h * h * p.beta * (1.0 - p.alpha_f));
  EXPECT_NEAR(round_off_floor(p, h, q), expected, 1e-14 * expected);
}

// The warning appears exactly when the floor exceeds 1e-3 of the accelerations, and the h it
// recommends is where the floor is 1e-3 of them (floor ∝ 1/h²).
TEST(RoundOffFloor, WarnsBelowTheStepItRecommends) {
  const AlphaParameters p = AlphaParameters::from_rho_inf(0.7);
  const double q = 10.0, acc = 3.5e-3;
  const double h_ok = std::sqrt(std::numeric_limits<double>::epsilon() * q * (1.0 - p.alpha_m) /
                                (p.beta * (1.0 - p.alpha_f) * 1e-3 * acc));
  EXPECT_TRUE(round_off_floor_warning(p, 1.01 * h_ok, q, acc).empty());
  const std::string w = round_off_floor_warning(p, 0.99 * h_ok, q, acc);
  EXPECT_NE(w.find("positions and velocities are not affected"), std::string::npos) << w;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", h_ok);
  EXPECT_NE(w.find(std::string("use h >= ") + buf + " s"), std::string::npos) << w;
  // A model at rest (q̈ = 0 at start and end): warned without a recommendation.
  EXPECT_NE(round_off_floor_warning(p, 1e-6, q, 0.0).find("q̈ = 0"), std::string::npos);
}

// Per reaction (round_off_floor.hpp): the estimate ε‖q‖(β'm + b) is judged against each joint's own
// largest |λ|; the joint with the largest share is named, the h it recommends is where its share is
// 1e-3 (β' ∝ 1/h², b fixed), and a joint whose b alone exceeds the share gets no h. Joints that
// carried no load are not judged. The figures: the 0.1-s spin-up's hub (m = 0.4 kg, b = 2.8e7,
// Λ = 3.65e-3 N·m, ‖q‖ = 10 m, measured by this run: docs/performance.md).
TEST(RoundOffFloor, PerReactionShareAndStep) {
  const AlphaParameters p = AlphaParameters::from_rho_inf(0.7);
  const double eps = std::numeric_limits<double>::epsilon(), q = 10.0;
  ReactionScale hub{"hub", 0.4, 2.8e7, 3.65e-3};
  EXPECT_NEAR(reaction_round_off(p, 1e-4, q, hub), eps * q * (p.beta_prime(1e-4) * 0.4 + 2.8e7), 1e-15);
  // h at which the share is 1e-3: β' = (1e-3 Λ/(ε‖q‖) − b)/m.
  const double beta_needed = (1e-3 * hub.reaction / (eps * q) - hub.stiffness) / hub.mass;
  const double h_ok = 1e-4 * std::sqrt(p.beta_prime(1e-4) / beta_needed);
  EXPECT_TRUE(reaction_round_off_warning(p, 1.01 * h_ok, q, {hub}).empty());
  const std::string w = reaction_round_off_warning(p, 0.99 * h_ok, q, {hub});
  EXPECT_NE(w.find("joint 'hub'"), std::string::npos) << w;
  EXPECT_NE(w.find("positions and velocities are not affected"), std::string::npos) << w;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", h_ok);
  EXPECT_NE(w.find(std::string("use h >= ") + buf + " s"), std::string::npos) << w;
  EXPECT_TRUE(reaction_round_off_warning(p, 1e-4, q, {hub}).empty());  // share 1.1e-4 at h = 1e-4
  // The worst share is named, not the first joint; unloaded joints are skipped.
  ReactionScale big{"big", 0.4, 2.8e7, 1e3}, idle{"idle", 1e9, 1e9, 0.0};
  EXPECT_NE(reaction_round_off_warning(p, 5e-6, q, {big, hub, idle}).find("joint 'hub'"), std::string::npos);
  EXPECT_TRUE(reaction_round_off_warning(p, 1e-9, q, {idle}).empty());
  // A stiffness alone above 1e-3 of the reaction: no step size helps, and the message says so.
  ReactionScale stiff{"stiff", 1.0, 1e14, 1.0};
  EXPECT_NE(reaction_round_off_warning(p, 1.0, q, {stiff}).find("No step size"), std::string::npos);
}

}  // namespace
}  // namespace alphaflex
