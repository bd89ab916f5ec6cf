// The tie of an interface node to a reduced flexible body (joints/reduced_interface_tie.hpp,
// docs/theory/reduced_bodies.md "Interface points"): its tangents, its exactness at a Craig–Bampton
// interface node, and a reduced cantilever held at its root and loaded at its tied tip.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "alphaflex/joints/reduced_interface_tie.hpp"
#include "alphaflex/modal/superelement.hpp"
#include "alphaflex/model/model.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using testing::central_differences;
using testing::input_error_of;
using testing::random_vector;
using testing::retracted_frames;

Matrix3d tie_random_rotation(std::mt19937& rng) { return exp_so3<double>(Vector3d(random_vector(rng, 3, -1.5, 1.5))); }

/// q ∘ exp(d) for the tie's local configuration: two frames (7 numbers, 6 increments each), then the
/// amplitudes (additive).
VectorXd retract_tie(const VectorXd& q, const VectorXd& d) {
  VectorXd out = q;
  out.head(14) = retracted_frames(q.head(14), d.head(12));
  out.tail(q.size() - 14) += d.tail(d.size() - 12);
  return out;
}

/// A tie with m amplitudes (nodes 0, 1, 2 …) at a random rotated, deformed state, ψ up to ~1 rad
/// (T(ψ) far from I): its shape Φ_a and its local configuration q.
struct TieAtRandomState {
  MatrixXd shape;
  ReducedInterfaceTie tie;
  VectorXd q;
};
TieAtRandomState random_tie_state(std::mt19937& rng, int m) {
  std::vector<int> amplitudes;
  for (int i = 0; i < m; ++i) amplitudes.push_back(2 + i);
  const MatrixXd shape = random_vector(rng, 6 * m, -0.6, 0.6).reshaped(6, m);
  const ReducedInterfaceTie tie("t", 0, 1, amplitudes, random_vector(rng, 3, -0.5, 0.5), tie_random_rotation(rng), shape);
  VectorXd q(14 + m);
  store_pose(random_vector(rng, 3, -1, 1), tie_random_rotation(rng), q.data());
  store_pose(random_vector(rng, 3, -1, 1), tie_random_rotation(rng), q.data() + 7);
  q.tail(m) = random_vector(rng, m, -0.6, 0.6);
  return {shape, tie, q};
}

/// Central differences of f along the tie's increments (h = 1e-6: truncation and round-off ~1e-10
/// relative).
MatrixXd fd_tie(const testing::VectorFunction& f, const VectorXd& q) {
  const Eigen::Index n = q.size() - 2;
  return central_differences([&](const VectorXd& d) { return f(retract_tie(q, d)); }, VectorXd::Zero(n),
                             testing::fixed_fd_step(1e-6));
}

