#pragma once
// `alphaflex modes`: the modes of a scene linearized about its initial state (after the consistent
// start), its static equilibrium (solver.analysis: static or solver.initial_static) or a checkpoint
// of a dynamic run (docs/modes.md). Writes OUTDIR/NAME_modes.csv and the animated mode shapes
// (OUTDIR/NAME_modeshapes.h5/.xdmf through the results writer).
#include <mpi.h>

#include <string>

#include "alphaflex/io/scene.hpp"
#include "alphaflex/modal/modal_analysis.hpp"

namespace alphaflex {

struct ModalRunOptions {
  std::string outdir = ".";
  bool write_results = true;
  std::string restart;  ///< a checkpoint of a dynamic run: its state is linearized about
  ModalOptions modes;
  MPI_Comm exit_comm = MPI_COMM_NULL;  ///< as RunOptions::exit_comm
  double exit_timeout = 5.0;
  int phases = 8;   ///< animation frames per mode (one period)
};

struct ModalRunSummary {
  std::string state;   ///< "initial", "static equilibrium", "checkpoint at t = ... s"
  double time = 0.0, load_factor = 1.0;
  int ranks = 1, unknowns = 0, coordinates = 0, multipliers = 0;
  ModalResult result;  ///< shapes on this rank's subdomain
  double wall = 0.0, solve_wall = 0.0;
  std::string csv, h5, xdmf;
};

/// Collective; throws InputError / SolverError on every rank alike.
ModalRunSummary run_modes(Scene& scene, const ModalRunOptions& options, MPI_Comm comm);

/// The table printed by `alphaflex modes`.
std::string format_modes(const Scene& scene, const ModalRunSummary& s);

}  // namespace alphaflex
