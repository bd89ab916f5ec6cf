// Validation of the modal analysis (src/modal, app/modal_run) against closed forms; every
// reference value states its source. Small models, a few seconds in all.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cmath>
#include <string>
#include <vector>

#include "alphaflex/app/modal_run.hpp"
#include "alphaflex/app/simulation.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/io/scene_modes.hpp"
#include "test_support.hpp"

namespace {

using alphaflex::Mode;
using alphaflex::ModeKind;
using alphaflex::ModalRunOptions;
using alphaflex::ModalRunSummary;

constexpr double kPi = 3.141592653589793;
const std::string kCantilever = std::string(ALPHAFLEX_SOURCE_DIR) + "/tests/modal/cantilever_modes.yaml";

ModalRunSummary modes_of(alphaflex::Scene& scene, int count, MPI_Comm comm = PETSC_COMM_WORLD) {
  ModalRunOptions opt;
  opt.write_results = false;
  opt.modes.count = count;
  return alphaflex::run_modes(scene, opt, comm);
}

/// The family of a cantilever mode from its shape (beam along x, section axes 2 = y, 3 = z):
/// 'a' axial, 'y'/'z' bending, 't' torsion (no translation, rotation about x).
char family(const Mode& m, int nodes) {
  double t[3] = {0, 0, 0}, rx = 0.0;
  for (int k = 0; k < nodes; ++k) {
    for (int d = 0; d < 3; ++d) t[d] += m.shape_re[6 * k + d] * m.shape_re[6 * k + d];
    rx += m.shape_re[6 * k + 3] * m.shape_re[6 * k + 3];
  }
  const double tt = t[0] + t[1] + t[2];
  if (tt < 1e-12 * rx) return 't';
  if (t[0] > 0.999 * tt) return 'a';
  if (t[1] > 0.999 * tt) return 'y';
  if (t[2] > 0.999 * tt) return 'z';
  return '?';
}

// Cantilever (clamped-free) frequencies against the closed forms:
//  bending (Euler–Bernoulli), ω_k = (β_k L)² √(EI/(ρA L⁴)), β_1 L = 1.875104068711961,
//    β_2 L = 4.694091132974175 (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-1);
//  torsion and extension (uniform bar, fixed-free), ω_k = (2k − 1)π/(2L) √(GJ/ρI_p) and
//    √(EA/ρA) (Blevins, Table 8-16), ρI_p = ρI2 + ρI3;
// on 4, 8 and 16 elements, with the order of convergence fitted to the errors.
TEST(ModalCantilever, FrequenciesConvergeToClosedForms) {
  const double EI3 = 1.0, EI2 = 4.0, GJ = 4.0e-5, EA = 400.0, rhoA = 1.0, rhoIp = 2.0e-7, L = 1.0;
  const double b1 = 1.875104068711961, b2 = 4.694091132974175;
  struct Ref {
    const char* what;
    char fam;
    int k;  // k-th mode of its family
    double omega;
  };
  const std::vector<Ref> refs = {
      {"bending y 1", 'y', 1, b1 * b1 * std::sqrt(EI3 / rhoA)}, {"bending y 2", 'y', 2, b2 * b2 * std::sqrt(EI3 / rhoA)},
      {"bending z 1", 'z', 1, b1 * b1 * std::sqrt(EI2 / rhoA)}, {"bending z 2", 'z', 2, b2 * b2 * std::sqrt(EI2 / rhoA)},
      {"torsion 1", 't', 1, kPi / (2 * L) * std::sqrt(GJ / rhoIp)}, {"torsion 2", 't', 2, 3 * kPi / (2 * L) * std::sqrt(GJ / rhoIp)},
      {"axial 1", 'a', 1, kPi / (2 * L) * std::sqrt(EA / rhoA)}};
  std::vector<double> hs;
  std::vector<std::vector<double>> errors(refs.size());
  for (int n : {4, 8, 16}) {
    alphaflex::Scene scene = alphaflex::read_scene(kCantilever, {"parameters.n=" + std::to_string(n)}, PETSC_COMM_SELF);
    const ModalRunSummary s = modes_of(scene, 14, PETSC_COMM_SELF);
    ASSERT_EQ(s.result.rigid_body_modes, 0);
    ASSERT_FALSE(s.result.damped);
    for (size_t r = 0; r < refs.size(); ++r) {
      int seen = 0;
      double omega = -1.0;
      for (const Mode& m : s.result.modes)
        if (family(m, n + 1) == refs[r].fam && ++seen == refs[r].k) {
          omega = 2 * kPi * m.frequency;
          break;
        }
      ASSERT_GT(omega, 0.0) << refs[r].what << " not among the 14 lowest modes on " << n << " elements";
      const double err = std::fabs(omega - refs[r].omega) / refs[r].omega;
      std::printf("cantilever n = %2d: %-12s omega %.8f rad/s, exact %.8f, error %.3e\n", n, refs[r].what, omega,
                  refs[r].omega, err);
      errors[r].push_back(err);
    }
    hs.push_back(L / n);
  }
  for (size_t r = 0; r < refs.size(); ++r) {
    const double order = alphaflex::testing::fitted_slope(hs, errors[r]);
    std::printf("cantilever %-12s: error %.3e on 16 elements, fitted order %.3f\n", refs[r].what, errors[r].back(), order);
    // Consistent mass, linear interpolation: order 2 in h (docs/theory/beam.md).
    EXPECT_NEAR(order, 2.0, 0.15) << refs[r].what;
    EXPECT_LT(errors[r].back(), 2e-2) << refs[r].what;
  }
}

// modes.below keeps the modes under a frequency; modes.shift finds those nearest a frequency
// (shift-and-invert at (2π shift)²). The reference is the same model's lowest-first solution.
TEST(ModalCantilever, BelowAndShiftSelectModes) {
  alphaflex::Scene scene = alphaflex::read_scene(kCantilever, {"parameters.n=8"}, PETSC_COMM_SELF);
  const ModalRunSummary all = modes_of(scene, 8, PETSC_COMM_SELF);
  ModalRunOptions opt;
  opt.write_results = false;
  opt.modes.count = 8;
  opt.modes.below = 0.5 * (all.result.modes[2].frequency + all.result.modes[3].frequency);
  const ModalRunSummary below = alphaflex::run_modes(scene, opt, PETSC_COMM_SELF);
  ASSERT_EQ(below.result.modes.size(), 3u);
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(below.result.modes[static_cast<size_t>(k)].frequency, all.result.modes[static_cast<size_t>(k)].frequency,
                1e-10 * all.result.modes[static_cast<size_t>(k)].frequency);
  opt.modes = alphaflex::ModalOptions{1, 0.0, all.result.modes[5].frequency * 1.001};
  const ModalRunSummary near = alphaflex::run_modes(scene, opt, PETSC_COMM_SELF);
  ASSERT_EQ(near.result.modes.size(), 1u);
  EXPECT_NEAR(near.result.modes[0].frequency, all.result.modes[5].frequency, 1e-10 * all.result.modes[5].frequency);
}

// About a static equilibrium: a simply supported column under an axial compressive load P (its
// static analysis runs first; the compression enters through the geometric stiffness). Euler–
// Bernoulli with axial load (Blevins, Formulas for Natural Frequency and Mode Shape, Table 8-15
// case 1; Timoshenko, Young & Weaver, Vibration Problems in Engineering, Sec. 5.13):
// ω_1² = (π/L)⁴ EI/ρA · (1 − P/P_cr), P_cr = π² EI/L², here P = P_cr/2 for bending about axis 3
// (EI3 = 1) and P_cr/8 about axis 2 (EI2 = 4). The sine shape normalized to 1: modal mass ρA L/2.
TEST(ModalStatic, CompressedColumnFrequencies) {
  const std::string column = std::string(ALPHAFLEX_SOURCE_DIR) + "/tests/modal/column_modes.yaml";
  const double exact[2] = {kPi * kPi * std::sqrt(0.5), kPi * kPi * 2.0 * std::sqrt(1.0 - 0.125)};
  std::vector<double> hs, e[2];
  for (int n : {4, 8, 16}) {
    alphaflex::Scene scene = alphaflex::read_scene(column, {"parameters.n=" + std::to_string(n)}, PETSC_COMM_SELF);
    const ModalRunSummary s = modes_of(scene, 2, PETSC_COMM_SELF);
    ASSERT_EQ(s.state, "static equilibrium");
    for (int k = 0; k < 2; ++k) {
      const double omega = 2 * kPi * s.result.modes[static_cast<size_t>(k)].frequency;
      e[k].push_back(std::fabs(omega - exact[k]) / exact[k]);
      std::printf("column n = %2d, P = Pcr/%d: omega %.8f rad/s, exact %.8f, error %.3e, modal mass %.5f\n", n,
                  k == 0 ? 2 : 8, omega, exact[k], e[k].back(), s.result.modes[static_cast<size_t>(k)].modal_mass);
    }
    if (n == 16) EXPECT_NEAR(s.result.modes[0].modal_mass, 0.5, 5e-3);  // measured 0.4968
    hs.push_back(1.0 / n);
  }
  for (int k = 0; k < 2; ++k) {
    const double order = alphaflex::testing::fitted_slope(hs, e[k]);
    std::printf("column mode %d: error %.3e on 16 elements, fitted order %.3f\n", k + 1, e[k].back(), order);
    EXPECT_NEAR(order, 2.0, 0.15);
    EXPECT_LT(e[k].back(), 1e-2);  // measured 6.4e-3 (P = Pcr/2) and 5e-3
  }
}

// Cantilever (C-F-F-F) square plate of shells against Leissa, Vibration of Plates, NASA SP-160
// (1969), the cantilever square plate for ν = 0.3: λ = ω a² √(ρh/D) = 3.492, 8.525, 21.43, 27.33,
// 31.11 (Ritz values, upper bounds of a few tenths of a percent). 16 × 16 MITC4 quadrilaterals:
// measured −0.54 %, −0.15 %, +0.16 %, +0.07 %, +0.19 %.
TEST(ModalPlate, CantileverPlateAgainstLeissa) {
  alphaflex::Scene scene =
      alphaflex::read_scene(std::string(ALPHAFLEX_SOURCE_DIR) + "/tests/modal/plate_modes.yaml", {}, PETSC_COMM_SELF);
  const ModalRunSummary s = modes_of(scene, 5, PETSC_COMM_SELF);
  const double E = 1e9, nu = 0.3, h = 0.01, rho = 1000.0, a = 1.0;
  const double D = E * h * h * h / (12.0 * (1.0 - nu * nu));
  const double lambda[5] = {3.492, 8.525, 21.43, 27.33, 31.11};
  ASSERT_EQ(s.result.modes.size(), 5u);
  for (int k = 0; k < 5; ++k) {
    const double exact = lambda[k] / (a * a) * std::sqrt(D / (rho * h)) / (2 * kPi);
    const double f = s.result.modes[static_cast<size_t>(k)].frequency;
    std::printf("cantilever plate mode %d: %.6f Hz, Leissa %.6f Hz, error %+.3e\n", k + 1, f, exact, (f - exact) / exact);
    EXPECT_NEAR(f, exact, 1e-2 * exact);
  }
}

// A closed-loop mechanism (tests/modal/fourbar_modes.yaml): a parallelogram four-bar (crank and
// rocker m, a; coupler m_c, which translates) held at the crank tip by a spring k across the
// motion. Closed form from its energies, T = ½θ̇²a²(2m/3 + m_c), V = ½k a²θ², ω² = k/(2m/3 + m_c)
// (Lagrange's equations, e.g. Meirovitch Sec. 6.2), and against the period of the small
// oscillations of the nonlinear transient run of the same scene (zero crossings of θ − θ₀ over
// 2 s, generalized-α at h = 1 ms: its period error (ωh)²-small, measured 1.1e-5).
TEST(ModalPendulum, ClosedLoopFourBarAgainstTransient) {
  const std::string file = std::string(ALPHAFLEX_SOURCE_DIR) + "/tests/modal/fourbar_modes.yaml";
  // The modes about the equilibrium at rest (w0 = 0: the run's small initial spin would add its
  // centripetal reactions, through K_Φ, at the 1e-9 level).
  alphaflex::Scene scene = alphaflex::read_scene(file, {"parameters.w0=0"}, PETSC_COMM_SELF);
  const ModalRunSummary s = modes_of(scene, 1, PETSC_COMM_SELF);
  ASSERT_EQ(s.result.modes.size(), 1u);
  const double f = s.result.modes[0].frequency, exact = std::sqrt(100.0 / (2.0 * 0.5 / 3.0 + 0.5)) / (2 * kPi);
  EXPECT_NEAR(f, exact, 1e-10 * exact);
  EXPECT_NEAR(s.result.modes[0].modal_mass, 2.0 * 0.5 / 3.0 + 0.5, 1e-10);  // tip A normalized to 1 m

  alphaflex::Scene run_scene = alphaflex::read_scene(file, {}, PETSC_COMM_SELF);
  alphaflex::RunOptions ro;
  ro.write_results = false;
  ro.verbose = false;
  ro.keep_history = true;
  const alphaflex::RunSummary run = alphaflex::run_simulation(run_scene, ro, PETSC_COMM_SELF);
  std::vector<double> crossings;
  for (size_t i = 0; i + 1 < run.times_out.size(); ++i) {
    const double y0 = run.sensor_history[i][0] - kPi / 2, y1 = run.sensor_history[i + 1][0] - kPi / 2;
    if ((y0 < 0.0 && y1 >= 0.0) || (y0 > 0.0 && y1 <= 0.0))
      crossings.push_back(run.times_out[i] - y0 * (run.times_out[i + 1] - run.times_out[i]) / (y1 - y0));
  }
  ASSERT_GE(crossings.size(), 4u);
  const double period = 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  std::printf("four-bar: modal %.10f Hz, closed form %.10f Hz, transient %.10f Hz (difference %.2e)\n", f, exact,
              1.0 / period, (1.0 / period - f) / f);
  EXPECT_NEAR(1.0 / period, f, 1e-4 * f);
}

// Spatial rigid rods on 3D revolute joints about z, hanging under gravity g: closed forms of small
// oscillations (e.g. Meirovitch, Elements of Vibration Analysis, 2nd ed., Sec. 6.2; Goldstein,
// Classical Mechanics, Sec. 6.2), uniform rods of mass m and length l:
//  compound pendulum: ω² = m g (l/2) / (m l²/3) = 3g/(2l);
//  double pendulum (absolute angles): M = m l² [[4/3, 1/2], [1/2, 1/3]], K = m g l [[3/2, 0], [0, 1/2]].
std::string rods(int count) {
  std::string s = R"(
dimension: 3
parameters: {m: 1.5, l: 0.8, Jt: m*l^2/12, Ja: 1.0e-3}
gravity: [0, -9.81, 0]
solver: {h: 1e-3, t_end: 1e-3}
bodies:
  - {name: rod1, type: rigid_body, mass: m, inertia: [Ja, Jt, Jt], orientation: [0, 0, -pi/2], position: [0, -0.5*l, 0]}
)";
  if (count == 2)
    s += "  - {name: rod2, type: rigid_body, mass: m, inertia: [Ja, Jt, Jt], orientation: [0, 0, -pi/2], position: [0, -1.5*l, 0]}\n";
  s += "joints:\n  - {name: hinge1, type: revolute, body1: rod1, body2: ground, location: [0, 0, 0], axis: [0, 0, 1]}\n";
  if (count == 2)
    s += "  - {name: hinge2, type: revolute, body1: rod2, body2: rod1, location: [0, -l, 0], axis: [0, 0, 1]}\n";
  return s;
}

