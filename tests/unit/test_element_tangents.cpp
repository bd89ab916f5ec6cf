// Element residual r = M(q) q̈ − g(q, q̇, t): tangents K = ∂r/∂q, C = ∂r/∂q̇, M = ∂r/∂q̈ against central differences of r, and r itself against hand-computed values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <random>
#include <string>

#include "alphaflex/core/time_function.hpp"
#include "alphaflex/elements/applied_load_2d.hpp"
#include "alphaflex/elements/rigid_body_2d.hpp"
#include "alphaflex/elements/spring_damper_2d.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/node.hpp"
#include "alphaflex/model/planar_marker.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

constexpr double kRelTol = 1e-6;    // FD tangent vs analytic, relative to the matrix norm
constexpr double kValueTol = 1e-12; // hand-computed residuals (relative)
constexpr int kSamples = 10;        // random states per element
using testing::kPi;
using testing::random_vector;
using testing::uniform;
using testing::vec;

// ------------------------------------------------------------------ nodes
Node rigid_node(const Eigen::Vector3d& q0) {
  Node n;
  n.name = "rigid";
  n.kind = NodeKind::RigidBody2D;
  n.ndof = Node::dofs_of(n.kind);
  n.q0 = q0;
  n.v0 = Eigen::VectorXd::Zero(3);
  return n;
}

Node particle_node(const Eigen::Vector2d& q0) {
  Node n;
  n.name = "particle";
  n.kind = NodeKind::Particle2D;
  n.ndof = Node::dofs_of(n.kind);
  n.q0 = q0;
  n.v0 = Eigen::VectorXd::Zero(2);
  return n;
}

Node line_node(const Eigen::Vector2d& origin, const Eigen::Vector2d& direction, double s0) {
  Node n;
  n.name = "line_particle";
  n.kind = NodeKind::LineParticle2D;
  n.ndof = Node::dofs_of(n.kind);
  n.q0 = Eigen::VectorXd::Constant(1, s0);
  n.v0 = Eigen::VectorXd::Zero(1);
  n.line_origin = origin;
  n.line_direction = direction.normalized();
  return n;
}

// ------------------------------------------------------------------ residual and tangents
Eigen::VectorXd residual(const Element& e, const LocalState& s) {
  LocalResidual out;
  out.reset(static_cast<int>(s.q.size()), false);
  e.evaluate(s, out, false);
  return out.r;
}

LocalResidual tangents(const Element& e, const LocalState& s) {
  LocalResidual out;
  out.reset(static_cast<int>(s.q.size()), true);
  e.evaluate(s, out, true);
  return out;
}

using alphaflex::testing::Wrt;

/// Central difference ∂r/∂x, x ∈ {q, q̇, q̈} (test_support.hpp's step rule h = 1e-6 max(1, |x_j|)).
Eigen::MatrixXd fd_jacobian(const Element& e, const LocalState& s, Wrt w) {
  return alphaflex::testing::central_differences(alphaflex::testing::element_residual_of(e, s, w),
                                                  alphaflex::testing::variable(s, w));
}

/// ‖A − A_fd‖ / ‖A‖, with ‖A‖ floored at 1e-3 of the element's largest tangent so that a tangent
/// that is (correctly) zero is compared on the element's scale.
double relative_discrepancy(const Eigen::MatrixXd& A, const Eigen::MatrixXd& A_fd, double scale) {
  const double denom = std::max({A.norm(), 1e-3 * scale, DBL_MIN});
  return (A - A_fd).norm() / denom;
}

struct Discrepancy {
  double K = 0.0, C = 0.0, M = 0.0;
};

