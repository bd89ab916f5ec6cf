#include "alphaflex/io/results_writer.hpp"

#include <hdf5.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {
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

/// The same result on every rank: failed anywhere means failed everywhere, with rank 0's message
/// (or the first failing rank's), so that no rank goes on into a collective call alone.
void agree(const Subdomain& sub, const std::string& local_error) {
  const int mine = local_error.empty() ? sub.size() : sub.rank();
  int first = mine;
  if (sub.size() > 1) MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, sub.comm());
  if (first == sub.size()) return;
  throw InputError(sub.broadcast(local_error, first));
}

}  // namespace

void ResultsWriter::Rows::add(unsigned long long first, unsigned long long n) {
  if (n == 0) return;
  if (!start.empty() && start.back() + count.back() == first) count.back() += n;
  else {
    start.push_back(first);
    count.push_back(n);
  }
  mine += n;
}

ResultsWriter::ResultsWriter(const Subdomain& sub, const std::string& outdir, const std::string& name, bool hdf5)
    : sub_(sub), model_(sub.model()), global_(sub.global_model()), root_(sub.rank() == 0), hdf5_(hdf5) {
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
  node_rows_.total = global_.nodes().size();
  conf_rows_.total = static_cast<unsigned long long>(global_.num_conf());
  dof_rows_.total = static_cast<unsigned long long>(global_.num_dofs());
  for (int i = 0; i < sub.num_owned_nodes(); ++i) {
    const Node& g = global_.node(sub.global_node(i));
    node_rows_.add(static_cast<unsigned long long>(sub.global_node(i)), 1);
    conf_rows_.add(static_cast<unsigned long long>(g.first_conf), static_cast<unsigned long long>(g.nconf));
    dof_rows_.add(static_cast<unsigned long long>(g.first_dof), static_cast<unsigned long long>(g.ndof));
  }
  joint_rows_.total = global_.constraints().size();
  mult_rows_.total = static_cast<unsigned long long>(global_.num_multipliers());
  for (size_t c = 0; c < model_.constraints().size(); ++c) {
    const int g = sub.global_constraint(static_cast<int>(c));
    joint_rows_.add(static_cast<unsigned long long>(g), 1);
    mult_rows_.add(static_cast<unsigned long long>(global_.first_multiplier(g)),
                   static_cast<unsigned long long>(model_.constraints()[c]->size()));
  }
  beam_rows_.total = beams_.size();
  shell_rows_.total = shells_.size();
  shell_conn_rows_.total = shell_topology_size_;
  for (size_t e = 0; e < model_.elements().size(); ++e) {
    const int g = sub.global_element(static_cast<int>(e));
    if (auto b = beam_row.find(g); b != beam_row.end()) {
      beam_rows_.add(static_cast<unsigned long long>(b->second), 1);
      local_beams_.push_back(static_cast<int>(e));
    } else if (auto sh = shell_row.find(g); sh != shell_row.end()) {
      shell_rows_.add(static_cast<unsigned long long>(sh->second), 1);
      shell_conn_rows_.add(shell_offset[static_cast<size_t>(sh->second)], 1 + model_.elements()[e]->nodes().size());
      local_shells_.push_back(static_cast<int>(e));
    }
  }

  namespace fs = std::filesystem;
  const fs::path dir = fs::absolute(outdir);
  h5_name_ = name + ".h5";
  h5_path_ = (dir / h5_name_).string();
  xdmf_path_ = (dir / (name + ".xdmf")).string();
  csv_path_ = (dir / (name + ".csv")).string();
  // Rank 0 makes the directory and the CSV; the ranks agree before the collective file creation.
  std::string err;
  if (root_) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) err = "output directory " + dir.string() + ": " + ec.message();
    else if (!(csv_ = std::fopen(csv_path_.c_str(), "w"))) err = "cannot write " + csv_path_;
    else {
      std::fprintf(csv_, "t");
      for (const auto& s : global_.sensors()) std::fprintf(csv_, ",%s", s.name.c_str());
      std::fprintf(csv_, "\n");
    }
  }
  agree(sub, err);
  if (!hdf5_) return;

  // Parallel HDF5 (MPI-IO) with collective transfers when there is more than one rank; the file
  // is the same either way.
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  transfer_ = H5Pcreate(H5P_DATASET_XFER);
  if (sub.size() > 1) {
    H5Pset_fapl_mpio(fapl, sub.comm(), MPI_INFO_NULL);
    H5Pset_dxpl_mpio(transfer_, H5FD_MPIO_COLLECTIVE);
  }
  file_ = H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl);
  H5Pclose(fapl);
  agree(sub, file_ < 0 ? "cannot create " + h5_path_ : std::string());

  const hid_t topo = H5Gcreate2(file_, "topology", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  std::vector<int> ids;
  for (int i = 0; i < sub.num_owned_nodes(); ++i) ids.push_back(sub.global_node(i));
  write_int_rows(topo, "nodes", node_rows_, ids.data());
  ids.clear();
  for (size_t c = 0; c < model_.constraints().size(); ++c) ids.push_back(sub.global_constraint(static_cast<int>(c)));
  write_int_rows(topo, "joints", joint_rows_, ids.data());
  if (!beams_.empty()) {
    Rows conn = beam_rows_;  // two node ids per beam: the same rows, twice as long
    conn.total *= 2;
    conn.mine *= 2;
    for (size_t k = 0; k < conn.start.size(); ++k) {
      conn.start[k] *= 2;
      conn.count[k] *= 2;
    }
    ids.clear();
    for (int e : local_beams_)
      for (int n : model_.elements()[static_cast<size_t>(e)]->nodes()) ids.push_back(sub.global_node(n));
    write_int_rows(topo, "beam_connectivity", conn, ids.data());
  }
  if (!shells_.empty()) {
    // XDMF Mixed topology: per cell its XDMF type (4 triangle, 5 quadrilateral), then its nodes.
    ids.clear();
    for (int e : local_shells_) {
      const auto& en = model_.elements()[static_cast<size_t>(e)]->nodes();
      ids.push_back(en.size() == 3 ? 4 : 5);
      for (int n : en) ids.push_back(sub.global_node(n));
    }
    write_int_rows(topo, "shell_connectivity", shell_conn_rows_, ids.data());
  }
  H5Gclose(topo);
}

