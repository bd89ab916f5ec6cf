// Joint stops (elements/joint_stop.hpp), the two angles of a universal joint
// (joints/joint_coordinate.hpp) and loads that read sensors (elements/sensor_feedback.hpp,
// model/sensor_function.hpp): tangents against central differences on the group, the physics
// against closed forms (restitution of a linear spring-dashpot stop, small oscillations on a
// universal joint, a PID-held arm as a third-order linear system), and bad input named.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "alphaflex/elements/joint_stop.hpp"
#include "alphaflex/elements/sensor_feedback.hpp"
#include "alphaflex/joints/joint_coordinate.hpp"
#include "alphaflex/model/model.hpp"
#include "test_scene_runs.hpp"

namespace alphaflex::testing {
namespace {

Eigen::Vector3d random3(std::mt19937& rng) { return {uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)}; }

/// q ∘ exp(d) on a node list of frames (7/6) and scalars (1/1).
Eigen::VectorXd retract_nodes(const std::vector<bool>& frame, const Eigen::VectorXd& q, const Eigen::VectorXd& d) {
  Eigen::VectorXd out = q;
  Eigen::Index c = 0, k = 0;
  for (bool f : frame) {
    if (f) {
      retract(NodeKind::Frame3D, q.data() + c, d.data() + k, out.data() + c);
      c += 7;
      k += 6;
    } else {
      out[c++] += d[k++];
    }
  }
  return out;
}

/// K (on the group) and C of `e` against central differences (h = 1e-6); worst relative error.
double check_stop_tangents(const Element& e, const LocalState& s, const std::vector<bool>& frame) {
  const LocalResidual t = element_tangents(e, s);
  const Eigen::Index n = s.v.size();
  Eigen::MatrixXd K(t.r.size(), n), C(t.r.size(), n);
  const double h = 1e-6;
  for (Eigen::Index j = 0; j < n; ++j) {
    const Eigen::VectorXd d = Eigen::VectorXd::Unit(n, j) * h;
    LocalState a = s, b = s;
    a.q = retract_nodes(frame, s.q, d);
    b.q = retract_nodes(frame, s.q, -d);
    K.col(j) = (element_residual(e, a) - element_residual(e, b)) / (2 * h);
    a = s;
    b = s;
    a.v[j] += h;
    b.v[j] -= h;
    C.col(j) = (element_residual(e, a) - element_residual(e, b)) / (2 * h);
  }
  const double ek = (t.K - K).norm() / std::max(K.norm(), 1e-300), ec = (t.C - C).norm() / std::max(C.norm(), 1e-300);
  EXPECT_LE(ek, 1e-6) << "K exact\n" << t.K << "\nFD\n" << K;
  EXPECT_LE(ec, 1e-6) << "C exact\n" << t.C << "\nFD\n" << C;
  return std::max(ek, ec);
}

constexpr const char* kJointSceneHead =
    "name: bad\ndimension: 3\nsolver: {h: 0.01, t_end: 0.02}\n"
    "bodies:\n  - {name: b, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0, 0, 1]}\n"
    "joints:\n  - {name: hinge, type: revolute, body1: b, location: [0, 0, 0], axis: [0, 0, 1]}\n"
    "  - {name: cross, type: universal, body1: b, location: [0, 0, 1], axis: [1, 0, 0], axis2: [0, 1, 0]}\n"
    "  - {name: ball, type: spherical, body1: b, location: [0, 0, 1]}\n";

void expect_joint_input_errors(const std::vector<std::pair<std::string, std::string>>& cases) {
  for (const auto& [tail, expected] : cases) {
    SCOPED_TRACE(tail);
    const std::string msg = input_error_of([&, &tail = tail] { read_scene_text(kJointSceneHead + tail, "bad.yaml"); });
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
  }
}

}  // namespace

// ============================================================ joint stops

