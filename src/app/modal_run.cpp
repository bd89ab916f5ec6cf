#include "alphaflex/app/modal_run.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>

#include "alphaflex/app/run_objects.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/integrators/generalized_alpha.hpp"
#include "alphaflex/integrators/quasi_static.hpp"
#include "alphaflex/io/checkpoint.hpp"
#include "alphaflex/joints/spatial_joints.hpp"
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


/// The joint `name` of a modes.rotating_frame / modes.campbell key at state `s`: the angular
/// velocity of its first body relative to its second (world frame, rad/s), and the axis (a3 of its
/// first marker) and the point of that marker in the world. Collective (the rank owning the joint
/// computes, the sum gives it to all).
struct JointFrame {
  Eigen::Vector3d spin = Eigen::Vector3d::Zero(), axis = Eigen::Vector3d::Zero(), point = Eigen::Vector3d::Zero();
};
JointFrame joint_frame(const Subdomain& sub, const MechanicalState& s, const std::string& name, const std::string& key,
                       const std::string& file) {
  bool found = false;
  for (const auto& c : sub.global_model().constraints())
    if (c->name() == name) {
      found = c->nodes().size() <= 2 && dynamic_cast<const SpatialJoint*>(c.get()) != nullptr;
      if (!found)
        throw InputError(file + ": " + key + ": joint '" + name + "' is a " + c->type() +
                         "; expected a spatial joint (revolute) of a 3D scene");
    }
  if (!found) throw InputError(file + ": " + key + ": no joint named '" + name + "'");
  const Model& m = sub.model();
  double local[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
  auto rotation = [&](const Node& n) {
    const Eigen::Vector4d qv = s.q.segment<4>(n.first_conf + 3);
    return Eigen::Quaterniond(qv[0], qv[1], qv[2], qv[3]).normalized().toRotationMatrix();
  };
  for (const auto& c : m.constraints()) {
    if (c->name() != name) continue;
    const auto& j = static_cast<const SpatialJoint&>(*c);
    Eigen::Vector3d w = Eigen::Vector3d::Zero(), axis, point;
    for (size_t k = 0; k < c->nodes().size(); ++k) {
      const Node& n = m.node(c->nodes()[k]);
      const Eigen::Matrix3d R = rotation(n);
      w += (k == 0 ? 1.0 : -1.0) * (R * s.v.segment<3>(n.first_dof + 3));
    }
    const SpatialMarker& a = j.marker_a();
    if (a.slot >= 0) {
      const Node& n = m.node(c->nodes()[static_cast<size_t>(a.slot)]);
      const Eigen::Matrix3d R = rotation(n);
      axis = R * a.rotation.col(2);
      point = s.q.segment<3>(n.first_conf) + R * a.position;
    } else {
      axis = a.rotation.col(2);
      point = a.position;
    }
    for (int d = 0; d < 3; ++d) local[d] = w[d], local[3 + d] = axis[d], local[6 + d] = point[d];
  }
  double all[9];
  MPI_Allreduce(local, all, 9, MPI_DOUBLE, MPI_SUM, sub.comm());
  JointFrame f;
  for (int d = 0; d < 3; ++d) f.spin[d] = all[d], f.axis[d] = all[3 + d], f.point[d] = all[6 + d];
  return f;
}

void write_campbell_csv(const std::string& path, const std::vector<double>& speeds,
                        const std::vector<ModalResult>& results) {
  std::ofstream out(path);
  if (!out) throw OutputError(path + ": cannot write the Campbell table");
  out << "speed_rad_s,speed_hz,mode,kind,frequency_hz,natural_frequency_hz,damping_ratio,whirl,dominant_part\n"
      << std::setprecision(17);
  for (size_t i = 0; i < speeds.size(); ++i)
    for (size_t k = 0; k < results[i].modes.size(); ++k) {
      const Mode& m = results[i].modes[k];
      out << speeds[i] << "," << speeds[i] / 6.283185307179586 << "," << k + 1 << "," << to_string(m.kind) << ","
          << m.frequency << "," << m.natural_frequency << "," << m.damping_ratio << "," << m.whirl << ","
          << (m.dominant_part >= 0 ? results[i].parts[static_cast<size_t>(m.dominant_part)] : "") << "\n";
    }
  if (!out) throw OutputError(path + ": write failed");
}

/// The chart of a Campbell table by scripts/campbell_plot.py (rank 0): its path, or empty with a
/// warning when Debian's python3 or the script is missing or fails (the CSV is written anyway).
std::string draw_campbell(const std::string& csv, std::vector<std::string>& warnings) {
  const std::string python = "/usr/bin/python3", script = std::string(ALPHAFLEX_SOURCE_DIR) + "/scripts/campbell_plot.py";
  std::error_code ec;
  if (!std::filesystem::exists(python, ec) || !std::filesystem::is_regular_file(script, ec)) {
    warnings.push_back("no Campbell chart: " + python + " or " + script + " is missing (the CSV is written)");
    return "";
  }
  auto quote = [](const std::string& t) {
    std::string q = "'";
    for (char c : t) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  };
  const std::string cmd = quote(python) + " " + quote(script) + " " + quote(csv) + " > /dev/null";
  std::cout.flush();
  if (std::system(cmd.c_str()) != 0) {
    warnings.push_back("no Campbell chart: " + cmd + " failed (the CSV is written)");
    return "";
  }
  return csv.substr(0, csv.size() - 4) + ".png";
}

/// Runs `write` on rank 0; an OutputError or InputError there is thrown on every rank.
template <class F>
void on_rank0(MPI_Comm comm, F write) {
  int rank = 0, ok = 1;
  MPI_Comm_rank(comm, &rank);
  std::string err;
  if (rank == 0) {
    try {
      write();
    } catch (const OutputError& e) {  // a file that cannot be written (exit 6)
      ok = 0;
      err = e.what();
    } catch (const InputError& e) {   // e.g. the chart script refused the table
      ok = -1;
      err = e.what();
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  if (ok == 0) throw OutputError(broadcast_text(err, comm));
  if (ok < 0) throw InputError(broadcast_text(err, comm));
}

ModalRunSummary modes_body(RunObjects& o, Scene& scene, const ModalRunOptions& opt, MPI_Comm comm) {
  const double wall0 = MPI_Wtime();
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

  ModalOptions mo = opt.modes;
  if (!mo.campbell_driver.empty()) {
    // The Campbell diagram: at each speed, the relative equilibrium of the structure turning about
    // the driver joint's axis (constructed directly: docs/modes.md says why), its modes in the
    // frame turning with it.
    for (const auto& c : sub.global_model().constraints())
      if (c->name() == mo.campbell_driver && std::string(c->type()) != "revolute")
        throw InputError(scene.file + ": modes.campbell.driver: joint '" + mo.campbell_driver + "' is a " + c->type() +
                         "; expected a revolute joint (the structure turns about its axis)");
    const JointFrame jf = joint_frame(sub, s, mo.campbell_driver, "modes.campbell.driver", scene.file);
    const double t0 = MPI_Wtime();
    for (double speed : mo.campbell_speeds) {
      const Eigen::Vector3d spin = speed * jf.axis;
      const MechanicalState steady = steady_rotation(*o.system, s, rs.load_factor, spin, jf.point);
      mo.frame_spin = spin;
      sum.campbell_speeds.push_back(speed);
      sum.campbell.push_back(compute_modes(*o.system, steady, rs.load_factor, mo));
    }
    sum.solve_wall = MPI_Wtime() - t0;
    sum.result = sum.campbell.back();
    sum.frame = "steady rotation about joint " + mo.campbell_driver + " (rotating frame), " +
                std::to_string(mo.campbell_speeds.size()) + " speeds";
    if (opt.write_results) {
      std::error_code ec;
      std::filesystem::create_directories(opt.outdir, ec);
      sum.campbell_csv = (std::filesystem::path(opt.outdir) / (scene.name + "_campbell.csv")).string();
      on_rank0(comm, [&] {
        write_campbell_csv(sum.campbell_csv, sum.campbell_speeds, sum.campbell);
        sum.campbell_chart = draw_campbell(sum.campbell_csv, sum.result.warnings);
      });
    }
    sum.wall = MPI_Wtime() - wall0;
    return sum;
  }
  if (!mo.rotating_frame.empty()) {
    mo.frame_spin = joint_frame(sub, s, mo.rotating_frame, "modes.rotating_frame", scene.file).spin;
    std::ostringstream os;
    os << "frame turning with joint " << mo.rotating_frame << " at |Omega| = " << mo.frame_spin.norm() << " rad/s";
    sum.frame = os.str();
  }
  const double t0 = MPI_Wtime();
  sum.result = compute_modes(*o.system, s, rs.load_factor, mo);
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
    on_rank0(comm, [&] { write_csv(sum.csv, sum.result); });
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
  if (!s.campbell.empty()) {
    os << "Campbell diagram of " << scene.name << ": " << s.frame << ", from the " << s.state << " on " << s.ranks
       << " rank(s)\n  speed (rad/s)  frequencies (Hz), whirl (f forward, b backward)\n";
    for (size_t i = 0; i < s.campbell.size(); ++i) {
      os << "  " << std::setw(13) << std::setprecision(6) << s.campbell_speeds[i] << " ";
      for (const Mode& m : s.campbell[i].modes)
        os << " " << std::setprecision(8) << m.frequency << (m.whirl.empty() ? "" : m.whirl == "forward" ? "f" : "b");
      os << "\n";
    }
    os << "  " << std::setprecision(3) << s.solve_wall << " s (whole command " << s.wall << " s)\n";
    for (const auto& w : r.warnings) os << "  warning: " << w << "\n";
    if (!s.campbell_csv.empty()) os << "  table: " << s.campbell_csv << "\n";
    if (!s.campbell_chart.empty()) os << "  chart: " << s.campbell_chart << "\n";
    return os.str();
  }
  os << "modes of " << scene.name << " about the " << s.state << " (t = " << s.time << " s, load factor "
     << s.load_factor << (s.frame.empty() ? "" : "; " + s.frame) << "): " << (r.damped ? "damped/gyroscopic (quadratic) problem" : "undamped problem") << ", "
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