ResultsWriter::~ResultsWriter() {
  if (csv_) std::fclose(csv_);
  if (transfer_ >= 0) H5Pclose(transfer_);
  if (file_ >= 0) H5Fclose(file_);
}

void ResultsWriter::write_sensors(double t, const std::vector<double>& values) {
  if (!root_) return;
  std::fprintf(csv_, "%.17g", t);
  for (double v : values) std::fprintf(csv_, ",%.17g", v);
  std::fprintf(csv_, "\n");
}

namespace {

/// The file dataspace of a `total` × `cols` dataset with this rank's rows selected, and the
/// matching memory dataspace.
std::pair<hid_t, hid_t> selections(const std::vector<unsigned long long>& start, const std::vector<unsigned long long>& count,
                                   unsigned long long total, unsigned long long mine, int cols) {
  const hsize_t dims[2] = {total, static_cast<hsize_t>(cols)};
  const int rank = cols > 1 ? 2 : 1;
  const hid_t file = H5Screate_simple(rank, dims, nullptr);
  const hsize_t mdims[2] = {std::max<hsize_t>(mine, 1), static_cast<hsize_t>(cols)};
  const hid_t mem = H5Screate_simple(rank, mdims, nullptr);
  if (mine == 0) {
    H5Sselect_none(file);
    H5Sselect_none(mem);
    return {file, mem};
  }
  H5Sselect_none(file);
  for (size_t k = 0; k < start.size(); ++k) {
    const hsize_t off[2] = {start[k], 0}, cnt[2] = {count[k], static_cast<hsize_t>(cols)};
    H5Sselect_hyperslab(file, H5S_SELECT_OR, off, nullptr, cnt, nullptr);
  }
  return {file, mem};
}

}  // namespace

void ResultsWriter::write_rows(long long loc, const char* name, const Rows& rows, int cols, const double* data) {
  const auto [file_space, mem_space] = selections(rows.start, rows.count, rows.total, rows.mine, cols);
  const hid_t set = H5Dcreate2(loc, name, H5T_IEEE_F64LE, file_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0) throw std::runtime_error(std::string("HDF5: cannot create dataset ") + name);
  if (rows.total > 0) H5Dwrite(set, H5T_NATIVE_DOUBLE, mem_space, file_space, transfer_, data);
  H5Dclose(set);
  H5Sclose(mem_space);
  H5Sclose(file_space);
}

