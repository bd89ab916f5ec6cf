// Geometrically nonlinear shell benchmarks of Sze, Liu & Lo (2004, Finite Elem. Anal. Des. 40:
// 1551–1569) on the paper's meshes: load–deflection paths against the paper's ABAQUS S4R tables
// (tests/reference/sze_*.csv, sources in their headers), within 2 % of the path's largest value at
// every tabulated load level; the roll-up against the exact circle, converging at second order in
// the element size. Charts: docs/benchmarks/shells.md (scripts/shell_benchmarks.py).
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::column;
using testing::fitted_slope;
using testing::read_csv;
using testing::run_scene;
using testing::source_path;

/// max over the table's load levels of |ours − ref| / max |ref|, for each sensor; the load steps
/// of the scene fall on the table's load levels (checked).
std::vector<double> path_errors(const RunSummary& r, const std::string& table, const std::vector<std::string>& sensors) {
  const auto ref = read_csv(source_path("tests/reference/" + table));
  const std::vector<double>& lf = ref.at("load_fraction");
  std::vector<double> out;
  for (const std::string& s : sensors) {
    double scale = 0.0, worst = 0.0;
    for (double v : ref.at(s)) scale = std::max(scale, std::fabs(v));
    for (size_t k = 0; k < lf.size(); ++k) {
      size_t step = 0;
      while (step < r.times_out.size() && std::fabs(r.times_out[step] - lf[k]) > 1e-9) ++step;
      EXPECT_LT(step, r.times_out.size()) << "no load step at load fraction " << lf[k];
      if (step == r.times_out.size()) continue;
      worst = std::max(worst, std::fabs(r.sensor_history[step][column(r, s)] - ref.at(s)[k]));
    }
    out.push_back(worst / scale);
    std::printf("[ Sze 2004 ] %s %s: path error %.2f %% of max |ref|, final %.4f (S4R %.3f)\n", table.c_str(), s.c_str(),
                100 * out.back(), r.final_sensors[column(r, s)], ref.at(s).back());
  }
  return out;
}

// Sec. 3.1, 16 × 1: tip displacements under the end shear force.
TEST(SzeShellBenchmarks, CantileverStripUnderEndShearFollowsThePublishedPath) {
  const RunSummary r = run_scene("shell_cantilever_shear", {});
  for (double e : path_errors(r, "sze_cantilever_shear.csv", {"tip_u", "tip_w"})) EXPECT_LT(e, 0.02);
}

// Sec. 3.3, 10 × 80: deflections at A and B of the lifted edge.
TEST(SzeShellBenchmarks, SlitAnnularPlateFollowsThePublishedPath) {
  const RunSummary r = run_scene("slit_annular_plate", {});
  for (double e : path_errors(r, "sze_slit_annular_plate.csv", {"wA", "wB"})) EXPECT_LT(e, 0.02);
}

// Sec. 3.4, 16 × 16 quarter: radial displacements of the pushed and the pulled point.
TEST(SzeShellBenchmarks, HemisphereWithHoleFollowsThePublishedPath) {
  const RunSummary r = run_scene("hemisphere_hole", {});
  for (double e : path_errors(r, "sze_hemisphere.csv", {"uA", "vB"})) EXPECT_LT(e, 0.02);
}

// Sec. 3.2: under M = 2π EI/L the exact tip returns to the root (u = −L, w = 0). The linear
// director interpolation represents a turn φ per element with curvature 2 sin(φ/2)/L_e instead of
// φ/L_e, so the tip overshoots by O(φ²) (docs/theory/shell.md): the differences between successive
// meshes must fall like h², and the finest mesh must be within the model's own distance from the
// circle (Green–Lagrange strains of a finite thickness: O((tκ)²) ≈ 3e-3). On the paper's 16 × 1
// mesh the tip is 2.8 % of L from the root (the paper's S4R: 0.0 %), documented as a shortfall.
TEST(SzeShellBenchmarks, RollUpConvergesToTheCircleWithOrderTwo) {
  const double L = 12.0;
  std::vector<double> h, diff;
  std::vector<Eigen::Vector2d> tip;
  for (int n : {16, 32, 64}) {
    const RunSummary r = run_scene("shell_rollup", {"mesh.parameters.nx=" + std::to_string(n)});
    tip.emplace_back(r.final_sensors[column(r, "tip_u")], r.final_sensors[column(r, "tip_w")]);
    std::printf("[ roll-up  ] %d x 1: tip distance from the root %.3e L (%ld Newton iterations)\n", n,
                (tip.back() - Eigen::Vector2d(-L, 0)).norm() / L, r.newton_total);
    if (tip.size() > 1) {
      h.push_back(1.0 / n);
      diff.push_back((tip[tip.size() - 1] - tip[tip.size() - 2]).norm());
    }
  }
  const double ratio = diff[0] / diff[1], order = std::log2(ratio);
  std::printf("[ roll-up  ] successive differences %.3e, %.3e: order %.2f\n", diff[0], diff[1], order);
  EXPECT_NEAR(order, 2.0, 0.25);
  EXPECT_LT((tip.back() - Eigen::Vector2d(-L, 0)).norm() / L, 3e-3);
}