TEST(ModalPendulum, CompoundPendulum) {
  alphaflex::Scene scene = alphaflex::read_scene_text(rods(1), "compound.yaml");
  const ModalRunSummary s = modes_of(scene, 1, PETSC_COMM_SELF);
  ASSERT_EQ(s.result.modes.size(), 1u);
  const double exact = std::sqrt(1.5 * 9.81 / 0.8) / (2 * kPi);
  std::printf("compound pendulum: %.12f Hz, exact %.12f Hz\n", s.result.modes[0].frequency, exact);
  EXPECT_NEAR(s.result.modes[0].frequency, exact, 1e-9 * exact);
  EXPECT_EQ(s.result.modes[0].kind, ModeKind::Elastic);
  // Normalized to a largest translation of 1 m: the centre of mass (the body's node, l/2 from the
  // hinge) moves 1 m and the rod turns 2/l rad: modal mass m + J_c (2/l)² = m (1 + 1/3).
  EXPECT_NEAR(s.result.modes[0].modal_mass, 1.5 * 4.0 / 3.0, 1e-9);
}

TEST(ModalPendulum, DoublePendulum) {
  alphaflex::Scene scene = alphaflex::read_scene_text(rods(2), "double.yaml");
  const ModalRunSummary s = modes_of(scene, 2, PETSC_COMM_SELF);
  ASSERT_EQ(s.result.modes.size(), 2u);
  // det(K − ω²M) = 0 with the matrices above (m, l cancel into g/l): (7/36)x² − (7/6)x + 3/4 = 0,
  // x = ω² l/g = 3 ∓ 6/√7.
  const double g_l = 9.81 / 0.8;
  const double exact[2] = {std::sqrt(g_l * (3.0 - 6.0 / std::sqrt(7.0))) / (2 * kPi),
                           std::sqrt(g_l * (3.0 + 6.0 / std::sqrt(7.0))) / (2 * kPi)};
  for (int k = 0; k < 2; ++k) {
    std::printf("double pendulum mode %d: %.12f Hz, exact %.12f Hz\n", k + 1, s.result.modes[static_cast<size_t>(k)].frequency,
                exact[k]);
    EXPECT_NEAR(s.result.modes[static_cast<size_t>(k)].frequency, exact[k], 1e-9 * exact[k]);
  }
}

