#include "alphaflex/io/results_writer.hpp"

#include <hdf5.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/fault_injection.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "hdf5_rows.hpp"

namespace alphaflex {

using io_detail::agree;
using io_detail::Rows;

namespace {

/// Shell elements (ReissnerMindlinShell), recognised by their type: io needs no element header.
bool is_shell(const Element& e) {
  const std::string type = e.type();
  return (type == "shell_quad4" && e.nodes().size() == 4) || (type == "shell_tri3" && e.nodes().size() == 3);
}

/// Result fields (Element::output) of the model's elements `which` at state s: one vector per field
/// (cell data), `nf` fields.
std::vector<std::vector<double>> element_fields(const Model& model, const std::vector<int>& which, size_t nf,
                                                const MechanicalState& s) {
  std::vector<std::vector<double>> fields(nf, std::vector<double>(which.size(), 0.0));
  LocalState ls;
  Eigen::VectorXd values;
  for (size_t b = 0; b < which.size(); ++b) {
    const Element& e = *model.elements()[static_cast<size_t>(which[b])];
    const auto idx = model.dofs_of(e.nodes());
    ls.q = gather(s.q, model.confs_of(e.nodes()));
    ls.v = gather(s.v, idx);
    ls.qdd = gather(s.qdd, idx);
    ls.t = s.t;
    e.output(ls, values);
    for (size_t f = 0; f < nf && f < static_cast<size_t>(values.size()); ++f) fields[f][b] = values[static_cast<Eigen::Index>(f)];
  }
  return fields;
}


/// rank 0's decision on every rank.
bool root_decides(const Subdomain& sub, bool decision) {
  int d = decision ? 1 : 0;
  if (sub.size() > 1) MPI_Bcast(&d, 1, MPI_INT, 0, sub.comm());
  return d != 0;
}

std::string part_file(long long k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "part_%06lld.h5", k);
  return buf;
}

std::string group_name(size_t k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "step_%06zu", k);
  return buf;
}

}  // namespace

struct ResultsWriter::RowsImpl {
  Rows node, joint, beam, shell, shell_conn;
  io_detail::StateRows state;
  explicit RowsImpl(const Subdomain& sub) : state(sub) {}
};

