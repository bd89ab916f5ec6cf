// Arc-length statics (integrators/arc_length.hpp) through the whole program:
//  - DaDeppo & Schmidt's (1975) clamped-hinged deep arch snaps through at P R²/EI = 897: the limit
//    point is found, reported, and passed (the load falls after it);
//  - on a path without limit points (the Euler elastica) arc length gives load control's states;
//  - a straight column under an axial load keeps its straight path, and the sign change of
//    det K_T at the Euler load π²EI/(4L²) is reported as a bifurcation candidate, with the same
//    bracket from the dense LU and from MUMPS' determinant (ICNTL(33));
//  - keys that make no sense are refused, naming the key.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <cstdio>

#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::column;
using testing::input_error_of;
using testing::run_scene;
using testing::source_path;
using testing::TestOutputDir;

const CriticalPoint* first_of(const RunSummary& r, bool limit) {
  for (const CriticalPoint& cp : r.path.critical_points)
    if ((cp.kind != CriticalPoint::Kind::Bifurcation) == limit) return &cp;
  return nullptr;
}

// The deep arch with P = 10 EI/R²: limit point at load factor 0.897 (DaDeppo & Schmidt 1975,
// P_cr R²/EI = 8.97 for the inextensible arch; EA R²/EI = 1e7 here). Measured: 0.9253 with 10
// elements per half, 0.9041 with 20 (errors 3.2 % and 0.79 %: h², ratio 4.0); the h² extrapolation
// of the two gives 0.8970. The test asks 20 per half within 1 % and the extrapolation within 0.2 %.
double arch_limit(int n, RunSummary* out = nullptr) {
  const RunSummary r = run_scene("deep_arch", {"mesh.parameters.n=" + std::to_string(n)});
  EXPECT_TRUE(r.arc_length);
  const CriticalPoint* lp = first_of(r, true);
  EXPECT_NE(lp, nullptr) << "no limit point in " << r.steps << " steps up to load factor " << r.path.load_factor;
  if (!lp) return 0.0;
  EXPECT_EQ(lp->kind, CriticalPoint::Kind::LimitMaximum);
  std::printf("deep arch (%d elements per half): limit load factor %.5f (P R^2/EI = %.4f; step %d of %d, %ld Newton its, "
              "%d cuts, %d line searches)\n", n, lp->load_factor, 10.0 * lp->load_factor, lp->step, r.steps,
              r.newton_total, r.static_cuts, r.path.line_searches);
  if (out) *out = r;
  return lp->load_factor;
}

TEST(ArcLength, DeepArchSnapsThroughAtDaDepposLimitLoad) {
  RunSummary r;
  const double l20 = arch_limit(20, &r), l10 = arch_limit(10);
  EXPECT_NEAR(l20, 0.897, 0.01 * 0.897);
  EXPECT_NEAR((4.0 * l20 - l10) / 3.0, 0.897, 0.002 * 0.897);
  EXPECT_GT(l10, l20);  // the coarser mesh is stiffer
  const CriticalPoint* lp = first_of(r, true);
  ASSERT_NE(lp, nullptr);
  // No bifurcation on this unsymmetric arch: the sign change of det K_T is the limit point's.
  EXPECT_EQ(first_of(r, false), nullptr);
  // Past the limit: the path goes on with a falling load (snap-through).
  double after = 1e9;
  for (size_t k = static_cast<size_t>(lp->step) + 1; k < r.times_out.size(); ++k) after = std::min(after, r.times_out[k]);
  EXPECT_LT(after, lp->load_factor - 0.2);
  // The crown has moved down by more than R at the limit point: a snap-through of the deep arch,
  // not a small-deflection buckle.
  EXPECT_LT(r.sensor_history[static_cast<size_t>(lp->step)][column(r, "crown_uy")], -100.0);
  // The Newton iterations per step stay near the target (6) the arc length adapts to.
  EXPECT_LE(static_cast<double>(r.newton_total) / r.steps, 7.0);
}

