// Spatial force elements (elements/spatial_force_elements.hpp) and the expressions with gradients
// they use (core/expression.hpp): r against the hand-written generalized force, K = ∂r/∂δ on the
// group and C = ∂r/∂q̇ against central differences, and the physics against closed forms (a damped
// spring–mass in 3D, a bushing's static stiffness in every direction).
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/joint_coordinate_force.hpp"
#include "alphaflex/elements/spatial_force_elements.hpp"
#include "alphaflex/joints/joint_coordinate.hpp"
#include "test_scene_runs.hpp"

namespace alphaflex::testing {
namespace {

constexpr double kForceRelTol = 1e-6;  // FD vs exact, relative to the matrix norm (FD error ~1e-9 at h = 1e-6)
constexpr int kForceSamples = 8;

/// K and C of `e` at `s` against central differences (on the group for K, h = 1e-6); returns the
/// worst relative discrepancy.
double check_force_tangents(const Element& e, const LocalState& s) {
  const LocalResidual t = element_tangents(e, s);
  const Eigen::MatrixXd K = central_differences_on_frames(element_residual_of(e, s, Wrt::q), s.q, fixed_fd_step(1e-6));
  const Eigen::MatrixXd C = central_differences(element_residual_of(e, s, Wrt::v), s.v, fixed_fd_step(1e-6));
  const double k_err = (t.K - K).norm() / std::max(K.norm(), 1e-300);
  const double c_err = (t.C - C).norm() / std::max(C.norm(), 1e-300);
  EXPECT_LE(k_err, kForceRelTol) << "K exact\n" << t.K << "\nFD\n" << K;
  EXPECT_LE(c_err, kForceRelTol) << "C exact\n" << t.C << "\nFD\n" << C;
  EXPECT_EQ(t.M.norm(), 0.0);
  return std::max(k_err, c_err);
}

LocalState state_with_random_velocity(const Eigen::VectorXd& q, std::mt19937& rng) {
  const int n = static_cast<int>(q.size() / 7 * 6);
  return local_state(q, random_vector(rng, n, -2.0, 2.0), Eigen::VectorXd::Zero(n));
}

std::vector<std::pair<std::string, ScalarForceLaw>> spring_laws() {
  const ExpressionScope scope{{"k3", 250.0}};
  return {{"linear with damping and preload", ScalarForceLaw::linear(300.0, 7.0, 0.8, 25.0)},
          {"expression of elongation, rate and t",
           ScalarForceLaw::expression(std::make_shared<ExpressionFunction>(
                                          "200*elongation + k3*elongation^3 + 5*rate*(1 + elongation^2) + 3*sin(t)",
                                          scope, std::vector<std::string>{"elongation", "rate", "t"}),
                                      0.6)},
          {"table and damping", ScalarForceLaw::table(make_table({-2.0, 0.0, 0.5, 3.0}, {-900.0, 0.0, 100.0, 1500.0}), 4.0, 0.7)}};
}

/// The start of the bad scenes: one body b at (0, 0, 1).
constexpr const char* kBadSceneHead =
    "name: bad\ndimension: 3\nsolver: {h: 0.01, t_end: 0.02}\n"
    "bodies:\n  - {name: b, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0, 0, 1]}\n";

/// Each (tail, expected) of `cases`: the scene head + tail is refused with a message containing
/// `expected` (an InputError, the file named bad.yaml).
void expect_input_errors(const std::string& head, const std::vector<std::pair<std::string, std::string>>& cases) {
  for (const auto& [tail, expected] : cases) {
    SCOPED_TRACE(tail);
    const std::string msg = input_error_of([&, &tail = tail] { read_scene_text(head + tail, "bad.yaml"); });
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
  }
}

}  // namespace

TEST(ExpressionFunction, GradientMatchesCentralDifferencesAndUnknownNamesListTheVariables) {
  const ExpressionScope scope{{"a", 1.5}};
  const std::vector<std::string> vars{"x", "y", "t"};
  for (const char* text : {"a*x^3 - 2*y*x + t", "sin(x)*exp(-y) + atan2(y, x)", "sqrt(x^2 + y^2) + hypot(x, t)",
                           "x^y + log(x) / (1 + t^2)", "max(x, y) - min(x, 2*y) + abs(x - 3)", "-(x - y)^2 / tan(t + 1)"}) {
    SCOPED_TRACE(text);
    const ExpressionFunction f(text, scope, vars);
    const Eigen::Vector3d x(1.3, 0.4, 0.2);
    Eigen::Vector3d g;
    const double v = f.value(x.data(), g.data());
    EXPECT_EQ(v, f.value(x.data()));  // the gradient pass computes the same value
    EXPECT_EQ(v, evaluate_expression(text, {{"a", 1.5}, {"x", 1.3}, {"y", 0.4}, {"t", 0.2}}));
    const Eigen::MatrixXd fd = central_differences(
        [&](const Eigen::VectorXd& p) { return Eigen::VectorXd::Constant(1, f.value(p.data())); }, x, fixed_fd_step(1e-6));
    EXPECT_LE((fd.row(0).transpose() - g).norm(), 1e-8 * std::max(1.0, g.norm())) << g.transpose() << " vs " << fd;
  }
  try {
    ExpressionFunction("k*elongation + c*rate", {{"k", 1.0}}, {"elongation", "rate", "t"});
    FAIL() << "an unknown name was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown name 'c' (the variables here are elongation, rate, t"), std::string::npos)
        << e.what();
  }
}