ResultsWriter::ResultsWriter(const Subdomain& sub, const std::string& outdir, const std::string& name, bool hdf5,
                             double commit_interval, const ResultsPosition* resume)
    : sub_(sub), model_(sub.model()), global_(sub.global_model()), root_(sub.rank() == 0), hdf5_(hdf5),
      commit_interval_(commit_interval), name_(name), rows_(std::make_unique<RowsImpl>(sub)) {
  // Beams (two-node elements with result fields) are drawn as line segments between their nodes,
  // shells (3- and 4-node shell elements) as triangles and quadrilaterals; rows in model order.
  std::map<int, int> beam_row, shell_row;
  std::vector<size_t> shell_offset;  // start of each shell's cell in the Mixed connectivity
  for (size_t e = 0; e < global_.elements().size(); ++e) {
    const Element& el = *global_.elements()[e];
    if (el.nodes().size() == 2 && !el.output_names().empty()) {
      if (beam_fields_.empty()) beam_fields_ = el.output_names();
      if (el.output_names() == beam_fields_) {
        beam_row[static_cast<int>(e)] = static_cast<int>(beams_.size());
        beams_.push_back(static_cast<int>(e));
      }
    } else if (is_shell(el) && !el.output_names().empty()) {
      if (shell_fields_.empty()) shell_fields_ = el.output_names();
      if (el.output_names() == shell_fields_) {
        shell_row[static_cast<int>(e)] = static_cast<int>(shells_.size());
        shells_.push_back(static_cast<int>(e));
        shell_offset.push_back(shell_topology_size_);
        shell_topology_size_ += 1 + el.nodes().size();
      }
    }
  }
  // This rank's rows. Local nodes, elements and joints are in increasing global order, so every
  // list below comes out sorted, as the file selections need.
  RowsImpl& r = *rows_;
  r.node.total = global_.nodes().size();
  for (int i = 0; i < sub.num_owned_nodes(); ++i) r.node.add(static_cast<unsigned long long>(sub.global_node(i)), 1);
  r.joint.total = global_.constraints().size();
  for (size_t c = 0; c < model_.constraints().size(); ++c)
    r.joint.add(static_cast<unsigned long long>(sub.global_constraint(static_cast<int>(c))), 1);
  r.beam.total = beams_.size();
  r.shell.total = shells_.size();
  r.shell_conn.total = shell_topology_size_;
  for (size_t e = 0; e < model_.elements().size(); ++e) {
    const int g = sub.global_element(static_cast<int>(e));
    if (auto b = beam_row.find(g); b != beam_row.end()) {
      r.beam.add(static_cast<unsigned long long>(b->second), 1);
      local_beams_.push_back(static_cast<int>(e));
    } else if (auto sh = shell_row.find(g); sh != shell_row.end()) {
      r.shell.add(static_cast<unsigned long long>(sh->second), 1);
      r.shell_conn.add(shell_offset[static_cast<size_t>(sh->second)], 1 + model_.elements()[e]->nodes().size());
      local_shells_.push_back(static_cast<int>(e));
    }
  }

  namespace fs = std::filesystem;
  const fs::path dir = fs::absolute(outdir);
  dir_ = dir.string();
  h5_path_ = (dir / (name + ".h5")).string();
  xdmf_path_ = (dir / (name + ".xdmf")).string();
  csv_path_ = (dir / (name + ".csv")).string();
  parts_name_ = name + ".h5.parts";
  parts_dir_ = (dir / parts_name_).string();
  // Rank 0 makes the directories and the CSV; the ranks agree before any collective file call.
  std::string err;
  if (root_) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) err = "output directory " + dir.string() + ": " + ec.message();
    if (err.empty() && hdf5_) {
      fs::create_directories(parts_dir_, ec);
      if (ec) err = "output directory " + parts_dir_ + ": " + ec.message();
    }
  }
  agree(sub, err);
  transfer_ = io_detail::transfer_list(sub.comm());
  if (resume) {
    resume_from(*resume);
    return;
  }
  if (root_) {
    if (!(csv_ = std::fopen(csv_path_.c_str(), "w"))) err = "cannot write " + csv_path_;
    else {
      std::fprintf(csv_, "t");
      for (const auto& s : global_.sensors()) std::fprintf(csv_, ",%s", s.name.c_str());
      std::fprintf(csv_, "\n");
      std::fflush(csv_);
    }
    // Parts of an earlier run in the same directory are not ours: remove them, and NAME.h5.
    if (err.empty() && hdf5_) {
      std::error_code ec;
      for (const auto& entry : fs::directory_iterator(parts_dir_, ec))
        if (entry.path().filename().string().rfind("part_", 0) == 0) fs::remove(entry.path(), ec);
      fs::remove(h5_path_, ec);
      fs::remove(xdmf_path_, ec);
    }
  }
  agree(sub, err);
  if (hdf5_ && root_) write_links();
}

ResultsWriter::~ResultsWriter() {
  if (csv_) std::fclose(csv_);
  // A part that was not committed stays under its temporary name: it is not part of the results.
  if (part_ >= 0) H5Fclose(part_);
  if (transfer_ >= 0) H5Pclose(transfer_);
}

void ResultsWriter::write_sensors(double t, const std::vector<double>& values) {
  ++csv_rows_;
  if (!root_) return;
  std::fprintf(csv_, "%.17g", t);
  for (double v : values) std::fprintf(csv_, ",%.17g", v);
  std::fprintf(csv_, "\n");
}

