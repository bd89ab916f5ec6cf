// Joint constraints Φ(q): Jacobian Φ_q, geometric stiffness ∂(Φ_qᵀλ)/∂q and acceleration term d²Φ(q + s q̇)/ds² against finite differences; Φ in known configurations; reactions −Φ_{r1}ᵀλ.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "alphaflex/joints/planar_joints.hpp"
#include "alphaflex/model/constraint.hpp"
#include "alphaflex/model/node.hpp"
#include "alphaflex/model/planar_marker.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

constexpr double kJointRelTol = 1e-6;   // FD vs analytic, relative to the norm of the analytic quantity
constexpr double kJointValueTol = 1e-12;
constexpr int kJointSamples = 10;
using testing::kPi;
using testing::random_vector;
using testing::uniform;
using testing::vec;

// ------------------------------------------------------------------ nodes
Node rigid_node_at_origin() {
  Node n;
  n.name = "rigid";
  n.kind = NodeKind::RigidBody2D;
  n.ndof = Node::dofs_of(n.kind);
  n.q0 = Eigen::VectorXd::Zero(3);
  n.v0 = Eigen::VectorXd::Zero(3);
  return n;
}

Node particle_node_at_origin() {
  Node n;
  n.name = "particle";
  n.kind = NodeKind::Particle2D;
  n.ndof = Node::dofs_of(n.kind);
  n.q0 = Eigen::VectorXd::Zero(2);
  n.v0 = Eigen::VectorXd::Zero(2);
  return n;
}

Node line_node_at_origin(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction) {
  Node n;
  n.name = "line_particle";
  n.kind = NodeKind::LineParticle2D;
  n.ndof = Node::dofs_of(n.kind);
  n.q0 = Eigen::VectorXd::Zero(1);
  n.v0 = Eigen::VectorXd::Zero(1);
  n.line_origin = origin;
  n.line_direction = direction.normalized();
  return n;
}

/// World position of the body point `s` of a rigid body at (x, y, θ), computed by hand.
Eigen::Vector2d body_point(const Eigen::Vector2d& x, double theta, const Eigen::Vector2d& s) {
  return x + Eigen::Vector2d(std::cos(theta) * s.x() - std::sin(theta) * s.y(),
                             std::sin(theta) * s.x() + std::cos(theta) * s.y());
}

// ------------------------------------------------------------------ joint cases
/// A joint whose body 1 is a rigid body with local point s1 at offset `body1_offset`; its local
/// vector has n entries, with the angles at `angles`.
struct JointCase {
  std::string label;
  std::shared_ptr<const Constraint> joint;
  int n = 0;
  std::vector<int> angles;
  int body1_offset = 0;
  Eigen::Vector2d s1 = Eigen::Vector2d::Zero();
};

Eigen::VectorXd random_q(std::mt19937& rng, const JointCase& c) {
  Eigen::VectorXd q = random_vector(rng, c.n, -1.5, 1.5);
  for (int a : c.angles) q[a] = uniform(rng, -kPi, kPi);
  return q;
}

const Eigen::Vector2d kS1(0.45, -0.25);  // body-1 point, off the centre of mass
const Eigen::Vector2d kS2(-0.3, 0.55);   // body-2 point, off the centre of mass
const Eigen::Vector2d kLineOrigin(0.2, -0.7), kLineDirection(0.8, 0.6);
const Eigen::Vector2d kGroundPoint(1.2, -0.4);
const Eigen::Vector2d kBodyAxis(2.0, 1.0);  // not unit: the joint normalizes it

