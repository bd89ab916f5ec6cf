// Planar bushing, joint spring-damper and joint motor (elements/planar_coordinate_force.hpp,
// src/io/types/force_elements_2d.cpp): tangents against central differences, and closed forms.
#include <Eigen/Geometry>
#include <random>

#include "alphaflex/elements/planar_coordinate_force.hpp"
#include "test_scene_runs.hpp"

namespace alphaflex::testing {
namespace {

using Geometry = PlanarCoordinateForce::Geometry;
using Coordinates = PlanarCoordinateForce::Coordinates;

/// Worst relative difference of K = ∂r/∂q and C = ∂r/∂q̇ from central differences (h = 1e-6).
double tangent_error(const Element& e, const LocalState& s) {
  const LocalResidual t = element_tangents(e, s);
  const Eigen::Index n = s.v.size();
  Eigen::MatrixXd K(n, n), C(n, n);
  const double h = 1e-6;
  for (Eigen::Index i = 0; i < n; ++i) {
    LocalState p = s, m = s;
    p.q[i] += h;
    m.q[i] -= h;
    K.col(i) = (element_residual(e, p) - element_residual(e, m)) / (2 * h);
    p = s;
    m = s;
    p.v[i] += h;
    m.v[i] -= h;
    C.col(i) = (element_residual(e, p) - element_residual(e, m)) / (2 * h);
  }
  const double scale = std::max({1.0, t.K.cwiseAbs().maxCoeff(), t.C.cwiseAbs().maxCoeff()});
  return std::max((K - t.K).cwiseAbs().maxCoeff(), (C - t.C).cwiseAbs().maxCoeff()) / scale;
}

}  // namespace

TEST(PlanarCoordinateForce, TangentsOfBushingsJointSpringsAndMotorsMatchCentralDifferences) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix3d K, C;
  K << 300, 40, -20, 40, 200, 10, -20, 10, 50;
  C << 3, 0.4, 0, 0.4, 2, 0.1, 0, 0.1, 0.5;
  Geometry bushing;
  bushing.point_a = {0.2, -0.1};
  bushing.point_b = {-0.3, 0.05};
  bushing.alpha = 0.4;
  bushing.gamma0 = 0.2;
  auto expression = std::make_shared<ExpressionFunction>("3*(1 - speed/20) + 2*sin(angle) + t*speed*speed", ExpressionScope(),
                                                         std::vector<std::string>{"angle", "speed", "t"});
  std::vector<std::pair<std::string, std::unique_ptr<Element>>> elements;
  for (bool two : {true, false}) {
    Geometry g = bushing;
    g.body_b = two;
    const std::vector<int> nodes = two ? std::vector<int>{0, 1} : std::vector<int>{0};
    elements.emplace_back(std::string("bushing, ") + (two ? "two bodies" : "body–ground"), std::make_unique<PlanarCoordinateForce>("b", nodes, g, K, C));
    for (Coordinates c : {Coordinates::rotation, Coordinates::translation}) {
      Geometry j;
      j.coordinates = c;
      j.body_b = two;
      j.axis_b = Eigen::Vector2d(0.6, 0.8);
      const std::string what = std::string(c == Coordinates::rotation ? "rotation" : "translation") + (two ? ", two bodies" : ", body–ground");
      elements.emplace_back("spring-damper on " + what, std::make_unique<PlanarCoordinateForce>(
                                                             "s", nodes, j, ScalarForceLaw::linear(40.0, 1.5, 0.1, 0.3), false, 0.2));
      elements.emplace_back("motor on " + what, std::make_unique<PlanarCoordinateForce>("m", nodes, j, ScalarForceLaw::expression(expression, 0.0), true, -0.1));
    }
  }
  double worst = 0.0;
  for (const auto& [what, e] : elements) {
    const int n = static_cast<int>(e->nodes().size()) * 3;
    for (int trial = 0; trial < 5; ++trial) {
      LocalState s;
      s.q = Eigen::VectorXd(n);
      s.v = Eigen::VectorXd(n);
      for (int i = 0; i < n; ++i) {
        s.q[i] = (i % 3 == 2 ? 3.0 : 1.0) * u(rng);
        s.v[i] = 2.0 * u(rng);
      }
      s.qdd = Eigen::VectorXd::Zero(n);
      s.t = 0.3;
      s.load_factor = 0.7;
      const double err = tangent_error(*e, s);
      worst = std::max(worst, err);
      EXPECT_LE(err, 1e-7) << what;
      // No inertia: M w = 0 from mass_action (the filtered error estimate's product), as in the tangent.
      Eigen::VectorXd Mw;
      EXPECT_TRUE(e->mass_action(s, s.v, Mw)) << what;
      EXPECT_EQ(Mw, (testing::element_tangents(*e, s).M * s.v).eval()) << what;
    }
  }
  std::printf("[ tangents ] planar bushing, joint spring-dampers and motors: worst relative difference %.1e\n", worst);
}

