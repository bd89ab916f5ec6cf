// Craig–Bampton superelement and rigid mass properties of a beam block
// (modal/superelement.hpp, docs/theory/reduced_bodies.md).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numeric>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/beam_section.hpp"
#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "alphaflex/elements/reduced_body.hpp"
#include "alphaflex/elements/shell.hpp"
#include "alphaflex/elements/spatial_elements.hpp"
#include "alphaflex/integrators/generalized_alpha.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "alphaflex/solvers/linear_solver.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/io/superelement_cache.hpp"
#include "alphaflex/modal/superelement.hpp"
#include "test_support.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/mesh_reconstruction.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

// A straight steel bar of n elements from `start` along the unit vector `axis` (not along a
// world axis, so that no coordinate decouples by accident).
struct Bar {
  Model model;
  std::vector<int> elements;
  BeamSection section = BeamSection::from_material(210e9, 0.3, 7850.0, SectionShape::rectangle(0.02, 0.01));
  double length = 0.0;
};

Bar straight_bar(int n, double L, const Vector3d& start, const Vector3d& axis) {
  Bar b;
  b.length = L;
  Matrix3d sec;
  EXPECT_TRUE(frame_from(axis, Vector3d(0.3, 1.0, -0.2), sec));
  for (int k = 0; k <= n; ++k) {
    Node nd;
    nd.name = "n" + std::to_string(k);
    nd.kind = NodeKind::Frame3D;
    nd.ndof = 6;
    nd.nconf = 7;
    nd.q0.resize(7);
    store_pose(start + axis * (L * k / n), sec, nd.q0.data());
    nd.v0 = VectorXd::Zero(6);
    b.model.add_node(nd);
  }
  for (int e = 0; e < n; ++e) {
    b.model.add_element(std::make_unique<GeometricallyExactBeam>("bar[" + std::to_string(e) + "]", e, e + 1, b.section,
                                                                 pose_of(b.model.node(e).q0.data()),
                                                                 pose_of(b.model.node(e + 1).q0.data()), sec, sec, Vector3d::Zero()));
    b.elements.push_back(e);
  }
  return b;
}

// Rows/columns `keep` of A.
MatrixXd sub(const MatrixXd& A, const std::vector<int>& keep) {
  MatrixXd B(keep.size(), keep.size());
  for (size_t i = 0; i < keep.size(); ++i)
    for (size_t j = 0; j < keep.size(); ++j) B(i, j) = A(keep[i], keep[j]);
  return B;
}

VectorXd generalized_eigenvalues(const MatrixXd& K, const MatrixXd& M) {
  return Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd>(K, M, Eigen::EigenvaluesOnly).eigenvalues();
}

// A cantilever (node 0 clamped: its rows removed) of 6 elements, interface = the tip's 6
// coordinates. The full linear model has 36 coordinates.
struct Cantilever {
  Bar bar = straight_bar(6, 0.8, Vector3d(0.1, -0.2, 0.3), Vector3d(2.0, 1.0, 0.5).normalized());
  BlockMatrices block = assemble_block(bar.model, bar.elements);
  std::vector<int> free_rows;
  MatrixXd K, M;
  std::vector<int> tip;  // interface rows, in the clamped numbering
  Cantilever() {
    for (int r = 6; r < block.K.rows(); ++r) free_rows.push_back(r);
    K = sub(block.K, free_rows);
    M = sub(block.M, free_rows);
    for (int k = 0; k < 6; ++k) tip.push_back(block.row_of(6, k) - 6);
  }
};

// Exactness (Craig & Bampton 1968: with every fixed-interface mode kept the transformation T is
// square and invertible, so the reduced pencil is congruent to the full one): the eigenvalues of
// (K̃, M̃) equal those of the full linear cantilever to round-off.
TEST(CraigBampton, AllModesKeptReproduceTheFullEigenvaluesToRoundOff) {
  const Cantilever c;
  const int all = available_modes(static_cast<int>(c.K.rows()), 6);
  ASSERT_EQ(all, 30);
  const Superelement se = craig_bampton(c.K, c.M, c.tip, all);
  ASSERT_EQ(se.K.rows(), 36);
  const VectorXd full = generalized_eigenvalues(c.K, c.M), reduced = generalized_eigenvalues(se.K, se.M);
  // Round-off of a backward-stable symmetric-definite eigensolver: |Δλ_j|/λ_j ≲ c ε λ_max/λ_j
  // (the pencil's spread is ~1e8 here: bending vs shear of short elements), c = 10, plus a floor
  // of 1e-12 (≈ 4500 ε: the dimension and the mass matrix's conditioning, rotary vs translational).
  const double lmax = full[full.size() - 1];
  for (int j = 0; j < full.size(); ++j)
    EXPECT_NEAR(reduced[j] / full[j], 1.0, 1e-12 + 10.0 * DBL_EPSILON * lmax / full[j]) << "mode " << j;
  std::printf("all modes kept: lowest omega^2 %.12e (full) %.12e (reduced), lambda_max/lambda_0 = %.3e\n", full[0], reduced[0],
              lmax / full[0]);
  // The normal modes are M-orthonormal and K-diagonal (ω_j²).
  const MatrixXd Mnn = se.M.bottomRightCorner(all, all), Knn = se.K.bottomRightCorner(all, all);
  EXPECT_LT((Mnn - MatrixXd::Identity(all, all)).norm(), 1e-10);
  EXPECT_LT((Knn - MatrixXd(Knn.diagonal().asDiagonal())).norm(), 1e-9 * Knn.norm());
  // Constraint modes are K-orthogonal to the fixed-interface modes (K_bn = 0).
  EXPECT_LT(se.K.topRightCorner(6, all).norm(), 1e-9 * se.K.norm());
}

// The constraint modes are the exact static response to interface loads, whatever the number of
// normal modes (Craig & Bampton 1968): a tip force and moment give the full model's tip motion
// with no normal mode at all.
TEST(CraigBampton, ConstraintModesGiveTheExactStaticResponseToInterfaceLoads) {
  const Cantilever c;
  const Superelement se = craig_bampton(c.K, c.M, c.tip, 0);
  VectorXd f = VectorXd::Zero(c.K.rows());
  const double load[6] = {3.0, -20.0, 7.0, 0.4, -1.1, 2.0};
  for (int k = 0; k < 6; ++k) f[c.tip[k]] = load[k];
  const VectorXd u = c.K.ldlt().solve(f);
  const VectorXd xi = se.K.ldlt().solve(se.T.transpose() * f);
  EXPECT_LT((se.T * xi - u).norm(), 1e-10 * u.norm());
}

// Rayleigh–Ritz: each reduced eigenvalue bounds the full one of the same rank from above, and the
// lowest bending frequency converges as modes are added (printed for docs/benchmarks/reduced.md).
TEST(CraigBampton, FewModesBoundTheFrequenciesFromAboveAndConverge) {
  const Cantilever c;
  const VectorXd full = generalized_eigenvalues(c.K, c.M);
  double previous = 1e300;
  for (int k : {0, 2, 4, 8}) {
    const Superelement se = craig_bampton(c.K, c.M, c.tip, k);
    const VectorXd red = generalized_eigenvalues(se.K, se.M);
    for (int j = 0; j < red.size(); ++j) EXPECT_GE(red[j], full[j] * (1.0 - 1e-10)) << "k = " << k << ", mode " << j;
    const double err = std::sqrt(red[0] / full[0]) - 1.0;
    std::printf("Craig-Bampton k = %d: lowest frequency %.6f Hz, full %.6f Hz, error %.3e\n", k,
                std::sqrt(red[0]) / (2 * M_PI), std::sqrt(full[0]) / (2 * M_PI), err);
    EXPECT_LE(err, previous * (1.0 + 1e-9));
    previous = err;
  }
  EXPECT_LT(previous, 1e-6);
}

TEST(CraigBampton, RefusesBadInterfacesAndModeCounts) {
  const Cantilever c;
  auto message = [](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([&] { craig_bampton(c.K, c.M, {}, 2); }).find("no interface"), std::string::npos);
  EXPECT_NE(message([&] { craig_bampton(c.K, c.M, c.tip, 31); }).find("asks for 31 fixed-interface modes; the block has 30"),
            std::string::npos);
  EXPECT_NE(message([&] { craig_bampton(c.K, c.M, {0, 0}, 1); }).find("twice"), std::string::npos);
  EXPECT_NE(message([&] { craig_bampton(c.K, c.M, {36}, 1); }).find("not in the block"), std::string::npos);
  // The free bar (no clamp) held at one node's translations only: it can still turn about that
  // node without strain.
  const BlockMatrices& b = c.block;
  EXPECT_NE(message([&] { craig_bampton(b.K, b.M, {0, 1, 2}, 1); }).find("does not hold the block"), std::string::npos);
}

