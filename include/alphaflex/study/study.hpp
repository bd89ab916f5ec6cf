#pragma once
// `alphaflex study`: runs a scene over step sizes and scheme settings (or model variants), measures
// errors against a named reference, cost (process CPU time, Newton iterations) and stability
// numbers, writes them to a CSV and calls scripts/study_plots.py for the charts (docs/study.md,
// docs/stability.md). Collective over the communicator: the convergence, oscillation, blow_up and
// fidelity modes split the ranks into groups that run different simulations concurrently
// (StudyOptions::ranks_per_run); rank 0 runs the peers (IDA, Radau), writes the files and calls
// the plotting script.
#include <mpi.h>

#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/study/measures.hpp"
#include "alphaflex/study/study_spec.hpp"

namespace alphaflex::study {

struct StudyOptions {
  std::string outdir = ".";
  std::vector<std::string> scene_overrides;  ///< --set: applied to every run, after the setting's solver keys
  bool verbose = true;                       ///< a line per run and the summary on rank 0
  bool plots = true;                         ///< false: never call the plotting script (--no-plots)
  /// Ranks of each simulation of a study (--ranks-per-run): the job's ranks split into groups of
  /// this size that run different simulations at the same time (run_groups.hpp). 0: the default (1
  /// for a scene of at most kSmallSceneUnknowns unknowns, else every rank; fidelity: from the
  /// reference variant's unknowns). It must divide the number of ranks.
  int ranks_per_run = 0;
};

/// One run of a study (a setting at a step size, a model variant, or a peer at a tolerance).
struct StudyRow {
  std::string method = "alphaflex";  ///< "alphaflex", "IDA (GGL index 2)", "SciPy Radau (index 1)"
  std::string label;                 ///< the setting, variant or peer
  AlphaParameters params;            ///< alphaflex rows
  bool scaling = true;
  double h = std::numeric_limits<double>::quiet_NaN();    ///< step size (s), alphaflex rows
  double tol = std::numeric_limits<double>::quiet_NaN();  ///< tolerance, peer rows and adaptive alphaflex rows
  double t_end = 0.0;
  /// fidelity with `study.load`: the load scale of the row's run (NaN without a load axis)
  double load_scale = std::numeric_limits<double>::quiet_NaN();
  bool ok = true;
  std::string failure;               ///< first line of the solver's message when !ok
  long steps = 0, newton_total = 0;
  int newton_max = 0;
  double cpu = 0.0;                  ///< process CPU seconds, summed over the ranks of the run
  double wall = 0.0;
  /// Errors at t_end: "q", "v", "lambda" (∞-norms of the state against the reference run) and
  /// each reported sensor by name; relative to the reference value unless study.errors: absolute.
  std::map<std::string, double> errors;
  /// Mode-specific numbers in output order (oscillation measures, growth factors, condition
  /// numbers, sensor differences).
  std::vector<std::pair<std::string, double>> extra;
  double get(const std::string& key) const;  ///< an error or extra value by name (NaN if absent)
};

/// Strain energy of one flexible part in one model variant (fidelity mode).
struct EnergyRow {
  std::string variant, part, kind;
  int elements = 0;
  double mean = 0.0;        ///< time average of its strain energy (J)
  double peak = 0.0;        ///< largest value (J)
  double share_mean = 0.0;  ///< mean / Σ_parts mean
  double share_peak = 0.0;  ///< its share of the total strain energy when the total peaks
};

struct StudyResult {
  StudySpec spec;
  std::string reference_label;      ///< what the errors are measured against (also in the CSV)
  std::vector<std::string> error_names;  ///< "q", "v", "lambda", then the sensors, in CSV order
  std::vector<StudyRow> rows;       ///< peers on rank 0 only
  std::vector<EnergyRow> energy;
  /// Observed orders: setting label → error name → least-squares slope of log(error) vs log(h).
  std::map<std::string, std::map<std::string, double>> slopes;
  /// The same fits with what they mean (measures.hpp: errors at round-off or at the reference's
  /// accuracy are left out; the slope is NaN when fewer than two remain).
  std::map<std::string, std::map<std::string, SlopeFit>> slope_fits;
  std::vector<std::string> files;   ///< files written (rank 0)
  std::vector<std::string> warnings;
  /// fidelity with study.tolerance: the printed recommendation, the label of the lightest
  /// acceptable variant and of the first rung from which all are acceptable ("" if none)
  std::string recommendation, recommended, acceptable_from;
  /// fidelity with `study.load`, per load scale (increasing): the printed recommendation ("" when
  /// the full rung failed there) and the label of the lightest acceptable rung along the ladder
  /// ("" if none); and the lines saying where that rung changes (load_change_points).
  std::vector<double> load_scales;
  std::vector<std::string> load_recommendations, load_lightest, load_changes;
};

/// Runs the study. Throws InputError for bad input (a setting's overrides, a reference without the
/// study's final time, parameters that fail eq. 17/18/20 without `force: on`) and SolverError
/// when the reference run fails (fidelity: the reference variant, after the CSV is written); a
/// failing study run is a result (status failed), not an error — in mode fidelity also a variant
/// whose scene cannot be built.
StudyResult run_study(const StudySpec& spec, const StudyOptions& options, MPI_Comm comm);

}  // namespace alphaflex::study
