#include "alphaflex/study/fidelity_ladder.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace alphaflex::study {

namespace {
// The lists of the scene that hold beam and shell blocks (io/types/beams_*.cpp, shells_3d.cpp).
const char* const kBlockLists[] = {"beams", "shells"};

/// A load scale as the study file gives it (6 significant digits, as the CSV's load_scale column).
std::string scale_text(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}

std::string sig3(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.3g", x);
  return b;
}
}  // namespace

std::string find_block(const YAML::Node& scene_root, const std::string& name) {
  if (!scene_root.IsMap()) return "";
  for (const char* list : kBlockLists) {
    const YAML::Node l = scene_root[list];
    if (!l || !l.IsSequence()) continue;
    for (size_t i = 0; i < l.size(); ++i)
      if (l[i].IsMap() && l[i]["name"] && l[i]["name"].IsScalar() && l[i]["name"].Scalar() == name)
        return std::string(list) + "." + std::to_string(i);
  }
  return "";
}

std::vector<std::string> block_names(const YAML::Node& scene_root) {
  std::vector<std::string> names;
  if (!scene_root.IsMap()) return names;
  for (const char* list : kBlockLists) {
    const YAML::Node l = scene_root[list];
    if (!l || !l.IsSequence()) continue;
    for (const auto& b : l)
      if (b.IsMap() && b["name"] && b["name"].IsScalar()) names.push_back(b["name"].Scalar());
  }
  return names;
}

std::string rung_label(const std::string& step) {
  if (step == "rigid" || step == "full") return step;
  return step + (step == "1" ? " mode" : " modes");
}

std::vector<std::string> rung_overrides(const ReductionLadder& ladder, const std::string& step) {
  std::vector<std::string> o;
  if (step == "full") {  // no `reduction` key: the block's full nonlinear mesh
    for (size_t b = 0; b < ladder.block_paths.size(); ++b)
      if (b < ladder.reduced_in_scene.size() && ladder.reduced_in_scene[b]) o.push_back(ladder.block_paths[b] + ".reduction=~");
    return o;
  }
  for (size_t b = 0; b < ladder.block_paths.size(); ++b) {
    YAML::Node r(YAML::NodeType::Map);
    r["method"] = step == "rigid" ? std::string("rigid") : ladder.method;
    if (step != "rigid") r["modes"] = std::stoi(step);
    YAML::Node names(YAML::NodeType::Sequence);
    for (const auto& n : ladder.interfaces[b]) names.push_back(n);
    r["interface"] = names;
    // The bodies welded into the block are part of every reduced rung, the rigid one too (its rigid
    // mass properties carry them).
    if (b < ladder.bodies.size() && !ladder.bodies[b].empty()) {
      YAML::Node welded(YAML::NodeType::Sequence);
      for (const auto& n : ladder.bodies[b]) welded.push_back(n);
      r["bodies"] = welded;
    }
    // The rigid rung keeps no elastic amplitude: the reader refuses both keys on it.
    if (step != "rigid" && ladder.geometric_stiffness) r["geometric_stiffness"] = "on";
    if (step != "rigid" && ladder.static_modes != "none") r["static_modes"] = ladder.static_modes;
    if (step != "rigid" && ladder.derivatives > 0) r["derivatives"] = ladder.derivatives;
    YAML::Emitter out;
    out << YAML::Flow << r;
    o.push_back(ladder.block_paths[b] + ".reduction=" + out.c_str());
  }
  return o;
}

double history_error(const std::vector<double>& x, const std::vector<double>& x_full, bool relative) {
  double dmax = 0.0, lo = HUGE_VAL, hi = -HUGE_VAL;
  for (size_t i = 0; i < x.size() && i < x_full.size(); ++i) {
    dmax = std::max(dmax, std::fabs(x[i] - x_full[i]));
    lo = std::min(lo, x_full[i]);
    hi = std::max(hi, x_full[i]);
  }
  // A NaN in either history makes the error NaN (not acceptable), not a silent 0.
  for (size_t i = 0; i < x.size() && i < x_full.size(); ++i)
    if (std::isnan(x[i]) || std::isnan(x_full[i])) return std::nan("");
  const double range = hi - lo;
  return relative && range > 0.0 ? dmax / range : dmax;
}

double history_range(const std::vector<double>& x) {
  if (x.empty()) return 0.0;
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  return *hi - *lo;
}

std::vector<size_t> matching_times(const std::vector<double>& t, const std::vector<double>& t_full, std::string& why) {
  std::vector<size_t> at;
  size_t j = 0;
  for (double tf : t_full) {
    const double tol = 1e-9 * std::max(1.0, std::fabs(tf));
    while (j < t.size() && t[j] < tf - tol) ++j;
    if (j == t.size() || std::fabs(t[j] - tf) > tol) {
      why = "its output times differ from the full run's (none at t = " + sig3(tf) + " s; " + std::to_string(t.size()) +
            " output times against " + std::to_string(t_full.size()) +
            "): give every variant the same solver.h and output.sensors_dt";
      return {};
    }
    at.push_back(j);
  }
  return at;
}