void ResultsWriter::write_int_rows(long long loc, const char* name, const Rows& rows, const int* data) {
  const auto [file_space, mem_space] = selections(rows.start, rows.count, rows.total, rows.mine, 1);
  const hid_t set = H5Dcreate2(loc, name, H5T_STD_I32LE, file_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0) throw std::runtime_error(std::string("HDF5: cannot create dataset ") + name);
  if (rows.total > 0) H5Dwrite(set, H5T_NATIVE_INT, mem_space, file_space, transfer_, data);
  H5Dclose(set);
  H5Sclose(mem_space);
  H5Sclose(file_space);
}

void ResultsWriter::write_fields(const MechanicalState& s) {
  if (!hdf5_) return;
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
  char gname[32];
  std::snprintf(gname, sizeof gname, "step_%06zu", times_.size());
  const hid_t g = H5Gcreate2(file_, gname, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) throw std::runtime_error("HDF5: cannot create group " + std::string(gname));
  const hsize_t one = 1;
  const hid_t aspace = H5Screate_simple(1, &one, nullptr);
  const hid_t attr = H5Acreate2(g, "time", H5T_IEEE_F64LE, aspace, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &s.t);  // every rank writes the same value: collective
  H5Aclose(attr);
  H5Sclose(aspace);
  write_rows(g, "node_position", node_rows_, 3, pos.data());
  write_rows(g, "node_velocity", node_rows_, 3, vel.data());
  write_rows(g, "node_acceleration", node_rows_, 3, acc.data());
  write_rows(g, "node_angle", node_rows_, 1, ang.data());
  write_rows(g, "node_axis", node_rows_, 3, axis.data());
  write_rows(g, "node_axis2", node_rows_, 3, axis2.data());
  write_rows(g, "node_axis3", node_rows_, 3, axis3.data());
  write_rows(g, "node_quaternion", node_rows_, 4, quat.data());
  write_rows(g, "node_displacement", node_rows_, 3, disp.data());
  if (!beams_.empty()) {
    // Section forces and strains per beam element (constant on a two-node element): cell data.
    const size_t nf = beam_fields_.size();
    const auto fields = element_fields(model_, local_beams_, nf, s);
    for (size_t f = 0; f < nf; ++f) write_rows(g, ("beam_" + beam_fields_[f]).c_str(), beam_rows_, 1, fields[f].data());
  }
  if (!shells_.empty()) {
    // Stress resultants and von Mises stresses per shell element (its area-weighted mean): cell data.
    const size_t nf = shell_fields_.size();
    const auto fields = element_fields(model_, local_shells_, nf, s);
    for (size_t f = 0; f < nf; ++f) write_rows(g, ("shell_" + shell_fields_[f]).c_str(), shell_rows_, 1, fields[f].data());
  }
  write_rows(g, "joint_location", joint_rows_, 3, jloc.data());
  write_rows(g, "joint_force", joint_rows_, 3, jforce.data());
  write_rows(g, "joint_moment", joint_rows_, 3, jmoment.data());
  // Generalized state in model order, for scripts and convergence studies: the owned part of the
  // local vectors (owned nodes come first) at their places.
  write_rows(g, "q", conf_rows_, 1, s.q.data());
  write_rows(g, "v", dof_rows_, 1, s.v.data());
  write_rows(g, "qdd", dof_rows_, 1, s.qdd.data());
  write_rows(g, "lambda", mult_rows_, 1, s.lambda.data());
  H5Gclose(g);
  // Flushing costs ~0.7 ms per call (it dominated small runs when done every step): at most once
  // per second of wall time, and always at the end, so a killed run loses at most ~1 s of output.
  // Collective, so rank 0's clock decides for all.
  const auto now = std::chrono::steady_clock::now();
  int flush = now - last_flush_ > std::chrono::seconds(1) ? 1 : 0;
  if (sub_.size() > 1) MPI_Bcast(&flush, 1, MPI_INT, 0, sub_.comm());
  if (flush) {
    H5Fflush(file_, H5F_SCOPE_GLOBAL);
    last_flush_ = now;
  }
  times_.push_back(s.t);
  groups_.push_back(gname);
  if (csv_) std::fflush(csv_);
}

void ResultsWriter::finish() {
  if (csv_) std::fflush(csv_);
  if (!hdf5_) return;
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
  if (root_) write_xdmf();
}

