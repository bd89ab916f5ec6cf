#include "alphaflex/study/study_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/expression.hpp"
#include "alphaflex/io/schema.hpp"

namespace alphaflex::study {

const char* mode_name(StudyMode m) {
  switch (m) {
    case StudyMode::Convergence: return "convergence";
    case StudyMode::Oscillation: return "oscillation";
    case StudyMode::BlowUp: return "blow_up";
    case StudyMode::Fidelity: return "fidelity";
  }
  return "?";
}

namespace {

namespace fs = std::filesystem;

using input::Key;
using input::KeyType;
using input::kRequired;
using input::Range;
using input::Reader;
using input::Schema;
using input::Section;

// The study map's schemas (docs/input.md, "Study files": generated tables).
const Schema kStudy{"study", {
    {"name", KeyType::Text, "–", "scene name + `_` + mode", "base name of the output files; no spaces or slashes"},
    {"mode", KeyType::Choice, "–", "`convergence`",
     "`convergence` (work–precision, convergence, cost), `oscillation` (multiplier oscillations), `blow_up` (forced unstable parameters), `fidelity` (model variants)",
     {}, "", "", {"convergence", "oscillation", "blow_up", "fidelity"}},
    {"h", KeyType::Numbers, "s", "**required** (one value for `fidelity`, default there: each scene's)", "step sizes; every run takes `solver.h` from here", Range::positive(), "step size (s)", "number or list"},
    {"tol", KeyType::Numbers, "–", "none", "`convergence`: tolerances of adaptive runs (`solver.tolerance` rtol = atol = tol, first step the first `h`) of every setting, beside its fixed step sizes; rows labelled `LABEL adaptive`", Range::positive(), "tolerance", "number or list"},
    {"t_end", KeyType::Number, "s", "the scene's `solver.t_end`", "final time of every run; the errors are measured there", Range::positive(), "final time (s)"},
    {"settings", KeyType::List, "–", "one setting: the scene's solver", "scheme settings (`study.settings`); labels unique; `fidelity` takes one"},
    {"reference", KeyType::Map, "–", "none (**required** for `convergence`)", "what the errors are measured against (`study.reference`)"},
    {"sensors", KeyType::Texts, "–", "every sensor with a reference value (`convergence`), every sensor (otherwise)", "the sensors to report; each must exist in the scene", {}, "", "list of names"},
    {"set", KeyType::Texts, "–", "none", "scene overrides `key=value` applied to every run (after the setting's solver keys, before the command line's `--set`)", {}, "", "list of `key=value`"},
    {"errors", KeyType::Choice, "–", "`relative`", "`relative`: |x − x_ref| / |x_ref| (absolute if x_ref = 0; `fidelity`: max over t of |x − x_ref| / the sensor's range in the reference run); `absolute`; `largest_range` (`fidelity` only): max over t of |x − x_ref| / the largest range of the study's sensors in the reference run, for sensors of one quantity (the components of a displacement: the error relative to the size of the motion)", {}, "", "", {"relative", "absolute", "largest_range"}},
    {"condition_number", KeyType::Flag, "–", "off", "`convergence`: the condition numbers of S_t at the last state of each run"},
    {"peers", KeyType::Map, "–", "none", "`convergence` only: other solvers on the same problem (`study.peers`)"},
    {"variants", KeyType::List, "–", "**required** for `fidelity` without `reduce` (at least 2)", "model variants (`study.variants`)"},
    {"reference_variant", KeyType::Text, "–", "the last variant", "`fidelity` with `variants`: the label of the variant the others are compared with"},
    {"reduce", KeyType::Map, "–", "none", "`fidelity`: the ladder rigid → reduced → full mesh of blocks of the scene, built from the one scene (`study.reduce`); not with `variants`"},
    {"load", KeyType::Map, "–", "none", "`fidelity` with `reduce`: the load axis (`study.load`): the whole ladder runs once per load scale, errors against that scale's `full` rung, and the study prints where the lightest acceptable rung changes"},
    {"tolerance", KeyType::Number, "–", "none (**required** with `reduce`)", "`fidelity`: the largest acceptable error of a variant (max over the sensors of max over the output times of |variant − reference| / the sensor's range in the reference run, or as `errors` says); the study recommends the variant of least CPU time within it", Range::positive(), "tolerance"},
    {"plots", KeyType::Flag, "–", "on", "call the plotting script after writing the CSVs"},
    {"python", KeyType::Text, "–", "`/usr/bin/python3`", "interpreter for the plotting script and the Radau peer"},
    {"plot_script", KeyType::Text, "–", "`scripts/study_plots.py` of the source tree", "relative to the study file"}}};
const Schema kSetting{"study.settings", {
    {"label", KeyType::Text, "–", kRequired, "the name in the CSV and the legends; unique; no commas or quotes"},
    {"scheme", KeyType::Text, "–", "the scene's", "as `solver.scheme`; if any scheme key is given, they replace all of the scene's scheme keys"},
    {"rho_inf", KeyType::Number, "–", "the scene's", "as `solver.rho_inf`"},
    {"alpha_m", KeyType::Number, "–", "the scene's", "as `solver.alpha_m`"},
    {"alpha_f", KeyType::Number, "–", "the scene's", "as `solver.alpha_f`"},
    {"beta", KeyType::Number, "–", "the scene's", "as `solver.beta`"},
    {"gamma", KeyType::Number, "–", "the scene's", "as `solver.gamma`"},
    {"scaling", KeyType::Flag, "–", "the scene's", "`solver.scaling`"},
    {"newton", KeyType::Map, "–", "the scene's", "merged into `solver.newton`"},
    {"set", KeyType::Texts, "–", "none", "further scene overrides `key=value`, applied after the study's `set` and the command line's `--set`", {}, "", "list of `key=value`"},
    {"force", KeyType::Flag, "–", "off", "run the setting even if its parameters fail eq. 17, 18 or 20 (a study refuses them otherwise)"}}};
const Schema kReference{"study.reference", {
    {"file", KeyType::Text, "–", "none", "a CSV of reference values (columns named like the sensors, and `t` in s), relative to the study file"},
    {"source", KeyType::Text, "–", "**required** with `file`", "where the reference values come from (method, tolerance, script)"},
    {"h", KeyType::Number, "s", "none", "step size of a reference run with the same scene; smaller than every study step size", Range::positive(), "step size of the reference run (s)"},
    {"setting", KeyType::Text, "–", "the first setting", "the label of the setting the reference run uses"}}};
const Schema kPeers{"study.peers", {
    {"problem", KeyType::Choice, "–", kRequired, "the problem the peers solve (the test set's equations)", {}, "", "", {"andrews"}},
    {"ida", KeyType::Numbers, "–", "none", "SUNDIALS IDA runs, one per tolerance (rtol = atol)", Range::positive(), "tolerance", "list of tolerances"},
    {"radau", KeyType::Numbers, "–", "none", "SciPy Radau runs, one per tolerance (rtol = atol)", Range::positive(), "tolerance", "list of tolerances"}}};
const Schema kVariant{"study.variants", {
    {"label", KeyType::Text, "–", kRequired, "the name in the CSV; unique; no commas or quotes"},
    {"scene", KeyType::Text, "–", "the scene on the command line", "a scene file, relative to the study file"},
    {"set", KeyType::Texts, "–", "none", "scene overrides `key=value`", {}, "", "list of `key=value`"}}};
const Schema kReduce{"study.reduce", {
    {"blocks", KeyType::List, "–", kRequired, "the beam or shell blocks of the scene (`beams[NAME]`, `shells[NAME]`) each rung reduces: names, or maps `{name: NAME, interface: [...]}`", {}, "", "list of names or maps"},
    {"interface", KeyType::Texts, "–", "**required** unless every block gives its own", "the interface points of the blocks (named points of the mesh, joint markers) where joints attach; for every block that gives none", {}, "", "list of names"},
    {"method", KeyType::Choice, "–", "`craig_bampton`", "the reduction of the rungs with k modes (`reduction.method` of the block)", {}, "", "", {"craig_bampton", "herting"}},
    {"geometric_stiffness", KeyType::Flag, "–", "off", "on: every reduced rung's blocks get `reduction.geometric_stiffness: on` (stress stiffening, the cubic and quartic terms of the block's own beam energy; docs/theory/reduced_bodies.md \"Geometric stiffness\"); not given to `rigid`"},
    {"static_modes", KeyType::Choice, "–", "`none`", "`inertia`: every reduced rung's blocks get `reduction.static_modes: inertia` (up to 12 static responses to the body-frame inertia loads appended to the k modes); not given to `rigid`", {}, "", "", {"none", "inertia"}},
    {"derivatives", KeyType::Integer, "–", "0", "with `geometric_stiffness: on`: every reduced rung's blocks get `reduction.derivatives: N` (the static modal derivatives of the first N basis vectors, against membrane locking; docs/theory/reduced_bodies.md \"Modal derivatives\"); not given to `rigid`", Range::non_negative()},
    {"ladder", KeyType::List, "–", "`[rigid, 2, 4, 8, 16, full]`", "the rungs, lightest first: `rigid` (each block one rigid body), a number of modes k (1 to 10000), `full` (the blocks' full nonlinear mesh, the reference; required)", {}, "", "list"}}};
const Schema kReduceBlock{"study.reduce.blocks", {
    {"name", KeyType::Text, "–", kRequired, "a beam or shell block of the scene"},
    {"interface", KeyType::Texts, "–", "`study.reduce.interface`", "this block's interface points", {}, "", "list of names"},
    {"bodies", KeyType::Texts, "–", "none", "rigid bodies of the scene welded to this block that every reduced rung takes into it (`reduction.bodies`: each welded by one `fixed` joint to a named point of the block)", {}, "", "list of names"}}};
const Schema kLoad{"study.load", {
    {"keys", KeyType::Texts, "–", kRequired, "the scene's numbers to scale, as `--set` names them (`load.factor`, `forces.0.value`): each a number, an expression of the scene's `parameters` or a list of them (a vector)", {}, "", "list of key paths"},
    {"scale", KeyType::Numbers, "–", kRequired, "the load scales, increasing: every rung runs with each key multiplied by each scale", Range::positive(), "load scale", "number or list"}}};
const Schema kStudyFile{"study.file", {{"study", KeyType::Map, "–", kRequired, "the study map"}}};

/// A non-empty string (labels, names, paths).
std::string nonempty_text(const Reader& rd, const YAML::Node& n, const std::string& key) {
  if (!n.IsScalar() || n.Scalar().empty()) rd.fail(n, key, "expected a non-empty string");
  return rd.text(n, key);
}
/// Opens item i of the list `list` ("study.settings"): a map `{shape}` with a unique label (no
/// commas, quotes or newlines: it is a CSV field); sets `key` to "LIST[LABEL]" for later messages.
std::string labelled_item(const Reader& rd, const YAML::Node& n, const std::string& list, size_t i, const char* shape,
                          const char* missing, const char* what, std::set<std::string>& labels, std::string& key) {
  key = list + "[" + std::to_string(i) + "]";
  if (!n.IsMap()) rd.fail(n, key, std::string("expected a map ") + shape);
  if (!n["label"]) rd.fail(n, key + ".label", missing);
  const std::string label = nonempty_text(rd, n["label"], key + ".label");
  key = list + "[" + label + "]";
  if (label.find_first_of(",\"\n") != std::string::npos)
    rd.fail(n["label"], key + ".label", "a label may not contain commas, quotes or newlines (it is a CSV field)");
  if (!labels.insert(label).second) rd.fail(n["label"], key + ".label", std::string("another ") + what + " has this label");
  return label;
}

/// `set:` entries: "key.path=value" strings, as --set takes them.
std::vector<std::string> assignments(const Reader& rd, const Section& section, const std::string& key) {
  std::vector<std::string> v = section.texts(key);
  const YAML::Node n = section.node(key);
  for (size_t i = 0; i < v.size(); ++i)
    if (v[i].find('=') == std::string::npos || v[i].front() == '=')
      rd.fail(n.IsSequence() ? n[i] : n, section.key_path(key), "expected key.path=value (as for --set), got '" + v[i] + "'");
  return v;
}
/// A path relative to the directory of the file being read.
std::string file_path(const Reader& rd, const YAML::Node& n, const std::string& key) {
  fs::path p = nonempty_text(rd, n, key);
  if (p.is_relative()) p = fs::path(rd.file()).parent_path() / p;
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) rd.fail(n, key, "no such file: " + p.string());
  return p.lexically_normal().string();
}

const char* kSchemeKeys[] = {"scheme", "rho_inf", "alpha_m", "alpha_f", "beta", "gamma"};

// The scene's solver map with the setting's scheme keys in place of the scene's, as one --set.
std::string solver_override(const YAML::Node& scene_solver, const YAML::Node& setting) {
  bool scheme_given = false, any = false;
  for (const char* k : kSchemeKeys) scheme_given = scheme_given || setting[k];
  any = scheme_given || setting["scaling"] || setting["newton"];
  if (!any) return "";
  YAML::Node solver = scene_solver && scene_solver.IsMap() ? YAML::Clone(scene_solver) : YAML::Node(YAML::NodeType::Map);
  if (scheme_given)
    for (const char* k : kSchemeKeys) solver.remove(k);
  for (const char* k : kSchemeKeys)
    if (setting[k]) solver[k] = YAML::Clone(setting[k]);
  if (setting["scaling"]) solver["scaling"] = YAML::Clone(setting["scaling"]);
  if (const YAML::Node n = setting["newton"]) {
    if (!solver["newton"] || !solver["newton"].IsMap()) solver["newton"] = YAML::Node(YAML::NodeType::Map);
    for (const auto& kv : n) solver["newton"][kv.first.Scalar()] = YAML::Clone(kv.second);  // names checked by Reader::key_name
  }
  YAML::Emitter out;
  out << YAML::Flow << solver;
  return std::string("solver=") + out.c_str();
}

/// `study.reduce`: the blocks (each found in the scene file, with its interface), the method and the
/// rungs, expanded into the fidelity study's variants (fidelity_ladder.hpp).
void read_ladder(const Reader& rd, const YAML::Node& r, const YAML::Node& scene_root, StudySpec& spec) {
  const Section reduce(rd, r, "study.reduce", kReduce);
  ReductionLadder& l = spec.reduce;
  l.method = kReduce.find("method")->choices[static_cast<size_t>(reduce.choice("method"))];
  l.geometric_stiffness = reduce.flag("geometric_stiffness", false);
  l.static_modes = kReduce.find("static_modes")->choices[static_cast<size_t>(reduce.choice("static_modes", 0))];
  l.derivatives = reduce.integer("derivatives", 0);
  if (l.derivatives > 0 && !l.geometric_stiffness)
    rd.fail(reduce.node("derivatives"), "study.reduce.derivatives", "needs `geometric_stiffness: on` (the derivatives are the basis of its quadratic energy)");
  std::vector<std::string> common;
  if (reduce.has("interface")) common = reduce.texts("interface");
  const YAML::Node blocks = reduce.node("blocks");
  if (!blocks.IsSequence() || blocks.size() == 0)
    rd.fail(blocks, "study.reduce.blocks", "expected a non-empty list of block names (or {name, interface} maps)");
  for (size_t i = 0; i < blocks.size(); ++i) {
    const YAML::Node b = blocks[i];
    std::string key = "study.reduce.blocks[" + std::to_string(i) + "]", name;
    std::vector<std::string> interface = common, welded;
    bool own = false;
    if (b.IsMap()) {
      const Section block(rd, b, key, kReduceBlock);
      name = nonempty_text(rd, block.node("name"), key + ".name");
      if (block.has("interface")) interface = block.texts("interface"), own = true;
      if (block.has("bodies")) welded = block.texts("bodies");
    } else {
      name = nonempty_text(rd, b, key);
    }
    const std::string path = find_block(scene_root, name);
    if (path.empty()) {
      std::string known;
      for (const auto& n : block_names(scene_root)) known += (known.empty() ? "" : ", ") + n;
      rd.fail(b, key, "the scene " + spec.scene + " has no beam or shell block named '" + name + "' (its blocks: " +
                          (known.empty() ? std::string("none") : known) + ")");
    }
    if (std::count(l.block_names.begin(), l.block_names.end(), name)) rd.fail(b, key, "block '" + name + "' is named twice");
    if (!own && !reduce.has("interface"))
      rd.fail(b, key, "no interface for block '" + name + "': give study.reduce.interface or {name: " + name + ", interface: [...]}");
    // A block the scene reduces already: the ladder's rungs replace its `reduction`, and the full
    // rung removes it (`PATH.reduction=~`): the reference is always the block's full mesh.
    const std::string list = path.substr(0, path.find('.'));
    l.reduced_in_scene.push_back(static_cast<bool>(scene_root[list][std::stoul(path.substr(path.find('.') + 1))]["reduction"]));
    l.block_paths.push_back(path);
    l.block_names.push_back(name);
    l.interfaces.push_back(interface);
    l.bodies.push_back(welded);
  }
  std::vector<YAML::Node> at;
  if (const YAML::Node steps = reduce.node("ladder")) {
    if (!steps.IsSequence() || steps.size() == 0)
      rd.fail(steps, "study.reduce.ladder", "expected a non-empty list of rungs: rigid, numbers of modes, full (e.g. [rigid, 2, 4, 8, 16, full])");
    l.steps.clear();
    for (size_t i = 0; i < steps.size(); ++i) {
      const YAML::Node n = steps[i];
      const std::string key = "study.reduce.ladder[" + std::to_string(i) + "]";
      if (!n.IsScalar()) rd.fail(n, key, "expected rigid, full or a number of modes");
      std::string step = n.Scalar();
      if (step != "rigid" && step != "full") {
        if (step.empty() || step.size() > 5 || step.find_first_not_of("0123456789") != std::string::npos ||
            std::stoi(step) < 1 || std::stoi(step) > 10000)
          rd.fail(n, key, "expected rigid, full or a number of modes from 1 to 10000, got '" + step + "'");
        step = std::to_string(std::stoi(step));
      }
      if (std::count(l.steps.begin(), l.steps.end(), step)) rd.fail(n, key, "the rung '" + step + "' is given twice");
      l.steps.push_back(step);
      at.push_back(n);
    }
    if (!std::count(l.steps.begin(), l.steps.end(), "full"))
      rd.fail(steps, "study.reduce.ladder", "expected `full` among the rungs: the errors are measured against the full mesh");
  }
  for (size_t i = 0; i < l.steps.size(); ++i) {
    ModelVariant v;
    v.label = rung_label(l.steps[i]);
    v.scene = spec.scene;
    v.overrides = rung_overrides(l, l.steps[i]);
    v.where = i < at.size() ? rd.where(at[i], "study.reduce.ladder[" + l.steps[i] + "]")
                            : rd.where(r, "study.reduce (rung " + l.steps[i] + " of the default ladder)");
    spec.variants.push_back(v);
  }
  spec.reference_variant = rung_label("full");
  spec.ladder = true;
}

/// `study.load`: the keys (each a number, an expression or a list of them in the scene, after the
/// study's `set:`) and the increasing positive scales.
void read_load(const Reader& rd, const YAML::Node& l, const YAML::Node& scene_root, StudySpec& spec) {
  const Section load(rd, l, "study.load", kLoad);
  LoadAxis& a = spec.load;
  a.keys = load.texts("keys");
  if (a.keys.empty()) rd.fail(load.node("keys"), "study.load.keys", "expected a non-empty list of scene keys to scale (e.g. [load.factor])");
  a.scales = load.numbers("scale");
  for (size_t i = 1; i < a.scales.size(); ++i)
    if (!(a.scales[i] > a.scales[i - 1]))
      rd.fail(load.node("scale"), "study.load.scale", "expected increasing load scales (the change points lie between neighbours)");
  // The scene as the runs see it before the load: the scene file with the study's `set:`.
  YAML::Node scene = YAML::Clone(scene_root);
  for (const auto& o : spec.overrides) input::apply_override(scene, o, "study.set", rd.file());
  Reader scene_reader(spec.scene);
  scene_reader.read_parameters(scene["parameters"]);
  const YAML::Node keys = load.node("keys");
  for (size_t k = 0; k < a.keys.size(); ++k) {
    const std::string& path = a.keys[k];
    const YAML::Node at = keys.IsSequence() ? keys[k] : keys;
    const std::string key = "study.load.keys[" + std::to_string(k) + "]";
    if (std::count(a.keys.begin(), a.keys.begin() + static_cast<long>(k), path)) rd.fail(at, key, "the key '" + path + "' is given twice");
    // Walk the path as --set does (maps by key, lists by index), without creating anything
    // (const access; reset() rebinds a handle, where yaml-cpp's operator= would overwrite the node).
    YAML::Node n = scene;
    std::string rest = path, walked;
    while (!rest.empty()) {
      const size_t dot = rest.find('.');
      const std::string part = rest.substr(0, dot);
      rest = dot == std::string::npos ? "" : rest.substr(dot + 1);
      const YAML::Node& here = n;
      const bool index = !part.empty() && part.size() < 9 && part.find_first_not_of("0123456789") == std::string::npos;
      if (here.IsSequence() && index && std::stoul(part) < here.size())
        n.reset(here[std::stoul(part)]);
      else if (here.IsMap() && !part.empty() && here[part])
        n.reset(here[part]);
      else
        rd.fail(at, key, "the scene " + spec.scene + " has no key '" + path + "' (no '" + part + "'" +
                             (walked.empty() ? std::string(" at its top level") : " in '" + walked + "'") + ")");
      walked += (walked.empty() ? "" : ".") + part;
    }
    // A number, an expression of the parameters or a list of them: what the scene reader would read.
    const auto check = [&](const YAML::Node& x, const std::string& which) {
      std::string why = "not a number";
      if (x.IsScalar()) {
        try {
          scene_reader.number(x, which);
          return;
        } catch (const InputError& e) {
          why = e.what();
        }
      }
      rd.fail(at, key, "the scene's '" + path + "' is not a number, an expression of its parameters or a list of them (" +
                           (x.IsMap() ? std::string("a map") : why) + "): a load scale multiplies numbers");
    };
    if (n.IsSequence()) {
      if (n.size() == 0) rd.fail(at, key, "the scene's '" + path + "' is an empty list: nothing to scale");
      for (size_t i = 0; i < n.size(); ++i) check(n[i], path + "[" + std::to_string(i) + "]");
    } else {
      check(n, path);
    }
    a.values.push_back(YAML::Clone(n));
  }
}

}  // namespace

