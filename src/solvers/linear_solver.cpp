#include "alphaflex/solvers/linear_solver.hpp"

#include <sstream>

namespace alphaflex {

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
    if (info1 == -9 || info1 == -8) os << " (workspace too small: raise -mat_mumps_icntl_14)";
  }
  failure_ = os.str();
  PetscFunctionReturn(0);
}

PetscErrorCode LinearSolver::factor(Mat A) {
  PetscFunctionBeginUser;
  failure_.clear();
  PetscObjectState state;
  PetscCall(MatGetNonzeroState(A, &state));
  if (state != last_state_) ++symbolic_;
  last_state_ = state;
  PetscCall(KSPSetOperators(ksp_, A, A));
  PetscCall(KSPSetUp(ksp_));
  PC pc;
  PetscCall(KSPGetPC(ksp_, &pc));
  // Count factorizations only when the options left the PC a factorization.
  PetscBool factors = PETSC_FALSE;
  PetscCall(PetscObjectTypeCompareAny(reinterpret_cast<PetscObject>(pc), &factors, PCLU, PCCHOLESKY, ""));
  if (factors) ++numeric_;
  else symbolic_ = 0;
  PCFailedReason pcreason;
  PetscCall(PCGetFailedReason(pc, &pcreason));
  if (pcreason != PC_NOERROR) PetscCall(describe_failure("factorization"));
  else if (factors) PetscCall(read_statistics(pc));
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
