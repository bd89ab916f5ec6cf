#include "alphaflex/solvers/linear_solver.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>

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

}  // namespace


LinearSolver::LinearSolver(MPI_Comm comm) {
  PetscFunctionBeginUser;
  PetscCallAbort(comm, KSPCreate(comm, &ksp_));
  PetscCallAbort(comm, KSPSetType(ksp_, KSPPREONLY));
  PC pc;
  PetscCallAbort(comm, KSPGetPC(ksp_, &pc));
  PetscCallAbort(comm, PCSetType(pc, PCLU));
  PetscCallAbort(comm, PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCallAbort(comm, KSPSetFromOptions(ksp_));
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
    os << "; MUMPS INFOG(1)=" << info1 << " INFOG(2)=" << info2;
    if (info1 == -10) os << " (numerically singular matrix)";
    if (workspace_too_small(info1))
      os << " (workspace too small even at ICNTL(14) = " << icntl14_ << " % after " << workspace_retries_
         << " retries: raise -mat_mumps_icntl_14 or give the ranks more memory)";
  }
  failure_ = os.str();
  PetscFunctionReturn(0);
}


PetscErrorCode LinearSolver::factor(Mat A) {
  PetscFunctionBeginUser;
  failure_.clear();
  workspace_failure_ = false;
  PetscObjectState state;
  PetscCall(MatGetNonzeroState(A, &state));
  if (state != last_state_) ++symbolic_;
  last_state_ = state;
  PC pc;
  PetscCall(KSPGetPC(ksp_, &pc));
  PetscCall(KSPSetOperators(ksp_, A, A));
  for (int attempt = 0;; ++attempt) {
    PetscCall(KSPSetUp(ksp_));
    // Count factorizations only when the options left the PC a factorization.
    PetscBool factors = PETSC_FALSE;
    PetscCall(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factors, PCLU, PCCHOLESKY, ""));
    if (factors) ++numeric_;
    else symbolic_ = 0;
    PCFailedReason pcreason;
    PetscCall(PCGetFailedReason(pc, &pcreason));
    if (pcreason == PC_NOERROR) {
      if (factors) PetscCall(read_statistics(pc));
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
    ++symbolic_;
  }
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
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::solve(Vec b, Vec x) {
  PetscFunctionBeginUser;
  if (!failure_.empty()) PetscFunctionReturn(0);
  PetscCall(KSPSolve(ksp_, b, x));
  KSPConvergedReason reason;
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  if (reason < 0) PetscCall(describe_failure("solve"));
  PetscFunctionReturn(0);
}

}  // namespace alphaflex
