#include "alphaflex/core/mpi_singleton.hpp"

#include <cstdlib>
#include <initializer_list>

namespace alphaflex {

void avoid_singleton_daemon() {
  for (const char* launched : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(launched)) return;
  setenv("OMPI_MCA_ess_singleton_isolated", "1", /*overwrite=*/0);
}

}  // namespace alphaflex