// Every joint has a finite-difference test of its tangent (docs/architecture.md): Φ_q, the
// geometric stiffness ∂(Φ_qᵀλ)/∂δ' and the acceleration term d²Φ(q ∘ exp(τv))/dτ², at random
// rotated, deformed states (frame and node far apart, amplitudes giving rotations of ~0.5 rad), with
// and without amplitudes (method `rigid`).
TEST(ReducedInterfaceTie, JacobianGeometricStiffnessAndAccelerationTermMatchFiniteDifferences) {
  std::mt19937 rng(1919);
  double worst = 0.0;
  for (const int m : {0, 7}) {
    for (int trial = 0; trial < 4; ++trial) {
      SCOPED_TRACE("m = " + std::to_string(m) + ", trial " + std::to_string(trial));
      std::vector<int> amplitudes;
      for (int i = 0; i < m; ++i) amplitudes.push_back(2 + i);
      const ReducedInterfaceTie tie("t", 0, 1, amplitudes, random_vector(rng, 3, -0.5, 0.5), tie_random_rotation(rng),
                                    MatrixXd(random_vector(rng, 6 * m, -0.4, 0.4).reshaped(6, m)));
      VectorXd q(14 + m);
      store_pose(random_vector(rng, 3, -1, 1), tie_random_rotation(rng), q.data());
      store_pose(random_vector(rng, 3, -1, 1), tie_random_rotation(rng), q.data() + 7);
      q.tail(m) = random_vector(rng, m, -0.5, 0.5);
      const VectorXd lambda = random_vector(rng, 6, -5.0, 5.0), v = random_vector(rng, 12 + m, -2.0, 2.0);
      const double t = 0.4;
      const auto phi_of = [&](const VectorXd& x) {
        VectorXd p;
        MatrixXd pq;
        tie.evaluate(x, t, p, pq);
        return p;
      };
      VectorXd phi;
      MatrixXd phi_q, k;
      tie.evaluate(q, t, phi, phi_q);
      ASSERT_EQ(phi_q.rows(), 6);
      ASSERT_EQ(phi_q.cols(), 12 + m);
      const MatrixXd fd_q = fd_tie(phi_of, q);
      const double e1 = (phi_q - fd_q).norm() / phi_q.norm();
      EXPECT_LE(e1, 1e-7) << phi_q << "\n" << fd_q;
      // K_Φ = ∂(Φ_qᵀλ)/∂δ' (the derivative of the gradient at the perturbed configuration).
      tie.geometric_stiffness(q, t, lambda, k);
      const MatrixXd fd_k = fd_tie(
          [&](const VectorXd& x) {
            VectorXd p;
            MatrixXd pq;
            tie.evaluate(x, t, p, pq);
            return VectorXd(pq.transpose() * lambda);
          },
          q);
      const double e2 = (k - fd_k).norm() / k.norm();
      EXPECT_LE(e2, 1e-7) << k << "\n" << fd_k;
      // (Φ_q v)_q v = d²Φ(q ∘ exp(τ v))/dτ² (scleronomic), by second differences (h = 1e-4:
      // truncation ~1e-8, round-off ~1e-8).
      VectorXd c;
      tie.acceleration_term(q, v, t, c);
      const double h = 1e-4;
      const VectorXd fd_c = (phi_of(retract_tie(q, h * v)) - 2 * phi + phi_of(retract_tie(q, -h * v))) / (h * h);
      const double e3 = (c - fd_c).norm() / std::max(1.0, c.norm());
      EXPECT_LE(e3, 1e-5) << c.transpose() << "\n" << fd_c.transpose();
      // The reaction is the tie's load on its node B: minus the multipliers' generalized force.
      const JointReaction r = tie.reaction(q, t, lambda);
      EXPECT_LT((r.force + (phi_q.transpose() * lambda).head<3>()).norm(), 1e-12 * (1 + r.force.norm()));
      worst = std::max({worst, e1, e2});
    }
  }
  std::printf("[ FD       ] worst rel. error %.1e  reduced interface tie (Φ_q, K_Φ)\n", worst);
}

// Φ_q in closed form (reduced_interface_tie.cpp, `first`) against forward AD of the scalar-generic
// equations (the former implementation: 18 kernel variables seeded as model/spatial_kernel.hpp,
// chained to ξ by Φ_a): equal to round-off, Φ itself too, at random rotated, deformed
// states with ψ up to ~1 rad (T(ψ) far from I).
TEST(ReducedInterfaceTie, ClosedFormJacobianEqualsForwardADToRoundOff) {
  std::mt19937 rng(2323);
  using A1 = ad::FixedAD1<18>;
  double worst = 0.0;
  for (int trial = 0; trial < 6; ++trial) {
    const int m = 5;
    const auto [shape, tie, q] = random_tie_state(rng, m);
    VectorXd phi;
    MatrixXd phi_q;
    tie.evaluate(q, 0.0, phi, phi_q);
    // The AD reference: variables δx_B, δθ_B, δx_f, δθ_f, z = Φ_a ξ.
    const Pose<A1> bs = kernel_detail::seeded_pose1<18>(pose_of(q.data()), 0);
    const Pose<A1> fs = kernel_detail::seeded_pose1<18>(pose_of(q.data() + 7), 6);
    const VectorXd z = shape * q.tail(m);
    Vec3<A1> u, psi;
    for (int i = 0; i < 3; ++i) {
      u[i] = A1(z[i], A1::DerType::Unit(12 + i));
      psi[i] = A1(z[3 + i], A1::DerType::Unit(15 + i));
    }
    std::array<A1, 6> out;
    tie.equations(bs, fs, u, psi, out.data());
    MatrixXd J(6, 18), ref(6, 12 + m);
    VectorXd phi_ad(6);
    for (int i = 0; i < 6; ++i) {
      phi_ad[i] = out[static_cast<size_t>(i)].value();
      J.row(i) = out[static_cast<size_t>(i)].derivatives().transpose();
    }
    ref.leftCols(12) = J.leftCols(12);
    ref.rightCols(m) = J.rightCols(6) * shape;
    // Φ by double arithmetic against AD's value part: the same expressions, a few ulps apart (the
    // AD types' rotation coefficients round differently).
    EXPECT_LT((phi - phi_ad).cwiseAbs().maxCoeff(), 1e-15 * (1.0 + phi_ad.norm())) << "trial " << trial;
    const double e = (phi_q - ref).norm() / ref.norm();
    EXPECT_LT(e, 1e-14) << "trial " << trial << "\n" << phi_q << "\n" << ref;
    worst = std::max(worst, e);
  }
  std::printf("reduced interface tie: closed-form Φ_q against AD, worst relative difference %.1e\n", worst);
}