TEST(PlanarBushing, StaticStiffnessAlongEachFrameAxisAndInRotationIsTheClosedForm) {
  // A body (m = 2 kg) on a bushing at its centre whose frame is at α = 0.3 rad, K = diag(kx, ky, kr):
  // a weight m g along frame axis 1 or 2 moves it by m g/kx or m g/ky along that axis and does not
  // turn it (the moment −u × K u of the frame's rotation vanishes for u along an axis of a diagonal
  // K; off an axis the frame attached to the body does couple them, as in 3D); a torque M turns it
  // by γ = M/kr without moving it. Exact (linear along these paths): static analysis, 1e-14.
  const double m = 2.0, g = 9.81, a = 0.3;
  const double k[3] = {1000, 4000, 50};
  for (int axis = 0; axis < 3; ++axis) {
    const Eigen::Vector2d e = axis == 0 ? Eigen::Vector2d(std::cos(a), std::sin(a)) : Eigen::Vector2d(-std::sin(a), std::cos(a));
    std::ostringstream y;
    y.precision(17);
    y << "name: bushing_2d\ngravity: [" << (axis < 2 ? g * e.x() : 0.0) << ", " << (axis < 2 ? g * e.y() : 0.0) << "]\n"
      << "solver: {analysis: static, static: {steps: 2}}\n"
      << "bodies:\n  - {name: b, type: rigid_body, mass: 2, inertia: 0.1, position: [0.5, 0.2]}\n"
      << "forces:\n  - {name: mount, type: bushing, body1: b, angle: 0.3, stiffness: [1000, 4000, 50], damping: [1, 1, 1]}\n"
      << (axis == 2 ? "  - {name: twist, type: torque, body: b, value: 3}\n" : "")
      << "sensors:\n  - {name: ux, type: point_displacement, body: b, component: x}\n"
      << "  - {name: uy, type: point_displacement, body: b, component: y}\n  - {name: th, type: body_angle, body: b}\n"
      << "  - {name: u1, type: force_output, element: mount, component: \"deflection[" << std::min(axis, 1) << "]\"}\n";
    const RunSummary r = run_text(y.str(), "bushing_2d.yaml");
    if (axis < 2) {
      const Eigen::Vector2d u = m * g / k[axis] * e;
      std::printf("[ closed   ] planar bushing, load along frame axis %d: u = (%.12e, %.12e) m, closed form (%.12e, %.12e)\n", axis + 1,
                  final_value(r, "ux"), final_value(r, "uy"), u.x(), u.y());
      EXPECT_NEAR(final_value(r, "ux"), u.x(), 1e-14);
      EXPECT_NEAR(final_value(r, "uy"), u.y(), 1e-14);
      EXPECT_NEAR(final_value(r, "th"), 0.0, 1e-14);
      EXPECT_NEAR(final_value(r, "u1"), -m * g / k[axis], 1e-14);  // the ground marker seen from the body's: −u
    } else {
      std::printf("[ closed   ] planar bushing, torque 3 N m: θ = %.12e rad, closed form %.12e\n", final_value(r, "th"), 3.0 / k[2]);
      EXPECT_NEAR(final_value(r, "th"), 3.0 / k[2], 1e-14);
      EXPECT_NEAR(final_value(r, "ux"), 0.0, 1e-14);
      EXPECT_NEAR(final_value(r, "uy"), 0.0, 1e-14);
    }
  }
}