/// Compares K, C, M with central differences of r at one state; returns the relative discrepancies.
Discrepancy check_tangents_at(const Element& e, const LocalState& s) {
  const LocalResidual t = tangents(e, s);
  const Eigen::VectorXd r = residual(e, s);
  EXPECT_LE((t.r - r).norm(), 1e-14 * std::max(1.0, r.norm()))
      << "r differs between evaluate(tangent = true) and evaluate(tangent = false)";
  const double scale = std::max({t.K.norm(), t.C.norm(), t.M.norm()});
  const Eigen::MatrixXd K_fd = fd_jacobian(e, s, Wrt::q);
  const Eigen::MatrixXd C_fd = fd_jacobian(e, s, Wrt::v);
  const Eigen::MatrixXd M_fd = fd_jacobian(e, s, Wrt::qdd);
  Discrepancy d;
  d.K = relative_discrepancy(t.K, K_fd, scale);
  d.C = relative_discrepancy(t.C, C_fd, scale);
  d.M = relative_discrepancy(t.M, M_fd, scale);
  const Eigen::IOFormat fmt(6, 0, " ", "\n", "  [", "]");
  EXPECT_LT(d.K, kRelTol) << "K = ∂r/∂q\nanalytic:\n" << t.K.format(fmt) << "\nFD:\n" << K_fd.format(fmt)
                          << "\nat q = " << s.q.transpose() << ", v = " << s.v.transpose();
  EXPECT_LT(d.C, kRelTol) << "C = ∂r/∂q̇\nanalytic:\n" << t.C.format(fmt) << "\nFD:\n" << C_fd.format(fmt)
                          << "\nat q = " << s.q.transpose() << ", v = " << s.v.transpose();
  EXPECT_LT(d.M, kRelTol) << "M = ∂r/∂q̈\nanalytic:\n" << t.M.format(fmt) << "\nFD:\n" << M_fd.format(fmt)
                          << "\nat q = " << s.q.transpose() << ", v = " << s.v.transpose();
  return d;
}

using Sampler = std::function<LocalState(std::mt19937&)>;

/// Runs check_tangents_at over kSamples seeded random states and prints the worst discrepancies.
void check_tangents(const Element& e, const Sampler& sample, const std::string& label, unsigned seed) {
  std::mt19937 rng(seed);
  Discrepancy worst;
  for (int i = 0; i < kSamples; ++i) {
    SCOPED_TRACE(label + ", random state #" + std::to_string(i));
    const Discrepancy d = check_tangents_at(e, sample(rng));
    worst.K = std::max(worst.K, d.K);
    worst.C = std::max(worst.C, d.C);
    worst.M = std::max(worst.M, d.M);
  }
  std::printf("[ FD       ] max rel. discrepancy  K %.1e  C %.1e  M %.1e  %s\n", worst.K, worst.C, worst.M,
              label.c_str());
}

/// A random state of n local dofs: q = base + perturbation, angles at `angles` uniform in (−π, π).
LocalState random_state(std::mt19937& rng, const Eigen::VectorXd& base, const std::vector<int>& angles) {
  const int n = static_cast<int>(base.size());
  LocalState s;
  s.q = base + random_vector(rng, n, -0.5, 0.5);
  for (int a : angles) s.q[a] = uniform(rng, -kPi, kPi);
  s.v = random_vector(rng, n, -2.0, 2.0);
  s.qdd = random_vector(rng, n, -3.0, 3.0);
  s.t = uniform(rng, 0.0, 2.0);
  return s;
}

LocalState state(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& qdd, double t = 0.0) {
  LocalState s;
  s.q = q;
  s.v = v;
  s.qdd = qdd;
  s.t = t;
  return s;
}

void expect_vector_near(const Eigen::VectorXd& actual, const Eigen::VectorXd& expected, double rel_tol) {
  ASSERT_EQ(actual.size(), expected.size());
  const double tol = rel_tol * std::max(1.0, expected.norm());
  EXPECT_LE((actual - expected).norm(), tol) << "actual:   " << actual.transpose()
                                             << "\nexpected: " << expected.transpose();
}

const Eigen::Vector2d kGravity(0.0, -9.81);

}  // namespace

// =================================================================== RigidBody2D
// r = diag(m, m, J) q̈ − [m g; 0]

TEST(RigidBody2D, TangentsKCMMatchFiniteDifferencesOfResidual) {
  const RigidBody2D body("body", 0, 2.5, 0.37, Eigen::Vector2d(0.3, -9.81));
  check_tangents(body, [](std::mt19937& rng) { return random_state(rng, vec({0.4, -1.0, 0.0}), {2}); },
                 "RigidBody2D (gravity)", 101);
}