TEST(JointStop, PenaltyActsOnlyBeyondItsLimitsWithExactOneSidedTangents) {
  const JointStop stop("s", 0, -0.3, 0.5, 1.0e4, 20.0);
  std::mt19937 rng(7);
  for (const double psi : {-0.7, -0.31, 0.0, 0.2, 0.51, 1.4}) {
    LocalState s = local_state(Eigen::VectorXd::Constant(1, psi), Eigen::VectorXd::Constant(1, uniform(rng, -3, 3)), Eigen::VectorXd::Zero(1));
    const double v = s.v[0];
    const double expected = psi > 0.5 ? 1.0e4 * (psi - 0.5) + 20.0 * v : psi < -0.3 ? 1.0e4 * (psi + 0.3) + 20.0 * v : 0.0;
    EXPECT_NEAR(element_residual(stop, s)[0], expected, 1e-9);
    if (expected != 0.0) check_stop_tangents(stop, s, {false});
    else EXPECT_EQ(element_tangents(stop, s).K(0, 0), 0.0);
    // Energy ½ k δ² and the force on the coordinate (−r) as outputs.
    Eigen::VectorXd out;
    stop.output(s, out);
    const double delta = std::max({psi - 0.5, -0.3 - psi, 0.0});
    EXPECT_NEAR(out[2], delta, 1e-15);
    EXPECT_NEAR(out[3], -expected, 1e-9);
    EXPECT_NEAR(stop.elastic_energy(s.q), 0.5e4 * delta * delta, 1e-9);
  }
}

TEST(JointStop, PendulumReboundsWithTheClosedFormRestitutionOfALinearSpringDashpot) {
  // A rod (m = 2 kg, centre 0.5 m from a vertical hinge, J_c = 0.1 kg m²: J = J_c + m l² = 0.6 kg m²)
  // turns freely (no gravity about the axis) at ω₀ = 2 rad/s into a stop at 0.1 rad, k = J ω_n²
  // with ω_n = 200 rad/s, c = 2 ζ √(k J) with ζ = 0.1. In contact J δ̈ + c δ̇ + k δ = 0 from δ = 0,
  // δ̇ = ω₀; it leaves at δ = 0 after half a damped period with δ̇ = −e ω₀,
  // e = exp(−ζπ/√(1 − ζ²)) = 0.72925 (e.g. Gilardi & Sharf 2002, eq. 9). ρ∞ = 1, h = 2e-5 s: the
  // contact (15.8 ms) takes ~790 steps.
  const double J = 0.1 + 2 * 0.25, wn = 200, zeta = 0.1, k = J * wn * wn, c = 2 * zeta * std::sqrt(k * J);
  const double e = std::exp(-zeta * M_PI / std::sqrt(1 - zeta * zeta));
  std::ostringstream y;
  y.precision(17);
  y << "name: stop\ndimension: 3\nsolver: {rho_inf: 1.0, h: 2.0e-5, t_end: 0.09}\n"
    << "bodies:\n  - {name: rod, type: rigid_body, mass: 2, inertia: [0.1, 0.1, 0.1], position: [0.5, 0, 0],"
    << " angular_velocity: [0, 0, 2], velocity: [0, 1, 0]}\n"
    << "joints:\n  - {name: hinge, type: revolute, body1: rod, location: [0, 0, 0], axis: [0, 0, 1]}\n"
    << "forces:\n  - {name: stop, type: joint_stop, joint: hinge, lower: -1, upper: 0.1, stiffness: " << k << ", damping: " << c << "}\n"
    << "sensors:\n  - {name: angle, type: joint_angle, joint: hinge}\n  - {name: speed, type: joint_speed, joint: hinge}\n"
    << "  - {name: pen, type: force_output, element: stop, component: penetration}\n";
  const RunSummary r = run_text(y.str(), "stop.yaml");
  const double after = final_value(r, "speed");
  EXPECT_LT(final_value(r, "angle"), 0.1);  // it has left the stop
  EXPECT_EQ(final_value(r, "pen"), 0.0);
  const double err = std::fabs(-after / 2.0 - e) / e;
  std::printf("[ closed   ] joint stop: restitution %.6f, closed form %.6f (ζ = 0.1), rel. error %.1e; Newton mean %.2f, max %d\n",
              -after / 2.0, e, err, double(r.newton_total) / double(r.times_out.size() - 1), r.newton_max);
  EXPECT_LE(err, 2e-3);
}

// ============================================================ universal joints

