#include "alphaflex/core/blas_library.hpp"

#include <dlfcn.h>
#include <limits.h>
#include <stdlib.h>

#include <string>
#include <vector>

#include "alphaflex/core/memory.hpp"


namespace alphaflex {

namespace {

// The object that defines `symbol` in the global scope, by its real path: Debian's
// /usr/lib/x86_64-linux-gnu/libblas.so.3 is a symbolic link through /etc/alternatives, and the
// path at its end names the implementation (blas/, openblas-serial/, openblas-pthread/, ...).
std::string defining_object(void* address) {
  Dl_info info;
  if (!address || !dladdr(address, &info) || !info.dli_fname) return "";
  char resolved[PATH_MAX];
  return realpath(info.dli_fname, resolved) ? std::string(resolved) : std::string(info.dli_fname);
}

}  // namespace

BlasLibrary loaded_blas() {
  BlasLibrary b;
  b.blas = defining_object(dlsym(RTLD_DEFAULT, "dgemm_"));
  b.lapack = defining_object(dlsym(RTLD_DEFAULT, "dgetrf_"));
  // OpenBLAS' own queries: present only when OpenBLAS is loaded (Debian's openblas libblas.so.3
  // forwards to libopenblas.so.0, which defines them).
  using text_query = char* (*)();
  using int_query = int (*)();
  void* config = dlsym(RTLD_DEFAULT, "openblas_get_config");
  if (config) {
    b.openblas = defining_object(config);
    if (const char* c = reinterpret_cast<text_query>(config)()) b.config = c;
    if (void* core = dlsym(RTLD_DEFAULT, "openblas_get_corename"))
      if (const char* c = reinterpret_cast<text_query>(core)()) b.kernel = c;
    if (void* n = dlsym(RTLD_DEFAULT, "openblas_get_num_threads")) b.threads = reinterpret_cast<int_query>(n)();
  }
  return b;
}

std::string describe(const BlasLibrary& b) {
  std::string s = b.blas.empty() ? std::string("none loaded") : b.blas;
  if (!b.openblas.empty()) {
    s += " -> " + (b.config.empty() ? b.openblas : b.config);
    if (!b.kernel.empty()) s += ", kernel " + b.kernel;
    s += ", " + std::to_string(b.threads) + (b.threads == 1 ? " thread" : " threads");
  }
  if (!b.lapack.empty() && b.lapack != b.blas) s += "; LAPACK " + b.lapack;
  return s;
}

void reserve_blas_workspace(MPI_Comm comm) {
  static bool reserved = false;  // once per process (OpenBLAS keeps its workspace)
  int done = reserved ? 1 : 0, all = 0;
  MPI_Allreduce(&done, &all, 1, MPI_INT, MPI_MIN, comm);
  if (all) return;
  require_address_space(comm, kBlasWorkspaceBytes, "the BLAS library (OpenBLAS) took its workspace for MUMPS' dense kernels");
  // 128×128: above OpenBLAS' small-matrix path, so the call goes through its workspace.
  // Looked up as MUMPS' calls resolve it (the executable does not link the BLAS itself).
  using gemm = void (*)(const char*, const char*, const int*, const int*, const int*, const double*, const double*,
                        const int*, const double*, const int*, const double*, double*, const int*);
  void* f = dlsym(RTLD_DEFAULT, "dgemm_");
  if (!f) return;  // no BLAS in the process: nothing to reserve
  const int n = 128;
  const double one = 1.0, zero = 0.0;
  std::vector<double> a(static_cast<size_t>(n * n), 0.0), c(static_cast<size_t>(n * n), 0.0);
  reinterpret_cast<gemm>(f)("N", "N", &n, &n, &n, &one, a.data(), &n, a.data(), &n, &zero, c.data(), &n);
  reserved = true;
}

}  // namespace alphaflex
