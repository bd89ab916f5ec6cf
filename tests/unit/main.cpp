// GoogleTest main that brings up PETSc/MPI once for all unit tests.
#include <gtest/gtest.h>
#include <petscsys.h>

#include "alphaflex/core/mpi_singleton.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  alphaflex::prepare_mpi_start();  // before MPI_Init: no orted when run without mpirun, no network layers on one node
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  const int result = RUN_ALL_TESTS();
  PetscCall(PetscFinalize());
  return result;
}
