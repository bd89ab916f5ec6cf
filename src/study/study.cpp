#include "alphaflex/study/study.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

#include "alphaflex/app/exit_agreement.hpp"
#include "alphaflex/app/simulation.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/io/sensor_schedule.hpp"
#include "alphaflex/study/fidelity_ladder.hpp"
#include "alphaflex/study/andrews_ida.hpp"
#include "alphaflex/study/cpu_time.hpp"
#include "alphaflex/study/iteration_matrix.hpp"
#include "alphaflex/study/measures.hpp"
#include "alphaflex/study/run_groups.hpp"
#include "alphaflex/study/strain_energy.hpp"

#ifndef ALPHAFLEX_SOURCE_DIR
#define ALPHAFLEX_SOURCE_DIR "."
#endif

namespace alphaflex::study {

double StudyRow::get(const std::string& key) const {
  const auto it = errors.find(key);
  if (it != errors.end()) return it->second;
  for (const auto& [k, v] : extra)
    if (k == key) return v;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

namespace fs = std::filesystem;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string num(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.17g", x);
  return b;
}
std::string sci(double x, int digits = 3) {
  if (std::isnan(x)) return "-";
  std::ostringstream os;
  os << std::scientific << std::setprecision(digits - 1) << x;
  return os.str();
}
std::string sig6(double x) {
  char b[40];
  std::snprintf(b, sizeof b, "%.6g", x);
  return b;
}
std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

/// A scene read on every rank, with the ranks agreeing on success before anything collective.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides, MPI_Comm comm) {
  Scene sc;
  std::string msg;
  int ok = 1;
  try {
    sc = read_scene(path, overrides, comm);  // rank 0 reads the file (and meshes), all parse
  } catch (const InputError& e) {
    ok = 0;
    msg = e.what();
  }
  int all = 1;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm);
  if (!all) throw InputError(msg.empty() ? path + ": unreadable on another rank" : msg);
  return sc;
}

/// A CSV of numbers with a header row after optional '#' comment lines.
struct CsvTable {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  int column(const std::string& n) const {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == n) return static_cast<int>(i);
    return -1;
  }
};

CsvTable read_numeric_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the reference file");
  CsvTable t;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line[0] == '#') continue;
    break;
  }
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) t.names.push_back(c);
  if (t.names.empty()) throw InputError(path + ": no header row (expected column names, e.g. t,theta1,...)");
  while (std::getline(in, line)) {
    ++lineno;
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream ls(line);
    for (std::string c; std::getline(ls, c, ',');) {
      try {
        size_t used = 0;
        row.push_back(std::stod(c, &used));
      } catch (const std::exception&) {
        throw InputError(path + ":" + std::to_string(lineno) + ": expected a number, got '" + c + "'");
      }
    }
    if (row.size() != t.names.size())
      throw InputError(path + ":" + std::to_string(lineno) + ": expected " + std::to_string(t.names.size()) +
                       " values (as many as header columns), got " + std::to_string(row.size()));
    t.rows.push_back(row);
  }
  return t;
}

/// What errors are measured against.
struct Reference {
  std::string label;
  std::map<std::string, double> at_end;                 ///< sensor values at t_end
  std::vector<double> times;                            ///< the file's t column (series)
  std::map<std::string, std::vector<double>> series;    ///< the file's columns
  bool has_state = false;
  MechanicalState state;                                ///< final state of the reference run
};

/// One alphaflex run and what the study keeps of it.
struct RunRecord {
  RunSummary summary;
  bool ok = true;
  std::string failure;
  double cpu = 0.0, wall = 0.0;
  std::vector<double> t;
  std::vector<std::vector<double>> sensors;    ///< per step (every step: on_step)
  std::vector<Eigen::VectorXd> lambda;         ///< per step, if asked
  std::vector<std::vector<double>> energy;     ///< per step and part, if asked
  MechanicalState last;                        ///< last converged state
};

/// What a run must record per step (a work–precision run records only the step count, so that the
/// observer costs nothing measurable).
struct RunNeeds {
  bool sensors = false;
  bool lambda = false;
  bool last_state = false;
  const std::vector<FlexiblePart>* parts = nullptr;
};

RunRecord run_one(Scene& scene, const RunNeeds& needs, MPI_Comm comm) {
  RunRecord rec;
  const Model& model = *scene.model;
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  opt.on_step = [&](const MechanicalState& st) {
    rec.t.push_back(st.t);
    if (needs.sensors) {
      std::vector<double> v;
      for (const auto& sn : model.sensors()) v.push_back(sn.evaluate(model, st));
      rec.sensors.push_back(std::move(v));
    }
    if (needs.lambda) rec.lambda.push_back(model.num_multipliers() > 0 ? st.lambda : st.qdd);
    if (needs.parts) rec.energy.push_back(strain_energies(model, *needs.parts, st));
    if (needs.last_state) rec.last = st;
  };
  const double c0 = process_cpu_seconds(), w0 = MPI_Wtime();
  try {
    rec.summary = run_simulation(scene, opt, comm);
  } catch (const SolverError& e) {
    rec.ok = false;
    rec.failure = first_line(e.what());
  }
  double cpu = process_cpu_seconds() - c0;
  MPI_Allreduce(MPI_IN_PLACE, &cpu, 1, MPI_DOUBLE, MPI_SUM, comm);
  rec.cpu = cpu;
  rec.wall = MPI_Wtime() - w0;
  return rec;
}

double error_of(double value, double ref, bool relative) {
  const double d = std::fabs(value - ref);
  return relative && std::fabs(ref) > 0.0 ? d / std::fabs(ref) : d;
}