// K_Φ = ∂(Φ_qᵀλ)/∂δ' by forward AD1 of the closed-form Jacobian (reduced_interface_tie.cpp,
// `second`) against nested forward AD2 of the scalar-generic equations (the former
// implementation, the 18 kernel variables seeded as model/spatial_kernel.hpp's `second`: outer
// perturbation first), chained to ξ by P = diag(I₁₂, Φ_a): equal to round-off at random rotated,
// deformed states with ψ up to ~1 rad, where ∂T(ψ)/∂ψ matters.
TEST(ReducedInterfaceTie, GeometricStiffnessEqualsNestedForwardADToRoundOff) {
  std::mt19937 rng(4747);
  using A1 = ad::FixedAD1<18>;
  using A2 = ad::FixedAD2<18>;
  const auto seeded_z2 = [](double x, int k) {
    A2::DerType outer;
    for (int o = 0; o < 18; ++o) outer[o] = A1(o == 12 + k ? 1.0 : 0.0, A1::DerType::Zero());
    return A2(A1(x, A1::DerType::Unit(12 + k)), outer);
  };
  double worst = 0.0;
  for (const int m : {0, 5}) {
    for (int trial = 0; trial < 5; ++trial) {
      const auto [shape, tie, q] = random_tie_state(rng, m);
      const VectorXd lambda = random_vector(rng, 6, -5.0, 5.0);
      MatrixXd k;
      tie.geometric_stiffness(q, 0.0, lambda, k);
      const Pose<A2> bs = kernel_detail::seeded_pose2<18>(pose_of(q.data()), 0);
      const Pose<A2> fs = kernel_detail::seeded_pose2<18>(pose_of(q.data() + 7), 6);
      const VectorXd z = shape * q.tail(m);
      Vec3<A2> u, psi;
      for (int i = 0; i < 3; ++i) {
        u[i] = seeded_z2(z[i], i);
        psi[i] = seeded_z2(z[3 + i], 3 + i);
      }
      std::array<A2, 6> out;
      tie.equations(bs, fs, u, psi, out.data());
      MatrixXd H = MatrixXd::Zero(18, 18);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 18; ++j) H.col(j) += lambda[i] * out[static_cast<size_t>(i)].derivatives()[j].derivatives();
      MatrixXd P = MatrixXd::Zero(18, 12 + m);
      P.topLeftCorner(12, 12).setIdentity();
      P.bottomRightCorner(6, m) = shape;
      const MatrixXd ref = P.transpose() * H * P;
      ASSERT_EQ(k.rows(), 12 + m);
      ASSERT_EQ(k.cols(), 12 + m);
      const double e = (k - ref).norm() / ref.norm();
      EXPECT_LT(e, 1e-14) << "m = " << m << ", trial " << trial << "\n" << k << "\n" << ref;
      worst = std::max(worst, e);
    }
  }
  std::printf("reduced interface tie: K_Φ by AD1 of the closed form against nested AD2, worst relative difference %.1e\n",
              worst);
}

