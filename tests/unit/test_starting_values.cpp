// The start of a run and Newton's stopping rule (docs/theory/starting_values.md): the corrected
// starting value of the auxiliary vector (Arnold, Brüls & Cardona 2015), the mass-weighted
// projection of the consistent start, and the convergence test on per-coordinate scales, which a
// shift of the scene by 10 km leaves as it is.
#include <algorithm>
#include <cmath>
#include <regex>

#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Runs the scene text `text` (written to `dir`) with overrides, every step's sensors kept.
RunSummary run_written_scene(const TestOutputDir& dir, const std::string& name, const std::string& text,
                    const std::vector<std::string>& overrides, std::function<void(const MechanicalState&)> on_step = {}) {
  Scene s = read_scene(dir.write(name + ".yaml", text), overrides);
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  opt.keep_history = true;
  opt.on_step = std::move(on_step);
  return run_simulation(s, opt, PETSC_COMM_WORLD);
}

// The start-up transient of the multipliers on quick_return (ρ∞ = 0.8), against a reference run of the
// same scene at h = 3.125e-5 (standard start; its own start-up error is (1/32)² of a run at 1e-3 and
// damped by ρ∞^32 per coarse step). Errors: the largest over the four reactions (slot_fx, slot_fy,
// O_fx, O_fy; ~66 N) at every coarse step, over the first 0.05 s and over (0.05, 0.2] s; and the
// transient itself, the largest second difference e_{n+1} − 2e_n + e_{n−1} of the error over the first
// 0.05 s (the smooth O(h²) error changes by O(h⁴) from step to step there, the parasitic modes of the
// start by a factor (ζ − 1)² of their size). What was measured (docs/theory/starting_values.md §1 and
// §5, also at ρ∞ = 0.5 and 0.95):
//  - standard and corrected starts: the first 0.05 s carry 20× the later error (0.155 / 0.151 N at
//    h = 1e-3 against 7.6e-3 N), and it is O(h²)·ρ∞ⁿ: a₀ = q̈₀ + Δ_α h q⃛₀ removes only an O(h) part,
//    which is small here because the mechanism starts at rest (3.7e-3 N at the first step of h = 1e-3);
//  - the smooth start (v₀, a₀, q̈₀ on the smooth expansion of the numerical solution, §5) removes the
//    parasitic transient to O(h³) (transient 1.68e-2 N at h = 1e-3 against 0.247 N, ÷13.3 at 5e-4
//    against ÷3.98), but the first 0.05 s still carry 11× the later error (8.0e-2 against 7.3e-3 N):
//    what remains is the scheme's smooth O(h²) error h²Λ(t), the same function of t at both h
//    (max |e_h(t) − 4e_{h/2}(t)| over the first 0.05 s is 6 % of max |e_h|; standard start 89 %),
//    large while the crank accelerates from rest (Λ ∝ w₂(Φ_qM⁻¹Φ_qᵀ)⁻¹Φ_q q⁽⁴⁾, §5), which no
//    starting value changes.
// Checks: (1) the corrected start is the standard one when Δ_α = α_m − α_f = 0 (ρ∞ = 1), bit for bit;
// (2) with Δ_α ≠ 0 it changes the first step's multipliers by an amount that vanishes with h (checked
// between 1e-4 and 1e-2 N, and falling at least 1.5× when h is halved); (3) the start-up error of
// every start falls like h² (ratio > 3.5 when h is halved); for the standard and corrected starts it is
// more than 10× the later error at h = 1e-3, the corrected start leaving it within 10 %; (4) the smooth
// start's transient is below a tenth of the standard start's at h = 1e-3 and falls more than 6× when h
// is halved (h³: 8; the standard start's by less than 5); (5) its remaining early error is the smooth
// error: max |e_h(t) − 4e_{h/2}(t)| < 0.15 max |e_h| over the first 0.05 s (standard start: > 0.5).
TEST(StartingValues, CorrectedStartOnQuickReturn) {
  const std::vector<std::string> end{"solver.t_end=0.2"};
  auto run = [&](std::vector<std::string> more) {
    more.insert(more.end(), end.begin(), end.end());
    return run_scene("quick_return", more);
  };
  // (1) ρ∞ = 1: nothing to correct.
  const RunSummary s1 = run({"solver.h=1e-3", "solver.rho_inf=1"});
  const RunSummary c1 = run({"solver.h=1e-3", "solver.rho_inf=1", "solver.start=corrected"});
  EXPECT_EQ(s1.final_state.lambda, c1.final_state.lambda);
  // error[h][start] over [0, 0.05 s], later[h][start] over (0.05, 0.2] s, transient[h][start].
  const RunSummary ref = run({"solver.h=3.125e-5"});
  const char* starts[3] = {"standard", "corrected", "smooth"};
  double first_step_change[2] = {0, 0}, error[2][3] = {}, later[2][3] = {}, transient[2][3] = {};
  // series[k][j][sensor]: the error at the first 50 steps' times t = 1e-3 i, i = 1..50.
  std::vector<std::vector<double>> series[2][3];
  for (int k = 0; k < 2; ++k) {
    const double h = k == 0 ? 1e-3 : 5e-4;
    const size_t stride = k == 0 ? 32 : 16, start_steps = k == 0 ? 50 : 100, steps = 4 * start_steps;
    std::vector<RunSummary> runs;
    for (const char* st : starts) runs.push_back(run({"solver.h=" + std::to_string(h), std::string("solver.start=") + st}));
    for (const RunSummary& r : runs) ASSERT_EQ(r.sensor_history.size(), steps + 1);
    for (const char* n : {"slot_fx", "slot_fy", "O_fx", "O_fy"}) {
      const size_t c = column(ref, n);
      first_step_change[k] =
          std::max(first_step_change[k], std::fabs(runs[1].sensor_history[1][c] - runs[0].sensor_history[1][c]));
      for (int j = 0; j < 3; ++j) {
        std::vector<double> e(steps + 1, 0.0);
        for (size_t i = 1; i <= steps; ++i) {
          EXPECT_NEAR(runs[j].times_out[i], ref.times_out[stride * i], 1e-12);
          e[i] = runs[j].sensor_history[i][c] - ref.sensor_history[stride * i][c];
          double& m = i <= start_steps ? error[k][j] : later[k][j];
          m = std::max(m, std::fabs(e[i]));
        }
        for (size_t i = 2; i < start_steps; ++i)
          transient[k][j] = std::max(transient[k][j], std::fabs(e[i + 1] - 2.0 * e[i] + e[i - 1]));
        std::vector<double> at_ms;
        for (size_t i = 1; i <= 50; ++i) at_ms.push_back(e[i * (k + 1)]);
        series[k][j].push_back(at_ms);
      }
    }
    std::printf("h %.1e: first-step change (corrected) %.3e N\n", h, first_step_change[k]);
    for (int j = 0; j < 3; ++j)
      std::printf("  %-9s multiplier error over [0, 0.05] s %.3e N, over (0.05, 0.2] s %.3e N (ratio %.2f), "
                  "transient %.3e N\n",
                  starts[j], error[k][j], later[k][j], error[k][j] / later[k][j], transient[k][j]);
  }
  double smooth_part[3] = {0, 0, 0};  // max |e_h(t) − 4e_{h/2}(t)| / max |e_h| over the first 0.05 s
  for (int j = 0; j < 3; ++j) {
    for (size_t c = 0; c < 4; ++c)
      for (size_t i = 0; i < 50; ++i)
        smooth_part[j] = std::max(smooth_part[j], std::fabs(series[0][j][c][i] - 4.0 * series[1][j][c][i]));
    smooth_part[j] /= error[0][j];
    std::printf("  %-9s max |e_h(t) - 4 e_h/2(t)| / max |e_h| over [0, 0.05] s: %.3f\n", starts[j], smooth_part[j]);
  }
  EXPECT_GT(first_step_change[0], 1e-4);
  EXPECT_LT(first_step_change[0], 1e-2);
  EXPECT_GT(first_step_change[0] / first_step_change[1], 1.5);
  for (int j = 0; j < 3; ++j) EXPECT_GT(error[0][j] / error[1][j], 3.5) << starts[j];
  for (int j = 0; j < 2; ++j) EXPECT_GT(error[0][j], 10.0 * later[0][j]) << starts[j];
  EXPECT_NEAR(error[0][1] / error[0][0], 1.0, 0.1);
  // (4) The smooth start removes the transient to O(h³).
  EXPECT_LT(transient[0][2], 0.1 * transient[0][0]);
  EXPECT_GT(transient[0][2] / transient[1][2], 6.0);
  EXPECT_LT(transient[0][0] / transient[1][0], 5.0);
  // (5) What remains early is the smooth error h²Λ(t).
  EXPECT_LT(smooth_part[2], 0.15);
  EXPECT_GT(smooth_part[0], 0.5);
}