// One degree of freedom with a viscous damper (line particle on a spring-damper): s = −ζω_n ±
// iω_n√(1−ζ²), ω_n = √(k/m), ζ = c/(2√(km)) (any vibrations text, e.g. Rao, Mechanical Vibrations,
// Sec. 2.6). m = 2 kg, k = 800 N/m, c = 8 N·s/m: ω_n = 20 rad/s, ζ = 0.1.
TEST(ModalDamped, DampedOscillator) {
  alphaflex::Scene scene = alphaflex::read_scene_text(R"(
solver: {h: 1e-3, t_end: 1e-3}
bodies:
  - {name: slider, type: line_particle, mass: 2, origin: [0, 0], direction: [1, 0], position: [0.5, 0]}
forces:
  - {name: spring, type: spring_damper, body1: slider, body2: ground, stiffness: 800, damping: 8, direction: [1, 0]}
)", "damped.yaml");
  const ModalRunSummary s = modes_of(scene, 1, PETSC_COMM_SELF);
  ASSERT_TRUE(s.result.damped);
  ASSERT_EQ(s.result.modes.size(), 1u);
  const Mode& m = s.result.modes[0];
  std::printf("damped oscillator: f = %.12f Hz, zeta = %.12f\n", m.frequency, m.damping_ratio);
  EXPECT_NEAR(m.natural_frequency, 20.0 / (2 * kPi), 1e-10);
  EXPECT_NEAR(m.frequency, 20.0 * std::sqrt(1.0 - 0.01) / (2 * kPi), 1e-10);
  EXPECT_NEAR(m.damping_ratio, 0.1, 1e-10);
  EXPECT_NEAR(m.modal_mass, 2.0, 1e-12);
}

