// GoogleTest main for the tests that run under mpirun (tests/mpi): PETSc/MPI once, results
// printed by rank 0 only, and the run fails if any rank saw a failure.
#include <gtest/gtest.h>
#include <petscsys.h>

#include "alphaflex/core/mpi_singleton.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  alphaflex::prepare_mpi_start();  // before MPI_Init: no orted when run without mpirun, no network layers on one node
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank != 0) {
    // Other ranks report their failures through the exit code (below), not a second printout.
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    delete listeners.Release(listeners.default_result_printer());
  }
  int result = RUN_ALL_TESTS(), any = 0;
  MPI_Allreduce(&result, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (rank != 0 && result) std::fprintf(stderr, "rank %d: a test failed\n", rank);
  PetscCall(PetscFinalize());
  return any;
}