TEST(SpatialSpringDamper, ResidualIsTheTensionAlongTheLineOfItsPoints) {
  // r_A = [−N e; −s_A × R_Aᵀ(N e)], r_B = [N e; s_B × R_Bᵀ(N e)] with e = (p_B − p_A)/L and
  // N = k (L − L0) + c L̇ + f0, L̇ = e·(ṗ_B − ṗ_A), ṗ = ẋ + R (Ω × s).
  std::mt19937 rng(2001);
  const double k = 300.0, c = 7.0, L0 = 0.8, f0 = 25.0;
  const Eigen::Vector3d sA(0.2, -0.1, 0.3), sB(-0.4, 0.1, 0.05);
  const SpatialSpringDamper spring("s", {0, 1}, marker(0, sA), marker(1, sB), ScalarForceLaw::linear(k, c, L0, f0));
  for (int i = 0; i < kForceSamples; ++i) {
    const Pose<double> A = random_pose(rng), B = random_pose(rng);
    const LocalState s = state_with_random_velocity(stored({A, B}), rng);
    const Eigen::Vector3d pA = A.x + A.R * sA, pB = B.x + B.R * sB;
    const Eigen::Vector3d vA = s.v.segment<3>(0) + A.R * s.v.segment<3>(3).cross(sA);
    const Eigen::Vector3d vB = s.v.segment<3>(6) + B.R * s.v.segment<3>(9).cross(sB);
    const double L = (pB - pA).norm();
    const Eigen::Vector3d e = (pB - pA) / L;
    const double N = k * (L - L0) + c * e.dot(vB - vA) + f0;
    Eigen::VectorXd r(12);
    r << -N * e, -sA.cross(A.R.transpose() * (N * e)), N * e, sB.cross(B.R.transpose() * (N * e));
    const Eigen::VectorXd got = element_residual(spring, s);
    EXPECT_LE((got - r).norm(), 1e-12 * r.norm()) << got.transpose() << "\n" << r.transpose();
    Eigen::VectorXd out;
    spring.output(s, out);
    EXPECT_NEAR(out[0], L, 1e-14);
    EXPECT_NEAR(out[3], N, 1e-11 * std::fabs(N));
  }
}

TEST(SpatialSpringDamper, TangentsMatchFiniteDifferencesOnTheGroup) {
  std::mt19937 rng(2002);
  for (const auto& [label, law] : spring_laws()) {
    double worst = 0.0;
    for (const bool ground : {false, true}) {
      SCOPED_TRACE(label + (ground ? ", to the ground" : ", between two nodes"));
      const SpatialSpringDamper spring("s", ground ? std::vector<int>{0} : std::vector<int>{0, 1},
                                       marker(0, {0.2, -0.1, 0.3}), marker(ground ? -1 : 1, {-0.4, 0.1, 1.05}), law);
      for (int i = 0; i < kForceSamples; ++i) {
        const Eigen::VectorXd q = ground ? stored({random_pose(rng)}) : stored({random_pose(rng), random_pose(rng)});
        LocalState s = state_with_random_velocity(q, rng);
        s.t = uniform(rng, 0.0, 2.0);
        worst = std::max(worst, check_force_tangents(spring, s));
      }
    }
    std::printf("[ FD       ] worst rel. error %.1e  spring_damper, %s\n", worst, label.c_str());
  }
}

TEST(SpatialSpringDamper, RefusesToEvaluateWhereItsPointsCoincide) {
  const SpatialSpringDamper spring("s", {0}, marker(0, Eigen::Vector3d::Zero()), marker(-1, {1.0, 2.0, 3.0}),
                                   ScalarForceLaw::linear(1.0, 0.0, 1.0, 0.0));
  const Eigen::VectorXd q = stored({{Eigen::Vector3d(1.0, 2.0, 3.0), Eigen::Matrix3d::Identity()}});
  LocalResidual out;
  out.reset(6, true);
  try {
    spring.evaluate(local_state(q, Eigen::VectorXd::Zero(6), Eigen::VectorXd::Zero(6)), out, true);
    FAIL() << "no error";
  } catch (const ConfigurationError& e) {
    EXPECT_NE(std::string(e.what()).find("spring_damper 's': its two points coincide"), std::string::npos) << e.what();
  }
}

TEST(Bushing, IsUnloadedWhereItsFramesCoincideAndTangentsMatchFiniteDifferences) {
  std::mt19937 rng(2003);
  Bushing::Matrix6 K, C;
  {
    const Eigen::MatrixXd a = random_vector(rng, 36, -1.0, 1.0).reshaped(6, 6), b = random_vector(rng, 36, -1.0, 1.0).reshaped(6, 6);
    K = 1e3 * a * a.transpose() + 500.0 * Bushing::Matrix6::Identity();
    C = 10.0 * b * b.transpose();
  }
  const Eigen::Vector3d sA(0.1, 0.2, -0.3), wA(0.3, -0.2, 0.5);
  double worst = 0.0;
  for (const bool ground : {false, true}) {
    SCOPED_TRACE(ground ? "to the ground" : "between two nodes");
    for (int i = 0; i < kForceSamples; ++i) {
      const Pose<double> A = random_pose(rng);
      // B's marker: the bushing frame of A at t = 0, seen from B (so ε = 0 there), then B moved.
      const Pose<double> frame{A.x + A.R * sA, A.R * exp_so3<double>(wA)};
      const Pose<double> B0 = random_pose(rng);
      SpatialMarker mb;
      mb.slot = ground ? -1 : 1;
      mb.position = ground ? frame.x : Eigen::Vector3d(B0.R.transpose() * (frame.x - B0.x));
      mb.rotation = ground ? frame.R : Eigen::Matrix3d(B0.R.transpose() * frame.R);
      const Bushing bushing("b", ground ? std::vector<int>{0} : std::vector<int>{0, 1}, marker(0, sA, wA), mb, K, C);
      const Eigen::VectorXd q0 = ground ? stored({A}) : stored({A, B0});
      // ε = 0 where the frames coincide: r = 0 at rest.
      EXPECT_LE(element_residual(bushing, local_state(q0, Eigen::VectorXd::Zero(q0.size() / 7 * 6),
                                                      Eigen::VectorXd::Zero(q0.size() / 7 * 6))).norm(), 1e-10);
      // Then a deflection (up to 0.4 rad, 0.2 m) and random velocities.
      const Eigen::VectorXd d = random_vector(rng, static_cast<int>(q0.size() / 7 * 6), -0.2, 0.2) * (i % 2 ? 2.0 : 1.0);
      const LocalState s = state_with_random_velocity(retracted_frames(q0, d), rng);
      worst = std::max(worst, check_force_tangents(bushing, s));
    }
  }
  std::printf("[ FD       ] worst rel. error %.1e  bushing\n", worst);
}