TEST(ReducedInterfaceTie, RefusesAShapeOfTheWrongSize) {
  EXPECT_THROW(ReducedInterfaceTie("t", 0, 1, {2, 3}, Vector3d::Zero(), Matrix3d::Identity(), MatrixXd::Zero(6, 3)),
               std::invalid_argument);
  EXPECT_THROW(ReducedInterfaceTie("t", 0, 1, {}, Vector3d::Zero(), Matrix3d::Identity(), MatrixXd::Zero(3, 0)), std::invalid_argument);
}

/// The cantilever of inputs/beam_elastica.yaml (16 elements, L = 1 m, EI3 = 1, the other
/// stiffnesses 10⁶) as the scene reader builds it, full: its beam elements and the ids of `root`
/// and `tip`.
struct ElasticaBlock {
  Scene scene;
  std::vector<int> elements;
  int root = -1, tip = -1;
  explicit ElasticaBlock(const std::vector<std::string>& overrides = {})
      : scene(read_scene(testing::source_path("inputs/beam_elastica.yaml"), overrides)) {
    const Model& m = *scene.model;
    for (size_t e = 0; e < m.elements().size(); ++e)
      if (std::string(m.elements()[e]->type()) == "beam") elements.push_back(static_cast<int>(e));
    root = m.find_node("root");
    tip = m.find_node("tip");
  }
};

// With the Craig–Bampton basis the interface node's rows of Φ are [R_f0ᵀ 0; 0 I] on its own 6
// constraint coordinates and zero on every other column (constraint modes are unit at their node,
// fixed-interface modes vanish there), so node_pose returns exactly the constraint coordinates —
// the tip's displacement (world axes at t = 0) and rotation (node frame) relative to the frame —
// and the tie at that pose is satisfied to round-off, for any frame pose and amplitudes.
TEST(ReducedInterfaceTie, IsExactAtACraigBamptonInterfaceNode) {
  const ElasticaBlock b;
  const Model& model = *b.scene.model;
  const BlockMatrices block = assemble_block(model, b.elements);
  const ReducedBlock rb = reduce_block(model, block, b.root, {b.tip}, 3);
  const int m = rb.matrices.elastic();
  ASSERT_EQ(m, 9);
  const size_t a = static_cast<size_t>(std::lower_bound(block.nodes.begin(), block.nodes.end(), b.tip) - block.nodes.begin());
  const Pose<double> F0 = pose_of(model.node(b.root).q0.data()), B0 = pose_of(model.node(b.tip).q0.data());
  MatrixXd expected = MatrixXd::Zero(6, m);
  expected.topLeftCorner<3, 3>() = F0.R.transpose();
  expected.block<3, 3>(3, 3).setIdentity();
  EXPECT_EQ((rb.shapes[a] - expected).cwiseAbs().maxCoeff(), 0.0) << rb.shapes[a];
  EXPECT_LT((rb.positions[a] - F0.R.transpose() * (B0.x - F0.x)).norm(), 1e-15);
  EXPECT_LT((rb.rotations[a] - F0.R.transpose() * B0.R).norm(), 1e-15);
  // The frame at rest: the tip moves by exactly its constraint coordinates.
  std::mt19937 rng(7);
  const VectorXd xi = random_vector(rng, m, -0.05, 0.05);
  Vector3d x;
  Matrix3d R;
  rb.node_pose(a, F0.x, F0.R, xi, x, R);
  EXPECT_LT((x - B0.x - xi.head<3>()).norm(), 1e-15);
  EXPECT_LT((R - B0.R * exp_so3<double>(Vector3d(xi.segment<3>(3)))).norm(), 1e-14);
  // Any frame pose: the tie holds at node_pose.
  std::vector<int> amplitudes;
  for (int i = 0; i < m; ++i) amplitudes.push_back(2 + i);
  const ReducedInterfaceTie tie("t", 0, 1, amplitudes, rb.positions[a], rb.rotations[a], rb.shapes[a]);
  const Vector3d xf = random_vector(rng, 3, -1, 1);
  const Matrix3d Rf = tie_random_rotation(rng);
  rb.node_pose(a, xf, Rf, xi, x, R);
  VectorXd q(14 + m);
  store_pose(x, R, q.data());
  store_pose(xf, Rf, q.data() + 7);
  q.tail(m) = xi;
  VectorXd phi;
  MatrixXd phi_q;
  tie.evaluate(q, 0.0, phi, phi_q);
  EXPECT_LT(phi.norm(), 1e-14) << phi.transpose();
}

