// GoogleTest main that brings up PETSc/MPI once for all unit tests.
#include <gtest/gtest.h>
#include <petscsys.h>

#include <cstdlib>

#include "alphaflex/core/mpi_singleton.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  // The reader's tests read every mesh with gmsh: no cached meshes (mesh/mesh_cache.hpp), which
  // tests/unit/test_mesh_cache.cpp turns on in a directory of its own.
  ::setenv("ALPHAFLEX_MESH_CACHE", "off", 1);
  alphaflex::prepare_mpi_start();  // before MPI_Init: no orted when run without mpirun, no network layers on one node
  PetscCall(PetscInitialize(&argc, &argv, nullptr, nullptr));
  const int result = RUN_ALL_TESTS();
  PetscCall(PetscFinalize());
  return result;
}
