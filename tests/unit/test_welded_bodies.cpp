// A rigid body inside a reduced body (docs/theory/reduced_bodies.md, "Rigid bodies inside a reduced
// body"): the rigid body about a point that is not its centre of mass (elements/spatial_elements.hpp,
// RigidBody3D with an offset), the reduced interface tie with an offset (joints/
// reduced_interface_tie.hpp), and a scene whose reduced link carries a welded payload
// (inputs/flexible_arm_payload.yaml). The runs against the full mesh: tests/cli/reduced_welded_body.py.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "alphaflex/elements/reduced_body.hpp"
#include "alphaflex/elements/spatial_elements.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/joints/reduced_interface_tie.hpp"
#include "alphaflex/model/model.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

VectorXd weld_random(std::mt19937& rng, int n, double a, double b) {
  VectorXd x(n);
  std::uniform_real_distribution<double> u(a, b);
  for (int i = 0; i < n; ++i) x[i] = u(rng);
  return x;
}
Matrix3d weld_rotation(std::mt19937& rng) { return exp_so3<double>(Vector3d(weld_random(rng, 3, -1.5, 1.5))); }

LocalResidual weld_evaluate(const Element& e, const LocalState& s, bool tangent) {
  LocalResidual out;
  out.reset(static_cast<int>(s.v.size()), tangent);
  e.evaluate(s, out, tangent);
  return out;
}

LocalState weld_state(std::mt19937& rng) {
  LocalState s;
  s.q.resize(7);
  store_pose(Vector3d(weld_random(rng, 3, -1, 1)), weld_rotation(rng), s.q.data());
  s.v = weld_random(rng, 6, -3, 3);
  s.qdd = weld_random(rng, 6, -4, 4);
  s.t = 0.3;
  s.load_factor = 0.7;
  return s;
}

// The body about its node P with the centre at c (node frame) is the body about its centre G moved
// by virtual work: δx_G = δx − R ĉ δθ, so r_P = [r_G,x; r_G,θ + ĉ Rᵀ r_G,x], with the centre's
// acceleration ẍ_G = ẍ + R(Ω̇ × c + Ω × (Ω × c)) (rigid kinematics) and the same Ω, Ω̇. An
// independent check of the offset equations (spatial_elements.hpp) against the centred ones.
TEST(RigidBody3DOffset, IsTheCentredBodyMovedToTheNodeByVirtualWork) {
  std::mt19937 rng(7101);
  const double m = 1.7;
  const Vector3d g(0.3, -0.2, -9.81);
  for (int trial = 0; trial < 6; ++trial) {
    const Matrix3d Q = weld_rotation(rng);
    const Matrix3d J = Q * Vector3d(0.2, 0.35, 0.5).asDiagonal() * Q.transpose();
    const Vector3d c = weld_random(rng, 3, -0.6, 0.6);
    const RigidBody3D at_node("p", 0, m, J, g, c), at_centre("g", 0, m, J, g);
    const LocalState s = weld_state(rng);
    const Pose<double> P = pose_of(s.q.data());
    const Vector3d W = s.v.tail<3>(), Wd = s.qdd.tail<3>();
    LocalState sg = s;
    store_pose(Vector3d(P.x + P.R * c), P.R, sg.q.data());
    sg.v.head<3>() = s.v.head<3>() + P.R * W.cross(c);
    sg.qdd.head<3>() = s.qdd.head<3>() + P.R * (Wd.cross(c) + W.cross(W.cross(c)));
    const VectorXd rg = weld_evaluate(at_centre, sg, false).r;
    VectorXd expected(6);
    expected << rg.head<3>(), rg.tail<3>() + c.cross(Vector3d(P.R.transpose() * rg.head<3>()));
    const VectorXd r = weld_evaluate(at_node, s, false).r;
    EXPECT_LT((r - expected).norm(), 1e-13 * (1.0 + expected.norm())) << r.transpose() << "\n" << expected.transpose();
  }
}