// A spinning symmetric rigid body (J = diag(Jt, Jt, Jp), spin Ω about its axis) on a spherical
// joint at its centre of mass, no load: the gyroscopic problem of the Lie-group linearization
// (C + M G, docs/theory/modes.md). Euler's equations of the torque-free symmetric top (Goldstein,
// Classical Mechanics, 3rd ed., Sec. 5.6): in the body frame the angular velocity precesses about
// the axis at λ = (Jp − Jt)/Jt · Ω, in the sense of the spin when Jp > Jt (forward whirl), and a tilt
// fixed in space turns at −Ω (backward whirl); turning about the axis itself is a rigid-body mode.
// Jp/Jt = 1.5, Ω = 20 rad/s: λ = 10 rad/s.
TEST(ModalDamped, SpinningRotorWhirl) {
  alphaflex::Scene scene = alphaflex::read_scene_text(R"(
dimension: 3
solver: {h: 1e-3, t_end: 1e-3}
bodies:
  - {name: rotor, type: rigid_body, mass: 2, inertia: [0.1, 0.1, 0.15], position: [0, 0, 0], angular_velocity: [0, 0, 20]}
joints:
  - {name: pivot, type: spherical, body1: rotor, body2: ground, location: [0, 0, 0]}
)", "rotor.yaml");
  const ModalRunSummary s = modes_of(scene, 3, PETSC_COMM_SELF);
  ASSERT_TRUE(s.result.damped);
  ASSERT_EQ(s.result.modes.size(), 3u);
  EXPECT_EQ(s.result.rigid_body_modes, 1);
  EXPECT_EQ(s.result.modes[0].kind, ModeKind::RigidBody);
  const Mode &nutation = s.result.modes[1], &tilt = s.result.modes[2];
  std::printf("spinning rotor: %.12f Hz (%s), %.12f Hz (%s); exact %.12f, %.12f Hz\n", nutation.frequency,
              nutation.whirl.c_str(), tilt.frequency, tilt.whirl.c_str(), 10.0 / (2 * kPi), 20.0 / (2 * kPi));
  // Relative 1e-9, as the pendulums (measured 1.6e-10 and 3.3e-10: the Jordan block of the spin
  // mode at 0 costs the Krylov solver a few digits).
  EXPECT_NEAR(nutation.frequency, 10.0 / (2 * kPi), 1e-9 * 10.0 / (2 * kPi));
  EXPECT_NEAR(tilt.frequency, 20.0 / (2 * kPi), 1e-9 * 20.0 / (2 * kPi));
  EXPECT_NEAR(nutation.damping_ratio, 0.0, 1e-9);
  EXPECT_EQ(nutation.whirl, "forward");
  EXPECT_EQ(tilt.whirl, "backward");
}

