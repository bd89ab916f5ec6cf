// core/blas_library.hpp: the BLAS the run summary names is the one this process really calls.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "alphaflex/core/blas_library.hpp"
#include "alphaflex/core/mpi_singleton.hpp"

namespace {

// dgemm_ as the process resolves it, called through the pointer the lookup returns: C = A·B for
// 2×2 column-major matrices. A BLAS the test names but the process did not load would fail here.
TEST(BlasLibrary, NamesTheObjectThatComputes) {
  const alphaflex::BlasLibrary b = alphaflex::loaded_blas();
  ASSERT_FALSE(b.blas.empty()) << "PETSc and MUMPS link a BLAS: dgemm_ must resolve";
  EXPECT_TRUE(std::filesystem::path(b.blas).is_absolute());
  EXPECT_TRUE(std::filesystem::exists(b.blas)) << b.blas;
  EXPECT_NE(b.blas.find("blas"), std::string::npos) << b.blas;
  EXPECT_FALSE(b.lapack.empty());

  using dgemm_t = void (*)(const char*, const char*, const int*, const int*, const int*, const double*, const double*,
                           const int*, const double*, const int*, const double*, double*, const int*);
  auto dgemm = reinterpret_cast<dgemm_t>(dlsym(RTLD_DEFAULT, "dgemm_"));
  ASSERT_NE(dgemm, nullptr);
  Dl_info info;
  ASSERT_NE(dladdr(reinterpret_cast<void*>(dgemm), &info), 0);
  EXPECT_EQ(std::filesystem::canonical(info.dli_fname).string(), b.blas);
  const double a[4] = {1, 2, 3, 4}, bm[4] = {5, 6, 7, 8}, one = 1, zero = 0;  // A = [1 3; 2 4], B = [5 7; 6 8]
  double c[4] = {0, 0, 0, 0};
  const int n = 2;
  dgemm("N", "N", &n, &n, &n, &one, a, &n, bm, &n, &zero, c, &n);
  EXPECT_DOUBLE_EQ(c[0], 23);  // 1·5 + 3·6
  EXPECT_DOUBLE_EQ(c[1], 34);  // 2·5 + 4·6
  EXPECT_DOUBLE_EQ(c[2], 31);  // 1·7 + 3·8
  EXPECT_DOUBLE_EQ(c[3], 46);  // 2·7 + 4·8

  const std::string line = alphaflex::describe(b);
  EXPECT_EQ(line.rfind(b.blas, 0), 0u) << line;
  if (!b.openblas.empty()) {  // OpenBLAS: its configuration, kernel and threads are named
    EXPECT_FALSE(b.kernel.empty());
    EXPECT_GE(b.threads, 1);
    EXPECT_NE(line.find("kernel " + b.kernel), std::string::npos) << line;
  }
}

using MpiEnvSettings = std::initializer_list<std::pair<const char*, const char*>>;

// The environment variables a test of the MPI start sets, saved when made and put back when
// destroyed, so that the test's settings never leak into the process's other tests.
class MpiEnvironmentSandbox {
 public:
  explicit MpiEnvironmentSandbox(std::vector<std::string> keys) : keys_(std::move(keys)) {
    for (const auto& k : keys_) {
      const char* v = std::getenv(k.c_str());
      saved_.emplace_back(v != nullptr, v ? v : "");
    }
  }
  ~MpiEnvironmentSandbox() {
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (saved_[i].first) setenv(keys_[i].c_str(), saved_[i].second.c_str(), 1);
      else unsetenv(keys_[i].c_str());
  }
  MpiEnvironmentSandbox(const MpiEnvironmentSandbox&) = delete;
  MpiEnvironmentSandbox& operator=(const MpiEnvironmentSandbox&) = delete;

  /// Every key unset, then only these set, then `start` (the function under test) called: what
  /// it left in `key`, or "(unset)".
  std::string after(MpiEnvSettings set, void (*start)(), const char* key) const {
    for (const auto& k : keys_) unsetenv(k.c_str());
    for (const auto& [k, v] : set) setenv(k, v, 1);
    start();
    const char* v = std::getenv(key);
    return v ? v : "(unset)";
  }

