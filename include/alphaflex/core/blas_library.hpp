#pragma once
// The BLAS and LAPACK this process runs on, found at run time. MUMPS' dense kernels (the
// factorization's fronts) call dgemm_/dtrsm_ through Debian's alternatives
// (libblas.so.3-x86_64-linux-gnu), so which implementation runs is a property of the machine, not
// of the build: the run summary names it (docs/performance.md, dense kernels).
#include <string>

namespace alphaflex {

struct BlasLibrary {
  std::string blas;     ///< real path of the object dgemm_ resolves to ("" if no BLAS is loaded)
  std::string lapack;   ///< real path of the object dgetrf_ resolves to
  std::string openblas; ///< OpenBLAS: real path of libopenblas, "" for another BLAS
  std::string config;   ///< OpenBLAS: openblas_get_config() (version, build options)
  std::string kernel;   ///< OpenBLAS: openblas_get_corename(), the kernel chosen for this CPU
  int threads = 0;      ///< OpenBLAS: openblas_get_num_threads()
};

/// Looks the symbols up in the process' global scope (the resolution MUMPS' own calls get) and
/// names the objects that define them.
BlasLibrary loaded_blas();

/// One line: "<blas path>" or "<blas path> -> OpenBLAS 0.3.21 ..., kernel Haswell, 1 thread".
std::string describe(const BlasLibrary& blas);

}  // namespace alphaflex

#include <mpi.h>

namespace alphaflex {

/// Address space OpenBLAS maps for its workspace at the first level-3 call of a thread (its
/// BUFFER_SIZE, 128 MiB on x86-64, measured: 131 MB of VmSize after one 128×128 dgemm) and 4 MiB.
constexpr double kBlasWorkspaceBytes = 132.0 * 1048576.0;

/// Collective over `comm`: makes the BLAS take its workspace now, at the start of a run, while there
/// is room (one small dgemm). OpenBLAS 0.3.21 retries a failed workspace mapping forever: left to
/// MUMPS' first factorization under an address-space limit (ulimit -v) the run would hang there. If
/// the room is not there even now, every rank throws MemoryError (require_address_space).
void reserve_blas_workspace(MPI_Comm comm);

}  // namespace alphaflex