// A reduced cantilever clamped at its root (the frame) and loaded at its tip (the tied interface
// node): the constraint modes carry the exact static response to interface loads (Craig & Bampton
// 1968), so the tip deflection is the full linear model's with or without fixed-interface modes,
// up to the geometric nonlinearity of the small load (tip deflection 3e-6 L: relative effects
// ~(PL²/EI)² ~ 1e-10, and the frame does not move). Reference: the linear K of the same 16
// elements (assemble_block on the full scene's model), root clamped, solved for the same load.
TEST(ReducedInterfaceTie, ReducedCantileverHasTheFullLinearStaticTipDeflection) {
  // Load factor 1e-6 of P = 10 EI/L² along y, plus an axial and an out-of-plane part, and a tip
  // moment (world components), so that the tie's reaction has a force and a moment to carry.
  const std::vector<std::string> load = {"load.factor=1e-6",
                                         "forces=[{name: tip_force, type: force, body: tip, value: [-2.0, P, 3.0]},"
                                         "{name: tip_moment, type: moment, body: tip, value: [0.5, -1.0, 2.0]}]"};
  const ElasticaBlock full(load);
  const Model& model = *full.scene.model;
  const BlockMatrices block = assemble_block(model, full.elements);
  std::vector<int> free_rows;
  for (int r = 0; r < block.K.rows(); ++r)
    if (block.row_of(full.root) < 0 || r < block.row_of(full.root) || r >= block.row_of(full.root) + 6) free_rows.push_back(r);
  const Eigen::Index n = static_cast<Eigen::Index>(free_rows.size());
  MatrixXd K(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) K(i, j) = block.K(free_rows[i], free_rows[j]);
  VectorXd f = VectorXd::Zero(n);
  const Vector3d F = 1e-6 * Vector3d(-2.0, 10.0, 3.0);  // δx rows: world components
  const Vector3d M = 1e-6 * Vector3d(0.5, -1.0, 2.0);   // δθ rows: the node frame's components
  const Matrix3d R_tip = pose_of(model.node(full.tip).q0.data()).R;
  const Vector3d M_node = R_tip.transpose() * M;
  for (int k = 0; k < 3; ++k) {
    f[std::find(free_rows.begin(), free_rows.end(), block.row_of(full.tip, k)) - free_rows.begin()] = F[k];
    f[std::find(free_rows.begin(), free_rows.end(), block.row_of(full.tip, 3 + k)) - free_rows.begin()] = M_node[k];
  }
  const VectorXd u = K.ldlt().solve(f);
  Vector3d tip;
  for (int k = 0; k < 3; ++k) tip[k] = u[std::find(free_rows.begin(), free_rows.end(), block.row_of(full.tip, k)) - free_rows.begin()];
  const double y = tip.y();
  std::printf("full linear tip displacement: %.10e %.10e %.10e m\n", tip.x(), tip.y(), tip.z());
  for (const char* reduction : {"{method: craig_bampton, modes: 0, interface: [root, tip]}",
                                "{method: craig_bampton, modes: 4, interface: [root, tip]}"}) {
    std::vector<std::string> o = load;
    o.push_back(std::string("beams.0.reduction=") + reduction);
    o.push_back("sensors=[{name: ux, type: point_displacement, body: tip, component: x},"
                "{name: uy, type: point_displacement, body: tip, component: y},"
                "{name: uz, type: point_displacement, body: tip, component: z},"
                "{name: fy, type: joint_reaction, joint: clamp, component: fy},"
                "{name: tfx, type: joint_reaction, joint: 'cantilever:tie:tip', component: fx},"
                "{name: tfy, type: joint_reaction, joint: 'cantilever:tie:tip', component: fy},"
                "{name: tfz, type: joint_reaction, joint: 'cantilever:tie:tip', component: fz},"
                "{name: tmx, type: joint_reaction, joint: 'cantilever:tie:tip', component: mx},"
                "{name: tmy, type: joint_reaction, joint: 'cantilever:tie:tip', component: my},"
                "{name: tmz, type: joint_reaction, joint: 'cantilever:tie:tip', component: mz}]");
    Scene s = read_scene(testing::source_path("inputs/beam_elastica.yaml"), o);
    RunOptions opt;
    opt.write_results = false;
    opt.verbose = false;
    const RunSummary r = run_simulation(s, opt, PETSC_COMM_WORLD);
    const Vector3d red(testing::final_value(r, "ux"), testing::final_value(r, "uy"), testing::final_value(r, "uz"));
    std::printf("%s: tip %.10e %.10e %.10e m, relative difference %.2e\n", reduction, red.x(), red.y(), red.z(),
                (red - tip).norm() / tip.norm());
    EXPECT_LT(std::fabs(red.y() - y), 1e-8 * std::fabs(y)) << reduction;
    EXPECT_LT((red - tip).norm(), 1e-8 * tip.norm()) << reduction;
    // The tie passes the tip load to the body: the clamp carries it all (reaction on the root
    // node, which the clamp holds: −F).
    EXPECT_NEAR(testing::final_value(r, "fy"), -F.y(), 1e-9 * F.y()) << reduction;
    // Equilibrium of the tip node, which carries only the loads and the tie: the tie's reaction
    // on it is −F and −M (the loads act at the node itself), in the joint frame (the node's
    // frame, R_tip at rest). The node turns by ~M L/EI + P L²/(2 EI) ≈ 7e-6 rad under the load, which
    // moves the components by that fraction: the bound is 2e-5 of |F| and |M|.
    const Vector3d tf(testing::final_value(r, "tfx"), testing::final_value(r, "tfy"), testing::final_value(r, "tfz"));
    const Vector3d tm(testing::final_value(r, "tmx"), testing::final_value(r, "tmy"), testing::final_value(r, "tmz"));
    EXPECT_LT((tf + R_tip.transpose() * F).norm(), 2e-5 * F.norm()) << reduction << ": " << tf.transpose();
    EXPECT_LT((tm + R_tip.transpose() * M).norm(), 2e-5 * M.norm()) << reduction << ": " << tm.transpose();
  }
}