void ResultsWriter::write_xdmf() const {
  const size_t nn = global_.nodes().size(), nj = global_.constraints().size();
  const std::string tmp = xdmf_path_ + ".tmp";
  std::ofstream x(tmp);
  x.precision(17);
  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n <Domain>\n";
  auto item = [&](const std::string& g, const char* set, size_t rows, int cols) {
    x << "      <DataItem Dimensions=\"" << rows;
    if (cols > 1) x << " " << cols;
    x << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << h5_name_ << ":/" << g << "/" << set
      << "</DataItem>\n";
  };
  auto grid = [&](const char* name, size_t n, const char* topo, const char* geom,
                  std::initializer_list<std::pair<const char*, const char*>> attrs) {
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < times_.size(); ++s) {
      x << "   <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n    <Time Value=\"" << times_[s] << "\"/>\n"
        << "    <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n << "\" NodesPerElement=\"1\">\n"
        << "      <DataItem Dimensions=\"" << n << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5_name_
        << ":/topology/" << topo << "</DataItem>\n    </Topology>\n    <Geometry GeometryType=\"XYZ\">\n";
      item(groups_[s], geom, n, 3);
      x << "    </Geometry>\n";
      for (const auto& [aname, set] : attrs) {
        const std::string name = set;
        const bool scalar = name == "node_angle", quaternion = name == "node_quaternion";
        x << "    <Attribute Name=\"" << aname << "\" AttributeType=\""
          << (scalar ? "Scalar" : quaternion ? "Matrix" : "Vector") << "\" Center=\"Node\">\n";
        item(groups_[s], set, n, scalar ? 1 : quaternion ? 4 : 3);
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
  auto element_grid = [&](const char* name, const std::string& topology, const Pairs& vectors,
                          const std::vector<std::string>& fields, const std::string& prefix, size_t ncells) {
    x << "  <Grid Name=\"" << name << "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (size_t s = 0; s < times_.size(); ++s) {
      x << "   <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n    <Time Value=\"" << times_[s] << "\"/>\n"
        << topology << "    <Geometry GeometryType=\"XYZ\">\n";
      item(groups_[s], "node_position", nn, 3);
      x << "    </Geometry>\n";
      for (const auto& [aname, set] : vectors) {
        x << "    <Attribute Name=\"" << aname << "\" AttributeType=\"Vector\" Center=\"Node\">\n";
        item(groups_[s], set, nn, 3);
        x << "    </Attribute>\n";
      }
      x << "    <Attribute Name=\"quaternion\" AttributeType=\"Matrix\" Center=\"Node\">\n";
      item(groups_[s], "node_quaternion", nn, 4);
      x << "    </Attribute>\n";
      for (const auto& f : fields) {
        x << "    <Attribute Name=\"" << f << "\" AttributeType=\"Scalar\" Center=\"Cell\">\n";
        item(groups_[s], (prefix + f).c_str(), ncells, 1);
        x << "    </Attribute>\n";
      }
      x << "   </Grid>\n";
    }
    x << "  </Grid>\n";
  };
  if (!beams_.empty()) {
    // Beams: line segments in the deformed configuration, node frames and section results.
    const size_t nb = beams_.size();
    std::ostringstream topo;
    topo << "    <Topology TopologyType=\"Polyline\" NumberOfElements=\"" << nb << "\" NodesPerElement=\"2\">\n"
         << "      <DataItem Dimensions=\"" << nb << " 2\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">" << h5_name_
         << ":/topology/beam_connectivity</DataItem>\n    </Topology>\n";
    element_grid("beams", topo.str(),
                 {{"displacement", "node_displacement"}, {"velocity", "node_velocity"}, {"axis2", "node_axis2"}, {"axis3", "node_axis3"}},
                 beam_fields_, "beam_", nb);
  }
  if (!shells_.empty()) {
    // Shells: triangles and quadrilaterals (one Mixed topology) in the deformed configuration,
    // node motion and the elements' resultants and stresses.
    const size_t ns = shells_.size();
    std::ostringstream topo;
    topo << "    <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << ns << "\">\n"
         << "      <DataItem Dimensions=\"" << shell_topology_size_ << "\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
         << h5_name_ << ":/topology/shell_connectivity</DataItem>\n    </Topology>\n";
    element_grid("shells", topo.str(),
                 {{"displacement", "node_displacement"}, {"velocity", "node_velocity"}, {"acceleration", "node_acceleration"}},
                 shell_fields_, "shell_", ns);
  }
  if (nj > 0) grid("joints", nj, "joints", "joint_location", {{"force", "joint_force"}, {"moment", "joint_moment"}});
  x << " </Domain>\n</Xdmf>\n";
  x.close();
  std::filesystem::rename(tmp, xdmf_path_);
}

}  // namespace alphaflex
