// Herting's free-interface superelement (modal/superelement.hpp `herting`, docs/theory/
// reduced_bodies.md "Herting's free-interface basis"): exactness with all modes, the kept
// free-interface modes exact and the frequencies closer than Craig–Bampton's at equal size, the
// interface rows, a free block's rigid modes, the sparse path, bad input, and the reduced body
// (element tangent, exactness at rest) on a Herting basis.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cfloat>
#include <cmath>
#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/beam_section.hpp"
#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "alphaflex/elements/reduced_body.hpp"
#include "alphaflex/modal/superelement.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

// A straight steel bar (rectangular 20 × 10 mm section: the two bending planes have distinct
// frequencies) of n elements along a skew axis, so that no coordinate decouples by accident.
struct SkewBar {
  Model model;
  std::vector<int> elements;
  BeamSection section = BeamSection::from_material(210e9, 0.3, 7850.0, SectionShape::rectangle(0.02, 0.01));
  double length = 0.0;
};

SkewBar skew_bar(int n, double L) {
  const Vector3d start(0.1, -0.2, 0.3), axis = Vector3d(2.0, 1.0, 0.5).normalized();
  SkewBar b;
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

VectorXd pencil_eigenvalues(const MatrixXd& K, const MatrixXd& M) {
  return Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd>(K, M, Eigen::EigenvaluesOnly).eigenvalues();
}

// A cantilever of n elements (node 0 clamped: its rows removed), interface = the tip's 6
// coordinates: the tip is free in the full model, so the cantilever's own modes are the
// free-interface modes Herting keeps.
struct SkewCantilever {
  SkewBar bar;
  BlockMatrices block;
  MatrixXd K, M;
  std::vector<int> tip;
  explicit SkewCantilever(int n, double L = 0.8) : bar(skew_bar(n, L)), block(assemble_block(bar.model, bar.elements)) {
    const Eigen::Index m = block.K.rows() - 6;
    K = block.K.bottomRightCorner(m, m);
    M = block.M.bottomRightCorner(m, m);
    for (int k = 0; k < 6; ++k) tip.push_back(block.row_of(n, k) - 6);
  }
};

std::string message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

// Exactness (as Craig–Bampton's test in test_superelement.cpp): with all 36 free-interface modes
// asked, the 30 that add to the span (the straight bar's top 6 modes miss whole families at the
// tip — axial, torsion — so the lowest 30 alone would not span it) make T square and invertible, the
// reduced pencil is congruent to the full one and its eigenvalues are the full cantilever's to
// round-off (the same bound: c ε λ_max/λ_j, c = 10, and a floor of 1e-12).
TEST(Herting, AllModesKeptReproduceTheFullEigenvaluesToRoundOff) {
  const SkewCantilever c(6);
  const Superelement se = herting(c.K, c.M, c.tip, 36);
  ASSERT_EQ(se.T.rows(), 36);
  ASSERT_EQ(se.T.cols(), 36);
  EXPECT_EQ(se.modes(), 30);
  // The modal columns are M-orthonormal (Gram–Schmidt in M).
  EXPECT_LT((se.M.bottomRightCorner(30, 30) - MatrixXd::Identity(30, 30)).norm(), 1e-10);
  EXPECT_GT(std::fabs(se.T.fullPivLu().determinant()), 0.0);
  EXPECT_EQ(se.T.fullPivLu().rank(), 36);
  const VectorXd full = pencil_eigenvalues(c.K, c.M), reduced = pencil_eigenvalues(se.K, se.M);
  const double lmax = full[full.size() - 1];
  double worst = 0.0;
  for (int j = 0; j < full.size(); ++j) {
    EXPECT_NEAR(reduced[j] / full[j], 1.0, 1e-12 + 10.0 * DBL_EPSILON * lmax / full[j]) << "mode " << j;
    worst = std::max(worst, std::fabs(reduced[j] / full[j] - 1.0));
  }
  std::printf("Herting, 36 modes asked, 30 kept: largest relative eigenvalue difference %.2e (lambda_max/lambda_0 = %.2e)\n", worst,
              lmax / full[0]);
}

// The interface coordinates stay generalized coordinates: T's interface rows are [I, 0] exactly
// (what ReducedInterfaceTie needs), and the constraint modes carry the exact static response to
// interface loads whatever the number of modes.
TEST(Herting, InterfaceRowsAreTheInterfaceCoordinatesAndStaticsAreExact) {
  const SkewCantilever c(6);
  for (int k : {0, 3, 8}) {
    const Superelement se = herting(c.K, c.M, c.tip, k);
    ASSERT_EQ(se.T.cols(), 6 + k);
    for (int b = 0; b < 6; ++b) {
      VectorXd unit = VectorXd::Zero(6 + k);
      unit[b] = 1.0;
      EXPECT_EQ(se.T.row(c.tip[static_cast<size_t>(b)]).transpose(), unit) << "k = " << k << ", interface row " << b;
    }
    VectorXd f = VectorXd::Zero(c.K.rows());
    const double load[6] = {3.0, -20.0, 7.0, 0.4, -1.1, 2.0};
    for (int b = 0; b < 6; ++b) f[c.tip[static_cast<size_t>(b)]] = load[b];
    const VectorXd u = c.K.ldlt().solve(f);
    const VectorXd xi = se.K.ldlt().solve(se.T.transpose() * f);
    EXPECT_LT((se.T * xi - u).norm(), 1e-10 * u.norm()) << "k = " << k;
  }
}

// Herting's point (Herting 1985; Sonneville et al. 2021, §4.3 and their comparison): the kept
// free-interface modes are in the basis, so the k lowest frequencies of the block free at its
// interface (here the cantilever with a free tip) are exact, where Craig–Bampton's at the same
// size (6 + k coordinates) are only Rayleigh–Ritz upper bounds. Reference: the full mesh of 20
// elements (120 coordinates), itself checked against Euler–Bernoulli's cantilever,
// f₁ = (1.87510²/2π) √(EI/(ρA L⁴)) in each bending plane (within 0.5 %: shear and rotary
// inertia at L/h = 40, and the mesh).
TEST(Herting, KeptFreeInterfaceFrequenciesAreExactAndCloserThanCraigBamptons) {
  const SkewCantilever c(20);
  const VectorXd full = pencil_eigenvalues(c.K, c.M);
  const BeamSection& s = c.bar.section;
  const double L = c.bar.length, beta = 1.8751040687;
  const double w_weak = beta * beta * std::sqrt(s.EI2() / (s.rhoA() * L * L * L * L));
  const double w_strong = beta * beta * std::sqrt(s.EI3() / (s.rhoA() * L * L * L * L));
  const double lo = std::min(w_weak, w_strong), hi = std::max(w_weak, w_strong);
  std::printf("cantilever, 20 elements: first bending %.4f Hz (Euler-Bernoulli %.4f Hz), other plane %.4f Hz (%.4f Hz)\n",
              std::sqrt(full[0]) / (2 * M_PI), lo / (2 * M_PI), std::sqrt(full[1]) / (2 * M_PI), hi / (2 * M_PI));
  EXPECT_NEAR(std::sqrt(full[0]) / lo, 1.0, 5e-3);
  EXPECT_NEAR(std::sqrt(full[1]) / hi, 1.0, 5e-3);
  for (int k : {2, 4, 8}) {
    const Superelement h = herting(c.K, c.M, c.tip, k), cb = craig_bampton(c.K, c.M, c.tip, k);
    const VectorXd rh = pencil_eigenvalues(h.K, h.M), rc = pencil_eigenvalues(cb.K, cb.M);
    std::printf("k = %d:", k);
    for (int j = 0; j < k; ++j) {
      const double eh = std::sqrt(rh[j] / full[j]) - 1.0, ec = std::sqrt(rc[j] / full[j]) - 1.0;
      std::printf("  f%d Herting %.1e CB %.1e", j + 1, eh, ec);
      EXPECT_LT(std::fabs(eh), 1e-9) << "k = " << k << ", mode " << j;  // exact to round-off
      EXPECT_GE(ec, -1e-10) << "k = " << k << ", mode " << j;           // Rayleigh–Ritz bound
      EXPECT_LT(std::fabs(eh), ec) << "k = " << k << ", mode " << j;
    }
    std::printf("\n");
    // The kept frequencies are the ones reported.
    for (int j = 0; j < k; ++j) EXPECT_NEAR(h.frequencies[j] / (std::sqrt(full[j]) / (2 * M_PI)), 1.0, 1e-9);
  }
  // Craig–Bampton at its best on the lowest mode is still visibly above: at k = 2 its lowest
  // frequency errs by more than 1e-7 (measured and printed above).
  const Superelement cb2 = craig_bampton(c.K, c.M, c.tip, 2);
  EXPECT_GT(std::sqrt(pencil_eigenvalues(cb2.K, cb2.M)[0] / full[0]) - 1.0, 1e-7);
}

// A free block (no support: 6 rigid-body modes) with an interface that holds it — the bar's two
// ends: the rigid modes are in the span of the constraint modes and not counted; the k lowest
// elastic free-free frequencies are exact, the reduced pencil has exactly 6 zero eigenvalues, and
// with all 36 elastic modes the full model is reproduced; 37 are more than the block has.
TEST(Herting, FreeBlockRigidModesAreHeldByTheConstraintModes) {
  const SkewBar bar = skew_bar(6, 0.8);
  const BlockMatrices b = assemble_block(bar.model, bar.elements);
  std::vector<int> ends;
  for (int k = 0; k < 6; ++k) ends.push_back(b.row_of(0, k));
  for (int k = 0; k < 6; ++k) ends.push_back(b.row_of(6, k));
  const VectorXd full = pencil_eigenvalues(b.K, b.M);
  ASSERT_LT(std::fabs(full[5]), 1e-12 * full[41]);  // rigid: the code's threshold
  for (int k : {3, 36}) {
    const Superelement se = herting(b.K, b.M, ends, k);
    ASSERT_EQ(se.T.cols(), 12 + std::min(k, 30));  // all 36 elastic modes: 30 add to the span
    const VectorXd red = pencil_eigenvalues(se.K, se.M);
    for (int j = 0; j < 6; ++j) EXPECT_LT(std::fabs(red[j]), 1e-9 * full[6]) << "k = " << k << ", rigid mode " << j;
    EXPECT_GT(red[6], 0.5 * full[6]);
    const int exact = k == 3 ? 3 : 36;
    for (int j = 6; j < 6 + exact; ++j) EXPECT_NEAR(red[j] / full[j], 1.0, 1e-9) << "k = " << k << ", mode " << j;
    // The elastic frequencies reported skip the rigid modes.
    EXPECT_NEAR(se.frequencies[0] / (std::sqrt(full[6]) / (2 * M_PI)), 1.0, 1e-9);
  }
  EXPECT_NE(message([&] { herting(b.K, b.M, ends, 37); }).find("asks for 37 free-interface modes; the block has 36 elastic ones (42 coordinates, 6 rigid-body modes)"),
            std::string::npos);
}

TEST(Herting, RefusesBadInterfacesModeCountsAndFreeBlocksWithoutAnInterface) {
  const SkewCantilever c(6);
  EXPECT_NE(message([&] { herting(c.K, c.M, c.tip, 37); }).find("asks for 37 free-interface modes; the block has 36 (36 coordinates, 6 on the interface)"),
            std::string::npos);
  EXPECT_NE(message([&] { herting(c.K, c.M, c.tip, -1); }).find("asks for -1 free-interface modes"), std::string::npos);
  EXPECT_NE(message([&] { herting(c.K, c.M, {0, 0}, 1); }).find("twice"), std::string::npos);
  EXPECT_NE(message([&] { herting(c.K, c.M, {36}, 1); }).find("not in the block"), std::string::npos);
  // The supported cantilever needs no interface: T is then its lowest modes.
  const Superelement modes_only = herting(c.K, c.M, {}, 4);
  EXPECT_EQ(modes_only.T.cols(), 4);
  const VectorXd full = pencil_eigenvalues(c.K, c.M), red = pencil_eigenvalues(modes_only.K, modes_only.M);
  for (int j = 0; j < 4; ++j) EXPECT_NEAR(red[j] / full[j], 1.0, 1e-9);
  // The free bar: no interface and no support; held at one node's translations only (it can turn
  // about that node without strain).
  const BlockMatrices& b = c.block;
  EXPECT_NE(message([&] { herting(b.K, b.M, {}, 2); }).find("no interface coordinates and no support"), std::string::npos);
  EXPECT_NE(message([&] { herting(b.K, b.M, {0, 1, 2}, 1); }).find("does not hold the block"), std::string::npos);
}

// The sparse path (LDLᵀ constraint modes, SLEPc shift-and-invert at 0 on the whole supported
// block, Rayleigh–Ritz) against the dense one: a cantilever of 100 elements (600 coordinates),
// tip interface, 8 modes. The dense solver's error is ε λ_max/λ_j (Craig–Bampton's test); the
// free tip's lowest mode is ~6 times lower than the clamped-clamped interior's, so the spread is
// ~36 times Craig–Bampton's: the bound on frequencies, K̃ and M̃ is 10 ε λ_max/λ_1 (printed), on T
// 1e-6 (eigenvectors: the residual over the spectral gap). A free block above the dense size is
// refused (shift-and-invert at 0 would factor a singular K).
TEST(Herting, SparsePathEqualsDensePathAndRefusesALargeFreeBlock) {
  const SkewCantilever c(100, 1.0);
  const Eigen::SparseMatrix<double> K = c.K.sparseView(), M = c.M.sparseView();
  const Superelement dense = herting(K, M, c.tip, 8, ModeSolver::dense), sparse = herting(K, M, c.tip, 8, ModeSolver::sparse);
  const double ef = (sparse.frequencies - dense.frequencies).cwiseQuotient(dense.frequencies).cwiseAbs().maxCoeff();
  const double eK = (sparse.K - dense.K).norm() / dense.K.norm(), eM = (sparse.M - dense.M).norm() / dense.M.norm();
  const double eT = (sparse.T - dense.T).norm() / dense.T.norm();
  const VectorXd lam = pencil_eigenvalues(c.K, c.M);
  const double bound = 10.0 * DBL_EPSILON * lam[lam.size() - 1] / lam[0];
  std::printf("Herting, 600 coordinates, 8 modes: sparse vs dense: frequencies %.1e, K %.1e, M %.1e, T %.1e "
              "(bound 10 eps lambda_max/lambda_1 = %.1e)\n", ef, eK, eM, eT, bound);
  EXPECT_LT(ef, bound);
  EXPECT_LT(eK, bound);
  EXPECT_LT(eM, bound);
  EXPECT_LT(eT, 1e-6);
  EXPECT_EQ(herting(K, M, c.tip, 8).T, sparse.T);  // automatic: sparse here
  const Eigen::SparseMatrix<double> Kf = c.block.K.sparseView(), Mf = c.block.M.sparseView();
  std::vector<int> ends;
  for (int k = 0; k < 6; ++k) ends.push_back(c.block.row_of(0, k));
  for (int k = 0; k < 6; ++k) ends.push_back(c.block.row_of(100, k));
  EXPECT_NE(message([&] { herting(Kf, Mf, ends, 8, ModeSolver::sparse); }).find("is free (it has rigid-body modes) and too large"),
            std::string::npos);
}

// ---------------------------------------------------------------- the reduced body on a Herting basis

// A free bar reduced on the frame of node 0 with node 4 on the interface (6 constraint-mode
// coordinates) and `modes` free-interface modes (node 0 clamped, node 4 free).
struct ReducedSkewBar {
  SkewBar bar = skew_bar(4, 0.6);
  BlockMatrices block = assemble_block(bar.model, bar.elements);
  ReducedBlock rb;
  ReducedSkewBar(int modes, bool inertia = false) : rb(reduce_block(bar.model, block, 0, {4}, modes, inertia, Reduction::herting)) {}
};

// The element needs no change for a Herting basis (full K̃ and M̃ in the amplitudes: it assumes no
// diagonal K̃ and no M-orthonormal modes), which its tangents against central differences show at
// random rotating, deformed states with gravity (as ReducedBody.TangentsMatchFiniteDifferences).
TEST(Herting, ReducedBodyTangentsMatchFiniteDifferences) {
  const ReducedSkewBar rb(3);
  const int m = rb.rb.matrices.elastic(), n = 6 + m;
  ASSERT_EQ(m, 9);
  // Not Craig–Bampton's form: K̃ is block diagonal (the constraint modes are K-orthogonal to any
  // shape that vanishes on the interface) but its modal block is full, not diag(ω²).
  const MatrixXd Kmm = rb.rb.superelement.K.bottomRightCorner(3, 3);
  EXPECT_GT((Kmm - MatrixXd(Kmm.diagonal().asDiagonal())).norm(), 1e-3 * Kmm.norm());
  EXPECT_LT(rb.rb.superelement.K.topRightCorner(6, 3).norm(), 1e-9 * rb.rb.superelement.K.norm());
  std::vector<int> coords;
  for (int i = 0; i < m; ++i) coords.push_back(1 + i);
  const ReducedBody body("link", 0, coords, rb.rb.matrices, Vector3d(0.0, 0.0, -9.81));
  std::mt19937 rng(1985);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const auto random = [&](int k, double s) {
    VectorXd x(k);
    for (int i = 0; i < k; ++i) x[i] = s * U(rng);
    return x;
  };
  for (int trial = 0; trial < 3; ++trial) {
    LocalState s;
    s.q.resize(7 + m);
    store_pose(random(3, 1.0), exp_so3<double>(Vector3d(random(3, 1.5))), s.q.data());
    s.q.tail(m) = random(m, 1e-3);
    s.v = random(n, 2.0);
    s.v.tail(m) *= 1e-3;
    s.qdd = random(n, 3.0);
    s.t = 0.0;
    LocalResidual t;
    t.reset(n, true);
    body.evaluate(s, t, true);
    const auto f = [&](const VectorXd& d) {
      LocalState p = s;
      retract(NodeKind::Frame3D, s.q.data(), d.data(), p.q.data());
      p.q.tail(m) = s.q.tail(m) + d.tail(m);
      LocalResidual o;
      o.reset(n, false);
      body.evaluate(p, o, false);
      return o.r;
    };
    // Central differences, h = 1e-6 in q (truncation ~1e-12 relative); r is quadratic in v and
    // linear in q̈, so a step of 1e-2 there leaves only round-off.
    const MatrixXd Kfd = testing::central_differences(f, VectorXd::Zero(n), testing::fixed_fd_step(1e-6));
    const MatrixXd Cfd = testing::central_differences(testing::element_residual_of(body, s, testing::Wrt::v), s.v,
                                                      testing::fixed_fd_step(1e-2));
    const MatrixXd Mfd = testing::central_differences(testing::element_residual_of(body, s, testing::Wrt::qdd), s.qdd,
                                                      testing::fixed_fd_step(1e-2));
    EXPECT_LT((t.K - Kfd).norm(), 1e-7 * (t.K.norm() + t.r.norm())) << "K, trial " << trial;
    EXPECT_LT((t.C - Cfd).norm(), 1e-7 * t.C.norm()) << "C, trial " << trial;
    EXPECT_LT((t.M - Mfd).norm(), 1e-9 * t.M.norm()) << "M, trial " << trial;
  }
}

// Exactness of the reduced body (the analogue of ReducedBody.AllModesKeptReproduceTheFullLinearModelAtRest):
// with the interface node 4 and all 24 free-interface modes asked (18 add to the span), its linearization at rest
// is Gᵀ K G, Gᵀ M G of the full free-free bar, G = [rigid motions of the frame | Φ] square and
// invertible, so the eigenfrequencies are the full linear model's to round-off. The interface
// node's rows of the basis are its own 6 coordinates (the tie's requirement).
TEST(Herting, ReducedBodyWithAllModesReproducesTheFullLinearModelAtRest) {
  const ReducedSkewBar rb(24);
  const int m = rb.rb.matrices.elastic(), n = 6 + m;
  ASSERT_EQ(n, rb.block.K.rows());
  const Matrix3d RA = pose_of(rb.bar.model.node(0).q0.data()).R;
  // Node 4 (block slot 4): [R_Aᵀ, 0; 0, I] on columns 0..5, zero on the modes.
  MatrixXd own = MatrixXd::Zero(6, m);
  own.topLeftCorner<3, 3>() = RA.transpose();
  own.block<3, 3>(3, 3).setIdentity();
  EXPECT_LT((rb.rb.shapes[4] - own).norm(), 1e-14);
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
  const VectorXd full = pencil_eigenvalues(rb.block.K, rb.block.M), red = pencil_eigenvalues(t.K, t.M);
  for (int j = 6; j < n; ++j) EXPECT_NEAR(red[j] / full[j], 1.0, 1e-9) << "mode " << j;
  for (int j = 0; j < 6; ++j) EXPECT_LT(std::fabs(red[j]), 1e-9 * full[6]) << "rigid mode " << j;
}

// Inertia static modes appended to a Herting basis are M-orthogonal to its (M-orthonormal) modal
// columns and unit in M.
TEST(Herting, InertiaModesAreMOrthogonalToTheFreeInterfaceColumns) {
  const ReducedSkewBar plain(4), with(4, true);
  const Superelement& se = with.rb.superelement;
  const int added = static_cast<int>(se.T.cols()) - 10;
  ASSERT_GT(added, 0);
  EXPECT_EQ(se.T.leftCols(10), plain.rb.superelement.T);
  const MatrixXd& Mm = se.M;
  EXPECT_LT(Mm.block(6, 10, 4, added).norm(), 1e-10 * Mm.norm());
  EXPECT_LT((Mm.bottomRightCorner(added, added) - MatrixXd::Identity(added, added)).norm(), 1e-10);
}

}  // namespace
}  // namespace alphaflex
