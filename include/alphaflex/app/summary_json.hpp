#pragma once
// OUTDIR/NAME.summary.json: every figure of the summary that `alphaflex run` and `alphaflex modes`
// print, for scripts (python/alphaflex_results.py). The printed summary and the JSON are made from
// the same RunSummary / ModalRunSummary, and the figures the summary derives (mean Newton
// iterations, time shares) come from run_figures() for both, so the two cannot disagree.
#include <string>

#include "alphaflex/app/modal_run.hpp"
#include "alphaflex/app/simulation.hpp"

namespace alphaflex {

/// Figures derived from a RunSummary, as printed.
struct RunFigures {
  double mean_newton = 0.0;      ///< Newton iterations per step
  double other_time = 0.0;       ///< s of wall time outside the named phases
  double us_per_step = 0.0;      ///< µs of wall time per step
  double load_imbalance = 1.0;   ///< largest / mean unknowns per rank
  /// Share (%) of the wall time.
  double percent(double seconds) const { return wall > 0.0 ? 100.0 * seconds / wall : 0.0; }
  double wall = 0.0;
};
RunFigures run_figures(const RunSummary& s);

/// The summary of a run as JSON text (the header's scheme, the scene's and the run's warnings,
/// the final sensor values and the result files included).
std::string summary_json(const Scene& scene, const RunSummary& s);
/// The modes (or Campbell diagram) of `alphaflex modes` as JSON text.
std::string modes_json(const Scene& scene, const ModalRunSummary& s);

/// Writes `text` to OUTDIR/NAME.summary.json (a temporary file renamed into place) and returns the
/// path; throws OutputError naming the file if it cannot be written.
std::string write_summary_json(const std::string& outdir, const std::string& name, const std::string& text);

}  // namespace alphaflex