std::vector<JointCase> revolute_cases() {
  const Node r = rigid_node_at_origin(), p = particle_node_at_origin(), l = line_node_at_origin(kLineOrigin, kLineDirection);
  std::vector<JointCase> cases;
  cases.push_back({"rigid-rigid",
                   std::make_shared<RevoluteJoint2D>("pin", std::vector<int>{0, 1}, PlanarMarker::on_node(r, kS1, 0),
                                                     PlanarMarker::on_node(r, kS2, 3)),
                   6, {2, 5}, 0, kS1});
  cases.push_back({"rigid-ground",
                   std::make_shared<RevoluteJoint2D>("pin", std::vector<int>{0}, PlanarMarker::on_node(r, kS1, 0),
                                                     PlanarMarker::ground(kGroundPoint)),
                   3, {2}, 0, kS1});
  cases.push_back({"rigid-particle",
                   std::make_shared<RevoluteJoint2D>("pin", std::vector<int>{0, 1}, PlanarMarker::on_node(r, kS1, 0),
                                                     PlanarMarker::on_node(p, Eigen::Vector2d::Zero(), 3)),
                   5, {2}, 0, kS1});
  cases.push_back({"rigid-line particle",
                   std::make_shared<RevoluteJoint2D>("pin", std::vector<int>{0, 1}, PlanarMarker::on_node(r, kS1, 0),
                                                     PlanarMarker::on_node(l, Eigen::Vector2d::Zero(), 3)),
                   4, {2}, 0, kS1});
  // Same rigid-rigid pin with the nodes stored in the other order in the local vector.
  cases.push_back({"rigid-rigid, body 2 first in the local vector",
                   std::make_shared<RevoluteJoint2D>("pin", std::vector<int>{1, 0}, PlanarMarker::on_node(r, kS1, 3),
                                                     PlanarMarker::on_node(r, kS2, 0)),
                   6, {2, 5}, 3, kS1});
  return cases;
}

std::vector<JointCase> point_on_line_cases() {
  const Node r = rigid_node_at_origin();
  std::vector<JointCase> cases;
  cases.push_back({"body 2 rigid and rotated",
                   std::make_shared<PointOnLineJoint2D>("line", std::vector<int>{0, 1},
                                                        PlanarMarker::on_node(r, kS1, 0),
                                                        PlanarMarker::on_node(r, kS2, 3), kBodyAxis),
                   6, {2, 5}, 0, kS1});
  cases.push_back({"body 2 ground",
                   std::make_shared<PointOnLineJoint2D>("line", std::vector<int>{0}, PlanarMarker::on_node(r, kS1, 0),
                                                        PlanarMarker::ground(kGroundPoint), kBodyAxis),
                   3, {2}, 0, kS1});
  cases.push_back({"body 2 rigid and rotated, body 2 first in the local vector",
                   std::make_shared<PointOnLineJoint2D>("line", std::vector<int>{1, 0},
                                                        PlanarMarker::on_node(r, kS1, 3),
                                                        PlanarMarker::on_node(r, kS2, 0), kBodyAxis),
                   6, {2, 5}, 3, kS1});
  return cases;
}

/// Point-on-line with a particle as body 1 (no angle): only the FD checks apply.
JointCase point_on_line_particle_case() {
  const Node r = rigid_node_at_origin(), p = particle_node_at_origin();
  return {"body 1 particle, body 2 rigid and rotated",
          std::make_shared<PointOnLineJoint2D>("line", std::vector<int>{0, 1},
                                               PlanarMarker::on_node(p, Eigen::Vector2d::Zero(), 0),
                                               PlanarMarker::on_node(r, kS2, 2), kBodyAxis),
          5, {4}, -1, Eigen::Vector2d::Zero()};
}

std::vector<JointCase> prismatic_cases() {
  const Node r = rigid_node_at_origin();
  std::vector<JointCase> cases;
  cases.push_back({"rigid-rigid",
                   std::make_shared<PrismaticJoint2D>("slider", std::vector<int>{0, 1},
                                                      PlanarMarker::on_node(r, kS1, 0),
                                                      PlanarMarker::on_node(r, kS2, 3), kBodyAxis, 0.4),
                   6, {2, 5}, 0, kS1});
  cases.push_back({"rigid-ground",
                   std::make_shared<PrismaticJoint2D>("slider", std::vector<int>{0}, PlanarMarker::on_node(r, kS1, 0),
                                                      PlanarMarker::ground(kGroundPoint), kBodyAxis, 0.4),
                   3, {2}, 0, kS1});
  return cases;
}

// ------------------------------------------------------------------ evaluation and FD
Eigen::VectorXd phi_of(const Constraint& c, const Eigen::VectorXd& q) {
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  c.evaluate(q, 0.0, phi, phi_q);
  return phi;
}

Eigen::MatrixXd phi_q_of(const Constraint& c, const Eigen::VectorXd& q) {
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  c.evaluate(q, 0.0, phi, phi_q);
  return phi_q;
}