// The rigid mass properties of a uniform bar (its kinetic energy under rigid motions of the
// nodes): m = ρA L, centre at mid-length, inertia about the centre ρA L³/12 + ρI L about the
// transverse section axes and ρI_polar L about the bar's axis (Euler–Bernoulli bar with rotary
// inertia). The beam's consistent mass reproduces rigid motions exactly, so the agreement is to
// round-off.
// The sparse path (LDLᵀ constraint modes, SLEPc shift-and-invert modes, Rayleigh–Ritz) against the
// dense one on a mid-size block: a cantilever of 100 elements (600 coordinates, 594 interior),
// interface = the tip, 8 modes. Frequencies and the reduced K̃, M̃ agree to 1e-9 relative, the
// bases T to 1e-6 (measured 9e-11, 1e-11 and 2e-10, printed): SLEPc converges to 1e-12 in the
// residual, the dense solver is limited by ε λ_max/λ_j (a 100-element beam with rotary inertia:
// λ_max/λ_1 ~ 1e6 and more), and eigenvectors converge as the residual over the spectral gap.
// The section is rectangular, so no two modes share a frequency and the (sign-fixed) vectors are
// unique.
TEST(CraigBampton, SparsePathEqualsDensePathOnAMidSizeBlock) {
  const Bar bar = straight_bar(100, 1.0, Vector3d(0.1, -0.2, 0.3), Vector3d(2.0, 1.0, 0.5).normalized());
  const BlockMatrices block = assemble_block(bar.model, bar.elements);
  std::vector<int> free_rows, tip;
  for (int r = 6; r < block.K.rows(); ++r) free_rows.push_back(r);
  for (int k = 0; k < 6; ++k) tip.push_back(block.row_of(100, k) - 6);
  const Eigen::SparseMatrix<double> K = sub(block.K, free_rows).sparseView(), M = sub(block.M, free_rows).sparseView();
  const auto time = [](const auto& f) {
    const auto t0 = std::chrono::steady_clock::now();
    Superelement se = f();
    return std::pair{se, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
  };
  const auto [dense, td] = time([&] { return craig_bampton(K, M, tip, 8, ModeSolver::dense); });
  const auto [sparse, ts] = time([&] { return craig_bampton(K, M, tip, 8, ModeSolver::sparse); });
  ASSERT_EQ(sparse.modes(), 8);
  const double ef = (sparse.frequencies - dense.frequencies).cwiseQuotient(dense.frequencies).cwiseAbs().maxCoeff();
  const double eK = (sparse.K - dense.K).norm() / dense.K.norm(), eM = (sparse.M - dense.M).norm() / dense.M.norm();
  const double eT = (sparse.T - dense.T).norm() / dense.T.norm();
  std::printf("Craig-Bampton, 594 interior coordinates, 8 modes: dense %.3f s, sparse %.3f s; relative differences "
              "frequencies %.1e, K %.1e, M %.1e, T %.1e\n", td, ts, ef, eK, eM, eT);
  EXPECT_LT(ef, 1e-9);
  EXPECT_LT(eK, 1e-9);
  EXPECT_LT(eM, 1e-9);
  EXPECT_LT(eT, 1e-6);
  // M-orthonormal to round-off on the sparse path too.
  EXPECT_LT((sparse.M.bottomRightCorner(8, 8) - MatrixXd::Identity(8, 8)).norm(), 1e-12);
  // automatic takes the sparse path here: the same modes.
  EXPECT_EQ(craig_bampton(K, M, tip, 8).T, sparse.T);
}

// The block's sparse K and M (from the elements' triplets) hold the dense assembly's numbers bit
// for bit — every entry, and no stored exact zero — and an assembly without the dense copies
// gives the same sparse matrices and the same reduction (the scene's path, reduced_beams_3d.cpp).
TEST(AssembleBlock, SparseEqualsTheDenseAssemblyBitForBit) {
  const Bar bar = straight_bar(5, 0.7, Vector3d(0.1, -0.2, 0.3), Vector3d(2.0, 1.0, 0.5).normalized());
  const BlockMatrices both = assemble_block(bar.model, bar.elements), sparse = assemble_block(bar.model, bar.elements, false);
  ASSERT_EQ(both.size(), 36);
  for (const auto& [S, D] : {std::pair{&both.K_sparse, &both.K}, std::pair{&both.M_sparse, &both.M}}) {
    ASSERT_EQ(D->rows(), 36);
    EXPECT_EQ((MatrixXd(*S) - *D).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(S->nonZeros(), (D->array() != 0.0).count());
    for (int k = 0; k < S->outerSize(); ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(*S, k); it; ++it) EXPECT_NE(it.value(), 0.0);
  }
  EXPECT_EQ(sparse.K.size(), 0);
  EXPECT_EQ(sparse.M.size(), 0);
  EXPECT_EQ((MatrixXd(sparse.K_sparse) - both.K).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((MatrixXd(sparse.M_sparse) - both.M).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(sparse.nodes, both.nodes);
  EXPECT_EQ(sparse.offsets, both.offsets);
  const ReducedBlock a = reduce_block(bar.model, both, 0, {5}, 4, true), b = reduce_block(bar.model, sparse, 0, {5}, 4, true);
  EXPECT_EQ((a.matrices.K - b.matrices.K).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((a.matrices.M0 - b.matrices.M0).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ((a.superelement.T - b.superelement.T).cwiseAbs().maxCoeff(), 0.0);
}

TEST(RigidMassProperties, UniformBarHasTheTextbookMassCentreAndInertia) {
  const Vector3d start(0.1, -0.2, 0.3), axis = Vector3d(2.0, 1.0, 0.5).normalized();
  const Bar bar = straight_bar(5, 0.8, start, axis);
  const BlockMatrices block = assemble_block(bar.model, bar.elements);
  const RigidMassProperties mp = rigid_mass_properties(bar.model, block);
  const BeamSection& s = bar.section;
  const double L = bar.length;
  EXPECT_NEAR(mp.mass, s.rhoA() * L, 1e-12 * s.rhoA() * L);
  EXPECT_LT((mp.centre - (start + 0.5 * L * axis)).norm(), 1e-12);
  const Matrix3d sec = pose_of(bar.model.node(0).q0.data()).R;  // columns: axis, section axes 2, 3
  const Matrix3d Jloc = sec.transpose() * mp.inertia * sec;
  const double bend = s.rhoA() * L * L * L / 12.0;
  EXPECT_NEAR(Jloc(0, 0), s.rhoI_polar() * L, 1e-9 * bend);
  EXPECT_NEAR(Jloc(1, 1), bend + s.rhoI2() * L, 1e-9 * bend);
  EXPECT_NEAR(Jloc(2, 2), bend + s.rhoI3() * L, 1e-9 * bend);
  EXPECT_LT(std::fabs(Jloc(0, 1)) + std::fabs(Jloc(0, 2)) + std::fabs(Jloc(1, 2)), 1e-9 * bend);
}

}  // namespace
}  // namespace alphaflex


// ============================================================== the reduced body (floating frame)
namespace alphaflex {
namespace {

// A free bar reduced on the frame of its first node, `modes` fixed-interface modes, and the
// interface node `other` (-1: none) whose 6 coordinates become constraint-mode coordinates.
struct ReducedBar {
  Bar bar = straight_bar(4, 0.6, Vector3d(0.1, -0.2, 0.3), Vector3d(2.0, 1.0, 0.5).normalized());
  BlockMatrices block = assemble_block(bar.model, bar.elements);
  ReducedBlock rb;
  ReducedBar(int modes, int other) : rb(reduce_block(bar.model, block, 0, other >= 0 ? std::vector<int>{other} : std::vector<int>{}, modes)) {}
};

LocalState body_state(const ReducedBlock& rb, std::mt19937& rng, double scale) {
  const int m = rb.matrices.elastic(), n = 6 + m;
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  auto random = [&](int k, double s) {
    VectorXd x(k);
    for (int i = 0; i < k; ++i) x[i] = s * U(rng);
    return x;
  };
  LocalState s;
  s.q.resize(7 + m);
  store_pose(random(3, 1.0), exp_so3<double>(Vector3d(random(3, 1.5))), s.q.data());
  s.q.tail(m) = random(m, scale);
  s.v = random(n, 2.0);
  s.v.tail(m) *= scale;
  s.qdd = random(n, 3.0);
  s.t = 0.0;
  return s;
}

// Every element has a finite-difference test of its tangent (docs/architecture.md): K along the
// right-trivialized increments of the frame and the amplitudes, C and M in the velocities and
// accelerations, at random states with gravity, rotating and deformed, with and without
// constraint-mode coordinates. Central differences with h = 1e-6 (truncation ~1e-12 relative).
TEST(ReducedBody, TangentsMatchFiniteDifferences) {
  std::mt19937 rng(19);
  for (int other : {-1, 4}) {
    const ReducedBar rb(3, other);
    const int m = rb.rb.matrices.elastic(), n = 6 + m;
    ASSERT_EQ(m, other >= 0 ? 9 : 3);
    std::vector<int> coords;
    for (int i = 0; i < m; ++i) coords.push_back(1 + i);
    const ReducedBody body("link", 0, coords, rb.rb.matrices, Vector3d(0.0, 0.0, -9.81));
    for (int trial = 0; trial < 3; ++trial) {
      const LocalState s = body_state(rb.rb, rng, 1e-3);
      LocalResidual t;
      t.reset(n, true);
      body.evaluate(s, t, true);
      LocalResidual plain;
      plain.reset(n, false);
      body.evaluate(s, plain, false);
      EXPECT_LT((plain.r - t.r).norm(), 1e-13 * t.r.norm());
      // K: the frame by the group retraction, the amplitudes additively.
      const auto f = [&](const VectorXd& d) {
        LocalState p = s;
        retract(NodeKind::Frame3D, s.q.data(), d.data(), p.q.data());
        p.q.tail(m) = s.q.tail(m) + d.tail(m);
        LocalResidual o;
        o.reset(n, false);
        body.evaluate(p, o, false);
        return o.r;
      };
      const MatrixXd Kfd = testing::central_differences(f, VectorXd::Zero(n), testing::fixed_fd_step(1e-6));
      // r is quadratic in v and linear in q̈: central differences are exact for any step, so a
      // large one (1e-2) leaves only round-off.
      const MatrixXd Cfd = testing::central_differences(testing::element_residual_of(body, s, testing::Wrt::v), s.v,
                                                        testing::fixed_fd_step(1e-2));
      const MatrixXd Mfd = testing::central_differences(testing::element_residual_of(body, s, testing::Wrt::qdd), s.qdd,
                                                        testing::fixed_fd_step(1e-2));
      EXPECT_LT((t.K - Kfd).norm(), 1e-7 * (t.K.norm() + t.r.norm())) << "K, trial " << trial << ", other " << other;
      EXPECT_LT((t.C - Cfd).norm(), 1e-7 * t.C.norm()) << "C, trial " << trial;
      EXPECT_LT((t.M - Mfd).norm(), 1e-9 * t.M.norm()) << "M, trial " << trial;
      EXPECT_LT((t.M - t.M.transpose()).norm(), 1e-12 * t.M.norm());
    }
  }
}

// The closed-form residual and tangent (docs/theory/reduced_bodies.md, "Closed-form residual and
// tangent") against the reference: forward AD of the scalar-generic residual, which is the element
// as first written. Same r, K, C, M to round-off at random rotating, deformed, accelerating states
// with gravity scaled by a load factor, for m = 3 (modes only), 9 and 14 (constraint-mode
// coordinates and modes). Amplitudes of 1e-2 (a large deformation for this bar) so that the terms
// quadratic in ξ weigh in. Measured: largest relative difference ~1e-15 (printed).
TEST(ReducedBody, ClosedFormEqualsAutomaticDifferentiation) {
  std::mt19937 rng(23);
  double worst = 0.0;
  for (const auto& [modes, other] : {std::pair{3, -1}, std::pair{3, 4}, std::pair{8, 4}}) {
    const ReducedBar rb(modes, other);
    const int m = rb.rb.matrices.elastic(), n = 6 + m;
    std::vector<int> coords;
    for (int i = 0; i < m; ++i) coords.push_back(1 + i);
    const ReducedBody body("link", 0, coords, rb.rb.matrices, Vector3d(0.3, -1.0, -9.81));
    for (int trial = 0; trial < 3; ++trial) {
      LocalState s = body_state(rb.rb, rng, 1e-2);
      s.load_factor = 0.7;
      LocalResidual c, a;
      c.reset(n, true);
      a.reset(n, true);
      body.evaluate(s, c, true);
      reduced_body_tangent_by_ad(body, s, a);
      const double er = (c.r - a.r).norm() / a.r.norm(), eK = (c.K - a.K).norm() / a.K.norm(),
                   eC = (c.C - a.C).norm() / a.C.norm(), eM = (c.M - a.M).norm() / a.M.norm();
      EXPECT_LT(er, 1e-13) << "r, m = " << m << ", trial " << trial;
      EXPECT_LT(eK, 1e-13) << "K, m = " << m << ", trial " << trial;
      EXPECT_LT(eC, 1e-13) << "C, m = " << m << ", trial " << trial;
      EXPECT_LT(eM, 1e-13) << "M, m = " << m << ", trial " << trial;
      worst = std::max({worst, er, eK, eC, eM});
    }
  }
  std::printf("reduced body, closed form vs AD: largest relative difference %.1e\n", worst);
}

// Exactness: with every mode kept the reduced body's linearization at rest is the full linear
// free-free bar in another basis, G = [rigid motions of the frame | Φ] (square, invertible), so
// K_r = Gᵀ K G, M_r = Gᵀ M G and the eigenfrequencies agree to round-off.
TEST(ReducedBody, AllModesKeptReproduceTheFullLinearModelAtRest) {
  const ReducedBar rb(24, -1);  // 5 nodes × 6 − 6 clamped = 24 modes: all of them
  const int m = rb.rb.matrices.elastic(), n = 6 + m;
  ASSERT_EQ(n, rb.block.K.rows());
  std::vector<int> coords;
  for (int i = 0; i < m; ++i) coords.push_back(1 + i);
  const ReducedBody body("link", 0, coords, rb.rb.matrices, Vector3d::Zero());
  LocalState s;
  s.q.resize(7 + m);
  s.q.head(7) = rb.bar.model.node(0).q0;
  s.q.tail(m).setZero();
  s.v = VectorXd::Zero(n);
  s.qdd = VectorXd::Zero(n);
  LocalResidual t;
  t.reset(n, true);
  body.evaluate(s, t, true);
  // G: δx_j = δx − R_A X̂_j δθ + Φᵗ_j ξ (world), δθ_j = R_jlocᵀ δθ + Φʳ_j ξ.
  const Matrix3d RA = pose_of(s.q.data()).R;
  MatrixXd G = MatrixXd::Zero(n, n);
  for (size_t a = 0; a < rb.block.nodes.size(); ++a) {
    const int o = rb.block.offsets[a];
    G.block<3, 3>(o, 0).setIdentity();
    G.block<3, 3>(o, 3) = -RA * hat<double>(rb.rb.positions[a]);
    G.block<3, 3>(o + 3, 3) = rb.rb.rotations[a].transpose();
    G.block(o, 6, 3, m) = RA * rb.rb.shapes[a].topRows<3>();
    G.block(o + 3, 6, 3, m) = rb.rb.shapes[a].bottomRows<3>();
  }
  const MatrixXd Mg = G.transpose() * rb.block.M * G, Kg = G.transpose() * rb.block.K * G;
  EXPECT_LT((t.M - Mg).norm(), 1e-12 * Mg.norm());
  EXPECT_LT((t.K - Kg).norm(), 1e-9 * Kg.norm());
  const VectorXd full = generalized_eigenvalues(rb.block.K, rb.block.M), red = generalized_eigenvalues(t.K, t.M);
  for (int j = 6; j < n; ++j) EXPECT_NEAR(red[j] / full[j], 1.0, 1e-9) << "mode " << j;
  for (int j = 0; j < 6; ++j) EXPECT_LT(std::fabs(red[j]), 1e-9 * full[6]) << "rigid mode " << j;
  // The rigid part of the mass is the block's rigid mass properties (about the frame's origin).
  const RigidMassProperties mp = rigid_mass_properties(rb.bar.model, rb.block);
  EXPECT_NEAR(t.M(0, 0), mp.mass, 1e-12 * mp.mass);
}

// Rigid limit: with no elastic coordinate and the frame at the centre of mass, 𝕄 = diag(m I, J)
// and the equations are RigidBody3D's Newton–Euler equations (Brüls, Cardona & Arnold 2012,
// eq. 56): same r, K, C, M at random rotating states with gravity.
TEST(ReducedBody, WithoutModesAndFrameAtTheCentreOfMassIsTheRigidBody) {
  const double mass = 2.5;
  Matrix3d J;
  J << 0.3, 0.02, -0.01, 0.02, 0.5, 0.03, -0.01, 0.03, 0.7;
  ReducedBodyMatrices d;
  d.M0 = MatrixXd::Zero(6, 6);
  d.M0.topLeftCorner<3, 3>() = mass * Matrix3d::Identity();
  d.M0.bottomRightCorner<3, 3>() = J;
  d.K = MatrixXd::Zero(0, 0);
  const Vector3d g(0.0, -9.81, 1.0);
  const ReducedBody body("b", 0, {}, d, g);
  const RigidBody3D rigid("b", 0, mass, J, g);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {
    LocalState s;
    s.q.resize(7);
    store_pose(Vector3d(U(rng), U(rng), U(rng)), exp_so3<double>(Vector3d(U(rng), U(rng), U(rng))), s.q.data());
    s.v = VectorXd::Random(6) * 3.0;
    s.qdd = VectorXd::Random(6) * 5.0;
    s.load_factor = 0.7;
    LocalResidual a, b;
    a.reset(6, true);
    b.reset(6, true);
    body.evaluate(s, a, true);
    rigid.evaluate(s, b, true);
    EXPECT_LT((a.r - b.r).norm(), 1e-13 * b.r.norm());
    EXPECT_LT((a.K - b.K).norm(), 1e-13 * b.r.norm());
    EXPECT_LT((a.C - b.C).norm(), 1e-13 * b.C.norm());
    EXPECT_LT((a.M - b.M).norm(), 1e-13 * b.M.norm());
  }
}



// The element in the Lie-group generalized-α (Brüls, Cardona & Arnold 2012) with its frame node
// and one-unknown amplitude nodes: a free flexible bar (frame at one end, the other end's 6
// constraint modes and 2 fixed-interface modes) tumbling and vibrating without gravity. The
// continuous system conserves energy and linear and angular momentum; with ρ∞ = 1 (no numerical
// dissipation) and h = 1e-4 s over 0.05 s the discrete drifts measured ~1e-6 (printed); the
// tolerance is 10× that.
TEST(ReducedBody, FreeTumblingBarConservesEnergyAndMomentaInGeneralizedAlpha) {
  const ReducedBar rb(2, 4);
  const int m = rb.rb.matrices.elastic();
  Model model;
  Node f = rb.bar.model.node(0);
  f.v0 = VectorXd::Zero(6);
  f.v0 << 0.3, -0.2, 0.1, 1.0, 4.0, -2.0;
  model.add_node(f);
  std::vector<int> coords;
  for (int i = 0; i < m; ++i) {
    Node c;
    c.name = "xi" + std::to_string(i);
    c.kind = NodeKind::LineParticle2D;
    c.ndof = c.nconf = 1;
    c.q0 = VectorXd::Zero(1);
    c.v0 = VectorXd::Constant(1, i == 6 ? 0.05 : 0.0);  // the first normal mode vibrates
    coords.push_back(model.add_node(c));
  }
  model.add_element(std::make_unique<ReducedBody>("link", 0, coords, rb.rb.matrices, Vector3d::Zero()));
  const ReducedBodyMatrices& d = rb.rb.matrices;
  auto invariants = [&](const MechanicalState& s, double& energy, Vector3d& p, Vector3d& L) {
    const Pose<double> F = pose_of(s.q.data());
    VectorXd xi(m), w(6 + m);
    for (int i = 0; i < m; ++i) xi[i] = s.q[7 + i];
    w << F.R.transpose() * s.v.head<3>(), s.v.segment<3>(3), s.v.tail(m);
    const VectorXd h = d.mass_matrix(xi) * w;
    energy = 0.5 * w.dot(h) + 0.5 * xi.dot(d.K * xi);
    p = F.R * h.head<3>();
    L = F.x.cross(p) + F.R * h.segment<3>(3);
  };
  Subdomain sub(model, PETSC_COMM_SELF);
  SaddlePointSystem sys(sub);
  LinearSolver solver(PETSC_COMM_SELF);
  IntegratorOptions opt;
  opt.newton.rtol = 1e-12;
  // Full Newton by name (the default takes modified Newton for a reduced body): the drifts are those
  // of the scheme, Newton converged quadratically far below rtol.
  opt.newton.method = NewtonOptions::Method::full;
  GeneralizedAlpha ga(sys, solver, AlphaParameters::from_rho_inf(1.0), opt);
  MechanicalState s = model.initial_state();
  ga.initialize(s);
  double e0, e;
  Vector3d p0, L0, p, L;
  invariants(s, e0, p0, L0);
  double de = 0.0, dp = 0.0, dL = 0.0;
  for (int n = 0; n < 500; ++n) {
    ga.step(s, 1e-4);
    invariants(s, e, p, L);
    de = std::max(de, std::fabs(e - e0) / e0);
    dp = std::max(dp, (p - p0).norm() / p0.norm());
    dL = std::max(dL, (L - L0).norm() / L0.norm());
  }
  std::printf("free tumbling reduced bar: relative drifts energy %.2e, momentum %.2e, angular momentum %.2e\n", de, dp, dL);
  EXPECT_LT(de, 1e-5);
  EXPECT_LT(dp, 1e-5);
  EXPECT_LT(dL, 1e-5);
}

}  // namespace
}  // namespace alphaflex

// ---- The full mesh rebuilt from a reduced body's state (model/mesh_reconstruction.hpp; issue 19).
namespace alphaflex {
namespace {

// The bar's mesh on its reduction: points in block order (the bar's nodes 0 … n), its beam
// elements on them.
std::shared_ptr<const MeshReconstruction> bar_mesh(const ReducedBar& rb) {
  std::vector<MeshReconstruction::Point> points(rb.rb.positions.size());
  for (size_t a = 0; a < points.size(); ++a) {
    EXPECT_EQ(rb.block.nodes[a], static_cast<int>(a));
    points[a] = {rb.rb.positions[a], rb.rb.rotations[a], rb.rb.shapes[a], rb.bar.model.node(static_cast<int>(a)).q0.head<3>()};
  }
  std::vector<std::shared_ptr<const Element>> cells;
  for (int e : rb.bar.elements) cells.emplace_back(rb.bar.model.elements()[static_cast<size_t>(e)]->renumbered(
      rb.bar.model.elements()[static_cast<size_t>(e)]->nodes()));
  return std::make_shared<const MeshReconstruction>(std::move(points), std::move(cells));
}

// The points' velocities are the time derivatives of their poses: central differences of the
// pose map along (ẋ_f, Ω_f, ξ̇) — the frame retracted by ±h v, ξ ± h ξ̇ — at random rotating,
// deformed states (truncation O(h²) ≈ 1e-10 relative with h = 1e-5).
TEST(MeshReconstruction, PointVelocitiesAreTheTimeDerivativesOfThePoses) {
  std::mt19937 rng(1919);
  const ReducedBar rb(3, 4);
  const auto mesh = bar_mesh(rb);
  const int m = rb.rb.matrices.elastic();
  for (int trial = 0; trial < 3; ++trial) {
    const LocalState s = body_state(rb.rb, rng, 0.05);
    const LocalState p = mesh->state(s);
    const double h = 1e-5;
    auto moved = [&](double sign) {
      LocalState t = s;
      const VectorXd d = sign * h * s.v.head<6>();
      retract(NodeKind::Frame3D, s.q.data(), d.data(), t.q.data());
      t.q.tail(m) = s.q.tail(m) + sign * h * s.v.tail(m);
      return mesh->state(t);
    };
    const LocalState plus = moved(1.0), minus = moved(-1.0);
    for (size_t a = 0; a < mesh->points(); ++a) {
      const Pose<double> P = pose_of(plus.q.data() + 7 * a), M = pose_of(minus.q.data() + 7 * a);
      const Vector3d xd = (P.x - M.x) / (2 * h), W = log_so3<double>(Matrix3d(M.R.transpose() * P.R)) / (2 * h);
      EXPECT_LT((xd - p.v.segment<3>(6 * a)).norm(), 1e-8 * (1.0 + xd.norm())) << "point " << a << ", trial " << trial;
      EXPECT_LT((W - p.v.segment<3>(6 * a + 3)).norm(), 1e-8 * (1.0 + W.norm())) << "point " << a << ", trial " << trial;
      // The poses are the reduced block's own (ReducedBlock::node_pose).
      Vector3d x;
      Matrix3d R;
      rb.rb.node_pose(a, pose_of(s.q.data()).x, pose_of(s.q.data()).R, s.q.tail(m), x, R);
      EXPECT_LT((x - pose_of(p.q.data() + 7 * a).x).norm(), 1e-14 * (1.0 + x.norm()));
      EXPECT_LT((R - pose_of(p.q.data() + 7 * a).R).norm(), 1e-14);
    }
  }
}

// A point sensor inside a reduced body reads point_position (model/sensor.cpp), not the whole
// state(): the two must agree to the last bit, so that a sensor's value does not depend on which
// path computed it (the sensors CSV of the slider-crank's reduced rod was bit-identical).
TEST(MeshReconstruction, OnePointsPositionIsTheWholeMeshsToTheLastBit) {
  std::mt19937 rng(2019);
  const ReducedBar rb(3, 4);
  const auto mesh = bar_mesh(rb);
  for (int trial = 0; trial < 3; ++trial) {
    const LocalState s = body_state(rb.rb, rng, 0.05);
    const LocalState p = mesh->state(s);
    for (size_t a = 0; a < mesh->points(); ++a) {
      const Vector3d x = mesh->point_position(s, a);
      for (int c = 0; c < 3; ++c) EXPECT_EQ(x[c], p.q[7 * static_cast<Eigen::Index>(a) + c]) << "point " << a << ", trial " << trial;
    }
  }
}

// A section-force sensor of a reduced body reads one element's element_output (model/sensor.cpp),
// not the whole output's element_outputs: the two must agree to the last bit, for beams and for
// shells, whose von Mises stresses are recomputed from the recovered resultants (the `derived`
// results). Also the layout both paths share: output_cell inverts output_index, and the body's
// whole output holds element_outputs at output_index. The shells' mesh: a 3 × 2 plate of
// quadrilaterals with arbitrary basis rows (the bit-identity holds for any basis), so that the
// elements share points in several ways.
void expect_one_element_is_the_whole_mesh(const MeshReconstruction& mesh, const ReducedBodyMatrices& matrices, const LocalState& s,
                                          const std::string& what) {
  const std::vector<VectorXd> all = mesh.element_outputs(s);
  ASSERT_EQ(all.size(), mesh.elements().size());
  std::vector<int> coords;
  for (int i = 0; i < mesh.elastic(); ++i) coords.push_back(1 + i);
  ReducedBody body("block", 0, coords, matrices, Vector3d::Zero());
  body.attach_reconstruction(std::shared_ptr<const MeshReconstruction>(&mesh, [](const MeshReconstruction*) {}));
  VectorXd values;
  body.output(s, values);
  ASSERT_EQ(values.size(), mesh.output_size());
  double largest = 0.0;
  for (size_t k = 0; k < all.size(); ++k) {
    const VectorXd one = mesh.element_output(s, k);
    ASSERT_EQ(one.size(), all[k].size()) << what << ", element " << k;
    for (Eigen::Index c = 0; c < one.size(); ++c) {
      EXPECT_EQ(one[c], all[k][c]) << what << ", element " << k << ", value " << c;
      const Eigen::Index at = mesh.output_index(k, static_cast<int>(c));
      EXPECT_EQ(values[at], one[c]) << what << ", element " << k << ", value " << c;
      size_t kk = 0;
      int cc = -1;
      EXPECT_TRUE(mesh.output_cell(at, kk, cc));
      EXPECT_EQ(kk, k);
      EXPECT_EQ(cc, c);
      largest = std::max(largest, std::abs(one[c]));
    }
  }
  EXPECT_GT(largest, 0.0) << what << ": the outputs are not all zero";
  size_t k = 0;
  int c = 0;
  EXPECT_FALSE(mesh.output_cell(6 * static_cast<Eigen::Index>(mesh.points()) - 1, k, c)) << "a point's index is no cell's";
}

TEST(MeshReconstruction, OneElementsOutputIsTheWholeMeshsToTheLastBit) {
  std::mt19937 rng(1919);
  const ReducedBar rb(3, 4);
  const auto bar = bar_mesh(rb);
  for (int trial = 0; trial < 3; ++trial)
    expect_one_element_is_the_whole_mesh(*bar, rb.rb.matrices, body_state(rb.rb, rng, 0.05), "beams, trial " + std::to_string(trial));

  // Shells: points (i, j) of a 0.3 m × 0.2 m plate, 0.1 m apart, counter-clockwise quadrilaterals.
  const int nx = 3, ny = 2, m = 5;
  const ShellSection section = ShellSection::isotropic(2.1e11, 0.3, 7800, 0.002);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<MeshReconstruction::Point> points;
  std::vector<Pose<double>> rest;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      MeshReconstruction::Point p;
      p.X = Vector3d(0.1 * i, 0.1 * j, 0.0);
      p.shape = MatrixXd::NullaryExpr(6, m, [&] { return 0.01 * U(rng); });
      p.initial = p.X;
      points.push_back(p);
      rest.push_back({p.X, Matrix3d::Identity()});
    }
  std::vector<std::shared_ptr<const Element>> cells;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i;
      const std::vector<int> nodes{a, a + 1, a + nx + 2, a + nx + 1};
      std::vector<Pose<double>> ref;
      for (int n : nodes) ref.push_back(rest[static_cast<size_t>(n)]);
      cells.push_back(std::make_shared<const ReissnerMindlinShell>("plate" + std::to_string(cells.size()), nodes, section, ref,
                                                                   std::vector<Vector3d>(4, Vector3d::UnitZ()), Vector3d::UnitX(),
                                                                   Vector3d::Zero()));
    }
  const double t = section.thickness;
  const MeshReconstruction plate(points, cells, {}, [t](VectorXd& v) { ReissnerMindlinShell::von_mises_from_resultants(v, t); });
  // The body's matrices only size its coordinates here (its output is the mesh's): a unit mass
  // and stiffness, no ξ-dependent inertia.
  ReducedBodyMatrices matrices;
  matrices.M0 = MatrixXd::Identity(6 + m, 6 + m);
  matrices.C.assign(m, MatrixXd::Zero(3, 6 + m));
  matrices.M2.assign(m * m, Matrix3d::Zero());
  matrices.K = MatrixXd::Identity(m, m);
  for (int trial = 0; trial < 3; ++trial) {
    LocalState s;
    s.q.resize(7 + m);
    store_pose(Vector3d(U(rng), U(rng), U(rng)), exp_so3<double>(Vector3d(1.5 * U(rng), 1.5 * U(rng), 1.5 * U(rng))), s.q.data());
    for (int i = 0; i < m; ++i) s.q[7 + i] = U(rng);
    s.v = VectorXd::NullaryExpr(6 + m, [&] { return 2.0 * U(rng); });
    s.qdd = VectorXd::Zero(6 + m);
    expect_one_element_is_the_whole_mesh(plate, matrices, s, "shells, trial " + std::to_string(trial));
  }
}

// Section forces recovered from the modes against statics: a cantilever (the frame node clamped)
// with its tip as the interface point and no normal mode — the constraint modes give the exact
// static response to a tip load (Craig & Bampton 1968) — under a small tip force P along section
// axis 2. Beam theory: V2 = P along the bar, M3 = P (L − s) at the element's mid-point s (sign
// by the section frame), the other resultants 0. The geometrically exact element's output at the
// rebuilt poses matches to O(deflection/L) ≈ 1e-6 (P chosen so). Also the layout of
// ReducedBody::output(): `M3[k]` is element k's M3, `point_displacement[3a+i]` point a's.
TEST(MeshReconstruction, SectionForcesFromTheModesMatchCantileverStatics) {
  const ReducedBar rb(0, 4);
  const auto mesh = bar_mesh(rb);
  const int m = rb.rb.matrices.elastic();
  ASSERT_EQ(m, 6);
  const Pose<double> F = pose_of(rb.bar.model.node(0).q0.data());
  const Pose<double> tip0 = pose_of(rb.bar.model.node(4).q0.data());
  const double P = 1.0;  // N: tip deflection P L³ / 3EI ≈ 3e-4 m for this bar
  // K̃ ξ = f: ξ are the tip's coordinates (δx world, δθ tip frame); the force in world components.
  VectorXd f = VectorXd::Zero(m);
  f.head<3>() = P * tip0.R.col(1);
  const VectorXd xi = rb.rb.matrices.K.ldlt().solve(f);
  std::vector<int> coords;
  for (int i = 0; i < m; ++i) coords.push_back(1 + i);
  ReducedBody body("link", 0, coords, rb.rb.matrices, Vector3d::Zero());
  body.attach_reconstruction(mesh);
  LocalState s;
  s.q.resize(7 + m);
  store_pose(F.x, F.R, s.q.data());
  s.q.tail(m) = xi;
  s.v = VectorXd::Zero(6 + m);
  s.qdd = VectorXd::Zero(6 + m);
  VectorXd values;
  body.output(s, values);
  const std::vector<std::string> names = body.output_names();
  ASSERT_EQ(static_cast<Eigen::Index>(names.size()), values.size());
  auto value = [&](const std::string& n) {
    const auto it = std::find(names.begin(), names.end(), n);
    EXPECT_NE(it, names.end()) << n;
    return values[it - names.begin()];
  };
  const double L = rb.bar.length, le = L / 4;
  for (int k = 0; k < 4; ++k) {
    const std::string e = "[" + std::to_string(k) + "]";
    const double Mk = P * (L - (k + 0.5) * le);
    EXPECT_NEAR(std::abs(value("M3" + e)), Mk, 1e-5 * P * L) << "element " << k;
    EXPECT_NEAR(std::abs(value("V2" + e)), P, 1e-5 * P) << "element " << k;
    for (const char* zero : {"N", "V3", "T", "M2"}) EXPECT_NEAR(value(zero + e), 0.0, 1e-5 * P * L) << zero << e;
  }
  // The tip displaced by the solution's own tip coordinates, reported as point 4's displacement.
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(value("point_displacement[" + std::to_string(12 + i) + "]"), xi[i], 1e-15);
  // The discrete tip deflection of n one-point-integrated two-node elements: the curvature of each
  // is M(s_mid)/EI, so the bending part is the midpoint rule of ∫ P (L − s)² / EI ds, L³/3 less
  // h² L / 12 (the rule's error for a quadratic), i.e. P L³/(3 EI) (1 − 1/(4 n²)); plus shear P L/(k G A).
  const double deflection = P * std::pow(L, 3) / (3 * rb.bar.section.EI3()) * (1.0 - 1.0 / 64.0) + P * L / rb.bar.section.GA2();
  EXPECT_NEAR(xi.head<3>().dot(tip0.R.col(1)), deflection, 1e-6 * deflection);
  // Why the odd part (MeshReconstruction::element_outputs): the element's exact strain at the
  // rebuilt poses alone carries a second-order axial force EA θ²/2 far above the 1e-5 P bound.
  const LocalState points = mesh->state(s);
  VectorXd direct;
  mesh->elements()[3]->output(mesh->element_state(points, 3), direct);
  EXPECT_GT(std::abs(direct[0]), 0.1 * P);
}

}  // namespace
}  // namespace alphaflex

// ---- Geometric stiffness (docs/theory/reduced_bodies.md, "Geometric stiffness"): the cubic term
// of the block's own beam energy along the basis, T = ∂³U/∂ξ³ at rest.
namespace alphaflex {
namespace {

// Residual and tangent of the bar's own elements at state q (model order = block order here: one
// Frame3D node after the other), for the full nonlinear static reference.
void full_static_system(const Bar& b, const BlockMatrices& block, const VectorXd& q, VectorXd& r, MatrixXd& K) {
  MechanicalState s = b.model.initial_state();
  s.q = q;
  s.v.setZero();
  s.qdd.setZero();
  r = VectorXd::Zero(block.K.rows());
  K = MatrixXd::Zero(block.K.rows(), block.K.cols());
  LocalResidual out;
  for (int e : b.elements) {
    const Element& el = *b.model.elements()[static_cast<size_t>(e)];
    LocalState ls = b.model.local_state(el, s);
    ls.load_factor = 0.0;
    out.reset(static_cast<int>(ls.v.size()), true);
    el.evaluate(ls, out, true);
    std::vector<int> rows;
    for (int node : el.nodes())
      for (int k = 0; k < 6; ++k) rows.push_back(block.row_of(node, k));
    for (size_t i = 0; i < rows.size(); ++i) {
      r[rows[i]] += out.r[static_cast<Eigen::Index>(i)];
      for (size_t j = 0; j < rows.size(); ++j) K(rows[i], rows[j]) += out.K(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    }
  }
}

// The full nonlinear mesh's static equilibrium under the dead loads `load` with node 0 clamped
// (`free_rows`: the rows 6 … n − 1), by Newton on the frames from the initial state.
VectorXd full_static_solution(const Bar& bar, const BlockMatrices& block, const VectorXd& load, const std::vector<int>& free_rows) {
  const Eigen::Index nrows = load.size();
  VectorXd q = bar.model.initial_state().q;
  for (int it = 0; it < 30; ++it) {
    VectorXd r;
    MatrixXd K;
    full_static_system(bar, block, q, r, K);
    const VectorXd g = VectorXd(r - load).tail(nrows - 6);
    if (g.norm() < 1e-10 * load.norm()) break;
    VectorXd dx = VectorXd::Zero(nrows);
    dx.tail(nrows - 6) = -sub(K, free_rows).lu().solve(g);
    bar.model.retract(q, dx);
  }
  return q;
}

// The reduced body's static equilibrium K̃ξ + ½T[ξ,ξ] + ⅙Q[ξ,ξ,ξ] = f̃ by Newton (at most
// `iterations`), f̃ the tip's translation rows of the basis times the tip load in the frame's axes.
VectorXd reduced_static_amplitudes(const ReducedBodyMatrices& d, const MatrixXd& tip_shape, const Matrix3d& R0,
                                   const Vector3d& tip_load, int iterations) {
  const VectorXd f = tip_shape.topRows<3>().transpose() * (R0.transpose() * tip_load);
  VectorXd xi = VectorXd::Zero(d.elastic());
  for (int it = 0; it < iterations; ++it) {
    MatrixXd G1, G2;
    d.geometric_terms(xi, G1, G2);
    const VectorXd g = d.elastic_force(xi) - f;
    if (g.norm() < 1e-12 * f.norm()) break;
    xi -= (d.K + G1 + 0.5 * G2).lu().solve(g);
  }
  return xi;
}

// The reduced body with geometric stiffness: its tangent against central differences (the cubic
// term's ½T[ξ,ξ] and T[ξ]), the closed form against AD of the scalar-generic residual, and the
// elastic force against the gradient of elastic_energy (U = ½ξᵀK̃ξ + ⅙T[ξ,ξ,ξ]). Amplitudes of
// 1e-2 so that the cubic term weighs in (it is ~10 % of K̃ξ there).
TEST(ReducedBodyGeometricStiffness, TangentsMatchFiniteDifferencesAndAD) {
  std::mt19937 rng(31);
  for (const auto& [modes, other] : {std::pair{3, -1}, std::pair{3, 4}}) {
    ReducedBar rb(modes, other);
    double asym = 0.0;
    nonlinear_stiffness(rb.bar.model, rb.bar.elements, rb.block, rb.rb, &asym);
    std::printf("geometric stiffness of a 4-element bar, m = %d: (i,j) asymmetry of T's differences %.1e\n", rb.rb.matrices.elastic(), asym);
    // The O(h²) truncation of the second differences, h = 1e-3 of the bar. With the 3 bending
    // modes alone T vanishes (w → −w symmetry: no cubic term without the stretch) and its
    // relative asymmetry is that of round-off over round-off: checked with the constraint modes.
    if (other >= 0) EXPECT_LT(asym, 1e-4);
    const int m = rb.rb.matrices.elastic(), n = 6 + m;
    std::vector<int> coords;
    for (int i = 0; i < m; ++i) coords.push_back(1 + i);
    const ReducedBody body("link", 0, coords, rb.rb.matrices, Vector3d(0.0, 0.0, -9.81));
    for (int trial = 0; trial < 3; ++trial) {
      const LocalState s = body_state(rb.rb, rng, 1e-2);
      LocalResidual t, a;
      t.reset(n, true);
      a.reset(n, true);
      body.evaluate(s, t, true);
      reduced_body_tangent_by_ad(body, s, a);
      EXPECT_LT((t.r - a.r).norm(), 1e-13 * a.r.norm());
      EXPECT_LT((t.K - a.K).norm(), 1e-13 * a.K.norm());
      const auto f = [&](const VectorXd& d) {
        LocalState p = s;
        retract(NodeKind::Frame3D, s.q.data(), d.data(), p.q.data());
        p.q.tail(m) = s.q.tail(m) + d.tail(m);
        LocalResidual o;
        o.reset(n, false);
        body.evaluate(p, o, false);
        return o.r;
      };
      const MatrixXd Kfd = testing::central_differences(f, VectorXd::Zero(n), testing::fixed_fd_step(1e-6));
      EXPECT_LT((t.K - Kfd).norm(), 1e-7 * (t.K.norm() + t.r.norm())) << "K, trial " << trial << ", other " << other;
      // The elastic force is the gradient of the elastic energy.
      const VectorXd xi = s.q.tail(m);
      const auto energy = [&](const VectorXd& x) {
        VectorXd q = s.q;
        q.tail(m) = x;
        return VectorXd::Constant(1, body.elastic_energy(q));
      };
      const VectorXd grad = testing::central_differences(energy, xi, testing::fixed_fd_step(1e-6)).row(0).transpose();
      const VectorXd force = rb.rb.matrices.elastic_force(xi);
      EXPECT_LT((grad - force).norm(), 1e-7 * force.norm());
      if (other >= 0) EXPECT_GT((force - rb.rb.matrices.K * xi).norm(), 1e-3 * force.norm());  // the nonlinear terms are there
    }
  }
}

// The packed storage and contraction (SymmetricTensor) against the straightforward evaluation on
// full arrays: T and Q generic fully symmetric tensors (sums of tensor powers of 5 random vectors,
// so every entry differs), every entry read back through the packed index, and G₁ = Σₖ T(·,·,k) ξₖ,
// G₂ = Σₖₗ Q(·,·,k,l) ξₖξₗ and the elastic force K̃ξ + ½T[ξ,ξ] + ⅙Q[ξ,ξ,ξ] summed over all m³ and
// m⁴ entries: equal to round-off (the sums run in another order). m = 1 and 2 are the edge cases
// of the multiplicities (all indices equal), 9 a general one.
TEST(ReducedBodyGeometricStiffness, PackedEvaluationEqualsTheFullTensorsToRoundOff) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const int m : {1, 2, 9}) {
    std::vector<VectorXd> a(5, VectorXd(m));
    for (VectorXd& v : a)
      for (int i = 0; i < m; ++i) v[i] = u(rng);
    const auto full3 = [&](int i, int j, int k, int) {
      double t = 0.0;
      for (const VectorXd& v : a) t += v[i] * v[j] * v[k];
      return t;
    };
    const auto full4 = [&](int i, int j, int k, int l) {
      double t = 0.0;
      for (const VectorXd& v : a) t += v[i] * v[j] * v[k] * v[l];
      return t;
    };
    ReducedBodyMatrices d;
    d.K = MatrixXd::Identity(m, m);
    d.T = SymmetricTensor(3, m, full3);
    d.Q = SymmetricTensor(4, m, full4);
    EXPECT_EQ(d.T.values().size(), static_cast<size_t>(m * (m + 1) * (m + 2) / 6));
    EXPECT_EQ(d.Q.values().size(), static_cast<size_t>(m * (m + 1) * (m + 2) * (m + 3) / 24));
    VectorXd xi(m);
    for (int i = 0; i < m; ++i) xi[i] = u(rng);
    MatrixXd G1f = MatrixXd::Zero(m, m), G2f = MatrixXd::Zero(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        for (int k = 0; k < m; ++k) {
          EXPECT_EQ(d.T(i, j, k), full3(std::min({i, j, k}), i + j + k - std::min({i, j, k}) - std::max({i, j, k}), std::max({i, j, k}), -1))
              << i << j << k;
          G1f(i, j) += full3(i, j, k, -1) * xi[k];
          for (int l = 0; l < m; ++l) {
            G2f(i, j) += full4(i, j, k, l) * xi[k] * xi[l];
            int x[4] = {i, j, k, l};
            std::sort(x, x + 4);
            EXPECT_EQ(d.Q(i, j, k, l), full4(x[0], x[1], x[2], x[3]));
          }
        }
    const VectorXd ff = xi + 0.5 * G1f * xi + G2f * xi / 6.0;
    MatrixXd G1, G2;
    d.geometric_terms(xi, G1, G2);
    EXPECT_LT((G1 - G1f).norm(), 1e-13 * G1f.norm()) << "m = " << m;
    EXPECT_LT((G2 - G2f).norm(), 1e-13 * G2f.norm()) << "m = " << m;
    EXPECT_EQ((G1 - G1.transpose()).norm(), 0.0);
    EXPECT_EQ((G2 - G2.transpose()).norm(), 0.0);
    EXPECT_LT((d.elastic_force(xi) - ff).norm(), 1e-13 * ff.norm()) << "m = " << m;
  }
  EXPECT_THROW(SymmetricTensor(2, 3, [](int, int, int, int) { return 0.0; }), std::invalid_argument);
}

// nonlinear_stiffness differentiates the elements' internal forces alone (Element::internal_force)
// where they offer them, else it evaluates them whole at rest: the same bar's T and Q both ways —
// the beams as they are, and wrapped in an element that offers only evaluate() — bit for bit.
class EvaluateOnly final : public Element {
 public:
  explicit EvaluateOnly(std::unique_ptr<Element> inner) : Element(inner->name(), inner->nodes()), inner_(std::move(inner)) {}
  const char* type() const override { return "evaluate_only"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<EvaluateOnly>(inner_->renumbered(nodes())); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override { inner_->evaluate(s, out, tangent); }

 private:
  std::shared_ptr<const Element> inner_;
};

TEST(ReducedBodyGeometricStiffness, InternalForcesAloneGiveTheSameTensorsBitForBit) {
  ReducedBar rb(3, 4);
  Model wrapped;
  for (const Node& nd : rb.bar.model.nodes()) wrapped.add_node(nd);
  for (int e : rb.bar.elements) {
    const Element& el = *rb.bar.model.elements()[static_cast<size_t>(e)];
    VectorXd r;
    ASSERT_TRUE(el.internal_force(rb.bar.model.initial_state().q.head(14), r));  // the beams offer it
    wrapped.add_element(std::make_unique<EvaluateOnly>(el.renumbered(el.nodes())));
  }
  ReducedBlock direct = rb.rb, whole = rb.rb;
  nonlinear_stiffness(rb.bar.model, rb.bar.elements, rb.block, direct);
  nonlinear_stiffness(wrapped, rb.bar.elements, rb.block, whole);
  ASSERT_EQ(direct.matrices.T.values().size(), whole.matrices.T.values().size());
  ASSERT_EQ(direct.matrices.Q.values().size(), whole.matrices.Q.values().size());
  EXPECT_TRUE(direct.matrices.T.values() == whole.matrices.T.values());
  EXPECT_TRUE(direct.matrices.Q.values() == whole.matrices.Q.values());
  double big = 0.0;
  for (double t : direct.matrices.T.values()) big = std::max(big, std::abs(t));
  EXPECT_GT(big, 0.0);  // the constraint modes carry the stretch: T is not zero here
}

// All modes and small motions still give the full linear model: at rest (ξ = 0) T[ξ] and Q[ξ,ξ]
// vanish, so the body's r, K, C, M with geometric stiffness equal those without (bit for bit: the
// added terms are exact zeros), which AllModesKeptReproduceTheFullLinearModelAtRest compares with
// the full mesh.
TEST(ReducedBodyGeometricStiffness, AtRestTheLinearizationIsUnchanged) {
  ReducedBar rb(24, -1);
  const ReducedBodyMatrices linear = rb.rb.matrices;
  nonlinear_stiffness(rb.bar.model, rb.bar.elements, rb.block, rb.rb);
  ASSERT_EQ(rb.rb.matrices.T.dim(), 24);
  const int m = 24, n = 6 + m;
  std::vector<int> coords;
  for (int i = 0; i < m; ++i) coords.push_back(1 + i);
  const ReducedBody with("link", 0, coords, rb.rb.matrices, Vector3d::Zero()), without("link", 0, coords, linear, Vector3d::Zero());
  LocalState s;
  s.q.resize(7 + m);
  s.q.head(7) = rb.bar.model.node(0).q0;
  s.q.tail(m).setZero();
  s.v = VectorXd::Zero(n);
  s.qdd = VectorXd::Zero(n);
  LocalResidual a, b;
  a.reset(n, true);
  b.reset(n, true);
  with.evaluate(s, a, true);
  without.evaluate(s, b, true);
  EXPECT_EQ((a.K - b.K).norm(), 0.0);
  EXPECT_EQ((a.M - b.M).norm(), 0.0);
  EXPECT_EQ((a.r - b.r).norm(), 0.0);
}

// T against the full nonlinear mesh and the analytic stiffening: a cantilever (the frame node
// clamped, interface = the tip) under an axial tension P and a small transverse tip load F.
// Beam-column under tension (Timoshenko & Gere, Theory of Elastic Stability, 2nd ed. (1961),
// §1.11): w = F (kL − tanh kL) / (P k), k² = P/EI, i.e. w / w_lin = 3 (kL − tanh kL) / (kL)³;
// EI is the mesh's own, from its linear tip deflection w_lin = F L³ / (3 EI). With kL = 1.5 the
// tension stiffens the bar by half (ratio 0.529). The reduced model without geometric stiffness
// has no stiffening at all (ratio 1); with it, the ratio of the full nonlinear mesh (Newton on
// all its frames) to the Ritz error of the basis: 6 constraint modes alone give the Rayleigh
// quotient of the static cubic shape, 1 / (1 + (2/5)(kL)²) = 0.526; all modes the mesh's own.
TEST(ReducedBodyGeometricStiffness, TensionStiffensTheCantileverAsTheFullMeshAndTheBeamColumn) {
  const int ne = 8;
  const Vector3d axis = Vector3d(2.0, 1.0, 0.5).normalized();
  const Bar bar = straight_bar(ne, 0.8, Vector3d(0.1, -0.2, 0.3), axis);
  const BlockMatrices block = assemble_block(bar.model, bar.elements);
  const int nrows = static_cast<int>(block.K.rows());
  const Matrix3d sec = pose_of(bar.model.node(0).q0.data()).R;
  const Vector3d e2 = sec.col(1);  // a transverse direction (a principal axis of the section)
  const int tip = ne;
  std::vector<int> free_rows;
  for (int r = 6; r < nrows; ++r) free_rows.push_back(r);
  // The mesh's linear tip deflection under F e2 → its own EI.
  const double L = bar.length, F = 1e-2;
  const MatrixXd Kc = sub(block.K, free_rows);
  VectorXd load = VectorXd::Zero(nrows);
  load.segment<3>(block.row_of(tip)) = F * e2;
  const VectorXd lin = Kc.ldlt().solve(VectorXd(load.tail(nrows - 6)));
  const double w_lin = e2.dot(lin.segment<3>(block.row_of(tip) - 6));
  const double EI = F * L * L * L / (3.0 * w_lin);
  const double kL = 1.5, P = kL * kL * EI / (L * L);
  const double analytic = 3.0 * (kL - std::tanh(kL)) / (kL * kL * kL);
  load.segment<3>(block.row_of(tip)) += P * axis;
  // Full nonlinear mesh: Newton on the frames (node 0 clamped), dead loads.
  const VectorXd q = full_static_solution(bar, block, load, free_rows);
  const Pose<double> p0 = pose_of(bar.model.node(0).q0.data());
  const Vector3d tip0 = pose_of(bar.model.node(tip).q0.data()).x;
  const double w_full = e2.dot(pose_of(q.data() + 7 * tip).x - tip0);
  // Reduced: K̃ξ + ½T[ξ,ξ] = f̃ (f̃ = the tip's basis rows times the load, in the frame's axes).
  const auto reduced = [&](int modes, bool geometric) {
    const ReducedBlock rb = reduce_block(bar.model, block, 0, {tip}, modes);
    ReducedBlock rg = rb;
    if (geometric) nonlinear_stiffness(bar.model, bar.elements, block, rg);
    const ReducedBodyMatrices& d = rg.matrices;
    const size_t a = static_cast<size_t>(tip);  // block order = node order
    const VectorXd xi = reduced_static_amplitudes(d, rb.shapes[a], p0.R, load.segment<3>(block.row_of(tip)), 30);
    return e2.dot(p0.R * (rb.shapes[a].topRows<3>() * xi));
  };
  const int all = 24;  // of 42: the quartic term's m⁴ storage and 4m³/3 evaluations; 24 converge already
  const double r_full = w_full / w_lin, r_lin = reduced(4, false) / w_lin, r_cm = reduced(0, true) / w_lin,
               r_4 = reduced(4, true) / w_lin, r_all = reduced(all, true) / w_lin;
  std::printf("tension-stiffened cantilever, w/w_lin at kL = 1.5: analytic %.5f, full mesh %.5f, reduced linear %.5f, "
              "geometric: constraint modes %.5f, +4 modes %.5f, all %d modes %.5f\n",
              analytic, r_full, r_lin, r_cm, r_4, all, r_all);
  EXPECT_NEAR(r_full, analytic, 0.01 * analytic);                    // the mesh of 8 elements (discretization, shear)
  EXPECT_NEAR(r_lin, 1.0, 1e-3);                                      // no stiffening without T (only the axial load's tiny rotation)
  EXPECT_NEAR(r_cm, 1.0 / (1.0 + 0.4 * kL * kL), 0.01);               // Rayleigh quotient of the cubic shape
  EXPECT_NEAR(r_4, r_full, 0.01 * r_full);
  EXPECT_NEAR(r_all, r_full, 1e-4 * r_full);                          // the cubic truncation of the mesh's own energy
}


// Modal derivatives against membrane locking (add_modal_derivatives; docs/theory/reduced_bodies.md,
// "Modal derivatives"). A slender cantilever (EA L²/EI = 7.7·10⁴), clamped at the frame node, tip
// free and loaded by a dead transverse force with w/L ≈ 3 %: statics K̃ξ + ½T[ξ,ξ] + ⅙Q[ξ,ξ,ξ] = f̃.
// The full nonlinear mesh (Newton on all its frames) is the reference. Four fixed-interface modes
// with geometric stiffness lock: bending needs the foreshortening u = −½∫w'², which no bending mode
// has, and EA charges the missing part (the deflection comes out too small). With the derivatives
// of the first two modes (3 vectors) the basis holds the foreshortening and the deflection is the
// mesh's to the basis' own truncation (4 linear modes against the mesh's linear deflection: the
// same bound, printed). Also: a derivative is orthogonal in M to the modes, and asking for more
// columns than the basis has is refused with the count.
TEST(ModalDerivatives, RemoveTheMembraneLockingOfATruncatedBasisUnderGeometricStiffness) {
  const int ne = 8;
  const Vector3d axis = Vector3d(2.0, 1.0, 0.5).normalized();
  const Bar bar = straight_bar(ne, 0.8, Vector3d(0.1, -0.2, 0.3), axis);
  const BlockMatrices block = assemble_block(bar.model, bar.elements);
  const int nrows = static_cast<int>(block.K.rows()), tip = ne;
  const Matrix3d sec = pose_of(bar.model.node(0).q0.data()).R;
  const Vector3d e2 = sec.col(1);
  std::vector<int> free_rows;
  for (int r = 6; r < nrows; ++r) free_rows.push_back(r);
  const double L = bar.length;
  // The load for w/L = 3 % in the linear model.
  VectorXd load = VectorXd::Zero(nrows);
  load.segment<3>(block.row_of(tip)) = e2;
  const VectorXd unit = sub(block.K, free_rows).ldlt().solve(VectorXd(load.tail(nrows - 6)));
  const double F = 0.03 * L / e2.dot(unit.segment<3>(block.row_of(tip) - 6));
  load *= F;
  const VectorXd q = full_static_solution(bar, block, load, free_rows);
  const Pose<double> p0 = pose_of(bar.model.node(0).q0.data());
  const double w_full = e2.dot(pose_of(q.data() + 7 * tip).x - pose_of(bar.model.node(tip).q0.data()).x);
  ASSERT_NEAR(w_full / (0.03 * L), 1.0, 0.01);  // small rotations: the mesh is nearly linear here
  const auto deflection = [&](int derivatives, bool geometric, int* added = nullptr) {
    ReducedBlock rb = reduce_block(bar.model, block, 0, {}, 4);
    const int n = add_modal_derivatives(bar.model, bar.elements, block, derivatives, rb);
    if (added) *added = n;
    if (geometric) nonlinear_stiffness(bar.model, bar.elements, block, rb);
    const ReducedBodyMatrices& d = rb.matrices;
    const size_t a = static_cast<size_t>(tip);
    const VectorXd xi = reduced_static_amplitudes(d, rb.shapes[a], p0.R, load.segment<3>(block.row_of(tip)), 50);
    return e2.dot(p0.R * (rb.shapes[a].topRows<3>() * xi));
  };
  int added = 0;
  const double w_lin4 = deflection(0, false), w_locked = deflection(0, true), w_mds = deflection(2, true, &added);
  const double truncation = std::fabs(w_lin4 / (0.03 * L) - 1.0);
  std::printf("slender cantilever, w/L = 3 %%: w/w_full 4 modes linear %.5f, geometric %.5f, geometric + %d derivatives %.5f "
              "(the 4 modes' linear truncation %.1e)\n",
              w_lin4 / w_full, w_locked / w_full, added, w_mds / w_full, truncation);
  EXPECT_EQ(added, 3);                             // the pairs (1,1), (1,2), (2,2)
  EXPECT_LT(w_locked / w_full, 0.9);               // locked
  EXPECT_NEAR(w_mds / w_full, 1.0, 2.0 * truncation + 1e-3);  // the basis' truncation, the lock gone
  // M-orthogonal to the modes; more columns than the basis has: refused.
  ReducedBlock rb = reduce_block(bar.model, block, 0, {}, 4);
  add_modal_derivatives(bar.model, bar.elements, block, 2, rb);
  const MatrixXd& Mt = rb.superelement.M;
  EXPECT_LT((Mt - MatrixXd::Identity(Mt.rows(), Mt.cols())).cwiseAbs().maxCoeff(), 1e-10);
  std::string refused;
  try {
    add_modal_derivatives(bar.model, bar.elements, block, 8, rb);
  } catch (const std::invalid_argument& e) {
    refused = e.what();
  }
  EXPECT_NE(refused.find("asks for the modal derivatives of 8 basis vectors; the basis has 7"), std::string::npos) << refused;
}

// The superelement cache's byte form (io/superelement_cache.hpp; what rank 0 sends and what the
// file's datasets hold): every field of a reduced block, geometric stiffness T and Q included,
// comes back to the last bit, and bytes that are cut off, run on, or claim more entries than they
// hold are refused with std::invalid_argument (a corrupt cache is recomputed, never read).
TEST(SuperelementCache, ByteFormKeepsEveryFieldToTheLastBitAndRefusesCorruptBytes) {
  ReducedBar rb(3, 4);
  nonlinear_stiffness(rb.bar.model, rb.bar.elements, rb.block, rb.rb);
  ReducedBlock& b = rb.rb;
  const int m = b.matrices.elastic();
  ASSERT_GT(m, 3);
  ASSERT_FALSE(b.matrices.T.empty());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  if (b.matrices.Q.empty()) b.matrices.Q = SymmetricTensor(4, m, [&](int, int, int, int) { return U(rng); });
  const std::string bytes = pack_reduced_block(b);
  const ReducedBlock c = unpack_reduced_block(bytes);
  EXPECT_EQ(c.frame_node, b.frame_node);
  EXPECT_EQ(c.superelement.boundary, b.superelement.boundary);
  EXPECT_TRUE(c.superelement.T == b.superelement.T && c.superelement.K == b.superelement.K && c.superelement.M == b.superelement.M);
  EXPECT_TRUE(c.superelement.frequencies == b.superelement.frequencies);
  EXPECT_TRUE(c.matrices.M0 == b.matrices.M0 && c.matrices.K == b.matrices.K);
  ASSERT_EQ(c.matrices.C.size(), b.matrices.C.size());
  for (size_t i = 0; i < c.matrices.C.size(); ++i) EXPECT_TRUE(c.matrices.C[i] == b.matrices.C[i]);
  ASSERT_EQ(c.matrices.M2.size(), b.matrices.M2.size());
  for (size_t i = 0; i < c.matrices.M2.size(); ++i) EXPECT_TRUE(c.matrices.M2[i] == b.matrices.M2[i]);
  EXPECT_EQ(c.matrices.T.values(), b.matrices.T.values());
  EXPECT_EQ(c.matrices.Q.values(), b.matrices.Q.values());
  EXPECT_EQ(c.matrices.Q(1, 0, 2, 1), b.matrices.Q(0, 1, 1, 2));  // the contraction plan is rebuilt
  ASSERT_EQ(c.shapes.size(), b.shapes.size());
  for (size_t a = 0; a < c.shapes.size(); ++a)
    EXPECT_TRUE(c.shapes[a] == b.shapes[a] && c.positions[a] == b.positions[a] && c.rotations[a] == b.rotations[a]);
  EXPECT_EQ(pack_reduced_block(c), bytes);
  // The same body's residual from both, bit for bit.
  std::vector<int> coords(static_cast<size_t>(m));
  std::iota(coords.begin(), coords.end(), 1);
  const ReducedBody e1("b", 0, coords, b.matrices, Vector3d(0, 0, -9.81)), e2("b", 0, coords, c.matrices, Vector3d(0, 0, -9.81));
  LocalState s = body_state(b, rng, 1e-2);
  LocalResidual r1, r2;
  r1.reset(6 + m, true);
  r2.reset(6 + m, true);
  e1.evaluate(s, r1, true);
  e2.evaluate(s, r2, true);
  EXPECT_TRUE(r1.r == r2.r && r1.K == r2.K);
  // Corrupt bytes.
  EXPECT_THROW(unpack_reduced_block(bytes.substr(0, bytes.size() - 1)), std::invalid_argument);
  EXPECT_THROW(unpack_reduced_block(bytes + "x"), std::invalid_argument);
  EXPECT_THROW(unpack_reduced_block(std::string()), std::invalid_argument);
  std::string huge = bytes;
  const unsigned long long count = 1ull << 60;  // the first field's shape count
  std::memcpy(huge.data(), &count, sizeof count);
  EXPECT_THROW(unpack_reduced_block(huge), std::invalid_argument);
}

}  // namespace
}  // namespace alphaflex
