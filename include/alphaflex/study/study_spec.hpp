#pragma once
// What `alphaflex study` runs: a `study:` map, either in the scene file or in a study file of its
// own (docs/input.md, section "Study files"). Every key is checked like a scene key: an unknown
// key, a wrong type or a bad value raises InputError naming the file, line and key.
#include <map>
#include <string>
#include <vector>

#include "alphaflex/study/fidelity_ladder.hpp"

namespace alphaflex::input {
struct Schema;
}

namespace alphaflex::study {

/// The schemas of the study map (for `alphaflex keys` and docs/input.md).
std::vector<const input::Schema*> schemas();

enum class StudyMode {
  Convergence,  ///< settings × step sizes: work–precision, convergence and cost charts
  Oscillation,  ///< multiplier oscillations (total variation per unit time), e.g. ρ∞ = 1 vs 0.7
  BlowUp,       ///< forced unstable parameters: measured growth per step against the roots of eq. 18, 19
  Fidelity,     ///< the same mechanism with parts rigid or flexible: sensor differences, cost, strain energy
};
const char* mode_name(StudyMode m);

/// One scheme setting: a labelled change of the scene's solver block.
struct SchemeSetting {
  std::string label;
  /// "solver={...}": the scene's solver map with the setting's scheme keys in place of the scene's
  /// (empty: the scene's solver as it is).
  std::string solver_override;
  std::vector<std::string> overrides;  ///< the setting's `set:` list, applied last
  bool force = false;  ///< run it even if eq. 17, 18 or 20 fails (the run's warnings)
  std::string where;   ///< "FILE:LINE: study.settings[LABEL]" for messages
};

/// A model variant of a fidelity study: another scene (or the same) with overrides.
struct ModelVariant {
  std::string label, scene;
  std::vector<std::string> overrides;
  std::string where;
};

struct ReferenceSpec {
  std::string file;    ///< CSV with a header row (after '#' comment lines); columns named like sensors
  std::string source;  ///< where its numbers come from (required with `file`; printed in the output)
  double h = 0.0;      ///< > 0: also a reference run at this step size (state errors in q, v, λ)
  std::string setting; ///< the setting of the reference run (default: the first setting)
};

struct PeerSpec {
  std::string problem;          ///< "andrews" (the only one: the peers' equations are problem-specific)
  std::vector<double> ida;      ///< IDA tolerances (rtol = atol)
  std::vector<double> radau;    ///< SciPy Radau tolerances (rtol = atol)
};

struct StudySpec {
  std::string file;      ///< the file the study map was read from
  std::string scene;     ///< the scene file
  std::string name;      ///< base name of the output files
  StudyMode mode = StudyMode::Convergence;
  std::vector<double> h; ///< step sizes (s)
  /// convergence: tolerances of adaptive runs (solver.tolerance rtol = atol; first step h[0]) of
  /// every setting, beside its fixed steps
  std::vector<double> tol;
  double t_end = 0.0;    ///< final time (s); 0: the scene's
  std::vector<SchemeSetting> settings;
  std::vector<ModelVariant> variants;
  std::string reference_variant;  ///< fidelity: the variant the others are compared with (default: the last)
  /// fidelity: `study.reduce` given: `variants` are its ladder's rungs (fidelity_ladder.hpp), the
  /// reference is the rung `full`
  bool ladder = false;
  ReductionLadder reduce;
  /// fidelity with `reduce`: `study.load` given: the ladder runs once per load scale
  LoadAxis load;
  /// fidelity: the largest acceptable error (max over the sensors, relative to each sensor's range in
  /// the reference run); > 0: the study recommends the lightest variant within it; 0: none given
  double tolerance = 0.0;
  ReferenceSpec reference;
  std::vector<std::string> sensors;  ///< sensors to report (empty: a default per mode)
  std::vector<std::string> overrides;  ///< `set:`: scene overrides for every run, before the settings' own
  bool relative_errors = true;
  /// fidelity, `errors: largest_range`: every sensor's difference over the largest range of the
  /// study's sensors in the reference run (one scale for sensors of one quantity)
  bool largest_range = false;
  bool condition_number = false;     ///< cond(S_t) at the final state of each run
  PeerSpec peers;
  bool plots = true;
  std::string python = "/usr/bin/python3";
  std::string plot_script;  ///< default: scripts/study_plots.py of the source tree
};

/// Reads the study of `scene_path`: from `study_path` if not empty (a file whose top level is one
/// `study:` map), else from the scene's own `study:` block. `study_overrides` are "key.path=value"
/// assignments inside the study map (--study-set), applied before validation. Every rank may call
/// it; it does no MPI.
StudySpec read_study(const std::string& scene_path, const std::string& study_path,
                     const std::vector<std::string>& study_overrides = {});

}  // namespace alphaflex::study