void ResultsWriter::write_topology(long long file) {
  const RowsImpl& r = *rows_;
  const hid_t topo = H5Gcreate2(file, "topology", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  std::string e;
  auto keep = [&](const std::string& x) {
    if (e.empty() && !x.empty()) e = x;
  };
  std::vector<int> ids;
  for (int i = 0; i < sub_.num_owned_nodes(); ++i) ids.push_back(sub_.global_node(i));
  keep(io_detail::write_int_rows(topo, "nodes", r.node, ids.data(), transfer_));
  ids.clear();
  for (size_t c = 0; c < model_.constraints().size(); ++c) ids.push_back(sub_.global_constraint(static_cast<int>(c)));
  keep(io_detail::write_int_rows(topo, "joints", r.joint, ids.data(), transfer_));
  if (!beams_.empty()) {
    Rows conn = r.beam;  // two node ids per beam: the same rows, twice as long
    conn.total *= 2;
    conn.mine *= 2;
    for (size_t k = 0; k < conn.start.size(); ++k) {
      conn.start[k] *= 2;
      conn.count[k] *= 2;
    }
    ids.clear();
    for (int el : local_beams_)
      for (int n : model_.elements()[static_cast<size_t>(el)]->nodes()) ids.push_back(sub_.global_node(n));
    keep(io_detail::write_int_rows(topo, "beam_connectivity", conn, ids.data(), transfer_));
  }
  if (!shells_.empty()) {
    // XDMF Mixed topology: per cell its XDMF type (4 triangle, 5 quadrilateral), then its nodes.
    ids.clear();
    for (int el : local_shells_) {
      const auto& en = model_.elements()[static_cast<size_t>(el)]->nodes();
      ids.push_back(en.size() == 3 ? 4 : 5);
      for (int n : en) ids.push_back(sub_.global_node(n));
    }
    keep(io_detail::write_int_rows(topo, "shell_connectivity", r.shell_conn, ids.data(), transfer_));
  }
  H5Gclose(topo);
  if (error_.empty()) error_ = e;
}

void ResultsWriter::open_part() {
  // A new part, under a temporary name until it is committed, with the topology of the model
  // (every part is complete in itself: the index needs no other file).
  const std::string tmp = parts_dir_ + "/" + part_file(parts_) + ".tmp";
  const hid_t fapl = io_detail::file_access(sub_.comm());
  part_ = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  agree(sub_, part_ < 0 ? "cannot create " + tmp : std::string());
  write_topology(part_);
  part_opened_ = std::chrono::steady_clock::now();
}

void ResultsWriter::write_fields(const MechanicalState& s) {
  if (!hdf5_) return;
  if (part_ < 0) open_part();
  // This rank's owned nodes (local 0 … owned−1, in increasing global order).
  const size_t nn = static_cast<size_t>(sub_.num_owned_nodes()), nj = model_.constraints().size();
  std::vector<double> pos(3 * nn, 0.0), vel(3 * nn, 0.0), acc(3 * nn, 0.0), ang(nn, 0.0), axis(3 * nn, 0.0);
  std::vector<double> axis2(3 * nn, 0.0), axis3(3 * nn, 0.0), quat(4 * nn, 0.0), disp(3 * nn, 0.0);
  for (size_t i = 0; i < nn; ++i) {
    const Node& n = model_.nodes()[i];
    if (n.spatial()) {
      const Pose<double> p = pose_of(s.q.data() + n.first_conf);
      for (int k = 0; k < 3; ++k) {
        pos[3 * i + k] = p.x[k];
        disp[3 * i + k] = p.x[k] - n.q0[k];
        vel[3 * i + k] = s.v[n.first_dof + k];
        acc[3 * i + k] = s.qdd[n.first_dof + k];
        axis[3 * i + k] = p.R(k, 0);
        axis2[3 * i + k] = p.R(k, 1);
        axis3[3 * i + k] = p.R(k, 2);
      }
      for (int k = 0; k < 4; ++k) quat[4 * i + k] = s.q[n.first_conf + 3 + k];  // (w, x, y, z)
      continue;
    }
    const PlanarMarker m = PlanarMarker::on_node(n, Eigen::Vector2d::Zero(), 0);
    const Eigen::VectorXd q = s.q.segment(n.first_conf, n.nconf), v = s.v.segment(n.first_dof, n.ndof);
    const Eigen::VectorXd a = s.qdd.segment(n.first_dof, n.ndof);
    const Eigen::Vector2d p = m.position(q), pv = m.velocity(q, v);
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(2, n.ndof);
    m.add_jacobian(q, 1.0, J);
    const Eigen::Vector2d pa = J * a + m.convective_acceleration(q, v);
    const double th = n.has_angle() ? q[2] : 0.0;
    for (int k = 0; k < 2; ++k) {
      pos[3 * i + k] = p[k];
      vel[3 * i + k] = pv[k];
      acc[3 * i + k] = pa[k];
    }
    ang[i] = th;
    axis[3 * i] = std::cos(th);
    axis[3 * i + 1] = std::sin(th);
    axis2[3 * i] = -std::sin(th);
    axis2[3 * i + 1] = std::cos(th);
    axis3[3 * i + 2] = 1.0;
    quat[4 * i] = std::cos(th / 2.0);
    quat[4 * i + 3] = std::sin(th / 2.0);
    const Eigen::Vector2d p0 = m.position(n.q0);
    disp[3 * i] = p[0] - p0[0];
    disp[3 * i + 1] = p[1] - p0[1];
  }
  std::vector<double> jloc(3 * nj, 0.0), jforce(3 * nj, 0.0), jmoment(3 * nj, 0.0);
  for (size_t c = 0; c < nj; ++c) {
    const Constraint& con = *model_.constraints()[c];
    const JointReaction r = con.reaction(gather(s.q, model_.confs_of(con.nodes())), s.t,
                                         s.lambda.segment(model_.first_multiplier(static_cast<int>(c)), con.size()));
    for (int k = 0; k < 3; ++k) {
      jloc[3 * c + k] = r.location[k];
      jforce[3 * c + k] = r.force[k];
      jmoment[3 * c + k] = r.moment[k];
    }
  }
  const RowsImpl& r = *rows_;
  const std::string gname = group_name(times_.size() + open_times_.size());
  const hid_t g = H5Gcreate2(part_, gname.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  agree(sub_, g < 0 ? "cannot create the group " + gname + " in " + parts_dir_ : std::string());
  {
    // time: an array of one double (the layout scripts read as attrs["time"][0]); every rank
    // writes the same value: collective.
    const hsize_t one = 1;
    const hid_t aspace = H5Screate_simple(1, &one, nullptr);
    const hid_t attr = H5Acreate2(g, "time", H5T_IEEE_F64LE, aspace, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attr, H5T_NATIVE_DOUBLE, &s.t);
    H5Aclose(attr);
    H5Sclose(aspace);
  }
  auto keep = [&](const std::string& x) {
    if (error_.empty() && !x.empty()) error_ = x + " of " + parts_dir_;
  };
  auto put = [&](const char* set, const Rows& rows, int cols, const double* data) {
    keep(io_detail::write_rows(g, set, rows, cols, data, transfer_));
  };
  put("node_position", r.node, 3, pos.data());
  put("node_velocity", r.node, 3, vel.data());
  put("node_acceleration", r.node, 3, acc.data());
  put("node_angle", r.node, 1, ang.data());
  put("node_axis", r.node, 3, axis.data());
  put("node_axis2", r.node, 3, axis2.data());
  put("node_axis3", r.node, 3, axis3.data());
  put("node_quaternion", r.node, 4, quat.data());
  put("node_displacement", r.node, 3, disp.data());
  if (!beams_.empty()) {
    // Section forces and strains per beam element (constant on a two-node element): cell data.
    const size_t nf = beam_fields_.size();
    const auto fields = element_fields(model_, local_beams_, nf, s);
    for (size_t f = 0; f < nf; ++f) put(("beam_" + beam_fields_[f]).c_str(), r.beam, 1, fields[f].data());
  }
  if (!shells_.empty()) {
    // Stress resultants and von Mises stresses per shell element (its area-weighted mean): cell data.
    const size_t nf = shell_fields_.size();
    const auto fields = element_fields(model_, local_shells_, nf, s);
    for (size_t f = 0; f < nf; ++f) put(("shell_" + shell_fields_[f]).c_str(), r.shell, 1, fields[f].data());
  }
  put("joint_location", r.joint, 3, jloc.data());
  put("joint_force", r.joint, 3, jforce.data());
  put("joint_moment", r.joint, 3, jmoment.data());
  // Generalized state in model order, for scripts and convergence studies: the owned part of the
  // local vectors (owned nodes come first) at their places.
  put("q", r.state.conf, 1, s.q.data());
  put("v", r.state.dof, 1, s.v.data());
  put("qdd", r.state.dof, 1, s.qdd.data());
  put("lambda", r.state.mult, 1, s.lambda.data());
  H5Gclose(g);
  // Tests of error handling: a write that fails on one rank only.
  if (fault_injected("output") && error_.empty()) error_ = "injected fault (-af_inject_fault output): cannot write " + h5_path_;
  const std::string failed = error_;
  error_.clear();
  agree(sub_, failed);  // every rank throws the same InputError if one write failed
  open_times_.push_back(s.t);
  open_groups_.push_back(gname);
  if (csv_) std::fflush(csv_);
  // Commit when the part has been open long enough (rank 0's clock decides for all), and at once
  // the first output step: from then on there is always an index to open. The index and NAME.h5
  // grow with the steps, so a commit costs more as a run goes on: the interval also grows to ten
  // times the last commit's cost, which keeps commits under ~10 % of the run.
  const double open_for = std::chrono::duration<double>(std::chrono::steady_clock::now() - part_opened_).count();
  if (root_decides(sub_, open_for >= std::max(commit_interval_, 10.0 * last_commit_cost_) || parts_ == 0)) commit();
}

void ResultsWriter::commit() {
  if (csv_) std::fflush(csv_);
  if (!hdf5_ || part_ < 0) return;
  const auto started = std::chrono::steady_clock::now();
  // Close (collective: all of every rank's rows are on disk), then rename into place, link the new
  // steps from NAME.h5 and rewrite the index (rank 0): each is a new file renamed over the old one,
  // so a kill at any moment leaves complete files and an index of complete steps.
  const herr_t closed = H5Fclose(part_);
  part_ = -1;
  std::string err = closed < 0 ? "cannot close " + parts_dir_ + "/" + part_file(parts_) + ".tmp" : std::string();
  if (root_ && err.empty()) {
    std::error_code ec;
    const std::string final_path = parts_dir_ + "/" + part_file(parts_);
    std::filesystem::rename(final_path + ".tmp", final_path, ec);
    if (ec) err = "cannot rename " + final_path + ".tmp: " + ec.message();
  }
  for (size_t k = 0; k < open_times_.size(); ++k) {
    times_.push_back(open_times_[k]);
    groups_.push_back(open_groups_[k]);
    group_part_.push_back(parts_);
  }
  open_times_.clear();
  open_groups_.clear();
  ++parts_;
  if (err.empty()) err = write_index();
  agree(sub_, err);
  last_commit_cost_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

void ResultsWriter::finish() {
  commit();
  if (csv_) std::fflush(csv_);
}

ResultsPosition ResultsWriter::position() const {
  ResultsPosition p;
  p.csv_rows = csv_rows_;
  p.steps = static_cast<long long>(times_.size());
  p.parts = parts_;
  return p;
}

void ResultsWriter::write_links() {
  // NAME.h5 holds external links only: /topology to the first part's, /step_NNNNNN to the part
  // that has it. Rebuilt as a new file and renamed over the old one (a few kB per 100 steps).
  const std::string tmp = h5_path_ + ".tmp";
  const hid_t f = H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (f < 0) throw InputError("cannot write " + tmp);
  const std::string first = parts_name_ + "/" + part_file(0);
  H5Lcreate_external(first.c_str(), "/topology", f, "topology", H5P_DEFAULT, H5P_DEFAULT);
  for (size_t k = 0; k < groups_.size(); ++k) {
    const std::string target = parts_name_ + "/" + part_file(group_part_[k]);
    H5Lcreate_external(target.c_str(), ("/" + groups_[k]).c_str(), f, groups_[k].c_str(), H5P_DEFAULT, H5P_DEFAULT);
  }
  if (H5Fclose(f) < 0) throw InputError("cannot write " + tmp);
  std::error_code ec;
  std::filesystem::rename(tmp, h5_path_, ec);
  if (ec) throw InputError("cannot rename " + tmp + ": " + ec.message());
}

void ResultsWriter::resume_from(const ResultsPosition& at) {
  namespace fs = std::filesystem;
  std::string err;
  if (root_) {
    // The CSV up to the checkpoint's rows (header + rows), or a new one if it is gone.
    std::ifstream in(csv_path_);
    std::vector<std::string> lines;
    for (std::string line; lines.size() < static_cast<size_t>(at.csv_rows) + 1 && std::getline(in, line);) lines.push_back(line);
    in.close();
    std::string header = "t";
    for (const auto& s : global_.sensors()) header += "," + s.name;
    if (lines.empty() || lines[0] != header || lines.size() != static_cast<size_t>(at.csv_rows) + 1) {
      warnings_.push_back(csv_path_ + " does not hold the " + std::to_string(at.csv_rows) +
                          " sensor rows of the checkpoint: it is started anew, from the restart time");
      lines.assign(1, header);
    }
    if (!(csv_ = std::fopen(csv_path_.c_str(), "w"))) err = "cannot write " + csv_path_;
    else {
      for (const auto& l : lines) std::fprintf(csv_, "%s\n", l.c_str());
      std::fflush(csv_);
    }
  }
  csv_rows_ = at.csv_rows;
  agree(sub_, err);
  if (!hdf5_) return;
  // The parts up to the checkpoint's, and their steps' times (rank 0 reads them; all need them).
  std::vector<double> times;
  std::vector<long long> parts_of;
  if (root_) {
    std::error_code ec;
    for (long long k = 0; k < at.parts && err.empty(); ++k) {
      const std::string path = parts_dir_ + "/" + part_file(k);
      const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      if (f < 0) {
        err = "restart: the results of the checkpoint are incomplete (" + path + " is missing or unreadable); restart into a new output directory (-o) to start the results anew";
        break;
      }
      for (size_t g = times.size();; ++g) {
        const std::string name = group_name(g);
        if (H5Lexists(f, name.c_str(), H5P_DEFAULT) <= 0) break;
        const hid_t grp = H5Gopen2(f, name.c_str(), H5P_DEFAULT);
        double t = 0.0;
        io_detail::read_attribute(grp, "time", t);
        H5Gclose(grp);
        times.push_back(t);
        parts_of.push_back(k);
      }
      H5Fclose(f);
    }
    if (err.empty() && static_cast<long long>(times.size()) != at.steps)
      err = "restart: the parts in " + parts_dir_ + " hold " + std::to_string(times.size()) + " output steps, the checkpoint " +
            std::to_string(at.steps) + "; restart into a new output directory (-o)";
    // Later parts (and an unfinished one) belong to the part of the run after the checkpoint.
    for (const auto& entry : fs::directory_iterator(parts_dir_, ec)) {
      const std::string f = entry.path().filename().string();
      if (f.rfind("part_", 0) != 0) continue;
      const long long k = std::atoll(f.substr(5, 6).c_str());
      if (k >= at.parts || f.size() > 14) fs::remove(entry.path(), ec);
    }
  }
  // A fresh output directory: the results continue from the restart, numbered after the checkpoint's.
  const bool fresh = root_decides(sub_, root_ && at.parts > 0 && !fs::exists(parts_dir_ + "/" + part_file(0)));
  if (fresh) {
    err.clear();
    times.clear();
    parts_of.clear();
    if (root_) warnings_.push_back(parts_dir_ + " does not hold the checkpoint's results: the HDF5 output starts anew at the restart time");
  }
  agree(sub_, err);
  unsigned long long n = times.size();
  if (sub_.size() > 1) MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, sub_.comm());
  times.resize(n);
  parts_of.resize(n);
  if (sub_.size() > 1 && n > 0) {
    MPI_Bcast(times.data(), static_cast<int>(n), MPI_DOUBLE, 0, sub_.comm());
    MPI_Bcast(parts_of.data(), static_cast<int>(n), MPI_LONG_LONG, 0, sub_.comm());
  }
  for (size_t k = 0; k < n; ++k) {
    times_.push_back(times[k]);
    groups_.push_back(group_name(k));
    group_part_.push_back(parts_of[k]);
  }
  // In a fresh directory the HDF5 results start at the restart: steps and parts numbered from 0.
  parts_ = fresh ? 0 : at.parts;
  err = write_index();
  agree(sub_, err);
}

std::string ResultsWriter::write_index() {
  if (!root_) return {};
  try {
    write_links();
    write_xdmf();
  } catch (const std::exception& e) {
    return e.what();
  }
  return {};
}

void ResultsWriter::write_xdmf() const {
  const size_t nn = global_.nodes().size(), nj = global_.constraints().size();
  // Every step refers to its own part: the part's topology and the step's group.
  auto in_part = [&](size_t s) { return parts_name_ + "/" + part_file(group_part_[s]); };
  const std::string tmp = xdmf_path_ + ".tmp";
  std::ofstream x(tmp);
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n";
  auto item = [&](size_t s, const char* set, size_t rows, int cols) {
    x << "      <DataItem Dimensions=\"" << rows;
    if (cols > 1) x << " " << cols;
    x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << in_part(s) << ":/" << groups_[s] << "/" << set
      << "</DataItem>\n";
  };
  auto grid = [&](const char* name, size_t n, const char* topo, const char* geom,
                  std::initializer_list<std::pair<const char*, const char*>> attrs) {
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < times_.size(); ++s) {
      x << "   <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n    <Time Value=\"" << times_[s] << "\"/>\n"
        << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\">\n"
        << "      <DataItem Dimensions=\"" << n << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << in_part(s)
        << ":/topology/" << topo << "</DataItem>\n    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n";
      item(s, geom, n, 3);
      x << "    </Geometry>\n";
      for (const auto& [aname, set] : attrs) {
        const std::string name = set;
        const bool scalar = name == "node_angle", quaternion = name == "node_quaternion";
        x << "    <Attribute Name=\"" << aname << "\" AttributeType=\""
          << (scalar ? "Scalar" : quaternion ? "Matrix" : "Vector") << "\" Center=\"Node\">\n";
        item(s, set, n, scalar ? 1 : quaternion ? 4 : 3);
        x << "    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n";
  };
  grid("bodies", nn, "nodes", "node_position",
       {{"displacement", "node_displacement"}, {"velocity", "node_velocity"}, {"acceleration", "node_acceleration"},
        {"angle", "node_angle"}, {"axis", "node_axis"}, {"axis2", "node_axis2"}, {"axis3", "node_axis3"},
        {"quaternion", "node_quaternion"}});
  // An element grid (beams, shells) per output step: its topology, the nodes' positions and
  // motion as point data, the elements' results (prefix + field in the HDF5 file) as cell data.
  using Pairs = std::vector<std::pair<const char*, const char*>>;
  auto element_grid = [&](const char* name, const std::function<std::string(size_t)>& topology, const Pairs& vectors,
                          const std::vector<std::string>& fields, const std::string& prefix, size_t ncells) {
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < times_.size(); ++s) {
      x << "   <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n    <Time Value=\"" << times_[s] << "\"/>\n"
        << topology(s) << "    <Geometry GeometryType=\"XYZ\">\n";
      item(s, "node_position", nn, 3);
      x << "    </Geometry>\n";
      for (const auto& [aname, set] : vectors) {
        x << "    <Attribute Name=\"" << aname << "\" AttributeType=\"Vector\" Center=\"Node\">\n";
        item(s, set, nn, 3);
        x << "    </Attribute>\n";
      }
      x << "    <Attribute Name=\"quaternion\" AttributeType=\"Matrix\" Center=\"Node\">\n";
      item(s, "node_quaternion", nn, 4);
      x << "    </Attribute>\n";
      for (const auto& f : fields) {
        x << "    <Attribute Name=\"" << f << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
        item(s, (prefix + f).c_str(), ncells, 1);
        x << "    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n";
  };
  if (!beams_.empty()) {
    // Beams: line segments in the deformed configuration, node frames and section results.
    const size_t nb = beams_.size();
    auto topo = [&](size_t s) {
      std::ostringstream t;
      t << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << nb << "\" NodesPerElement=\"2\">\n"
        << "      <DataItem Dimensions=\"" << nb << " 2\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << in_part(s)
        << ":/topology/beam_connectivity</DataItem>\n    </Topology>\n";
      return t.str();
    };
    element_grid("beams", topo,
                 {{"displacement", "node_displacement"}, {"velocity", "node_velocity"}, {"axis2", "node_axis2"}, {"axis3", "node_axis3"}},
                 beam_fields_, "beam_", nb);
  }
  if (!shells_.empty()) {
    // Shells: triangles and quadrilaterals (one Mixed topology) in the deformed configuration,
    // node motion and the elements' resultants and stresses.
    const size_t ns = shells_.size();
    auto topo = [&](size_t s) {
      std::ostringstream t;
      t << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << ns << "\">\n"
        << "      <DataItem Dimensions=\"" << shell_topology_size_ << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
        << in_part(s) << ":/topology/shell_connectivity</DataItem>\n    </Topology>\n";
      return t.str();
    };
    element_grid("shells", topo,
                 {{"displacement", "node_displacement"}, {"velocity", "node_velocity"}, {"acceleration", "node_acceleration"}},
                 shell_fields_, "shell_", ns);
  }
  if (nj > 0) grid("joints", nj, "joints", "joint_location", {{"force", "joint_force"}, {"moment", "joint_moment"}});
  x << " </Domain>\n</Xdmf>\n";
  x.close();
  if (!x) throw InputError("cannot write " + tmp);
  std::error_code ec;
  std::filesystem::rename(tmp, xdmf_path_, ec);
  if (ec) throw InputError("cannot rename " + tmp + ": " + ec.message());
}

}  // namespace alphaflex
