#include "alphaflex/solvers/linear_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include <petscblaslapack.h>

#include "alphaflex/core/blas_library.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/memory.hpp"
#include "alphaflex/core/petsc_error.hpp"

namespace alphaflex {
namespace {

/// MUMPS' INFOG(1) codes for workspace smaller than the factorization needs (MUMPS users' guide,
/// "error diagnostics"): raising ICNTL(14) is the cure for each.
bool workspace_too_small(PetscInt info1) {
  switch (info1) {
    case -8: case -9: case -11: case -12: case -14: case -15: case -17: case -20: return true;
    default: return false;
  }
}

/// MUMPS' INFOG(1) codes of an allocation the operating system refused (MUMPS users' guide 5.5,
/// "error diagnostics"), with the bytes of one unit of INFO(2): −5 real and −7 integer workspace of
/// the analysis, −13 an ALLOCATE of the factorization or solve (scalar entries). 0: not one of them.
double refused_allocation_unit(PetscInt info1) {
  switch (info1) {
    case -5: case -13: return sizeof(PetscScalar);
    case -7: return sizeof(PetscInt);
    default: return 0.0;
  }
}

}  // namespace


LinearSolver::LinearSolver(MPI_Comm comm, double low_rank) : comm_(comm), low_rank_(low_rank) {
  check_petsc(KSPCreate(comm, &ksp_), "KSPCreate");
  check_petsc(KSPSetType(ksp_, KSPPREONLY), "KSPSetType");
  PC pc;
  check_petsc(KSPGetPC(ksp_, &pc), "KSPGetPC");
  check_petsc(PCSetType(pc, PCLU), "PCSetType");
  check_petsc(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  check_petsc(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  // OpenBLAS (MUMPS' dense kernels) takes its workspace now, while there is room: it would wait
  // forever for it at the first factorization under an address-space limit.
  reserve_blas_workspace(comm);
}

LinearSolver::~LinearSolver() { KSPDestroy(&ksp_); }

PetscErrorCode LinearSolver::describe_failure(const char* phase) {
  PetscFunctionBeginUser;
  KSPConvergedReason reason;
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  PC pc;
  PetscCall(KSPGetPC(ksp_, &pc));
  PCFailedReason pcreason;
  PetscCall(PCGetFailedReason(pc, &pcreason));
  std::ostringstream os;
  os << phase << " failed (" << KSPConvergedReasons[reason] << ", " << PCFailedReasons[pcreason] << ")";
  Mat F = nullptr;
  PetscBool is_mumps = PETSC_FALSE;
  MatSolverType type = nullptr;
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  if (type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &is_mumps));
  if (is_mumps) {
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscInt info1 = 0, info2 = 0;
    PetscCall(MatMumpsGetInfog(F, 1, &info1));
    PetscCall(MatMumpsGetInfog(F, 2, &info2));
    // An allocation the system refused (the solve's workspace, −13): memory exhaustion, on every rank.
    if (refused_allocation_unit(info1) > 0.0) throw_memory_failure(F, info1, phase);
    os << "; MUMPS INFOG(1)=" << info1 << " INFOG(2)=" << info2;
    if (info1 == -10) os << " (numerically singular matrix)";
    if (workspace_too_small(info1))
      os << " (workspace too small even at ICNTL(14) = " << icntl14_ << " % after " << workspace_retries_
         << " retries: raise -mat_mumps_icntl_14 or give the ranks more memory)";
  }
  failure_ = os.str();
  PetscFunctionReturn(0);
}


PetscErrorCode LinearSolver::choose_backend(Mat A) {
  PetscFunctionBeginUser;
  // Dense on one rank for small systems, unless the user chose a solver in the options database.
  int size = 1;
  MPI_Comm_size(comm_, &size);
  PetscInt n = 0, limit = kDenseLimit;
  PetscCall(MatGetSize(A, &n, nullptr));
  PetscCall(PetscOptionsGetInt(nullptr, nullptr, "-af_dense_lu", &limit, nullptr));
  // Any KSP, PC or MUMPS option (-ksp_type, -ksp_view, -pc_factor_mat_solver_type,
  // -mat_mumps_icntl_14, ...) means the user wants the PETSc path.
  char* all = nullptr;
  PetscCall(PetscOptionsGetAll(nullptr, &all));
  const std::string options = all ? all : "";
  PetscCall(PetscFree(all));
  bool chosen = false;
  for (const char* key : {"-ksp_", "-pc_", "-mat_mumps_"}) chosen = chosen || options.find(key) != std::string::npos;
  backend_ = (size == 1 && n <= limit && !chosen && low_rank_ <= 0.0) ? Backend::Dense : Backend::Krylov;
  if (backend_ == Backend::Dense) {
    dense_.setZero(n, n);
    pivots_.assign(static_cast<size_t>(n), 0);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::factor_dense(Mat A) {
  PetscFunctionBeginUser;
  // The values of the sequential AIJ matrix into the dense one (the pattern is fixed; zeros stay).
  PetscInt n = 0, nz = 0;
  const PetscInt* cols = nullptr;
  const PetscScalar* vals = nullptr;
  PetscCall(MatGetSize(A, &n, nullptr));
  dense_.setZero();
  for (PetscInt i = 0; i < n; ++i) {
    PetscCall(MatGetRow(A, i, &nz, &cols, &vals));
    for (PetscInt k = 0; k < nz; ++k) dense_(i, cols[k]) = vals[k];
    PetscCall(MatRestoreRow(A, i, &nz, &cols, &vals));
  }
  // LAPACK's dgetrf on the column-major storage, in place: the blocked right-looking LU with row
  // pivoting, on the BLAS the package set installs (OpenBLAS, scripts/install-deps.sh) — 1.8×
  // Eigen's PartialPivLU at 100–150 unknowns on this machine (Eigen's kernels are built for SSE2,
  // OpenBLAS picks AVX2 at run time; docs/performance.md, "Small systems"), the same algorithm.
  stats_ = FactorStatistics{};
  stats_.dense = true;
  stats_.entries = static_cast<double>(n) * static_cast<double>(n);
  stats_.flops = 2.0 / 3.0 * static_cast<double>(n) * static_cast<double>(n) * static_cast<double>(n);
  stats_.memory_max_mb = stats_.memory_sum_mb = stats_.entries * 8.0 / 1048576.0;  // factored in place
  ++numeric_;
  // A NaN or Inf entry (an element evaluated where it has no value) is not given to LAPACK, whose
  // pivot search is not defined for it (OpenBLAS has returned out-of-range pivots then).
  if (!dense_.allFinite()) {
    failure_ = "factorization failed: the iteration matrix has a non-finite entry (NaN or Inf)";
    PetscFunctionReturn(0);
  }
  PetscBLASInt bn = 0, info = 0;
  PetscCall(PetscBLASIntCast(n, &bn));
  const PetscBLASInt lda = std::max<PetscBLASInt>(bn, 1);  // LAPACK asks LDA ≥ max(1, N), also for N = 0
  PetscCallBLAS("LAPACKgetrf", LAPACKgetrf_(&bn, &bn, dense_.data(), &lda, pivots_.data(), &info));
  PetscCheck(info >= 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getrf: argument %d is illegal", -static_cast<int>(info));
  if (determinant_) {
    // sign(det) = sign(det P) · Π sign(u_ii): the product itself over/underflows for n ~ 100.
    // pivots_[i] (1-based) is the row swapped with row i: each swap flips the sign.
    int sign = 1;
    for (PetscInt i = 0; i < n; ++i) sign *= (pivots_[static_cast<size_t>(i)] != i + 1 ? -1 : 1) * (dense_(i, i) < 0.0 ? -1 : 1);
    det_sign_ = sign;
  }
  // A zero (or non-finite) pivot after partial pivoting (info > 0: u_ii exactly zero): the matrix
  // is singular, as MUMPS' -10.
  const auto d = dense_.diagonal();
  bool singular = info > 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) singular = singular || !(std::fabs(d[i]) > 0.0) || !std::isfinite(d[i]);
  if (singular) failure_ = "factorization failed: dense LU found a zero pivot (numerically singular matrix)";
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::factor(Mat A) {
  PetscFunctionBeginUser;
  failure_.clear();
  workspace_failure_ = false;
  det_sign_ = 0;
  if (backend_ == Backend::Undecided) PetscCall(choose_backend(A));
  if (backend_ == Backend::Dense) {
    if (last_state_ == -1) ++symbolic_;  // the pattern, once (as for MUMPS)
    last_state_ = 0;
    PetscCall(factor_dense(A));
    PetscFunctionReturn(0);
  }
  PetscObjectState state;
  PetscCall(MatGetNonzeroState(A, &state));
  if (state != last_state_) ++symbolic_;
  last_state_ = state;
  PC pc;
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(KSPSetOperators(ksp_, A, A));
  PetscCall(set_low_rank(pc));
  for (int attempt = 0;; ++attempt) {
    PetscCall(set_determinant(pc));
    {
      // PETSc's own allocations (the matrix handed to MUMPS as triples, the factor's structures):
      // an out-of-memory is a MemoryError naming the phase, without PETSc's trace.
      const QuietPetscErrors quiet;
      quiet.check(KSPSetUp(ksp_), "handing the iteration matrix to MUMPS for its analysis and factorization");
    }
    // Count factorizations only when the options left the PC a factorization.
    PetscBool factors = PETSC_FALSE;
    PetscCall(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factors, PCLU, PCCHOLESKY, ""));
    if (factors) ++numeric_;
    else symbolic_ = 0;
    PCFailedReason pcreason;
    PetscCall(PCGetFailedReason(pc, &pcreason));
    if (pcreason == PC_NOERROR) {
      if (factors) PetscCall(read_statistics(pc));
      if (factors) PetscCall(read_determinant(pc));
      break;
    }
    // Workspace too small: the same factorization again with ICNTL(14) doubled. INFOG is global,
    // so every rank takes the same branch.
    Mat F = nullptr;
    PetscInt info1 = 0;
    MatSolverType type = nullptr;
    PetscBool is_mumps = PETSC_FALSE;
    PetscCall(PCFactorGetMatSolverType(pc, &type));
    if (type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &is_mumps));
    if (is_mumps) {
      PetscCall(PCFactorGetMatrix(pc, &F));
      PetscCall(MatMumpsGetInfog(F, 1, &info1));
      PetscCall(read_analysis_estimate(F));
      // INFOG is global: every rank throws the same error.
      if (refused_allocation_unit(info1) > 0.0) throw_memory_failure(F, info1, info1 == -13 ? "factorization" : "analysis");
    }
    if (!is_mumps || !workspace_too_small(info1) || attempt >= 5) {
      workspace_failure_ = is_mumps && workspace_too_small(info1);
      PetscCall(describe_failure("factorization"));
      break;
    }
    PetscInt percent = 0;
    PetscCall(MatMumpsGetIcntl(F, 14, &percent));
    icntl14_ = static_cast<int>(std::max<PetscInt>(2 * percent, 20));
    ++workspace_retries_;
    // PETSc's MUMPS interface does not refactor numerically once INFOG(1) < 0: start the factor
    // afresh (a new analysis, counted) with the larger ICNTL(14), set both on the new factor and in
    // the options database, which the analysis reads (so that -mat_mumps_icntl_14 given on the
    // command line does not put the old value back). It stays for the rest of the run.
    PetscCall(PCReset(pc));
    char value[32];
    std::snprintf(value, sizeof value, "%d", icntl14_);
    PetscCall(PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_14", value));
    PetscCall(KSPSetOperators(ksp_, A, A));
    PetscCall(PCFactorSetUpMatSolverType(pc));
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(MatMumpsSetIcntl(F, 14, icntl14_));
    low_rank_set_ = false;
    PetscCall(set_low_rank(pc));
    ++symbolic_;
  }
  PetscFunctionReturn(0);
}

namespace {
/// The MUMPS factor matrix of `pc` in `F`, nullptr when the options chose another solver.
PetscErrorCode mumps_factor(PC pc, Mat* F) {
  PetscFunctionBeginUser;
  *F = nullptr;
  MatSolverType type = nullptr;
  PetscBool is_mumps = PETSC_FALSE;
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  if (type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &is_mumps));
  if (is_mumps) PetscCall(PCFactorGetMatrix(pc, F));
  PetscFunctionReturn(0);
}
}  // namespace
PetscErrorCode LinearSolver::read_analysis_estimate(Mat F) {
  PetscFunctionBeginUser;
  // INFOG(16), INFOG(17): MB MUMPS' analysis estimates for the in-core factorization, on the
  // largest rank and summed (with ICNTL(14)'s margin; users' guide 5.5, section 6.2).
  PetscInt largest = 0, sum = 0;
  PetscCall(MatMumpsGetInfog(F, 16, &largest));
  PetscCall(MatMumpsGetInfog(F, 17, &sum));
  if (largest > 0) {
    estimate_.largest_mb = static_cast<double>(largest);
    estimate_.sum_mb = static_cast<double>(sum);
  }
  PetscFunctionReturn(0);
}

void LinearSolver::throw_memory_failure(Mat F, PetscInt info1, const char* phase) {
  PetscInt info2 = 0, n = 0;
  check_petsc(MatMumpsGetInfog(F, 2, &info2), "MatMumpsGetInfog");
  check_petsc(MatGetSize(F, &n, nullptr), "MatGetSize");
  // INFO(2) < 0: millions of units.
  const double units = info2 < 0 ? -1e6 * static_cast<double>(info2) : static_cast<double>(info2);
  std::ostringstream what;
  what << "MUMPS ran its " << phase << " of the iteration matrix (" << n
       << " unknowns; MUMPS INFOG(1) = " << info1 << ", INFOG(2) = " << info2;
  if (estimate_.largest_mb > 0.0)
    what << "; its analysis estimated " << estimate_.largest_mb << " MB per rank for the factorization";
  what << ")";
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  throw MemoryError(out_of_memory_message(what.str(), units * refused_allocation_unit(info1), rank));
}

PetscErrorCode LinearSolver::set_low_rank(PC pc) {
  PetscFunctionBeginUser;
  if (low_rank_ <= 0.0 || low_rank_set_) PetscFunctionReturn(0);
  // The factor must exist before the analysis reads ICNTL(35): MUMPS chooses the BLR clustering
  // of the fronts there. ICNTL(35) = 2: BLR in the factorization and the solve (the factors stay
  // compressed, which is what saves memory); CNTL(7): the dropping tolerance ε of the low-rank
  // approximations, ‖B − XYᵀ‖ ≤ ε‖B‖ per block (MUMPS 5.5 users' guide, ICNTL(35), CNTL(7)).
  // Options given on the command line (-mat_mumps_icntl_35, -mat_mumps_cntl_7) still win: PETSc
  // reads them into the factor at the analysis.
  PetscCall(PCFactorSetUpMatSolverType(pc));
  Mat F = nullptr;
  PetscCall(mumps_factor(pc, &F));
  if (F) {
    PetscCall(MatMumpsSetIcntl(F, 35, 2));
    PetscCall(MatMumpsSetCntl(F, 7, low_rank_));
  }
  low_rank_set_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::set_determinant(PC pc) {
  PetscFunctionBeginUser;
  if (!determinant_) PetscFunctionReturn(0);
  PetscCall(PCFactorSetUpMatSolverType(pc));
  Mat F = nullptr;
  PetscCall(mumps_factor(pc, &F));
  if (F) PetscCall(MatMumpsSetIcntl(F, 33, 1));  // determinant during the factorization (ICNTL(33))
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::read_determinant(PC pc) {
  PetscFunctionBeginUser;
  if (!determinant_) PetscFunctionReturn(0);
  Mat F = nullptr;
  PetscCall(mumps_factor(pc, &F));
  if (!F) PetscFunctionReturn(0);
  // det A = RINFOG(12) · 2^INFOG(34) (real case; RINFOG is global: the same on every rank).
  PetscReal mantissa = 0.0;
  PetscCall(MatMumpsGetRinfog(F, 12, &mantissa));
  det_sign_ = mantissa > 0.0 ? 1 : (mantissa < 0.0 ? -1 : 0);
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::read_statistics(PC pc) {
  PetscFunctionBeginUser;
  MatSolverType type = nullptr;
  PetscBool is_mumps = PETSC_FALSE;
  PetscCall(PCFactorGetMatSolverType(pc, &type));
  if (type) PetscCall(PetscStrcmp(type, MATSOLVERMUMPS, &is_mumps));
  stats_ = FactorStatistics{};
  if (!is_mumps) PetscFunctionReturn(0);
  Mat F;
  PetscCall(PCFactorGetMatrix(pc, &F));
  PetscCall(read_analysis_estimate(F));
  PetscInt entries = 0, mem_max = 0, mem_sum = 0;
  PetscReal flops = 0.0;
  PetscCall(MatMumpsGetRinfog(F, 3, &flops));
  PetscCall(MatMumpsGetInfog(F, 29, &entries));
  PetscCall(MatMumpsGetInfog(F, 21, &mem_max));
  PetscCall(MatMumpsGetInfog(F, 22, &mem_sum));
  stats_.mumps = true;
  stats_.flops = flops;
  stats_.entries = entries < 0 ? -1e6 * static_cast<double>(entries) : static_cast<double>(entries);  // < 0: millions
  stats_.memory_max_mb = static_cast<double>(mem_max);
  stats_.memory_sum_mb = static_cast<double>(mem_sum);
  PetscInt blr = 0;
  PetscCall(MatMumpsGetIcntl(F, 35, &blr));
  if (blr > 0) {
    PetscInt compressed = 0;
    PetscReal tolerance = 0.0;
    PetscCall(MatMumpsGetInfog(F, 35, &compressed));
    PetscCall(MatMumpsGetCntl(F, 7, &tolerance));
    PetscCall(MatMumpsGetRinfog(F, 14, &stats_.low_rank_flops));
    stats_.low_rank_tolerance = tolerance;
    stats_.low_rank_entries = compressed < 0 ? -1e6 * static_cast<double>(compressed) : static_cast<double>(compressed);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::solve(Vec b, Vec x) {
  PetscFunctionBeginUser;
  if (!failure_.empty()) PetscFunctionReturn(0);
  if (backend_ == Backend::Dense) {
    PetscCall(VecCopy(b, x));
    PetscScalar* xx = nullptr;
    PetscBLASInt bn = 0, one = 1, info = 0;
    PetscCall(PetscBLASIntCast(dense_.rows(), &bn));
    const PetscBLASInt lda = std::max<PetscBLASInt>(bn, 1);
    PetscCall(VecGetArray(x, &xx));
    PetscCallBLAS("LAPACKgetrs", LAPACKgetrs_("N", &bn, &one, dense_.data(), &lda, pivots_.data(), xx, &lda, &info));
    if (!Eigen::Map<Eigen::VectorXd>(xx, dense_.rows()).allFinite()) failure_ = "solve failed: the dense LU solution is not finite";
    PetscCall(VecRestoreArray(x, &xx));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK getrs: argument %d is illegal", -static_cast<int>(info));
    PetscFunctionReturn(0);
  }
  PetscCall(KSPSolve(ksp_, b, x));
  KSPConvergedReason reason;
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  if (reason < 0) PetscCall(describe_failure("solve"));
  PetscFunctionReturn(0);
}

}  // namespace alphaflex