TEST(RigidBody2D, ResidualIsMassTimesAccelerationMinusWeight) {
  const double m = 2.0, J = 0.5;
  const RigidBody2D body("body", 0, m, J, kGravity);
  // At rest the residual is minus the weight: r = [0, m·9.81, 0].
  expect_vector_near(residual(body, state(vec({1.0, 2.0, 0.3}), vec({0.7, -0.2, 4.0}), vec({0.0, 0.0, 0.0}))),
                     vec({0.0, m * 9.81, 0.0}), kValueTol);
  // Accelerating: r = [m ẍ, m (ÿ + 9.81), J θ̈], independent of q and q̇.
  expect_vector_near(residual(body, state(vec({-3.0, 0.1, 2.0}), vec({1.0, 1.0, -1.0}), vec({1.0, 2.0, 3.0}))),
                     vec({2.0 * 1.0, 2.0 * (2.0 + 9.81), 0.5 * 3.0}), kValueTol);
  const LocalResidual t = tangents(body, state(vec({0.0, 0.0, 0.0}), vec({0.0, 0.0, 0.0}), vec({0.0, 0.0, 0.0})));
  EXPECT_EQ(t.M, Eigen::Vector3d(m, m, J).asDiagonal().toDenseMatrix());
}

// =================================================================== PointMass
// r = m JᵀJ q̈ − Jᵀ m g with the constant point Jacobian J (I for a particle, u for a line particle).

TEST(PointMass, TangentsKCMMatchFiniteDifferencesOnParticle) {
  const Node node = particle_node(Eigen::Vector2d(0.5, 1.5));
  const PointMass mass("mass", 0, node, 1.7, kGravity);
  check_tangents(mass, [](std::mt19937& rng) { return random_state(rng, vec({0.5, 1.5}), {}); },
                 "PointMass on Particle2D (gravity)", 202);
}

TEST(PointMass, TangentsKCMMatchFiniteDifferencesOnLineParticle) {
  const Node node = line_node(Eigen::Vector2d(1.0, -2.0), Eigen::Vector2d(3.0, 4.0), 0.4);
  const PointMass mass("mass", 0, node, 1.7, kGravity);
  check_tangents(mass, [](std::mt19937& rng) { return random_state(rng, vec({0.4}), {}); },
                 "PointMass on LineParticle2D (gravity)", 203);
}

TEST(PointMass, ParticleResidualIsMassTimesAccelerationMinusWeight) {
  const double m = 3.0;
  const Node node = particle_node(Eigen::Vector2d(0.0, 0.0));
  const PointMass mass("mass", 0, node, m, kGravity);
  expect_vector_near(residual(mass, state(vec({5.0, -1.0}), vec({1.0, 2.0}), vec({0.5, -0.25}))),
                     vec({m * 0.5, m * (-0.25 + 9.81)}), kValueTol);
}

TEST(PointMass, LineParticleResidualIsMassTimesAccelerationMinusWeightAlongTheLine) {
  // Line direction u = (0.6, 0.8): the weight component along the line is m g·u = −0.8·9.81 m.
  const double m = 3.0;
  const Node node = line_node(Eigen::Vector2d(2.0, 1.0), Eigen::Vector2d(0.6, 0.8), 0.0);
  const PointMass mass("mass", 0, node, m, kGravity);
  expect_vector_near(residual(mass, state(vec({1.3}), vec({0.4}), vec({2.0}))), vec({m * 2.0 + m * 9.81 * 0.8}),
                     kValueTol);
  const LocalResidual t = tangents(mass, state(vec({1.3}), vec({0.4}), vec({2.0})));
  EXPECT_NEAR(t.M(0, 0), m, 1e-14);  // uᵀu = 1
}

// =================================================================== SpringDamper2D
// r = N Bᵀe, N = k (L − L0) + c L̇ (point to point), or e = u, L = u·(r1 − r2) (fixed axis).

