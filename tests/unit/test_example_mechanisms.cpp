// The example scenes beyond the paper: exact discrete invariants of the cart-pendulum (prismatic
// and revolute joints, gravity) and the quick-return mechanism (a point-on-line joint on a turning
// lever) against an independent reference (tests/reference/README.md).
#include <gtest/gtest.h>

#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

size_t column(const Scene& sc, const std::string& name) {
  for (size_t i = 0; i < sc.model->sensors().size(); ++i)
    if (sc.model->sensors()[i].name == name) return i;
  throw std::runtime_error("no sensor " + name);
}

// With no spring and no push, the only horizontal forces are internal (the pin) or zero (the
// rail's reaction is normal to it). Equilibrium is enforced exactly at every step, so
// Σ m q̈_x = 0, hence Σ m a_x = 0 by eq. (3), and by eq. (5) the horizontal momentum
// mc·vx_cart + mp·vx_pendulum keeps its initial value 0 to round-off.
TEST(CartPendulum, HorizontalMomentumIsConservedWithoutExternalHorizontalForce) {
  const std::vector<std::string> free{"forces.0.stiffness=0", "forces.0.damping=0", "forces.1.value=[0, 0]"};
  Scene sc = read_scene(source_path("inputs/cart_pendulum.yaml"), free);
  const RunSummary r = run_scene("cart_pendulum", free);
  const size_t vc = column(sc, "vx_cart"), vp = column(sc, "vx_pendulum");
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
  Scene sc = read_scene(source_path("inputs/cart_pendulum.yaml"));
  const RunSummary r = run_scene("cart_pendulum", {});
  const size_t fy = column(sc, "rail_fy"), ay = column(sc, "ay_pendulum");
  const double mc = 2.0, mp = 0.5, g = 9.81;
  for (const auto& row : r.sensor_history)
    ASSERT_NEAR(row[fy], (mc + mp) * g + mp * row[ay], 1e-8 * (mc + mp) * g);
}

}  // namespace
}  // namespace alphaflex::testing
