// Material damping of beams (`beams: damping: η`, Kelvin–Voigt, docs/theory/beam.md, Material
// damping) in whole runs, 3D and planar: a struck cantilever's free vibration loses energy at every
// output step, its first bending mode decays with the damping ratio ζ = η ω/2, and `damping: 0`
// is the elastic beam bit for bit. The element tangents are tested in test_beam.cpp and
// test_planar_beam.cpp (suites BeamDamping, PlanarBeamDamping).
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "test_scene_runs.hpp"

namespace alphaflex::testing {
namespace {

/// The cantilever of inputs/beam_impulse_damped.yaml (10 m, 10 elements, EI = 1.4e4 N·m²,
/// ρA = 1.2 kg/m; first bending mode ω1 = 1.8751² √(EI/(ρA L⁴)) = 3.80 rad/s, Euler–Bernoulli),
/// struck at its tip by a 0.1 s triangle of 200 N (a tip deflection of ~3 cm: linear), then free.
/// ρ∞ = 1: the scheme adds no damping of its own. `damping` is the text of the beam block's key
/// ("" for none).
std::string cantilever_yaml(int dimension, const std::string& damping, double t_end) {
  std::ostringstream y;
  y << "name: damped_cantilever\ndimension: " << dimension << "\n"
    << "solver: {rho_inf: 1.0, h: 0.005, t_end: " << t_end << "}\n"
    << "mesh: {file: ../meshes/struck_beam.geo, parameters: {L: 10, n: 10}}\n"
    << "beams:\n  - name: beam\n    group: beam\n";
  if (!damping.empty()) y << "    damping: " << damping << "\n";
  if (dimension == 3)
    y << "    orientation: [0, 1, 0]\n"
      << "    section: {EA: 2.8e7, GA2: 1.0e7, GA3: 1.0e7, GJ: 1.4e4, EI2: 1.4e4, EI3: 1.4e4, rhoA: 1.2, rhoI2: 6.0e-4, "
         "rhoI3: 6.0e-4}\n";
  else
    y << "    section: {EA: 2.8e7, GA: 1.0e7, EI: 1.4e4, rhoA: 1.2, rhoI: 6.0e-4}\n";
  y << "joints:\n  - {name: root, type: fixed, body1: p0}\n"
    << "forces:\n  - {name: hit, type: force, body: p10, value: [0, {type: table, t: [0, 0.05, 0.1, 1000], values: [0, "
       "200, 0, 0]}"
    << (dimension == 3 ? ", 0" : "") << "]}\n"
    << "sensors:\n  - {name: tip_y, type: point_displacement, body: p10, component: y}\n"
    << "  - {name: E, type: energy, of: beam, kind: total}\n";
  return y.str();
}

RunSummary run_cantilever(int dimension, const std::string& damping, double t_end) {
  return run_text(cantilever_yaml(dimension, damping, t_end), source_path("inputs/damped_cantilever.yaml"));
}

/// The tip's successive maxima (times and values, parabola through the three samples around each).
void maxima(const RunSummary& r, size_t col, double after, std::vector<double>& t, std::vector<double>& y) {
  for (size_t i = 1; i + 1 < r.times_out.size(); ++i) {
    const double a = r.sensor_history[i - 1][col], b = r.sensor_history[i][col], c = r.sensor_history[i + 1][col];
    if (r.times_out[i] < after || !(b > a && b >= c)) continue;
    const double h = r.times_out[i + 1] - r.times_out[i], den = a - 2.0 * b + c;
    const double s = 0.5 * (a - c) / den;  // vertex offset in steps
    t.push_back(r.times_out[i] + s * h);
    y.push_back(b - 0.25 * (a - c) * s);
  }
}

}  // namespace

// After the blow (t > 0.1 s) nothing works on the beam: its energy falls at every output step
// (dE/dt = −Σ L0 η ε̇ᵀCε̇ ≤ 0; with ρ∞ = 1 the scheme dissipates next to nothing itself: the undamped
// beam keeps its energy to 1e-4). The higher modes die first (ζ grows with ω; ζ2 = 0.24 for mode 2, gone
// by t = 1.5 s), so the tip then swings in mode 1 and the logarithmic decrement of successive
// maxima, δ = ln(y_k/y_{k+1}), gives ζ = δ/√(4π² + δ²); the measured period gives ω_d and
// ω = ω_d/√(1 − ζ²). Expected: ζ = η ω/2 (modal equation of stiffness-proportional damping;
// Clough & Penzien, Dynamics of Structures, §12-5), within 1 % (the time step's period error at
// ω h = 0.019 is 3e-5 and the decay of the trapezoidal rule is exact for a linear system to the
// same order; the residue of mode 2, e^{−0.24·23.8·1.5} = 2e-4 of its amplitude, and the small
// geometric nonlinearity stay well below 1 %).
TEST(BeamDampingRuns, FreeVibrationLosesEnergyAndTheFirstModeDecaysWithZetaEqualEtaOmegaOverTwo) {
  const double eta = 0.02;
  for (int dim : {3, 2}) {
    const RunSummary r = run_cantilever(dim, "0.02", 6.0);
    const size_t E = column(r, "E"), y = column(r, "tip_y");
    int rises = 0, steps = 0;
    for (size_t i = 1; i < r.times_out.size(); ++i) {
      if (r.times_out[i - 1] < 0.1 + 1e-9) continue;
      ++steps;
      if (r.sensor_history[i][E] > r.sensor_history[i - 1][E]) ++rises;
    }
    EXPECT_GT(steps, 1000);
    EXPECT_EQ(rises, 0) << "dimension " << dim;
    std::vector<double> t, a;
    maxima(r, y, 1.5, t, a);
    ASSERT_GE(t.size(), 3u);
    const double periods = static_cast<double>(t.size() - 1);
    const double delta = std::log(a.front() / a.back()) / periods;
    const double zeta = delta / std::sqrt(4.0 * kPi * kPi + delta * delta);
    const double omega = 2.0 * kPi / ((t.back() - t.front()) / periods) / std::sqrt(1.0 - zeta * zeta);
    std::printf("[ damping  ] %dD: first mode omega %.5f rad/s, measured zeta %.6f, eta omega/2 = %.6f (%zu maxima after "
                "1.5 s); energy at 0.1 s %.4e J, at 6 s %.4e J\n",
                dim, omega, zeta, 0.5 * eta * omega, t.size(), r.sensor_history[20][E], r.final_sensors[E]);
    EXPECT_NEAR(zeta, 0.5 * eta * omega, 0.01 * 0.5 * eta * omega) << "dimension " << dim;
    EXPECT_NEAR(omega, 3.7975, 0.01 * 3.7975);  // Euler–Bernoulli 1.8751² √(EI/(ρA L⁴)) = 3.797 rad/s
    // Undamped: the energy after the blow stays (ρ∞ = 1; measured drift 1.9e-5 relative over 0.8 s,
    // the trapezoidal rule on a mildly nonlinear beam), against 88 % lost with damping.
    const RunSummary u = run_cantilever(dim, "", 1.0);
    EXPECT_NEAR(u.final_sensors[E], u.sensor_history[40][E], 1e-4 * u.final_sensors[E]) << "dimension " << dim;
  }
}

// `damping: 0` is the elastic beam: the same history to the last bit (3D and planar).
TEST(BeamDampingRuns, ZeroDampingIsTheElasticBeamBitForBit) {
  for (int dim : {3, 2}) {
    const RunSummary none = run_cantilever(dim, "", 0.3), zero = run_cantilever(dim, "0", 0.3);
    ASSERT_EQ(none.sensor_history.size(), zero.sensor_history.size());
    for (size_t i = 0; i < none.sensor_history.size(); ++i) EXPECT_EQ(none.sensor_history[i], zero.sensor_history[i]);
    const RunSummary damped = run_cantilever(dim, "0.02", 0.3);
    EXPECT_NE(damped.final_sensors, none.final_sensors);
  }
}

TEST(BeamDampingRuns, BadDampingIsRefusedNamingTheKey) {
  for (int dim : {3, 2}) {
    const std::string m = input_error_of([&] { run_cantilever(dim, "-0.01", 0.01); });
    EXPECT_NE(m.find("damping"), std::string::npos) << m;
    EXPECT_NE(m.find("-0.01"), std::string::npos) << m;
  }
  std::string reduced = cantilever_yaml(3, "0.01", 0.01);
  reduced.replace(reduced.find("    orientation"), 0, "    reduction: {modes: 2}\n");
  const std::string m = input_error_of([&] { run_text(reduced, source_path("inputs/damped_cantilever.yaml")); });
  EXPECT_NE(m.find("material damping is for a full-mesh block"), std::string::npos) << m;
}

}  // namespace alphaflex::testing