namespace {

const double kStiffness = 80.0, kDamping = 3.0, kRest = 0.7;
const Eigen::Vector2d kAxis = Eigen::Vector2d(std::cos(0.4), std::sin(0.4));

std::optional<Eigen::Vector2d> axis_if(bool along_axis) {
  return along_axis ? std::optional<Eigen::Vector2d>(kAxis) : std::nullopt;
}

// (a) two rigid bodies, off-centre points; local vector [x1 y1 θ1 x2 y2 θ2].
void check_spring_rigid_rigid(bool along_axis, unsigned seed) {
  const Node b1 = rigid_node(Eigen::Vector3d(0.0, 0.0, 0.0)), b2 = rigid_node(Eigen::Vector3d(2.5, 1.0, 0.0));
  const PlanarMarker m1 = PlanarMarker::on_node(b1, Eigen::Vector2d(0.4, -0.2), 0);
  const PlanarMarker m2 = PlanarMarker::on_node(b2, Eigen::Vector2d(-0.3, 0.5), 3);
  const SpringDamper2D spring("spring", {0, 1}, m1, m2, kStiffness, kDamping, kRest, axis_if(along_axis));
  check_tangents(spring,
                 [](std::mt19937& rng) { return random_state(rng, vec({0.0, 0.0, 0.0, 2.5, 1.0, 0.0}), {2, 5}); },
                 std::string("SpringDamper2D ") + (along_axis ? "axis" : "point-to-point") + ", rigid-rigid", seed);
}

// (b) a rigid body and the ground; local vector [x y θ].
void check_spring_rigid_ground(bool along_axis, unsigned seed) {
  const Node b1 = rigid_node(Eigen::Vector3d(1.0, 0.5, 0.0));
  const PlanarMarker m1 = PlanarMarker::on_node(b1, Eigen::Vector2d(0.6, 0.3), 0);
  const PlanarMarker m2 = PlanarMarker::ground(Eigen::Vector2d(-1.0, 2.0));
  const SpringDamper2D spring("spring", {0}, m1, m2, kStiffness, kDamping, kRest, axis_if(along_axis));
  check_tangents(spring, [](std::mt19937& rng) { return random_state(rng, vec({1.0, 0.5, 0.0}), {2}); },
                 std::string("SpringDamper2D ") + (along_axis ? "axis" : "point-to-point") + ", rigid-ground", seed);
}

// (c) a particle and a line particle; local vector [x y s].
void check_spring_particle_line(bool along_axis, unsigned seed) {
  const Node p = particle_node(Eigen::Vector2d(1.0, 2.0));
  const Node l = line_node(Eigen::Vector2d(0.0, -1.0), Eigen::Vector2d(0.8, 0.6), 0.0);
  const PlanarMarker m1 = PlanarMarker::on_node(p, Eigen::Vector2d::Zero(), 0);
  const PlanarMarker m2 = PlanarMarker::on_node(l, Eigen::Vector2d::Zero(), 2);
  const SpringDamper2D spring("spring", {0, 1}, m1, m2, kStiffness, kDamping, kRest, axis_if(along_axis));
  check_tangents(spring, [](std::mt19937& rng) { return random_state(rng, vec({1.0, 2.0, 0.0}), {}); },
                 std::string("SpringDamper2D ") + (along_axis ? "axis" : "point-to-point") +
                     ", particle-line particle",
                 seed);
}

}  // namespace

TEST(SpringDamper2D, PointToPointTangentsMatchFiniteDifferencesBetweenTwoRigidBodies) {
  check_spring_rigid_rigid(false, 301);
}
TEST(SpringDamper2D, AxisTangentsMatchFiniteDifferencesBetweenTwoRigidBodies) { check_spring_rigid_rigid(true, 302); }
TEST(SpringDamper2D, PointToPointTangentsMatchFiniteDifferencesBetweenRigidBodyAndGround) {
  check_spring_rigid_ground(false, 303);
}
TEST(SpringDamper2D, AxisTangentsMatchFiniteDifferencesBetweenRigidBodyAndGround) {
  check_spring_rigid_ground(true, 304);
}
TEST(SpringDamper2D, PointToPointTangentsMatchFiniteDifferencesBetweenParticleAndLineParticle) {
  check_spring_particle_line(false, 305);
}
TEST(SpringDamper2D, AxisTangentsMatchFiniteDifferencesBetweenParticleAndLineParticle) {
  check_spring_particle_line(true, 306);
}

TEST(SpringDamper2D, PointToPointResidualIsTensionAlongTheSpringOnRigidBodyToGround) {
  // Body at (1, 0), θ = π/2, point s = (0.5, 0) → arm a = R s = (0, 0.5), point r1 = (1, 0.5).
  // Ground point (−2, 4.5): d = r1 − r2 = (3, −4), L = 5, e = (0.6, −0.8).
  // Static: N = k (L − L0) = 100 (5 − 4) = 100; r = N [e; a × e] = [60, −80, −30].
  const Node b = rigid_node(Eigen::Vector3d(1.0, 0.0, kPi / 2));
  const SpringDamper2D spring("spring", {0}, PlanarMarker::on_node(b, Eigen::Vector2d(0.5, 0.0), 0),
                              PlanarMarker::ground(Eigen::Vector2d(-2.0, 4.5)), 100.0, 10.0, 4.0, std::nullopt);
  const Eigen::VectorXd q = vec({1.0, 0.0, kPi / 2});
  EXPECT_NEAR(spring.length(q), 5.0, 1e-14);
  expect_vector_near(residual(spring, state(q, vec({0.0, 0.0, 0.0}), vec({0.0, 0.0, 0.0}))),
                     vec({60.0, -80.0, -30.0}), kValueTol);
  // Moving with ẋ = 1: L̇ = e·ḋ = 0.6, N = 100 + 10·0.6 = 106.
  expect_vector_near(residual(spring, state(q, vec({1.0, 0.0, 0.0}), vec({0.0, 0.0, 0.0}))),
                     vec({63.6, -84.8, -31.8}), kValueTol);
  // Spinning with θ̇ = 2: point velocity ω perp(a) = (−1, 0), L̇ = −0.6, N = 100 − 6 = 94.
  expect_vector_near(residual(spring, state(q, vec({0.0, 0.0, 2.0}), vec({0.0, 0.0, 0.0}))),
                     vec({56.4, -75.2, -28.2}), kValueTol);
}