/// Central-difference ∂f/∂q column by column, h = 1e-6 max(1, |q_j|) (test_support.hpp).
using alphaflex::testing::central_differences;

/// d²/ds² Φ(q + s v) at s = 0: central second difference, Richardson-extrapolated (O(h⁴)).
Eigen::VectorXd fd_second_derivative_along(const Constraint& c, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const auto second = [&](double h) {
    return ((phi_of(c, q + h * v) - 2.0 * phi_of(c, q) + phi_of(c, q - h * v)) / (h * h)).eval();
  };
  const double h = 1e-2;
  return (4.0 * second(h / 2) - second(h)) / 3.0;
}

/// d/ds [Φ_q(q + s v) v] at s = 0 = (Φ_q q̇)_q q̇: central first difference.
Eigen::VectorXd fd_derivative_of_phi_q_v(const Constraint& c, const Eigen::VectorXd& q, const Eigen::VectorXd& v) {
  const double h = 1e-6;
  return (phi_q_of(c, q + h * v) * v - phi_q_of(c, q - h * v) * v) / (2.0 * h);
}

double floored_discrepancy(const Eigen::MatrixXd& A, const Eigen::MatrixXd& A_fd, double floor) {
  return (A - A_fd).norm() / std::max({A.norm(), floor, DBL_MIN});
}

const Eigen::IOFormat kFmt(6, 0, " ", "\n", "  [", "]");

void joint_report(const std::string& what, const std::string& label, double worst) {
  std::printf("[ FD       ] max rel. discrepancy %.1e  %s, %s\n", worst, what.c_str(), label.c_str());
}

// ------------------------------------------------------------------ the checks, per case
void check_constraint_jacobian(const JointCase& c, unsigned seed) {
  std::mt19937 rng(seed);
  double worst = 0.0;
  for (int i = 0; i < kJointSamples; ++i) {
    SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
    const Eigen::VectorXd q = random_q(rng, c);
    Eigen::VectorXd phi;
    Eigen::MatrixXd phi_q;
    c.joint->evaluate(q, 0.0, phi, phi_q);
    ASSERT_EQ(phi.size(), c.joint->size());
    ASSERT_EQ(phi_q.rows(), c.joint->size());
    ASSERT_EQ(phi_q.cols(), c.n);
    const Eigen::MatrixXd fd = central_differences([&](const Eigen::VectorXd& x) { return phi_of(*c.joint, x); }, q);
    const double d = floored_discrepancy(phi_q, fd, 0.0);
    worst = std::max(worst, d);
    EXPECT_LT(d, kJointRelTol) << "Φ_q analytic:\n" << phi_q.format(kFmt) << "\nFD:\n" << fd.format(kFmt)
                          << "\nat q = " << q.transpose();
  }
  joint_report("Φ_q", c.label, worst);
}

void check_geometric_stiffness(const JointCase& c, unsigned seed) {
  std::mt19937 rng(seed);
  double worst = 0.0;
  for (int i = 0; i < kJointSamples; ++i) {
    SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
    const Eigen::VectorXd q = random_q(rng, c);
    const Eigen::VectorXd lambda = random_vector(rng, c.joint->size(), -5.0, 5.0);
    Eigen::MatrixXd k;
    c.joint->geometric_stiffness(q, 0.0, lambda, k);
    ASSERT_EQ(k.rows(), c.n);
    ASSERT_EQ(k.cols(), c.n);
    const Eigen::MatrixXd fd = central_differences(
        [&](const Eigen::VectorXd& x) { return (phi_q_of(*c.joint, x).transpose() * lambda).eval(); }, q);
    // Φ_q is O(1) here: floor the norm at 1e-3 |λ| for configurations where k nearly vanishes.
    const double d = floored_discrepancy(k, fd, 1e-3 * lambda.norm());
    worst = std::max(worst, d);
    EXPECT_LT(d, kJointRelTol) << "∂(Φ_qᵀλ)/∂q analytic:\n" << k.format(kFmt) << "\nFD:\n" << fd.format(kFmt)
                          << "\nat q = " << q.transpose() << ", λ = " << lambda.transpose();
    // A Hessian of λᵀΦ: symmetric.
    EXPECT_LE((k - k.transpose()).norm(), 1e-14 * std::max(1.0, k.norm())) << "k is not symmetric:\n" << k;
  }
  joint_report("∂(Φ_qᵀλ)/∂q", c.label, worst);
}

