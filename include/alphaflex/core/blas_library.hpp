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
