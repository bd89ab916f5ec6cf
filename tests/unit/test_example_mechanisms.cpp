// The example scenes beyond the paper: exact discrete invariants of the cart-pendulum (prismatic
// and revolute joints, gravity) and the quick-return mechanism (a point-on-line joint on a turning
// lever) against an independent reference (tests/reference/README.md).
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

// With no spring and no push, the only horizontal forces are internal (the pin) or zero (the
// rail's reaction is normal to it). Equilibrium is enforced exactly at every step, so
// Σ m q̈_x = 0, hence Σ m a_x = 0 by eq. (3), and by eq. (5) the horizontal momentum
// mc·vx_cart + mp·vx_pendulum keeps its initial value 0 to round-off.
TEST(CartPendulum, HorizontalMomentumIsConservedWithoutExternalHorizontalForce) {
  const std::vector<std::string> free{"forces.0.stiffness=0", "forces.0.damping=0", "forces.1.value=[0, 0]"};
  const RunSummary r = run_scene("cart_pendulum", free);
  const size_t vc = column(r, "vx_cart"), vp = column(r, "vx_pendulum");
  const double mc = 2.0, mp = 0.5;  // inputs/cart_pendulum.yaml
  double worst = 0.0, scale = 0.0;
  for (const auto& row : r.sensor_history) {
    worst = std::max(worst, std::fabs(mc * row[vc] + mp * row[vp]));
    scale = std::max(scale, mp * std::fabs(row[vp]));
  }
  EXPECT_GT(scale, 0.1);  // the pendulum does swing
  EXPECT_LT(worst, 1e-10 * scale);
}

// Vertical equilibrium of cart + pendulum: the rail carries the weight plus the pendulum's
// vertical inertia force, rail_fy = (mc + mp) g + mp ÿ_pendulum, at every step (the cart's own
// ÿ is zero: the rail constraint is linear and holds exactly). Checks the sign and size of
// the reported joint reaction.
TEST(CartPendulum, RailReactionBalancesWeightAndPendulumInertia) {
  const RunSummary r = run_scene("cart_pendulum", {});
  const size_t fy = column(r, "rail_fy"), ay = column(r, "ay_pendulum");
  const double mc = 2.0, mp = 0.5, g = 9.81;
  for (const auto& row : r.sensor_history)
    ASSERT_NEAR(row[fy], (mc + mp) * g + mp * row[ay], 1e-8 * (mc + mp) * g);
}

// Quick-return mechanism against the independent reference tests/reference/quick_return.csv
// (scripts/reference/quick_return_reference.py: Lagrange in the crank angle, DOP853 at 1e-13,
// cross-checked by an absolute-coordinate index-1 model). At t = 1 s the errors in φ, in the
// slot force on the crank and in the ground force at O fall like h² (slope in [1.8, 2.2]).
TEST(QuickReturn, SecondOrderConvergenceAgainstReference) {
  const std::vector<std::string> names{"phi", "slot_fx", "O_fx"};
  const std::vector<double> p =
      error_slopes("quick_return", "tests/reference/quick_return.csv", names, {2e-3, 1e-3, 5e-4, 2.5e-4}, 1.0);
  for (size_t k = 0; k < names.size(); ++k) {
    EXPECT_GE(p[k], 1.8) << names[k];
    EXPECT_LE(p[k], 2.2) << names[k];
  }
}

// Over the whole history (every 0.01 s from t = 0.05 s) the error is C(t) h² with a smooth C:
// Richardson extrapolation (4 y(h/2) − y(h))/3 of runs at h = 5e-4 and 2.5e-4 must be at least
// 100 times closer to the reference than the finer run, for angles, reactions and point
// positions alike. (Before 0.05 s the start-up transient of the multipliers, damped like ρ∞ⁿ
// as eq. (38) says, is not yet O(h²).)
TEST(QuickReturn, HistoryErrorIsSecondOrderRichardson) {
  const auto ref = read_csv(source_path("tests/reference/quick_return.csv"));
  const RunSummary coarse = run_scene("quick_return", {"solver.h=5e-4"});
  const RunSummary fine = run_scene("quick_return", {"solver.h=2.5e-4"});
  for (const char* n : {"phi", "psi", "slot_fx", "slot_fy", "O_fx", "O_fy", "Bx", "By"}) {
    const size_t c = column(fine, n);
    double err_fine = 0.0, err_extrapolated = 0.0;
    for (size_t i = 5; i <= 100; ++i) {
      const double t = 0.01 * static_cast<double>(i), y_ref = at_time(ref, n, t);
      const double yc = coarse.sensor_history[20 * i][c], yf = fine.sensor_history[40 * i][c];
      ASSERT_NEAR(fine.times_out[40 * i], t, 1e-9);
      err_fine = std::max(err_fine, std::fabs(yf - y_ref));
      err_extrapolated = std::max(err_extrapolated, std::fabs((4.0 * yf - yc) / 3.0 - y_ref));
    }
    EXPECT_LT(err_extrapolated, 0.01 * err_fine) << n;
  }
}

}  // namespace
}  // namespace alphaflex::testing
