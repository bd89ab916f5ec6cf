#include "alphaflex/app/modal_run.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <sstream>

#include "alphaflex/app/run_objects.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/integrators/generalized_alpha.hpp"
#include "alphaflex/integrators/quasi_static.hpp"
#include "alphaflex/io/checkpoint.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "alphaflex/solvers/linear_solver.hpp"

namespace alphaflex {

namespace {

/// Parts with a non-zero share in some mode (loads without stiffness drop out of the table).
std::vector<size_t> active_parts(const ModalResult& r) {
  std::vector<size_t> out;
  for (size_t p = 0; p < r.parts.size(); ++p)
    for (const Mode& m : r.modes)
      if (m.kinetic_share[p] != 0.0 || m.strain_share[p] != 0.0) {
        out.push_back(p);
        break;
      }
  return out;
}

void write_csv(const std::string& path, const ModalResult& r) {
  std::ofstream out(path);
  if (!out) throw OutputError(path + ": cannot write the modes table");
  const std::vector<size_t> parts = active_parts(r);
  out << "mode,kind,frequency_hz,natural_frequency_hz,damping_ratio,eigenvalue_re,eigenvalue_im,modal_mass,"
         "dominant_part,whirl";
  for (size_t p : parts) out << ",kinetic_" << r.parts[p];
  for (size_t p : parts) out << ",strain_" << r.parts[p];
  out << "\n" << std::setprecision(17);
  for (size_t i = 0; i < r.modes.size(); ++i) {
    const Mode& m = r.modes[i];
    out << i + 1 << "," << to_string(m.kind) << "," << m.frequency << "," << m.natural_frequency << ","
        << m.damping_ratio << "," << m.re << "," << m.im << "," << m.modal_mass << ","
        << (m.dominant_part >= 0 ? r.parts[static_cast<size_t>(m.dominant_part)] : "") << "," << m.whirl;
    for (size_t p : parts) out << "," << m.kinetic_share[p];
    for (size_t p : parts) out << "," << m.strain_share[p];
    out << "\n";
  }
  if (!out) throw OutputError(path + ": write failed");
}

ModalRunSummary modes_body(RunObjects& o, Scene& scene, const ModalRunOptions& opt, MPI_Comm comm) {
  const double wall0 = MPI_Wtime();
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const RunSettings& rs = scene.settings;
  o.sub = std::make_unique<Subdomain>(*scene.model, comm);
  Subdomain& sub = *o.sub;
  o.system = std::make_unique<SaddlePointSystem>(sub);
  o.solver = std::make_unique<LinearSolver>(comm);
  o.integrator = std::make_unique<GeneralizedAlpha>(*o.system, *o.solver, rs.parameters, rs.integrator);
  ModalRunSummary sum;
  sum.ranks = sub.size();
  sum.unknowns = sub.dof_map().global_size();
  sum.coordinates = scene.model->num_dofs();
  sum.multipliers = scene.model->num_multipliers();
  sum.load_factor = rs.load_factor;

  // The state: a checkpoint, the static equilibrium, or the consistent start at t = 0.
  MechanicalState s = sub.model().initial_state();
  const bool statics = rs.analysis == Analysis::Static || rs.initial_static;
  if (!opt.restart.empty()) {
    if (statics)
      throw InputError(opt.restart + ": --restart linearizes about a dynamic run's checkpoint; this scene is a static "
                       "analysis (or has solver.initial_static), which has none");
    s = read_checkpoint(sub, opt.restart, rs.parameters, rs.h).state;
    std::ostringstream os;
    os << "checkpoint " << opt.restart << " at t = " << s.t << " s";
    sum.state = os.str();
  } else {
    if (statics) {
      QuasiStatic qs(*o.system, *o.solver, rs.statics);
      try {
        qs.solve(s);
      } catch (const SolverError& e) {
        throw SolverError(std::string("modes: the static equilibrium to linearize about: ") + e.what());
      } catch (const InputError& e) {
        throw InputError(scene.file + ": " + e.what());
      }
      sum.state = "static equilibrium";
    }
    if (rs.analysis != Analysis::Static) {
      try {
        o.integrator->initialize(s);
      } catch (const InputError& e) {
        throw InputError(scene.file + ": " + e.what());
      } catch (const ConfigurationError& e) {
        throw InputError(scene.file + ": the scene cannot start (consistent start at t = 0): " + e.what());
      }
      sum.state = statics ? "static equilibrium (solver.initial_static) after the consistent start"
                          : "initial state after the consistent start";
    }
  }
  sum.time = s.t;

  const double t0 = MPI_Wtime();
  sum.result = compute_modes(*o.system, s, rs.load_factor, opt.modes);
  sum.solve_wall = MPI_Wtime() - t0;

  if (opt.write_results) {
    std::error_code ec;
    std::filesystem::create_directories(opt.outdir, ec);
    // The shapes as a time series ParaView plays: mode k over t ∈ [k, k+1), one period in
    // `phases` frames, at an amplitude of 10 % of the model's size (at most 0.3 rad of rotation).
    // A frame is a whole state (~70 bytes per unknown): `output.hdf5: off` leaves them out.
    if (rs.hdf5) o.writer = std::make_unique<ResultsWriter>(sub, opt.outdir, scene.name + "_modeshapes", true, 0.0);
    for (size_t k = 0; o.writer && k < sum.result.modes.size(); ++k) {
      const Mode& m = sum.result.modes[k];
      double amp = 0.1 * sum.result.model_size;
      if (m.largest_rotation * amp > 0.3) amp = 0.3 / m.largest_rotation;
      for (int f = 0; f < opt.phases; ++f) {
        MechanicalState d = displaced_state(sub.model(), s, m, amp, 6.283185307179586 * f / opt.phases);
        d.t = static_cast<double>(k + 1) + static_cast<double>(f) / opt.phases;
        o.writer->write_fields(d);
      }
    }
    if (o.writer) {
      o.writer->finish();
      sum.h5 = o.writer->h5_path();
      sum.xdmf = o.writer->xdmf_path();
    }
    sum.csv = (std::filesystem::path(opt.outdir) / (scene.name + "_modes.csv")).string();
    int ok = 1;
    std::string err;
    if (rank == 0) {
      try {
        write_csv(sum.csv, sum.result);
      } catch (const OutputError& e) {
        ok = 0;
        err = e.what();
      }
    }
    MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
    if (!ok) throw OutputError(broadcast_text(err, comm));
  }
  sum.wall = MPI_Wtime() - wall0;
  return sum;
}

}  // namespace

ModalRunSummary run_modes(Scene& scene, const ModalRunOptions& opt, MPI_Comm comm) {
  return run_with_objects(opt.exit_comm, opt.exit_timeout,
                          [&](RunObjects& objects) { return modes_body(objects, scene, opt, comm); });
}

std::string format_modes(const Scene& scene, const ModalRunSummary& s) {
  const ModalResult& r = s.result;
  std::ostringstream os;
  os << "modes of " << scene.name << " about the " << s.state << " (t = " << s.time << " s, load factor "
     << s.load_factor << "): " << (r.damped ? "damped/gyroscopic (quadratic) problem" : "undamped problem") << ", "
     << s.unknowns << " unknowns (" << s.coordinates << " coordinates, " << s.multipliers << " joint equations) on "
     << s.ranks << " rank(s)\n";
  for (const auto& w : r.warnings) os << "  warning: " << w << "\n";
  os << "  " << std::setw(4) << "mode" << std::setw(12) << "kind" << std::setw(16) << "frequency (Hz)";
  if (r.damped) os << std::setw(12) << "damping" << std::setw(10) << "whirl";
  os << std::setw(14) << "modal mass" << "  dominant part (kinetic share)\n";
  for (size_t i = 0; i < r.modes.size(); ++i) {
    const Mode& m = r.modes[i];
    os << "  " << std::setw(4) << i + 1 << std::setw(12) << to_string(m.kind) << std::setw(16) << std::setprecision(8)
       << m.frequency;
    if (r.damped) os << std::setw(12) << std::setprecision(4) << m.damping_ratio << std::setw(10) << m.whirl;
    os << std::setw(14) << std::setprecision(5) << m.modal_mass << "  ";
    if (m.dominant_part >= 0)
      os << r.parts[static_cast<size_t>(m.dominant_part)] << " (" << std::setprecision(3)
         << 100.0 * m.kinetic_share[static_cast<size_t>(m.dominant_part)] << " %)";
    os << "\n";
  }
  os << "  rigid-body (zero-frequency) modes: " << r.rigid_body_modes << " of the " << r.modes.size() << " found; "
     << r.iterations << " eigensolver iterations, " << std::setprecision(3) << s.solve_wall << " s (whole command "
     << s.wall << " s)\n";
  if (!s.csv.empty()) os << "  table: " << s.csv << "\n";
  if (!s.xdmf.empty()) os << "  shapes: " << s.xdmf << " (mode k plays over t in [k, k+1))\n";
  return os.str();
}

}  // namespace alphaflex
