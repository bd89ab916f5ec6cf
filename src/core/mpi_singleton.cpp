#include "alphaflex/core/mpi_singleton.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <string>

namespace alphaflex {

namespace {
bool started_by_a_launcher() {
  for (const char* launched : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(launched)) return true;
  return false;
}

// Open MPI's reading of a boolean MCA variable: 0, false, no, f, n (any case) are off, the rest on.
bool switched_on(const char* value) {
  if (!value) return false;
  std::string v(value);
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
  return !(v == "0" || v == "false" || v == "no" || v == "f" || v == "n" || v.empty());
}
}  // namespace

void avoid_singleton_daemon() {
  if (started_by_a_launcher()) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", /*overwrite=*/0);
  // Every isolated singleton is job 1 of job family 0, so all of them on a machine share one
  // session directory, /tmp/ompi.<host>.<uid>/jf.0/1: a process that ends removes it while
  // another one starting creates it, and the second fails in MPI_Init ("A call to mkdir was
  // unable to create the desired directory", session_dir.c). Measured: 6 of 900 starts failed in
  // three concurrent loops, 0 of 2000 without session directories. An isolated singleton has no
  // daemon and no peers, nothing to put there (shared-memory segments go to /dev/shm), so none
  // is made. Not with the daemon (the user set isolated off): orted writes its contact file there.
  if (switched_on(std::getenv("OMPI_MCA_ess_singleton_isolated")))
    setenv("OMPI_MCA_orte_create_session_dirs", "0", /*overwrite=*/0);
}

void prefer_shared_memory_on_one_node() {
  if (std::getenv("OMPI_MCA_pml") || std::getenv("OMPI_MCA_mtl")) return;  // the user's choice
  const char* size = std::getenv("OMPI_COMM_WORLD_SIZE");
  const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
  const bool one_node = size ? (local && std::strcmp(size, local) == 0) : !started_by_a_launcher();
  if (one_node) setenv("OMPI_MCA_pml", "ob1", /*overwrite=*/0);
}

void prepare_mpi_start() {
  avoid_singleton_daemon();
  prefer_shared_memory_on_one_node();
}

}  // namespace alphaflex