TEST(Bushing, StaticStiffnessInEveryDirectionMatchesTheClosedForm) {
  // A body held to the ground by a bushing at its centre (bushing frame turned by `orientation`),
  // loaded by a dead force or moment along one axis of the bushing frame. Closed forms:
  //   translation along axis i:  u_i = F / k_i exactly (no coupling with a diagonal K);
  //   rotation about axis i:     M = k_i · 2 tan(φ/2) / cos²(φ/2) (γ = 2 tan(φ/2), M = (∂γ/∂φ) k γ),
  // φ ≈ 0.35 rad here, where the linear estimate M/k would be 3 % off.
  const Eigen::Vector3d w(0.3, -0.4, 0.5);  // bushing frame: world axes turned by exp(w^)
  const Eigen::Matrix3d F = exp_so3<double>(w);
  const double k[6] = {2.0e4, 3.0e4, 5.0e4, 800.0, 1200.0, 1500.0};
  const double load[6] = {150.0, -240.0, 300.0, 300.0, -480.0, 600.0};
  for (int i = 0; i < 6; ++i) {
    SCOPED_TRACE("direction " + std::to_string(i));
    const Eigen::Vector3d dir = F.col(i % 3) * load[i];
    std::ostringstream y;
    y.precision(17);
    y << "name: bushing_static\ndimension: 3\nsolver: {analysis: static, static: {steps: 4}}\n"
      << "bodies:\n  - {name: b, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0.5, -0.2, 1.0]}\n"
      << "forces:\n  - {name: mount, type: bushing, body1: b, orientation: [" << w.x() << ", " << w.y() << ", " << w.z()
      << "], stiffness: [" << k[0] << ", " << k[1] << ", " << k[2] << ", " << k[3] << ", " << k[4] << ", " << k[5] << "]}\n"
      << "  - {name: load, type: " << (i < 3 ? "force" : "moment") << ", body: b, value: [" << dir.x() << ", " << dir.y()
      << ", " << dir.z() << "]}\n"
      << "sensors:\n";
    for (const char* c : {"x", "y", "z"}) {
      y << "  - {name: u" << c << ", type: point_displacement, body: b, component: " << c << "}\n";
      y << "  - {name: r" << c << ", type: body_rotation, body: b, component: " << c << "}\n";
    }
    Scene scene = read_scene_text(y.str(), "bushing_static.yaml");
    RunOptions opt;
    opt.write_results = false;
    opt.verbose = false;
    const RunSummary r = run_simulation(scene, opt, PETSC_COMM_WORLD);
    const Eigen::Vector3d u(final_value(r, "ux"), final_value(r, "uy"), final_value(r, "uz"));
    const Eigen::Vector3d rot(final_value(r, "rx"), final_value(r, "ry"), final_value(r, "rz"));
    if (i < 3) {
      const Eigen::Vector3d expected = F.col(i) * (load[i] / k[i]);
      EXPECT_LE((u - expected).norm(), 1e-9 * expected.norm()) << u.transpose() << " vs " << expected.transpose();
      EXPECT_LE(rot.norm(), 1e-12);
      std::printf("[ closed   ] bushing translation %d: |u − F/k| / |u| = %.1e\n", i, (u - expected).norm() / expected.norm());
    } else {
      const double phi = rot.dot(F.col(i - 3));  // the rotation is about the bushing axis
      EXPECT_LE((rot - phi * F.col(i - 3)).norm(), 1e-10 * std::fabs(phi));
      const double c = std::cos(phi / 2);
      const double moment = k[i] * 2.0 * std::tan(phi / 2) / (c * c);
      EXPECT_LE(std::fabs(moment - load[i]), 1e-9 * std::fabs(load[i])) << "φ = " << phi;
      EXPECT_GT(std::fabs(phi - load[i] / k[i]), 0.01 * std::fabs(phi));  // the linear estimate is not it
      EXPECT_LE(u.norm(), 1e-12);
      std::printf("[ closed   ] bushing rotation %d: φ = %.6f rad, |M(φ) − M| / |M| = %.1e\n", i - 3, phi,
                  std::fabs(moment - load[i]) / std::fabs(load[i]));
    }
  }
}