/// Runs `f`, which must throw an InputError whose message contains `text`.
template <class F>
void expect_input_error(F f, const std::string& text) {
  try {
    f();
    ADD_FAILURE() << "no error; expected one with: " << text;
  } catch (const alphaflex::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
  }
}

// Errors: more modes than degrees of freedom; a coordinate nothing holds.
TEST(ModalErrors, TooManyModesAndFreeMasslessCoordinates) {
  alphaflex::Scene scene = alphaflex::read_scene_text(rods(1), "compound.yaml");
  expect_input_error([&] { modes_of(scene, 2, PETSC_COMM_SELF); },
                     "modes.count = 2: the model has only 1 degrees of freedom");
  alphaflex::Scene loose = alphaflex::read_scene_text(R"(
solver: {h: 1e-3, t_end: 1e-3}
bodies:
  - {name: slider, type: line_particle, mass: 2, origin: [0, 0], direction: [1, 0], position: [0.5, 0]}
  - {name: ghost, type: particle, position: [0, 1]}
forces:
  - {name: spring, type: spring_damper, body1: slider, body2: ground, stiffness: 800, direction: [1, 0]}
)", "loose.yaml");
  // Through `alphaflex modes` the consistent start names the coordinate first …
  expect_input_error([&] { modes_of(loose, 1, PETSC_COMM_SELF); }, "body 'ghost' (x) has no mass and no joint fixes it");
  // … and the modal analysis itself refuses it at any state (a checkpoint, a static state).
  alphaflex::Subdomain sub(*loose.model, PETSC_COMM_SELF);
  alphaflex::SaddlePointSystem system(sub);
  expect_input_error(
      [&] { alphaflex::compute_modes(system, sub.model().initial_state(), 1.0, alphaflex::ModalOptions{1, 0.0, 0.0}); },
      "neither mass nor stiffness nor a joint (ghost.x, ghost.y)");
}

