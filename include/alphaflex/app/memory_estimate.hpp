#pragma once
// The memory a run needs per rank, estimated once MUMPS has analysed the iteration matrix (issue 24,
// defect 3): what the rank held before the matrix (libraries, the scene's model, the subdomain),
// the matrix as preallocated, and MUMPS' own estimate of its factorization (INFOG(16)). Printed
// before the steps of large models, compared with what the machine and the process' limit leave,
// and kept in NAME.summary.json; docs/running.md ("Memory exhaustion") measures it against the peak.
#include <mpi.h>

#include <string>

#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {

struct MemoryEstimate {
  double base_mb = 0.0;           ///< resident before the matrix, largest rank
  double matrix_mb = 0.0;         ///< the iteration matrix and its entry maps, largest rank
  double factorization_mb = 0.0;  ///< MUMPS' analysis, INFOG(16) (largest rank); dense path: its n² storage
  double total_mb = 0.0;          ///< per rank: the largest rank's sum
  double limit_mb = -1.0;         ///< RLIMIT_AS of the rank (−1: none)
  double available_mb = -1.0;     ///< MemAvailable of the node with the most need
  /// Non-empty when the estimate exceeds the limit or what the node has available.
  std::string warning;
  bool known() const { return total_mb > 0.0; }
  /// "memory estimate: 340 MB per rank (matrix 45 MB, factorization 110 MB from MUMPS' analysis, 185 MB before the matrix)"
  std::string line() const;
};

/// Models from this many unknowns on print their estimate before the steps (below it a run takes
/// ~200 MB per rank, mostly libraries).
constexpr long kMemoryEstimateUnknowns = 20000;

/// Collective over `comm`. `base_mb`: this rank's resident memory before the matrix was made.
MemoryEstimate estimate_memory(MPI_Comm comm, double base_mb, const SaddlePointSystem& system, const LinearSolver& solver);

}  // namespace alphaflex
