#include "alphaflex/app/simulation.hpp"

#include <petscsys.h>
#include <sys/resource.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "alphaflex/app/exit_agreement.hpp"
#include "alphaflex/app/progress.hpp"
#include "alphaflex/app/run_objects.hpp"
#include "alphaflex/app/sensor_integrals.hpp"
#include "alphaflex/app/stop_signals.hpp"
#include "alphaflex/app/summary_json.hpp"
#include "alphaflex/assembly/diagnostics.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/blas_library.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/fault_injection.hpp"
#include "alphaflex/core/memory.hpp"
#include "alphaflex/driver/step_controller.hpp"
#include "alphaflex/driver/time_loop.hpp"
#include "alphaflex/integrators/quasi_static.hpp"
#include "alphaflex/integrators/round_off_floor.hpp"
#include "alphaflex/io/checkpoint.hpp"
#include "alphaflex/io/sensor_schedule.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {
namespace {

/// Every sensor's value in scene order, on every rank: each is evaluated by the rank that owns
/// it (on its local state) and the others add zero.
std::vector<double> sensor_values(const Subdomain& sub, const MechanicalState& s) {
  std::vector<double> v(sub.global_model().sensors().size(), 0.0);
  const Model& m = sub.model();
  for (size_t k = 0; k < m.sensors().size(); ++k)
    v[static_cast<size_t>(sub.global_sensor(static_cast<int>(k)))] = m.sensors()[k].evaluate(m, s);
  sub.sum(v);
  return v;
}

RunSummary run_body(RunObjects& objects, Scene& scene, const RunOptions& opt, MPI_Comm comm);

/// A failed write of the results or of a checkpoint (issue 24, defect 1: a full disk), on every
/// rank: the results are left as last committed — consistent in the CSV, NAME.h5 and the index —
/// and a checkpoint of that state is written if there is room (the failed part's space is given
/// back first). Throws the OutputError the user sees: the failed write (file, errno) and what was kept.
[[noreturn]] void keep_committed_results(RunObjects& o, const OutputError& e) {
  o.writer->abandon();
  const CommittedState& c = o.committed;
  std::ostringstream os;
  os << e.what() << "\n  The results up to t = " << c.state.t << " s (output steps: " << c.position.results.steps
     << ", sensor rows: " << c.position.results.csv_rows << ") are complete and consistent in ";
  // Only the files this run writes are named: with output.sensors off there is no CSV (its path is empty).
  std::vector<std::string> kept;
  if (!o.writer->csv_path().empty()) kept.push_back(o.writer->csv_path());
  if (c.position.results.parts > 0) kept.insert(kept.end(), {o.writer->h5_path(), o.writer->xdmf_path()});
  for (std::size_t i = 0; i < kept.size(); ++i)
    os << (i == 0 ? "" : i + 1 == kept.size() ? " and " : ", ") << kept[i];
  if (kept.empty()) os << "(no result files: sensors and fields are off)";
  try {
    write_checkpoint(*o.sub, c.checkpoint, c.state, c.auxiliary, c.position, c.parameters, c.h, c.keep);
    os << "; a checkpoint of that state: " << c.checkpoint << ".\n  Once there is room, go on with: alphaflex run "
       << c.scene_file << " --restart " << c.checkpoint << " -o " << std::filesystem::absolute(c.outdir).string()
       << " (and the same --set options)";
  } catch (const OutputError& again) {
    os << "; no checkpoint of it could be written (" << again.what() << ")";
  }
  throw OutputError(os.str());
}

}  // namespace

RunSummary run_simulation(Scene& scene, const RunOptions& opt, MPI_Comm comm) {
  return run_with_objects(opt.exit_comm, opt.exit_timeout, [&](RunObjects& objects) {
    try {
      return run_body(objects, scene, opt, comm);
    } catch (const OutputError& e) {
      if (!objects.writer || objects.committed.checkpoint.empty()) throw;
      keep_committed_results(objects, e);
    }
  });
}