// Free-free: a beam with no joint has six rigid-body modes, reported at zero frequency and counted,
// then the first bending pair at (β L)² √(EI/(ρA L⁴)) with β L = 4.730040744862704 (Blevins,
// Table 8-1, free-free).
TEST(ModalCantilever, FreeFreeBeamHasSixRigidBodyModes) {
  alphaflex::Scene scene =
      alphaflex::read_scene(kCantilever, {"parameters.n=16", "joints=[]"}, PETSC_COMM_SELF);
  const ModalRunSummary s = modes_of(scene, 8, PETSC_COMM_SELF);
  EXPECT_EQ(s.result.rigid_body_modes, 6);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(s.result.modes[static_cast<size_t>(k)].kind, ModeKind::RigidBody);
  const double exact = std::pow(4.730040744862704, 2) / (2 * kPi);  // EI3 = ρA = L = 1
  const double f7 = s.result.modes[6].frequency;
  std::printf("free-free beam, 16 elements: first bending %.8f Hz, exact %.8f Hz (error %.2e)\n", f7, exact,
              (f7 - exact) / exact);
  // Discretization error of order 2 as for the cantilever (its second bending mode, β L = 4.69,
  // is off by 9.6e-3 on 16 elements); measured 6.0e-3.
  EXPECT_NEAR(f7, exact, 8e-3 * exact);
  EXPECT_GT(f7, exact);  // consistent mass, conforming stiffness: from above
}