std::vector<const input::Schema*> schemas() {
  return {&kStudyFile, &kStudy, &kSetting, &kReference, &kPeers, &kVariant, &kReduce, &kReduceBlock, &kLoad};
}

StudySpec read_study(const std::string& scene_path, const std::string& study_path,
                     const std::vector<std::string>& study_overrides) {
  StudySpec spec;
  spec.scene = scene_path;
  const std::string file = study_path.empty() ? scene_path : study_path;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw InputError(file + ": cannot open the " + std::string(study_path.empty() ? "scene" : "study") + " file");
  YAML::Node root, scene_root;
  try {
    root = YAML::LoadFile(file);
    scene_root = study_path.empty() ? root : YAML::LoadFile(scene_path);
  } catch (const YAML::Exception& e) {
    throw InputError((study_path.empty() ? file : (fs::is_regular_file(scene_path, ec) ? file : scene_path)) + ":" +
                     std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  Reader rd(file, read_mesh, "--study-set");
  spec.file = file;
  if (!root.IsMap()) rd.fail(root, "(top level)", "expected a map with a `study:` key");
  if (!study_path.empty()) rd.keys(root, "(top level)", kStudyFile);
  YAML::Node s = root["study"];
  if (!s)
    rd.fail(root, "study", study_path.empty() ? "missing: the scene has no study: block (give one, or --study FILE)"
                                              : "missing (required)");
  for (const auto& o : study_overrides) rd.add_override(input::apply_override(s, o, "--study-set", file), o);
  const Section study(rd, s, "study", kStudy);

  spec.mode = static_cast<StudyMode>(study.choice("mode", static_cast<int>(StudyMode::Convergence)));
  const std::string default_name =
      (scene_root["name"] && scene_root["name"].IsScalar() ? scene_root["name"].Scalar()
                                                           : fs::path(scene_path).stem().string()) +
      "_" + mode_name(spec.mode);
  spec.name = study.has("name") ? nonempty_text(rd, s["name"], "study.name") : default_name;
  if (spec.name.find_first_of("/\\ ") != std::string::npos)
    rd.fail(s["name"], "study.name", "expected a plain file name (no spaces or slashes)");
  if (study.has("h")) spec.h = study.numbers("h");
  else if (spec.mode != StudyMode::Fidelity) rd.fail(s, "study.h", "missing: the step sizes to run (s), e.g. [1e-3, 5e-4]");
  if (study.has("tol")) {
    spec.tol = study.numbers("tol");
    if (spec.mode != StudyMode::Convergence) rd.fail(s["tol"], "study.tol", "only in mode convergence");
  }
  spec.t_end = study.number("t_end", spec.t_end);
  for (double h : spec.h)
    if (spec.t_end > 0.0 && h > spec.t_end) rd.fail(s["h"], "study.h", "a step size exceeds study.t_end");

  // Settings: the scene's solver block with the setting's keys.
  const YAML::Node scene_solver = scene_root["solver"];
  if (const YAML::Node list = s["settings"]) {
    if (!list.IsSequence() || list.size() == 0) rd.fail(list, "study.settings", "expected a list of settings {label: ..., ...}");
    std::set<std::string> labels;
    for (size_t i = 0; i < list.size(); ++i) {
      const YAML::Node n = list[i];
      std::string key;
      SchemeSetting st;
      st.label = labelled_item(rd, n, "study.settings", i, "{label: ..., scheme: ..., rho_inf: ...}",
                               "missing (required): the name of the setting in the legend", "setting", labels, key);
      const Section setting(rd, n, key, kSetting);
      if (n["newton"] && !n["newton"].IsMap()) rd.fail(n["newton"], key + ".newton", "expected a map (rtol, atol, atol_lambda, max_iter)");
      // The newton map goes into the scene's solver.newton, where the scene reader checks its keys
      // and values; here only that its keys are names (a map as a key is not).
      if (n["newton"])
        for (const auto& kv : n["newton"]) rd.key_name(kv.first, key + ".newton");
      st.force = setting.flag("force", st.force);
      if (setting.has("set")) st.overrides = assignments(rd, setting, "set");
      st.solver_override = solver_override(scene_solver, n);
      st.where = rd.where(n, key);
      spec.settings.push_back(st);
    }
  } else {
    SchemeSetting st;
    st.label = "scene solver";
    st.where = rd.where(s, "study.settings");
    spec.settings.push_back(st);
  }

  if (const YAML::Node r = s["reference"]) {
    const Section ref(rd, r, "study.reference", kReference);
    if (r["file"]) {
      spec.reference.file = file_path(rd, r["file"], "study.reference.file");
      if (!r["source"])
        rd.fail(r, "study.reference.source", "missing: say where the reference values come from (method, tolerance, script)");
    }
    if (r["source"]) spec.reference.source = nonempty_text(rd, r["source"], "study.reference.source");
    spec.reference.h = ref.number("h", spec.reference.h);
    if (r["setting"]) {
      spec.reference.setting = nonempty_text(rd, r["setting"], "study.reference.setting");
      bool found = false;
      for (const auto& st : spec.settings) found = found || st.label == spec.reference.setting;
      if (!found) rd.fail(r["setting"], "study.reference.setting", "no setting is labelled '" + spec.reference.setting + "'");
    }
    if (spec.reference.file.empty() && !(spec.reference.h > 0.0))
      rd.fail(r, "study.reference", "give a reference file (with its source) or a reference run step size h, or both");
    for (double h : spec.h)
      if (spec.reference.h > 0.0 && !(spec.reference.h < h))
        rd.fail(r["h"], "study.reference.h", "the reference run must use a smaller step than every study step size");
  }
  if ((spec.mode == StudyMode::Convergence) && spec.reference.file.empty() && !(spec.reference.h > 0.0))
    rd.fail(s, "study.reference", "missing: a convergence study needs a reference (file with source, or a run step size h)");
  if (study.has("sensors")) spec.sensors = study.texts("sensors");
  if (study.has("set")) spec.overrides = assignments(rd, study, "set");
  const int errors = study.choice("errors", spec.relative_errors ? 0 : 1);
  spec.relative_errors = errors == 0;
  spec.largest_range = errors == 2;
  if (spec.largest_range && spec.mode != StudyMode::Fidelity)
    rd.fail(s["errors"], "study.errors", "largest_range belongs to mode fidelity (errors over the sensors' histories)");
  spec.condition_number = study.flag("condition_number", spec.condition_number);

  if (const YAML::Node p = s["peers"]) {
    const Section peers(rd, p, "study.peers", kPeers);
    if (!p["problem"]) rd.fail(p, "study.peers.problem", "missing: the problem the peers solve (andrews)");
    spec.peers.problem = kPeers.find("problem")->choices[static_cast<size_t>(peers.choice("problem"))];
    spec.peers.ida = peers.numbers("ida");
    spec.peers.radau = peers.numbers("radau");
    if (spec.mode != StudyMode::Convergence) rd.fail(p, "study.peers", "peers belong to a convergence (work-precision) study");
  }

  if (study.has("tolerance")) {
    spec.tolerance = study.number("tolerance");
    if (spec.mode != StudyMode::Fidelity) rd.fail(s["tolerance"], "study.tolerance", "only in mode fidelity");
  }
  if (s["load"] && !s["reduce"])
    rd.fail(s["load"], "study.load", "the load axis runs the reduction ladder at each load scale: give study.reduce (mode fidelity)");
  if (const YAML::Node r = s["reduce"]) {
    if (spec.mode != StudyMode::Fidelity) rd.fail(r, "study.reduce", "the reduction ladder belongs to mode: fidelity");
    if (s["variants"]) rd.fail(s["variants"], "study.variants", "give either study.reduce (the ladder) or study.variants, not both");
    if (s["reference_variant"])
      rd.fail(s["reference_variant"], "study.reference_variant", "with study.reduce the reference is the rung `full`");
    if (!s["tolerance"]) rd.fail(s, "study.tolerance", "missing: the largest acceptable error of a rung (e.g. 0.01: 1 % of each sensor's range)");
    read_ladder(rd, r, scene_root, spec);
    if (const YAML::Node l = s["load"]) read_load(rd, l, scene_root, spec);
  } else if (const YAML::Node v = s["variants"]) {
    if (spec.mode != StudyMode::Fidelity) rd.fail(v, "study.variants", "variants belong to mode: fidelity");
    if (!v.IsSequence() || v.size() < 2) rd.fail(v, "study.variants", "expected a list of at least 2 variants {label, scene, set}");
    std::set<std::string> labels;
    for (size_t i = 0; i < v.size(); ++i) {
      const YAML::Node n = v[i];
      std::string key;
      ModelVariant mv;
      mv.label = labelled_item(rd, n, "study.variants", i, "{label: ..., scene: ..., set: [...]}", "missing (required)", "variant",
                               labels, key);
      const Section variant(rd, n, key, kVariant);
      mv.scene = variant.has("scene") ? file_path(rd, variant.node("scene"), variant.key_path("scene")) : scene_path;
      if (variant.has("set")) mv.overrides = assignments(rd, variant, "set");
      mv.where = rd.where(n, key);
      spec.variants.push_back(mv);
    }
    spec.reference_variant = spec.variants.back().label;
    if (s["reference_variant"]) {
      spec.reference_variant = nonempty_text(rd, s["reference_variant"], "study.reference_variant");
      if (!labels.count(spec.reference_variant))
        rd.fail(s["reference_variant"], "study.reference_variant", "no variant is labelled '" + spec.reference_variant + "'");
    }
  } else if (spec.mode == StudyMode::Fidelity) {
    rd.fail(s, "study.variants",
            "missing: a fidelity study compares model variants {label, scene, set}, or the rungs of a ladder (study.reduce)");
  }
  if (spec.mode == StudyMode::Fidelity && spec.h.size() > 1)
    rd.fail(s["h"], "study.h", "a fidelity study runs every variant at one step size");
  if (spec.mode == StudyMode::Fidelity && spec.settings.size() > 1)
    rd.fail(s["settings"], "study.settings", "a fidelity study runs every variant with one setting");

  spec.plots = study.flag("plots", spec.plots);
  if (study.has("python")) spec.python = nonempty_text(rd, s["python"], "study.python");
  if (study.has("plot_script")) spec.plot_script = file_path(rd, s["plot_script"], "study.plot_script");
  return spec;
}

}  // namespace alphaflex::study