TEST(PlanarJointSpringDamper, PendulumOnARotationalSpringHasTheClosedFormSmallOscillationFrequency) {
  // The spatial test's pendulum in the plane: rod m = 2 kg, centre l = 0.5 m below the pin,
  // J_c = 0.1 kg m², spring k = 20 N m/rad: ω = √((k + m g l)/(J_c + m l²)) (small θ; amplitude
  // 0.028 rad: θ₀²/16 ≈ 5e-5 of nonlinearity in the period). ρ∞ = 1, h = T/400.
  const double m = 2.0, l = 0.5, Jc = 0.1, k = 20.0, g = 9.81;
  const double omega = std::sqrt((k + m * g * l) / (Jc + m * l * l)), T = 2 * M_PI / omega;
  std::ostringstream y;
  y.precision(17);
  y << "name: pendulum_spring_2d\ngravity: [0, " << -g << "]\nsolver: {rho_inf: 1.0, h: " << T / 400 << ", t_end: " << 2.3 * T << "}\n"
    << "bodies:\n  - {name: rod, type: rigid_body, mass: " << m << ", inertia: " << Jc << ", position: [0, " << -l
    << "], angular_velocity: 0.2, velocity: [" << 0.2 * l << ", 0]}\n"
    << "joints:\n  - {name: hinge, type: revolute, body1: rod, location: [0, 0]}\n"
    << "forces:\n  - {name: spring, type: joint_spring_damper, joint: hinge, stiffness: " << k << "}\n"
    << "sensors:\n  - {name: angle, type: body_angle, body: rod}\n  - {name: torque, type: force_output, element: spring, component: force}\n"
    << "  - {name: V, type: energy, of: spring, kind: strain}\n  - {name: E, type: energy, of: model, kind: total}\n";
  const RunSummary r = run_text(y.str(), "pendulum_spring_2d.yaml");
  const std::vector<double> up = upward_zero_crossings(r, 0);
  ASSERT_GE(up.size(), 2u);
  const double period = up[1] - up[0], err = std::fabs(period - T) / T;
  std::printf("[ closed   ] planar pendulum on a rotational spring: period %.7f s, closed form %.7f s, rel. error %.1e\n", period, T, err);
  EXPECT_LE(err, 2e-4);
  // The spring's torque −k θ and energy ½ k θ², and the model's total energy (kinetic + spring +
  // gravity −m g·y): constant up to the scheme's error (ρ∞ = 1: no numerical dissipation).
  double drift = 0.0;
  for (size_t i = 0; i < r.times_out.size(); ++i) {
    const double th = r.sensor_history[i][0];
    EXPECT_NEAR(r.sensor_history[i][1], -k * th, 1e-9);
    EXPECT_NEAR(r.sensor_history[i][2], 0.5 * k * th * th, 1e-12);
    drift = std::max(drift, std::fabs(r.sensor_history[i][3] - r.sensor_history[0][3]));
  }
  const double T0 = 0.5 * (Jc + m * l * l) * 0.2 * 0.2;  // the initial kinetic energy
  std::printf("[ energy   ] planar pendulum: max |E − E(0)| = %.1e J of T(0) = %.2e J\n", drift, T0);
  EXPECT_LE(drift, 1e-6 * T0);  // measured 6.9e-10 J = 6e-8 T(0)
}

TEST(PlanarJointMotor, DcMotorSpinsUpAFlywheelAlongTheClosedFormAngleOverManyTurns) {
  // J θ̈ = T_s (1 − θ̇/ω₀), J = 0.04 kg m², T_s = 10 N m, ω₀ = 100 rad/s: θ(t) = ω₀ (t − τ (1 − e^(−t/τ))),
  // τ = J ω₀/T_s = 0.4 s; ten turns by t = 1 s (the planar angle is a coordinate: unwrapped).
  const RunSummary r = run_text(
      "name: dc_motor_2d\nparameters: {T_s: 10, w0: 100}\nsolver: {rho_inf: 0.9, h: 0.001, t_end: 1.0}\n"
      "bodies:\n  - {name: wheel, type: rigid_body, mass: 5, inertia: 0.04, position: [0, 0]}\n"
      "joints:\n  - {name: shaft, type: revolute, body1: wheel, location: [0, 0]}\n"
      "forces:\n  - {name: dc, type: joint_motor, joint: shaft, torque: \"T_s*(1 - speed/w0)\"}\n"
      "sensors:\n  - {name: angle, type: body_angle, body: wheel}\n  - {name: drive, type: force_output, element: dc, component: drive}\n"
      "  - {name: speed, type: force_output, element: dc, component: speed}\n",
      "dc_motor_2d.yaml");
  const double tau = 0.4;
  double worst = 0.0;
  for (size_t i = 0; i < r.times_out.size(); ++i) {
    const double t = r.times_out[i], a = 100 * (t - tau * (1 - std::exp(-t / tau)));
    worst = std::max(worst, std::fabs(r.sensor_history[i][0] - a) / std::max(1.0, a));
    EXPECT_NEAR(r.sensor_history[i][1], 10 * (1 - r.sensor_history[i][2] / 100), 1e-9);
  }
  std::printf("[ closed   ] planar DC motor: max |θ − θ(t)|/θ = %.1e, θ(1 s) = %.3f rad\n", worst, final_value(r, "angle"));
  EXPECT_GT(final_value(r, "angle"), 60.0);
  EXPECT_LE(worst, 1e-5);
}

