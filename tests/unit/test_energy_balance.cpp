// Energy totals and the energy balance (inputs/energy_balance.yaml): E(t) − E(0) = W_ext(t) − D(t)
// for a scene with gravity, a spring-damper, a bushing, a joint motor and a flexible beam; the
// sensors `energy` (of: a block, a body, the model) and `work` (accumulated by the trapezoidal rule).
#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

/// max over the output times of |E − E(0) − W + D|, and the scale of the exchanges (max |W|, |D|).
struct Balance {
  double residual = 0.0, scale = 0.0, final_residual = 0.0;
};

Balance balance(const RunSummary& r) {
  const size_t E = column(r, "E"), W = column(r, "W"), D = column(r, "D");
  Balance b;
  for (const auto& row : r.sensor_history) {
    const double res = row[E] - r.sensor_history[0][E] - row[W] + row[D];
    b.residual = std::max(b.residual, std::fabs(res));
    b.scale = std::max({b.scale, std::fabs(row[W]), std::fabs(row[D])});
    b.final_residual = res;
  }
  return b;
}

}  // namespace

TEST(EnergyBalance, TotalEnergyChangeEqualsTheWorkOfTheLoadsLessTheDissipationAtOrderTwoInTheStep) {
  // ρ∞ = 1 (α_m = α_f = ½, β = ¼, γ = ½): no numerical dissipation, so what is left of
  // E − E(0) − W + D is the time discretization of the scheme and of the trapezoidal integrals of
  // the powers, both second order: halving h must divide it by ~4 (fitted slope ≥ 1.8; measured 2.00,
  // max residual 4.5e-3, 1.1e-3, 2.8e-4 J against W = 4.9 J over 0.4 s).
  std::vector<double> hs, res;
  for (double h : {0.004, 0.002, 0.001}) {
    const RunSummary r = run_scene("energy_balance", {"solver.h=" + std::to_string(h)});
    const Balance b = balance(r);
    hs.push_back(h);
    res.push_back(b.residual);
    std::printf("[ balance  ] h = %.4f s: max |E − E0 − W + D| = %.3e J (W = %.4f J, D = %.4f J at t_end; scale %.3f J)\n", h, b.residual,
                final_value(r, "W"), final_value(r, "D"), b.scale);
    EXPECT_GT(b.scale, 0.1);                           // the motor and the dampers do exchange energy
    EXPECT_GT(final_value(r, "D"), 0.0);
    EXPECT_LE(b.residual, 1e-2 * b.scale);
    // The model's total is the sum of its parts (kinetic, strain, gravity), to round-off.
    EXPECT_NEAR(final_value(r, "E"), final_value(r, "kinetic") + final_value(r, "strain") + final_value(r, "gravity"), 1e-12);
    EXPECT_GT(final_value(r, "beam_strain"), 0.0);
    EXPECT_LE(final_value(r, "damper_loss"), final_value(r, "D") + 1e-15);
  }
  const double slope = fitted_slope(hs, res);
  std::printf("[ balance  ] fitted order of the balance residual in h: %.2f\n", slope);
  EXPECT_GE(slope, 1.8);
}

TEST(EnergyBalance, WithRhoInfBelowOneTheSchemeDissipatesWhatTheBalanceThenMisses) {
  // ρ∞ = 0.6 damps (mostly the beam's high frequencies): E − E(0) − W + D at t_end is lower than
  // with ρ∞ = 1 at the same step by that numerical dissipation, which the balance does not count.
  const RunSummary damped = run_scene("energy_balance", {"solver.rho_inf=0.6", "solver.h=0.004"});
  const RunSummary exact = run_scene("energy_balance", {"solver.h=0.004"});
  const Balance bd = balance(damped), be = balance(exact);
  std::printf("[ balance  ] h = 0.004 s: E − E0 − W + D at t_end = %.3e J with ρ∞ = 0.6, %.3e J with ρ∞ = 1: numerical dissipation %.2e J\n",
              bd.final_residual, be.final_residual, be.final_residual - bd.final_residual);
  EXPECT_LT(bd.final_residual, be.final_residual);
}

TEST(EnergyBalance, PotentialEnergyOfGravityAndSumsOverABlockAndABody) {
  // At t = 0 (nothing has moved): gravity potential −Σ m g·x = 9.81 · (bob 1 kg at z = −0.5 m) = −4.905 J
  // (the beam and the arm are at z = 0); the bob's kinetic energy ½ 1 · 0.5² = 0.125 J is the
  // model's; the beam's strain energy is 0; the work sensors start at 0.
  const RunSummary r = run_scene("energy_balance", {"solver.t_end=0.004"});
  const auto& row = r.sensor_history[0];
  EXPECT_NEAR(row[column(r, "gravity")], -4.905, 1e-12);
  EXPECT_NEAR(row[column(r, "kinetic")], 0.125, 1e-12);
  EXPECT_NEAR(row[column(r, "beam_strain")], 0.0, 1e-20);
  EXPECT_EQ(row[column(r, "W")], 0.0);
  EXPECT_EQ(row[column(r, "D")], 0.0);
  EXPECT_NEAR(row[column(r, "arm_kinetic")], 0.0, 1e-20);
}

TEST(EnergyBalance, BadInputIsRefusedNamingTheKey) {
  const std::string head =
      "name: bad\ndimension: 3\nsolver: {h: 0.01, t_end: 0.01}\n"
      "bodies:\n  - {name: b, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0, 0, 0]}\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"sensors:\n  - {name: e, type: energy, of: nobody, kind: kinetic}\n", "sensors[e].of: no block, body or force element named 'nobody'"},
      {"sensors:\n  - {name: e, type: energy, kind: kinetic}\n", "sensors[e]: give either `element` (one element) or `of`"},
      {"sensors:\n  - {name: e, type: energy, element: b, of: model, kind: kinetic}\n", "sensors[e]: give either `element`"},
      {"sensors:\n  - {name: w, type: work, kind: heat}\n", "sensors[w].kind:"},
  };
  for (const auto& [tail, expected] : cases) {
    const std::string msg = input_error_of([&] { read_scene_text(head + tail, source_path("bad.yaml")); });
    EXPECT_NE(msg.find(expected), std::string::npos) << "got: " << msg << "\nexpected: " << expected;
  }
}

}  // namespace alphaflex::testing