 private:
  std::vector<std::string> keys_;
  std::vector<std::pair<bool, std::string>> saved_;
};

/// What avoid_singleton_daemon reads and writes: its two settings and the launchers' markers.
std::vector<std::string> singleton_variables() {
  return {"OMPI_MCA_ess_singleton_isolated", "OMPI_MCA_orte_create_session_dirs", "OMPI_COMM_WORLD_SIZE",
          "PMIX_RANK", "PMI_RANK", "PMI_SIZE"};
}

// The daemon-free singleton is asked for only when no launcher started the process, and never
// over the user's own setting.
TEST(MpiSingleton, OnlyWithoutALauncherAndNotOverTheUser) {
  MpiEnvironmentSandbox env(singleton_variables());
  auto isolated = [&](MpiEnvSettings set) {
    return env.after(set, alphaflex::avoid_singleton_daemon, "OMPI_MCA_ess_singleton_isolated");
  };
  EXPECT_EQ(isolated({}), "1") << "a singleton started by hand";
  EXPECT_EQ(isolated({{"OMPI_COMM_WORLD_SIZE", "2"}}), "(unset)") << "set under mpirun";
  EXPECT_EQ(isolated({{"PMIX_RANK", "0"}}), "(unset)") << "set under a PMIx launcher";
  EXPECT_EQ(isolated({{"PMI_SIZE", "2"}}), "(unset)") << "set under a PMI launcher";
  EXPECT_EQ(isolated({{"OMPI_MCA_ess_singleton_isolated", "0"}}), "0") << "the user's setting must win";
}

// An isolated singleton makes no session directory: every one of them is job 1 of job family 0,
// and concurrent runs raced on /tmp/ompi.<host>.<uid>/jf.0/1 (a CI run failed in MPI_Init on it).
// With the daemon (isolated off by the user) the directory stays, since orted needs it; under a
// launcher, or over the user's own setting, nothing is touched.
TEST(MpiSingleton, IsolatedSingletonsMakeNoSharedSessionDirectory) {
  MpiEnvironmentSandbox env(singleton_variables());
  auto session_dirs = [&](MpiEnvSettings set) {
    return env.after(set, alphaflex::avoid_singleton_daemon, "OMPI_MCA_orte_create_session_dirs");
  };
  EXPECT_EQ(session_dirs({}), "0") << "a singleton started by hand";
  EXPECT_EQ(session_dirs({{"OMPI_MCA_ess_singleton_isolated", "true"}}), "0");
  EXPECT_EQ(session_dirs({{"OMPI_MCA_ess_singleton_isolated", "0"}}), "(unset)") << "orted needs the directory";
  EXPECT_EQ(session_dirs({{"OMPI_MCA_ess_singleton_isolated", "False"}}), "(unset)");
  EXPECT_EQ(session_dirs({{"OMPI_COMM_WORLD_SIZE", "2"}}), "(unset)") << "mpirun's ranks keep theirs";
  EXPECT_EQ(session_dirs({{"PMIX_RANK", "0"}}), "(unset)");
  EXPECT_EQ(session_dirs({{"OMPI_MCA_orte_create_session_dirs", "1"}}), "1") << "the user's setting must win";
}

// Shared memory (ob1) is asked for only when every rank is on this node and the user chose no PML
// or MTL; on several nodes, under a launcher without Open MPI's variables (srun), or over the
// user's choice nothing is set.
TEST(MpiStart, SharedMemoryOnlyOnOneNodeAndNotOverTheUser) {
  MpiEnvironmentSandbox sandbox({"OMPI_MCA_pml", "OMPI_MCA_mtl", "OMPI_COMM_WORLD_SIZE",
                                 "OMPI_COMM_WORLD_LOCAL_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"});
  auto env = [&](MpiEnvSettings set) {
    return sandbox.after(set, alphaflex::prefer_shared_memory_on_one_node, "OMPI_MCA_pml");
  };
  EXPECT_EQ(env({}), "ob1") << "a singleton is one node";
  EXPECT_EQ(env({{"OMPI_COMM_WORLD_SIZE", "2"}, {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"}, {"PMIX_RANK", "0"}}), "ob1");
  EXPECT_EQ(env({{"OMPI_COMM_WORLD_SIZE", "4"}, {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"}, {"PMIX_RANK", "0"}}), "(unset)")
      << "ranks on two nodes need the network";
  EXPECT_EQ(env({{"OMPI_COMM_WORLD_SIZE", "2"}, {"PMIX_RANK", "0"}}), "(unset)") << "no local size: not known to be one node";
  EXPECT_EQ(env({{"PMIX_RANK", "0"}}), "(unset)") << "a launcher without Open MPI's variables";
  EXPECT_EQ(env({{"PMI_SIZE", "2"}}), "(unset)");
  EXPECT_EQ(env({{"OMPI_COMM_WORLD_SIZE", "2"}, {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"}, {"OMPI_MCA_pml", "ucx"}}), "ucx")
      << "the user's PML must win";
  EXPECT_EQ(env({{"OMPI_COMM_WORLD_SIZE", "2"}, {"OMPI_COMM_WORLD_LOCAL_SIZE", "2"}, {"OMPI_MCA_mtl", "psm2"}}), "(unset)")
      << "the user's MTL must win";
  EXPECT_EQ(env({{"OMPI_MCA_mtl", "ofi"}}), "(unset)");
}

}  // namespace