void check_acceleration_term(const JointCase& c, unsigned seed) {
  std::mt19937 rng(seed);
  double worst1 = 0.0, worst2 = 0.0;
  for (int i = 0; i < kJointSamples; ++i) {
    SCOPED_TRACE(c.label + ", random state #" + std::to_string(i));
    const Eigen::VectorXd q = random_q(rng, c);
    const Eigen::VectorXd v = random_vector(rng, c.n, -2.0, 2.0);
    Eigen::VectorXd acc;
    c.joint->acceleration_term(q, v, 0.0, acc);
    ASSERT_EQ(acc.size(), c.joint->size());
    const double floor = 1e-3 * v.squaredNorm();
    const Eigen::VectorXd fd2 = fd_second_derivative_along(*c.joint, q, v);
    const Eigen::VectorXd fd1 = fd_derivative_of_phi_q_v(*c.joint, q, v);
    const double d2 = floored_discrepancy(acc, fd2, floor), d1 = floored_discrepancy(acc, fd1, floor);
    worst1 = std::max(worst1, d1);
    worst2 = std::max(worst2, d2);
    EXPECT_LT(d2, kJointRelTol) << "acceleration term " << acc.transpose() << " vs d²Φ(q + s q̇)/ds² (FD) "
                           << fd2.transpose() << "\nat q = " << q.transpose() << ", q̇ = " << v.transpose();
    EXPECT_LT(d1, kJointRelTol) << "acceleration term " << acc.transpose() << " vs d/ds Φ_q(q + s q̇) q̇ (FD) "
                           << fd1.transpose() << "\nat q = " << q.transpose() << ", q̇ = " << v.transpose();
    // Scleronomic: Φ_t = 0.
    Eigen::VectorXd phi_t;
    c.joint->time_derivative(q, 0.0, phi_t);
    EXPECT_LE(phi_t.size() == 0 ? 0.0 : phi_t.norm(), 0.0);
  }
  joint_report("c vs d²Φ(q+sq̇)/ds²", c.label, worst2);
  joint_report("c vs d/ds Φ_q(q+sq̇) q̇", c.label, worst1);
}

/// The reaction on body 1 is the generalized force −Φ_{q1}ᵀλ read as a force F at the joint point
/// and a moment M_z: −Φ_{q1}ᵀλ = [F; (r_point − x_cm) × F + M_z] (virtual work on the rigid body 1).
void check_reaction_virtual_work(const JointCase& c, unsigned seed) {
  std::mt19937 rng(seed);
  for (int i = 0; i < kJointSamples; ++i) {
    SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
    const Eigen::VectorXd q = random_q(rng, c);
    const Eigen::VectorXd lambda = random_vector(rng, c.joint->size(), -5.0, 5.0);
    const JointReaction r = c.joint->reaction(q, 0.0, lambda);
    const int o = c.body1_offset;
    const Eigen::Vector2d x_cm(q[o], q[o + 1]);
    const Eigen::Vector2d point = body_point(x_cm, q[o + 2], c.s1);
    EXPECT_LE((r.location.head<2>() - point).norm(), 1e-14 * std::max(1.0, point.norm()))
        << "reaction location " << r.location.transpose() << ", body-1 joint point " << point.transpose();
    EXPECT_EQ(r.location.z(), 0.0);
    EXPECT_EQ(r.force.z(), 0.0);
    EXPECT_EQ(r.moment.x(), 0.0);
    EXPECT_EQ(r.moment.y(), 0.0);

    const Eigen::Vector3d generalized = -phi_q_of(*c.joint, q).middleCols(o, 3).transpose() * lambda;
    const Eigen::Vector2d arm = r.location.head<2>() - x_cm;
    const Eigen::Vector3d from_reaction(r.force.x(), r.force.y(),
                                        arm.x() * r.force.y() - arm.y() * r.force.x() + r.moment.z());
    EXPECT_LE((generalized - from_reaction).norm(), 1e-12 * std::max(1.0, generalized.norm()))
        << "−Φ_q1ᵀλ = " << generalized.transpose() << "\n[F; a × F + M] = " << from_reaction.transpose();
  }
}