TEST(UniversalJointCoordinates, AnglesAreTheCrossRotationsAndTheLinksTangentsMatchFiniteDifferences) {
  std::mt19937 rng(11);
  using C = JointCoordinateLink::Coordinate;
  // R_Bᵀ R_A = R_y(ψ2) R_x(ψ1) in the joint frame: frame_value gives ψ1 and ψ2 back.
  SpatialMarker a, b;
  a.slot = 0;
  b.slot = 1;
  a.position = {0.1, -0.2, 0.3};
  b.position = {-0.3, 0.1, 0.2};
  a.rotation = exp_so3<double>(Eigen::Vector3d(0.3, -0.2, 0.5));
  b.rotation = exp_so3<double>(Eigen::Vector3d(-0.4, 0.1, 0.2));
  for (int i = 0; i < 8; ++i) {
    const double p1 = uniform(rng, -3.0, 3.0), p2 = uniform(rng, -1.5, 1.5);
    const Eigen::Matrix3d RB = exp_so3<double>(random3(rng));
    const Eigen::Matrix3d Rm = RB * b.rotation * Eigen::AngleAxisd(p2, Eigen::Vector3d::UnitY()).toRotationMatrix() *
                               Eigen::AngleAxisd(p1, Eigen::Vector3d::UnitX()).toRotationMatrix();
    const Eigen::Matrix3d RA = Rm * a.rotation.transpose();
    Eigen::VectorXd q(14);
    store_pose(random3(rng), RA, q.data());
    store_pose(random3(rng), RB, q.data() + 7);
    const JointCoordinateLink l1("u1", {0, 1, 2}, a, b, C::universal_axis), l2("u2", {0, 1, 2}, a, b, C::universal_axis2);
    EXPECT_NEAR(l1.frame_value(q), p1, 1e-12);
    EXPECT_NEAR(l2.frame_value(q), p2, 1e-12);
  }
  // Φ_q, K_Φ and the acceleration term against central differences on the group.
  double worst = 0.0;
  for (const C c : {C::universal_axis, C::universal_axis2}) {
    const JointCoordinateLink link("l", {0, 1, 2}, a, b, c);
    for (int i = 0; i < 8; ++i) {
      Eigen::VectorXd q(15);
      store_pose(random3(rng), exp_so3<double>(3.0 * random3(rng).normalized()), q.data());
      store_pose(random3(rng), exp_so3<double>(3.0 * random3(rng).normalized()), q.data() + 7);
      q[14] = uniform(rng, -20, 20);
      const std::vector<bool> frame{true, true, false};
      const double lambda = uniform(rng, -5, 5);
      Eigen::VectorXd phi, v(13);
      for (int j = 0; j < 13; ++j) v[j] = uniform(rng, -2, 2);
      Eigen::MatrixXd phi_q, k;
      link.evaluate(q, 0.0, phi, phi_q);
      link.geometric_stiffness(q, 0.0, Eigen::VectorXd::Constant(1, lambda), k);
      Eigen::MatrixXd fd_q(1, 13), fd_k(13, 13);
      for (int j = 0; j < 13; ++j) {
        const Eigen::VectorXd d = Eigen::VectorXd::Unit(13, j) * 1e-6;
        Eigen::VectorXd pp, pm;
        Eigen::MatrixXd jp, jm;
        link.evaluate(retract_nodes(frame, q, d), 0.0, pp, jp);
        link.evaluate(retract_nodes(frame, q, -d), 0.0, pm, jm);
        fd_q(0, j) = (pp[0] - pm[0]) / 2e-6;
        fd_k.col(j) = lambda * (jp - jm).row(0).transpose() / 2e-6;
      }
      const double e1 = (phi_q - fd_q).norm() / phi_q.norm(), e2 = (k - fd_k).norm() / std::max(k.norm(), 1e-12);
      EXPECT_LE(e1, 1e-6);
      EXPECT_LE(e2, 1e-6) << k << "\n" << fd_k;
      Eigen::VectorXd cterm;
      link.acceleration_term(q, v, 0.0, cterm);
      const double h = 1e-4;
      Eigen::VectorXd pp, pm;
      Eigen::MatrixXd jj;
      link.evaluate(retract_nodes(frame, q, h * v), 0.0, pp, jj);
      link.evaluate(retract_nodes(frame, q, -h * v), 0.0, pm, jj);
      EXPECT_NEAR(cterm[0], (pp[0] - 2 * phi[0] + pm[0]) / (h * h), 1e-5 * std::max(1.0, std::fabs(cterm[0])));
      worst = std::max({worst, e1, e2});
    }
  }
  std::printf("[ FD       ] worst rel. error %.1e  universal joint coordinate links (Φ_q, K_Φ)\n", worst);
}