// Sec. 3.2 with `director_interpolation: geodesic` (docs/theory/shell.md): the bending strains see
// the arc φ between the nodes' directors, so the constant curvature of the circle is exact and the
// roll-up closes on the paper's 16 × 1 mesh, as the paper's S4R does (tip u = −L, w = 0): within the
// model's own distance from the circle, O((tκ)²) ≈ 3e-3 L (as above), against 2.8e-2 L with linear
// directors. Measured: 4.6e-4 L, 241 Newton iterations (linear: 243).
TEST(SzeShellBenchmarks, GeodesicRollUpClosesTheCircleOnThePapersMesh) {
  const double L = 12.0;
  const RunSummary r = run_scene("shell_rollup", {"shells.0.director_interpolation=geodesic"});
  const Eigen::Vector2d tip(r.final_sensors[column(r, "tip_u")], r.final_sensors[column(r, "tip_w")]);
  std::printf("[ roll-up  ] geodesic, 16 x 1: tip distance from the root %.3e L (%ld Newton iterations)\n",
              (tip - Eigen::Vector2d(-L, 0)).norm() / L, r.newton_total);
  EXPECT_LT((tip - Eigen::Vector2d(-L, 0)).norm() / L, 3e-3);
  for (double e : path_errors(r, "sze_rollup.csv", {"tip_u", "tip_w"})) EXPECT_LT(e, 0.02);
}

// Sec. 3.1, 3.2 and 3.4 with geodesic directors and `membrane_edges: arc` (docs/theory/shell.md,
// "Arc membrane edges"): the edges measured along the arcs that the directors define. The roll-up
// still closes on the paper's 16 × 1 mesh (within the model's own O((tκ)²) ≈ 3e-3 L of the circle,
// as above) and every path stays within the suite's 2 % of S4R. Measured: the tip 4.6e-4 L from the
// root; path errors cantilever 0.03 / 0.04 %, roll-up 0.08 / 0.19 %, hemisphere 0.87 / 1.24 %
// (geodesic with chords: 1.71 / 1.16 %); the slit plate (0.72 / 0.56 %, unchanged from the chords)
// is left out here for its run time.
TEST(SzeShellBenchmarks, GeodesicDirectorsWithArcEdgesFollowThePublishedPaths) {
  const std::vector<std::string> arc = {"shells.0.director_interpolation=geodesic", "shells.0.membrane_edges=arc"};
  const double L = 12.0;
  const RunSummary roll = run_scene("shell_rollup", arc);
  const Eigen::Vector2d tip(roll.final_sensors[column(roll, "tip_u")], roll.final_sensors[column(roll, "tip_w")]);
  std::printf("[ roll-up  ] geodesic + arc, 16 x 1: tip distance from the root %.3e L (%ld Newton iterations)\n",
              (tip - Eigen::Vector2d(-L, 0)).norm() / L, roll.newton_total);
  EXPECT_LT((tip - Eigen::Vector2d(-L, 0)).norm() / L, 3e-3);
  for (double e : path_errors(roll, "sze_rollup.csv", {"tip_u", "tip_w"})) EXPECT_LT(e, 0.02);
  const RunSummary shear = run_scene("shell_cantilever_shear", arc);
  for (double e : path_errors(shear, "sze_cantilever_shear.csv", {"tip_u", "tip_w"})) EXPECT_LT(e, 0.02);
  const RunSummary hemi = run_scene("hemisphere_hole", arc);
  for (double e : path_errors(hemi, "sze_hemisphere.csv", {"uA", "vB"})) EXPECT_LT(e, 0.02);
}

}  // namespace
}  // namespace alphaflex