void expect_same_vector(const Eigen::VectorXd& actual, const Eigen::VectorXd& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  EXPECT_LE((actual - expected).norm(), kJointValueTol * std::max(1.0, expected.norm()))
      << "actual:   " << actual.transpose() << "\nexpected: " << expected.transpose();
}

}  // namespace

// =================================================================== RevoluteJoint2D
// Φ = r1 − r2

TEST(RevoluteJoint2D, ConstraintJacobianMatchesFiniteDifferences) {
  unsigned seed = 1000;
  for (const JointCase& c : revolute_cases()) check_constraint_jacobian(c, seed++);
}

TEST(RevoluteJoint2D, GeometricStiffnessMatchesFiniteDifferencesOfPhiQTransposeLambda) {
  unsigned seed = 1100;
  for (const JointCase& c : revolute_cases()) check_geometric_stiffness(c, seed++);
}

TEST(RevoluteJoint2D, AccelerationTermIsSecondDerivativeOfPhiAlongVelocity) {
  unsigned seed = 1200;
  for (const JointCase& c : revolute_cases()) check_acceleration_term(c, seed++);
}

TEST(RevoluteJoint2D, ReactionIsMinusLambdaAndSatisfiesVirtualWorkOnBody1) {
  unsigned seed = 1300;
  for (const JointCase& c : revolute_cases()) {
    check_reaction_virtual_work(c, seed++);
    const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(c.n, 0.1, 0.9);
    const JointReaction r = c.joint->reaction(q, 0.0, vec({3.0, -7.0}));
    EXPECT_EQ(r.force, Eigen::Vector3d(-3.0, 7.0, 0.0)) << c.label;
    EXPECT_EQ(r.moment, Eigen::Vector3d::Zero()) << c.label;
  }
}

TEST(RevoluteJoint2D, PhiVanishesWhenPointsCoincideAndEqualsTheShiftOtherwise) {
  const double th1 = 0.3, th2 = -0.8;
  const Eigen::Vector2d x1(1.0, 2.0), delta(0.1, -0.25);
  const Eigen::Vector2d p = body_point(x1, th1, kS1);  // the pin point when assembled
  const std::vector<JointCase> cases = revolute_cases();
  for (const JointCase& c : cases) {
    SCOPED_TRACE(c.label);
    Eigen::VectorXd q(c.n);
    Eigen::VectorXd shifted;
    if (c.label == "rigid-rigid") {
      const Eigen::Vector2d x2 = p - (body_point(Eigen::Vector2d::Zero(), th2, kS2));
      q << x1, th1, x2, th2;
    } else if (c.label == "rigid-ground") {
      const Eigen::Vector2d x = kGroundPoint - body_point(Eigen::Vector2d::Zero(), th1, kS1);
      q << x, th1;
    } else if (c.label == "rigid-particle") {
      q << x1, th1, p;
    } else if (c.label == "rigid-line particle") {
      // The line particle at s = 1.5 sits at origin + 1.5 u; body 1 placed so that its point is there.
      const double s = 1.5;
      const Eigen::Vector2d on_line = kLineOrigin + s * kLineDirection.normalized();
      q << on_line - body_point(Eigen::Vector2d::Zero(), th1, kS1), th1, s;
      // Moving the line particle by ε along its line gives Φ = −ε u.
      Eigen::VectorXd q2 = q;
      q2[3] += 0.2;
      expect_same_vector(phi_of(*c.joint, q2), -0.2 * kLineDirection.normalized());
    } else {
      continue;  // the reordered variant is covered by the FD checks
    }
    expect_same_vector(phi_of(*c.joint, q), Eigen::Vector2d::Zero());
    shifted = q;
    shifted.head<2>() += delta;  // translate body 1 by δ
    expect_same_vector(phi_of(*c.joint, shifted), delta);
  }
}

// =================================================================== PointOnLineJoint2D
// Φ = n·(r1 − r2), n = R(θ2) perp(axis/|axis|)

TEST(PointOnLineJoint2D, ConstraintJacobianMatchesFiniteDifferences) {
  unsigned seed = 2000;
  for (const JointCase& c : point_on_line_cases()) check_constraint_jacobian(c, seed++);
  check_constraint_jacobian(point_on_line_particle_case(), seed++);
}