TEST(SpatialSpringDamper, DampedSpringMassIn3DHasTheClosedFormFrequencyAndLogarithmicDecrement) {
  // A mass m on a spring k with damper c along the oblique line (1, 2, 2)/3 from a ground point,
  // started 0.1 m beyond its rest length: u(t) = A e^(−ζω t) cos(ω_d t + ψ), ω = √(k/m),
  // ζ = c / (2√(km)), ω_d = ω √(1 − ζ²), logarithmic decrement δ = ln(u_n / u_{n+1}) over one period
  // = 2πζ / √(1 − ζ²) (e.g. Thomson & Dahleh, Theory of Vibration, §2.6). ρ∞ = 1 (no numerical
  // damping), h = T/400: the scheme's period error is O((ωh)²) ≈ 1e-4.
  const double m = 2.0, k = 800.0, c = 4.0;
  const double omega = std::sqrt(k / m), zeta = c / (2.0 * std::sqrt(k * m)), omega_d = omega * std::sqrt(1 - zeta * zeta);
  const double delta = 2 * M_PI * zeta / std::sqrt(1 - zeta * zeta), T = 2 * M_PI / omega_d;
  std::ostringstream y;
  y.precision(17);
  y << "name: spring_mass_3d\ndimension: 3\nsolver: {rho_inf: 1.0, h: " << T / 400 << ", t_end: " << 3.2 * T << "}\n"
    << "bodies:\n  - {name: m, type: rigid_body, mass: " << m << ", inertia: [0.1, 0.1, 0.1], position: ["
    << 1.1 / 3 << ", " << 2.2 / 3 << ", " << 2.2 / 3 << "]}\n"
    << "forces:\n  - {name: s, type: spring_damper, body1: m, body2: ground, stiffness: " << k << ", damping: " << c
    << ", rest_length: 1.0}\n"
    << "sensors:\n  - {name: x, type: point_displacement, body: m, component: x}\n";
  Scene scene = read_scene_text(y.str(), "spring_mass_3d.yaml");
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  opt.keep_history = true;
  const RunSummary r = run_simulation(scene, opt, PETSC_COMM_WORLD);
  // u along the line = 3 x − 0.1 … the x displacement is u/3 from 0.1/3.
  std::vector<double> t = r.times_out, u;
  for (const auto& row : r.sensor_history) u.push_back(3.0 * row[0] + 0.1);
  // Peaks: parabola through the three samples around each local maximum.
  std::vector<double> tp, up;
  for (size_t i = 1; i + 1 < u.size(); ++i)
    if (u[i] > u[i - 1] && u[i] >= u[i + 1]) {
      const double a = 0.5 * (u[i + 1] - 2 * u[i] + u[i - 1]), b = 0.5 * (u[i + 1] - u[i - 1]);
      const double s = -b / (2 * a), h = t[i + 1] - t[i];
      tp.push_back(t[i] + s * h);
      up.push_back(u[i] + b * s + a * s * s);
    }
  ASSERT_GE(tp.size(), 3u);
  const double period = (tp[2] - tp[0]) / 2.0, decrement = std::log(up[0] / up[2]) / 2.0;
  const double period_error = std::fabs(period - T) / T, decrement_error = std::fabs(decrement - delta) / delta;
  std::printf("[ closed   ] spring-mass 3D: period %.8f s (closed form %.8f, rel. error %.1e), log. decrement %.6f "
              "(closed form %.6f, rel. error %.1e)\n", period, T, period_error, decrement, delta, decrement_error);
  EXPECT_LE(period_error, 2e-4);
  EXPECT_LE(decrement_error, 2e-3);
}

TEST(ForceElementScenes, BadInputIsRefusedNamingTheKey) {
  const std::string head = std::string(kBadSceneHead) + "forces:\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"  - {name: mount, type: bushing, body1: b, stiffness: [[1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], [0, 0, 1, 0, 0, 0], "
       "[0, 0, 0, 1, 2, 0], [0, 0, 0, 2, 1, 0], [0, 0, 0, 0, 0, 1]]}\n",
       "bad.yaml:7: forces[mount].stiffness: the matrix must be positive semi-definite, but it has the eigenvalue -1"},
      {"  - {name: mount, type: bushing, body1: b, stiffness: [1, 1, 1, 1, 1, 1], damping: [[1, 2, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0], "
       "[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0], [0, 0, 0, 0, 0, 1]]}\n",
       "forces[mount].damping: the matrix must be symmetric"},
      {"  - {name: mount, type: bushing, body1: b, stiffness: [1, 1, 1]}\n",
       "forces[mount].stiffness: expected 6 numbers (the diagonal) or 6 rows of 6 numbers (N/m, N·m/rad)"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 3], stiffness: 10, force: \"elongation\"}\n",
       "forces[s]: give one force law: stiffness, force or table, not several"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 3]}\n",
       "forces[s]: give the force law: stiffness (linear), force (an expression of elongation, rate, t) or table"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 3], force: \"k*elongation\"}\n",
       "forces[s].force: in expression 'k*elongation' at character 1: unknown name 'k' (the variables here are elongation, rate, t"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 1], stiffness: 10}\n",
       "forces[s]: the two points coincide at t = 0"},
      {"  - {name: s, type: spring_damper, body1: b, body2: b, point2: [0, 0, 3], stiffness: 10}\n",
       "forces[s]: both ends are on 'b'"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 3], table: [[0, 0], [0, 1]]}\n",
       "forces[s].table[1]: elongations must increase strictly"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 3], force: \"elongation\", damping: 2}\n",
       "forces[s].damping: the force expression gives the damping through `rate`"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 3], stiffness: 10}\n"
       "sensors:\n  - {name: n, type: force_output, element: spring, component: tension}\n",
       "sensors[n].element: no force element named 'spring' in `forces` (its force elements: s)"},
      {"  - {name: s, type: spring_damper, body1: b, point2: [0, 0, 3], stiffness: 10}\n"
       "sensors:\n  - {name: n, type: force_output, element: s, component: force}\n",
       "sensors[n].component: unknown"},
  };
  expect_input_errors(head, cases);
}

TEST(ForceElementScenes, ForceOutputSensorsReadTheTensionAndTheBushingForce) {
  // A 2 kg mass hanging at rest (static analysis) from a spring (k = 1000 N/m) and, beside it, a
  // 1 kg mass on a bushing (k_z = 500 N/m) under gravity 9.81: tension m g = 19.62 N, elongation
  // m g / k; the bushing's generalized force on u_z is the weight it carries, −9.81 N (u_z = z_B − z_A
  // of the ground's copy relative to body1's, positive when body1 sags).
  const std::string scene =
      "name: hang\ndimension: 3\ngravity: [0, 0, -9.81]\nsolver: {analysis: static, static: {steps: 2}}\n"
      "bodies:\n  - {name: m, type: rigid_body, mass: 2, inertia: [1, 1, 1], position: [0, 0, -1]}\n"
      "  - {name: b, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [3, 0, 0]}\n"
      "joints:\n  - {name: guide, type: prismatic, body1: m, axis: [0, 0, 1]}\n"
      "forces:\n  - {name: s, type: spring_damper, body1: m, point2: [0, 0, 0], stiffness: 1000, rest_length: 1}\n"
      "  - {name: mount, type: bushing, body1: b, stiffness: [1e4, 1e4, 500, 100, 100, 100]}\n"
      "sensors:\n  - {name: N, type: force_output, element: s, component: tension}\n"
      "  - {name: e, type: force_output, element: s, component: elongation}\n"
      "  - {name: fz, type: force_output, element: mount, component: 'force[2]'}\n"
      "  - {name: uz, type: force_output, element: mount, component: 'deflection[2]'}\n";
  Scene s = read_scene_text(scene, "hang.yaml");
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  const RunSummary r = run_simulation(s, opt, PETSC_COMM_WORLD);
  EXPECT_NEAR(final_value(r, "N"), 2 * 9.81, 1e-10);
  EXPECT_NEAR(final_value(r, "e"), 2 * 9.81 / 1000, 1e-13);
  EXPECT_NEAR(final_value(r, "uz"), 9.81 / 500, 1e-13);
  EXPECT_NEAR(final_value(r, "fz"), 9.81, 1e-10);
}