TEST(PlanarJointMotor, AForceOnAPrismaticJointAcceleratesTheSliderAlongItsAxis) {
  // A slider (m = 3 kg) on a prismatic joint along (0.6, 0.8) pushed by F = 6 N: displacement
  // s(t) = F t²/(2m) along the axis (exact for the scheme: constant acceleration), and a spring
  // k = 27 N/m with the same slider oscillates at ω = √(k/m) = 3 rad/s.
  const RunSummary r = run_text(
      "name: slider_2d\nsolver: {rho_inf: 0.9, h: 0.01, t_end: 0.5}\n"
      "bodies:\n  - {name: s, type: rigid_body, mass: 3, inertia: 0.1, position: [1, 1]}\n"
      "joints:\n  - {name: rail, type: prismatic, body1: s, location: [1, 1], axis: [0.6, 0.8]}\n"
      "forces:\n  - {name: push, type: joint_motor, joint: rail, force: \"6\"}\n"
      "sensors:\n  - {name: x, type: point_displacement, body: s, component: x}\n  - {name: y, type: point_displacement, body: s, component: y}\n"
      "  - {name: s, type: force_output, element: push, component: coordinate}\n",
      "slider_2d.yaml");
  const double t = 0.5, s = 6 * t * t / 6;
  EXPECT_NEAR(final_value(r, "s"), s, 1e-10);
  EXPECT_NEAR(final_value(r, "x"), 0.6 * s, 1e-10);
  EXPECT_NEAR(final_value(r, "y"), 0.8 * s, 1e-10);
}

TEST(PlanarForceElements, BadInputIsRefusedNamingTheKey) {
  const std::string head =
      "name: bad\nsolver: {h: 0.01, t_end: 0.01}\n"
      "bodies:\n  - {name: b, type: rigid_body, mass: 1, inertia: 1, position: [0, 0]}\n  - {name: p, type: particle, mass: 1, position: [1, 0]}\n"
      "joints:\n  - {name: pin, type: revolute, body1: b, location: [0, 0]}\n  - {name: line, type: point_on_line, body1: b, location: [0, 0], axis: [1, 0]}\n"
      "  - {name: pp, type: revolute, body1: p, location: [1, 0]}\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"forces:\n  - {name: k, type: bushing, body1: b, stiffness: [1, -2, 3]}\n", "forces[k].stiffness: the matrix must be positive semi-definite"},
      {"forces:\n  - {name: k, type: bushing, body1: b, stiffness: [1, 2]}\n", "forces[k].stiffness: expected 3 numbers (the diagonal) or 3 rows of 3 numbers"},
      {"forces:\n  - {name: k, type: bushing, body1: p, stiffness: [1, 2, 3]}\n", "forces[k].body1: 'p' is not a rigid body"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: line, stiffness: 1}\n", "forces[k].joint: 'line' is a point_on_line joint"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: pp, stiffness: 1}\n", "which is not a rigid body: it has no angle"},
      {"forces:\n  - {name: m, type: joint_motor, joint: pin, force: 3}\n", "forces[m].force: this motor drives a rotation: give `torque`"},
      {"forces:\n  - {name: m, type: joint_motor, joint: pin, torque: \"k*speed\"}\n", "forces[m].torque: in expression 'k*speed'"},
  };
  for (const auto& [tail, expected] : cases) {
    const std::string msg = input_error_of([&] { read_scene_text(head + tail, "bad.yaml"); });
    EXPECT_NE(msg.find(expected), std::string::npos) << "got: " << msg << "\nexpected: " << expected;
  }
}

}  // namespace alphaflex::testing