TEST(UniversalJointCoordinates, PendulumOnSpringsAboutBothAxesOscillatesAtTheClosedFormFrequencies) {
  // A rod (m = 2 kg, centre 0.5 m below a universal joint to the ground, J_c = 0.1 kg m²) with
  // rotational springs k1 = 20 N m/rad on angle 1 (about x, body 1's axis) and k2 = 40 N m/rad on
  // angle 2 (about y, the ground's axis), under gravity. Small oscillations about each axis
  // uncouple: ω_i = √((k_i + m g l)/(J_c + m l²)). Started turning about x only, angle 1 oscillates
  // at ω1 and angle 2 stays 0; about y only, angle 2 at ω2 (amplitude 0.02 rad: the nonlinearity
  // θ₀²/16 is 2.5e-5 of the period).
  for (const int axis : {1, 2}) {
    SCOPED_TRACE(axis);
    const double m = 2, l = 0.5, Jc = 0.1, g = 9.81, k = axis == 1 ? 20 : 40;
    const double w = std::sqrt((k + m * g * l) / (Jc + m * l * l)), T = 2 * M_PI / w, w0 = 0.02 * w;
    std::ostringstream y;
    y.precision(17);
    y << "name: cardan\ndimension: 3\ngravity: [0, 0, " << -g << "]\nsolver: {rho_inf: 1.0, h: " << T / 400 << ", t_end: " << 2.3 * T << "}\n"
      << "bodies:\n  - {name: rod, type: rigid_body, mass: 2, inertia: [0.1, 0.1, 0.1], position: [0, 0, -0.5], angular_velocity: ["
      << (axis == 1 ? w0 : 0.0) << ", " << (axis == 1 ? 0.0 : w0) << ", 0], velocity: [" << (axis == 1 ? 0.0 : -w0 * l) << ", "
      << (axis == 1 ? w0 * l : 0.0) << ", 0]}\n"
      << "joints:\n  - {name: cross, type: universal, body1: rod, location: [0, 0, 0], axis: [1, 0, 0], axis2: [0, 1, 0]}\n"
      << "forces:\n  - {name: k1, type: joint_spring_damper, joint: cross, coordinate: 1, stiffness: 20}\n"
      << "  - {name: k2, type: joint_spring_damper, joint: cross, coordinate: 2, stiffness: 40}\n"
      << "sensors:\n  - {name: a1, type: joint_angle, joint: cross, coordinate: 1}\n"
      << "  - {name: a2, type: joint_angle, joint: cross, coordinate: 2}\n  - {name: s1, type: joint_speed, joint: cross, coordinate: 1}\n";
    const RunSummary r = run_text(y.str(), "cardan.yaml");
    const size_t on = axis == 1 ? 0 : 1, off = 1 - on;
    std::vector<double> up;
    double stray = 0.0;
    for (size_t i = 1; i < r.times_out.size(); ++i) {
      const double a = r.sensor_history[i - 1][on], b = r.sensor_history[i][on];
      if (a < 0.0 && b >= 0.0) up.push_back(r.times_out[i - 1] + (r.times_out[i] - r.times_out[i - 1]) * a / (a - b));
      stray = std::max(stray, std::fabs(r.sensor_history[i][off]));
    }
    EXPECT_NEAR(r.sensor_history[0][2], axis == 1 ? w0 : 0.0, 1e-12);  // ψ̇(0) from the bodies' velocities
    ASSERT_GE(up.size(), 2u);
    const double err = std::fabs(up[1] - up[0] - T) / T;
    std::printf("[ closed   ] universal joint, spring on angle %d: period rel. error %.1e, other angle max %.1e rad\n", axis, err, stray);
    EXPECT_LE(err, 2e-4);
    EXPECT_LE(stray, 1e-12);
  }
}