namespace {

RunSummary run_body(RunObjects& o, Scene& scene, const RunOptions& opt, MPI_Comm comm) {
  const double wall0 = MPI_Wtime();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const Model& model = *scene.model;
  const RunSettings& rs = scene.settings;

  // This rank's part of the model (METIS partition, owned and ghost nodes): the state below is
  // local to it.
  o.phase = "partitioning the model (this rank's subdomain)";
  o.sub = std::make_unique<Subdomain>(model, comm);
  Subdomain& sub = *o.sub;
  // Tests of error handling: a bad value that one rank only finds (it ends the job, not a hang).
  if (fault_injected("input")) throw InputError(scene.file + ": injected fault (-af_inject_fault input): a bad value found on this rank only");
  // The solver first: it makes the BLAS take its workspace while the most room is left.
  o.solver = std::make_unique<LinearSolver>(comm, rs.low_rank);
  LinearSolver& solver = *o.solver;
  o.phase = "preallocating the iteration matrix";
  const double base_mb = memory_status().resident_mb;  // before the matrix: the memory estimate's base
  o.system = std::make_unique<SaddlePointSystem>(sub);
  SaddlePointSystem& system = *o.system;
  o.integrator = std::make_unique<GeneralizedAlpha>(system, solver, rs.parameters, rs.integrator);
  GeneralizedAlpha& integrator = *o.integrator;

  RunSummary sum;
  sum.coordinates = model.num_dofs();
  sum.multipliers = model.num_multipliers();
  sum.unknowns = sub.dof_map().global_size();
  sum.ranks = sub.size();
  sum.edge_cut = sub.dof_map().edge_cut();
  sum.unknowns_per_rank = sub.dof_map().unknowns_per_rank();
  sum.ghosts_per_rank.assign(static_cast<size_t>(sub.size()), 0);
  {
    const int ghosts = sub.num_ghost_nodes();
    MPI_Allgather(&ghosts, 1, MPI_INT, sum.ghosts_per_rank.data(), 1, MPI_INT, comm);
  }
  for (const auto& sn : model.sensors()) sum.sensor_names.push_back(sn.name);

  // A restart reads its checkpoint first: the results go on from the position it records.
  const bool restarting = !opt.restart.empty();
  Checkpoint ck;
  if (restarting) {
    if (rs.analysis == Analysis::Static || rs.initial_static)
      throw InputError(opt.restart + ": --restart continues a dynamic run; a static analysis (or solver.initial_static) has no checkpoints");
    ck = read_checkpoint(sub, opt.restart, rs.parameters, rs.h);
    if (!(ck.state.t < rs.t_end - 1e-12 * std::max(1.0, std::fabs(rs.t_end)))) {
      std::ostringstream os;
      os << opt.restart << ": the checkpoint is at t = " << ck.state.t << " s, solver.t_end = " << rs.t_end
         << " s: nothing to do (give a larger solver.t_end, e.g. --set solver.t_end=" << 2.0 * ck.state.t << ", to go on)";
      throw InputError(os.str());
    }
    sum.restarted_from = opt.restart;
    sum.restart_time = ck.state.t;
    for (const auto& w : ck.warnings) sum.warnings.push_back(w);
  }
  // Output files (collective: the ranks agree on success inside, so a failure on one rank does not
  // leave the others waiting).
  std::unique_ptr<ResultsWriter>& writer = o.writer;
  if (opt.write_results && !opt.stop_after_start)
    writer = std::make_unique<ResultsWriter>(sub, opt.outdir, scene.name, rs.hdf5, rs.commit_interval,
                                             restarting ? &ck.position.results : nullptr, rs.sensors);
  if (writer)
    for (const auto& w : writer->warnings()) sum.warnings.push_back(w);

  integrator.times().setup += MPI_Wtime() - wall0;  // partition, subdomain, preallocation, files
  std::vector<double> values;
  // Sensor rows (output.sensors, output.sensors_dt; io/sensor_schedule.hpp). The values are
  // evaluated only for a row, a study's history or the last step (the summary's final values); a
  // static analysis writes every load step it records. Accumulated sensors (`work`) need the
  // values of every step (trapezoidal rule over the accepted steps).
  const bool dynamic = rs.analysis != Analysis::Static;
  SensorSchedule sensor_rows(rs.sensors, dynamic ? rs.sensors_dt : 0.0, restarting ? ck.state.t : 0.0, !restarting);
  SensorIntegrals integrals(sub.global_model().sensors());  // work of the loads, dissipated energy
  if (restarting && !integrals.empty() && !integrals.restore(ck.position.accumulated))
    throw InputError(opt.restart + ": the checkpoint has no running sums of this scene's " +
                     std::to_string(integrals.state().size() / 2) +
                     " accumulated sensors (`work`; it holds " + std::to_string(ck.position.accumulated.size() / 2) +
                     "): it is of a scene with other sensors; run from t = 0");
  auto record = [&](const MechanicalState& st, bool fields, double field_time = std::numeric_limits<double>::quiet_NaN()) {
    const bool last = !dynamic || st.t >= rs.t_end - 1e-12 * std::max(1.0, std::fabs(rs.t_end));
    const bool row = sensor_rows.due(st.t, last);
    if (row || last || opt.keep_history || !integrals.empty()) {
      values = sensor_values(sub, st);
      integrals.integrate(st.t, values);
    }
    // The observer sees the whole state in model order (a gather, O(model), only when it is set).
    if (opt.on_step) opt.on_step(sub.size() == 1 ? st : sub.gather(st));
    if (opt.keep_history) {
      sum.times_out.push_back(st.t);
      sum.sensor_history.push_back(values);
    }
    const double t0 = MPI_Wtime();
    if (writer) {
      if (row) writer->write_sensors(st.t, values);
      if (fields && std::isnan(field_time)) writer->write_fields(st);
      if (fields && !std::isnan(field_time)) {
        MechanicalState at = st;  // the fields' time is another path parameter (arc length: the step)
        at.t = field_time;
        writer->write_fields(at);
      }
    }
    integrator.times().output += MPI_Wtime() - t0;
  };
  // The memory estimate once MUMPS has analysed the matrix (issue 24): printed before the steps of
  // large models, with a warning if it exceeds what the ranks may have.
  auto estimate = [&](bool print) {
    if (sum.memory_estimate.known() || solver.numeric_count() == 0) return;
    sum.memory_estimate = estimate_memory(comm, base_mb, system, solver);
    if (print && opt.verbose && rank == 0 && sum.unknowns >= kMemoryEstimateUnknowns)
      std::cout << "  " << sum.memory_estimate.line() << std::endl;
    if (!sum.memory_estimate.warning.empty()) sum.warnings.push_back(sum.memory_estimate.warning);
  };
  // Closes the output and fills the summary (end of a static or a dynamic run).
  auto finish = [&](const MechanicalState& final_state) {
    estimate(false);
    if (writer) {
      writer->finish();
      sum.csv = writer->csv_path();
      if (rs.hdf5) {
        sum.h5 = writer->h5_path();
        sum.xdmf = writer->xdmf_path();
      }
    }
    sum.final_state = sub.gather(final_state);  // model order, every rank (O(model), once)
    sum.final_sensors = values;
    sum.times = integrator.times();
    sum.factorizations = solver.numeric_count();
    if (dynamic) {  // static load steps: full Newton always
      sum.newton_method = integrator.newton_method();
      if (sum.static_steps > 0) sum.newton_method += "; the initial static load steps: full Newton";
    }
    if (integrator.modified_newton()) {
      sum.reused_iterations = integrator.reused_iterations();
      sum.contraction_refreshes = integrator.contraction_refreshes();
      sum.fresh_starts = integrator.fresh_starts();
      sum.rescaled_iterations = integrator.rescaled_iterations();
    }
    sum.mumps = solver.statistics();
    sum.workspace_retries = solver.workspace_retries();
    sum.workspace_percent = solver.workspace_percent();
    sum.blas = describe(loaded_blas());
    // Peak resident memory of every rank (getrusage: the whole process, in KB on Linux).
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    double mb[2] = {static_cast<double>(ru.ru_maxrss) / 1024.0, 0.0}, tot[2] = {0.0, 0.0};
    mb[1] = mb[0];
    MPI_Allreduce(&mb[0], &tot[0], 1, MPI_DOUBLE, MPI_SUM, comm);
    MPI_Allreduce(&mb[1], &tot[1], 1, MPI_DOUBLE, MPI_MAX, comm);
    sum.peak_memory_mb = tot[0];
    sum.peak_memory_max_mb = tot[1];
    sum.symbolic_analyses = solver.symbolic_count();
    sum.wall = MPI_Wtime() - wall0;
    return sum;
  };
  MechanicalState s = sub.model().initial_state();
  // A static solve (the whole analysis or a dynamic run's pre-load) is the run itself.
  if (opt.stop_after_start && (rs.analysis == Analysis::Static || rs.initial_static)) return sum;
  if (restarting) {
    s = ck.state;
  } else if (rs.analysis == Analysis::Static || rs.initial_static) {
    // Quasi-static load stepping (integrators/quasi_static.hpp): the whole analysis, or the
    // pre-loaded equilibrium a dynamic run starts from.
    const bool is_static = rs.analysis == Analysis::Static;
    QuasiStatic qs(system, solver, rs.statics);
    // Path following through limit points (integrators/arc_length.hpp), a static analysis only.
    const bool arc = is_static && rs.statics.method == StaticOptions::Method::ArcLength;
    std::unique_ptr<ArcLength> path;
    if (arc) path = std::make_unique<ArcLength>(system, solver, rs.statics);
    std::vector<std::vector<double>> step_sensors;  // per converged point (arc length: critical points' sensors)
    ProgressReporter progress(opt.verbose && rank == 0, rs.progress_interval, 0.0, rs.load_factor, rs.statics.steps, stderr,
                              "load factor", "");
    long load_steps = 0;
    auto at_load = [&](const MechanicalState& st, double lf) {
      MechanicalState c = st;
      c.t = lf;  // the CSV's first column is the load factor in a static analysis
      // Along an arc-length path the load factor goes up and down; ParaView orders the steps of
      // NAME.xdmf by their time, so there the time of step k is k.
      record(c, true, arc ? static_cast<double>(step_sensors.size()) : std::numeric_limits<double>::quiet_NaN());
      if (arc) step_sensors.push_back(values);
      if (arc ? step_sensors.size() > 1 : lf > 0.0) progress.update(++load_steps, lf, -1);
    };
    if (is_static) at_load(s, 0.0);
    StaticReport rep;
    try {
      if (arc) {
        sum.path = path->solve(s, at_load);
        rep = sum.path;
      } else {
        rep = qs.solve(s, is_static ? std::function<void(const MechanicalState&, double)>(at_load)
                                    : std::function<void(const MechanicalState&, double)>());
      }
    } catch (const SolverError& e) {
      if (writer) writer->finish();
      // A body nothing holds (no joint, no stiffness) has no equilibrium: bad input, named (the
      // factorization alone said "zero pivot").
      const std::string unheld = load_steps == 0 ? find_unheld_motion(sub, s) : std::string();
      if (!unheld.empty())
        throw InputError(scene.file + ": the " + (is_static ? "static analysis" : "initial static equilibrium") +
                         " has no equilibrium to find: no joint and no stiffness acts on these motions (attach the body "
                         "by a joint or a spring, or run a dynamic analysis):" + unheld);
      throw SolverError(std::string(is_static ? "static analysis: " : "initial static equilibrium: ") + e.what() +
                        (writer && is_static ? "\n  The converged load steps are written to " + writer->xdmf_path() + "." : ""));
    } catch (const InputError& e) {
      if (writer) writer->finish();
      throw InputError(scene.file + ": " + e.what());
    }
    progress.finish();
    sum.static_steps = rep.load_steps;
    sum.static_cuts = rep.cuts;
    sum.newton_total += rep.iterations;
    sum.newton_max = std::max(sum.newton_max, rep.max_iterations);
    const PhaseTimes& st = arc ? path->times() : qs.times();
    integrator.times().assembly += st.assembly;
    integrator.times().factorization += st.factorization;
    integrator.times().solve += st.solve;
    sum.arc_length = arc;
    for (const CriticalPoint& cp : sum.path.critical_points) sum.critical_sensors.push_back(step_sensors.at(static_cast<size_t>(cp.step)));
    if (is_static) {
      sum.steps = rep.load_steps;
      return finish(s);
    }
  }
  if (restarting) {
    // The state, a and the counters as they were: the steps below are those the uninterrupted
    // run would have taken (the consistent start belongs to t = 0 only).
    sum.steps = static_cast<int>(ck.position.step);
    sum.newton_total = ck.position.newton_total;
    sum.newton_max = static_cast<int>(ck.position.newton_max);
    sum.step_cuts = static_cast<int>(ck.position.step_cuts);
  } else {
    if (!rs.integrator.consistent_start) {
      const double viol = constraint_violation(sub, s);
      if (viol > 1e-9 * std::max(1.0, sub.max_abs(s.q)))
        sum.warnings.push_back("solver.consistent_start is off and the initial positions violate the joints by up to " +
                               std::to_string(viol) + ": the first steps' multipliers will be far off");
    }
    o.phase = "computing the consistent start at t = 0 (the first factorizations)";
    try {
      sum.projection = integrator.initialize(s);
    } catch (const InputError& e) {
      throw InputError(scene.file + ": " + e.what());  // the model as given cannot start
    } catch (const ConfigurationError& e) {
      // Before the first step the state is the scene's own (projected onto its joints): an element
      // that cannot be evaluated there (a spring whose points coincide) is a fault of the scene.
      // Other solver failures of the start (a matrix MUMPS cannot factor) stay solver failures.
      throw InputError(scene.file + ": the scene cannot start (consistent start at t = 0): " + e.what());
    }
  }
  if (opt.stop_after_start) return sum;
  estimate(true);
  o.phase = "taking the time steps";

  const double h = rs.h;
  // The step policy (driver/step_controller.hpp): fixed, cut-back on Newton failures, or adaptive.
  const AdaptiveOptions adaptive{rs.tolerance_rtol, rs.tolerance_atol, rs.h_min, rs.h_max, rs.output_dt, rs.breakpoints,
                                 rs.tolerance_hold};
  const std::unique_ptr<StepController> controller = make_step_controller(h, rs.t_end, rs.step_cuts, adaptive);
  const std::string checkpoint_path = (std::filesystem::absolute(opt.outdir) / (scene.name + ".checkpoint.h5")).string();
  Checkpointer checkpointer(sub, writer.get(), checkpoint_path, rs.parameters, h, rs.checkpoint_keep);
  if (!integrals.empty()) checkpointer.set_accumulated([&integrals] { return integrals.state(); });
  TimeLoopSettings ls;
  ls.output_every = rs.output_every;
  ErrorFilter filter(system, solver, integrator);
  if (rs.filtered_error_estimate) ls.filter = &filter;
  ls.checkpoint_steps = rs.checkpoint_steps;
  ls.checkpoint_wall = rs.checkpoint_wall;
  ls.checkpoint_at_end = rs.checkpoint_at_end;
  ls.scene_file = scene.file;
  ls.outdir = opt.outdir;
  ls.stop_signal = [] { return stop_signal(); };
  ls.signal_name = [](int sig) { return signal_name(sig); };
  // A write that fails later (a full disk: run_simulation) leaves the results as last committed and
  // a checkpoint of the state they end at: that state is kept at every commit (a copy of the local
  // state, once per commit), starting with the one committed so far (t = 0, or the restart's).
  ls.on_commit = [&](const MechanicalState& st, const Eigen::VectorXd& aux, const RunPosition& pos) {
    o.committed = {st, aux, pos, checkpoint_path, rs.parameters, h, rs.checkpoint_keep, scene.file, opt.outdir};
  };
  TimeLoop loop(sub, integrator, *controller, checkpointer, writer.get(), ls);
  if (restarting) loop.restore(ck, h);
  if (const auto* fixed = dynamic_cast<const FixedSteps*>(controller.get())) {
    const std::string w = fixed->shortened_last_step(s.t, restarting);
    if (!w.empty()) sum.warnings.push_back(w);
  }
  if (opt.verbose && rank == 0)
    for (const auto& w : sum.warnings) std::cout << "  warning: " << w << std::endl;

  LoopCounters counters;
  counters.steps = sum.steps;
  counters.newton_total = sum.newton_total;
  counters.newton_max = sum.newton_max;
  ProgressReporter progress(opt.verbose && rank == 0, rs.progress_interval, s.t, rs.t_end,
                            controller->total_steps(counters.steps, s.t));
  loop.add_observer([&](const StepEvent& e) { record(e.state, e.fields); });
  loop.add_observer([&](const StepEvent& e) {
    if (e.step > 0)
      progress.update(e.step, e.state.t, counters.newton_total, e.controller.variable() ? e.controller.state().rejected : -1,
                      e.controller.state().h);
  });
  long first = 1, last_written = 0;
  if (restarting) {
    first = static_cast<long>(ck.position.step) + 1;
    last_written = static_cast<long>(ck.position.last_written);
  } else {
    loop.observe(0, s, true);
  }
  const double acc_start = sub.max_abs(s.qdd);
  // Each reaction's own size over the run (committed steps and the start): the scale its round-off
  // is judged against (integrators/round_off_floor.hpp).
  Eigen::VectorXd max_lambda = s.lambda.cwiseAbs();
  loop.add_observer([&](const StepEvent& e) {
    if (e.state.lambda.size() == max_lambda.size()) max_lambda = max_lambda.cwiseMax(e.state.lambda.cwiseAbs());
  });
  loop.run(s, first, last_written, counters);
  progress.finish();
  {
    const double h_small = controller->state().h_min > 0.0 ? controller->state().h_min : h;
    const double q_norm = sub.max_abs(s.q);
    std::vector<std::string> ws = {round_off_floor_warning(rs.parameters, h_small, q_norm,
                                                           std::max(acc_start, sub.max_abs(s.qdd)))};
    if (model.num_multipliers() > 0) {
      // The joint whose estimate is the largest share of its own reaction, from the rank holding it.
      const std::vector<ReactionScale> local = reaction_scales(system, s, rs.parameters, h_small, max_lambda);
      const ReactionScale* worst = nullptr;
      double share = -1.0;
      for (const ReactionScale& r : local) {
        const double x = r.reaction > 0.0 ? reaction_round_off(rs.parameters, h_small, q_norm, r) / r.reaction : 0.0;
        if (x > share) share = x, worst = &r;
      }
      const int root = sub.rank_of_max(share);
      std::ostringstream enc;
      enc.precision(17);
      if (worst) enc << worst->mass << ' ' << worst->stiffness << ' ' << worst->reaction << ' ' << worst->joint;
      std::istringstream dec(sub.broadcast(enc.str(), root));
      ReactionScale r;
      if (dec >> r.mass >> r.stiffness >> r.reaction) {
        dec.get();
        std::getline(dec, r.joint);
        ws.push_back(reaction_round_off_warning(rs.parameters, h_small, q_norm, {r}));
      }
    }
    for (const std::string& w : ws) {
      if (w.empty()) continue;
      sum.warnings.push_back(w);
      if (opt.verbose && rank == 0) std::cout << "  warning: " << w << std::endl;
    }
  }
  sum.steps = static_cast<int>(counters.steps);
  sum.newton_total = counters.newton_total;
  sum.newton_max = counters.newton_max;
  static_cast<CheckpointStats&>(sum) = counters;
  const StepControllerState& st_end = controller->state();
  sum.step_cuts = static_cast<int>(st_end.newton_failures);
  sum.rejected_steps = st_end.rejected;
  sum.h_min = st_end.h_min;
  sum.h_max = st_end.h_max;
  return finish(s);
}

}  // namespace

