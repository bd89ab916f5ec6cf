#pragma once
// The fidelity study's ladder (issue 19): one scene expanded into model variants — a block rigid,
// reduced to k modes, or its full nonlinear mesh — as in-memory patches of the scene (the `--set`
// assignments of io/schema.hpp, so a variant is exactly the scene a user gets with those --set
// options); the error of a variant against the full model, sensor by sensor, over the output
// times; and the recommendation of the lightest variant within the study's tolerance
// (docs/study.md, "Rigid, reduced or full").
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace alphaflex::study {

/// `study.reduce`: which blocks of the scene the ladder reduces, and how.
struct ReductionLadder {
  /// The blocks' places in the scene ("beams.0", "shells.2"), in the order the study names them.
  std::vector<std::string> block_paths;
  std::vector<std::string> block_names;
  /// Interface points (named points or joint markers) of each block, in block order.
  std::vector<std::vector<std::string>> interfaces;
  /// Rigid bodies welded into each block (`reduction.bodies`), in block order; empty: none (not written).
  std::vector<std::vector<std::string>> bodies;
  /// Whether the scene itself gives each block a `reduction` (the full rung then removes it); empty: none does.
  std::vector<bool> reduced_in_scene;
  std::string method = "craig_bampton";  ///< craig_bampton | herting: the reduced rungs' method
  /// The reduced rungs' `reduction.geometric_stiffness` (stress stiffening: ½ T[ξ,ξ] + ⅙ Q[ξ,ξ,ξ],
  /// docs/theory/reduced_bodies.md "Geometric stiffness"); never given to the rigid rung.
  bool geometric_stiffness = false;
  /// The reduced rungs' `reduction.static_modes`: "none" (not written) or "inertia".
  std::string static_modes = "none";
  /// The reduced rungs' `reduction.derivatives` (0: not written).
  int derivatives = 0;
  /// The rungs, lightest first: "rigid", a number of modes ("4"), "full" (the reference).
  std::vector<std::string> steps{"rigid", "2", "4", "8", "16", "full"};
};

/// The place of the beam or shell block named `name` in the scene tree ("beams.0", "shells.1"),
/// or "" if the scene has none of that name.
std::string find_block(const YAML::Node& scene_root, const std::string& name);
/// The names of the scene's beam and shell blocks (for "its blocks: ..." in messages).
std::vector<std::string> block_names(const YAML::Node& scene_root);

/// The label of a rung in the CSV and the charts: "rigid", "4 modes", "full".
std::string rung_label(const std::string& step);

/// The scene overrides (key.path=value, as --set takes them) that make rung `step` of the ladder:
/// per block `PATH.reduction={method: rigid, interface: [...]}`, `{method: M, modes: k,
/// interface: [...]}` (+ `geometric_stiffness: on`, `static_modes: inertia` when the ladder asks for
/// them), or nothing at all for "full" (no `reduction` key: the full mesh). This is the contract
/// with the reduced bodies' reader (issue 19, io/types/reduced_beams_3d.cpp).
std::vector<std::string> rung_overrides(const ReductionLadder& ladder, const std::string& step);

/// Error of a variant's sensor history `x` against the full model's `x_full` at the same output
/// times: max_t |x − x_full| divided by the full run's range max_t x_full − min_t x_full
/// (`relative`), or max_t |x − x_full| (not `relative`, or a sensor constant in the full run).
double history_error(const std::vector<double>& x, const std::vector<double>& x_full, bool relative);

/// The range max − min of a history (0 for an empty one).
double history_range(const std::vector<double>& x);

/// Positions in `t` of the full run's output times `t_full` (equal to 1e-9 relative, as output
/// times are matched elsewhere: io/sensor_schedule.cpp). When a full-run time has no match,
/// returns an empty vector and says which in `why`.
std::vector<size_t> matching_times(const std::vector<double>& t, const std::vector<double>& t_full, std::string& why);

/// `study.load`: the load axis of a ladder (issue 19, "where reduction fails"): the whole ladder
/// runs once per load scale, with the keys multiplied by it.
struct LoadAxis {
  /// Places in the scene tree of the numbers to scale ("load.factor", "forces.0.value"), as --set
  /// names them.
  std::vector<std::string> keys;
  /// Their values in the scene (after the study's `set:`): a number or an expression of the
  /// scene's parameters, or a list of them (a vector).
  std::vector<YAML::Node> values;
  std::vector<double> scales;  ///< the factors, increasing
  bool given() const { return !keys.empty(); }
};

/// The assignments (as --set takes them) that multiply every key of `axis` by `scale`: a number
/// becomes the product (17 digits: the same double), an expression e becomes `(e)*scale` (the
/// scene reader evaluates it with the scene's parameters), a list element by element.
std::vector<std::string> load_overrides(const LoadAxis& axis, double scale);

/// One variant as the recommendation sees it.
struct Rung {
  std::string label;
  bool ok = true;      ///< the run succeeded and its error was measured
  double cpu = 0.0;    ///< s
  double error = 0.0;  ///< max over the study's sensors
};

/// The lightest acceptable variant and where along the ladder the acceptable ones start.
struct Recommendation {
  std::vector<bool> acceptable;  ///< per rung: ok and error ≤ tolerance
  int lightest = -1;             ///< the acceptable rung of least CPU time (-1: none)
  /// The first rung from which every rung that ran is acceptable (-1: not even the last).
  int acceptable_from = -1;
  /// The first acceptable rung in the ladder's order, lightest first (-1: none): the load axis's
  /// "lightest acceptable variant", which unlike `lightest` does not depend on measured CPU times
  /// (so that one rank and several agree on it).
  int first_acceptable = -1;
  std::string text;  ///< the printed recommendation
};
/// `measure`: what the error is, for the printed text.
Recommendation recommend(const std::vector<Rung>& rungs, double tolerance,
                         const std::string& measure = "max error over the sensors, relative to each sensor's range in the full run");

/// Where the lightest acceptable variant changes along a load axis: `lightest[i]` is the label of
/// the lightest acceptable rung at load scale `scales[i]` ("" if none is acceptable there). One
/// line per change, "lightest acceptable variant changes from `2 modes` to `full` between load
/// scale 0.003 and 0.01", or one line saying it is the same at every scale.
std::vector<std::string> load_change_points(const std::vector<double>& scales, const std::vector<std::string>& lightest);

}  // namespace alphaflex::study
