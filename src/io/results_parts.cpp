#include "results_parts.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/fault_injection.hpp"
#include "alphaflex/model/planar_marker.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex::io_detail {

ResultsParts::ResultsParts(const Subdomain& sub, const std::vector<ElementGrid>& grids, std::string parts_dir,
                           std::string parts_name, std::string h5_path)
    : sub_(sub), model_(sub.model()), grids_(grids), parts_dir_(std::move(parts_dir)), parts_name_(std::move(parts_name)),
      h5_path_(std::move(h5_path)), state_(sub) {
  // This rank's rows. Local nodes, elements and joints are in increasing global order, so every
  // list below comes out sorted, as the file selections need.
  const Model& global = sub.global_model();
  node_.total = global.nodes().size();
  for (int i = 0; i < sub.num_owned_nodes(); ++i) node_.add(static_cast<unsigned long long>(sub.global_node(i)), 1);
  joint_.total = global.constraints().size();
  for (size_t c = 0; c < model_.constraints().size(); ++c)
    joint_.add(static_cast<unsigned long long>(sub.global_constraint(static_cast<int>(c))), 1);
  cells_.resize(grids.size());
  connectivity_.resize(grids.size());
  local_elements_.resize(grids.size());
  std::vector<std::pair<size_t, size_t>> row_of(global.elements().size(), {grids.size(), 0});  // (grid, row)
  for (size_t k = 0; k < grids.size(); ++k) {
    cells_[k].total = grids[k].elements.size();
    connectivity_[k].total = grids[k].connectivity_size;
    for (size_t r = 0; r < grids[k].elements.size(); ++r) row_of[static_cast<size_t>(grids[k].elements[r])] = {k, r};
  }
  for (size_t e = 0; e < model_.elements().size(); ++e) {
    const auto [k, r] = row_of[static_cast<size_t>(sub.global_element(static_cast<int>(e)))];
    if (k == grids.size()) continue;
    cells_[k].add(r, 1);
    connectivity_[k].add(grids[k].offset[r], cell_size(grids[k].shapes[r], grids[k].lines));
    local_elements_[k].push_back(static_cast<int>(e));
  }
  // Bodies and links (results_layout.hpp): rows in the order of the global ids, which the local
  // nodes and joints follow.
  layout_ = node_layout(global, grids);
  body_.total = layout_.bodies.size();
  for (int i = 0; i < sub.num_owned_nodes(); ++i) {
    const int r = layout_.body_row[static_cast<size_t>(sub.global_node(i))];
    if (r >= 0) body_.add(static_cast<unsigned long long>(r), 1);
  }
  link_.total = 3 * layout_.links.size();
  for (size_t c = 0; c < model_.constraints().size(); ++c) {
    const int r = layout_.link_row[static_cast<size_t>(sub.global_constraint(static_cast<int>(c)))];
    if (r >= 0) link_.add(3 * static_cast<unsigned long long>(r), 3);
  }
  shapes_.emplace(sub, layout_.shapes);
  reduced_.emplace(sub, layout_.reduced);
  // A first estimate of an output step's bytes: its values, and ~1 KiB of HDF5 metadata per
  // dataset (object header, the group's index); measured after each step.
  unsigned long long values = node_.total * 26 + joint_.total * 9 + state_.conf.total + 2 * state_.dof.total + state_.mult.total +
                         9 * layout_.shapes.points() +  // shape points, displacement, velocity
                         19 * layout_.reduced.points() + 2 * layout_.reduced.modes();  // rebuilt meshes, modal coordinates
  size_t sets = 20;
  for (const ReducedGrid& g : layout_.reduced.grids)
    for (const CellField& f : g.fields) values += g.cells() * static_cast<unsigned long long>(f.components);
  for (size_t k = 0; k < grids.size(); ++k)
    for (const CellField& f : grids[k].fields) {
      values += cells_[k].total * static_cast<unsigned long long>(f.components);
      ++sets;
    }
  step_bytes_ = 8 * values + 1024 * sets;
  H5Calls h5(parts_dir_);
  transfer_ = transfer_list(h5, sub.comm());
  agree<OutputError>(sub, h5.error());
}