TEST(PointOnLineJoint2D, GeometricStiffnessMatchesFiniteDifferencesOfPhiQTransposeLambda) {
  unsigned seed = 2100;
  for (const JointCase& c : point_on_line_cases()) check_geometric_stiffness(c, seed++);
  check_geometric_stiffness(point_on_line_particle_case(), seed++);
}

TEST(PointOnLineJoint2D, AccelerationTermIsSecondDerivativeOfPhiAlongVelocity) {
  unsigned seed = 2200;
  for (const JointCase& c : point_on_line_cases()) check_acceleration_term(c, seed++);
  check_acceleration_term(point_on_line_particle_case(), seed++);
}

TEST(PointOnLineJoint2D, ReactionIsMinusLambdaTimesNormalAndSatisfiesVirtualWorkOnBody1) {
  unsigned seed = 2300;
  for (const JointCase& c : point_on_line_cases()) check_reaction_virtual_work(c, seed++);
  // Ground line along (2, 1)/√5: n = (−1, 2)/√5, so λ = 2 gives F = −2 n = (2, −4)/√5, no moment.
  const JointCase ground = point_on_line_cases()[1];
  const JointReaction r = ground.joint->reaction(vec({0.3, 0.1, 0.2}), 0.0, vec({2.0}));
  EXPECT_NEAR(r.force.x(), 2.0 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(r.force.y(), -4.0 / std::sqrt(5.0), 1e-15);
  EXPECT_EQ(r.moment, Eigen::Vector3d::Zero());
}

TEST(PointOnLineJoint2D, PhiIsTheNormalDistanceOfPoint1FromTheLine) {
  const Eigen::Vector2d a = kBodyAxis.normalized();
  {
    SCOPED_TRACE("body 2 rigid and rotated");
    const JointCase c = point_on_line_cases()[0];
    const double th1 = -0.6, th2 = 0.7;
    const Eigen::Vector2d x2(0.5, -0.3);
    const Eigen::Vector2d p2 = body_point(x2, th2, kS2);
    const Eigen::Vector2d t(std::cos(th2) * a.x() - std::sin(th2) * a.y(),
                            std::sin(th2) * a.x() + std::cos(th2) * a.y());
    const Eigen::Vector2d n(-t.y(), t.x());
    // Point 1 on the line, 1.3 along it: Φ = 0; moved along the line: still 0; off it by δ n: Φ = δ.
    const Eigen::Vector2d p1 = p2 + 1.3 * t;
    Eigen::VectorXd q(6);
    q << p1 - body_point(Eigen::Vector2d::Zero(), th1, kS1), th1, x2, th2;
    expect_same_vector(phi_of(*c.joint, q), vec({0.0}));
    Eigen::VectorXd q_along = q, q_off = q;
    q_along.head<2>() += 0.8 * t;
    q_off.head<2>() += 0.25 * n;
    expect_same_vector(phi_of(*c.joint, q_along), vec({0.0}));
    expect_same_vector(phi_of(*c.joint, q_off), vec({0.25}));
    // Rotating body 2 by π about point 2 flips the line's normal: Φ = −δ.
    Eigen::VectorXd q_flip = q_off;
    q_flip.segment<2>(3) = p2 - body_point(Eigen::Vector2d::Zero(), th2 + kPi, kS2);
    q_flip[5] = th2 + kPi;
    expect_same_vector(phi_of(*c.joint, q_flip), vec({-0.25}));
  }
  {
    SCOPED_TRACE("body 2 ground");
    const JointCase c = point_on_line_cases()[1];
    const Eigen::Vector2d n(-a.y(), a.x());
    const double th1 = 1.1;
    Eigen::VectorXd q(3);
    q << kGroundPoint - 2.0 * a - body_point(Eigen::Vector2d::Zero(), th1, kS1), th1;
    expect_same_vector(phi_of(*c.joint, q), vec({0.0}));
    Eigen::VectorXd q_off = q;
    q_off.head<2>() += -0.4 * n + 3.0 * a;
    expect_same_vector(phi_of(*c.joint, q_off), vec({-0.4}));
  }
}

// =================================================================== PrismaticJoint2D
// Φ = [n·(r1 − r2); θ1 − θ2 − θ0]

TEST(PrismaticJoint2D, ConstraintJacobianMatchesFiniteDifferences) {
  unsigned seed = 3000;
  for (const JointCase& c : prismatic_cases()) check_constraint_jacobian(c, seed++);
}

TEST(PrismaticJoint2D, GeometricStiffnessMatchesFiniteDifferencesOfPhiQTransposeLambda) {
  unsigned seed = 3100;
  for (const JointCase& c : prismatic_cases()) check_geometric_stiffness(c, seed++);
}

TEST(PrismaticJoint2D, AccelerationTermIsSecondDerivativeOfPhiAlongVelocity) {
  unsigned seed = 3200;
  for (const JointCase& c : prismatic_cases()) check_acceleration_term(c, seed++);
}

TEST(PrismaticJoint2D, ReactionIsForceAlongNormalPlusMomentAndSatisfiesVirtualWorkOnBody1) {
  unsigned seed = 3300;
  for (const JointCase& c : prismatic_cases()) check_reaction_virtual_work(c, seed++);
  // Ground rail along (2, 1)/√5: λ = (2, 1.5) → F = −2 n = (2, −4)/√5 and M_z = −1.5.
  const JointCase ground = prismatic_cases()[1];
  const JointReaction r = ground.joint->reaction(vec({0.3, 0.1, 0.2}), 0.0, vec({2.0, 1.5}));
  EXPECT_NEAR(r.force.x(), 2.0 / std::sqrt(5.0), 1e-15);
  EXPECT_NEAR(r.force.y(), -4.0 / std::sqrt(5.0), 1e-15);
  EXPECT_EQ(r.moment, Eigen::Vector3d(0.0, 0.0, -1.5));
}

TEST(PrismaticJoint2D, PhiIsNormalDistanceAndRelativeAngleError) {
  const Eigen::Vector2d a = kBodyAxis.normalized();
  const double theta0 = 0.4;
  {
    SCOPED_TRACE("rigid-rigid");
    const JointCase c = prismatic_cases()[0];
    const double th2 = 0.7, th1 = th2 + theta0;
    const Eigen::Vector2d x2(0.5, -0.3);
    const Eigen::Vector2d p2 = body_point(x2, th2, kS2);
    const Eigen::Vector2d t(std::cos(th2) * a.x() - std::sin(th2) * a.y(),
                            std::sin(th2) * a.x() + std::cos(th2) * a.y());
    const Eigen::Vector2d n(-t.y(), t.x());
    Eigen::VectorXd q(6);
    q << p2 - 0.9 * t - body_point(Eigen::Vector2d::Zero(), th1, kS1), th1, x2, th2;
    expect_same_vector(phi_of(*c.joint, q), vec({0.0, 0.0}));
    Eigen::VectorXd q_off = q;
    q_off.head<2>() += 0.3 * n + 2.0 * t;  // sliding along the rail is free
    expect_same_vector(phi_of(*c.joint, q_off), vec({0.3, 0.0}));
    Eigen::VectorXd q_turn = q;
    q_turn[2] += 0.05;  // body 1 turned by ε: second equation = ε
    EXPECT_NEAR(phi_of(*c.joint, q_turn)[1], 0.05, 1e-15);
    q_turn = q;
    q_turn[5] += 0.05;  // body 2 turned by ε: second equation = −ε
    EXPECT_NEAR(phi_of(*c.joint, q_turn)[1], -0.05, 1e-15);
  }
  {
    SCOPED_TRACE("rigid-ground");
    const JointCase c = prismatic_cases()[1];
    const Eigen::Vector2d n(-a.y(), a.x());
    Eigen::VectorXd q(3);
    q << kGroundPoint + 1.7 * a - body_point(Eigen::Vector2d::Zero(), theta0, kS1), theta0;
    expect_same_vector(phi_of(*c.joint, q), vec({0.0, 0.0}));
    Eigen::VectorXd q_off = q;
    q_off.head<2>() += 0.15 * n;
    q_off[2] = theta0 - 0.2;  // also turned, about the centre of mass: the point moves as well
    Eigen::VectorXd expected(2);
    expected << n.dot(body_point(q_off.head<2>(), q_off[2], kS1) - kGroundPoint), -0.2;
    expect_same_vector(phi_of(*c.joint, q_off), expected);
    Eigen::VectorXd q_shift = q;
    q_shift.head<2>() += 0.15 * n;
    expect_same_vector(phi_of(*c.joint, q_shift), vec({0.15, 0.0}));
  }
}

// =================================================================== FixedJoint2D
// Φ = [r1 − r2; θ1 − θ2 − θ0] (clamp of a beam end, or a weld).
namespace {

std::vector<JointCase> fixed_cases() {
  const Node r = rigid_node_at_origin();
  std::vector<JointCase> cases;
  cases.push_back({"rigid-rigid", std::make_shared<FixedJoint2D>("weld", std::vector<int>{0, 1},
                                                                  PlanarMarker::on_node(r, kS1, 0),
                                                                  PlanarMarker::on_node(r, kS2, 3), 0.4),
                   6, {2, 5}, 0, kS1});
  cases.push_back({"rigid-ground", std::make_shared<FixedJoint2D>("clamp", std::vector<int>{0},
                                                                   PlanarMarker::on_node(r, kS1, 0),
                                                                   PlanarMarker::ground(kGroundPoint), 0.4),
                   3, {2}, 0, kS1});
  return cases;
}

TEST(FixedJoint2D, ConstraintJacobianMatchesFiniteDifferences) {
  unsigned seed = 4000;
  for (const JointCase& c : fixed_cases()) check_constraint_jacobian(c, seed++);
}

TEST(FixedJoint2D, GeometricStiffnessMatchesFiniteDifferencesOfPhiQTransposeLambda) {
  unsigned seed = 4100;
  for (const JointCase& c : fixed_cases()) check_geometric_stiffness(c, seed++);
}

TEST(FixedJoint2D, AccelerationTermIsSecondDerivativeOfPhiAlongVelocity) {
  unsigned seed = 4200;
  for (const JointCase& c : fixed_cases()) check_acceleration_term(c, seed++);
}

TEST(FixedJoint2D, ReactionIsMinusLambdaAndSatisfiesVirtualWorkOnBody1) {
  unsigned seed = 4300;
  for (const JointCase& c : fixed_cases()) check_reaction_virtual_work(c, seed++);
  const JointReaction r = fixed_cases()[1].joint->reaction(vec({0.3, 0.1, 0.2}), 0.0, vec({2.0, -1.0, 1.5}));
  EXPECT_EQ(r.force, Eigen::Vector3d(-2.0, 1.0, 0.0));
  EXPECT_EQ(r.moment, Eigen::Vector3d(0.0, 0.0, -1.5));
}

// The table of planar joint kinds names each equation of Φ: its rows must have as many names as
// evaluate() gives equations, and the messages print them.
TEST(PlanarJointKinds, EquationNamesMatchTheEquationsOfPhi) {
  std::mt19937 rng(4400);
  std::vector<JointCase> all = revolute_cases();
  for (const auto& cases : {point_on_line_cases(), prismatic_cases(), fixed_cases()}) all.insert(all.end(), cases.begin(), cases.end());
  for (const JointCase& c : all) {
    SCOPED_TRACE(std::string(c.joint->type()) + ": " + c.label);
    const Eigen::VectorXd phi = phi_of(*c.joint, random_q(rng, c));
    ASSERT_EQ(phi.size(), c.joint->size());
    for (int k = 0; k < c.joint->size(); ++k) EXPECT_FALSE(c.joint->equation_name(k).empty());
  }
  const auto names = [](PlanarJointType t) { return planar_joint_kinds()[static_cast<size_t>(t)].equations; };
  EXPECT_EQ(names(PlanarJointType::revolute), (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(names(PlanarJointType::point_on_line), (std::vector<std::string>{"n·(r1 − r2)"}));
  EXPECT_EQ(names(PlanarJointType::prismatic), (std::vector<std::string>{"n·(r1 − r2)", "θ1 − θ2"}));
  EXPECT_EQ(names(PlanarJointType::fixed), (std::vector<std::string>{"x", "y", "θ1 − θ2"}));
  EXPECT_EQ(std::string(fixed_cases()[0].joint->type()), "fixed");
  EXPECT_EQ(fixed_cases()[0].joint->equation_label(2), "equation 3 (θ1 − θ2)");
  EXPECT_EQ(std::string(prismatic_cases()[0].joint->type()), "prismatic");
}

}  // namespace
}  // namespace alphaflex
