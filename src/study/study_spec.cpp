#include "alphaflex/study/study_spec.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/expression.hpp"

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

// Checked reading of the study map: every error is "FILE:LINE: study.KEY: what was expected"
// (or "FILE: --study-set ASSIGNMENT: ..." for a value given on the command line).
class StudyReader {
 public:
  explicit StudyReader(std::string file) : file_(std::move(file)) {}
  std::vector<std::pair<YAML::Node, std::string>> overrides;

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
    std::ostringstream os;
    os << file_;
    bool from_set = false;
    for (const auto& [node, text] : overrides)
      if (at.IsDefined() && node.is(at)) {
        os << ": --study-set " << text;
        from_set = true;
      }
    if (!from_set && at.IsDefined() && at.Mark().line >= 0) os << ":" << (at.Mark().line + 1);
    os << ": " << key << ": " << what;
    throw InputError(os.str());
  }
  std::string where(const YAML::Node& at, const std::string& key) const {
    std::ostringstream os;
    os << file_;
    if (at.IsDefined() && at.Mark().line >= 0) os << ":" << (at.Mark().line + 1);
    os << ": " << key;
    return os.str();
  }
  void keys(const YAML::Node& map, const std::string& path, const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, path, "expected a map of keys");
    std::set<std::string> seen;
    for (const auto& kv : map) {
      const std::string k = kv.first.as<std::string>();
      if (!allowed.count(k)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(kv.first, path + "." + k, "unknown key (allowed here: " + list + ")");
      }
      if (!seen.insert(k).second) fail(kv.first, path + "." + k, "given twice");
    }
  }
  double number(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) fail(n, key, "expected a number");
    try {
      const double v = evaluate_expression(n.Scalar(), {});
      if (!std::isfinite(v)) fail(n, key, "'" + n.Scalar() + "' is not a finite number");
      return v;
    } catch (const std::invalid_argument& e) {
      fail(n, key, std::string("expected a number, ") + e.what());
    }
  }
  double positive(const YAML::Node& n, const std::string& key, const std::string& what) const {
    const double v = number(n, key);
    if (!(v > 0.0)) fail(n, key, "expected a positive " + what + ", got " + n.Scalar());
    return v;
  }
  std::vector<double> positive_list(const YAML::Node& n, const std::string& key, const std::string& what) const {
    if (n.IsScalar()) return {positive(n, key, what)};
    if (!n.IsSequence() || n.size() == 0) fail(n, key, "expected a list of " + what + "s, e.g. [1e-3, 5e-4]");
    std::vector<double> v;
    for (size_t i = 0; i < n.size(); ++i) v.push_back(positive(n[i], key + "[" + std::to_string(i) + "]", what));
    return v;
  }
  bool flag(const YAML::Node& n, const std::string& key) const {
    if (n.IsScalar()) {
      const std::string s = n.Scalar();
      if (s == "true" || s == "on" || s == "yes" || s == "1") return true;
      if (s == "false" || s == "off" || s == "no" || s == "0") return false;
    }
    fail(n, key, "expected on/off (or true/false)");
  }
  std::string text(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar() || n.Scalar().empty()) fail(n, key, "expected a non-empty string");
    return n.Scalar();
  }
  std::vector<std::string> text_list(const YAML::Node& n, const std::string& key) const {
    if (n.IsScalar()) return {text(n, key)};
    if (!n.IsSequence()) fail(n, key, "expected a list of strings");
    std::vector<std::string> v;
    for (size_t i = 0; i < n.size(); ++i) v.push_back(text(n[i], key + "[" + std::to_string(i) + "]"));
    return v;
  }
  /// `set:` entries: "key.path=value" strings, as --set takes them.
  std::vector<std::string> assignments(const YAML::Node& n, const std::string& key) const {
    std::vector<std::string> v = text_list(n, key);
    for (size_t i = 0; i < v.size(); ++i)
      if (v[i].find('=') == std::string::npos || v[i].front() == '=')
        fail(n.IsSequence() ? n[i] : n, key, "expected key.path=value (as for --set), got '" + v[i] + "'");
    return v;
  }
  /// A path relative to the directory of the file being read.
  std::string path(const YAML::Node& n, const std::string& key, bool must_exist = true) const {
    fs::path p = text(n, key);
    if (p.is_relative()) p = fs::path(file_).parent_path() / p;
    std::error_code ec;
    if (must_exist && !fs::is_regular_file(p, ec)) fail(n, key, "no such file: " + p.string());
    return p.lexically_normal().string();
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

// "a.b.c=value" applied to the study tree (maps created on the way, list items by index).
YAML::Node apply_assignment(YAML::Node root, const std::string& assignment, const std::string& label) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(label + ": --study-set " + assignment + ": expected key.path=value");
  std::vector<std::string> parts;
  std::stringstream ss(assignment.substr(0, eq));
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  YAML::Node cur = root;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    if (cur.IsSequence()) {
      const std::string& k = parts[i];
      if (k.empty() || k.find_first_not_of("0123456789") != std::string::npos || std::stoul(k) >= cur.size())
        throw InputError(label + ": --study-set " + assignment + ": '" + k + "' is not an index of that list");
      cur.reset(cur[std::stoul(k)]);
    } else if (cur.IsMap() || cur.IsNull()) {
      if (!cur[parts[i]]) cur[parts[i]] = YAML::Node(YAML::NodeType::Map);
      cur.reset(cur[parts[i]]);
    } else {
      throw InputError(label + ": --study-set " + assignment + ": '" + parts[i] + "' is inside a value, not a map");
    }
  }
  YAML::Node v;
  try {
    v = YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    throw InputError(label + ": --study-set " + assignment + ": " + e.msg);
  }
  if (cur.IsSequence()) {
    const std::string& k = parts.back();
    if (k.empty() || k.find_first_not_of("0123456789") != std::string::npos || std::stoul(k) >= cur.size())
      throw InputError(label + ": --study-set " + assignment + ": '" + k + "' is not an index of that list");
    cur[std::stoul(k)] = v;
  } else {
    cur[parts.back()] = v;
  }
  return v;
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
    for (const auto& kv : n) solver["newton"][kv.first.as<std::string>()] = YAML::Clone(kv.second);
  }
  YAML::Emitter out;
  out << YAML::Flow << solver;
  return std::string("solver=") + out.c_str();
}

}  // namespace

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
  StudyReader rd(file);
  spec.file = file;
  if (!root.IsMap()) rd.fail(root, "(top level)", "expected a map with a `study:` key");
  if (!study_path.empty()) rd.keys(root, "(top level)", {"study"});
  YAML::Node s = root["study"];
  if (!s)
    rd.fail(root, "study", study_path.empty() ? "missing: the scene has no study: block (give one, or --study FILE)"
                                              : "missing (required)");
  for (const auto& o : study_overrides) rd.overrides.emplace_back(apply_assignment(s, o, file), o);
  rd.keys(s, "study", {"name", "mode", "h", "t_end", "settings", "reference", "sensors", "errors", "condition_number",
                       "peers", "variants", "reference_variant", "plots", "python", "plot_script", "set"});

  if (s["mode"]) {
    const std::string m = rd.text(s["mode"], "study.mode");
    if (m == "convergence") spec.mode = StudyMode::Convergence;
    else if (m == "oscillation") spec.mode = StudyMode::Oscillation;
    else if (m == "blow_up") spec.mode = StudyMode::BlowUp;
    else if (m == "fidelity") spec.mode = StudyMode::Fidelity;
    else rd.fail(s["mode"], "study.mode", "unknown mode '" + m + "' (expected convergence, oscillation, blow_up, fidelity)");
  }
  const std::string default_name =
      (scene_root["name"] && scene_root["name"].IsScalar() ? scene_root["name"].Scalar()
                                                           : fs::path(scene_path).stem().string()) +
      "_" + mode_name(spec.mode);
  spec.name = s["name"] ? rd.text(s["name"], "study.name") : default_name;
  if (spec.name.find_first_of("/\\ ") != std::string::npos)
    rd.fail(s["name"], "study.name", "expected a plain file name (no spaces or slashes)");
  if (s["h"]) spec.h = rd.positive_list(s["h"], "study.h", "step size (s)");
  else if (spec.mode != StudyMode::Fidelity) rd.fail(s, "study.h", "missing: the step sizes to run (s), e.g. [1e-3, 5e-4]");
  if (s["t_end"]) spec.t_end = rd.positive(s["t_end"], "study.t_end", "final time (s)");
  for (double h : spec.h)
    if (spec.t_end > 0.0 && h > spec.t_end) rd.fail(s["h"], "study.h", "a step size exceeds study.t_end");

  // Settings: the scene's solver block with the setting's keys.
  const YAML::Node scene_solver = scene_root["solver"];
  if (const YAML::Node list = s["settings"]) {
    if (!list.IsSequence() || list.size() == 0) rd.fail(list, "study.settings", "expected a list of settings {label: ..., ...}");
    std::set<std::string> labels;
    for (size_t i = 0; i < list.size(); ++i) {
      const YAML::Node n = list[i];
      std::string key = "study.settings[" + std::to_string(i) + "]";
      if (!n.IsMap()) rd.fail(n, key, "expected a map {label: ..., scheme: ..., rho_inf: ...}");
      if (!n["label"]) rd.fail(n, key + ".label", "missing (required): the name of the setting in the legend");
      SchemeSetting st;
      st.label = rd.text(n["label"], key + ".label");
      key = "study.settings[" + st.label + "]";
      if (st.label.find_first_of(",\"\n") != std::string::npos)
        rd.fail(n["label"], key + ".label", "a label may not contain commas, quotes or newlines (it is a CSV field)");
      if (!labels.insert(st.label).second) rd.fail(n["label"], key + ".label", "another setting has this label");
      rd.keys(n, key, {"label", "scheme", "rho_inf", "alpha_m", "alpha_f", "beta", "gamma", "scaling", "newton", "set",
                       "force"});
      if (n["newton"] && !n["newton"].IsMap()) rd.fail(n["newton"], key + ".newton", "expected a map (rtol, atol, atol_lambda, max_iter)");
      if (n["force"]) st.force = rd.flag(n["force"], key + ".force");
      if (n["set"]) st.overrides = rd.assignments(n["set"], key + ".set");
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
    rd.keys(r, "study.reference", {"file", "source", "h", "setting"});
    if (r["file"]) {
      spec.reference.file = rd.path(r["file"], "study.reference.file");
      if (!r["source"])
        rd.fail(r, "study.reference.source", "missing: say where the reference values come from (method, tolerance, script)");
    }
    if (r["source"]) spec.reference.source = rd.text(r["source"], "study.reference.source");
    if (r["h"]) spec.reference.h = rd.positive(r["h"], "study.reference.h", "step size of the reference run (s)");
    if (r["setting"]) {
      spec.reference.setting = rd.text(r["setting"], "study.reference.setting");
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
  if (s["sensors"]) spec.sensors = rd.text_list(s["sensors"], "study.sensors");
  if (s["set"]) spec.overrides = rd.assignments(s["set"], "study.set");
  if (s["errors"]) {
    const std::string e = rd.text(s["errors"], "study.errors");
    if (e == "relative") spec.relative_errors = true;
    else if (e == "absolute") spec.relative_errors = false;
    else rd.fail(s["errors"], "study.errors", "expected relative or absolute");
  }
  if (s["condition_number"]) spec.condition_number = rd.flag(s["condition_number"], "study.condition_number");

  if (const YAML::Node p = s["peers"]) {
    rd.keys(p, "study.peers", {"problem", "ida", "radau"});
    if (!p["problem"]) rd.fail(p, "study.peers.problem", "missing: the problem the peers solve (andrews)");
    spec.peers.problem = rd.text(p["problem"], "study.peers.problem");
    if (spec.peers.problem != "andrews")
      rd.fail(p["problem"], "study.peers.problem",
              "unknown problem '" + spec.peers.problem + "' (expected andrews: the peers' equations are the test set's)");
    if (p["ida"]) spec.peers.ida = rd.positive_list(p["ida"], "study.peers.ida", "tolerance");
    if (p["radau"]) spec.peers.radau = rd.positive_list(p["radau"], "study.peers.radau", "tolerance");
    if (spec.mode != StudyMode::Convergence) rd.fail(p, "study.peers", "peers belong to a convergence (work-precision) study");
  }

  if (const YAML::Node v = s["variants"]) {
    if (spec.mode != StudyMode::Fidelity) rd.fail(v, "study.variants", "variants belong to mode: fidelity");
    if (!v.IsSequence() || v.size() < 2) rd.fail(v, "study.variants", "expected a list of at least 2 variants {label, scene, set}");
    std::set<std::string> labels;
    for (size_t i = 0; i < v.size(); ++i) {
      const YAML::Node n = v[i];
      std::string key = "study.variants[" + std::to_string(i) + "]";
      if (!n.IsMap()) rd.fail(n, key, "expected a map {label: ..., scene: ..., set: [...]}");
      if (!n["label"]) rd.fail(n, key + ".label", "missing (required)");
      ModelVariant mv;
      mv.label = rd.text(n["label"], key + ".label");
      key = "study.variants[" + mv.label + "]";
      if (mv.label.find_first_of(",\"\n") != std::string::npos)
        rd.fail(n["label"], key + ".label", "a label may not contain commas, quotes or newlines (it is a CSV field)");
      if (!labels.insert(mv.label).second) rd.fail(n["label"], key + ".label", "another variant has this label");
      rd.keys(n, key, {"label", "scene", "set"});
      mv.scene = n["scene"] ? rd.path(n["scene"], key + ".scene") : scene_path;
      if (n["set"]) mv.overrides = rd.assignments(n["set"], key + ".set");
      mv.where = rd.where(n, key);
      spec.variants.push_back(mv);
    }
    spec.reference_variant = spec.variants.back().label;
    if (s["reference_variant"]) {
      spec.reference_variant = rd.text(s["reference_variant"], "study.reference_variant");
      if (!labels.count(spec.reference_variant))
        rd.fail(s["reference_variant"], "study.reference_variant", "no variant is labelled '" + spec.reference_variant + "'");
    }
  } else if (spec.mode == StudyMode::Fidelity) {
    rd.fail(s, "study.variants", "missing: a fidelity study compares model variants {label, scene, set}");
  }
  if (spec.mode == StudyMode::Fidelity && spec.h.size() > 1)
    rd.fail(s["h"], "study.h", "a fidelity study runs every variant at one step size");
  if (spec.mode == StudyMode::Fidelity && spec.settings.size() > 1)
    rd.fail(s["settings"], "study.settings", "a fidelity study runs every variant with one setting");

  if (s["plots"]) spec.plots = rd.flag(s["plots"], "study.plots");
  if (s["python"]) spec.python = rd.text(s["python"], "study.python");
  if (s["plot_script"]) spec.plot_script = rd.path(s["plot_script"], "study.plot_script");
  return spec;
}

}  // namespace alphaflex::study