ResultsParts::~ResultsParts() {
  // A part that was not committed is not part of the results (an error ended the run).
  discard();
  if (transfer_ >= 0) H5Pclose(transfer_);
}

void ResultsParts::discard() {
  if (part_ < 0) return;
  discard_file(part_, open_path_);
  part_ = -1;
  if (sub_.rank() == 0) {
    std::error_code ec;
    std::filesystem::remove(open_path_, ec);
  }
}

void ResultsParts::write_topology(H5Calls& h5, hid_t file) const {
  const hid_t topo = h5(H5Gcreate2(file, "topology", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create the group topology");
  if (topo < 0) return;
  h5.group = "/topology";
  std::vector<int> ids;
  for (int i = 0; i < sub_.num_owned_nodes(); ++i) ids.push_back(sub_.global_node(i));
  write_int_rows(h5, topo, "nodes", node_, ids.data(), transfer_);
  ids.clear();
  for (size_t c = 0; c < model_.constraints().size(); ++c) ids.push_back(sub_.global_constraint(static_cast<int>(c)));
  write_int_rows(h5, topo, "joints", joint_, ids.data(), transfer_);
  if (!layout_.all_bodies() && !layout_.bodies.empty()) {  // the body datasets' own rows, in order
    ids.clear();
    for (int i = 0; i < sub_.num_owned_nodes(); ++i)
      if (layout_.body_row[static_cast<size_t>(sub_.global_node(i))] >= 0)
        ids.push_back(layout_.body_row[static_cast<size_t>(sub_.global_node(i))]);
    write_int_rows(h5, topo, "bodies", body_, ids.data(), transfer_);
  }
  if (!layout_.links.empty()) {  // polylines of 3 points: link_points rows 3r, 3r + 1, 3r + 2
    ids.clear();
    for (size_t c = 0; c < model_.constraints().size(); ++c) {
      const int r = layout_.link_row[static_cast<size_t>(sub_.global_constraint(static_cast<int>(c)))];
      for (int k = 0; r >= 0 && k < 3; ++k) ids.push_back(3 * r + k);
    }
    write_int_rows(h5, topo, "links", link_, ids.data(), transfer_);
  }
  shapes_->write_topology(h5, topo, transfer_);
  reduced_->write_topology(h5, topo, transfer_);
  for (size_t k = 0; k < grids_.size(); ++k) {
    if (grids_[k].elements.empty()) continue;
    ids.clear();
    for (int e : local_elements_[k])
      append_cell(grids_[k], *model_.elements()[static_cast<size_t>(e)], [&](int n) { return sub_.global_node(n); }, ids);
    write_int_rows(h5, topo, grids_[k].connectivity().c_str(), connectivity_[k], ids.data(), transfer_);
  }
  h5.group.clear();
  h5(H5Gclose(topo), "close the group topology");
}

void ResultsParts::open(long long k) {
  // A new part, under a temporary name until it is committed, with the topology of the model
  // (every part is complete in itself: the index needs no other file).
  const std::string tmp = part_path(k) + ".tmp";
  open_path_ = tmp;
  H5Calls h5(tmp);
  const hid_t fapl = file_access(h5, sub_.comm());
  if (fapl >= 0) {
    part_ = h5(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, fapl), "create the file");
    h5(H5Pclose(fapl), "close the file access list");
  }
  agree<OutputError>(sub_, h5.error());
  write_topology(h5, part_);
  agree<OutputError>(sub_, h5.error());
}

namespace {

/// Element results of the local elements `which` of a grid at state s: one array per field, its
/// components row after row (missing values stay 0).
std::vector<std::vector<double>> cell_data(const Model& model, const std::vector<int>& which,
                                           const std::vector<CellField>& fields, const MechanicalState& s) {
  std::vector<std::vector<double>> data(fields.size());
  for (size_t f = 0; f < fields.size(); ++f) data[f].assign(which.size() * static_cast<size_t>(fields[f].components), 0.0);
  Eigen::VectorXd values;
  for (size_t b = 0; b < which.size(); ++b) {
    const Element& e = *model.elements()[static_cast<size_t>(which[b])];
    e.output(model.local_state(e, s), values);
    Eigen::Index at = 0;
    for (size_t f = 0; f < fields.size(); ++f) {
      const size_t nc = static_cast<size_t>(fields[f].components);
      for (size_t c = 0; c < nc; ++c, ++at)
        if (at < values.size()) data[f][nc * b + c] = values[at];
    }
  }
  return data;
}

/// The position of a local node's reference point (a frame's origin, a planar node's point).
Eigen::Vector3d node_point(const Node& n, const MechanicalState& s) {
  if (n.spatial()) return pose_of(s.q.data() + n.first_conf).x;
  const Eigen::Vector2d p = PlanarMarker::on_node(n, Eigen::Vector2d::Zero(), 0).position(s.q.segment(n.first_conf, n.nconf));
  return {p[0], p[1], 0.0};
}

}  // namespace

void ResultsParts::append_link(const Constraint& con, const Eigen::Vector3d& at, const MechanicalState& s,
                               std::vector<double>& out) const {
  // Body 1's centre → the joint → body 2's centre; a side that is the ground or a mesh node (drawn
  // by its beam or shell) is the joint's point itself.
  const auto& nodes = con.nodes();
  auto side = [&](size_t k) {
    if (k < nodes.size() && layout_.body_row[static_cast<size_t>(sub_.global_node(nodes[k]))] >= 0)
      return node_point(model_.nodes()[static_cast<size_t>(nodes[k])], s);
    return Eigen::Vector3d(at);
  };
  for (const Eigen::Vector3d& p : {side(0), Eigen::Vector3d(at), side(1)}) out.insert(out.end(), p.data(), p.data() + 3);
}

void ResultsParts::write_step(const MechanicalState& s, const std::string& group) {
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
  std::vector<double> jloc(3 * nj, 0.0), jforce(3 * nj, 0.0), jmoment(3 * nj, 0.0), links;
  for (size_t c = 0; c < nj; ++c) {
    const Constraint& con = *model_.constraints()[c];
    const JointReaction r = con.reaction(gather(s.q, model_.confs_of(con.nodes())), s.t,
                                         s.lambda.segment(model_.first_multiplier(static_cast<int>(c)), con.size()));
    for (int k = 0; k < 3; ++k) {
      jloc[3 * c + k] = r.location[k];
      jforce[3 * c + k] = r.force[k];
      jmoment[3 * c + k] = r.moment[k];
    }
    if (layout_.link_row[static_cast<size_t>(sub_.global_constraint(static_cast<int>(c)))] >= 0)
      append_link(con, r.location, s, links);
  }
  // Room for this step and the metadata HDF5 still holds, with a margin (twice the step, 64 KiB for
  // the close), agreed on before the collective writes.
  agree<OutputError>(sub_, room_for(open_path_, part_, 2 * step_bytes_ + 65536, "write the group " + group));
  haddr_t eoa_before = 0;
  H5Fget_eoa(part_, &eoa_before);
  H5Calls h5(open_path_);
  const hid_t g = h5(H5Gcreate2(part_, group.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create the group " + group);
  agree<OutputError>(sub_, h5.error());
  h5.group = "/" + group;
  // time: an array of one double (the layout scripts read as attrs["time"][0]); every rank
  // writes the same value: collective.
  write_attribute_array(h5, g, "time", s.t);
  auto put = [&](const std::string& set, const Rows& rows, int cols, const double* data) {
    write_rows(h5, g, set.c_str(), rows, cols, data, transfer_);
  };
  put("node_position", node_, 3, pos.data());
  put("node_velocity", node_, 3, vel.data());
  put("node_acceleration", node_, 3, acc.data());
  put("node_angle", node_, 1, ang.data());
  put("node_axis", node_, 3, axis.data());
  put("node_axis2", node_, 3, axis2.data());
  put("node_axis3", node_, 3, axis3.data());
  put("node_quaternion", node_, 4, quat.data());
  put("node_displacement", node_, 3, disp.data());
  if (!layout_.blocks.empty())
    put("node_elastic_displacement", node_, 3, elastic_displacements(sub_, layout_, pos, disp).data());
  if (!layout_.all_bodies() && !layout_.bodies.empty()) {
    // The bodies grid's own datasets: the owned body nodes' rows of the node datasets.
    auto rows_of_bodies = [&](const std::vector<double>& all, size_t cols) {
      std::vector<double> out;
      for (size_t i = 0; i < nn; ++i)
        if (layout_.body_row[static_cast<size_t>(sub_.global_node(static_cast<int>(i)))] >= 0)
          out.insert(out.end(), all.begin() + static_cast<long>(cols * i), all.begin() + static_cast<long>(cols * (i + 1)));
      return out;
    };
    const std::pair<const char*, std::pair<const std::vector<double>*, int>> body_sets[] = {
        {"body_position", {&pos, 3}}, {"body_velocity", {&vel, 3}},     {"body_acceleration", {&acc, 3}},
        {"body_angle", {&ang, 1}},    {"body_axis", {&axis, 3}},        {"body_axis2", {&axis2, 3}},
        {"body_axis3", {&axis3, 3}},  {"body_quaternion", {&quat, 4}},  {"body_displacement", {&disp, 3}}};
    for (const auto& [set, data] : body_sets)
      put(set, body_, data.second, rows_of_bodies(*data.first, static_cast<size_t>(data.second)).data());
  }
  if (!layout_.links.empty()) put("link_points", link_, 3, links.data());
  shapes_->write_step(h5, g, s, transfer_);
  reduced_->write_step(h5, g, s, transfer_);
  // Element results (a beam's section forces and strains, a shell's resultants and stresses),
  // constant on an element: cell data, one dataset per field.
  for (size_t k = 0; k < grids_.size(); ++k) {
    if (grids_[k].elements.empty()) continue;
    const auto data = cell_data(model_, local_elements_[k], grids_[k].fields, s);
    for (size_t f = 0; f < grids_[k].fields.size(); ++f)
      put(grids_[k].dataset(grids_[k].fields[f]), cells_[k], grids_[k].fields[f].components, data[f].data());
  }
  put("joint_location", joint_, 3, jloc.data());
  put("joint_force", joint_, 3, jforce.data());
  put("joint_moment", joint_, 3, jmoment.data());
  // Generalized state in model order, for scripts and convergence studies: the owned part of the
  // local vectors (owned nodes come first) at their places.
  put("q", state_.conf, 1, s.q.data());
  put("v", state_.dof, 1, s.v.data());
  put("qdd", state_.dof, 1, s.qdd.data());
  put("lambda", state_.mult, 1, s.lambda.data());
  h5.group.clear();
  h5(H5Gclose(g), "close the group " + group);
  // Tests of error handling: a write that fails on one rank only.
  if (fault_injected("output")) h5.fail("write the group " + group + " (injected fault, -af_inject_fault output)");
  agree<OutputError>(sub_, h5.error());  // every rank throws the same OutputError if one write failed
  haddr_t eoa_after = 0;
  if (H5Fget_eoa(part_, &eoa_after) >= 0 && eoa_after > eoa_before) step_bytes_ = std::max<unsigned long long>(step_bytes_, eoa_after - eoa_before);
}

std::string ResultsParts::close(long long k) {
  H5Calls h5(open_path_);
  // The flush is where a full disk shows; a failed H5Fclose would leave the file half-closed in
  // HDF5 (hdf5_rows.hpp, discard_file), so the ranks agree on the flush before the close.
  const std::string room = sub_.first_error(room_for(open_path_, part_, 65536, "write the file"));
  if (room.empty()) h5(H5Fflush(part_, H5F_SCOPE_LOCAL), "write the file");
  const std::string error = room.empty() ? sub_.first_error(h5.error()) : room;
  if (!error.empty()) {
    discard();
    return error;
  }
  h5(H5Fclose(part_), "close the file");
  part_ = -1;
  if (sub_.rank() == 0 && h5.error().empty()) {
    std::error_code ec;
    std::filesystem::rename(open_path_, part_path(k), ec);
    if (ec) h5.fail("rename to " + part_path(k));  // errno says why
  }
  return h5.error();
}

std::string ResultsParts::write_links(const std::vector<OutputStep>& steps) const {
  // NAME.h5 holds external links only: /topology to the first part's, /step_NNNNNN to the part
  // that has it. Rebuilt as a new file and renamed over the old one (a few kB per 100 steps).
  const std::string tmp = h5_path_ + ".tmp";
  H5Calls h5(tmp);
  const hid_t f = h5(H5Fcreate(tmp.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), "create the file");
  if (f < 0) return h5.error();
  const std::string first = parts_name_ + "/" + part_file(0);
  h5(H5Lcreate_external(first.c_str(), "/topology", f, "topology", H5P_DEFAULT, H5P_DEFAULT), "link /topology");
  for (const OutputStep& s : steps) {
    const std::string target = parts_name_ + "/" + part_file(s.part);
    h5(H5Lcreate_external(target.c_str(), ("/" + s.group).c_str(), f, s.group.c_str(), H5P_DEFAULT, H5P_DEFAULT),
       "link /" + s.group);
  }
  if (!h5.error().empty()) {
    discard_file(f, tmp);
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    return h5.error();
  }
  h5(H5Fclose(f), "close the file");
  return h5.error();
}

std::string ResultsParts::publish_links() const {
  const std::string tmp = h5_path_ + ".tmp";
  H5Calls h5(tmp);
  std::error_code ec;
  std::filesystem::rename(tmp, h5_path_, ec);
  if (ec) h5.fail("rename to " + h5_path_);  // errno says why
  return h5.error();
}

std::string ResultsParts::read_steps(long long parts, std::vector<OutputStep>& steps) const {
  for (long long k = 0; k < parts; ++k) {
    const std::string path = part_path(k);
    const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (f < 0)
      return "restart: the results of the checkpoint are incomplete (" + path + " is missing or unreadable); restart into a new output directory (-o) to start the results anew";
    bool ok = true;
    for (size_t g = steps.size(); ok; ++g) {
      const std::string name = group_name(g);
      const htri_t exists = H5Lexists(f, name.c_str(), H5P_DEFAULT);
      ok = exists >= 0;
      if (exists <= 0) break;
      const hid_t grp = H5Gopen2(f, name.c_str(), H5P_DEFAULT);
      double t = 0.0;
      ok = grp >= 0 && read_attribute(grp, "time", t);
      if (grp >= 0) ok = H5Gclose(grp) >= 0 && ok;
      if (ok) steps.push_back({t, name, k});
    }
    ok = H5Fclose(f) >= 0 && ok;
    if (!ok)
      return "restart: " + path + " cannot be read (an output step or its time); restart into a new output directory (-o) to start the results anew";
  }
  return {};
}

void ResultsParts::remove_from(long long from) const {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parts_dir_, ec)) {
    const std::string f = entry.path().filename().string();
    if (f.rfind("part_", 0) != 0) continue;
    const long long k = std::atoll(f.substr(5, 6).c_str());
    if (k >= from || f.size() > 14) fs::remove(entry.path(), ec);
  }
}

}  // namespace alphaflex::io_detail