// Every element has a finite-difference test of its tangent (docs/architecture.md): M, C and K of the
// offset body against central differences of its residual in q̈, v and along the group (h = 1e-6:
// error ~1e-10 of the entries).
TEST(RigidBody3DOffset, TangentsMatchFiniteDifferences) {
  std::mt19937 rng(7202);
  double worst = 0.0;
  for (int trial = 0; trial < 6; ++trial) {
    const Matrix3d Q = weld_rotation(rng);
    const RigidBody3D body("p", 0, 2.3, Matrix3d(Q * Vector3d(0.3, 0.4, 0.6).asDiagonal() * Q.transpose()), Vector3d(0, 0, -9.81),
                           weld_random(rng, 3, -0.5, 0.5));
    const LocalState s = weld_state(rng);
    const LocalResidual t = weld_evaluate(body, s, true);
    EXPECT_EQ(t.r, weld_evaluate(body, s, false).r);
    const auto step = testing::fixed_fd_step(1e-6);
    const MatrixXd M = testing::central_differences(testing::element_residual_of(body, s, testing::Wrt::qdd), s.qdd, step);
    const MatrixXd C = testing::central_differences(testing::element_residual_of(body, s, testing::Wrt::v), s.v, step);
    const MatrixXd K = testing::central_differences_on_frames(testing::element_residual_of(body, s, testing::Wrt::q), s.q, step);
    const double eM = (t.M - M).norm() / t.M.norm(), eC = (t.C - C).norm() / t.C.norm(), eK = (t.K - K).norm() / t.K.norm();
    EXPECT_LT(eM, 1e-8) << t.M << "\n" << M;
    EXPECT_LT(eC, 1e-8) << t.C << "\n" << C;
    EXPECT_LT(eK, 1e-8) << t.K << "\n" << K;
    // M symmetric: the kinetic energy's Hessian.
    EXPECT_LT((t.M - t.M.transpose()).norm(), 1e-14 * t.M.norm());
    worst = std::max({worst, eM, eC, eK});
    // No elastic force (a reduction's internal-force differences skip it).
    VectorXd f;
    ASSERT_TRUE(body.internal_force(s.q, f));
    EXPECT_EQ(f, VectorXd::Zero(6));
  }
  std::printf("[ FD       ] worst rel. error %.1e  rigid body about an offset node (M, C, K)\n", worst);
}

/// q ∘ exp(d) for the tie: two frames, then the amplitudes.
VectorXd weld_retract(const VectorXd& q, const VectorXd& d) {
  VectorXd out = q;
  out.head(14) = testing::retracted_frames(q.head(14), d.head(12));
  out.tail(q.size() - 14) += d.tail(d.size() - 12);
  return out;
}

// The tie with an offset (p, R_o): Φ_q, K_Φ = ∂(Φ_qᵀλ)/∂δ' and the acceleration term against central
// differences at random rotated, deformed states (ψ up to ~1 rad), with and without amplitudes; and
// its pose: at Φ = 0 the tied node sits at (x_a + R_a p, R_a R_o).
TEST(ReducedInterfaceTieOffset, TangentsMatchFiniteDifferencesAndTheNodeSitsAtTheOffset) {
  std::mt19937 rng(7303);
  double worst = 0.0;
  for (const int m : {0, 5}) {
    for (int trial = 0; trial < 4; ++trial) {
      std::vector<int> amplitudes;
      for (int i = 0; i < m; ++i) amplitudes.push_back(2 + i);
      const MatrixXd shape = weld_random(rng, 6 * m, -0.5, 0.5).reshaped(6, m);
      const Vector3d X = weld_random(rng, 3, -0.5, 0.5), p = weld_random(rng, 3, -0.4, 0.4);
      const Matrix3d Rbar = weld_rotation(rng), Ro = weld_rotation(rng);
      const ReducedInterfaceTie tie("w", 0, 1, amplitudes, X, Rbar, shape, p, Ro);
      VectorXd q(14 + m);
      store_pose(Vector3d(weld_random(rng, 3, -1, 1)), weld_rotation(rng), q.data());
      store_pose(Vector3d(weld_random(rng, 3, -1, 1)), weld_rotation(rng), q.data() + 7);
      q.tail(m) = weld_random(rng, m, -0.6, 0.6);
      const auto phi_of = [&](const VectorXd& x) {
        VectorXd ph;
        MatrixXd pq;
        tie.evaluate(x, 0.0, ph, pq);
        return ph;
      };
      const auto fd = [&](const testing::VectorFunction& f) {
        return testing::central_differences([&](const VectorXd& d) { return f(weld_retract(q, d)); }, VectorXd::Zero(12 + m),
                                            testing::fixed_fd_step(1e-6));
      };
      VectorXd phi;
      MatrixXd phi_q, k;
      tie.evaluate(q, 0.0, phi, phi_q);
      const double e1 = (phi_q - fd(phi_of)).norm() / phi_q.norm();
      EXPECT_LT(e1, 1e-7);
      const VectorXd lambda = weld_random(rng, 6, -5, 5);
      tie.geometric_stiffness(q, 0.0, lambda, k);
      const MatrixXd fd_k = fd([&](const VectorXd& x) {
        VectorXd ph;
        MatrixXd pq;
        tie.evaluate(x, 0.0, ph, pq);
        return VectorXd(pq.transpose() * lambda);
      });
      const double e2 = (k - fd_k).norm() / k.norm();
      EXPECT_LT(e2, 1e-7);
      const VectorXd v = weld_random(rng, 12 + m, -2, 2);
      VectorXd c;
      tie.acceleration_term(q, v, 0.0, c);
      const double h = 1e-4;
      const VectorXd fd_c = (phi_of(weld_retract(q, h * v)) - 2 * phi + phi_of(weld_retract(q, -h * v))) / (h * h);
      EXPECT_LT((c - fd_c).norm() / std::max(1.0, c.norm()), 1e-5);
      worst = std::max({worst, e1, e2});
      // Place B where the tie holds it: the block node's pose from the frame and the amplitudes,
      // then the offset; Φ vanishes there.
      const Pose<double> f = pose_of(q.data() + 7);
      const VectorXd z = shape * q.tail(m);
      const Matrix3d Ra = f.R * Rbar * exp_so3<double>(Vector3d(z.tail<3>()));
      const Vector3d xa = f.x + f.R * (X + z.head<3>());
      VectorXd qb = q;
      store_pose(Vector3d(xa + Ra * p), Matrix3d(Ra * Ro), qb.data());
      EXPECT_LT(phi_of(qb).norm(), 1e-14);
    }
  }
  std::printf("[ FD       ] worst rel. error %.1e  reduced interface tie with an offset (Φ_q, K_Φ)\n", worst);
}

