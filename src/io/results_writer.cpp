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

void write_array(hid_t loc, const char* name, const double* data, hsize_t rows, hsize_t cols) {
  const hsize_t dims[2] = {rows, cols};
  const hid_t space = H5Screate_simple(cols > 1 ? 2 : 1, dims, nullptr);
  const hid_t set = H5Dcreate2(loc, name, H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (set < 0) throw std::runtime_error(std::string("HDF5: cannot create dataset ") + name);
  if (rows > 0) H5Dwrite(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
  H5Dclose(set);
  H5Sclose(space);
}

void write_ints(hid_t loc, const char* name, const std::vector<int>& v) {
  const hsize_t dims[1] = {v.size()};
  const hid_t space = H5Screate_simple(1, dims, nullptr);
  const hid_t set = H5Dcreate2(loc, name, H5T_STD_I32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  if (!v.empty()) H5Dwrite(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Dclose(set);
  H5Sclose(space);
}

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

}  // namespace

ResultsWriter::ResultsWriter(const Model& model, const std::string& outdir, const std::string& name, bool hdf5,
                             int rank)
    : model_(model), active_(rank == 0), hdf5_(hdf5) {
  // Beams (two-node elements with result fields) are drawn as line segments between their nodes,
  // shells (3- and 4-node shell elements) as triangles and quadrilaterals.
  for (size_t e = 0; e < model.elements().size(); ++e) {
    const Element& el = *model.elements()[e];
    if (el.nodes().size() == 2 && !el.output_names().empty()) {
      if (beam_fields_.empty()) beam_fields_ = el.output_names();
      if (el.output_names() == beam_fields_) beams_.push_back(static_cast<int>(e));
    } else if (is_shell(el) && !el.output_names().empty()) {
      if (shell_fields_.empty()) shell_fields_ = el.output_names();
      if (el.output_names() == shell_fields_) {
        shells_.push_back(static_cast<int>(e));
        shell_topology_size_ += 1 + el.nodes().size();
      }
    }
  }
  namespace fs = std::filesystem;
  const fs::path dir = fs::absolute(outdir);
  h5_name_ = name + ".h5";
  h5_path_ = (dir / h5_name_).string();
  xdmf_path_ = (dir / (name + ".xdmf")).string();
  csv_path_ = (dir / (name + ".csv")).string();
  if (!active_) return;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("output directory " + dir.string() + ": " + ec.message());
  csv_ = std::fopen(csv_path_.c_str(), "w");
  if (!csv_) throw InputError("cannot write " + csv_path_);
  std::fprintf(csv_, "t");
  for (const auto& s : model_.sensors()) std::fprintf(csv_, ",%s", s.name.c_str());
  std::fprintf(csv_, "\n");
  if (hdf5_) {
    file_ = H5Fcreate(h5_path_.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    if (file_ < 0) throw InputError("cannot create " + h5_path_);
    const hid_t topo = H5Gcreate2(file_, "topology", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    std::vector<int> nodes(model_.nodes().size()), joints(model_.constraints().size());
    for (size_t i = 0; i < nodes.size(); ++i) nodes[i] = static_cast<int>(i);
    for (size_t i = 0; i < joints.size(); ++i) joints[i] = static_cast<int>(i);
    write_ints(topo, "nodes", nodes);
    write_ints(topo, "joints", joints);
    std::vector<int> conn;
    for (int e : beams_) for (int n : model_.elements()[static_cast<size_t>(e)]->nodes()) conn.push_back(n);
    if (!beams_.empty()) write_ints(topo, "beam_connectivity", conn);
    // XDMF Mixed topology: per cell its XDMF type (4 triangle, 5 quadrilateral), then its nodes.
    conn.clear();
    for (int e : shells_) {
      const auto& en = model_.elements()[static_cast<size_t>(e)]->nodes();
      conn.push_back(en.size() == 3 ? 4 : 5);
      for (int n : en) conn.push_back(n);
    }
    if (!shells_.empty()) write_ints(topo, "shell_connectivity", conn);
    H5Gclose(topo);
  }
}

ResultsWriter::~ResultsWriter() {
  if (csv_) std::fclose(csv_);
  if (file_ >= 0) H5Fclose(file_);
}

void ResultsWriter::write_sensors(double t, const std::vector<double>& values) {
  if (!active_) return;
  std::fprintf(csv_, "%.17g", t);
  for (double v : values) std::fprintf(csv_, ",%.17g", v);
  std::fprintf(csv_, "\n");
}

void ResultsWriter::write_fields(const MechanicalState& s) {
  if (!active_ || !hdf5_) return;
  const size_t nn = model_.nodes().size(), nj = model_.constraints().size();
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
  H5Awrite(attr, H5T_NATIVE_DOUBLE, &s.t);
  H5Aclose(attr);
  H5Sclose(aspace);
  write_array(g, "node_position", pos.data(), nn, 3);
  write_array(g, "node_velocity", vel.data(), nn, 3);
  write_array(g, "node_acceleration", acc.data(), nn, 3);
  write_array(g, "node_angle", ang.data(), nn, 1);
  write_array(g, "node_axis", axis.data(), nn, 3);
  write_array(g, "node_axis2", axis2.data(), nn, 3);
  write_array(g, "node_axis3", axis3.data(), nn, 3);
  write_array(g, "node_quaternion", quat.data(), nn, 4);
  write_array(g, "node_displacement", disp.data(), nn, 3);
  if (!beams_.empty()) {
    // Section forces and strains per beam element (constant on a two-node element): cell data.
    const size_t nb = beams_.size(), nf = beam_fields_.size();
    const auto fields = element_fields(model_, beams_, nf, s);
    for (size_t f = 0; f < nf; ++f) write_array(g, ("beam_" + beam_fields_[f]).c_str(), fields[f].data(), nb, 1);
  }
  if (!shells_.empty()) {
    // Stress resultants and von Mises stresses per shell element (its area-weighted mean): cell data.
    const size_t ns = shells_.size(), nf = shell_fields_.size();
    const auto fields = element_fields(model_, shells_, nf, s);
    for (size_t f = 0; f < nf; ++f) write_array(g, ("shell_" + shell_fields_[f]).c_str(), fields[f].data(), ns, 1);
  }
  write_array(g, "joint_location", jloc.data(), nj, 3);
  write_array(g, "joint_force", jforce.data(), nj, 3);
  write_array(g, "joint_moment", jmoment.data(), nj, 3);
  // Generalized state in model order, for scripts and convergence studies.
  write_array(g, "q", s.q.data(), static_cast<hsize_t>(s.q.size()), 1);
  write_array(g, "v", s.v.data(), static_cast<hsize_t>(s.v.size()), 1);
  write_array(g, "qdd", s.qdd.data(), static_cast<hsize_t>(s.qdd.size()), 1);
  write_array(g, "lambda", s.lambda.data(), static_cast<hsize_t>(s.lambda.size()), 1);
  H5Gclose(g);
  // Flushing costs ~0.7 ms per call (it dominated small runs when done every step): at most once
  // per second of wall time, and always at the end, so a killed run loses at most ~1 s of output.
  const auto now = std::chrono::steady_clock::now();
  if (now - last_flush_ > std::chrono::seconds(1)) {
    H5Fflush(file_, H5F_SCOPE_GLOBAL);
    last_flush_ = now;
  }
  times_.push_back(s.t);
  groups_.push_back(gname);
  std::fflush(csv_);
}

void ResultsWriter::finish() {
  if (!active_) return;
  std::fflush(csv_);
  if (!hdf5_) return;
  H5Fflush(file_, H5F_SCOPE_GLOBAL);
  write_xdmf();
}

void ResultsWriter::write_xdmf() const {
  const size_t nn = model_.nodes().size(), nj = model_.constraints().size();
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
