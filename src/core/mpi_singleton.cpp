#include "alphaflex/core/mpi_singleton.hpp"

#include <cstdlib>
#include <cstring>
#include <initializer_list>

namespace alphaflex {

namespace {
bool started_by_a_launcher() {
  for (const char* launched : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(launched)) return true;
  return false;
}
}  // namespace

void avoid_singleton_daemon() {
  if (started_by_a_launcher()) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", /*overwrite=*/0);
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
