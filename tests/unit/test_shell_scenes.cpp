// Shell scenes of inputs/ against closed forms: the clamped plate under pressure in its linear
// range (Kirchhoff), and the beam-stiffened plate bending as one Timoshenko section. (Kept apart
// from test_shell_benchmarks.cpp, whose Sze benchmarks CI runs from a Release binary of their own:
// tests/CMakeLists.txt.)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::column;
using testing::run_scene;

// inputs/plate_pressure.yaml in the linear range (p = 100 Pa, w/t ≈ 7e-4): the clamped square
// plate's centre deflection is Kirchhoff's 0.00126532 p a⁴/D (Taylor & Govindjee 2004; Mindlin's
// correction at a/t = 100 and the 16 × 16 mesh are below 0.2 %, test_shell.cpp).
TEST(ShellScenes, ClampedPlateUnderPressureMatchesKirchhoffInTheLinearRange) {
  const RunSummary r = run_scene("plate_pressure", {"load.factor=1e-4", "solver.static.steps=1"});
  const double E = 2.1e11, nu = 0.3, t = 0.01, p = 100.0;
  const double D = E * t * t * t / (12 * (1 - nu * nu));
  const double exact = -0.00126532 * p / D;  // pressure pushes against the normal (+z)
  const double w = r.final_sensors[column(r, "w_centre")];
  std::printf("[ plate    ] clamped, p = %g Pa: w_centre %.6e m, Kirchhoff %.6e m (%.2e)\n", p, w, exact, w / exact - 1);
  EXPECT_NEAR(w / exact, 1.0, 5e-3);
}

// inputs/stiffened_plate.yaml: plate and edge beams share the nodes and bend as one Timoshenko
// beam, w = P L³/(3 EI) + P L/(κGA) with EI = E (b t³/12 + 2 w h³/12); at the first elements'
// centres (x = L/40) the stiffeners' and the plate's moments add up to P (L − L/40).
TEST(ShellScenes, BeamStiffenedPlateBendsAsOneSection) {
  const RunSummary r = run_scene("stiffened_plate", {});
  const double E = 70e9, G = E / 2, b = 0.2, t = 0.005, wb = 0.01, h = 0.03, L = 1.0, P = 10.0;
  const double EI = E * (b * t * t * t / 12 + 2 * wb * h * h * h / 12);
  const double kGA = 5.0 / 6.0 * G * (b * t + 2 * wb * h);
  const double exact = -(P * L * L * L / (3 * EI) + P * L / kGA);
  const double w = r.final_sensors[column(r, "tip_w")];
  const double M = 2 * std::fabs(r.final_sensors[column(r, "root_moment_stiffener")]) +
                   b * std::fabs(r.final_sensors[column(r, "root_m11_plate")]);
  std::printf("[ stiffened] tip w %.6e m (Timoshenko %.6e, %.1e); section moment %.4f N m (P(L - L/40) = %.4f)\n", w,
              exact, w / exact - 1, M, P * (L - L / 40));
  EXPECT_NEAR(w / exact, 1.0, 2e-3);
  EXPECT_NEAR(M / (P * (L - L / 40)), 1.0, 1e-3);
}

}  // namespace
}  // namespace alphaflex