TEST(SpringDamper2D, AxisResidualIsTensionAlongTheAxisOnParticleAndLineParticle) {
  // Particle at (3, 1); line particle on y = 1 (origin (0, 1), direction (1, 0)) at s = 1 → (1, 1).
  // Axis u = (1, 0): δ = u·(r1 − r2) = 2, N = k (δ − L0) + c δ̇ = 50 (2 − 0.5) + 10·0.2 = 77
  // (only the axial velocity 0.2 counts, not the transverse 5). r = N [u; −u·dir] = [77, 0, −77].
  const Node p = particle_node(Eigen::Vector2d(3.0, 1.0));
  const Node l = line_node(Eigen::Vector2d(0.0, 1.0), Eigen::Vector2d(1.0, 0.0), 1.0);
  const SpringDamper2D spring("spring", {0, 1}, PlanarMarker::on_node(p, Eigen::Vector2d::Zero(), 0),
                              PlanarMarker::on_node(l, Eigen::Vector2d::Zero(), 2), 50.0, 10.0, 0.5,
                              Eigen::Vector2d(1.0, 0.0));
  const Eigen::VectorXd q = vec({3.0, 1.0, 1.0});
  EXPECT_NEAR(spring.length(q), 2.0, 1e-14);
  expect_vector_near(residual(spring, state(q, vec({0.2, 5.0, 0.0}), vec({0.0, 0.0, 0.0}))),
                     vec({77.0, 0.0, -77.0}), kValueTol);
  // Compressed past the rest length along the axis (δ = −1): a push, N = 50 (−1 − 0.5) = −75.
  expect_vector_near(residual(spring, state(vec({0.0, 7.0, 1.0}), vec({0.0, 0.0, 0.0}), vec({0.0, 0.0, 0.0}))),
                     vec({-75.0, 0.0, 75.0}), kValueTol);
}

TEST(SpringDamper2D, PointToPointForcesOnTwoRigidBodiesBalanceForceAndMoment) {
  // An internal force along the line of the two points: Σ F = 0 and Σ moments about the origin = 0,
  // i.e. r1_xy + r2_xy = 0 and r1_θ + r2_θ + x1 × r1_xy + x2 × r2_xy = 0 (r = −generalized force).
  const Node b1 = rigid_node(Eigen::Vector3d::Zero()), b2 = rigid_node(Eigen::Vector3d::Zero());
  const SpringDamper2D spring("spring", {0, 1}, PlanarMarker::on_node(b1, Eigen::Vector2d(0.4, -0.2), 0),
                              PlanarMarker::on_node(b2, Eigen::Vector2d(-0.3, 0.5), 3), kStiffness, kDamping, kRest,
                              std::nullopt);
  std::mt19937 rng(307);
  for (int i = 0; i < kSamples; ++i) {
    const LocalState s = random_state(rng, vec({0.0, 0.0, 0.0, 2.5, 1.0, 0.0}), {2, 5});
    const Eigen::VectorXd r = residual(spring, s);
    const auto cross = [](double ax, double ay, double bx, double by) { return ax * by - ay * bx; };
    EXPECT_NEAR(r[0] + r[3], 0.0, 1e-12 * r.norm());
    EXPECT_NEAR(r[1] + r[4], 0.0, 1e-12 * r.norm());
    const double moment = r[2] + r[5] + cross(s.q[0], s.q[1], r[0], r[1]) + cross(s.q[3], s.q[4], r[3], r[4]);
    EXPECT_NEAR(moment, 0.0, 1e-12 * r.norm());
    // The force on body 1 is −N e: along the line from point 2 to point 1.
    const Eigen::Vector2d d = Eigen::Vector2d(s.q[0], s.q[1]) + rotate(s.q[2], Eigen::Vector2d(0.4, -0.2)) -
                              Eigen::Vector2d(s.q[3], s.q[4]) - rotate(s.q[5], Eigen::Vector2d(-0.3, 0.5));
    EXPECT_NEAR(r[0] * d.y() - r[1] * d.x(), 0.0, 1e-12 * r.norm() * d.norm());
  }
}