TEST(UniversalJointCoordinates, BadCoordinatesAndJointsWithoutACoordinateAreRefusedByName) {
  expect_joint_input_errors({
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: cross, stiffness: 1}\n",
       "forces[k].coordinate: missing (required for a universal joint): 1 (the angle about axis) or 2 (the angle about axis2)"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: cross, coordinate: 3, stiffness: 1}\n",
       "forces[k].coordinate: unknown coordinate '3' (a universal joint has 1 (the angle about axis) and 2 (the angle about axis2))"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: hinge, coordinate: 1, stiffness: 1}\n",
       "forces[k].coordinate: unknown coordinate '1' (a revolute joint has rotation or translation)"},
      {"forces:\n  - {name: k, type: joint_spring_damper, joint: ball, stiffness: 1}\n",
       "forces[k].joint: 'ball' is a spherical joint, which has no single rotation or translation coordinate"},
      {"sensors:\n  - {name: d, type: joint_displacement, joint: cross}\n",
       "sensors[d].joint: 'cross' is a universal joint, which has two rotations"},
      {"forces:\n  - {name: s, type: joint_stop, joint: hinge, lower: 0.2, upper: 0.1, stiffness: 1}\n", "forces[s].upper: must be above `lower`"},
      {"forces:\n  - {name: s, type: joint_stop, joint: hinge, lower: 0.2, stiffness: 1}\n",
       "forces[s].lower: the joint starts below it (its coordinate is 0.000000 rad at t = 0)"},
      {"forces:\n  - {name: s, type: joint_stop, joint: hinge, stiffness: 1}\n", "forces[s]: give `lower`, `upper` or both"},
      {"forces:\n  - {name: s, type: joint_stop, joint: ball, upper: 1, stiffness: 1}\n", "forces[s].joint: 'ball' is a spherical joint"},
  });
}

// ============================================================ loads that read sensors

namespace {

/// An arm on a revolute joint about z (J = 0.13 kg m² about the axis, no gravity) held at `set` by
/// a motor whose torque reads sensors; a constant disturbance torque Td = 0.5 N m on the joint.
std::string pid_arm(const std::string& torque, const std::string& sensors, const std::string& solver) {
  return "name: pid_arm\ndimension: 3\nparameters: {Kp: 4, Kd: 0.8, Ki: 6, set: 1.2, Td: 0.5}\nsolver: " + solver +
         "\nbodies:\n  - {name: arm, type: rigid_body, mass: 1, inertia: [0.02, 0.02, 0.04], position: [0.3, 0, 0],"
         " markers: [{name: tip, position: [0.2, 0, 0]}]}\n"
         "joints:\n  - {name: shoulder, type: revolute, body1: arm, location: [0, 0, 0], axis: [0, 0, 1]}\n"
         "forces:\n  - {name: pid, type: joint_motor, joint: shoulder, torque: \"" + torque + "\"}\n"
         "  - {name: disturbance, type: joint_motor, joint: shoulder, torque: Td}\n"
         "sensors:\n" + sensors;
}

}  // namespace