// Joints, loads and sensors at every interface point; a point named twice is refused.
TEST(ReducedInterfaceTie, SceneGivesEveryInterfacePointANodeAndRefusesARepeatedPoint) {
  const std::string red = "beams.0.reduction={method: craig_bampton, modes: 2, interface: [root, tip]}";
  const ElasticaBlock b({red});
  const Model& m = *b.scene.model;
  ASSERT_GE(b.tip, 0);
  EXPECT_EQ(m.node(b.tip).kind, NodeKind::Frame3D);
  int ties = 0;
  for (const auto& c : m.constraints())
    if (std::string(c->type()) == "reduced_interface_tie") {
      ++ties;
      EXPECT_EQ(c->name(), "cantilever:tie:tip");
      EXPECT_EQ(c->nodes().front(), b.tip);
      EXPECT_EQ(c->nodes()[1], b.root);
      EXPECT_EQ(c->nodes().size(), 2u + 8u);  // B, the frame, 6 constraint-mode coordinates of the tip and 2 modes
    }
  EXPECT_EQ(ties, 1);
  const std::string e = input_error_of([] {
    read_scene(testing::source_path("inputs/beam_elastica.yaml"),
               {"beams.0.reduction={method: craig_bampton, modes: 2, interface: [root, tip, tip]}"});
  });
  EXPECT_NE(e.find("beams[cantilever].reduction.interface: 'tip' is given twice"), std::string::npos) << e;
}

}  // namespace
}  // namespace alphaflex