// ============================================================ joint coordinates, springs, motors

namespace {

/// q ∘ exp(d) for the frames (7 numbers, 6 increments each) and ψ (1 and 1, additive) of a link.
Eigen::VectorXd retract_link(const Eigen::VectorXd& q, const Eigen::VectorXd& d) {
  Eigen::VectorXd out = q;
  const Eigen::Index nf = (q.size() - 1) / 7;
  out.head(7 * nf) = retracted_frames(q.head(7 * nf), d.head(6 * nf));
  out[7 * nf] += d[6 * nf];
  return out;
}

/// Central differences of f along the link's increments (h = 1e-6).
Eigen::MatrixXd fd_link(const VectorFunction& f, const Eigen::VectorXd& q) {
  const Eigen::Index n = (q.size() - 1) / 7 * 6 + 1;
  Eigen::MatrixXd J;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, j) * 1e-6;
    const Eigen::VectorXd col = (f(retract_link(q, e)) - f(retract_link(q, -e))) / 2e-6;
    if (j == 0) J.resize(col.size(), n);
    J.col(j) = col;
  }
  return J;
}

/// The link of the tests below: marker A on node 1, B on node 2 or the ground.
JointCoordinateLink test_link(JointCoordinateLink::Coordinate c, bool ground) {
  return JointCoordinateLink("l", ground ? std::vector<int>{0, 1} : std::vector<int>{0, 1, 2},
                             marker(0, {0.2, -0.1, 0.3}, {0.1, 0.4, -0.3}),
                             marker(ground ? -1 : 1, {-0.4, 0.1, 0.05}, {-0.2, 0.3, 0.6}), c);
}

/// Random frames (one, or two) and ψ over many turns.
Eigen::VectorXd random_link_configuration(std::mt19937& rng, bool ground) {
  Eigen::VectorXd q = ground ? stored({random_pose(rng)}) : stored({random_pose(rng), random_pose(rng)});
  q.conservativeResize(q.size() + 1);
  q[q.size() - 1] = uniform(rng, -20.0, 20.0);
  return q;
}

}  // namespace

TEST(JointCoordinateLink, JacobianGeometricStiffnessAndAccelerationTermMatchFiniteDifferences) {
  std::mt19937 rng(2004);
  double worst = 0.0;
  for (const auto c : {JointCoordinateLink::Coordinate::rotation, JointCoordinateLink::Coordinate::translation}) {
    for (const bool ground : {false, true}) {
      SCOPED_TRACE(std::string(c == JointCoordinateLink::Coordinate::rotation ? "rotation" : "translation") +
                   (ground ? ", to the ground" : ", two nodes"));
      const JointCoordinateLink link = test_link(c, ground);
      for (int i = 0; i < kForceSamples; ++i) {
        const Eigen::VectorXd q = random_link_configuration(rng, ground);
        const Eigen::Index n = (q.size() - 1) / 7 * 6 + 1;
        const Eigen::VectorXd v = random_vector(rng, static_cast<int>(n), -2.0, 2.0);
        const double t = 0.3, lambda = uniform(rng, -5.0, 5.0);
        Eigen::VectorXd phi;
        Eigen::MatrixXd phi_q, k;
        link.evaluate(q, t, phi, phi_q);
        const auto phi_of = [&](const Eigen::VectorXd& x) {
          Eigen::VectorXd p;
          Eigen::MatrixXd pq;
          link.evaluate(x, t, p, pq);
          return p;
        };
        const Eigen::MatrixXd fd_q = fd_link(phi_of, q);
        const double e1 = (phi_q - fd_q).norm() / phi_q.norm();
        EXPECT_LE(e1, kForceRelTol) << phi_q << "\n" << fd_q;
        // K_Φ = ∂(Φ_qᵀλ)/∂δ' (the derivative of the gradient at the perturbed configuration).
        link.geometric_stiffness(q, t, Eigen::VectorXd::Constant(1, lambda), k);
        const Eigen::MatrixXd fd_k = fd_link(
            [&](const Eigen::VectorXd& x) {
              Eigen::VectorXd p;
              Eigen::MatrixXd pq;
              link.evaluate(x, t, p, pq);
              return Eigen::VectorXd(lambda * pq.row(0).transpose());
            },
            q);
        const double e2 = (k - fd_k).norm() / std::max(k.norm(), 1e-12);
        EXPECT_LE(e2, kForceRelTol) << k << "\n" << fd_k;
        // (Φ_q v)_q v = d²Φ(q ∘ exp(τ v))/dτ² (scleronomic), by second differences (h = 1e-4).
        Eigen::VectorXd c_term;
        link.acceleration_term(q, v, t, c_term);
        const double h = 1e-4;
        const double fd_c = (phi_of(retract_link(q, h * v))[0] - 2 * phi[0] + phi_of(retract_link(q, -h * v))[0]) / (h * h);
        const double e3 = std::fabs(c_term[0] - fd_c) / std::max(1.0, std::fabs(c_term[0]));
        EXPECT_LE(e3, 1e-5) << c_term[0] << " vs " << fd_c;
        worst = std::max({worst, e1, e2});
      }
    }
  }
  std::printf("[ FD       ] worst rel. error %.1e  joint coordinate link (Φ_q, K_Φ)\n", worst);
}