// Sabir & Lock's hinged roof, t = 12.7 mm, the whole roof on 8 × 8 quadrilaterals: the limit load
// (P in kN = the load factor) against the 2.25 kN quoted for it in the literature (e.g. Sze, Liu &
// Lo 2004, Sec. 3.7's curve). Measured: 2.224 kN on 8 × 8 and 2.223 on 16 × 16 (converged in the
// mesh; the 1.2 % left is the reference's reading precision and the shell theory), the load then
// falls to a minimum near 0.55 kN and rises again to 3 kN.
TEST(ArcLength, CylindricalRoofSnapsThroughAtItsLimitLoad) {
  const RunSummary r = run_scene("cylindrical_roof", {});
  ASSERT_TRUE(r.arc_length);
  for (const CriticalPoint& cp : r.path.critical_points)
    std::printf("  %s at %.4f (step %d, %.4f to %.4f)\n", cp.kind_name().c_str(), cp.load_factor, cp.step, cp.lower, cp.upper);
  // The two limit points; between them, on the falling branch, det K_T changes sign twice more
  // (a second eigenvalue of the full, symmetric roof goes negative and comes back: 1.67 and
  // 0.91 kN measured), reported as bifurcation candidates, which the symmetric path passes.
  std::vector<CriticalPoint> limits, bifurcations;
  for (const CriticalPoint& cp : r.path.critical_points)
    (cp.kind == CriticalPoint::Kind::Bifurcation ? bifurcations : limits).push_back(cp);
  ASSERT_EQ(limits.size(), 2u);
  const CriticalPoint& top = limits[0];
  const CriticalPoint& bottom = limits[1];
  EXPECT_EQ(bifurcations.size() % 2, 0u);
  for (const CriticalPoint& b : bifurcations) {
    EXPECT_GT(b.step, top.step);
    EXPECT_LT(b.step, bottom.step);
  }
  std::printf("roof 8 x 8: limit loads %.4f kN (max) and %.4f kN (min), %d steps, %ld Newton its\n", top.load_factor,
              bottom.load_factor, r.steps, r.newton_total);
  EXPECT_EQ(top.kind, CriticalPoint::Kind::LimitMaximum);
  EXPECT_EQ(bottom.kind, CriticalPoint::Kind::LimitMinimum);
  EXPECT_NEAR(top.load_factor, 2.25, 0.02 * 2.25);
  EXPECT_GT(bottom.load_factor, 0.3);
  EXPECT_LT(bottom.load_factor, 0.8);
  // At the maximum the centre has gone down by about 10.5 mm (less than the rise of 12.7 mm).
  const double w = r.sensor_history[static_cast<size_t>(top.step)][column(r, "w_center")];
  EXPECT_LT(w, -8.0);
  EXPECT_GT(w, -12.7);
  EXPECT_EQ(r.path.stop, "max_load_factor");
}

// On the elastica (no limit point) every arc-length state is load control's at the same load
// factor, and the last step lands on load.factor.
TEST(ArcLength, ReproducesLoadControlOnAPathWithoutLimitPoints) {
  const std::vector<std::string> arc = {"solver.static.method=arc_length", "solver.static.arc_length.initial=0.05",
                                        "solver.static.arc_length.max=0.2"};
  const RunSummary a = run_scene("beam_elastica_2d", arc);
  ASSERT_TRUE(a.arc_length);
  EXPECT_TRUE(a.path.critical_points.empty());
  EXPECT_EQ(a.path.stop, "max_load_factor");
  EXPECT_DOUBLE_EQ(a.times_out.back(), 1.0);
  const size_t ux = column(a, "tip_ux"), uy = column(a, "tip_uy");
  const RunSummary lc = run_scene("beam_elastica_2d", {});
  EXPECT_NEAR(a.final_sensors[ux], lc.final_sensors[ux], 1e-8);
  EXPECT_NEAR(a.final_sensors[uy], lc.final_sensors[uy], 1e-8);
  // Intermediate states: load control straight to the arc-length load factors of three steps.
  ASSERT_GE(a.times_out.size(), 5u);
  for (size_t k : {size_t{1}, a.times_out.size() / 2, a.times_out.size() - 2}) {
    char lf[40];
    std::snprintf(lf, sizeof lf, "%.17g", a.times_out[k]);  // the exact double
    const RunSummary l = run_scene("beam_elastica_2d", {std::string("load.factor=") + lf, "solver.static.steps=10"});
    EXPECT_NEAR(l.final_sensors[uy], a.sensor_history[k][uy], 1e-8) << "load factor " << lf;
    EXPECT_NEAR(l.final_sensors[ux], a.sensor_history[k][ux], 1e-8) << "load factor " << lf;
  }
  std::printf("elastica by arc length: %d steps, %ld Newton its (load control: %d steps, %ld its)\n", a.steps,
              a.newton_total, lc.steps, lc.newton_total);
}

