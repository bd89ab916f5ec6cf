#include "alphaflex/study/iteration_matrix.hpp"

#include <petscksp.h>

#include <Eigen/SVD>
#include <limits>
#include <vector>

#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/petsc_error.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex::study {
namespace {

// The owned rows of A as (row, column, value) triplets, gathered on rank 0 into a dense matrix.
Eigen::MatrixXd gather_dense(Mat A, int n, MPI_Comm comm) {
  PetscInt r0 = 0, r1 = 0;
  check_petsc(MatGetOwnershipRange(A, &r0, &r1), "MatGetOwnershipRange (condition number of S_t)");
  std::vector<double> local;  // flattened triplets (row, col, value) as doubles
  for (PetscInt i = r0; i < r1; ++i) {
    PetscInt ncols = 0;
    const PetscInt* cols = nullptr;
    const PetscScalar* vals = nullptr;
    check_petsc(MatGetRow(A, i, &ncols, &cols, &vals), "MatGetRow (condition number of S_t)");
    for (PetscInt k = 0; k < ncols; ++k) {
      local.push_back(static_cast<double>(i));
      local.push_back(static_cast<double>(cols[k]));
      local.push_back(vals[k]);
    }
    check_petsc(MatRestoreRow(A, i, &ncols, &cols, &vals), "MatRestoreRow (condition number of S_t)");
  }
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int count = static_cast<int>(local.size());
  std::vector<int> counts(static_cast<size_t>(size)), displs(static_cast<size_t>(size));
  MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  std::vector<double> all;
  if (rank == 0) {
    int total = 0;
    for (int r = 0; r < size; ++r) {
      displs[static_cast<size_t>(r)] = total;
      total += counts[static_cast<size_t>(r)];
    }
    all.resize(static_cast<size_t>(total));
  }
  MPI_Gatherv(local.data(), count, MPI_DOUBLE, all.data(), counts.data(), displs.data(), MPI_DOUBLE, 0, comm);
  Eigen::MatrixXd D;
  if (rank == 0) {
    D = Eigen::MatrixXd::Zero(n, n);
    for (size_t k = 0; k + 2 < all.size(); k += 3)
      D(static_cast<int>(all[k]), static_cast<int>(all[k + 1])) += all[k + 2];
  }
  return D;
}

// MUMPS' condition numbers from its error analysis of one solve with A (RINFOG(10), (11)).
void mumps_condition(Mat A, Vec b, Vec x, MPI_Comm comm, double& cond1, double& cond2) {
  KSP ksp = nullptr;
  check_petsc(KSPCreate(comm, &ksp), "KSPCreate (condition number of S_t)");
  check_petsc(KSPSetType(ksp, KSPPREONLY), "KSPSetType (condition number of S_t)");
  PC pc = nullptr;
  check_petsc(KSPGetPC(ksp, &pc), "KSPGetPC (condition number of S_t)");
  check_petsc(PCSetType(pc, PCLU), "PCSetType (condition number of S_t)");
  check_petsc(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType (condition number of S_t)");
  check_petsc(KSPSetOperators(ksp, A, A), "KSPSetOperators (condition number of S_t)");
  check_petsc(PCFactorSetUpMatSolverType(pc), "PCFactorSetUpMatSolverType (condition number of S_t)");
  Mat F = nullptr;
  check_petsc(PCFactorGetMatrix(pc, &F), "PCFactorGetMatrix (condition number of S_t)");
  check_petsc(MatMumpsSetIcntl(F, 11, 1), "MatMumpsSetIcntl(11) (condition number of S_t)");  // full error analysis in the solve
  check_petsc(KSPSetUp(ksp), "KSPSetUp (condition number of S_t)");
  check_petsc(KSPSolve(ksp, b, x), "KSPSolve (condition number of S_t)");
  PetscReal c1 = 0, c2 = 0;
  check_petsc(MatMumpsGetRinfog(F, 10, &c1), "MatMumpsGetRinfog(10) (condition number of S_t)");
  check_petsc(MatMumpsGetRinfog(F, 11, &c2), "MatMumpsGetRinfog(11) (condition number of S_t)");
  cond1 = c1;
  cond2 = c2;
  KSPDestroy(&ksp);
}

}  // namespace

ConditionNumbers iteration_matrix_condition(const Model& model, const MechanicalState& s, const AlphaParameters& p,
                                            double h, bool scaling, MPI_Comm comm, int dense_limit) {
  Subdomain sub(model, comm);
  SaddlePointSystem system(sub);
  const MechanicalState local = sub.restrict(s);  // this rank's owned and ghost nodes
  const double bh2 = p.beta * h * h;
  AssemblyCoefficients c;
  c.mass = p.beta_prime(h);  // β' (eq. 6)
  c.damping = p.gamma_prime(h);                                        // γ'
  c.stiffness = 1.0;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(local.v.size());
  if (model.has_lie_group_nodes()) c.increment = &zero;
  ConditionNumbers out;
  out.unknowns = sub.dof_map().global_size();
  out.two_norm = std::numeric_limits<double>::quiet_NaN();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (out.unknowns <= dense_limit) {
    // cond₂(S) = ‖S‖₂ ‖S⁻¹‖₂, with S⁻¹ formed from the scaled matrix S_s, which is well conditioned:
    // S = D_L S_s D_R exactly, D_L = diag(1/(βh²) on dynamic rows, 1 on constraint rows),
    // D_R = diag(1 on coordinates, βh² on multipliers), so S⁻¹ = D_R⁻¹ S_s⁻¹ D_L⁻¹ is accurate entry by
    // entry even when cond₂(S) is far beyond 1/ε (an SVD of S itself cannot resolve σ_min then).
    AssemblyCoefficients cs = c;
    cs.row_scale = bh2;
    cs.multiplier_scale = 1.0 / bh2;
    check_petsc(system.assemble(local, cs, ConstraintRows::Dynamic, true), "assembly (condition number of S_t)");
    const Eigen::MatrixXd Ss = gather_dense(system.matrix(), out.unknowns, comm);
    // Which PETSc indices are multipliers (each owned by one rank).
    std::vector<int> is_multiplier(static_cast<size_t>(out.unknowns), 0);
    for (int j : sub.multiplier_indices()) is_multiplier[static_cast<size_t>(j)] = 1;
    MPI_Allreduce(MPI_IN_PLACE, is_multiplier.data(), out.unknowns, MPI_INT, MPI_MAX, comm);
    double k = 0.0;
    if (rank == 0) {
      Eigen::VectorXd dl = Eigen::VectorXd::Ones(out.unknowns), dr = Eigen::VectorXd::Ones(out.unknowns);
      if (!scaling)
        for (int i = 0; i < out.unknowns; ++i) {
          if (is_multiplier[static_cast<size_t>(i)]) dr[i] = bh2;
          else dl[i] = 1.0 / bh2;
        }
      const Eigen::MatrixXd S = dl.asDiagonal() * Ss * dr.asDiagonal();
      const Eigen::MatrixXd Sinv = dr.cwiseInverse().asDiagonal() * Ss.fullPivLu().inverse() * dl.cwiseInverse().asDiagonal();
      const double smax = Eigen::BDCSVD<Eigen::MatrixXd>(S).singularValues()(0);
      const double imax = Eigen::BDCSVD<Eigen::MatrixXd>(Sinv).singularValues()(0);
      k = smax * imax;
    }
    MPI_Bcast(&k, 1, MPI_DOUBLE, 0, comm);
    out.two_norm = k;
  }
  if (scaling) {
    c.row_scale = bh2;
    c.multiplier_scale = 1.0 / bh2;
  }
  check_petsc(system.assemble(local, c, ConstraintRows::Dynamic, true), "assembly (condition number of S_t)");
  Vec b = nullptr, x = nullptr;
  check_petsc(VecDuplicate(system.residual(), &b), "VecDuplicate (condition number of S_t)");
  check_petsc(VecDuplicate(system.residual(), &x), "VecDuplicate (condition number of S_t)");
  check_petsc(VecSet(b, 1.0), "VecSet (condition number of S_t)");
  mumps_condition(system.matrix(), b, x, comm, out.mumps_cond1, out.mumps_cond2);
  VecDestroy(&x);
  VecDestroy(&b);
  return out;
}

}  // namespace alphaflex::study