TEST(SensorFeedback, PidArmSettlesOnItsSetPointAlongTheClosedFormThirdOrderResponse) {
  // J θ̈ = −Kp (θ − θs) − Kd θ̇ − Ki I + Td, İ = θ − θs (the `integral` sensor), from rest at θ = 0,
  // I = 0: x = (θ − θs, θ̇, I) obeys ẋ = A x + b, A = [[0, 1, 0], [−Kp/J, −Kd/J, −Ki/J], [1, 0, 0]],
  // b = (0, Td/J, 0), so x(t) = e^(At) x0 + A⁻¹(e^(At) − I) b (closed form; the roots of
  // J s³ + Kd s² + Kp s + Ki have negative real parts): θ → θs, I → Td/Ki. The angle, speed and
  // integral are sensors the torque names; its tangent includes their exact derivatives.
  const std::string sensors = "  - {name: arm_angle, type: joint_angle, joint: shoulder}\n"
                              "  - {name: arm_speed, type: joint_speed, joint: shoulder}\n"
                              "  - {name: err_int, type: integral, of: \"error\"}\n"
                              "  - {name: error, type: expression, value: \"arm_angle - set\"}\n";
  // Full Newton by name (the default takes modified Newton for a motor that reads sensors): the
  // exact tangent through the sensors shows as Newton's quadratic convergence, ≤ 3 iterations.
  const RunSummary r = run_text(pid_arm("-Kp*error - Kd*arm_speed - Ki*err_int", sensors,
                                        "{rho_inf: 0.9, h: 0.002, t_end: 4.0, newton: {modified: off}}"),
                                "pid_arm.yaml");
  const double J = 0.04 + 0.09, Kp = 4, Kd = 0.8, Ki = 6, set = 1.2, Td = 0.5;
  Eigen::Matrix3d A;
  A << 0, 1, 0, -Kp / J, -Kd / J, -Ki / J, 1, 0, 0;
  const Eigen::Vector3d b(0, Td / J, 0), x0(-set, 0, 0);
  double worst = 0.0, worst_i = 0.0;
  for (size_t i = 0; i < r.times_out.size(); ++i) {
    const Eigen::Matrix3d E = (A * r.times_out[i]).exp();
    const Eigen::Vector3d x = E * x0 + A.partialPivLu().solve((E - Eigen::Matrix3d::Identity()) * b);
    worst = std::max(worst, std::fabs(r.sensor_history[i][0] - set - x[0]) / set);
    worst_i = std::max(worst_i, std::fabs(r.sensor_history[i][2] - x[2]) / (Td / Ki));
    EXPECT_NEAR(r.sensor_history[i][3], r.sensor_history[i][0] - set, 1e-14);
  }
  const double mean = double(r.newton_total) / double(r.times_out.size() - 1);
  // The same arm without feedback (only the disturbance): Newton's iterations for comparison.
  const RunSummary open = run_text(pid_arm("0", "  - {name: arm_angle, type: joint_angle, joint: shoulder}\n", "{rho_inf: 0.9, h: 0.002, t_end: 4.0}"),
                                   "open_arm.yaml");
  std::printf("[ closed   ] PID arm: max |θ − θ(t)| / θs = %.1e, max |I − I(t)| / I(∞) = %.1e, final θ − θs = %.1e; Newton mean %.2f, max %d"
              " (no feedback: mean %.2f, max %d)\n",
              worst, worst_i, final_value(r, "arm_angle") - set, mean, r.newton_max,
              double(open.newton_total) / double(open.times_out.size() - 1), open.newton_max);
  EXPECT_LE(worst, 1e-4);
  EXPECT_LE(worst_i, 1e-4);
  EXPECT_LE(r.newton_max, 3);
}