// A planar cantilever column, L = 1, EI = 1, under an axial dead load 4 P_E (P_E = π²EI/(4L²)):
// the straight path has no limit point, and det K_T changes sign at load factor 1/4 (16 elements:
// the discrete Euler load is within 0.1 % of the continuum one).
std::string column_scene(const TestOutputDir& dir) {
  return dir.write("column.yaml", R"(name: column
parameters: {P: pi^2}
load: {factor: 0.4}
solver:
  analysis: static
  static: {method: arc_length, arc_length: {initial: 0.02, max: 0.02}}
mesh: {file: )" + source_path("meshes/cantilever.geo") + R"(, elements: 16}
beams:
  - {name: column, group: beam, section: {EA: 1.0e6, GA: 1.0e6, EI: 1.0, rhoA: 1.0, rhoI: 1.0e-3}}
joints:
  - {name: clamp, type: fixed, body1: root}
forces:
  - {name: thrust, type: force, body: tip, value: [-P, 0]}
sensors:
  - {name: tip_uy, type: point_displacement, body: tip, component: y}
)");
}

TEST(ArcLength, ColumnReportsABifurcationCandidateAtTheEulerLoad) {
  TestOutputDir dir("arc_length_column");
  const std::string file = column_scene(dir);
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  opt.keep_history = true;
  std::vector<double> mids;
  for (const char* dense : {"150", "0"}) {  // the dense LU's determinant, then MUMPS' (ICNTL(33))
    PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsSetValue(nullptr, "-af_dense_lu", dense));
    Scene s = read_scene(file, {});
    const RunSummary r = run_simulation(s, opt, PETSC_COMM_WORLD);
    PetscCallAbort(PETSC_COMM_WORLD, PetscOptionsClearValue(nullptr, "-af_dense_lu"));
    EXPECT_EQ(r.mumps.dense, std::string(dense) != "0");
    ASSERT_EQ(r.path.critical_points.size(), 1u) << "-af_dense_lu " << dense;
    const CriticalPoint& cp = r.path.critical_points[0];
    EXPECT_EQ(cp.kind, CriticalPoint::Kind::Bifurcation);
    EXPECT_LE(cp.lower, 0.25 * 1.001);
    EXPECT_GE(cp.upper, 0.25 * 0.999);
    EXPECT_LE(cp.upper - cp.lower, 0.021);
    EXPECT_LT(std::fabs(r.final_sensors[0]), 1e-9);  // still straight
    mids.push_back(cp.load_factor);
  }
  // The same bracket from both determinants: its midpoint agrees to the round-off of the path's
  // Newton solutions (the two LU factorizations differ in their last bits: 6 ulp measured); another
  // bracket would move it by a bisection step, ≥ 1e-4 here.
  EXPECT_NEAR(mids[0], mids[1], 1e-13);
}

TEST(ArcLength, KeysThatMakeNoSenseAreNamed) {
  const std::string a = input_error_of([] { run_scene("beam_elastica_2d", {"solver.static.arc_length.initial=0.1"}); });
  EXPECT_NE(a.find("solver.static.arc_length"), std::string::npos) << a;
  EXPECT_NE(a.find("method: arc_length"), std::string::npos) << a;
  const std::string b = input_error_of([] {
    run_scene("beam_elastica_2d", {"solver.static.method=arc_length", "solver.static.arc_length.initial=2",
                                   "solver.static.arc_length.max=1"});
  });
  EXPECT_NE(b.find("min ≤ initial ≤ max"), std::string::npos) << b;
  const std::string c = input_error_of([] {
    run_scene("beam_elastica_2d", {"solver.analysis=dynamic", "solver.static.method=arc_length"});
  });
  EXPECT_NE(c.find("solver.static.method"), std::string::npos) << c;
}

}  // namespace
}  // namespace alphaflex
