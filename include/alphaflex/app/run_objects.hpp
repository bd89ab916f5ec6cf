#pragma once
// The objects of a run (`alphaflex run`, `alphaflex modes`) whose destructors are collective
// (PETSc matrices and vectors, MUMPS, the parallel HDF5 file): they live outside the run's body,
// so that after an error they are destroyed only once the ranks know that they all failed.
#include <mpi.h>

#include <exception>
#include <memory>
#include <string>

#include "alphaflex/app/exit_agreement.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/memory.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/integrators/generalized_alpha.hpp"
#include "alphaflex/io/checkpoint.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {

/// The state at the last commit of the results, and where its checkpoint goes: what a run leaves
/// when a later write fails (a full disk; app/simulation.cpp).
struct CommittedState {
  MechanicalState state;      ///< local
  Eigen::VectorXd auxiliary;  ///< local
  RunPosition position;
  std::string checkpoint;     ///< its path (empty: nothing committed yet)
  AlphaParameters parameters;
  double h = 0.0;
  int keep = 1;
  std::string scene_file, outdir;
};

/// Members go in reverse order of destruction.
struct RunObjects {
  /// What the run is doing (for a std::bad_alloc, which says nothing: "out of memory while …").
  const char* phase = "setting up the run";
  CommittedState committed;
  std::unique_ptr<Subdomain> sub;
  std::unique_ptr<SaddlePointSystem> system;
  std::unique_ptr<LinearSolver> solver;
  std::unique_ptr<GeneralizedAlpha> integrator;
  std::unique_ptr<ResultsWriter> writer;
};

/// body(objects): an error one rank only saw ends the job (fail_together) before a collective
/// destructor waits for ranks that are elsewhere; one that every rank saw is rethrown.
template <class Body>
auto run_with_objects(MPI_Comm exit_comm, double exit_timeout, Body body) -> decltype(body(std::declval<RunObjects&>())) {
  RunObjects objects;
  try {
    try {
      return body(objects);
    } catch (const std::bad_alloc&) {
      // An allocation of alphaflex's own that the system refused: a MemoryError (exit 3) saying
      // what was being done, not an internal error.
      int rank = 0;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
      throw MemoryError(out_of_memory_message(objects.phase, 0.0, rank));
    }
  } catch (const std::exception& e) {
    fail_together(exit_comm, exit_code_of(e), e.what(), exit_timeout);
    throw;
  }
}

}  // namespace alphaflex
