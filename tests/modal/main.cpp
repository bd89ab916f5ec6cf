#include <gtest/gtest.h>
#include <slepcsys.h>

#include "alphaflex/core/mpi_singleton.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  alphaflex::prepare_mpi_start();  // before MPI_Init: no orted when run without mpirun, no network layers on one node
  PetscCall(SlepcInitialize(&argc, &argv, nullptr, nullptr));
  const int result = RUN_ALL_TESTS();
  PetscCall(SlepcFinalize());
  return result;
}