Recommendation recommend(const std::vector<Rung>& rungs, double tolerance, const std::string& measure) {
  Recommendation r;
  r.acceptable.resize(rungs.size(), false);
  for (size_t i = 0; i < rungs.size(); ++i) {
    const Rung& g = rungs[i];
    r.acceptable[i] = g.ok && g.error <= tolerance;  // NaN compares false: not acceptable
    if (r.acceptable[i] && r.first_acceptable < 0) r.first_acceptable = static_cast<int>(i);
    if (r.acceptable[i] && (r.lightest < 0 || g.cpu < rungs[static_cast<size_t>(r.lightest)].cpu)) r.lightest = static_cast<int>(i);
  }
  // From the heaviest rung down: the ladder is acceptable from the first rung after the last
  // rung that ran and was not (a failed rung breaks nothing: it says nothing about accuracy).
  for (int i = static_cast<int>(rungs.size()) - 1; i >= 0; --i) {
    if (rungs[static_cast<size_t>(i)].ok && !r.acceptable[static_cast<size_t>(i)]) break;
    if (r.acceptable[static_cast<size_t>(i)]) r.acceptable_from = i;
  }
  std::ostringstream os;
  os << "tolerance " << sig3(tolerance) << " (" << measure << "): ";
  if (r.lightest < 0) {
    os << "no variant is within it";
  } else {
    const Rung& best = rungs[static_cast<size_t>(r.lightest)];
    os << "the lightest variant within it is '" << best.label << "' (error " << sig3(best.error) << ", CPU " << sig3(best.cpu)
       << " s)";
    if (r.acceptable_from >= 0) {
      os << "; along the ladder the variants are acceptable from '" << rungs[static_cast<size_t>(r.acceptable_from)].label << "' on";
      std::string lighter;
      for (int i = 0; i < r.acceptable_from; ++i)
        if (r.acceptable[static_cast<size_t>(i)]) lighter += (lighter.empty() ? "" : ", ") + ("'" + rungs[static_cast<size_t>(i)].label + "'");
      if (!lighter.empty()) os << " (also acceptable before it: " << lighter << ")";
    }
  }
  std::string failed;
  for (const auto& g : rungs)
    if (!g.ok) failed += (failed.empty() ? "" : ", ") + ("'" + g.label + "'");
  if (!failed.empty()) os << "; failed or not measured: " << failed;
  r.text = os.str();
  return r;
}

std::vector<std::string> load_overrides(const LoadAxis& axis, double scale) {
  char factor[40];
  std::snprintf(factor, sizeof factor, "%.17g", scale);
  // One scalar times the scale: a number stays a number, anything else is an expression.
  const auto scaled = [&](const YAML::Node& v) -> std::string {
    const std::string& text = v.Scalar();
    char* end = nullptr;
    const double x = std::strtod(text.c_str(), &end);
    if (!text.empty() && end && *end == '\0') {
      char b[40];
      std::snprintf(b, sizeof b, "%.17g", x * scale);
      return b;
    }
    return "(" + text + ")*" + factor;
  };
  std::vector<std::string> o;
  for (size_t k = 0; k < axis.keys.size(); ++k) {
    const YAML::Node& v = axis.values[k];
    YAML::Node value;
    if (v.IsSequence()) {
      value = YAML::Node(YAML::NodeType::Sequence);
      for (size_t i = 0; i < v.size(); ++i) value.push_back(scaled(v[i]));
    } else {
      value = scaled(v);
    }
    // Emitted, not pasted: an expression with a comma (`atan2(a, b)`) is quoted inside a list.
    YAML::Emitter out;
    out << YAML::Flow << value;
    o.push_back(axis.keys[k] + "=" + out.c_str());
  }
  return o;
}

std::vector<std::string> load_change_points(const std::vector<double>& scales, const std::vector<std::string>& lightest) {
  const auto name = [](const std::string& l) { return l.empty() ? std::string("none") : "`" + l + "`"; };
  std::vector<std::string> lines;
  for (size_t i = 1; i < scales.size() && i < lightest.size(); ++i)
    if (lightest[i] != lightest[i - 1])
      lines.push_back("lightest acceptable variant changes from " + name(lightest[i - 1]) + " to " + name(lightest[i]) +
                      " between load scale " + scale_text(scales[i - 1]) + " and " + scale_text(scales[i]));
  if (lines.empty() && !scales.empty() && !lightest.empty())
    lines.push_back("lightest acceptable variant is " + name(lightest.front()) + " at every load scale (" + scale_text(scales.front()) +
                    (scales.size() > 1 ? " to " + scale_text(scales.back()) : std::string()) + ")");
  return lines;
}

}  // namespace alphaflex::study