// The closed forms (joints/joint_coordinate.cpp: Φ_q from the first derivatives of marker axes and
// points, K_Φ by forward AD1 of that closed form) against forward and nested AD of the equation
// (the former implementation): equal to round-off for the four coordinates, to the ground and
// between two nodes, at random frames and many turns of ψ.
TEST(JointCoordinateLink, ClosedFormJacobianAndGeometricStiffnessEqualAutomaticDifferentiation) {
  using C = JointCoordinateLink::Coordinate;
  std::mt19937 rng(2005);
  double worst = 0.0;
  for (const C c : {C::rotation, C::translation, C::universal_axis, C::universal_axis2}) {
    for (const bool ground : {false, true}) {
      SCOPED_TRACE("coordinate " + std::to_string(static_cast<int>(c)) + (ground ? ", to the ground" : ", two nodes"));
      const JointCoordinateLink link = test_link(c, ground);
      for (int i = 0; i < kForceSamples; ++i) {
        const Eigen::VectorXd q = random_link_configuration(rng, ground);
        const Eigen::VectorXd lambda = Eigen::VectorXd::Constant(1, uniform(rng, -5.0, 5.0));
        Eigen::VectorXd phi, phi_ad;
        Eigen::MatrixXd phi_q, phi_q_ad, k, k_ad;
        link.evaluate(q, 0.3, phi, phi_q);
        link.evaluate_by_ad(q, 0.3, phi_ad, phi_q_ad);
        link.geometric_stiffness(q, 0.3, lambda, k);
        link.geometric_stiffness_by_ad(q, 0.3, lambda, k_ad);
        ASSERT_EQ(phi_q.cols(), phi_q_ad.cols());
        ASSERT_EQ(k.rows(), k_ad.rows());
        EXPECT_LE(std::fabs(phi[0] - phi_ad[0]), 1e-15 * (1.0 + std::fabs(phi_ad[0])));
        const double e1 = (phi_q - phi_q_ad).cwiseAbs().maxCoeff() / std::max(1.0, phi_q_ad.cwiseAbs().maxCoeff());
        const double e2 = (k - k_ad).cwiseAbs().maxCoeff() / std::max(1.0, k_ad.cwiseAbs().maxCoeff());
        EXPECT_LE(e1, 1e-14) << phi_q << "\n" << phi_q_ad;
        EXPECT_LE(e2, 1e-14) << k << "\n" << k_ad;
        worst = std::max({worst, e1, e2});
      }
    }
  }
  std::printf("joint coordinate links: closed forms against AD, worst difference %.1e (relative to the largest entry)\n", worst);
}

TEST(JointCoordinateForce, TangentsAreTheLawsDerivativesAndAMotorScalesWithTheLoadFactor) {
  const auto f = std::make_shared<ExpressionFunction>("10*(1 - speed/100) + 2*sin(angle) + t", ExpressionScope{},
                                                      std::vector<std::string>{"angle", "speed", "t"});
  const JointCoordinateForce motor("m", 0, ScalarForceLaw::expression(f, 0.0), JointCoordinateForce::Role::motor);
  const JointCoordinateForce spring("s", 0, ScalarForceLaw::linear(20.0, 0.5, 0.3, 1.0), JointCoordinateForce::Role::spring_damper);
  for (const JointCoordinateForce* e : {&motor, &spring}) {
    LocalState s = local_state(Eigen::VectorXd::Constant(1, 17.3), Eigen::VectorXd::Constant(1, 42.0), Eigen::VectorXd::Zero(1));
    s.t = 0.7;
    s.load_factor = 0.6;
    const LocalResidual t = element_tangents(*e, s);
    EXPECT_LE(std::fabs(t.K(0, 0) - central_differences(element_residual_of(*e, s, Wrt::q), s.q)(0, 0)), 1e-7);
    EXPECT_LE(std::fabs(t.C(0, 0) - central_differences(element_residual_of(*e, s, Wrt::v), s.v)(0, 0)), 1e-7);
  }
  LocalState s = local_state(Eigen::VectorXd::Constant(1, 17.3), Eigen::VectorXd::Constant(1, 42.0), Eigen::VectorXd::Zero(1));
  s.t = 0.7;
  s.load_factor = 0.6;
  EXPECT_NEAR(element_residual(motor, s)[0], -0.6 * (10 * (1 - 0.42) + 2 * std::sin(17.3) + 0.7), 1e-13);
  EXPECT_NEAR(element_residual(spring, s)[0], 20.0 * (17.3 - 0.3) + 0.5 * 42.0 + 1.0, 1e-12);  // not scaled
}

TEST(JointSpringDamper, PendulumOnARotationalSpringHasTheClosedFormSmallOscillationFrequency) {
  // A rod (m = 2 kg, centre 0.5 m below the hinge, J_c = 0.1 kg m²) on a revolute joint with a
  // rotational spring k = 20 N m/rad, under gravity: J_O θ̈ + (k + m g l) θ = 0, J_O = J_c + m l²,
  // ω = √((k + m g l) / J_O) for small θ (amplitude 0.028 rad: the sin θ ≈ θ error of the period is
  // θ₀²/16 ≈ 5e-5). Started with θ̇ = 0.2 rad/s at θ = 0.
  const double m = 2.0, l = 0.5, Jc = 0.1, k = 20.0, g = 9.81;
  const double omega = std::sqrt((k + m * g * l) / (Jc + m * l * l)), T = 2 * M_PI / omega;
  std::ostringstream y;
  y.precision(17);
  y << "name: pendulum_spring\ndimension: 3\ngravity: [0, 0, " << -g << "]\nsolver: {rho_inf: 1.0, h: " << T / 400
    << ", t_end: " << 2.3 * T << "}\n"
    << "bodies:\n  - {name: rod, type: rigid_body, mass: " << m << ", inertia: [" << Jc << ", " << Jc << ", " << Jc
    << "], position: [0, 0, " << -l << "], angular_velocity: [0, 0.2, 0], velocity: [" << -0.2 * l << ", 0, 0]}\n"
    << "joints:\n  - {name: hinge, type: revolute, body1: rod, location: [0, 0, 0], axis: [0, 1, 0]}\n"
    << "forces:\n  - {name: spring, type: joint_spring_damper, joint: hinge, stiffness: " << k << "}\n"
    << "sensors:\n  - {name: angle, type: joint_angle, joint: hinge}\n";
  const RunSummary r = run_text(y.str(), "pendulum_spring.yaml");
  // Zero crossings upward (linear interpolation): one period apart.
  const std::vector<double> up = upward_zero_crossings(r, 0);
  ASSERT_GE(up.size(), 2u);
  const double period = up[1] - up[0], err = std::fabs(period - T) / T;
  std::printf("[ closed   ] pendulum on a rotational spring: period %.7f s, closed form %.7f s, rel. error %.1e\n", period, T, err);
  EXPECT_LE(err, 2e-4);
}

