// Component mode synthesis of a flexible block (docs/theory/reduced_bodies.md, "Superelement").
#include "alphaflex/modal/superelement.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <slepceps.h>
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/petsc_error.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/mesh_reconstruction.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

int BlockMatrices::row_of(int node, int k) const {
  const auto it = std::lower_bound(nodes.begin(), nodes.end(), node);
  if (it == nodes.end() || *it != node) return -1;
  return offsets[static_cast<size_t>(it - nodes.begin())] + k;
}

BlockMatrices assemble_block(const Model& model, const std::vector<int>& element_ids, bool dense) {
  if (element_ids.empty()) throw std::invalid_argument("assemble_block: the block has no elements");
  BlockMatrices b;
  for (int e : element_ids)
    for (int n : model.elements().at(static_cast<size_t>(e))->nodes()) b.nodes.push_back(n);
  std::sort(b.nodes.begin(), b.nodes.end());
  b.nodes.erase(std::unique(b.nodes.begin(), b.nodes.end()), b.nodes.end());
  int n = 0;
  for (int id : b.nodes) {
    b.offsets.push_back(n);
    n += model.node(id).ndof;
  }
  // The undeformed state at rest: K is the linear (material) stiffness, M the consistent mass;
  // velocity-dependent terms vanish (Ω = 0), so the linearization is the block's linear model.
  MechanicalState s = model.initial_state();
  s.v.setZero();
  s.qdd.setZero();
  LocalResidual out;
  std::vector<Eigen::Triplet<double>> tk, tm;
  for (int e : element_ids) {
    const Element& el = *model.elements()[static_cast<size_t>(e)];
    const LocalState ls = model.local_state(el, s);
    out.reset(static_cast<int>(ls.v.size()), true);
    el.evaluate(ls, out, true);
    std::vector<int> rows;
    for (int node : el.nodes())
      for (int k = 0; k < model.node(node).ndof; ++k) rows.push_back(b.row_of(node, k));
    for (size_t i = 0; i < rows.size(); ++i)
      for (size_t j = 0; j < rows.size(); ++j) {
        tk.emplace_back(rows[i], rows[j], out.K(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
        tm.emplace_back(rows[i], rows[j], out.M(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)));
      }
  }
  // setFromTriplets sums the duplicates of an entry in the triplets' order, as the dense sums
  // below do (from 0, and 0 + a = a exactly): both hold the same numbers. Exact zeros (a coupling
  // the element's kernel leaves empty) are dropped, as from a dense matrix's sparse view.
  const auto assemble = [&](const std::vector<Eigen::Triplet<double>>& t, Eigen::SparseMatrix<double>& A, Eigen::MatrixXd& D) {
    A.resize(n, n);
    A.setFromTriplets(t.begin(), t.end());
    A.prune(0.0, 0.0);
    if (!dense) return;
    D = Eigen::MatrixXd::Zero(n, n);
    for (const Eigen::Triplet<double>& x : t) D(x.row(), x.col()) += x.value();
  };
  assemble(tk, b.K_sparse, b.K);
  assemble(tm, b.M_sparse, b.M);
  return b;
}

/// Shift-and-invert with MUMPS (KSPPREONLY + PCLU), as the mechanism's modes use it; defined in
/// modal_analysis.cpp.
void set_mumps_shift_invert(ST st);

namespace {
using SparseMatrix = Eigen::SparseMatrix<double>;

const char* const kNotHeld =
    "the interface does not hold the block: its interior can move without strain "
    "(a mechanism or a free part); add interface points or a support";

// The interior must be held by the interface: K_ii positive definite. The pivots of its Cholesky
// factor measure it (a free rigid motion of the interior gives a pivot at round-off).
Eigen::LLT<Eigen::MatrixXd> check_held(const Eigen::MatrixXd& Kii) {
  const Eigen::LLT<Eigen::MatrixXd> llt(Kii);
  const Eigen::VectorXd d = Eigen::MatrixXd(llt.matrixL()).diagonal();
  if (llt.info() != Eigen::Success || !(d.minCoeff() > 1e-7 * d.maxCoeff())) throw std::invalid_argument(kNotHeld);
  return llt;
}

// The same test on the sparse LDLᵀ factor (fill-reducing ordering): D holds the squares of the
// Cholesky pivots, so the bound is squared.
void check_held(const Eigen::SimplicialLDLT<SparseMatrix>& ldlt) {
  const Eigen::VectorXd& D = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(D.minCoeff() > 1e-14 * D.maxCoeff())) throw std::invalid_argument(kNotHeld);
}

SparseMatrix submatrix(const SparseMatrix& A, const std::vector<int>& rows, const std::vector<int>& cols) {
  std::vector<int> r(static_cast<size_t>(A.rows()), -1), c(static_cast<size_t>(A.cols()), -1);
  for (size_t i = 0; i < rows.size(); ++i) r[static_cast<size_t>(rows[i])] = static_cast<int>(i);
  for (size_t j = 0; j < cols.size(); ++j) c[static_cast<size_t>(cols[j])] = static_cast<int>(j);
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < A.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(A, k); it; ++it)
      if (r[static_cast<size_t>(it.row())] >= 0 && c[static_cast<size_t>(it.col())] >= 0)
        t.emplace_back(r[static_cast<size_t>(it.row())], c[static_cast<size_t>(it.col())], it.value());
  SparseMatrix B(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(cols.size()));
  B.setFromTriplets(t.begin(), t.end());
  return B;
}

// Each mode's sign fixed by its product with a fixed quasi-random (Weyl sequence) vector: positive.
// (Its largest entry would not do: the antisymmetric modes of a symmetric block have two largest
// entries of opposite signs.) The two paths then give the same vectors.
void fix_signs(Eigen::MatrixXd& V) {
  Eigen::VectorXd w(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) w[i] = std::fmod(0.6180339887498949 * static_cast<double>(i + 1), 1.0) - 0.5;
  for (Eigen::Index j = 0; j < V.cols(); ++j)
    if (w.dot(V.col(j)) < 0.0) V.col(j) = -V.col(j);
}

struct LowestModes {
  Eigen::VectorXd eigenvalues;  ///< ω², ascending
  Eigen::MatrixXd vectors;      ///< M-orthonormal
};

// The rows of a block of n coordinates that are not in `boundary`, after checking `boundary`
// (distinct, in range) and the number of normal modes asked (Craig–Bampton's at most n − n_b,
// Herting's at most n; `kind` names them).
std::vector<int> interior_of(int n, const std::vector<int>& boundary, int modes, const char* who, const char* kind) {
  const bool herting_modes = std::string(kind) == "free-interface";
  std::vector<char> is_boundary(static_cast<size_t>(n), 0);
  for (int r : boundary) {
    if (r < 0 || r >= n) throw std::invalid_argument(std::string(who) + ": interface coordinate " + std::to_string(r) + " is not in the block");
    if (is_boundary[static_cast<size_t>(r)])
      throw std::invalid_argument(std::string(who) + ": interface coordinate " + std::to_string(r) + " is given twice");
    is_boundary[static_cast<size_t>(r)] = 1;
  }
  const int nb = static_cast<int>(boundary.size()), ni = herting_modes ? n : available_modes(n, nb);
  if (modes < 0 || modes > ni) {
    std::ostringstream os;
    os << "asks for " << modes << " " << kind << " modes; the block has " << ni << " (" << n << " coordinates, " << nb
       << " on the interface)";
    throw std::invalid_argument(os.str());
  }
  std::vector<int> interior;
  for (int r = 0; r < n; ++r)
    if (!is_boundary[static_cast<size_t>(r)]) interior.push_back(r);
  return interior;
}

