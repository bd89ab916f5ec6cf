#pragma once
// `alphaflex modes`: the modes of a scene linearized about its initial state (after the consistent
// start), its static equilibrium (solver.analysis: static or solver.initial_static) or a checkpoint
// of a dynamic run (docs/modes.md). Writes OUTDIR/NAME_modes.csv and the animated mode shapes
// (OUTDIR/NAME_modeshapes.h5/.xdmf through the results writer). With modes.rotating_frame the
// linearization is taken in the frame turning with a joint's body; with modes.campbell, the modes
// about the steady rotation at each of a list of speeds (OUTDIR/NAME_campbell.csv).
#include <mpi.h>

#include <string>
#include <vector>

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
  /// The reference frame: empty (inertial) or "frame turning with joint J at |Ω| = ... rad/s".
  std::string frame;
  /// modes.campbell: the speeds (rad/s) and the modes about the steady rotation at each (rotating
  /// frame); `result` is then the last speed's. campbell_csv: OUTDIR/NAME_campbell.csv.
  std::vector<double> campbell_speeds;
  std::vector<ModalResult> campbell;
  std::string campbell_csv, campbell_chart;  ///< the chart: scripts/campbell_plot.py (rank 0)
};

/// Collective; throws InputError / SolverError on every rank alike.
ModalRunSummary run_modes(Scene& scene, const ModalRunOptions& options, MPI_Comm comm);

/// The table printed by `alphaflex modes`.
std::string format_modes(const Scene& scene, const ModalRunSummary& s);

}  // namespace alphaflex