namespace {

// A flywheel (inertia 0.04 kg m² about z) at `position` on a revolute joint `shaft` to the ground,
// driven by a DC motor `dc` (stall torque T_s = 10 N m, no-load speed w0 = 100 rad/s).
std::string flywheel_on_dc_motor(const std::string& name, const std::string& solver, const std::string& position,
                                 const std::string& sensors) {
  return "name: " + name + "\ndimension: 3\nparameters: {T_s: 10, w0: 100}\nsolver: " + solver +
         "\nbodies:\n  - {name: wheel, type: rigid_body, mass: 5, inertia: [0.02, 0.02, 0.04], position: " + position +
         "}\njoints:\n  - {name: shaft, type: revolute, body1: wheel, location: [0, 0, 0], axis: [0, 0, 1]}\n"
         "forces:\n  - {name: dc, type: joint_motor, joint: shaft, torque: \"T_s*(1 - speed/w0)\"}\nsensors:\n" +
         sensors;
}

}  // namespace

TEST(JointMotor, DcMotorSpinsUpAFlywheelAlongTheClosedFormSpeedOverManyTurns) {
  // J ω̇ = T_s (1 − ω/ω₀): ω(t) = ω₀ (1 − e^(−t/τ)), θ(t) = ω₀ (t − τ (1 − e^(−t/τ))), τ = J ω₀ / T_s
  // (J = 0.04 kg m², T_s = 10 N m, ω₀ = 100 rad/s: τ = 0.4 s; θ(1 s) = 63 rad, ten turns: the
  // joint angle is unwrapped). The flywheel spins about z on a revolute joint to the ground.
  const RunSummary r = run_text(flywheel_on_dc_motor("dc_motor", "{rho_inf: 0.9, h: 0.001, t_end: 1.0}", "[0, 0, 0]",
                                                     "  - {name: angle, type: joint_angle, joint: shaft}\n"
                                                     "  - {name: speed, type: joint_speed, joint: shaft}\n"
                                                     "  - {name: torque, type: force_output, element: dc, component: drive}\n"),
                                "dc_motor.yaml");
  const double tau = 0.04 * 100 / 10;
  double worst_w = 0.0, worst_a = 0.0;
  for (size_t i = 0; i < r.times_out.size(); ++i) {
    const double t = r.times_out[i];
    const double w = 100 * (1 - std::exp(-t / tau)), a = 100 * (t - tau * (1 - std::exp(-t / tau)));
    worst_w = std::max(worst_w, std::fabs(r.sensor_history[i][1] - w) / 100);
    worst_a = std::max(worst_a, std::fabs(r.sensor_history[i][0] - a) / std::max(1.0, a));
    EXPECT_NEAR(r.sensor_history[i][2], 10 * (1 - r.sensor_history[i][1] / 100), 1e-9);
  }
  std::printf("[ closed   ] DC motor: max |ω − ω(t)| / ω₀ = %.1e, max |θ − θ(t)| / θ = %.1e, θ(1 s) = %.4f rad (%.2f turns)\n",
              worst_w, worst_a, final_value(r, "angle"), final_value(r, "angle") / (2 * M_PI));
  EXPECT_GT(final_value(r, "angle"), 60.0);
  EXPECT_LE(worst_w, 1e-5);
  EXPECT_LE(worst_a, 1e-5);
}

TEST(JointSpringDamper, ASpringOnAJointWithoutSuchACoordinateIsRefusedByName) {
  const std::string head = std::string(kBadSceneHead) +
      "joints:\n  - {name: ball, type: spherical, body1: b, location: [0, 0, 0]}\n"
      "  - {name: cyl, type: cylindrical, body1: b, body2: ground, location: [0, 0, 1], axis: [0, 0, 1]}\n"
      "  - {name: slide, type: prismatic, body1: b, body2: ground, location: [0, 0, 1], axis: [1, 0, 0]}\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: ball, stiffness: 1}\n",
       "forces[k].joint: 'ball' is a spherical joint, which has no single rotation or translation coordinate"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: cyl, stiffness: 1}\n",
       "forces[k].coordinate: missing (required for a cylindrical joint): rotation or translation"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: slide, coordinate: rotation, stiffness: 1}\n",
       "forces[k].coordinate: a prismatic joint has a translation along its axis only"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: hinge, stiffness: 1}\n", "forces[k].joint: no joint named 'hinge'"},
      {"forces:\n  - {name: m, type: joint_motor, joint: slide, torque: 3}\n",
       "forces[m].torque: this motor drives a translation: give `force`"},
      {"forces:\n  - {name: m, type: joint_motor, joint: cyl, coordinate: rotation, torque: \"k*speed\"}\n",
       "forces[m].torque: unknown name 'k': no variable (angle, speed, t), parameter or sensor of that name"},
      {"sensors:\n  - {name: a, type: joint_angle, joint: slide}\n",
       "sensors[a].joint: 'slide' is a prismatic joint, which has a translation along its axis only"},
  };
  expect_input_errors(head, cases);
}