LowestModes dense_modes(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, int k, const char* not_definite) {
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (es.info() != Eigen::Success) throw std::invalid_argument(not_definite);
  return {es.eigenvalues().head(k), es.eigenvectors().leftCols(k)};
}

// A SeqAIJ copy of A on this process (the block is reduced by every rank, identically).
Mat petsc_matrix(const SparseMatrix& A) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor, PetscInt> R(A);
  const PetscInt n = static_cast<PetscInt>(R.rows());
  std::vector<PetscInt> nnz(static_cast<size_t>(n));
  for (PetscInt i = 0; i < n; ++i) nnz[static_cast<size_t>(i)] = R.outerIndexPtr()[i + 1] - R.outerIndexPtr()[i];
  Mat P = nullptr;
  check_petsc(MatCreateSeqAIJ(PETSC_COMM_SELF, n, n, 0, nnz.data(), &P), "MatCreateSeqAIJ");
  try {
    for (PetscInt i = 0; i < n; ++i)
      check_petsc(MatSetValues(P, 1, &i, nnz[static_cast<size_t>(i)], R.innerIndexPtr() + R.outerIndexPtr()[i],
                               R.valuePtr() + R.outerIndexPtr()[i], INSERT_VALUES),
                  "MatSetValues");
    check_petsc(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    check_petsc(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  } catch (...) {
    MatDestroy(&P);  // created here, so destroyed here when the copy fails
    throw;
  }
  return P;
}

// The k lowest modes of (K, M), K and M symmetric positive definite: SLEPc's Krylov–Schur on the
// shift-and-invert spectral transformation (K − σM)⁻¹M at σ = 0 (MUMPS factors K once), then the
// Rayleigh–Ritz projection of (K, M) on the converged vectors, whose dense solution makes them
// M-orthonormal to round-off and refines the eigenvalues.
LowestModes sparse_modes(const SparseMatrix& K, const SparseMatrix& M, int k) {
  PetscBool slepc = PETSC_FALSE;
  check_petsc(SlepcInitialized(&slepc), "SlepcInitialized");
  if (!slepc) check_petsc(SlepcInitializeNoArguments(), "SlepcInitializeNoArguments");  // unit-test drivers start PETSc only
  const Eigen::Index n = K.rows();
  Mat Kp = nullptr, Mp = nullptr;
  EPS eps = nullptr;
  Vec x = nullptr;
  Eigen::MatrixXd V(n, k);
  const auto destroy = [&] {
    VecDestroy(&x);
    EPSDestroy(&eps);
    MatDestroy(&Kp);
    MatDestroy(&Mp);
  };
  try {
    Kp = petsc_matrix(K);
    Mp = petsc_matrix(M);
    check_petsc(EPSCreate(PETSC_COMM_SELF, &eps), "EPSCreate");
    check_petsc(EPSSetOperators(eps, Kp, Mp), "EPSSetOperators");
    check_petsc(EPSSetProblemType(eps, EPS_GHEP), "EPSSetProblemType");
    check_petsc(EPSSetDimensions(eps, k, PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
    check_petsc(EPSSetTarget(eps, 0.0), "EPSSetTarget");
    check_petsc(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
    check_petsc(EPSSetTolerances(eps, 1e-12, 500), "EPSSetTolerances");
    ST st;
    check_petsc(EPSGetST(eps, &st), "EPSGetST");
    set_mumps_shift_invert(st);
    check_petsc(EPSSolve(eps), "EPSSolve (fixed-interface modes)");
    PetscInt nconv = 0;
    check_petsc(EPSGetConverged(eps, &nconv), "EPSGetConverged");
    if (nconv < k)
      throw SolverError("craig_bampton: the eigensolver converged " + std::to_string(nconv) + " of the " + std::to_string(k) +
                        " fixed-interface modes asked");
    check_petsc(MatCreateVecs(Kp, &x, nullptr), "MatCreateVecs");
    for (int j = 0; j < k; ++j) {
      PetscScalar lambda;
      check_petsc(EPSGetEigenpair(eps, j, &lambda, nullptr, x, nullptr), "EPSGetEigenpair");
      const PetscScalar* a = nullptr;
      check_petsc(VecGetArrayRead(x, &a), "VecGetArrayRead");
      V.col(j) = Eigen::Map<const Eigen::VectorXd>(a, n);
      check_petsc(VecRestoreArrayRead(x, &a), "VecRestoreArrayRead");
    }
  } catch (...) {
    destroy();
    throw;
  }
  destroy();
  const Eigen::MatrixXd KV = K * V, MV = M * V;
  Eigen::MatrixXd Kr = V.transpose() * KV, Mr = V.transpose() * MV;
  Kr = 0.5 * (Kr + Kr.transpose()).eval();
  Mr = 0.5 * (Mr + Mr.transpose()).eval();
  LowestModes r = dense_modes(Kr, Mr, k, "the block's mass matrix is not positive definite on its interior");
  r.vectors = (V * r.vectors).eval();
  return r;
}
}  // namespace

Superelement craig_bampton(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const std::vector<int>& boundary, int modes) {
  if (K.rows() != K.cols() || M.rows() != K.rows() || M.cols() != K.rows())
    throw std::invalid_argument("craig_bampton: K and M must be square and of one size");
  return craig_bampton(SparseMatrix(K.sparseView(0.0, 0.0)), SparseMatrix(M.sparseView(0.0, 0.0)), boundary, modes);
}

Superelement craig_bampton(const SparseMatrix& K, const SparseMatrix& M, const std::vector<int>& boundary, int modes,
                           ModeSolver solver) {
  const int n = static_cast<int>(K.rows());
  if (K.cols() != n || M.rows() != n || M.cols() != n) throw std::invalid_argument("craig_bampton: K and M must be square and of one size");
  if (boundary.empty())
    throw std::invalid_argument("the block has no interface coordinates: a reduced block needs interface points "
                                "(where joints or supports attach) to define its constraint modes");
  const std::vector<int> interior = interior_of(n, boundary, modes, "craig_bampton", "fixed-interface");
  const int nb = static_cast<int>(boundary.size()), ni = available_modes(n, nb);
  Superelement se;
  se.boundary = boundary;
  se.T = Eigen::MatrixXd::Zero(n, nb + modes);
  for (int c = 0; c < nb; ++c) se.T(boundary[static_cast<size_t>(c)], c) = 1.0;
  if (ni > 0) {
    const SparseMatrix Kii = submatrix(K, interior, interior), Mii = submatrix(M, interior, interior);
    const Eigen::MatrixXd Kib = Eigen::MatrixXd(submatrix(K, interior, boundary));
    const bool dense = solver == ModeSolver::dense ||
                       (solver == ModeSolver::automatic && (ni <= 300 || 4 * modes > ni));
    const char* not_definite = "the block's mass matrix is not positive definite on its interior";
    // Static constraint modes Ψ = −K_ii⁻¹ K_ib (Craig & Bampton 1968, eq. 9); fixed-interface
    // normal modes K_ii φ = ω² M_ii φ, M-orthonormal, ascending.
    Eigen::MatrixXd Psi;
    LowestModes lm;
    if (dense) {
      const Eigen::MatrixXd Kd(Kii), Md(Mii);
      const Eigen::LLT<Eigen::MatrixXd> llt = check_held(Kd);
      Psi = nb > 0 ? Eigen::MatrixXd(-llt.solve(Kib)) : Eigen::MatrixXd::Zero(ni, 0);
      if (modes > 0) lm = dense_modes(Kd, Md, modes, not_definite);
    } else {
      const Eigen::SimplicialLDLT<SparseMatrix> ldlt(Kii);
      check_held(ldlt);
      Psi = nb > 0 ? Eigen::MatrixXd(-ldlt.solve(Kib)) : Eigen::MatrixXd::Zero(ni, 0);
      if (modes > 0) lm = sparse_modes(Kii, Mii, modes);
    }
    for (size_t i = 0; i < interior.size(); ++i) se.T.row(interior[i]).head(nb) = Psi.row(static_cast<Eigen::Index>(i));
    if (modes > 0) {
      fix_signs(lm.vectors);
      se.frequencies.resize(modes);
      for (int j = 0; j < modes; ++j) {
        se.frequencies[j] = std::sqrt(std::max(lm.eigenvalues[j], 0.0)) / (2.0 * M_PI);
        for (size_t i = 0; i < interior.size(); ++i) se.T(interior[i], nb + j) = lm.vectors(static_cast<Eigen::Index>(i), j);
      }
    }
  }
  const Eigen::MatrixXd KT = K * se.T, MT = M * se.T;
  se.K = se.T.transpose() * KT;
  se.M = se.T.transpose() * MT;
  // Symmetric to round-off by construction; make it exact so downstream factorizations see it.
  se.K = 0.5 * (se.K + se.K.transpose()).eval();
  se.M = 0.5 * (se.M + se.M.transpose()).eval();
  return se;
}

Superelement herting(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const std::vector<int>& boundary, int modes) {
  if (K.rows() != K.cols() || M.rows() != K.rows() || M.cols() != K.rows())
    throw std::invalid_argument("herting: K and M must be square and of one size");
  return herting(SparseMatrix(K.sparseView(0.0, 0.0)), SparseMatrix(M.sparseView(0.0, 0.0)), boundary, modes);
}

// Herting's basis in Sonneville et al.'s (2021) form (header; docs/theory/reduced_bodies.md):
// a free-interface mode v solves K_ii v_i + K_ib v_b = ω² (M v)_i, so v_i = Ψ v_b + ω² K_ii⁻¹ (M v)_i
// and the column v − [0; Ψ v_b] = [0; ω² K_ii⁻¹ (M v)_i] is Sonneville's Ψ_D column scaled by −ω²:
// the mode is exactly T [v_b; e_j]. The span is Herting's {constraint modes, free-interface modes}
// (the residual-flexibility attachment modes of the supported block lie in the span of the
// constraint modes, whose interface rows are the identity), and u_b stays a coordinate.
Superelement herting(const SparseMatrix& K, const SparseMatrix& M, const std::vector<int>& boundary, int modes, ModeSolver solver) {
  const int n = static_cast<int>(K.rows());
  if (K.cols() != n || M.rows() != n || M.cols() != n) throw std::invalid_argument("herting: K and M must be square and of one size");
  const std::vector<int> interior = interior_of(n, boundary, modes, "herting", "free-interface");
  const int nb = static_cast<int>(boundary.size()), ni = static_cast<int>(interior.size());
  const bool dense = solver == ModeSolver::dense || (solver == ModeSolver::automatic && (n <= 300 || 4 * modes > n));
  const char* not_definite = "the block's mass matrix is not positive definite";
  Superelement se;
  se.boundary = boundary;
  se.T = Eigen::MatrixXd::Zero(n, nb + modes);
  for (int c = 0; c < nb; ++c) se.T(boundary[static_cast<size_t>(c)], c) = 1.0;
  // The interior must be held (by the interface, or by a support when there is no interface).
  const auto held = [&](auto&& check) {
    try {
      check();
    } catch (const std::invalid_argument&) {
      if (nb > 0) throw;
      throw std::invalid_argument("the block has no interface coordinates and no support: it moves without strain; "
                                  "a reduced block needs interface points (where joints or supports attach) or a support");
    }
  };
  Eigen::MatrixXd Psi = Eigen::MatrixXd::Zero(ni, nb);
  LowestModes lm;
  lm.vectors = Eigen::MatrixXd::Zero(n, 0);
  if (ni > 0) {
    const SparseMatrix Kii = submatrix(K, interior, interior);
    const Eigen::MatrixXd Kib = Eigen::MatrixXd(submatrix(K, interior, boundary));
    // Static constraint modes Ψ = −K_ii⁻¹ K_ib (as Craig–Bampton).
    if (dense) {
      const Eigen::MatrixXd Kd(Kii);
      // No interface (a supported block): Ψ has no columns, and Eigen's triangular solve must not
      // be handed an empty right-hand side (its data pointer is null; UBSan, CI of session 9).
      held([&] {
        const Eigen::LLT<Eigen::MatrixXd> llt = check_held(Kd);
        if (nb > 0) Psi = -llt.solve(Kib);
      });
    } else {
      const Eigen::SimplicialLDLT<SparseMatrix> ldlt(Kii);
      held([&] { check_held(ldlt); });
      if (nb > 0) Psi = -ldlt.solve(Kib);
    }
  }
  if (modes > 0) {
    // Free-interface modes of the whole block, the rigid-body ones (a free block) skipped: they are
    // in the span of the constraint modes (the interface holds the block) and their column would
    // vanish. Round-off puts them at |ω²| ~ ε ω²_max; the threshold 1e-12 ω²_max leaves elastic
    // modes alone up to a spread ω²_max/ω²_1 of 1e12 (beam blocks here: 1e6–1e9).
    if (dense) {
      const Eigen::MatrixXd Kd(K), Md(M);
      const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kd, Md, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
      if (es.info() != Eigen::Success) throw std::invalid_argument(not_definite);
      const Eigen::VectorXd& lam = es.eigenvalues();
      int rigid = 0;
      while (rigid < n && lam[rigid] < 1e-12 * lam[n - 1]) ++rigid;
      if (rigid + modes > n) {
        std::ostringstream os;
        os << "asks for " << modes << " free-interface modes; the block has " << n - rigid << " elastic ones (" << n
           << " coordinates, " << rigid << " rigid-body modes)";
        throw std::invalid_argument(os.str());
      }
      lm.eigenvalues = lam.segment(rigid, modes);
      lm.vectors = es.eigenvectors().middleCols(rigid, modes);
    } else {
      // Shift-and-invert at 0 factors K: a supported block only.
      const Eigen::SimplicialLDLT<SparseMatrix> ldlt(K);
      const Eigen::VectorXd& D = ldlt.vectorD();
      if (ldlt.info() != Eigen::Success || !(D.minCoeff() > 1e-14 * D.maxCoeff())) {
        std::ostringstream os;
        os << "herting: the block (" << n << " coordinates) is free (it has rigid-body modes) and too large for the dense "
           << "eigensolver (at most 300 coordinates, or more than a quarter of its modes asked); support it (clamp its frame "
           << "point) or use craig_bampton";
        throw std::invalid_argument(os.str());
      }
      lm = sparse_modes(K, M, modes);
    }
    fix_signs(lm.vectors);
    // Column j: v_j less its constraint-mode part, w_j = v_j − [0; Ψ v_b,j], zero on the interface.
    Eigen::MatrixXd Vb(nb, modes);
    for (int c = 0; c < nb; ++c) Vb.row(c) = lm.vectors.row(boundary[static_cast<size_t>(c)]);
    const Eigen::MatrixXd PsiVb = Psi * Vb;
    Eigen::MatrixXd W = Eigen::MatrixXd::Zero(n, modes);
    for (size_t i = 0; i < interior.size(); ++i)
      W.row(interior[i]) = lm.vectors.row(interior[i]) - PsiVb.row(static_cast<Eigen::Index>(i));
    // The w_j live in the n − n_b interior coordinates, and a combination of kept modes that is a
    // static interface shape gives a dependent one (Herting's residual flexibility of the dropped
    // modes singular: a straight beam's dropped top modes miss whole families at the interface).
    // Gram–Schmidt in M, in frequency order, twice (re-orthogonalized to round-off): a column whose
    // M-norm falls below 1e-6 of its own is (to a frequency error ~1e-12) a combination of the lower
    // ones and gets no amplitude. The kept columns are M-orthonormal, the span of the first j is
    // that of w_1 … w_j, so every kept mode stays exact; with all n modes, n − n_b remain (complete).
    std::vector<Eigen::VectorXd> kept;
    std::vector<int> kept_mode;
    for (int j = 0; j < modes; ++j) {
      Eigen::VectorXd w = W.col(j);
      const double before = std::sqrt(w.dot(M * w));
      for (int pass = 0; pass < 2; ++pass)
        for (const Eigen::VectorXd& u : kept) w -= u * u.dot(M * w);
      const double after = std::sqrt(w.dot(M * w));
      if (!(after > 1e-6 * before)) continue;
      kept.push_back(w / after);
      kept_mode.push_back(j);
    }
    const int k = static_cast<int>(kept.size());
    se.T.conservativeResize(Eigen::NoChange, nb + k);
    se.frequencies.resize(k);
    for (int c = 0; c < k; ++c) {
      se.T.col(nb + c) = kept[static_cast<size_t>(c)];
      se.frequencies[c] = std::sqrt(std::max(lm.eigenvalues[kept_mode[static_cast<size_t>(c)]], 0.0)) / (2.0 * M_PI);
    }
  }
  for (size_t i = 0; i < interior.size(); ++i) se.T.row(interior[i]).head(nb) = Psi.row(static_cast<Eigen::Index>(i));
  const Eigen::MatrixXd KT = K * se.T, MT = M * se.T;
  se.K = se.T.transpose() * KT;
  se.M = se.T.transpose() * MT;
  se.K = 0.5 * (se.K + se.K.transpose()).eval();
  se.M = 0.5 * (se.M + se.M.transpose()).eval();
  return se;
}

RigidMassProperties rigid_mass_properties(const Model& model, const BlockMatrices& block) {
  const int n = block.size();
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, 6);
  for (size_t a = 0; a < block.nodes.size(); ++a) {
    const Node& nd = model.node(block.nodes[a]);
    if (!nd.spatial()) throw std::invalid_argument("rigid_mass_properties: node '" + nd.name + "' is not a spatial frame");
    const Pose<double> p = pose_of(nd.q0.data());
    const int o = block.offsets[a];
    // δx_j = δx₀ + δθ₀ × X_j, δθ_j = R_jᵀ δθ₀ (δθ_j in the node frame).
    G.block<3, 3>(o, 0).setIdentity();
    G.block<3, 3>(o, 3) = -hat(p.x);
    G.block<3, 3>(o + 3, 3) = p.R.transpose();
  }
  const Eigen::MatrixXd R = G.transpose() * (block.M_sparse * G);
  RigidMassProperties mp;
  mp.mass = R.topLeftCorner<3, 3>().trace() / 3.0;
  if (!(mp.mass > 0.0)) throw std::invalid_argument("rigid_mass_properties: the block has no mass");
  // Coupling block −m ĉ (kinetic energy m v₀·(ω × c)).
  const Eigen::Matrix3d C = -R.block<3, 3>(0, 3) / mp.mass;
  mp.centre = Eigen::Vector3d(0.5 * (C(2, 1) - C(1, 2)), 0.5 * (C(0, 2) - C(2, 0)), 0.5 * (C(1, 0) - C(0, 1)));
  const Eigen::Vector3d c = mp.centre;
  const Eigen::Matrix3d Jo = 0.5 * (R.block<3, 3>(3, 3) + R.block<3, 3>(3, 3).transpose());
  // Parallel-axis theorem: J_O = J_c + m (|c|² I − c cᵀ).
  mp.inertia = Jo - mp.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  return mp;
}

}  // namespace alphaflex

namespace alphaflex {

void ReducedBlock::node_pose(size_t a, const Eigen::Vector3d& xf, const Eigen::Matrix3d& Rf, const Eigen::VectorXd& xi,
                             Eigen::Vector3d& x, Eigen::Matrix3d& R) const {
  reduced_point_pose(positions[a], rotations[a], shapes[a], xf, Rf, xi, x, R);
}

namespace {

// Static "inertia modes" (modal truncation augmentation: Dickens, Nakagawa & Wittbrodt, Comput.
// Struct. 62 (1997) 985; load-dependent Ritz vectors: Wilson, Yuan & Dickens, Earthq. Eng. Struct.
// Dyn. 10 (1982) 813): the interior's static response K_ii⁻¹ (M g)_i to the body-frame inertia
// loads of a floating frame — the 3 uniform accelerations and the 9 fields linear in position,
// g(x) = eᵢ (x − x_f)ⱼ, which span the centrifugal ω × (ω × x) and angular α × x loads — with
// the interface held. Made M-orthogonal to the kept fixed-interface modes (or Herting's columns,
// M-orthonormal as well) and to each other
// (Gram–Schmidt in M), M-unit, appended after them; those dependent on the basis (relative norm
// below 1e-6 after the projection) are dropped. They are zero on the interface, so the
// constraint modes stay K-orthogonal to them (Ψ is the static condensation).
// Appends `candidates` (vectors on the block's coordinates without the frame node's) to the basis
// of `se`, M-orthonormalized against its modal columns (those after the constraint modes) and each
// other by Gram–Schmidt, twice (re-orthogonalized to round-off); a candidate whose M-norm is not
// above `floor`, or that keeps less than 10⁻⁶ of it after the projection (dependent), is dropped.
// Then K̃ and M̃ anew. Returns how many were appended (inertia modes, modal derivatives).
int append_m_orthonormal(const SparseMatrix& Kc, const SparseMatrix& Mc, const std::vector<Eigen::VectorXd>& candidates, double floor,
                         Superelement& se) {
  const Eigen::Index nm = se.T.cols() - se.interface_size();
  std::vector<Eigen::VectorXd> added;
  for (Eigen::VectorXd s : candidates) {
    const double before = std::sqrt(s.dot(Mc * s));
    if (!(before > floor)) continue;
    for (int pass = 0; pass < 2; ++pass) {
      if (nm > 0) s -= se.T.rightCols(nm) * (se.T.rightCols(nm).transpose() * (Mc * s));
      for (const Eigen::VectorXd& v : added) s -= v * v.dot(Mc * s);
    }
    const double after = std::sqrt(s.dot(Mc * s));
    if (after < 1e-6 * before) continue;
    added.push_back(s / after);
  }
  const Eigen::Index n0 = se.T.cols();
  se.T.conservativeResize(Eigen::NoChange, n0 + static_cast<Eigen::Index>(added.size()));
  for (size_t k = 0; k < added.size(); ++k) se.T.col(n0 + static_cast<Eigen::Index>(k)) = added[k];
  const Eigen::MatrixXd KT = Kc * se.T, MT = Mc * se.T;
  se.K = se.T.transpose() * KT;
  se.M = se.T.transpose() * MT;
  se.K = 0.5 * (se.K + se.K.transpose()).eval();
  se.M = 0.5 * (se.M + se.M.transpose()).eval();
  return static_cast<int>(added.size());
}

void add_inertia_modes(const Model& model, const BlockMatrices& block, int frame_node, const std::vector<int>& keep,
                       const std::vector<int>& position, const SparseMatrix& Kc, const SparseMatrix& Mc, Superelement& se) {
  const int nk = static_cast<int>(keep.size());
  std::vector<char> is_boundary(static_cast<size_t>(nk), 0);
  for (int r : se.boundary) is_boundary[static_cast<size_t>(r)] = 1;
  std::vector<int> interior;
  for (int r = 0; r < nk; ++r)
    if (!is_boundary[static_cast<size_t>(r)]) interior.push_back(r);
  if (interior.empty()) return;
  const Eigen::Vector3d xf = pose_of(model.node(frame_node).q0.data()).x;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(nk, 12);
  for (size_t a = 0; a < block.nodes.size(); ++a) {
    const Eigen::Vector3d d = pose_of(model.node(block.nodes[a]).q0.data()).x - xf;
    for (int r = 0; r < 3; ++r) {
      const int row = position[static_cast<size_t>(block.offsets[a] + r)];
      if (row < 0) continue;  // the frame node's rows (clamped)
      G(row, r) = 1.0;
      for (int j = 0; j < 3; ++j) G(row, 3 + 3 * r + j) = d[j];
    }
  }
  const Eigen::MatrixXd F = Mc * G;
  Eigen::MatrixXd Fi(static_cast<Eigen::Index>(interior.size()), 12);
  for (size_t i = 0; i < interior.size(); ++i) Fi.row(static_cast<Eigen::Index>(i)) = F.row(interior[i]);
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(submatrix(Kc, interior, interior));
  check_held(ldlt);
  const Eigen::MatrixXd Si = ldlt.solve(Fi);
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(nk, 12);
  for (size_t i = 0; i < interior.size(); ++i) S.row(interior[i]) = Si.row(static_cast<Eigen::Index>(i));
  std::vector<Eigen::VectorXd> candidates;
  for (int c = 0; c < 12; ++c) candidates.push_back(S.col(c));
  append_m_orthonormal(Kc, Mc, candidates, 0.0, se);
}

void complete_block(const Model& model, const BlockMatrices& block, ReducedBlock& rb);

}  // namespace

ReducedBlock reduce_block(const Model& model, const BlockMatrices& block, int frame_node, const std::vector<int>& interface_nodes,
                          int modes, bool inertia_modes, Reduction method) {
  const int n = block.size();
  if (block.row_of(frame_node) < 0)
    throw std::invalid_argument("the interface point '" + model.node(frame_node).name + "' is not a node of the block");
  for (int id : block.nodes)
    if (!model.node(id).spatial()) throw std::invalid_argument("reduce_block: node '" + model.node(id).name + "' is not a spatial frame");
  // Coordinates without the frame node's (clamped: the frame carries the rigid motion).
  const int f0 = block.row_of(frame_node);
  std::vector<int> keep, position(static_cast<size_t>(n), -1);
  for (int r = 0; r < n; ++r)
    if (r < f0 || r >= f0 + 6) {
      position[static_cast<size_t>(r)] = static_cast<int>(keep.size());
      keep.push_back(r);
    }
  std::vector<int> boundary;
  for (int id : interface_nodes) {
    if (block.row_of(id) < 0)
      throw std::invalid_argument("the interface point '" + model.node(id).name + "' is not a node of the block");
    if (id == frame_node) continue;
    for (int k = 0; k < 6; ++k) boundary.push_back(position[static_cast<size_t>(block.row_of(id, k))]);
  }
  // The block's matrices are sparse (a node couples to its elements' nodes only): everything below
  // works on their nonzeros, O(n · bandwidth · m), not O(n³).
  const SparseMatrix& Ks = block.K_sparse;
  const SparseMatrix& Ms = block.M_sparse;
  const SparseMatrix Kc = submatrix(Ks, keep, keep), Mc = submatrix(Ms, keep, keep);
  const int nk = static_cast<int>(keep.size());
  ReducedBlock rb;
  rb.frame_node = frame_node;
  // A block held only by its frame node has no constraint modes; Craig–Bampton with the frame
  // clamped then needs no interface coordinates (the clamp is the interface), and Herting's
  // free-interface modes are the same modes (no interface coordinate is left free).
  const bool herting_basis = method == Reduction::herting;
  if (boundary.empty()) {
    if (modes < 0 || modes > nk) {
      std::ostringstream os;
      os << "asks for " << modes << (herting_basis ? " free-interface" : " fixed-interface") << " modes; the block has " << nk << " ("
         << n << " coordinates, 6 on the interface)";
      throw std::invalid_argument(os.str());
    }
    Superelement& se = rb.superelement;
    LowestModes lm;
    const char* not_definite = "the block's mass matrix is not positive definite";
    // Held by the stiffness alone: a ratio of eigenvalues ω² would also compare the tiny rotary
    // inertias of a thin section and refuse a sound block.
    // No modes (method rigid, or a block held at its frame only): only the check.
    lm.vectors = Eigen::MatrixXd::Zero(nk, 0);
    if (nk <= 300 || 4 * modes > nk) {
      const Eigen::MatrixXd Kd(Kc), Md(Mc);
      if (modes > 0) lm = dense_modes(Kd, Md, modes, not_definite);
      check_held(Kd);
    } else {
      check_held(Eigen::SimplicialLDLT<SparseMatrix>(Kc));
      if (modes > 0) lm = sparse_modes(Kc, Mc, modes);
    }
    fix_signs(lm.vectors);
    se.T = lm.vectors;
    se.frequencies.resize(modes);
    for (int j = 0; j < modes; ++j) se.frequencies[j] = std::sqrt(lm.eigenvalues[j]) / (2.0 * M_PI);
    const Eigen::MatrixXd KT = Kc * se.T, MT = Mc * se.T;
    se.K = se.T.transpose() * KT;
    se.M = se.T.transpose() * MT;
    se.K = 0.5 * (se.K + se.K.transpose()).eval();
    se.M = 0.5 * (se.M + se.M.transpose()).eval();
  } else {
    rb.superelement = herting_basis ? herting(Kc, Mc, boundary, modes) : craig_bampton(Kc, Mc, boundary, modes);
  }
  if (inertia_modes) add_inertia_modes(model, block, frame_node, keep, position, Kc, Mc, rb.superelement);
  complete_block(model, block, rb);
  return rb;
}

namespace {

// The rest of a ReducedBlock from its basis rb.superelement (on the block's coordinates without
// the frame node's) and rb.frame_node: the nodes' data (X, R̄, Φ rows) and the inertia invariants.
// Whatever these held before is replaced.
void complete_block(const Model& model, const BlockMatrices& block, ReducedBlock& rb) {
  const int n = block.size(), frame_node = rb.frame_node;
  const int f0 = block.row_of(frame_node);
  std::vector<int> keep;
  for (int r = 0; r < n; ++r)
    if (r < f0 || r >= f0 + 6) keep.push_back(r);
  const int nk = static_cast<int>(keep.size());
  const SparseMatrix& Ms = block.M_sparse;
  rb.positions.clear();
  rb.rotations.clear();
  rb.shapes.clear();
  rb.matrices = ReducedBodyMatrices();
  const Superelement& se = rb.superelement;
  const int m = static_cast<int>(se.T.cols());
  // Φ on all block rows (zero on the frame node's).
  Eigen::MatrixXd Phi = Eigen::MatrixXd::Zero(n, m);
  for (int i = 0; i < nk; ++i) Phi.row(keep[static_cast<size_t>(i)]) = se.T.row(i);
  const Pose<double> F = pose_of(model.node(frame_node).q0.data());
  // Velocities of the mesh in the floating frame (translations in its axes, rotations in the node
  // frames): 𝒱 = P₀ w + Σᵢ ξᵢ Dᵢ ω, the mass in the same components M̄ = Qᵀ M Q (Q, block
  // diagonal, turns the translations from the frame's axes to the world's).
  Eigen::MatrixXd P0 = Eigen::MatrixXd::Zero(n, 6 + m);
  std::vector<Eigen::Triplet<double>> q;
  std::vector<Eigen::MatrixXd> D(static_cast<size_t>(m), Eigen::MatrixXd::Zero(n, 3));
  for (size_t a = 0; a < block.nodes.size(); ++a) {
    const Pose<double> p = pose_of(model.node(block.nodes[a]).q0.data());
    const int o = block.offsets[a];
    const Eigen::Vector3d X = F.R.transpose() * (p.x - F.x);
    const Eigen::Matrix3d Rloc = F.R.transpose() * p.R;
    Eigen::MatrixXd S(6, m);
    S.topRows<3>() = F.R.transpose() * Phi.middleRows(o, 3);
    S.bottomRows<3>() = Phi.middleRows(o + 3, 3);
    rb.positions.push_back(X);
    rb.rotations.push_back(Rloc);
    rb.shapes.push_back(S);
    for (int r = 0; r < 3; ++r) {
      q.emplace_back(o + 3 + r, o + 3 + r, 1.0);
      for (int c = 0; c < 3; ++c) q.emplace_back(o + r, o + c, F.R(r, c));
    }
    P0.block<3, 3>(o, 0).setIdentity();
    P0.block<3, 3>(o, 3) = -hat<double>(X);
    P0.block<3, 3>(o + 3, 3) = Rloc.transpose();
    P0.block(o, 6, 6, m) = S;
    for (int i = 0; i < m; ++i) D[static_cast<size_t>(i)].block<3, 3>(o, 0) = -hat<double>(Eigen::Vector3d(S.col(i).head<3>()));
  }
  SparseMatrix Q(n, n);
  Q.setFromTriplets(q.begin(), q.end());
  const SparseMatrix Mbar = SparseMatrix(Q.transpose()) * Ms * Q;
  ReducedBodyMatrices& d = rb.matrices;
  const Eigen::MatrixXd MP0 = Mbar * P0;
  d.M0 = P0.transpose() * MP0;
  d.M0 = 0.5 * (d.M0 + d.M0.transpose()).eval();
  std::vector<Eigen::MatrixXd> MD(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) {
    MD[static_cast<size_t>(i)] = Mbar * D[static_cast<size_t>(i)];
    d.C.push_back(MD[static_cast<size_t>(i)].transpose() * P0);
  }
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) d.M2.push_back(D[static_cast<size_t>(i)].transpose() * MD[static_cast<size_t>(j)]);
  d.K = se.K;
}

}  // namespace


namespace {

// The block's internal forces at the poses the reduced body gives its nodes for amplitudes ξ
// (ReducedBlock::node_pose, the frame at its initial pose): `full` on the block's rows (δx world,
// δθ node frame, as BlockMatrices), `projected` f̃(ξ) = Σₐ (R_f Φᵗₐ)ᵀ fₓ,ₐ + (T(φₐ) Φʳₐ)ᵀ f_θ,ₐ
// through the derivative of node_pose (nonlinear_stiffness, add_modal_derivatives).
class BlockForces {
 public:
  BlockForces(const Model& model, const std::vector<int>& element_ids, const BlockMatrices& block, const ReducedBlock& rb)
      : model_(model), ids_(element_ids), block_(block), rb_(rb), F_(pose_of(model.node(rb.frame_node).q0.data())), s0_(model.initial_state()) {
    const size_t nn = block.nodes.size();
    s0_.v.setZero();
    s0_.qdd.setZero();
    conf_.resize(nn);
    for (size_t a = 0; a < nn; ++a) conf_[a] = model.confs_of({block.nodes[a]}).front();
    // The block's size: the scale of the difference steps.
    for (const Eigen::Vector3d& X : rb.positions) size_ = std::max(size_, X.norm());
    if (size_ <= 0.0) size_ = 1.0;
    // Each element's configuration entries in the state and its residual's rows in the block.
    for (int e : element_ids) {
      const Element& el = *model.elements()[static_cast<size_t>(e)];
      confs_.push_back(model.confs_of(el.nodes()));
      rows_.emplace_back();
      for (int node : el.nodes())
        for (int c = 0; c < model.node(node).ndof; ++c) rows_.back().push_back(block.row_of(node, c));
    }
    block_rows_ = static_cast<Eigen::Index>(block.offsets.back() + model.node(block.nodes.back()).ndof);
  }
  double size() const { return size_; }

  Eigen::VectorXd full(const Eigen::VectorXd& xi, std::vector<Eigen::Vector3d>* phi = nullptr) const {
    const size_t nn = block_.nodes.size();
    MechanicalState s = s0_;
    if (phi) phi->resize(nn);
    for (size_t a = 0; a < nn; ++a) {
      Eigen::Vector3d x;
      Eigen::Matrix3d R;
      rb_.node_pose(a, F_.x, F_.R, xi, x, R);
      if (phi) (*phi)[a] = rb_.shapes[a].bottomRows<3>() * xi;
      const Eigen::Quaterniond qa(R);
      s.q.segment<3>(conf_[a]) = x;
      s.q[conf_[a] + 3] = qa.w();
      s.q[conf_[a] + 4] = qa.x();
      s.q[conf_[a] + 5] = qa.y();
      s.q[conf_[a] + 6] = qa.z();
    }
    Eigen::VectorXd f = Eigen::VectorXd::Zero(block_rows_);
    Eigen::VectorXd r;
    for (size_t b = 0; b < ids_.size(); ++b) {
      const Element& el = *model_.elements()[static_cast<size_t>(ids_[b])];
      // The elastic force alone (Element::internal_force: no inertia terms, which vanish at rest
      // but cost most of a beam's evaluation); an element without it, evaluated whole at rest.
      if (!el.internal_force(gather(s.q, confs_[b]), r)) {
        LocalState ls = model_.local_state(el, s);
        ls.load_factor = 0.0;  // no applied load, no gravity
        LocalResidual out;
        out.reset(static_cast<int>(ls.v.size()), false);
        el.evaluate(ls, out, false);
        r = out.r;
      }
      for (size_t k = 0; k < rows_[b].size(); ++k) f[rows_[b][k]] += r[static_cast<Eigen::Index>(k)];
    }
    return f;
  }

  Eigen::VectorXd projected(const Eigen::VectorXd& xi) const {
    std::vector<Eigen::Vector3d> phi;
    const Eigen::VectorXd f = full(xi, &phi);
    Eigen::VectorXd ft = Eigen::VectorXd::Zero(xi.size());
    for (size_t a = 0; a < block_.nodes.size(); ++a) {
      const int o = block_.offsets[a];
      const Eigen::Matrix<double, 3, Eigen::Dynamic> Bx = F_.R * rb_.shapes[a].topRows<3>();
      const Eigen::Matrix<double, 3, Eigen::Dynamic> Bt = tangent_so3<double>(phi[a]) * rb_.shapes[a].bottomRows<3>();
      ft += Bx.transpose() * f.segment<3>(o) + Bt.transpose() * f.segment<3>(o + 3);
    }
    return ft;
  }

 private:
  const Model& model_;
  const std::vector<int>& ids_;
  const BlockMatrices& block_;
  const ReducedBlock& rb_;
  Pose<double> F_;
  MechanicalState s0_;
  std::vector<int> conf_;
  std::vector<std::vector<int>> confs_, rows_;
  double size_ = 0.0;
  Eigen::Index block_rows_ = 0;
};

}  // namespace

int add_modal_derivatives(const Model& model, const std::vector<int>& element_ids, const BlockMatrices& block, int columns,
                          ReducedBlock& rb) {
  const int m = rb.matrices.elastic();
  if (columns < 0 || columns > m) {
    std::ostringstream os;
    os << "asks for the modal derivatives of " << columns << " basis vectors; the basis has " << m;
    throw std::invalid_argument(os.str());
  }
  if (columns == 0) return 0;
  const int n = block.size(), f0 = block.row_of(rb.frame_node);
  std::vector<int> keep;
  for (int r = 0; r < n; ++r)
    if (r < f0 || r >= f0 + 6) keep.push_back(r);
  const int nk = static_cast<int>(keep.size());
  const SparseMatrix Kc = submatrix(block.K_sparse, keep, keep), Mc = submatrix(block.M_sparse, keep, keep);
  Superelement& se = rb.superelement;
  std::vector<char> is_boundary(static_cast<size_t>(nk), 0);
  for (int r : se.boundary) is_boundary[static_cast<size_t>(r)] = 1;
  std::vector<int> interior;
  for (int r = 0; r < nk; ++r)
    if (!is_boundary[static_cast<size_t>(r)]) interior.push_back(r);
  if (interior.empty()) return 0;
  const Eigen::SimplicialLDLT<SparseMatrix> ldlt(submatrix(Kc, interior, interior));
  check_held(ldlt);
  std::vector<Eigen::VectorXd> theta;
  double largest = 0.0;
  {  // `forces` reads rb's node data, which complete_block rebuilds below: it ends here.
    const BlockForces forces(model, element_ids, block, rb);
    // Difference steps as nonlinear_stiffness: 10⁻³ of the block's size in each direction's largest
    // displacement (a rotation counted by its lever, the block's size).
    const double size = forces.size();
    Eigen::VectorXd h(m);
    for (int i = 0; i < m; ++i) {
      double big = 0.0;
      for (size_t a = 0; a < block.nodes.size(); ++a)
        big = std::max({big, rb.shapes[a].col(i).head<3>().cwiseAbs().maxCoeff(), size * rb.shapes[a].col(i).tail<3>().cwiseAbs().maxCoeff()});
      h[i] = 1e-3 * size / std::max(big, 1e-300);
    }
    const Eigen::VectorXd zero = forces.full(Eigen::VectorXd::Zero(m));
    const auto unit = [&](int i) { return Eigen::VectorXd(Eigen::VectorXd::Unit(m, i) * h[i]); };
    // θᵢⱼ: K_ii θ = −(∂²f/∂ξᵢ∂ξⱼ)_i on the interior, zero on the interface rows (held, as the
    // constraint modes hold them: the interface rows of the basis stay [I, 0]).
    for (int i = 0; i < columns; ++i)
      for (int j = i; j < columns; ++j) {
        Eigen::VectorXd d2;
        if (i == j) {
          d2 = (forces.full(unit(i)) - 2.0 * zero + forces.full(-unit(i))) / (h[i] * h[i]);
        } else {
          const Eigen::VectorXd a = unit(i), b = unit(j);
          d2 = (forces.full(a + b) - forces.full(a - b) - forces.full(b - a) + forces.full(-a - b)) / (4.0 * h[i] * h[j]);
        }
        Eigen::VectorXd gi(static_cast<Eigen::Index>(interior.size()));
        for (size_t r = 0; r < interior.size(); ++r) gi[static_cast<Eigen::Index>(r)] = d2[keep[static_cast<size_t>(interior[r])]];
        const Eigen::VectorXd ti = -ldlt.solve(gi);
        Eigen::VectorXd t = Eigen::VectorXd::Zero(nk);
        for (size_t r = 0; r < interior.size(); ++r) t[interior[r]] = ti[static_cast<Eigen::Index>(r)];
        largest = std::max(largest, std::sqrt(t.dot(Mc * t)));
        theta.push_back(std::move(t));
      }
  }
  // M-orthonormalized against the normal (and inertia) modes and each other, as add_inertia_modes;
  // a derivative below 10⁻⁶ of the largest (a pair whose curvature does not strain the block, e.g.
  // a rigid motion of the interface) or dependent on the others (to 10⁻⁶) is dropped.
  const int added = append_m_orthonormal(Kc, Mc, theta, 1e-6 * largest, se);
  complete_block(model, block, rb);
  return added;
}

void nonlinear_stiffness(const Model& model, const std::vector<int>& element_ids, const BlockMatrices& block, ReducedBlock& rb,
                         double* asymmetry) {
  const int m = rb.matrices.elastic();
  const size_t nn = block.nodes.size();
  const BlockForces forces(model, element_ids, block, rb);
  const double size = forces.size();
  const auto projected_force = [&](const Eigen::VectorXd& xi) { return forces.projected(xi); };
  // The stencils below meet the same points again (±hⱼeⱼ in T's diagonal and in every Q term with
  // two equal indices, whose signs cancel exactly): each distinct ξ is evaluated once — the same
  // values, so the tensors are unchanged to the last bit (m = 14: 4061 evaluations for 4872).
  std::map<std::vector<double>, Eigen::VectorXd> seen;
  const auto force_at = [&](const Eigen::VectorXd& xi) -> const Eigen::VectorXd& {
    std::vector<double> key(xi.data(), xi.data() + xi.size());
    for (double& v : key) v += 0.0;  // −0 and +0 are one point
    auto it = seen.find(key);
    if (it == seen.end()) it = seen.emplace(std::move(key), projected_force(xi)).first;
    return it->second;
  };
  const Eigen::VectorXd f0 = force_at(Eigen::VectorXd::Zero(m));
  const double kscale = rb.matrices.K.cwiseAbs().maxCoeff();
  Eigen::VectorXd h(m);
  for (int i = 0; i < m; ++i) {
    double big = 0.0;
    for (size_t a = 0; a < nn; ++a)
      big = std::max({big, rb.shapes[a].col(i).head<3>().cwiseAbs().maxCoeff(), size * rb.shapes[a].col(i).tail<3>().cwiseAbs().maxCoeff()});
    h[i] = 1e-3 * size / std::max(big, 1e-300);
  }
  if (f0.norm() > 1e-8 * kscale * h.maxCoeff())
    throw std::invalid_argument("geometric stiffness: the block is not stress-free in its initial state");
  // T[k](i, j) = ∂²f̃ᵢ/∂ξⱼ∂ξₖ: f̃'s even part, by central second differences (its odd part cancels).
  std::vector<Eigen::MatrixXd> T(static_cast<size_t>(m), Eigen::MatrixXd::Zero(m, m));
  const auto unit = [&](int i) { return Eigen::VectorXd(Eigen::VectorXd::Unit(m, i) * h[i]); };
  for (int j = 0; j < m; ++j)
    for (int k = j; k < m; ++k) {
      Eigen::VectorXd d2;
      if (j == k) {
        d2 = (force_at(unit(j)) - 2.0 * f0 + force_at(-unit(j))) / (h[j] * h[j]);
      } else {
        const Eigen::VectorXd a = unit(j), b = unit(k);
        d2 = (force_at(a + b) - force_at(a - b) - force_at(b - a) + force_at(-a - b)) / (4.0 * h[j] * h[k]);
      }
      for (int i = 0; i < m; ++i) T[static_cast<size_t>(k)](i, j) = T[static_cast<size_t>(j)](i, k) = d2[i];
    }
  // Full symmetry: T_ijk is a third derivative. The differences are symmetric in (j, k) by
  // construction; (i, j) measures their error.
  double tmax = 0.0, asym = 0.0;
  std::vector<Eigen::MatrixXd> Ts(static_cast<size_t>(m), Eigen::MatrixXd::Zero(m, m));
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) {
        const auto t = [&](int a, int b, int c) { return T[static_cast<size_t>(c)](a, b); };
        const double sym = (t(i, j, k) + t(i, k, j) + t(j, i, k) + t(j, k, i) + t(k, i, j) + t(k, j, i)) / 6.0;
        tmax = std::max(tmax, std::abs(t(i, j, k)));
        asym = std::max(asym, std::abs(t(i, j, k) - sym));
        Ts[static_cast<size_t>(k)](i, j) = sym;
      }
  if (asymmetry) *asymmetry = tmax > 0.0 ? asym / tmax : 0.0;
  for (Eigen::MatrixXd& t : Ts) t = 0.5 * (t + t.transpose()).eval();
  // Q[k·m + l](i, j) = ∂³f̃ᵢ/∂ξⱼ∂ξₖ∂ξₗ by the eight-point polarization stencil
  // Σ s₁s₂s₃ f̃(s₁a + s₂b + s₃c) / (8 hⱼhₖhₗ): its weight is odd under a global sign change, so
  // every even term of f̃ cancels and the error is O(h²) of the 6th derivative of U.
  std::vector<Eigen::MatrixXd> Q(static_cast<size_t>(m * m), Eigen::MatrixXd::Zero(m, m));
  for (int j = 0; j < m; ++j)
    for (int k = j; k < m; ++k)
      for (int l = k; l < m; ++l) {
        const Eigen::VectorXd a = unit(j), b = unit(k), c = unit(l);
        Eigen::VectorXd d3 = Eigen::VectorXd::Zero(m);
        for (int s1 : {-1, 1})
          for (int s2 : {-1, 1})
            for (int s3 : {-1, 1}) d3 += double(s1 * s2 * s3) * force_at(s1 * a + s2 * b + s3 * c);
        d3 /= 8.0 * h[j] * h[k] * h[l];
        const int idx[3] = {j, k, l};
        const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
        for (const auto& p : perm)
          for (int i = 0; i < m; ++i) Q[static_cast<size_t>(idx[p[1]] * m + idx[p[2]])](i, idx[p[0]]) = d3[i];
      }
  // Full symmetry over the four indices: the differences are symmetric in (j, k, l); average the
  // four choices of the force index.
  std::vector<Eigen::MatrixXd> Qs(static_cast<size_t>(m * m), Eigen::MatrixXd::Zero(m, m));
  const auto q = [&](int i, int j, int k, int l) { return Q[static_cast<size_t>(k * m + l)](i, j); };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k)
        for (int l = 0; l < m; ++l)
          Qs[static_cast<size_t>(k * m + l)](i, j) = 0.25 * (q(i, j, k, l) + q(j, i, k, l) + q(k, j, i, l) + q(l, j, k, i));
  for (Eigen::MatrixXd& t : Qs) t = 0.5 * (t + t.transpose()).eval();
  // Stored by their unique entries (i ≤ j ≤ k (≤ l)): the symmetrized tensors' entries there.
  rb.matrices.T = SymmetricTensor(3, m, [&](int i, int j, int k, int) { return Ts[static_cast<size_t>(k)](i, j); });
  rb.matrices.Q = SymmetricTensor(4, m, [&](int i, int j, int k, int l) { return Qs[static_cast<size_t>(k * m + l)](i, j); });
}

}  // namespace alphaflex
