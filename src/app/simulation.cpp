#include "alphaflex/app/simulation.hpp"

#include <petscsys.h>

#include <cmath>
#include <iomanip>
#include <sstream>

#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/partition/dof_map.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {
namespace {

std::vector<double> sensor_values(const Model& m, const MechanicalState& s) {
  std::vector<double> v;
  for (const auto& sn : m.sensors()) v.push_back(sn.evaluate(m, s));
  return v;
}

}  // namespace

RunSummary run_simulation(Scene& scene, const RunOptions& opt, MPI_Comm comm) {
  const double wall0 = MPI_Wtime();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const Model& model = *scene.model;
  const RunSettings& rs = scene.settings;

  DofMap map(model, comm);
  SaddlePointSystem system(model, map, comm);
  LinearSolver solver(comm);
  GeneralizedAlpha integrator(system, solver, rs.parameters, rs.integrator);

  RunSummary sum;
  sum.coordinates = model.num_dofs();
  sum.multipliers = model.num_multipliers();
  sum.unknowns = map.global_size();

  // Output files first, and agree on success: only rank 0 writes, so a failure there must not
  // leave the other ranks waiting in the first collective call.
  std::unique_ptr<ResultsWriter> writer;
  int ok = 1;
  std::string err;
  if (opt.write_results) {
    try {
      writer = std::make_unique<ResultsWriter>(model, opt.outdir, scene.name, rs.hdf5, rank);
    } catch (const std::exception& e) {
      ok = 0;
      err = e.what();
    }
  }
  int all_ok = 1;
  MPI_Allreduce(&ok, &all_ok, 1, MPI_INT, MPI_MIN, comm);
  if (!all_ok) throw InputError(err.empty() ? "cannot create the output files (see rank 0)" : err);

  MechanicalState s = model.initial_state();
  try {
    sum.projection = integrator.initialize(s);
  } catch (const InputError& e) {
    throw InputError(scene.file + ": " + e.what());  // the model as given cannot start
  }

  const double h = rs.h;
  const double ratio = rs.t_end / h;
  long nsteps = std::lround(ratio);
  if (std::fabs(ratio - static_cast<double>(nsteps)) > 1e-9 * std::max(1.0, ratio))
    nsteps = static_cast<long>(std::ceil(ratio));  // last step shortened to land on t_end

  auto record = [&](const MechanicalState& st) {
    sum.times_out.push_back(st.t);
    sum.sensor_history.push_back(sensor_values(model, st));
  };
  auto output = [&](const MechanicalState& st, bool fields) {
    const double t0 = MPI_Wtime();
    if (writer) {
      writer->write_sensors(st);
      if (fields) writer->write_fields(st);
    }
    integrator.times().output += MPI_Wtime() - t0;
  };
  record(s);
  output(s, true);
  long last_written = 0;

  for (long n = 1; n <= nsteps; ++n) {
    const double hn = (n == nsteps) ? rs.t_end - s.t : h;
    StepReport rep;
    try {
      rep = integrator.step(s, hn);
    } catch (const SolverError& e) {
      // Keep what was computed: the last converged state goes to the files before we stop.
      if (writer) {
        if (last_written != n - 1) writer->write_fields(s);
        writer->finish();
      }
      std::ostringstream os;
      os << "step " << n << " of " << nsteps << ": " << e.what() << "\n  The last converged state (t = " << s.t
         << " s) is written" << (writer ? " to " + writer->xdmf_path() : std::string(" nowhere (no output)")) << ".";
      throw SolverError(os.str());
    }
    ++sum.steps;
    sum.newton_total += rep.iterations;
    sum.newton_max = std::max(sum.newton_max, rep.iterations);
    record(s);
    const bool fields = (n % rs.output_every == 0) || n == nsteps;
    output(s, fields);
    if (fields) last_written = n;
  }
  if (writer) {
    writer->finish();
    sum.csv = writer->csv_path();
    if (rs.hdf5) {
      sum.h5 = writer->h5_path();
      sum.xdmf = writer->xdmf_path();
    }
  }
  sum.final_state = s;
  sum.final_sensors = sensor_values(model, s);
  sum.times = integrator.times();
  sum.factorizations = solver.numeric_count();
  sum.symbolic_analyses = solver.symbolic_count();
  sum.wall = MPI_Wtime() - wall0;
  return sum;
}

std::string format_summary(const Scene& scene, const RunSummary& s) {
  std::ostringstream os;
  os.precision(4);
  const double mean = s.steps ? static_cast<double>(s.newton_total) / s.steps : 0.0;
  const PhaseTimes& t = s.times;
  const double other = std::max(0.0, s.wall - t.assembly - t.factorization - t.solve - t.output);
  auto pct = [&](double x) { return s.wall > 0 ? 100.0 * x / s.wall : 0.0; };
  os << "summary of " << scene.name << "\n"
     << "  unknowns            " << s.unknowns << " (" << s.coordinates << " coordinates, " << s.multipliers
     << " multipliers)\n"
     << "  steps               " << s.steps << " (h = " << scene.settings.h << " s, t_end = " << scene.settings.t_end
     << " s)\n"
     << "  Newton iterations   total " << s.newton_total << ", mean " << mean << " per step, max " << s.newton_max << "\n"
     << "  factorizations      " << s.factorizations << " numeric, " << s.symbolic_analyses << " symbolic\n"
     << std::fixed << std::setprecision(3)
     << "  wall time           " << s.wall << " s (" << (s.steps ? 1e6 * s.wall / s.steps : 0.0) << " us per step)\n"
     << "    assembly          " << t.assembly << " s (" << std::setprecision(1) << pct(t.assembly) << " %)\n" << std::setprecision(3)
     << "    factorization     " << t.factorization << " s (" << std::setprecision(1) << pct(t.factorization) << " %)\n" << std::setprecision(3)
     << "    solve             " << t.solve << " s (" << std::setprecision(1) << pct(t.solve) << " %)\n" << std::setprecision(3)
     << "    output            " << t.output << " s (" << std::setprecision(1) << pct(t.output) << " %)\n" << std::setprecision(3)
     << "    other             " << other << " s (" << std::setprecision(1) << pct(other) << " %)\n";
  if (!s.csv.empty()) os << "results\n  sensors  " << s.csv << "\n";
  if (!s.xdmf.empty()) os << "  fields   " << s.h5 << "\n  ParaView paraview " << s.xdmf << "\n";
  return os.str();
}

}  // namespace alphaflex