TEST(JointMotor, PdControlledArmSettlesAlongTheClosedFormLinearResponse) {
  // An arm (J = 0.13 kg m² about its revolute axis, no gravity) driven by a PD motor
  // T = −Kp (θ − θ_set) − Kd θ̇ with Kp = 4 N m/rad, Kd = 0.4 N m s/rad: J θ̈ + Kd θ̇ + Kp θ = Kp θ_set,
  // ω_n = √(Kp/J) = 5.5 rad/s, ζ = Kd / (2 √(Kp J)) = 0.28, and from rest at θ = 0
  // θ(t) = θ_set [1 − e^(−ζω_n t) (cos ω_d t + ζ/√(1 − ζ²) sin ω_d t)], ω_d = ω_n √(1 − ζ²).
  // The motor's tangent includes ∂T/∂θ = −Kp and ∂T/∂θ̇ = −Kd (exact), so Newton converges as without
  // the controller: at most 3 iterations per step (measured 2.8 on average; the same arm turning
  // freely takes 2, the nonlinearity being the frames' rotation and the link's sin(ϕ − ψ)).
  const RunSummary r = run_text(
      "name: pd_arm\ndimension: 3\nparameters: {Kp: 4, Kd: 0.4, theta_set: 1.2}\nsolver: {rho_inf: 0.9, h: 0.002, t_end: 1.5}\n"
      "bodies:\n  - {name: arm, type: rigid_body, mass: 1, inertia: [0.02, 0.02, 0.04], position: [0.3, 0, 0]}\n"
      "joints:\n  - {name: shoulder, type: revolute, body1: arm, location: [0, 0, 0], axis: [0, 0, 1]}\n"
      "forces:\n  - {name: pd, type: joint_motor, joint: shoulder, torque: \"-Kp*(angle - theta_set) - Kd*speed\"}\n"
      "sensors:\n  - {name: angle, type: joint_angle, joint: shoulder}\n",
      "pd_arm.yaml");
  // J about the axis: the body's 0.04 plus m d² = 0.09 (centre 0.3 m off the axis) = 0.13 kg m².
  const double J = 0.04 + 1 * 0.3 * 0.3, Kp = 4, Kd = 0.4, set = 1.2;
  const double wn = std::sqrt(Kp / J), zeta = Kd / (2 * std::sqrt(Kp * J)), wd = wn * std::sqrt(1 - zeta * zeta);
  double worst = 0.0;
  for (size_t i = 0; i < r.times_out.size(); ++i) {
    const double t = r.times_out[i];
    const double th = set * (1 - std::exp(-zeta * wn * t) * (std::cos(wd * t) + zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t)));
    worst = std::max(worst, std::fabs(r.sensor_history[i][0] - th) / set);
  }
  std::printf("[ closed   ] PD arm: max |θ − θ(t)| / θ_set = %.1e; Newton iterations: mean %.2f, max %d per step\n", worst,
              double(r.newton_total) / double(r.times_out.size() - 1), r.newton_max);
  EXPECT_LE(worst, 1e-4);
  EXPECT_LE(r.newton_max, 3);
}

TEST(EnergySensors, KineticAndStrainEnergiesOfASpringMassExchangeAtConstantSum) {
  // Undamped mass (m = 2 kg) on a spring (k = 800 N/m) along (1, 2, 2)/3, released 0.1 m beyond
  // its rest length: strain ½ k u² + kinetic ½ m u̇² = ½ k 0.1² = 4 J at every time (closed form);
  // the kinetic energy from the element's mass matrix equals ½ m |v|² of the body's velocity.
  // ρ∞ = 1: α_m = α_f = ½, which on this linear oscillator conserves the quadratic energy at the
  // steps (measured 2.6e-14 relative: round-off).
  const RunSummary r = run_text(
      "name: energy\ndimension: 3\nsolver: {rho_inf: 1.0, h: 0.00078539816, t_end: 0.5}\n"
      "bodies:\n  - {name: m, type: rigid_body, mass: 2, inertia: [0.1, 0.1, 0.1], position: [0.36666666666666667, 0.73333333333333333, 0.73333333333333333]}\n"
      "forces:\n  - {name: s, type: spring_damper, body1: m, stiffness: 800, rest_length: 1.0}\n"
      "sensors:\n  - {name: T, type: energy, element: m, kind: kinetic}\n  - {name: V, type: energy, element: s, kind: strain}\n"
      "  - {name: vx, type: point_velocity, body: m, component: x}\n  - {name: vy, type: point_velocity, body: m, component: y}\n"
      "  - {name: vz, type: point_velocity, body: m, component: z}\n",
      "energy.yaml");
  double worst = 0.0, worst_t = 0.0;
  for (const auto& row : r.sensor_history) {
    worst = std::max(worst, std::fabs(row[0] + row[1] - 4.0) / 4.0);
    worst_t = std::max(worst_t, std::fabs(row[0] - 0.5 * 2.0 * (row[2] * row[2] + row[3] * row[3] + row[4] * row[4])));
  }
  EXPECT_NEAR(r.sensor_history[0][1], 4.0, 1e-12);
  EXPECT_LE(worst_t, 1e-12);
  std::printf("[ closed   ] spring-mass energy: max |T + V − 4 J| / 4 J = %.1e\n", worst);
  EXPECT_LE(worst, 1e-12);
}

TEST(EnergySensors, ConstraintViolationOfAJointAndOfItsCoordinateLinkStaysAtRoundOff) {
  const RunSummary r = run_text(flywheel_on_dc_motor("violation", "{rho_inf: 0.9, h: 0.002, t_end: 0.2}", "[0.1, 0, 0]",
                                                     "  - {name: shaft, type: constraint_violation, joint: shaft}\n"
                                                     "  - {name: link, type: constraint_violation, joint: shaft.angle}\n"),
                                "violation.yaml");
  for (const auto& row : r.sensor_history) {
    EXPECT_LE(row[0], 1e-12);
    EXPECT_LE(row[1], 1e-12);
  }
}

}  // namespace alphaflex::testing
