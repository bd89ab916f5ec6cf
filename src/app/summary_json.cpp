#include "alphaflex/app/summary_json.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "alphaflex/core/error.hpp"

namespace alphaflex {

using json = nlohmann::ordered_json;

RunFigures run_figures(const RunSummary& s) {
  RunFigures f;
  const PhaseTimes& t = s.times;
  f.wall = s.wall;
  f.mean_newton = s.steps ? static_cast<double>(s.newton_total) / s.steps : 0.0;
  f.other_time = std::max(0.0, s.wall - t.setup - t.assembly - t.factorization - t.solve - t.output - s.checkpoint_time);
  f.us_per_step = s.steps ? 1e6 * s.wall / s.steps : 0.0;
  int hi = 0;
  for (int u : s.unknowns_per_rank) hi = std::max(hi, u);
  const double avg = s.ranks > 0 ? static_cast<double>(s.unknowns) / s.ranks : 0.0;
  f.load_imbalance = avg > 0.0 && !s.unknowns_per_rank.empty() ? hi / avg : 1.0;
  return f;
}

namespace {

/// {"s": seconds, "percent": share of the wall time}.
json phase(const RunFigures& f, double seconds) { return {{"s", seconds}, {"percent", f.percent(seconds)}}; }

json scheme(const Scene& scene) {
  const AlphaParameters& p = scene.settings.parameters;
  return {{"name", p.scheme},         {"alpha_m", p.alpha_m}, {"alpha_f", p.alpha_f},
          {"beta", p.beta},           {"gamma", p.gamma},     {"rho_inf", p.rho_infinity()},
          {"scaling", scene.settings.integrator.scaling}};
}

}  // namespace

std::string summary_json(const Scene& scene, const RunSummary& s) {
  const RunFigures f = run_figures(s);
  const RunSettings& rs = scene.settings;
  const bool is_static = rs.analysis == Analysis::Static;
  json j;
  j["command"] = "run";
  j["scene"] = scene.name;
  j["file"] = scene.file;
  j["analysis"] = is_static ? "static" : "dynamic";
  j["scheme"] = scheme(scene);
  j["unknowns"] = s.unknowns;
  j["coordinates"] = s.coordinates;
  j["multipliers"] = s.multipliers;
  j["steps"] = s.steps;
  if (is_static) {
    j["load_factor"] = rs.load_factor;
    j["static_cuts"] = s.static_cuts;
    if (s.arc_length) {
      // Path following (solver.static.method: arc_length): where it ended and its critical points.
      json points = json::array();
      for (size_t k = 0; k < s.path.critical_points.size(); ++k) {
        const CriticalPoint& cp = s.path.critical_points[k];
        json sensors = json::object();
        for (size_t i = 0; i < s.sensor_names.size() && i < s.critical_sensors[k].size(); ++i)
          sensors[s.sensor_names[i]] = s.critical_sensors[k][i];
        points.push_back({{"kind", cp.kind == CriticalPoint::Kind::Bifurcation ? "bifurcation" : "limit"},
                          {"extremum", cp.kind == CriticalPoint::Kind::LimitMaximum ? "maximum"
                                       : cp.kind == CriticalPoint::Kind::LimitMinimum ? "minimum" : ""},
                          {"load_factor", cp.load_factor}, {"step", cp.step}, {"between", {cp.lower, cp.upper}},
                          {"sensors", sensors}});
      }
      j["arc_length"] = {{"final_load_factor", s.path.load_factor}, {"ended_by", s.path.stop},
                         {"min_arc_length", s.path.min_arc}, {"max_arc_length", s.path.max_arc},
                         {"line_searches", s.path.line_searches}, {"critical_points", points}};
    }
  } else {
    j["h"] = rs.h;
    j["t_end"] = rs.t_end;
    if (rs.step_cuts > 0) {
      j["step_cuts"] = s.step_cuts;
      j["h_min"] = s.h_min;
    }
    if (s.static_steps > 0) j["initial_statics"] = {{"load_steps", s.static_steps}, {"step_cuts", s.static_cuts}};
  }
  j["consistent_start_projection"] = s.projection;
  j["partition"] = {{"ranks", s.ranks},
                    {"edge_cut", s.edge_cut},
                    {"load_imbalance", f.load_imbalance},
                    {"unknowns_per_rank", s.unknowns_per_rank},
                    {"ghost_nodes_per_rank", s.ghosts_per_rank}};
  j["newton"] = {{"total", s.newton_total}, {"mean_per_step", f.mean_newton}, {"max", s.newton_max}};
  if (!s.newton_method.empty()) j["newton"]["method"] = s.newton_method;
  j["factorizations"] = {{"numeric", s.factorizations}, {"symbolic", s.symbolic_analyses}};
  if (s.reused_iterations >= 0)
    j["modified_newton"] = {{"reused_iterations", s.reused_iterations}, {"contraction_refreshes", s.contraction_refreshes},
                            {"fresh_starts", s.fresh_starts},
                            {"rescaled_iterations", s.rescaled_iterations}};
  j["linear_solver"] = {{"dense", s.mumps.dense}, {"mumps", s.mumps.mumps}};
  if (s.mumps.mumps)
    j["mumps"] = {{"factor_entries", s.mumps.entries},
                  {"flops_per_factorization", s.mumps.flops},
                  {"memory_mb_all_ranks", s.mumps.memory_sum_mb},
                  {"memory_mb_largest_rank", s.mumps.memory_max_mb},
                  {"workspace_retries", s.workspace_retries},
                  {"workspace_percent", s.workspace_percent}};
  if (s.mumps.mumps && s.mumps.low_rank_tolerance > 0.0)
    j["mumps"]["low_rank"] = {{"tolerance", s.mumps.low_rank_tolerance}, {"factor_entries", s.mumps.low_rank_entries},
                              {"flops_per_factorization", s.mumps.low_rank_flops}};
  j["blas"] = s.blas;
  j["memory_mb"] = {{"peak_all_ranks", s.peak_memory_mb}, {"peak_largest_rank", s.peak_memory_max_mb}};
  if (s.scene_memory_mb >= 0.0) j["memory_mb"]["scene_per_rank"] = s.scene_memory_mb;
  // The estimate made after MUMPS' analysis (app/memory_estimate.hpp), per rank (largest rank).
  const MemoryEstimate& me = s.memory_estimate;
  if (me.known())
    j["memory_mb"]["estimate_per_rank"] = {{"total", me.total_mb}, {"before_matrix", me.base_mb}, {"matrix", me.matrix_mb},
                                           {"factorization", me.factorization_mb}};
  if (!s.restarted_from.empty()) j["restart"] = {{"from", s.restarted_from}, {"time", s.restart_time}};
  j["checkpoints"] = {{"written", s.checkpoints}, {"bytes_each", s.checkpoint_bytes}, {"last", s.checkpoint}};
  const PhaseTimes& t = s.times;
  j["wall_time"] = {{"s", s.wall},
                    {"us_per_step", f.us_per_step},
                    {"setup", phase(f, t.setup)},
                    {"assembly", phase(f, t.assembly)},
                    {"factorization", phase(f, t.factorization)},
                    {"solve", phase(f, t.solve)},
                    {"output", phase(f, t.output)},
                    {"checkpoints", phase(f, s.checkpoint_time)},
                    {"other", phase(f, f.other_time)}};
  json sensors = json::object();
  for (size_t k = 0; k < s.sensor_names.size() && k < s.final_sensors.size(); ++k)
    sensors[s.sensor_names[k]] = s.final_sensors[k];
  j["final_time"] = s.final_state.t;
  j["final_sensors"] = sensors;
  std::vector<std::string> warnings = scene.warnings;
  warnings.insert(warnings.end(), s.warnings.begin(), s.warnings.end());
  j["warnings"] = warnings;
  j["results"] = {{"sensors", s.csv}, {"fields", s.h5}, {"xdmf", s.xdmf}};
  return j.dump(1) + "\n";
}

std::string modes_json(const Scene& scene, const ModalRunSummary& s) {
  auto modes = [](const ModalResult& r) {
    json list = json::array();
    for (const Mode& m : r.modes) {
      json x = {{"kind", to_string(m.kind)},           {"frequency_hz", m.frequency},
                {"natural_frequency_hz", m.natural_frequency}, {"damping_ratio", m.damping_ratio},
                {"modal_mass", m.modal_mass},          {"largest_rotation", m.largest_rotation},
                {"whirl", m.whirl},                    {"kinetic_share", m.kinetic_share},
                {"strain_share", m.strain_share}};
      x["dominant_part"] = m.dominant_part >= 0 ? json(r.parts[static_cast<size_t>(m.dominant_part)]) : json();
      list.push_back(x);
    }
    return list;
  };
  const ModalResult& r = s.result;
  json j = {{"command", "modes"},  {"scene", scene.name},   {"file", scene.file},
            {"state", s.state},     {"time", s.time},        {"load_factor", s.load_factor},
            {"frame", s.frame},     {"damped", r.damped},    {"unknowns", s.unknowns},
            {"coordinates", s.coordinates}, {"multipliers", s.multipliers}, {"ranks", s.ranks},
            {"parts", r.parts}};
  j["modes"] = modes(r);
  j["rigid_body_modes"] = r.rigid_body_modes;
  j["eigensolver_iterations"] = r.iterations;
  j["wall_time"] = {{"solve_s", s.solve_wall}, {"command_s", s.wall}};
  j["warnings"] = r.warnings;
  if (!s.campbell.empty()) {
    json rows = json::array();
    for (size_t i = 0; i < s.campbell.size(); ++i)
      rows.push_back({{"speed_rad_s", s.campbell_speeds[i]}, {"modes", modes(s.campbell[i])}});
    j["campbell"] = rows;
  }
  j["results"] = {{"table", s.csv},          {"fields", s.h5},
                  {"xdmf", s.xdmf},          {"campbell_table", s.campbell_csv},
                  {"campbell_chart", s.campbell_chart}};
  return j.dump(1) + "\n";
}

std::string write_summary_json(const std::string& outdir, const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::path(outdir) / (name + ".summary.json")).string();
  const std::string tmp = path + ".tmp";
  errno = 0;
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    out.close();
    if (!out)
      throw OutputError("cannot write the summary: " + tmp + (errno ? std::string(" (") + std::strerror(errno) + ")" : ""));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw OutputError("cannot rename to " + path + ": " + tmp + " (" + ec.message() + ")");
  return path;
}

}  // namespace alphaflex