// =================================================================== PointForce2D
// r = −Jᵀ F(t) for a dead world force F at a body point: K = −∂(JᵀF)/∂q, C = M = 0.

TEST(PointForce2D, TangentsKCMMatchFiniteDifferencesAtOffCentrePoint) {
  const Node b = rigid_node(Eigen::Vector3d(0.2, -0.4, 0.0));
  const PointForce2D force("force", 0, PlanarMarker::on_node(b, Eigen::Vector2d(0.7, -0.35), 0),
                           make_sine(12.0, 0.3, 0.2, 1.5), make_ramp(0.0, 2.0, -4.0, 9.0));
  check_tangents(force, [](std::mt19937& rng) { return random_state(rng, vec({0.2, -0.4, 0.0}), {2}); },
                 "PointForce2D (time-dependent, off-centre point)", 401);
}

TEST(PointForce2D, ResidualIsMinusForceAndItsMomentAboutTheCentreOfMass) {
  // θ = π/2, point s = (1, 0) → arm a = (0, 1). At t = 1: F = (ramp 0→10 over [0, 2], 2 sin(2π·0.25 t))
  // = (5, 2); moment a × F = 0·2 − 1·5 = −5. r = −[F; a × F] = [−5, −2, 5].
  const Node b = rigid_node(Eigen::Vector3d(3.0, 4.0, kPi / 2));
  const PointForce2D force("force", 0, PlanarMarker::on_node(b, Eigen::Vector2d(1.0, 0.0), 0),
                           make_ramp(0.0, 2.0, 0.0, 10.0), make_sine(2.0, 0.25, 0.0, 0.0));
  expect_vector_near(residual(force, state(vec({3.0, 4.0, kPi / 2}), vec({1.0, 1.0, 1.0}), vec({1.0, 1.0, 1.0}), 1.0)),
                     vec({-5.0, -2.0, 5.0}), kValueTol);
  // At t = 2 the ramp is at 10 and the sine at 2 sin(π) = 0: r = [−10, 0, 10].
  expect_vector_near(residual(force, state(vec({3.0, 4.0, kPi / 2}), vec({0.0, 0.0, 0.0}), vec({0.0, 0.0, 0.0}), 2.0)),
                     vec({-10.0, 0.0, 10.0}), 1e-12);
}

TEST(PointForce2D, ResidualOnLineParticleIsMinusForceComponentAlongTheLine) {
  // Line direction (0.6, 0.8), F = (5, 10): r = −u·F = −(3 + 8) = −11.
  const Node l = line_node(Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.6, 0.8), 0.0);
  const PointForce2D force("force", 0, PlanarMarker::on_node(l, Eigen::Vector2d::Zero(), 0), make_constant(5.0),
                           make_constant(10.0));
  expect_vector_near(residual(force, state(vec({2.0}), vec({1.0}), vec({0.0}))), vec({-11.0}), kValueTol);
}

// =================================================================== Torque2D
// r_θ = −T(t); no dependence on q, q̇, q̈.

TEST(Torque2D, TangentsKCMMatchFiniteDifferences) {
  const Torque2D torque("torque", 0, make_sine(3.0, 0.5, 0.1, -1.0));
  check_tangents(torque, [](std::mt19937& rng) { return random_state(rng, vec({0.0, 0.0, 0.0}), {2}); },
                 "Torque2D (time-dependent)", 501);
}

TEST(Torque2D, ResidualIsMinusTorqueOnTheAngle) {
  // Ramp 0 → 8 over [0, 4], at t = 1: T = 2, r = [0, 0, −2].
  const Torque2D torque("torque", 0, make_ramp(0.0, 4.0, 0.0, 8.0));
  expect_vector_near(residual(torque, state(vec({1.0, 2.0, 0.5}), vec({1.0, 0.0, 3.0}), vec({0.0, 0.0, 0.0}), 1.0)),
                     vec({0.0, 0.0, -2.0}), kValueTol);
}

}  // namespace alphaflex