std::string format_summary(const Scene& scene, const RunSummary& s) {
  std::ostringstream os;
  os.precision(4);
  // Derived figures: the same function as the JSON summary's (app/summary_json.hpp).
  const RunFigures fig = run_figures(s);
  const double mean = fig.mean_newton, other = fig.other_time;
  const PhaseTimes& t = s.times;
  auto pct = [&](double x) { return fig.percent(x); };
  os << "summary of " << scene.name << "\n"
     << "  unknowns            " << s.unknowns << " (" << s.coordinates << " coordinates, " << s.multipliers
     << " multipliers)\n"
     << (scene.settings.analysis == Analysis::Static ? "  load steps          " : "  steps               ") << s.steps;
  if (s.arc_length) {
    os << " (static, arc length: load factor 0 to " << s.path.load_factor << ", ended by " << s.path.stop << "; "
       << s.static_cuts << " arc-length cuts, arc length " << s.path.min_arc << " to " << s.path.max_arc << ", "
       << s.path.line_searches << " line searches)\n";
    for (size_t k = 0; k < s.path.critical_points.size(); ++k) {
      const CriticalPoint& cp = s.path.critical_points[k];
      os << "  " << cp.kind_name() << " at load factor " << cp.load_factor << " (near step " << cp.step << ", between "
         << cp.lower << " and " << cp.upper << ")";
      for (size_t i = 0; i < s.sensor_names.size() && i < s.critical_sensors[k].size(); ++i)
        os << (i == 0 ? ": " : ", ") << s.sensor_names[i] << " = " << s.critical_sensors[k][i];
      os << "\n";
    }
  } else if (scene.settings.analysis == Analysis::Static)
    os << " (static, load factor 0 to " << scene.settings.load_factor << ", " << s.static_cuts << " step cuts)\n";
  else if (scene.settings.tolerance_rtol > 0.0 || scene.settings.tolerance_atol > 0.0)
    os << " accepted, " << s.rejected_steps << " rejected, " << s.step_cuts << " Newton failures (adaptive: rtol "
       << scene.settings.tolerance_rtol << ", atol " << scene.settings.tolerance_atol << "; h from " << s.h_min << " to " << s.h_max
       << " s, first " << scene.settings.h << " s; t_end = " << scene.settings.t_end << " s)\n";
  else if (scene.settings.step_cuts > 0)
    os << " (h = " << scene.settings.h << " s, t_end = " << scene.settings.t_end << " s; " << s.step_cuts
       << " step cuts, smallest h = " << s.h_min << " s)\n";
  else
    os << " (h = " << scene.settings.h << " s, t_end = " << scene.settings.t_end << " s)\n";
  if (scene.settings.analysis != Analysis::Static && s.static_steps > 0)
    os << "  initial statics     " << s.static_steps << " load steps, " << s.static_cuts << " step cuts\n";
  if (s.ranks > 1) {
    // Partition quality (METIS): unknowns each rank owns, its ghost nodes, the couplings cut.
    os << "  partition           METIS, " << s.ranks << " ranks, edge cut " << s.edge_cut << ", load imbalance "
       << std::fixed << std::setprecision(3) << fig.load_imbalance << std::defaultfloat << std::setprecision(4) << " (largest / mean unknowns per rank)\n"
       << "    rank      unknowns   ghost nodes\n";
    for (int r = 0; r < s.ranks; ++r)
      os << "    " << std::setw(4) << r << std::setw(14) << s.unknowns_per_rank[static_cast<size_t>(r)] << std::setw(14)
         << s.ghosts_per_rank[static_cast<size_t>(r)] << "\n";
  }
  if (!s.newton_method.empty()) os << "  Newton method       " << s.newton_method << "\n";
  os
     << "  Newton iterations   total " << s.newton_total << ", mean " << mean << " per step, max " << s.newton_max << "\n"
     << "  factorizations      " << s.factorizations << " numeric, " << s.symbolic_analyses << " symbolic, "
     << static_cast<double>(s.factorizations) / std::max(1, s.steps) << " per accepted step\n";
  if (s.reused_iterations >= 0)
    os << "  modified Newton     " << s.reused_iterations << " iterations on a kept factorization (" << s.rescaled_iterations
       << " of them made for another h), " << s.contraction_refreshes
       << " refactorizations for a contraction rate above solver.newton.max_contraction, " << s.fresh_starts
       << " steps begun on a fresh factorization after an old one failed its first rate test\n";
  if (s.mumps.dense)
    os << "  linear solver       dense LU with partial pivoting (one rank, " << s.unknowns << " unknowns <= -af_dense_lu "
       << LinearSolver::kDenseLimit << " by default; MUMPS above)\n";
  if (s.mumps.mumps)
    os << "  MUMPS               " << s.mumps.entries << " entries in the factors, " << s.mumps.flops
       << " flop per factorization, " << s.mumps.memory_sum_mb << " MB in all (" << s.mumps.memory_max_mb
       << " MB on the largest rank)\n";
  if (s.mumps.mumps && s.mumps.low_rank_tolerance > 0.0)
    os << "  MUMPS low-rank      BLR at tolerance " << s.mumps.low_rank_tolerance << ": " << s.mumps.low_rank_entries
       << " entries in the compressed factors (INFOG(35)), " << std::setprecision(3)
       << 100.0 * s.mumps.low_rank_entries / s.mumps.entries << " % of the full-rank " << s.mumps.entries
       << " (INFOG(29)); " << s.mumps.low_rank_flops << " flop per factorization (RINFOG(14)), "
       << 100.0 * s.mumps.low_rank_flops / s.mumps.flops << " %\n" << std::setprecision(4);
  if (!s.blas.empty()) os << "  BLAS                " << s.blas << "\n";
  if (s.workspace_retries > 0)
    os << "  MUMPS workspace     " << s.workspace_retries << " factorizations repeated with more workspace (ICNTL(14) now "
       << s.workspace_percent << " %)\n";
  os << "  memory              peak " << std::setprecision(4) << s.peak_memory_mb << " MB resident in all ranks ("
     << s.peak_memory_max_mb << " MB largest rank)";
  if (s.scene_memory_mb >= 0.0) os << ", " << s.scene_memory_mb << " MB of it per rank for the scene's whole model";
  if (s.memory_estimate.known()) os << "; estimated " << s.memory_estimate.total_mb << " MB per rank";
  os << "\n";
  for (const auto& note : scene.superelements) os << "  superelement        " << note << "\n";
  if (!s.restarted_from.empty()) os << "  restarted from      " << s.restarted_from << " (t = " << s.restart_time << " s)\n";
  if (s.checkpoints > 0)
    os << "  checkpoints         " << s.checkpoints << " written (" << std::setprecision(3) << s.checkpoint_bytes / 1e6
       << " MB each), the last: " << s.checkpoint << "\n" << std::setprecision(4);
  os << std::fixed << std::setprecision(3)
     << "  wall time           " << s.wall << " s (" << fig.us_per_step << " us per step)\n"
     << "    setup             " << t.setup << " s (" << std::setprecision(1) << pct(t.setup) << " %)\n" << std::setprecision(3)
     << "    assembly          " << t.assembly << " s (" << std::setprecision(1) << pct(t.assembly) << " %)\n" << std::setprecision(3)
     << "    factorization     " << t.factorization << " s (" << std::setprecision(1) << pct(t.factorization) << " %)\n" << std::setprecision(3)
     << "    solve             " << t.solve << " s (" << std::setprecision(1) << pct(t.solve) << " %)\n" << std::setprecision(3)
     << "    output            " << t.output << " s (" << std::setprecision(1) << pct(t.output) << " %)\n" << std::setprecision(3)
     << "    checkpoints       " << s.checkpoint_time << " s (" << std::setprecision(1) << pct(s.checkpoint_time) << " %)\n" << std::setprecision(3)
     << "    other             " << other << " s (" << std::setprecision(1) << pct(other) << " %)\n";
  if (!s.csv.empty()) os << "results\n  sensors  " << s.csv << "\n";
  if (!s.xdmf.empty()) os << "  fields   " << s.h5 << "\n  ParaView paraview " << s.xdmf << "\n";
  return os.str();
}

}  // namespace alphaflex