TEST(SensorFeedback, TangentsThroughEverySensorKindMatchFiniteDifferences) {
  // A motor whose torque reads a joint angle and speed, point positions, displacements and
  // velocities (world and in a moving frame, on both bodies), an integral and a nested expression:
  // K and C of its row against central differences on the group at random states.
  const std::string scene =
      "name: fd\ndimension: 3\nparameters: {a: 0.7}\nsolver: {h: 0.01, t_end: 0.02}\n"
      "bodies:\n  - {name: b1, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0.3, 0, 0]}\n"
      "  - {name: b2, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0.3, 0.5, 0.1]}\n"
      "joints:\n  - {name: hinge, type: revolute, body1: b1, location: [0, 0, 0], axis: [0, 0, 1]}\n"
      "forces:\n  - {name: m1, type: joint_motor, joint: hinge, torque: \"a*angle*speed + sin(th)*w\"}\n"
      "  - {name: m2, type: joint_motor, joint: hinge, torque: \"px*fy + e2^2\"}\n"
      "  - {name: m3, type: joint_motor, joint: hinge, torque: \"vz*dx + I*t\"}\n"
      "sensors:\n  - {name: th, type: joint_angle, joint: hinge}\n"
      "  - {name: w, type: joint_speed, joint: hinge}\n"
      "  - {name: px, type: point_position, body: b2, point: [0.1, 0.2, -0.3], component: x}\n"
      "  - {name: fy, type: point_position, body: b2, point: [0.1, 0.2, -0.3], relative_to: b1, component: y}\n"
      "  - {name: dx, type: point_displacement, body: b1, point: [0.2, 0, 0.1], relative_to: b2, component: x}\n"
      "  - {name: vz, type: point_velocity, body: b2, point: [-0.2, 0.1, 0.3], relative_to: b1, component: z}\n"
      "  - {name: I, type: integral, of: \"e2\"}\n"
      "  - {name: e2, type: expression, value: \"px*vz - th\"}\n";
  Scene sc = read_scene_text(scene, "fd.yaml");
  const Model& model = *sc.model;
  std::mt19937 rng(5);
  double worst = 0.0;
  int checked = 0;
  for (const auto& e : model.elements()) {
    if (std::string(e->type()) != "joint_motor" && std::string(e->type()) != "sensor_integrator") continue;
    std::vector<bool> frame;
    for (int n : e->nodes()) frame.push_back(model.node(n).spatial());
    for (int i = 0; i < 4; ++i) {
      Eigen::VectorXd q, v;
      for (bool f : frame) {
        const Eigen::Index c = q.size(), d = v.size();
        q.conservativeResize(c + (f ? 7 : 1));
        v.conservativeResize(d + (f ? 6 : 1));
        if (f) store_pose(random3(rng), exp_so3<double>(random3(rng)), q.data() + c);
        else q[c] = uniform(rng, -2, 2);
        for (Eigen::Index k = d; k < v.size(); ++k) v[k] = uniform(rng, -2, 2);
      }
      LocalState s = local_state(q, v, Eigen::VectorXd::Zero(v.size()));
      s.t = 0.3;
      s.load_factor = 0.8;
      worst = std::max(worst, check_stop_tangents(*e, s, frame));
      ++checked;
    }
  }
  EXPECT_EQ(checked, 16);  // three motors and the integrator
  std::printf("[ FD       ] worst rel. error %.1e  loads through sensors (K, C)\n", worst);
}

TEST(SensorFeedback, UnknownSensorsLoopsAndSensorsWithoutDerivativesAreRefusedByTheirKey) {
  expect_joint_input_errors({
      {"forces:\n  - {name: m, type: joint_motor, joint: hinge, torque: \"-4*th\"}\n",
       "forces[m].torque: unknown name 'th': no variable (angle, speed, t), parameter or sensor of that name (sensors: none)"},
      {"sensors:\n  - {name: a, type: expression, value: \"b + 1\"}\n  - {name: b, type: expression, value: \"2*c\"}\n"
       "  - {name: c, type: expression, value: \"a - t\"}\n",
       "sensors[c].value: reads sensor 'a', which depends on this expression: a loop (a → b → c → a)"},
      {"sensors:\n  - {name: a, type: expression, value: \"a + 1\"}\n", "sensors[a].value: reads sensor 'a', which depends on this expression: a loop (a → a)"},
      {"forces:\n  - {name: m, type: joint_motor, joint: hinge, torque: \"-r\"}\n"
       "sensors:\n  - {name: r, type: joint_reaction, joint: hinge, component: mz}\n",
       "forces[m].torque: sensor 'r' is a joint reaction (a multiplier, which an element cannot read), whose derivative a load cannot take"},
      {"sensors:\n  - {name: a, type: expression, value: \"2*t\"}\n", "sensors[a].value: names no sensor"},
      {"sensors:\n  - {name: i, type: integral, of: \"x\"}\n", "sensors[i].of: unknown name 'x'"},
      {"forces:\n  - {name: m, type: joint_motor, joint: hinge, torque: \"a + b + c + speed + angle\"}\n"
       "sensors:\n  - {name: a, type: joint_angle, joint: hinge}\n  - {name: b, type: joint_speed, joint: hinge}\n"
       "  - {name: c, type: integral, of: \"a\"}\n",
       "forces[m].torque: uses 5 variables and sensors (a, b, c, speed, angle); an expression may use at most 4"},
  });
  // An integral breaks a loop: its value is a state.
  EXPECT_NO_THROW(read_scene_text(std::string(kJointSceneHead) + "sensors:\n  - {name: i, type: integral, of: \"-e\"}\n"
                                  "  - {name: e, type: expression, value: \"i + t\"}\n", "ok.yaml"));
}

}  // namespace alphaflex::testing
