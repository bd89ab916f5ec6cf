#pragma once
// Direct solve of the saddle-point system: KSPPREONLY + PCLU + MATSOLVERMUMPS (the matrix is
// indefinite and, with gyroscopic or damping terms, unsymmetric). The sparsity pattern is fixed,
// so PETSc reuses MUMPS' symbolic analysis and only refactorizes numerically. Every default can be
// overridden from the options database (-ksp_type, -pc_type, -pc_factor_mat_solver_type,
// -mat_mumps_icntl_*, ...).
//
// Small systems on one rank take a dense path instead: LU with partial pivoting (LAPACK) of the
// matrix copied into preallocated dense storage. Below a few hundred unknowns MUMPS' fixed cost
// per call (its driver, ~90 µs per factorization and per solve in MUMPS 5.5 whatever the size:
// docs/performance.md) is far above the O(n³) work; the dense path has no allocation per call.
// It is used on one rank up to -af_dense_lu N unknowns (default kDenseLimit, chosen by
// measurement; 0: never), and never when the options choose a KSP, PC or solver type.
#include <petscksp.h>

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace alphaflex {

/// What the last factorization cost, from MUMPS' own statistics (zero when the options replaced
/// MUMPS by another solver).
struct FactorStatistics {
  bool mumps = false;
  bool dense = false;         ///< the dense path (entries n², flops 2n³/3)
  double flops = 0.0;         ///< RINFOG(3): operations of the elimination
  double entries = 0.0;       ///< INFOG(29): entries in the factors, all ranks
  double memory_max_mb = 0.0; ///< INFOG(21): MB used during the factorization, largest rank
  double memory_sum_mb = 0.0; ///< INFOG(22): the same, summed over the ranks
  /// Block low-rank factorization (MUMPS' BLR, ICNTL(35) = 2, CNTL(7) = the tolerance; Amestoy et
  /// al. 2015, SIAM J. Sci. Comput. 37(3)): 0 when off. With it on, `entries` is still the full-rank
  /// count INFOG(29) and `low_rank_entries` the entries the compressed factors hold, INFOG(35);
  /// `flops` is still the full-rank count RINFOG(3) and `low_rank_flops` the operations the BLR
  /// factorization did, RINFOG(14) (MUMPS 5.5 users' guide; its ICNTL(4) = 2 statistics print both).
  double low_rank_tolerance = 0.0;
  double low_rank_entries = 0.0;
  double low_rank_flops = 0.0;
};

/// MUMPS' estimate, from its analysis, of the memory its factorization takes (0 before an analysis or
/// without MUMPS).
struct FactorEstimate {
  double largest_mb = 0.0;  ///< INFOG(16): MB on the rank that needs the most
  double sum_mb = 0.0;      ///< INFOG(17): MB summed over the ranks
};

class LinearSolver {
 public:
  /// Unknowns up to which one rank factors densely unless -af_dense_lu says otherwise (measured:
  /// docs/performance.md, "small systems": with LAPACK on OpenBLAS the dense path is ahead of MUMPS
  /// up to ~200 unknowns on the sparsest systems, banded beams, and at 153 on the reduced four-bar
  /// 1.65× per step; 150 with Eigen's LU before).
  static constexpr int kDenseLimit = 200;

  /// `low_rank` > 0: MUMPS' block low-rank factorization with that dropping tolerance (CNTL(7),
  /// relative to the norm of each block; solver.linear.low_rank); it implies the MUMPS path.
  explicit LinearSolver(MPI_Comm comm, double low_rank = 0.0);
  ~LinearSolver();
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;

  /// Numerical factorization of A (symbolic analysis only the first time). When MUMPS reports that
  /// its workspace was too small (INFOG(1) = −8, −9, −11, −12, −14, −15, −17, −20: the estimate of
  /// the analysis did not cover the pivoting), the factorization is repeated with ICNTL(14) doubled,
  /// up to 5 times (20 % → 640 % over the estimate), before it is reported as a failure.
  PetscErrorCode factor(Mat A);
  /// x = A⁻¹ b with the last factorization.
  PetscErrorCode solve(Vec b, Vec x);

  /// Empty when the last factor/solve succeeded; otherwise what failed, with MUMPS' INFOG codes.
  const std::string& failure() const { return failure_; }
  /// True if the last failure was MUMPS running out of workspace even after the retries (not a
  /// singular matrix: no diagnosis of the model is due).
  bool workspace_failure() const { return workspace_failure_; }
  /// Factorizations repeated with more MUMPS workspace (ICNTL(14) doubled) after INFOG(1) said the
  /// estimate was too small; and the ICNTL(14) in use now (percent over MUMPS' estimate).
  int workspace_retries() const { return workspace_retries_; }
  int workspace_percent() const { return icntl14_; }
  /// True once the dense path was chosen (at the first factorization).
  bool dense() const { return backend_ == Backend::Dense; }
  /// Number of symbolic analyses and numeric factorizations done so far (0 when the options
  /// replace the LU by an iterative method).
  int symbolic_count() const { return symbolic_; }
  int numeric_count() const { return numeric_; }
  /// MUMPS' statistics of the last successful factorization.
  const FactorStatistics& statistics() const { return stats_; }
  /// Ask every following factorization for the sign of det A (path following: a sign change of
  /// the tangent's determinant marks a limit or bifurcation point). MUMPS computes it during the
  /// factorization with ICNTL(33) = 1 (RINFOG(12)·2^INFOG(34), users' guide 5.5); the dense path
  /// takes it from the LU factors.
  void compute_determinant(bool on) { determinant_ = on; }
  /// Sign of det A of the last factorization (+1, −1), 0 when not asked for or not available
  /// (the options replaced MUMPS by another solver).
  int determinant_sign() const { return det_sign_; }
  /// MUMPS' estimate of the factorization's memory from its last analysis (issue 24: the memory
  /// estimate printed before large runs). Memory exhaustion — MUMPS' INFOG(1) = −5, −7 or −13 (an
  /// allocation the system refused), or a PETSc allocation on the way to MUMPS — is thrown by
  /// factor() as MemoryError on every rank (INFOG is global; a PETSc allocation failing on one
  /// rank only ends the job through the ranks' exit agreement).
  const FactorEstimate& estimate() const { return estimate_; }

 private:
  PetscErrorCode describe_failure(const char* phase);
  PetscErrorCode read_statistics(PC pc);
  PetscErrorCode choose_backend(Mat A);
  PetscErrorCode factor_dense(Mat A);
  PetscErrorCode set_low_rank(PC pc);
  PetscErrorCode set_determinant(PC pc);
  PetscErrorCode read_determinant(PC pc);
  PetscErrorCode read_analysis_estimate(Mat F);
  /// MemoryError for MUMPS' INFOG(1) = −5, −7, −13 in `phase` (analysis, factorization, solve).
  [[noreturn]] void throw_memory_failure(Mat F, PetscInt info1, const char* phase);

  enum class Backend { Undecided, Dense, Krylov } backend_ = Backend::Undecided;
  MPI_Comm comm_;
  Eigen::MatrixXd dense_;              ///< the matrix copied from A, then its LU factors in place (preallocated)
  std::vector<PetscBLASInt> pivots_;  ///< LAPACK's row interchanges (1-based)

  KSP ksp_ = nullptr;
  std::string failure_;
  int symbolic_ = 0, numeric_ = 0;
  PetscObjectState last_state_ = -1;
  FactorStatistics stats_;
  FactorEstimate estimate_;
  bool workspace_failure_ = false;
  int workspace_retries_ = 0, icntl14_ = 0;
  double low_rank_ = 0.0;
  bool low_rank_set_ = false;  ///< ICNTL(35)/CNTL(7) given to the current MUMPS factor
  bool determinant_ = false;
  int det_sign_ = 0;
};

}  // namespace alphaflex