// 1 and 2 ranks: under mpirun -np 2 the whole communicator solves the cantilever, the double
// pendulum and the compressed column (about its static equilibrium); each rank solves them alone
// too; frequencies agree to 1e-8 relative.
TEST(ModalRanks, OneAndTwoRanksAgree) {
  const std::string column = std::string(ALPHAFLEX_SOURCE_DIR) + "/tests/modal/column_modes.yaml";
  const char* names[3] = {"cantilever", "double pendulum", "compressed column (static state)"};
  for (int which = 0; which < 3; ++which) {
    auto read = [&](MPI_Comm comm) {
      return which == 0   ? alphaflex::read_scene(kCantilever, {"parameters.n=8"}, comm)
             : which == 1 ? alphaflex::read_scene_text(rods(2), "double.yaml")
                          : alphaflex::read_scene(column, {"parameters.n=8"}, comm);
    };
    alphaflex::Scene world = read(PETSC_COMM_WORLD), self = read(PETSC_COMM_SELF);
    const int count = which == 1 ? 2 : 6;
    const ModalRunSummary a = modes_of(world, count, PETSC_COMM_WORLD), b = modes_of(self, count, PETSC_COMM_SELF);
    ASSERT_EQ(a.result.modes.size(), b.result.modes.size());
    for (size_t k = 0; k < a.result.modes.size(); ++k) {
      const double fa = a.result.modes[k].frequency, fb = b.result.modes[k].frequency;
      EXPECT_NEAR(fa, fb, 1e-8 * fb) << "mode " << k + 1 << " on " << a.ranks << " ranks";
      EXPECT_NEAR(a.result.modes[k].modal_mass, b.result.modes[k].modal_mass, 1e-6 * b.result.modes[k].modal_mass);
    }
    int rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
    if (rank == 0) std::printf("%s: %d modes agree on %d and 1 ranks\n", names[which], count, a.ranks);
  }
}

}  // namespace
