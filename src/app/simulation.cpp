#include "alphaflex/app/simulation.hpp"

#include <petscsys.h>
#include <sys/resource.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "alphaflex/app/exit_agreement.hpp"
#include "alphaflex/app/progress.hpp"
#include "alphaflex/app/run_objects.hpp"
#include "alphaflex/app/stop_signals.hpp"
#include "alphaflex/app/summary_json.hpp"
#include "alphaflex/assembly/diagnostics.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/blas_library.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/fault_injection.hpp"
#include "alphaflex/integrators/quasi_static.hpp"
#include "alphaflex/io/checkpoint.hpp"
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

}  // namespace

RunSummary run_simulation(Scene& scene, const RunOptions& opt, MPI_Comm comm) {
  return run_with_objects(opt.exit_comm, opt.exit_timeout,
                          [&](RunObjects& objects) { return run_body(objects, scene, opt, comm); });
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
  o.sub = std::make_unique<Subdomain>(model, comm);
  Subdomain& sub = *o.sub;
  // Tests of error handling: a bad value that one rank only finds (it ends the job, not a hang).
  if (fault_injected("input")) throw InputError(scene.file + ": injected fault (-af_inject_fault input): a bad value found on this rank only");
  o.system = std::make_unique<SaddlePointSystem>(sub);
  SaddlePointSystem& system = *o.system;
  o.solver = std::make_unique<LinearSolver>(comm, rs.low_rank);
  LinearSolver& solver = *o.solver;
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
                                             restarting ? &ck.position.results : nullptr);
  if (writer)
    for (const auto& w : writer->warnings()) sum.warnings.push_back(w);

  integrator.times().setup += MPI_Wtime() - wall0;  // partition, subdomain, preallocation, files
  std::vector<double> values;
  auto record = [&](const MechanicalState& st, bool fields) {
    values = sensor_values(sub, st);
    // The observer sees the whole state in model order (a gather, O(model), only when it is set).
    if (opt.on_step) opt.on_step(sub.size() == 1 ? st : sub.gather(st));
    if (opt.keep_history) {
      sum.times_out.push_back(st.t);
      sum.sensor_history.push_back(values);
    }
    const double t0 = MPI_Wtime();
    if (writer) {
      writer->write_sensors(st.t, values);
      if (fields) writer->write_fields(st);
    }
    integrator.times().output += MPI_Wtime() - t0;
  };
  // Closes the output and fills the summary (end of a static or a dynamic run).
  auto finish = [&](const MechanicalState& final_state) {
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
    if (rs.integrator.newton.modified) {
      sum.reused_iterations = integrator.reused_iterations();
      sum.contraction_refreshes = integrator.contraction_refreshes();
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
    ProgressReporter progress(opt.verbose && rank == 0, rs.progress_interval, 0.0, rs.load_factor, rs.statics.steps, stderr,
                              "load factor", "");
    long load_steps = 0;
    auto at_load = [&](const MechanicalState& st, double lf) {
      MechanicalState c = st;
      c.t = lf;  // the CSV's first column is the load factor in a static analysis
      record(c, true);
      if (lf > 0.0) progress.update(++load_steps, lf, -1);
    };
    if (is_static) at_load(s, 0.0);
    StaticReport rep;
    try {
      rep = qs.solve(s, is_static ? std::function<void(const MechanicalState&, double)>(at_load)
                                  : std::function<void(const MechanicalState&, double)>());
    } catch (const SolverError& e) {
      if (writer) writer->finish();
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
    integrator.times().assembly += qs.times().assembly;
    integrator.times().factorization += qs.times().factorization;
    integrator.times().solve += qs.times().solve;
    if (is_static) {
      sum.steps = rep.load_steps;
      return finish(s);
    }
  }
  if (restarting) {
    // The state, a and the counters as they were: the steps below are those the uninterrupted
    // run would have taken (the consistent start belongs to t = 0 only).
    integrator.set_auxiliary(ck.auxiliary);
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

  const double h = rs.h;
  // Fixed steps: a restart goes on from the checkpoint's step and time with the scene's h, which may
  // differ from the checkpoint's (a warning says so): the steps left are counted from there.
  const long steps_before = restarting ? static_cast<long>(ck.position.step) : 0;
  const double t_from = restarting ? s.t : 0.0;
  const double ratio = (rs.t_end - t_from) / h;
  long nsteps = steps_before + std::lround(ratio);
  if (std::fabs(ratio - std::round(ratio)) > 1e-9 * std::max(1.0, ratio)) {
    nsteps = steps_before + static_cast<long>(std::ceil(ratio));  // last step shortened to land on t_end
    std::ostringstream os;
    os << "t_end = " << rs.t_end << " s is not a multiple of h = " << h << " s" << (restarting ? " after the restart time" : "")
       << ": the last step is shortened to " << rs.t_end - t_from - static_cast<double>(nsteps - steps_before - 1) * h
       << " s (the order-2 condition, eq. 17, holds for constant h)";
    sum.warnings.push_back(os.str());
  }
  {
    // Index-3 round-off floor (paper Sec. 3.3): q carries round-off ε‖q‖, which q̈ = β'Δq and λ
    // amplify by β' ~ 1/(βh²). Warn when that floor is no longer small against q̈ itself.
    const auto& p = rs.parameters;
    const double beta_p = (1.0 - p.alpha_m) / (h * h * p.beta * (1.0 - p.alpha_f));
    const double floor = std::numeric_limits<double>::epsilon() * std::max(sub.max_abs(s.q), 1e-300) * beta_p;
    const double acc = sub.max_abs(s.qdd);
    if (floor > 1e-3 * acc) {
      std::ostringstream os;
      os.precision(3);
      os << "at h = " << h << " s accelerations and multipliers carry round-off of about " << floor
         << " (in q̈ units; |q̈0| = " << acc << "): ε‖q‖/(βh²) of the index-3 formulation. Use a larger h.";
      sum.warnings.push_back(os.str());
    }
  }

  if (opt.verbose && rank == 0)
    for (const auto& w : sum.warnings) std::cout << "  warning: " << w << std::endl;

  long first = 1, last_written = 0;
  if (restarting) {
    first = static_cast<long>(ck.position.step) + 1;
    last_written = static_cast<long>(ck.position.last_written);
  } else {
    record(s, true);
  }
  ProgressReporter progress(opt.verbose && rank == 0, rs.progress_interval, s.t, rs.t_end, nsteps);

  // Checkpoints (io/checkpoint.hpp): every checkpoint_every steps or s of wall time, at the end,
  // after a failure and on a stop signal. The results are committed first, so the checkpoint's
  // position of the results is complete on disk.
  RunPosition pos;
  pos.h = h;
  double hc = h;  // the step size in use (step cuts)
  int cuts_in_row = 0, good = 0;
  if (restarting) {
    // With step cuts the checkpoint's step size in use goes on, unless the scene changed h.
    if (std::fabs(ck.position.h - h) <= 1e-14 * h || ck.position.h < h) hc = ck.position.h;
    cuts_in_row = static_cast<int>(ck.position.cuts_in_row);
    good = static_cast<int>(ck.position.good_steps);
    sum.h_min = ck.position.h_min;
  }
  const std::string checkpoint_path = (std::filesystem::absolute(opt.outdir) / (scene.name + ".checkpoint.h5")).string();
  double last_checkpoint = MPI_Wtime();
  auto checkpoint = [&](long n) {
    if (!writer) return;
    const double t0 = MPI_Wtime();
    writer->commit();
    pos.step = n;
    pos.h = hc;
    pos.cuts_in_row = cuts_in_row;
    pos.good_steps = good;
    pos.newton_total = sum.newton_total;
    pos.newton_max = sum.newton_max;
    pos.step_cuts = sum.step_cuts;
    pos.h_min = sum.h_min;
    pos.last_written = last_written;
    pos.results = writer->position();
    sum.checkpoint_bytes = write_checkpoint(sub, checkpoint_path, s, integrator.auxiliary(), pos, rs.parameters, h,
                                            rs.checkpoint_keep);
    sum.checkpoint = checkpoint_path;
    ++sum.checkpoints;
    sum.checkpoint_time += MPI_Wtime() - t0;
    last_checkpoint = MPI_Wtime();
    // Modified Newton: a restart has no factorization to keep; refactor here too, so that the
    // run and its restart take the same iterations bit for bit.
    integrator.invalidate_factorization();
  };
  // After every step, the ranks agree whether to checkpoint (rank 0's wall clock, the step count)
  // and whether to stop (a signal on any rank): one small all-reduce.
  auto due = [&](long n) {
    int flags[2] = {stop_signal(), 0};
    if (rs.checkpoint_steps > 0 && n % rs.checkpoint_steps == 0) flags[1] = 1;
    if (rank == 0 && rs.checkpoint_wall > 0.0 && MPI_Wtime() - last_checkpoint >= rs.checkpoint_wall) flags[1] = 1;
    if (sub.size() > 1) MPI_Allreduce(MPI_IN_PLACE, flags, 2, MPI_INT, MPI_MAX, comm);
    if (flags[1] || flags[0]) checkpoint(n);
    if (!flags[0]) return;
    // Stop on request: the checkpoint is written; the state reached goes to the results too.
    if (writer) {
      if (last_written != n) writer->write_fields(s);
      writer->finish();
    }
    progress.finish();
    std::ostringstream os;
    os << "stopped by " << signal_name(flags[0]) << " at t = " << s.t << " s (step " << n << " of " << nsteps << ")";
    if (writer)
      os << ": checkpoint " << checkpoint_path << ", results in " << writer->xdmf_path() << ".\n  Go on with: alphaflex run "
         << scene.file << " --restart " << checkpoint_path << " -o " << std::filesystem::absolute(opt.outdir).string()
         << " (and the same --set options)";
    else
      os << " (no output, no checkpoint)";
    throw Interrupted(os.str());
  };

  // A failed step: keep what was computed (a checkpoint of the last converged state, which goes to
  // the files too) and stop.
  auto stop = [&](long n, const SolverError& e) {
    if (writer) {
      checkpoint(n - 1);
      if (last_written != n - 1) writer->write_fields(s);
      writer->finish();
    }
    std::ostringstream os;
    os << "step " << n << " of " << nsteps << ": " << e.what() << "\n  The last converged state (t = " << s.t
       << " s) is written" << (writer ? " to " + writer->xdmf_path() + "; a checkpoint of it to " + checkpoint_path
                                            : std::string(" nowhere (no output)"))
       << ".";
    throw SolverError(os.str());
  };
  if (!restarting) sum.h_min = h;
  long n = first - 1;
  if (rs.step_cuts == 0) {
    // Fixed steps (the paper's scheme exactly): stop at the first Newton failure.
    for (n = first; n <= nsteps; ++n) {
      const double hn = (n == nsteps) ? rs.t_end - s.t : h;
      StepReport rep;
      try {
        rep = integrator.step(s, hn);
      } catch (const SolverError& e) {
        stop(n, e);
      }
      if (fault_injected("internal")) throw std::runtime_error("injected fault (-af_inject_fault internal) at step " + std::to_string(n));
      ++sum.steps;
      sum.newton_total += rep.iterations;
      sum.newton_max = std::max(sum.newton_max, rep.iterations);
      const bool fields = (n % rs.output_every == 0) || n == nsteps;
      record(s, fields);
      if (fields) last_written = n;
      progress.update(n, s.t, sum.newton_total);
      if (n < nsteps) due(n);
    }
    n = nsteps;
  } else {
    // Newton failure policy (solver.step_cuts): a step that does not converge is retried from the
    // same state (q, v, q̈, λ and the auxiliary a) with h halved, up to step_cuts times in a row;
    // after 4 converged steps h doubles again, up to the scene's h. The auxiliary a is kept as it is
    // across a change of h: the scheme stays stable, but its second order holds only for constant h
    // (Arnold & Brüls 2007, eq. 17) — a run with cuts carries that extra error (measured in
    // tests/unit/test_step_cuts.cpp); rescaling a − q̈ with the step ratio was tried and was worse.
    // The summary counts the cuts.
    const double t_tol = 1e-12 * std::max(1.0, std::fabs(rs.t_end));
    while (rs.t_end - s.t > t_tol) {
      const double hn = std::min(hc, rs.t_end - s.t);
      const MechanicalState saved = s;
      const Eigen::VectorXd saved_a = integrator.auxiliary();
      StepReport rep;
      try {
        rep = integrator.step(s, hn);
      } catch (const SolverError& e) {
        if (cuts_in_row >= rs.step_cuts) stop(n + 1, e);
        s = saved;
        integrator.set_auxiliary(saved_a);
        hc = 0.5 * hn;
        ++cuts_in_row;
        ++sum.step_cuts;
        good = 0;
        sum.h_min = std::min(sum.h_min, hc);
        continue;
      }
      ++n;
      cuts_in_row = 0;
      if (hc < h && ++good >= 4) {
        hc = std::min(h, 2.0 * hc);
        good = 0;
      }
      ++sum.steps;
      sum.newton_total += rep.iterations;
      sum.newton_max = std::max(sum.newton_max, rep.iterations);
      const bool last = rs.t_end - s.t <= t_tol;
      const bool fields = (n % rs.output_every == 0) || last;
      record(s, fields);
      if (fields) last_written = n;
      progress.update(n, s.t, sum.newton_total);
      if (!last) due(n);
    }
  }
  progress.finish();
  checkpoint(n);  // the end of a run always leaves one (a longer solver.t_end can go on from it)
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
  if (scene.settings.analysis == Analysis::Static)
    os << " (static, load factor 0 to " << scene.settings.load_factor << ", " << s.static_cuts << " step cuts)\n";
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
  os
     << "  Newton iterations   total " << s.newton_total << ", mean " << mean << " per step, max " << s.newton_max << "\n"
     << "  factorizations      " << s.factorizations << " numeric, " << s.symbolic_analyses << " symbolic\n";
  if (s.reused_iterations >= 0)
    os << "  modified Newton     " << s.reused_iterations << " iterations on a kept factorization, " << s.contraction_refreshes
       << " refactorizations for a contraction rate above solver.newton.max_contraction\n";
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
       << " (INFOG(29))\n" << std::setprecision(4);
  if (!s.blas.empty()) os << "  BLAS                " << s.blas << "\n";
  if (s.workspace_retries > 0)
    os << "  MUMPS workspace     " << s.workspace_retries << " factorizations repeated with more workspace (ICNTL(14) now "
       << s.workspace_percent << " %)\n";
  os << "  memory              peak " << std::setprecision(4) << s.peak_memory_mb << " MB resident in all ranks ("
     << s.peak_memory_max_mb << " MB largest rank)";
  if (s.scene_memory_mb >= 0.0) os << ", " << s.scene_memory_mb << " MB of it per rank for the scene's whole model";
  os << "\n";
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