// The paper's slider-crank with its massless hinge (point 5) placed 1 cm and 2 cm off the crank tip:
// the mass-weighted projection moves the hinge back onto crank and rod, and the bodies (crank, rod,
// slider, mass 4) stay where they were placed, to round-off of their coordinates (the weight of the
// hinge is ε = 1e-12 of the largest mass: the crank moves by ~ε/m of the hinge's 2.2 cm, < 1e-13).
// The minimum-norm projection turns the crank instead (checked, so that the test can fail).
TEST(StartingValues, MassWeightedProjectionMovesTheMasslessPoint) {
  const TestOutputDir dir("mass_projection");
  std::string text = read_text(source_path("inputs/slider_crank.yaml"));
  const std::string hinge = "position: [l1*cos(theta1), l1*sin(theta1)]";
  ASSERT_NE(text.find(hinge), std::string::npos);
  text.replace(text.find(hinge), hinge.size(), "position: [l1*cos(theta1) + 0.01, l1*sin(theta1) - 0.02]");
  auto start_of = [&](const std::string& projection, Eigen::VectorXd& q_start) {
    bool first = true;
    const RunSummary r = run_written_scene(dir, "slider_crank_moved", text,
                                  {"solver.t_end=5e-3", "solver.start_projection=" + projection},
                                  [&](const MechanicalState& st) {
                                    if (first) q_start = st.q;
                                    first = false;
                                  });
    return r.projection;
  };
  Scene placed = read_scene(dir.write("placed.yaml", text));
  const Eigen::VectorXd q0 = placed.model->initial_state().q;
  // Coordinates: crank (x1, y1, θ1), rod (x2, y2, θ2), slider x3, mass x4, hinge (x5, y5).
  ASSERT_EQ(q0.size(), 10);
  Eigen::VectorXd q_mass, q_norm;
  const double moved = start_of("mass", q_mass);
  EXPECT_NEAR(moved, 0.02, 1e-12);  // the hinge's y back to l1 sin θ1 = 0.3
  EXPECT_LT((q_mass.head(8) - q0.head(8)).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_NEAR(q_mass[8], 0.3 * std::cos(M_PI / 2), 1e-13);
  EXPECT_NEAR(q_mass[9], 0.3, 1e-13);
  start_of("minimum-norm", q_norm);
  EXPECT_GT(std::fabs(q_norm[2] - q0[2]), 1e-3);  // θ1: the crank turned
}

// Newton's test on the scales of the model, not of its coordinates' values: the slider-crank shifted
// by 10 km in x and y takes the same Newton iterations and reaches the same motion (before the
// scales: 2.7 instead of 3.2 iterations per step). Tolerances: at |x| = 1e4 m a position is stored
// to an ulp of 1.8e-12 m (~1e-16 of the offset), and the residual is formed from differences of
// such numbers; over 200 steps the motions part by 4.5e-10 rad in θ1 (measured), so positions
// relative to the offset and angles are compared to 1e-8 (1e-12 of the offset). The index-3
// multipliers resolve only β'·m·εX ≈ 1.5e5 s⁻² · 0.7 kg · 1.8e-12 m ≈ 2e-7 N per step, carried on by
// the motion: measured up to 4.5e-6 N over the run; compared to 2e-5 N (1e-6 of the ~20 N forces).
TEST(NewtonScales, ShiftedSceneTakesTheSameIterations) {
  const TestOutputDir dir("shifted_scene");
  const std::string text = read_text(source_path("inputs/slider_crank.yaml"));
  // Every world position: bodies, the rail's origin, the ground point of joint O.
  std::string shifted = std::regex_replace(text, std::regex(R"(position: \[(.*), ([^,\]]*)\])"),
                                           "position: [($1) + ox, ($2) + oy]");
  shifted = std::regex_replace(shifted, std::regex(R"((origin|point2): \[0, 0\])"), "$1: [ox, oy]");
  shifted = std::regex_replace(shifted, std::regex("parameters:\n"), "parameters:\n  ox: 1.0e4\n  oy: 1.0e4\n");
  const RunSummary at_origin = run_written_scene(dir, "slider_crank", text, {});
  const RunSummary far = run_written_scene(dir, "slider_crank_shifted", shifted, {});
  ASSERT_EQ(far.steps, at_origin.steps);
  std::printf("Newton iterations: %ld at the origin, %ld at 10 km (%d steps)\n", at_origin.newton_total,
              far.newton_total, at_origin.steps);
  EXPECT_EQ(far.newton_total, at_origin.newton_total);
  EXPECT_EQ(far.newton_max, at_origin.newton_max);
  const MechanicalState &a = at_origin.final_state, &b = far.final_state;
  ASSERT_EQ(a.q.size(), b.q.size());
  for (int i : {0, 1, 3, 4, 8, 9}) EXPECT_NEAR(b.q[i] - 1e4, a.q[i], 1e-8) << "coordinate " << i;
  for (int i : {2, 5, 6, 7}) EXPECT_NEAR(b.q[i], a.q[i], 1e-8) << "coordinate " << i;
  EXPECT_LT((a.lambda - b.lambda).cwiseAbs().maxCoeff(), 2e-5);
}

}  // namespace
}  // namespace alphaflex::testing