// The scene (inputs/flexible_arm_payload.yaml): the payload's node stays, without a mass of its own;
// its weld is a tie; and the reduced link's rigid-body mass block (M0's first 6 × 6, frame = the
// root at the origin, axes the world's) is the link's plus the payload's, which a rotated payload
// with a general inertia tests: m I, −m r̂ and J_G + m(|r|²I − rrᵀ) with r its centre.
TEST(ReducedWeldedBody, ThePayloadsMassJoinsTheLinkAndItsWeldIsATie) {
  const std::string scene = testing::source_path("inputs/flexible_arm_payload.yaml");
  const Vector3d r(1.05, 0.02, -0.03);
  const Matrix3d Rb = exp_so3<double>(Vector3d(0.3, -0.5, 0.8));
  const Vector3d J(2.0e-3, 3.0e-3, 4.0e-3);
  const double mp = 1.3;
  const std::vector<std::string> payload = {
      "bodies.0.position=[1.05, 0.02, -0.03]", "bodies.0.mass=1.3", "bodies.0.inertia=[2.0e-3, 3.0e-3, 4.0e-3]",
      "bodies.0.orientation=[0.3, -0.5, 0.8]",
      // The grip (marker1 of the weld) at the body's centre: the weld freezes the body's pose
      // relative to the tip wherever the marker is.
      "bodies.0.markers=[{name: grip, position: [0, 0, 0]}]"};
  const Scene with = read_scene(scene, payload);
  std::vector<std::string> alone = payload;
  alone.push_back("beams.0.reduction={method: craig_bampton, modes: 4, interface: [root]}");
  alone.push_back("joints.1={name: weld, type: fixed, body1: payload, body2: root}");  // keep the payload out of the link
  const Scene without = read_scene(scene, alone);
  const auto body_of = [](const Model& model) -> const ReducedBody& {
    for (const auto& e : model.elements())
      if (const auto* b = dynamic_cast<const ReducedBody*>(e.get())) return *b;
    throw std::runtime_error("no reduced body");
  };
  const MatrixXd M = body_of(*with.model).matrices().M0.topLeftCorner(6, 6) - body_of(*without.model).matrices().M0.topLeftCorner(6, 6);
  const Matrix3d JG = Rb * J.asDiagonal() * Rb.transpose();
  MatrixXd expected(6, 6);
  expected << mp * Matrix3d::Identity(), -mp * hat<double>(r), mp * hat<double>(r),
      JG + mp * (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose());
  EXPECT_LT((M - expected).norm(), 1e-12 * expected.norm()) << M << "\n\n" << expected;
  // The payload: a node, no element of its own; the weld: a tie of it to the link's frame.
  const Model& model = *with.model;
  const int node = model.find_node("payload");
  ASSERT_GE(node, 0);
  for (const auto& e : model.elements()) EXPECT_NE(e->name(), "payload");
  int ties = 0;
  for (const auto& c : model.constraints())
    if (c->name() == "weld") {
      ++ties;
      EXPECT_EQ(std::string(c->type()), "reduced_interface_tie");
      EXPECT_EQ(c->nodes().front(), node);
      const auto& tie = dynamic_cast<const ReducedInterfaceTie&>(*c);
      // The payload's pose relative to the tip (at x = 1 m, the node frame the world's here).
      EXPECT_LT((tie.offset_position() - (r - Vector3d(1, 0, 0))).norm(), 1e-14);
      EXPECT_LT((tie.offset_rotation() - Rb).norm(), 1e-14);
    }
  EXPECT_EQ(ties, 1);
}

}  // namespace
}  // namespace alphaflex