double inf_norm(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

/// State errors (∞-norms) of a final state against the reference run's.
void state_errors(const Model& model, const MechanicalState& s, const MechanicalState& ref, bool relative,
                  std::map<std::string, double>& out) {
  auto norm_err = [&](double d, double scale) { return relative && scale > 0.0 ? d / scale : d; };
  out["q"] = norm_err(inf_norm(model.difference(ref.q, s.q)), inf_norm(ref.q));
  out["v"] = norm_err(inf_norm(s.v - ref.v), inf_norm(ref.v));
  if (model.num_multipliers() > 0) out["lambda"] = norm_err(inf_norm(s.lambda - ref.lambda), inf_norm(ref.lambda));
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

class Study {
 public:
  Study(const StudySpec& spec, const StudyOptions& opt, MPI_Comm comm) : spec_(spec), opt_(opt), comm_(comm) {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &size_);
    res_.spec = spec;
  }

  StudyResult run() {
    prepare_output();
    check_settings();
    switch (spec_.mode) {
      case StudyMode::Convergence: convergence(); break;
      case StudyMode::Oscillation: oscillation(); break;
      case StudyMode::BlowUp: blow_up(); break;
      case StudyMode::Fidelity: fidelity(); break;
    }
    write_outputs();
    if (!fatal_.empty()) throw SolverError(fatal_);
    return res_;
  }

 private:
  // ------------------------------------------------------------------ set-up
  void say(const std::string& line) const {
    if (opt_.verbose && rank_ == 0) std::cout << line << std::endl;
  }

  void prepare_output() {
    int ok = 1;
    std::string err;
    if (rank_ == 0) {
      std::error_code ec;
      fs::create_directories(opt_.outdir, ec);
      const std::string probe = (fs::path(opt_.outdir) / (".alphaflex_study_probe")).string();
      std::ofstream f(probe);
      if (!f) {
        ok = 0;
        err = opt_.outdir + ": cannot write the study's output files there (" +
              (ec ? ec.message() : std::string("not writable")) + ")";
      } else {
        f.close();
        fs::remove(probe, ec);
      }
    }
    MPI_Bcast(&ok, 1, MPI_INT, 0, comm_);
    if (!ok) throw OutputError(err.empty() ? "cannot write the study's output files (see rank 0)" : err);
  }

  /// Overrides of one run: the setting's solver map, the study's `set:`, the command line's --set,
  /// the setting's `set:` list, then the study's h and t_end.
  std::vector<std::string> overrides(const SchemeSetting& st, double h, double tol = 0.0) const {
    std::vector<std::string> o;
    if (!st.solver_override.empty()) o.push_back(st.solver_override);
    o.insert(o.end(), spec_.overrides.begin(), spec_.overrides.end());
    o.insert(o.end(), opt_.scene_overrides.begin(), opt_.scene_overrides.end());
    o.insert(o.end(), st.overrides.begin(), st.overrides.end());
    if (h > 0.0) o.push_back("solver.h=" + num(h));
    if (spec_.t_end > 0.0) o.push_back("solver.t_end=" + num(spec_.t_end));
    if (tol > 0.0) {
      o.push_back("solver.tolerance.rtol=" + num(tol));
      o.push_back("solver.tolerance.atol=" + num(tol));
    }
    return o;
  }

  /// The scene of a run, read on `comm` (default: the study's; a group's for concurrent runs);
  /// `tol` > 0: an adaptive run (solver.tolerance rtol = atol = tol, first step h).
  Scene scene_for(const SchemeSetting& st, double h, const std::string& scene_file = "", MPI_Comm comm = MPI_COMM_NULL,
                  double tol = 0.0) {
    Scene sc;
    try {
      sc = load_scene(scene_file.empty() ? spec_.scene : scene_file, overrides(st, h, tol), comm == MPI_COMM_NULL ? comm_ : comm);
    } catch (const InputError& e) {
      throw InputError(std::string(e.what()) + "\n  (in the runs of " + st.where + ")");
    }
    if (!sc.warnings.empty() && !st.force) {
      std::string w;
      for (const auto& s : sc.warnings) w += "\n  " + s;
      throw InputError(st.where + ": the scheme's parameters fail the checks a run warns about:" + w +
                       "\n  A study runs such a setting only when told: add `force: on` to it (mode blow_up shows "
                       "what happens).");
    }
    return sc;
  }

  /// Every setting (or variant) read once before any run, so that bad input stops the study at once.
  void check_settings() {
    const double h = spec_.h.empty() ? 0.0 : spec_.h.front();
    if (spec_.mode == StudyMode::Fidelity) {
      // The reference variant only: every error is measured against it. Another variant that
      // cannot be built (a key this build does not know, bad overrides) is a failed row.
      for (const auto& v : spec_.variants)
        if (v.label == spec_.reference_variant) {
          // With a load axis: at its first scale (the load overrides are checked by the scene reader).
          const Scene sc = scene_for(variant_setting(at_load(v, 0)), h, v.scene);
          reference_unknowns_ = sc.model->num_dofs() + sc.model->num_multipliers();
          for (const auto& s : spec_.sensors) {
            std::string names;
            bool found = false;
            for (const auto& sn : sc.model->sensors()) {
              names += (names.empty() ? "" : ", ") + sn.name;
              found = found || sn.name == s;
            }
            if (!found)
              throw InputError(spec_.file + ": study.sensors: the reference variant's scene " + v.scene +
                               " has no sensor named '" + s + "' (its sensors: " + names + ")");
          }
        }
      return;
    }
    for (const auto& st : spec_.settings) scene_for(st, h);
  }

  const SchemeSetting& reference_setting() const {
    for (const auto& st : spec_.settings)
      if (st.label == spec_.reference.setting) return st;
    return spec_.settings.front();
  }

  /// Reference values at t_end (file) and the reference run (if asked), and the sensors to report.
  /// `reference_run_later`: the reference run is one of the study's concurrent runs, and
  /// take_reference_run() gives its results when they are gathered.
  void prepare_reference(const Scene& base, double t_end, bool reference_run_later = false) {
    Reference& r = ref_;
    if (!spec_.reference.file.empty()) {
      const CsvTable tab = read_numeric_csv(spec_.reference.file);
      const int tc = tab.column("t");
      if (tc < 0) {
        if (tab.rows.size() != 1)
          throw InputError(spec_.reference.file + ": a reference without a t column must have one row (the values at t_end)");
        for (size_t k = 0; k < tab.names.size(); ++k) r.at_end[tab.names[k]] = tab.rows[0][k], file_values_.insert(tab.names[k]);
      } else {
        const std::vector<double>* row_end = nullptr;
        for (const auto& row : tab.rows) {
          r.times.push_back(row[static_cast<size_t>(tc)]);
          if (std::fabs(row[static_cast<size_t>(tc)] - t_end) <= 1e-9 * std::max(1.0, t_end)) row_end = &row;
        }
        for (size_t k = 0; k < tab.names.size(); ++k) {
          if (static_cast<int>(k) == tc) continue;
          std::vector<double> col;
          for (const auto& row : tab.rows) col.push_back(row[k]);
          r.series[tab.names[k]] = col;
        }
        if (!row_end && spec_.mode == StudyMode::Convergence)
          throw InputError(spec_.reference.file + ": no row at t = " + sig6(t_end) + " s, the study's final time (rows from " +
                           (r.times.empty() ? std::string("-") : sig6(r.times.front())) + " to " +
                           (r.times.empty() ? std::string("-") : sig6(r.times.back())) + " s)");
        if (row_end)
          for (size_t k = 0; k < tab.names.size(); ++k)
            if (static_cast<int>(k) != tc) r.at_end[tab.names[k]] = (*row_end)[k], file_values_.insert(tab.names[k]);
      }
      reference_parts_.push_back(spec_.reference.file + " (" + spec_.reference.source + ")");
    }
    if (spec_.reference.h > 0.0) {
      if (reference_run_later) {
        // Run with the others (convergence): the scene's sensors will have the run's values.
        r.has_state = true;
        for (const auto& sn : base.model->sensors())
          if (!r.at_end.count(sn.name)) r.at_end[sn.name] = kNaN;
      } else {
        say("reference run: " + reference_run_name() + " ...");
        Scene sc = scene_for(reference_setting(), spec_.reference.h);
        RunRecord rec = run_one(sc, {}, comm_);
        if (!rec.ok) throw SolverError("the study's reference run (" + reference_run_name() + ") failed: " + rec.failure);
        take_reference_run(rec.summary.final_state, rec.summary.sensor_names, rec.summary.final_sensors, rec.summary.steps,
                           rec.cpu);
      }
    }
    set_reference_label();

    // Sensors to report: those asked (each must exist), else every sensor with a reference value.
    std::vector<std::string> names;
    for (const auto& sn : base.model->sensors()) names.push_back(sn.name);
    if (!spec_.sensors.empty()) {
      for (const auto& s : spec_.sensors) {
        if (std::find(names.begin(), names.end(), s) == names.end()) {
          std::string l;
          for (const auto& n : names) l += (l.empty() ? "" : ", ") + n;
          throw InputError(spec_.file + ": study.sensors: the scene has no sensor named '" + s + "' (its sensors: " + l + ")");
        }
        if (spec_.mode == StudyMode::Convergence && !r.at_end.count(s))
          throw InputError(spec_.file + ": study.sensors: '" + s + "' has no reference value (the reference file has no column '" +
                           s + "'; give study.reference.h for a reference run)");
      }
      sensors_ = spec_.sensors;
    } else {
      for (const auto& n : names)
        if (spec_.mode != StudyMode::Convergence || r.at_end.count(n)) sensors_.push_back(n);
    }
    if (r.has_state) res_.error_names = {"q", "v"};
    if (r.has_state && base.model->num_multipliers() > 0) res_.error_names.push_back("lambda");
    for (const auto& s : sensors_) res_.error_names.push_back(s);
  }

  std::string reference_run_name() const {
    std::ostringstream os;
    os << "alphaflex run at h = " << spec_.reference.h << " s with setting '" << reference_setting().label << "'";
    return os.str();
  }

  /// The reference run's final state, and its sensor values where the reference file has none.
  void take_reference_run(const MechanicalState& final_state, const std::vector<std::string>& names,
                          const std::vector<double>& values, long steps, double cpu) {
    ref_.has_state = true;
    ref_.state = final_state;
    for (size_t k = 0; k < names.size(); ++k)
      if (!file_values_.count(names[k])) ref_.at_end[names[k]] = values[k];
    std::ostringstream os;
    os << reference_run_name() << ", " << steps << " steps, CPU " << std::setprecision(3) << cpu << " s";
    reference_parts_.push_back(os.str() + (spec_.reference.file.empty() ? "" : " (state errors q, v, lambda and sensors the file lacks)"));
    set_reference_label();
  }

  void set_reference_label() {
    ref_.label.clear();
    for (size_t i = 0; i < reference_parts_.size(); ++i) ref_.label += (i ? "; " : "") + reference_parts_[i];
    res_.reference_label = ref_.label;
  }

  StudyRow row_for(const Scene& sc, const SchemeSetting& st, double h, const RunRecord& rec) const {
    StudyRow row;
    row.label = st.label;
    row.params = sc.settings.parameters;
    row.scaling = sc.settings.integrator.scaling;
    row.h = h;
    row.t_end = sc.settings.t_end;
    row.ok = rec.ok;
    row.failure = rec.failure;
    row.steps = rec.ok ? rec.summary.steps : static_cast<long>(rec.t.size()) - 1;
    row.newton_total = rec.summary.newton_total;
    row.newton_max = rec.summary.newton_max;
    row.cpu = rec.cpu;
    row.wall = rec.wall;
    return row;
  }

  void print_row(const StudyRow& r) const {
    if (!opt_.verbose || rank_ != 0) return;
    std::ostringstream os;
    os << "  [" << r.label << "] ";
    if (!std::isnan(r.h)) os << "h = " << r.h << " s: ";
    if (!std::isnan(r.tol)) os << "tol = " << r.tol << ": ";
    os << r.steps << " steps";
    if (r.method == "alphaflex" && r.steps > 0 && r.ok)
      os << ", Newton " << std::fixed << std::setprecision(2) << static_cast<double>(r.newton_total) / r.steps
         << "/step" << std::defaultfloat;
    os << ", CPU " << std::setprecision(3) << r.cpu << " s";
    if (!r.ok) os << ", FAILED: " << r.failure;
    for (const auto& n : res_.error_names) {
      const auto it = r.errors.find(n);
      if (it != r.errors.end()) os << "; err " << n << " " << sci(it->second);
    }
    for (const auto& [k, v] : r.extra)
      os << "; " << k << " " << (v == std::floor(v) && std::fabs(v) < 1e9 ? std::to_string(static_cast<long>(v)) : sci(v));
    std::cout << os.str() << std::endl;
  }

  // ------------------------------------------------------------------ concurrent runs
  struct ConvergenceRun {
    const SchemeSetting* setting;
    double h;
    bool reference;
    double tol = 0.0;  ///< > 0: an adaptive run (study.tol), first step h
  };

  /// One run on the group communicator `comm`: its row (errors not yet measured: the reference
  /// may be another group's run) and final values. An exception is kept in the outcome, not
  /// thrown: the other groups are still running and meet this one in the gather.
  RunOutcome run_on_group(const ConvergenceRun& run, MPI_Comm comm) {
    RunNeeds needs;
    needs.last_state = spec_.condition_number && !run.reference && run.tol == 0.0;
    return run_measured(*run.setting, run.h, needs, comm, run.tol, [&](const Scene& sc, const RunRecord& rec, RunOutcome& o) {
      if (rec.ok) {
        o.sensor_names = rec.summary.sensor_names;
        o.final_sensors = rec.summary.final_sensors;
        o.final_state = rec.summary.final_state;
      }
      if (needs.last_state && rec.t.size() > 0) {
        const ConditionNumbers c = iteration_matrix_condition(*sc.model, rec.last, o.row.params, run.h, o.row.scaling, comm);
        o.row.extra.emplace_back("cond_2norm", c.two_norm);
        o.row.extra.emplace_back("cond_mumps1", c.mumps_cond1);
        o.row.extra.emplace_back("cond_mumps2", c.mumps_cond2);
      }
    });
  }

  /// The runs on groups of k ranks, each group its share (longest first by step count, t_end/h);
  /// the outcomes in the order of `runs` on every rank. An error a run threw is rethrown on every
  /// rank once all groups are done (the first in run order).
  /// On one node the groups take the runs one at a time, longest first, from a shared counter
  /// (RunGroups::next_task), and rank 0 runs the peers (IDA, Radau) first, while the other groups
  /// take runs: the groups end together whatever the runs and the peers cost. Else each group runs
  /// its share by LPT and rank 0 runs the peers afterwards (convergence()).
  std::vector<RunOutcome> run_concurrently(const std::vector<ConvergenceRun>& runs, int k, double t_end) {
    std::vector<double> cost;
    for (const auto& r : runs) cost.push_back(t_end / r.h);
    return run_tasks(
        cost, k, [&](size_t i, MPI_Comm comm) { return run_on_group(runs[i], comm); }, !runs.empty() && runs[0].reference,
        [&] { run_peers_guarded(t_end); });
  }

  /// Tasks 0 … n−1 of estimated costs `cost` on groups of k ranks; `run_task(i, comm)` runs task i
  /// on the group's communicator and keeps any exception in the outcome. `first_is_reference`:
  /// task 0's failure leaves the others without their reference (a group stops after it).
  /// `rank0_first` (may be empty): what rank 0 runs before its group takes tasks when the groups
  /// share a counter (peers_first_), else nothing (the caller runs it afterwards).
  std::vector<RunOutcome> run_tasks(const std::vector<double>& cost, int k,
                                    const std::function<RunOutcome(size_t, MPI_Comm)>& run_task, bool first_is_reference,
                                    const std::function<void()>& rank0_first = {}) {
    RunGroups groups(comm_, k);
    std::vector<size_t> order(cost.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost[a] > cost[b]; });
    const std::vector<int> group = groups.assign(cost);
    peers_first_ = groups.shares_a_counter();
    if (peers_first_ && rank_ == 0 && rank0_first) rank0_first();
    std::vector<RunOutcome> mine;
    for (size_t n = 0;; ++n) {
      size_t i = 0;
      if (groups.shares_a_counter()) {
        i = static_cast<size_t>(groups.from_leader(groups.leads_group() ? groups.next_task() : 0));
      } else {
        while (n < order.size() && group[order[n]] != groups.group()) ++n;
        i = n < order.size() ? order[n] : order.size();
      }
      if (i >= cost.size()) break;
      if (groups.shares_a_counter()) i = order[i];
      RunOutcome o = run_task(i, groups.group_comm());
      o.task = static_cast<int>(i);
      const bool stop = o.error_code != 0 || (first_is_reference && i == 0 && !o.row.ok);  // the others' errors need the reference
      mine.push_back(std::move(o));
      if (stop) break;
    }
    std::vector<RunOutcome> all(cost.size());
    std::vector<bool> have(cost.size(), false);
    for (const std::string& bytes : groups.allgather(groups.leads_group() ? pack(mine) : std::string()))
      for (RunOutcome& o : unpack(bytes)) {
        have[static_cast<size_t>(o.task)] = true;
        all[static_cast<size_t>(o.task)] = std::move(o);
      }
    for (size_t i = 0; i < all.size(); ++i)
      if (have[i] && all[i].error_code != 0) rethrow(all[i]);
    for (size_t i = 0; i < all.size(); ++i)
      if (!have[i] && !(first_is_reference && !all[0].row.ok))
        throw std::logic_error("study: run " + std::to_string(i) + " of the study has no outcome");
    return all;
  }

  /// Ranks per run for the scene `base` (--ranks-per-run, else the default by its size); sets
  /// run_ranks_ (the CSV's note on CPU times).
  int ranks_per_run(const Scene& base) {
    const int k = opt_.ranks_per_run > 0 ? opt_.ranks_per_run
                                         : default_ranks_per_run(base.model->num_dofs() + base.model->num_multipliers(), size_);
    const std::string problem = ranks_per_run_problem(k, size_);
    if (!problem.empty()) throw InputError(problem);  // the command line checks it first (exit 2)
    run_ranks_ = k;
    return k;
  }

  /// ", N runs at a time on k rank(s) each" for the study's first line ("" with one group).
  std::string groups_note(int k) const {
    std::ostringstream groups;
    if (size_ > k) groups << ", " << size_ / k << " runs at a time on " << k << " rank(s) each";
    return groups.str();
  }

  /// One run of a study on the group communicator `comm`: `measure` turns the run into the row's
  /// extras, final values and history on the group; an exception is kept in the outcome.
  /// `tol` > 0: an adaptive run (scene_for).
  RunOutcome run_measured(const SchemeSetting& st, double h, const RunNeeds& needs, MPI_Comm comm, double tol,
                          const std::function<void(const Scene&, const RunRecord&, RunOutcome&)>& measure) {
    RunOutcome o;
    try {
      Scene sc = scene_for(st, h, "", comm, tol);
      RunRecord rec = run_one(sc, needs, comm);
      o.row = row_for(sc, st, h, rec);
      measure(sc, rec, o);
    } catch (const std::exception& e) {
      o.error_code = exit_code_of(e);
      o.error = e.what();
    }
    return o;
  }

  // ------------------------------------------------------------------ modes
  void convergence() {
    Scene base = scene_for(spec_.settings.front(), spec_.h.front());
    const double t_end = base.settings.t_end;
    const int k = ranks_per_run(base);
    const bool reference_run = spec_.reference.h > 0.0;
    prepare_reference(base, t_end, reference_run);
    say("study " + spec_.name + ": convergence, " + std::to_string(spec_.settings.size()) + " setting(s) x " +
        std::to_string(spec_.h.size()) + " step size(s)" + groups_note(k) + "; reference: " +
        (reference_run ? res_.reference_label + (res_.reference_label.empty() ? "" : "; ") + reference_run_name() + " (with the runs)"
                       : res_.reference_label));

    // The runs: the reference run (if any) first, then setting by setting, h by h (the CSV's order).
    std::vector<ConvergenceRun> runs;
    if (reference_run) runs.push_back({&reference_setting(), spec_.reference.h, true});
    // Per setting the fixed step sizes, then the tolerances of adaptive runs (first step h[0]).
    for (const auto& st : spec_.settings) {
      for (double h : spec_.h) runs.push_back({&st, h, false});
      for (double tol : spec_.tol) runs.push_back({&st, spec_.h.front(), false, tol});
    }
    std::vector<RunOutcome> outcomes = run_concurrently(runs, k, t_end);

    size_t first = 0;
    if (reference_run) {
      const RunOutcome& o = outcomes[first++];
      if (!o.row.ok) throw SolverError("the study's reference run (" + reference_run_name() + ") failed: " + o.row.failure);
      take_reference_run(o.final_state, o.sensor_names, o.final_sensors, o.row.steps, o.row.cpu);
    }
    for (size_t i = first; i < outcomes.size(); ++i) {
      StudyRow& row = outcomes[i].row;
      if (runs[i].tol > 0.0) {
        row.label = runs[i].setting->label + " adaptive";
        row.h = std::numeric_limits<double>::quiet_NaN();
        row.tol = runs[i].tol;
      }
      if (row.ok) {
        const auto& names = outcomes[i].sensor_names;
        for (const auto& s : sensors_) {
          const size_t j = static_cast<size_t>(std::find(names.begin(), names.end(), s) - names.begin());
          row.errors[s] = error_of(outcomes[i].final_sensors[j], ref_.at_end.at(s), spec_.relative_errors);
        }
        // Every run has the base scene's nodes (settings change the solver): its model measures q.
        if (ref_.has_state) state_errors(*base.model, outcomes[i].final_state, ref_.state, spec_.relative_errors, row.errors);
      }
      print_row(row);
      res_.rows.push_back(row);
    }
    if (rank_ == 0) {
      if (!peers_first_) run_peers_guarded(t_end);
      for (const auto& [p, label] : peer_results_) add_peer_row(p, label);
    }
    fit_slopes();
  }

  /// Rank 0 alone: a failing peer must not throw past the collective calls that follow. The peers'
  /// results wait in peer_results_ for the reference (their errors) and their rows' place.
  void run_peers_guarded(double t_end) {
    try {
      run_peers(t_end);
    } catch (const std::exception& e) {
      warn(std::string("the peers stopped: ") + e.what());
    }
  }

  void run_peers(double t_end) {
    const PeerSpec& p = spec_.peers;
    if (p.problem.empty()) return;
    for (double tol : p.ida) {
      peer_results_.emplace_back(andrews_ida(tol, tol, t_end), "IDA");
    }
    if (!p.radau.empty()) {
      const std::string script = std::string(ALPHAFLEX_SOURCE_DIR) + "/scripts/study_radau_andrews.py";
      const std::string out = (fs::path(opt_.outdir) / (spec_.name + "_radau.csv")).string();
      std::string tols;
      for (double t : p.radau) tols += (tols.empty() ? "" : ",") + num(t);
      std::error_code ec;
      if (!fs::is_regular_file(script, ec) || !python_ok()) {
        warn("Radau peer skipped: " + (python_ok() ? script + " not found" : spec_.python + " not found"));
        return;
      }
      const std::string cmd = shell_quote(python()) + " " + shell_quote(script) + " --tolerances " + tols +
                              " --t-end " + num(t_end) + " --out " + shell_quote(out) + (opt_.verbose ? "" : " > /dev/null");
      std::cout.flush();
      const int rc = std::system(cmd.c_str());
      if (rc != 0) {
        warn("Radau peer failed (" + cmd + " returned " + std::to_string(rc) + ")");
        return;
      }
      const MixedTable tab = read_numeric_csv_mixed(out);
      for (const auto& row : tab.rows) peer_results_.emplace_back(radau_result(row), "Radau");
      res_.files.push_back(out);
    }
  }

  // The Radau CSV has text columns (method, message): read them as strings.
  struct MixedTable {
    std::vector<std::string> names;
    std::vector<std::vector<std::string>> rows;
  };
  static MixedTable read_numeric_csv_mixed(const std::string& path) {
    MixedTable t;
    std::ifstream in(path);
    std::string line;
    if (!std::getline(in, line)) return t;
    std::stringstream hs(line);
    for (std::string c; std::getline(hs, c, ',');) t.names.push_back(c);
    while (std::getline(in, line)) {
      std::vector<std::string> row;
      std::stringstream ls(line);
      for (std::string c; std::getline(ls, c, ',');) row.push_back(c);
      if (row.size() == t.names.size()) t.rows.push_back(row);
    }
    return t;
  }

  static PeerResult radau_result(const std::vector<std::string>& row) {
    // Columns of scripts/study_radau_andrews.py: method,rtol,atol,ok,cpu,steps,nfev,njev,nlu,message,values...
    PeerResult r;
    static const std::vector<std::string> head{"method", "rtol", "atol", "ok", "cpu", "steps", "nfev", "njev", "nlu", "message"};
    r.method = row[0];
    r.rtol = std::stod(row[1]);
    r.atol = std::stod(row[2]);
    r.ok = row[3] == "1";
    r.cpu = std::stod(row[4]);
    r.steps = std::stol(row[5]);
    r.residual_evals = std::stol(row[6]);
    r.jacobian_evals = std::stol(row[7]);
    r.failure = r.ok ? "" : row[9];
    const std::vector<std::string> names{"beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon", "lambda1",
                                         "lambda2", "lambda3", "lambda4", "lambda5", "lambda6"};
    for (size_t k = 0; k < names.size() && head.size() + k < row.size(); ++k) {
      r.names.push_back(names[k]);
      r.values.push_back(std::stod(row[head.size() + k]));
    }
    return r;
  }

  void add_peer_row(const PeerResult& p, const std::string& label) {
    StudyRow row;
    row.method = p.method;
    row.label = label;
    row.tol = p.rtol;
    row.t_end = spec_.t_end;
    row.ok = p.ok;
    row.failure = p.failure;
    row.steps = p.steps;
    row.cpu = p.cpu;
    row.extra.emplace_back("residual_evals", static_cast<double>(p.residual_evals));
    row.extra.emplace_back("jacobian_evals", static_cast<double>(p.jacobian_evals));
    if (p.ok)
      for (const auto& s : sensors_)
        for (size_t k = 0; k < p.names.size(); ++k)
          if (p.names[k] == s) row.errors[s] = error_of(p.values[k], ref_.at_end.at(s), spec_.relative_errors);
    print_row(row);
    res_.rows.push_back(row);
  }

  void fit_slopes() {
    for (const auto& st : spec_.settings)
      for (const auto& e : res_.error_names) {
        std::vector<double> hs, es;
        for (const auto& r : res_.rows)
          if (r.method == "alphaflex" && r.label == st.label && r.ok && r.errors.count(e)) {
            hs.push_back(r.h);
            es.push_back(r.errors.at(e));
          }
        if (hs.size() < 2) continue;
        // Errors at round-off or at the reference's accuracy are left out of the fit (measures.hpp):
        // a slope through them is noise, and the log, the CSV and the charts say so instead.
        const SlopeFit fit = fit_convergence(hs, es, spec_.relative_errors ? kRoundoff : 0.0);
        res_.slopes[st.label][e] = fit.slope;
        res_.slope_fits[st.label][e] = fit;
      }
    if (!opt_.verbose || rank_ != 0 || res_.slopes.empty()) return;
    std::cout << "observed orders (least-squares slope of log error vs log h over the h whose errors are above "
                 "round-off and the reference's accuracy; theory: 2 for generalized-alpha with rho_inf < 1, eq. 38):\n";
    for (const auto& st : spec_.settings) {
      if (!res_.slope_fits.count(st.label)) continue;
      std::ostringstream os;
      os << "  " << st.label << ":";
      const auto& fits = res_.slope_fits[st.label];
      for (const auto& e : res_.error_names) {
        const auto it = fits.find(e);
        if (it == fits.end()) continue;
        // A plain slope on the label's line; a slope with a floor, or none, on a line of its own.
        if (it->second.at_floor == 0 && !std::isnan(it->second.slope)) os << " " << e << " " << it->second.describe();
      }
      for (const auto& e : res_.error_names) {
        const auto it = fits.find(e);
        if (it != fits.end() && (it->second.at_floor > 0 || std::isnan(it->second.slope)))
          os << "\n    " << e << ": " << it->second.describe();
      }
      std::cout << os.str() << "\n";
    }
    std::cout.flush();
  }

  /// Relative errors at or below this are round-off (measures.hpp, fit_convergence): ~4500 ε.
  static constexpr double kRoundoff = 1e-12;

  /// The runs of oscillation and blow_up: h by h, setting by setting (oscillation) or setting by
  /// setting, h by h (blow_up), the CSV's order.
  struct SettingRun {
    const SchemeSetting* setting;
    double h;
  };

  /// The runs of a mode whose rows come from each run's histories, on groups of k ranks (the
  /// convergence study's run_tasks); `measure` runs on the group of each.
  std::vector<RunOutcome> run_settings(const std::vector<SettingRun>& runs, int k, double t_end, const RunNeeds& needs,
                                       const std::function<void(const Scene&, const RunRecord&, RunOutcome&)>& measure) {
    std::vector<double> cost;
    for (const auto& r : runs) cost.push_back(t_end / r.h);
    return run_tasks(cost, k, [&](size_t i, MPI_Comm comm) {
      return run_measured(*runs[i].setting, runs[i].h, needs, comm, 0.0, measure);
    }, false);
  }

  /// Rank 0 keeps a run's history (gathered from its group) for NAME_history.csv.
  void keep_history(const std::string& label, double h, const RunOutcome& o, const std::vector<std::string>& names) {
    if (rank_ != 0) return;
    history_names_ = names;
    histories_.push_back(History{label, h, o.history_t, o.history});
  }

  void oscillation() {
    Scene base = scene_for(spec_.settings.front(), spec_.h.front());
    const double t_end = base.settings.t_end;
    const int k = ranks_per_run(base);
    if (!spec_.reference.file.empty() || spec_.reference.h > 0.0) prepare_reference(base, t_end);
    else prepare_sensors_only(base);
    say("study " + spec_.name + ": oscillation, " + std::to_string(spec_.settings.size()) + " setting(s) x " +
        std::to_string(spec_.h.size()) + " step size(s)" + groups_note(k));
    std::vector<SettingRun> runs;
    for (double h : spec_.h)
      for (const auto& st : spec_.settings) runs.push_back({&st, h});
    RunNeeds needs;
    needs.lambda = true;
    needs.sensors = true;
    // On the run's group: the measures of each sensor and of the multipliers; the ratios to the
    // first setting's at the same h (tv_ratio_*) once every run is back.
    std::vector<RunOutcome> outcomes = run_settings(runs, k, t_end, needs, [&](const Scene& sc, const RunRecord& rec, RunOutcome& o) {
      StudyRow& row = o.row;
      const double span = rec.t.empty() ? 0.0 : rec.t.back() - rec.t.front();
      const auto& names = sc.model->sensors();
      std::vector<size_t> idx;
      for (const auto& s : sensors_) {
        size_t j = 0;
        while (names[j].name != s) ++j;
        idx.push_back(j);
        std::vector<double> x;
        for (const auto& v : rec.sensors) x.push_back(v[j]);
        row.extra.emplace_back("tv_" + s, span > 0 ? total_variation(x) / span : kNaN);
        row.extra.emplace_back("d2_" + s, rms_second_difference(x));
        if (ref_.series.count(s)) row.extra.emplace_back("rmserr_" + s, rms_error_against_series(rec.t, x, s));
        row.extra.emplace_back("tv_ratio_" + s, kNaN);
      }
      // The multipliers as a whole: the largest total variation rate over their components.
      double tvl = 0.0, d2l = 0.0;
      const int nm = rec.lambda.empty() ? 0 : static_cast<int>(rec.lambda.front().size());
      for (int j = 0; j < nm; ++j) {
        std::vector<double> x;
        for (const auto& l : rec.lambda) x.push_back(l[j]);
        tvl = std::max(tvl, span > 0 ? total_variation(x) / span : kNaN);
        d2l = std::max(d2l, rms_second_difference(x));
      }
      row.extra.emplace_back("tv_lambda_max", tvl);
      row.extra.emplace_back("d2_lambda_max", d2l);
      row.extra.emplace_back("tv_ratio_lambda_max", kNaN);
      o.history_t = rec.t;
      for (const auto& v : rec.sensors) {
        std::vector<double> kept;
        for (size_t j : idx) kept.push_back(v[j]);
        o.history.push_back(std::move(kept));
      }
    });
    auto extra = [](const StudyRow& r, const std::string& key) {
      for (const auto& [k, v] : r.extra)
        if (k == key) return v;
      return kNaN;
    };
    for (size_t i = 0; i < outcomes.size(); ++i) {
      // The first setting's run at this h: the settings of one h are consecutive.
      const StudyRow& first = outcomes[i - i % spec_.settings.size()].row;
      StudyRow& row = outcomes[i].row;
      for (auto& [key, v] : row.extra)
        if (key.rfind("tv_ratio_", 0) == 0) {
          const std::string tv = "tv_" + key.substr(9);
          v = extra(row, tv) / extra(first, tv);
        }
      print_row(row);
      res_.rows.push_back(row);
      keep_history(runs[i].setting->label, runs[i].h, outcomes[i], sensors_);
    }
  }

  double rms_error_against_series(const std::vector<double>& t, const std::vector<double>& x, const std::string& s) const {
    // At the run's output times that are also rows of the reference file (no interpolation).
    const auto& rt = ref_.times;
    const auto& rv = ref_.series.at(s);
    double sum = 0.0;
    int n = 0;
    size_t j = 0;
    for (size_t i = 0; i < t.size(); ++i) {
      while (j < rt.size() && rt[j] < t[i] - 1e-9 * std::max(1.0, std::fabs(t[i]))) ++j;
      if (j < rt.size() && std::fabs(rt[j] - t[i]) <= 1e-9 * std::max(1.0, std::fabs(t[i]))) {
        sum += (x[i] - rv[j]) * (x[i] - rv[j]);
        ++n;
      }
    }
    return n ? std::sqrt(sum / n) : kNaN;
  }

  void prepare_sensors_only(const Scene& base) {
    std::vector<std::string> names;
    for (const auto& sn : base.model->sensors()) names.push_back(sn.name);
    if (spec_.sensors.empty()) {
      sensors_ = names;
    } else {
      for (const auto& s : spec_.sensors)
        if (std::find(names.begin(), names.end(), s) == names.end())
          throw InputError(spec_.file + ": study.sensors: the scene has no sensor named '" + s + "'");
      sensors_ = spec_.sensors;
    }
    res_.reference_label = "none (stability measures need no reference)";
  }

  // Time histories for the charts (NAME_history.csv): label, h, step, t, then the sensors.
  struct History {
    std::string label;
    double h;
    std::vector<double> t;
    std::vector<std::vector<double>> values;  // per step
  };
  std::vector<History> histories_;
  std::vector<std::string> history_names_;
  void blow_up() {
    Scene base = scene_for(spec_.settings.front(), spec_.h.front());
    const int k = ranks_per_run(base);
    prepare_sensors_only(base);
    say("study " + spec_.name + ": blow_up, " + std::to_string(spec_.settings.size()) + " setting(s) x " +
        std::to_string(spec_.h.size()) + " step size(s)" + groups_note(k));
    std::vector<SettingRun> runs;
    for (const auto& st : spec_.settings)
      for (double h : spec_.h) runs.push_back({&st, h});
    RunNeeds needs;
    needs.lambda = true;
    std::vector<RunOutcome> outcomes = run_settings(runs, k, base.settings.t_end, needs, [&](const Scene&, const RunRecord& rec, RunOutcome& o) {
      StudyRow& row = o.row;
      // Growth measure: g_n = ‖λ_{n+1} − 2λ_n + λ_{n−1}‖∞, O(h²) on a smooth solution, dominated
      // by a parasitic root ζ of ϱ or σ once |ζ| > 1 (it then grows like |ζ|ⁿ).
      std::vector<double> g, lam;
      for (size_t n = 1; n + 1 < rec.lambda.size(); ++n)
        g.push_back(inf_norm(rec.lambda[n + 1] - 2.0 * rec.lambda[n] + rec.lambda[n - 1]));
      for (const auto& l : rec.lambda) lam.push_back(inf_norm(l));
      const AlphaParameters& p = row.params;
      double rs = 0.0;
      for (const auto& z : sigma_roots(p)) rs = std::max(rs, std::abs(z));
      // Linear theory holds while the parasitic mode is small against λ itself: its scale is the
      // median of ‖λ‖∞ over the first tenth of the run.
      double scale = std::numeric_limits<double>::infinity();
      if (lam.size() >= 10) {
        std::vector<double> head(lam.begin(), lam.begin() + static_cast<long>(lam.size() / 10));
        std::nth_element(head.begin(), head.begin() + static_cast<long>(head.size() / 2), head.end());
        scale = head[head.size() / 2];
      }
      row.extra.emplace_back("growth_measured", geometric_growth(g, scale));
      row.extra.emplace_back("growth_predicted", predicted_growth(p));
      row.extra.emplace_back("root_rho", std::abs(rho_roots(p)[1]));
      row.extra.emplace_back("root_sigma", rs);
      row.extra.emplace_back("t_last", rec.t.empty() ? kNaN : rec.t.back());
      row.extra.emplace_back("lambda_inf_max", lam.empty() ? kNaN : *std::max_element(lam.begin(), lam.end()));
      o.history_t = rec.t;
      for (size_t n = 0; n < rec.t.size(); ++n) {
        const double gn = (n >= 1 && n + 1 < rec.t.size() && n - 1 < g.size()) ? g[n - 1] : kNaN;
        o.history.push_back({lam[n], gn});
      }
    });
    for (size_t i = 0; i < outcomes.size(); ++i) {
      print_row(outcomes[i].row);
      res_.rows.push_back(outcomes[i].row);
      keep_history(runs[i].setting->label, runs[i].h, outcomes[i], {"lambda_inf", "d2_lambda_inf"});
    }
  }

  /// The setting of a fidelity variant: the study's one setting with the variant's overrides.
  SchemeSetting variant_setting(const ModelVariant& v) const {
    SchemeSetting vs = spec_.settings.front();
    vs.overrides.insert(vs.overrides.end(), v.overrides.begin(), v.overrides.end());
    vs.where = v.where;
    vs.label = v.label;
    return vs;
  }

  /// One fidelity variant on the group communicator `comm`: its row, its sensors' histories at the
  /// output times (the rows NAME.csv would have: every step, or output.sensors_dt) and the strain
  /// energy of its flexible parts. A variant that cannot be built or whose run fails is a failed
  /// row with the message.
  RunOutcome fidelity_run(const ModelVariant& v, double h, MPI_Comm comm) {
    RunOutcome o;
    const SchemeSetting vs = variant_setting(v);
    o.row.label = v.label;
    try {
      Scene sc = scene_for(vs, h, v.scene, comm);
      const std::vector<FlexiblePart> parts = flexible_parts(*sc.model);
      RunNeeds needs;
      needs.parts = &parts;
      needs.sensors = true;
      RunRecord rec = run_one(sc, needs, comm);
      o.row = row_for(sc, vs, sc.settings.h, rec);
      o.row.extra.emplace_back("unknowns", rec.summary.unknowns > 0 ? rec.summary.unknowns
                                                                     : sc.model->num_dofs() + sc.model->num_multipliers());
      for (const auto& sn : sc.model->sensors()) o.sensor_names.push_back(sn.name);
      o.histories.resize(o.sensor_names.size());
      SensorSchedule rows(true, sc.settings.sensors_dt, rec.t.empty() ? 0.0 : rec.t.front(), true);
      for (size_t n = 0; n < rec.t.size(); ++n) {
        if (!rows.due(rec.t[n], n + 1 == rec.t.size())) continue;
        o.times.push_back(rec.t[n]);
        for (size_t k = 0; k < o.histories.size(); ++k) o.histories[k].push_back(rec.sensors[n][k]);
      }
      if (rec.ok) o.energy = energy_rows(v.label, parts, rec.t, rec.energy);
    } catch (const InputError& e) {
      o.row.ok = false;
      o.row.t_end = kNaN;
      o.row.failure = e.what();
    } catch (const SolverError& e) {
      o.row.ok = false;
      o.row.failure = e.what();
    } catch (const std::exception& e) {
      o.error_code = exit_code_of(e);
      o.error = e.what();
    }
    return o;
  }

  /// Strain energy per part: time average (trapezoid over the steps), peak, shares.
  static std::vector<EnergyRow> energy_rows(const std::string& variant, const std::vector<FlexiblePart>& parts,
                                            const std::vector<double>& t, const std::vector<std::vector<double>>& energy) {
    std::vector<EnergyRow> out;
    const size_t np = parts.size();
    if (t.size() < 2) return out;
    std::vector<double> mean(np, 0.0), peak(np, 0.0);
    size_t ipeak = 0;
    double total_peak = -1.0;
    for (size_t n = 0; n < t.size(); ++n) {
      double total = 0.0;
      for (size_t p = 0; p < np; ++p) {
        peak[p] = std::max(peak[p], energy[n][p]);
        total += energy[n][p];
        if (n > 0) mean[p] += 0.5 * (energy[n][p] + energy[n - 1][p]) * (t[n] - t[n - 1]);
      }
      if (total > total_peak) {
        total_peak = total;
        ipeak = n;
      }
    }
    const double span = t.back() - t.front();
    double sum_mean = 0.0;
    for (size_t p = 0; p < np; ++p) sum_mean += (mean[p] /= span);
    for (size_t p = 0; p < np; ++p) {
      EnergyRow e;
      e.variant = variant;
      e.part = parts[p].name;
      e.kind = parts[p].kind;
      e.elements = static_cast<int>(parts[p].elements.size());
      e.mean = mean[p];
      e.peak = peak[p];
      e.share_mean = sum_mean > 0 ? mean[p] / sum_mean : kNaN;
      e.share_peak = total_peak > 0 ? energy[ipeak][p] / total_peak : kNaN;
      out.push_back(e);
    }
    return out;
  }

  /// Load levels of a fidelity study: one per `study.load.scale`, or one (the scene's loads).
  size_t load_levels() const { return spec_.load.given() ? spec_.load.scales.size() : 1; }

  /// Variant `v` at load level `level`: its overrides and then the load axis's (the keys times the
  /// level's scale, fidelity_ladder.hpp), applied last.
  ModelVariant at_load(const ModelVariant& v, size_t level) const {
    if (!spec_.load.given()) return v;
    ModelVariant w = v;
    const std::vector<std::string> o = load_overrides(spec_.load, spec_.load.scales[level]);
    w.overrides.insert(w.overrides.end(), o.begin(), o.end());
    return w;
  }

  void fidelity() {
    const double h = spec_.h.empty() ? 0.0 : spec_.h.front();
    const int k = opt_.ranks_per_run > 0 ? opt_.ranks_per_run : default_ranks_per_run(reference_unknowns_, size_);
    const std::string problem = ranks_per_run_problem(k, size_);
    if (!problem.empty()) throw InputError(problem);  // the command line checks it first (exit 2)
    run_ranks_ = k;
    std::ostringstream groups;
    if (size_ > k) groups << ", " << size_ / k << " runs at a time on " << k << " rank(s) each";
    const size_t nv = spec_.variants.size(), levels = load_levels();
    say("study " + spec_.name + ": fidelity, " + std::to_string(nv) +
        (spec_.ladder ? " rungs of the ladder" : " model variants") +
        (spec_.load.given() ? " at " + std::to_string(levels) + " load scales" : std::string()) + groups.str());
    // Cost estimate for the order of the runs: the reference (the most detailed model) first.
    // Task i is variant i % nv at load level i / nv.
    std::vector<double> cost;
    size_t iref = 0;
    for (size_t l = 0; l < levels; ++l)
      for (size_t i = 0; i < nv; ++i) {
        const bool is_ref = spec_.variants[i].label == spec_.reference_variant;
        if (is_ref) iref = i;
        cost.push_back(is_ref ? 2.0 : 1.0);
      }
    std::vector<RunOutcome> runs = run_tasks(
        cost, k, [&](size_t i, MPI_Comm comm) { return fidelity_run(at_load(spec_.variants[i % nv], i / nv), h, comm); },
        false);
    const ModelVariant& refv = spec_.variants[iref];
    res_.reference_label = "model variant '" + refv.label + "' (" + refv.scene + ")" +
                           (spec_.load.given() ? " at the same load scale" : std::string());
    // Sensors: those asked (each in the reference), or those the reference and every variant that
    // ran have (a rigid scene may lack a flexible part's sensors).
    if (!spec_.sensors.empty()) {
      sensors_ = spec_.sensors;
    } else {
      const RunOutcome* ref = nullptr;
      for (size_t l = 0; l < levels && !ref; ++l)
        if (runs[l * nv + iref].row.ok) ref = &runs[l * nv + iref];
      if (ref)
        for (const auto& n : ref->sensor_names) {
          bool all = true;
          for (const auto& r : runs) all = all && (!r.row.ok || std::count(r.sensor_names.begin(), r.sensor_names.end(), n));
          if (all) sensors_.push_back(n);
        }
    }
    res_.error_names = sensors_;
    res_.error_names.push_back("max");
    for (size_t l = 0; l < levels; ++l) {
      std::vector<RunOutcome*> level;
      for (size_t i = 0; i < nv; ++i) level.push_back(&runs[l * nv + i]);
      measure_level(level, iref, l);
    }
    if (spec_.load.given()) {
      res_.load_changes = load_change_points(spec_.load.scales, res_.load_lightest);
      for (const auto& c : res_.load_changes) say("load axis: " + c);
    }
  }

  /// The errors of one load level's variants against its reference variant `iref`, the
  /// recommendation, the rows.
  void measure_level(const std::vector<RunOutcome*>& runs, size_t iref, size_t level) {
    const bool axis = spec_.load.given();
    const double scale = axis ? spec_.load.scales[level] : kNaN;
    const std::string at = axis ? " at load scale " + sig6(scale) : std::string();
    const RunOutcome& ref = *runs[iref];
    if (!ref.row.ok && fatal_.empty())
      fatal_ = "the reference variant '" + ref.row.label + "' failed" + at + ", so no error can be measured: " + ref.row.failure;
    const bool relative = spec_.relative_errors;
    auto history = [](const RunOutcome& r, const std::string& s) -> const std::vector<double>* {
      const auto it = std::find(r.sensor_names.begin(), r.sensor_names.end(), s);
      return it == r.sensor_names.end() ? nullptr : &r.histories[static_cast<size_t>(it - r.sensor_names.begin())];
    };
    // errors: largest_range: one divisor, the largest range of the study's sensors in the reference.
    double common_range = 0.0;
    if (spec_.largest_range && ref.row.ok)
      for (const auto& s : sensors_)
        if (const std::vector<double>* xr = history(ref, s)) common_range = std::max(common_range, history_range(*xr));
    for (size_t i = 0; i < runs.size(); ++i) {
      StudyRow& row = runs[i]->row;
      const RunOutcome& r = *runs[i];
      row.load_scale = scale;
      if (row.ok && ref.row.ok) {
        // The error: per sensor max over the reference's output times of |x − x_ref| over the
        // sensor's range in the reference run (fidelity_ladder.hpp), then the max over the sensors.
        std::string why;
        const std::vector<size_t> times = matching_times(r.times, ref.times, why);
        double worst = 0.0;
        for (const auto& s : sensors_) {
          const std::vector<double>* x = history(r, s);
          if (!x) {
            why = "the variant's scene has no sensor named '" + s + "' (study.sensors)";
            break;
          }
          if (times.empty()) break;
          std::vector<double> xs;
          for (size_t j : times) xs.push_back((*x)[j]);
          const std::vector<double>& xr = *history(ref, s);
          const double e = spec_.largest_range
                               ? history_error(xs, xr, false) / (common_range > 0.0 ? common_range : 1.0)
                               : history_error(xs, xr, relative);
          row.errors[s] = e;
          worst = std::isnan(e) || std::isnan(worst) ? kNaN : std::max(worst, e);
          if (relative && !(history_range(xr) > 0.0) && i == iref)
            warn("sensor '" + s + "' is constant in the reference run" + at + ": its error is the absolute difference");
          if (spec_.largest_range && !(common_range > 0.0) && i == iref && s == sensors_.front())
            warn("every sensor is constant in the reference run" + at + ": the errors are absolute differences");
        }
        if (why.empty()) {
          row.errors["max"] = worst;
        } else {
          row.errors.clear();
          row.ok = false;
          row.failure = "no error measured: " + why;
        }
      }
      row.extra.emplace_back("cpu_ratio", r.row.steps > 0 && ref.row.ok && ref.row.cpu > 0.0 ? r.row.cpu / ref.row.cpu : kNaN);
      for (auto e : r.energy) {
        if (axis) e.variant += " at load scale " + sig6(scale);
        res_.energy.push_back(e);
      }
    }
    std::string lightest;
    if (spec_.tolerance > 0.0 && ref.row.ok) {
      std::vector<Rung> rungs;
      for (const auto* r : runs) rungs.push_back({r->row.label, r->row.ok, r->row.cpu, r->row.ok ? r->row.errors.at("max") : kNaN});
      const Recommendation rec = recommend(
          rungs, spec_.tolerance,
          spec_.largest_range ? "max error over the sensors, relative to the largest sensor range in the full run"
          : relative          ? "max error over the sensors, relative to each sensor's range in the full run"
                              : "max absolute error over the sensors");
      for (size_t i = 0; i < runs.size(); ++i) {
        runs[i]->row.extra.emplace_back("acceptable", rec.acceptable[i] ? 1.0 : 0.0);
        runs[i]->row.extra.emplace_back("recommended", static_cast<int>(i) == rec.lightest ? 1.0 : 0.0);
      }
      if (axis) {
        res_.load_recommendations.push_back(rec.text);
        lightest = rec.first_acceptable >= 0 ? runs[static_cast<size_t>(rec.first_acceptable)]->row.label : "";
      } else {
        res_.recommendation = rec.text;
        res_.recommended = rec.lightest >= 0 ? runs[static_cast<size_t>(rec.lightest)]->row.label : "";
        res_.acceptable_from = rec.acceptable_from >= 0 ? runs[static_cast<size_t>(rec.acceptable_from)]->row.label : "";
      }
    } else if (axis) {
      res_.load_recommendations.push_back("");
    }
    if (axis) {
      res_.load_scales.push_back(scale);
      res_.load_lightest.push_back(lightest);
      say("load scale " + sig6(scale) + ":");
    }
    for (const auto* r : runs) {
      print_row(r->row);
      if (opt_.verbose && rank_ == 0)
        for (const auto& e : r->energy)
          std::cout << "      strain energy of " << e.kind << " '" << e.part << "' (" << e.elements
                    << " elements): mean " << sci(e.mean) << " J, peak " << sci(e.peak) << " J, share "
                    << std::fixed << std::setprecision(1) << 100.0 * e.share_mean << " % of the mean, "
                    << 100.0 * e.share_peak << " % at the peak" << std::defaultfloat << std::endl;
      res_.rows.push_back(r->row);
    }
    if (!res_.recommendation.empty()) say("recommendation: " + res_.recommendation);
    if (axis && !res_.load_recommendations.back().empty())
      say("recommendation at load scale " + sig6(scale) + ": " + res_.load_recommendations.back());
  }

  // ------------------------------------------------------------------ output
  void warn(const std::string& w) {
    res_.warnings.push_back(w);
    if (rank_ == 0) std::cerr << "alphaflex study: warning: " << w << std::endl;
  }
  bool python_ok() const {
    std::error_code ec;
    return fs::exists(spec_.python, ec) || spec_.python.find('/') == std::string::npos;
  }
  std::string python() const { return spec_.python; }

  std::string csv_path(const std::string& suffix) const {
    return (fs::path(opt_.outdir) / (spec_.name + suffix)).string();
  }

  void write_outputs() {
    int ok = 1;
    std::string err;
    if (rank_ == 0) {
      try {
        write_csv();
        if (!histories_.empty()) write_history();
        if (!res_.slope_fits.empty()) write_slopes();
        if (!res_.energy.empty()) write_energy();
      } catch (const std::exception& e) {
        ok = 0;
        err = e.what();
      }
    }
    MPI_Bcast(&ok, 1, MPI_INT, 0, comm_);
    if (!ok) throw OutputError(err.empty() ? "cannot write the study's files (see rank 0)" : err);
    if (spec_.plots && opt_.plots) {
      const int parts = chart_parts();
      if (rank_ < parts) plot(parts);
    }
    wait_asleep(comm_);  // the ranks without charts (or fewer) must not spin while the others draw
  }

  static std::string field(double x) { return std::isnan(x) ? "" : num(x); }

  void write_csv() {
    const std::string path = csv_path("_study.csv");
    std::ofstream f(path);
    if (!f) throw OutputError(path + ": cannot write");
    f << "# alphaflex study " << spec_.name << ": mode " << mode_name(spec_.mode) << ", scene " << spec_.scene
      << ", study " << spec_.file << "\n";
    f << "# reference: " << res_.reference_label << "\n";
    if (spec_.mode != StudyMode::Fidelity)
      f << "# errors: " << (spec_.relative_errors ? "relative" : "absolute")
        << " at t_end (err_q, err_v, err_lambda: infinity norms of the state against the reference run)\n";
    if (spec_.mode == StudyMode::Fidelity)
      f << "# fidelity errors: per sensor the max over the reference's output times of |variant - reference|"
        << (spec_.relative_errors ? " / the sensor's range (max - min) in the reference run"
            : spec_.largest_range ? " / the largest range (max - min) of the study's sensors in the reference run"
                                  : "")
        << "; err_max: the max over the sensors\n";
    if (!res_.recommendation.empty()) f << "# recommendation: " << res_.recommendation << "\n";
    for (size_t l = 0; l < res_.load_recommendations.size(); ++l)
      if (!res_.load_recommendations[l].empty())
        f << "# recommendation at load scale " << sig6(res_.load_scales[l]) << ": " << res_.load_recommendations[l] << "\n";
    if (spec_.load.given()) {
      std::string keys;
      for (const auto& k : spec_.load.keys) keys += (keys.empty() ? "" : ", ") + k;
      f << "# load axis: every rung at each load_scale, the scene's " << keys
        << " multiplied by it; errors against the full rung at the same scale\n";
      for (const auto& c : res_.load_changes) f << "# load axis: " << c << "\n";
    }
    f << "# cpu: process CPU time (s) of each run, summed over its " << (run_ranks_ > 0 ? run_ranks_ : size_)
      << " MPI rank(s); wall: elapsed (s)\n";
    std::vector<std::string> extras;
    for (const auto& r : res_.rows)
      for (const auto& [k, v] : r.extra)
        if (std::find(extras.begin(), extras.end(), k) == extras.end()) extras.push_back(k);
    const bool axis = spec_.load.given();
    f << "mode,method,label," << (axis ? "load_scale," : "") << "scheme,rho_inf,alpha_m,alpha_f,beta,gamma,scaling,h,tol,t_end,status,steps,newton_total,"
         "newton_mean,newton_max,cpu,cpu_per_step,wall";
    for (const auto& e : res_.error_names) f << ",err_" << e;
    for (const auto& e : extras) f << "," << e;
    f << ",failure\n";
    for (const auto& r : res_.rows) {
      const bool ours = r.method == "alphaflex";
      f << mode_name(spec_.mode) << "," << r.method << "," << r.label << ",";
      if (axis) f << (std::isnan(r.load_scale) ? std::string() : sig6(r.load_scale)) << ",";
      if (ours && !std::isnan(r.t_end))  // a variant that could not be built has no scheme (t_end NaN)
        f << r.params.scheme << "," << sig6(r.params.rho_infinity()) << "," << num(r.params.alpha_m) << ","
          << num(r.params.alpha_f) << "," << num(r.params.beta) << "," << num(r.params.gamma) << ","
          << (r.scaling ? "on" : "off");
      else
        f << ",,,,,,";
      f << "," << field(r.h) << "," << field(r.tol) << "," << field(r.t_end) << "," << (r.ok ? "ok" : "failed") << ","
        << r.steps << "," << (ours ? std::to_string(r.newton_total) : "") << ","
        << (ours && r.steps > 0 ? num(static_cast<double>(r.newton_total) / r.steps) : "") << ","
        << (ours ? std::to_string(r.newton_max) : "") << "," << num(r.cpu) << ","
        << (r.steps > 0 ? num(r.cpu / r.steps) : "") << "," << (ours ? num(r.wall) : "");
      for (const auto& e : res_.error_names) f << "," << (r.errors.count(e) ? field(r.errors.at(e)) : "");
      for (const auto& e : extras) f << "," << field(r.get(e));
      std::string fail = r.failure;
      for (char& c : fail)
        if (c == ',' || c == '\n' || c == '"') c = ';';
      f << "," << fail << "\n";
    }
    res_.files.push_back(path);
  }

  /// NAME_slopes.csv: the fitted orders of a convergence study with what they mean (the log's
  /// lines; scripts/study_plots.py puts them on the chart).
  void write_slopes() {
    const std::string path = csv_path("_slopes.csv");
    std::ofstream f(path);
    if (!f) throw OutputError(path + ": cannot write");
    f << "label,error,slope,points,at_floor,roundoff,floor,h_floor,meaning\n";
    for (const auto& st : spec_.settings) {
      if (!res_.slope_fits.count(st.label)) continue;
      for (const auto& e : res_.error_names) {
        const auto it = res_.slope_fits[st.label].find(e);
        if (it == res_.slope_fits[st.label].end()) continue;
        const SlopeFit& k = it->second;
        std::string meaning = k.describe();
        for (char& c : meaning)
          if (c == ',') c = ';';
        f << st.label << "," << e << "," << field(k.slope) << "," << k.points << "," << k.at_floor << ","
          << (k.roundoff ? "yes" : "no") << "," << field(k.at_floor ? k.floor : std::nan("")) << ","
          << field(k.at_floor ? k.h_floor : std::nan("")) << "," << meaning << "\n";
      }
    }
    res_.files.push_back(path);
  }

  void write_history() {
    const std::string path = csv_path("_history.csv");
    std::ofstream f(path);
    f << "label,h,step,t";
    for (const auto& n : history_names_) f << "," << n;
    f << "\n";
    for (const auto& hi : histories_)
      for (size_t n = 0; n < hi.t.size(); ++n) {
        f << hi.label << "," << num(hi.h) << "," << n << "," << num(hi.t[n]);
        for (double v : hi.values[n]) f << "," << field(v);
        f << "\n";
      }
    res_.files.push_back(path);
  }

  void write_energy() {
    const std::string path = csv_path("_energy.csv");
    std::ofstream f(path);
    f << "variant,part,kind,elements,mean_energy,peak_energy,share_mean,share_at_peak\n";
    for (const auto& e : res_.energy)
      f << e.variant << "," << e.part << "," << e.kind << "," << e.elements << "," << num(e.mean) << "," << num(e.peak)
        << "," << field(e.share_mean) << "," << field(e.share_peak) << "\n";
    res_.files.push_back(path);
  }

  /// How many ranks draw the charts: a convergence study has three or four charts of ~1 s of CPU
  /// each, as much as all the runs of a small study (docs/performance.md, "Studies on several
  /// ranks"); with the default script, on one node (every rank sees the CSV rank 0 has just
  /// written), up to three ranks each draw every N-th chart (study_plots.py --part r/N).
  int chart_parts() const {
    if (spec_.mode != StudyMode::Convergence || !spec_.plot_script.empty() || size_ == 1) return 1;
    MPI_Comm node;
    MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    int node_size = 0;
    MPI_Comm_size(node, &node_size);
    MPI_Comm_free(&node);
    int one_node = node_size == size_ ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &one_node, 1, MPI_INT, MPI_MIN, comm_);
    return one_node ? std::min(size_, 3) : 1;
  }

  /// Rank r < parts draws its part of the charts (all of them with one part).
  void plot(int parts) {
    const std::string script =
        spec_.plot_script.empty() ? std::string(ALPHAFLEX_SOURCE_DIR) + "/scripts/study_plots.py" : spec_.plot_script;
    std::error_code ec;
    if (!fs::is_regular_file(script, ec)) {
      warn("no charts: the plotting script " + script + " is not there (the CSV is written)");
      return;
    }
    if (!python_ok()) {
      warn("no charts: " + spec_.python + " not found (study.python)");
      return;
    }
    const std::string part = parts > 1 ? " --part " + std::to_string(rank_) + "/" + std::to_string(parts) : "";
    const std::string cmd = shell_quote(python()) + " " + shell_quote(script) + " " + shell_quote(csv_path("_study.csv")) +
                            part + (opt_.verbose ? "" : " > /dev/null");
    std::cout.flush();
    const int rc = std::system(cmd.c_str());
    if (rc != 0) {
      const std::string w = "the plotting script failed (" + cmd + " returned " + std::to_string(rc) + "); the CSV is written";
      if (rank_ == 0) warn(w);
      else std::cerr << "alphaflex study: warning (rank " << rank_ << "): " << w << std::endl;
    } else if (opt_.verbose && rank_ == 0) {
      std::cout << "charts: " << opt_.outdir << "/" << spec_.name << "_*.png" << std::endl;
    }
  }

  const StudySpec& spec_;
  const StudyOptions& opt_;
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  StudyResult res_;
  Reference ref_;
  std::set<std::string> file_values_;          ///< sensors whose reference value is the file's
  std::vector<std::string> reference_parts_;   ///< what the reference label lists
  int run_ranks_ = 0;                          ///< ranks of each run (0: all, one run at a time)
  bool peers_first_ = false;                   ///< rank 0 ran the peers while the other groups ran
  std::vector<std::pair<PeerResult, std::string>> peer_results_;  ///< rank 0: the peers' results, labels
  std::vector<std::string> sensors_;
  int reference_unknowns_ = 0;  ///< fidelity: unknowns of the reference variant (default ranks per run)
  std::string fatal_;           ///< fidelity: the reference failed; thrown once the rows are written
};

}  // namespace

StudyResult run_study(const StudySpec& spec, const StudyOptions& options, MPI_Comm comm) {
  return Study(spec, options, comm).run();
}

}  // namespace alphaflex::study
