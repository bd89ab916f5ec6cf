#include "alphaflex/app/memory_estimate.hpp"

#include <algorithm>
#include <sstream>

#include "alphaflex/core/memory.hpp"

namespace alphaflex {

std::string MemoryEstimate::line() const {
  std::ostringstream os;
  os.precision(4);
  os << "memory estimate: " << total_mb << " MB per rank (matrix " << matrix_mb << " MB, factorization "
     << factorization_mb << " MB from MUMPS' analysis, " << base_mb << " MB before the matrix)";
  return os.str();
}

MemoryEstimate estimate_memory(MPI_Comm comm, double base_mb, const SaddlePointSystem& system, const LinearSolver& solver) {
  MemoryEstimate e;
  const FactorStatistics& st = solver.statistics();
  // The dense path's storage (the matrix copy and its LU) is exact; MUMPS' INFOG(16) is the same on
  // every rank (the largest rank's).
  const double factor_mb = st.dense ? st.memory_max_mb : solver.estimate().largest_mb;
  const MemoryStatus m = memory_status();
  const double mine[3] = {base_mb, system.matrix_megabytes(), base_mb + system.matrix_megabytes() + factor_mb};
  double largest[3] = {0.0, 0.0, 0.0};
  MPI_Allreduce(mine, largest, 3, MPI_DOUBLE, MPI_MAX, comm);
  e.base_mb = largest[0];
  e.matrix_mb = largest[1];
  e.factorization_mb = factor_mb;
  e.total_mb = largest[2];
  e.limit_mb = m.limit_mb;
  // What the ranks of one node still need together against what that node has available: the
  // ranks sharing memory are found by MPI (MPI_COMM_TYPE_SHARED).
  MPI_Comm node;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  double need = std::max(0.0, mine[2] - m.resident_mb), node_need = 0.0;
  MPI_Allreduce(&need, &node_need, 1, MPI_DOUBLE, MPI_SUM, node);
  MPI_Comm_free(&node);
  // Over the node with the least room to spare; every rank gets the same figures.
  double spare = m.available_mb < 0.0 ? 1e300 : m.available_mb - node_need, least = 0.0;
  MPI_Allreduce(&spare, &least, 1, MPI_DOUBLE, MPI_MIN, comm);
  double limit = m.limit_mb < 0.0 ? 1e300 : m.limit_mb, smallest_limit = 0.0;
  MPI_Allreduce(&limit, &smallest_limit, 1, MPI_DOUBLE, MPI_MIN, comm);
  e.available_mb = least >= 1e299 ? -1.0 : least + node_need;
  e.limit_mb = smallest_limit >= 1e299 ? -1.0 : smallest_limit;
  std::ostringstream w;
  w.precision(4);
  if (e.limit_mb >= 0.0 && e.total_mb > e.limit_mb)
    w << "the memory estimate, " << e.total_mb << " MB per rank, exceeds the ranks' address-space limit (ulimit -v) of "
      << e.limit_mb << " MB";
  else if (least < 0.0)
    w << "the memory estimate, " << e.total_mb << " MB per rank, needs " << node_need
      << " MB more on a node that has " << e.available_mb << " MB available (MemAvailable)";
  if (!w.str().empty())
    e.warning = w.str() + ": the run may fail for memory; use more ranks (on more nodes) or a coarser model";
  return e;
}

}  // namespace alphaflex
