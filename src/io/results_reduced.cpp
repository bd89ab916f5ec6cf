#include "results_reduced.hpp"

#include <algorithm>

#include "alphaflex/model/mesh_reconstruction.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "results_mesh.hpp"

namespace alphaflex::io_detail {

ReducedLayout reduced_layout(const Model& global) {
  ReducedLayout L;
  const auto& elements = global.elements();
  for (size_t e = 0; e < elements.size(); ++e) {
    const MeshReconstruction* mesh = reconstruction_of(*elements[e]);
    if (!mesh) continue;
    if (L.elements.empty()) {
      L.point_offset = L.cell_offset = L.connectivity_offset = L.modal_offset = {0};
      L.structure = mesh->structure() ? mesh->structure() : "cell";
      L.fields = mesh->cell_fields();
    }
    L.elements.push_back(static_cast<int>(e));
    L.names.push_back(elements[e]->name());
    for (const auto& c : mesh->elements()) L.lines = L.lines && c->output_cell().shape == CellShape::line;
    L.point_offset.push_back(L.point_offset.back() + mesh->points());
    L.cell_offset.push_back(L.cell_offset.back() + mesh->elements().size());
    L.modal_offset.push_back(L.modal_offset.back() + static_cast<unsigned long long>(mesh->elastic()));
  }
  // Connectivity sizes once `lines` is known for the whole grid.
  for (size_t b = 0; b < L.elements.size(); ++b) {
    unsigned long long n = 0;
    for (const auto& c : reconstruction_of(*elements[static_cast<size_t>(L.elements[b])])->elements())
      n += cell_size(c->output_cell().shape, L.lines);
    L.connectivity_offset.push_back(L.connectivity_offset.back() + n);
  }
  return L;
}

ReducedRows::ReducedRows(const Subdomain& sub, const ReducedLayout& layout) : sub_(sub), layout_(layout) {
  points_.total = layout.points();
  cells_.total = layout.cells();
  connectivity_.total = layout.connectivity_size();
  modal_.total = layout.modes();
  if (layout.empty()) return;
  const auto& elements = sub.model().elements();
  for (size_t e = 0; e < elements.size(); ++e) {
    const int g = sub.global_element(static_cast<int>(e));
    const auto it = std::lower_bound(layout.elements.begin(), layout.elements.end(), g);
    if (it == layout.elements.end() || *it != g) continue;
    const size_t b = static_cast<size_t>(it - layout.elements.begin());
    mine_.emplace_back(static_cast<int>(b), static_cast<int>(e));
    points_.add(layout.point_offset[b], layout.point_offset[b + 1] - layout.point_offset[b]);
    cells_.add(layout.cell_offset[b], layout.cell_offset[b + 1] - layout.cell_offset[b]);
    connectivity_.add(layout.connectivity_offset[b], layout.connectivity_offset[b + 1] - layout.connectivity_offset[b]);
    modal_.add(layout.modal_offset[b], layout.modal_offset[b + 1] - layout.modal_offset[b]);
  }
}

void ReducedRows::write_topology(H5Calls& h5, hid_t topo, hid_t xfer) const {
  if (layout_.empty()) return;
  std::vector<int> ids;
  ElementGrid grid;
  grid.lines = layout_.lines;
  for (const auto& [b, e] : mine_) {
    const int first = static_cast<int>(layout_.point_offset[static_cast<size_t>(b)]);
    for (const auto& c : reconstruction_of(*sub_.model().elements()[static_cast<size_t>(e)])->elements())
      append_cell(grid, *c, [&](int n) { return first + n; }, ids);
  }
  write_int_rows(h5, topo, ("reduced_" + layout_.structure + "_connectivity").c_str(), connectivity_, ids.data(), xfer);
  std::vector<int> offsets;
  std::string names;
  for (size_t b = 0; b < layout_.modal_offset.size(); ++b) offsets.push_back(static_cast<int>(layout_.modal_offset[b]));
  for (const std::string& n : layout_.names) names += n + "\n";
  const Rows all = Rows::all_on_root(offsets.size(), sub_.rank() == 0);
  write_int_rows(h5, topo, "modal_offsets", all, offsets.data(), xfer);
  write_attribute(h5, topo, "modal_bodies", names);
}

void ReducedRows::write_step(H5Calls& h5, hid_t group, const MechanicalState& s, hid_t xfer) const {
  if (layout_.empty()) return;
  std::vector<double> pos, disp, vel, quat, axis2, axis3, xi, xid;
  std::vector<std::vector<double>> cells(layout_.fields.size());
  const Model& model = sub_.model();
  for (const auto& [b, e] : mine_) {
    const Element& el = *model.elements()[static_cast<size_t>(e)];
    const MeshReconstruction& mesh = *reconstruction_of(el);
    const LocalState body = model.local_state(el, s);
    const LocalState p = mesh.state(body);
    const int m = mesh.elastic();
    xi.insert(xi.end(), body.q.data() + 7, body.q.data() + 7 + m);
    xid.insert(xid.end(), body.v.data() + 6, body.v.data() + 6 + m);
    for (size_t a = 0; a < mesh.points(); ++a) {
      const Pose<double> pa = pose_of(p.q.data() + 7 * a);
      const Eigen::Vector3d u = pa.x - mesh.point(a).initial;
      pos.insert(pos.end(), pa.x.data(), pa.x.data() + 3);
      disp.insert(disp.end(), u.data(), u.data() + 3);
      vel.insert(vel.end(), p.v.data() + 6 * a, p.v.data() + 6 * a + 3);
      quat.insert(quat.end(), p.q.data() + 7 * a + 3, p.q.data() + 7 * a + 7);  // (w, x, y, z)
      for (int k = 0; k < 3; ++k) {
        axis2.push_back(pa.R(k, 1));
        axis3.push_back(pa.R(k, 2));
      }
    }
    // Each element's own results recovered from the modes (a beam's section forces and strains).
    const bool same = mesh.cell_fields() == layout_.fields;
    const std::vector<Eigen::VectorXd> outputs = same ? mesh.element_outputs(body) : std::vector<Eigen::VectorXd>{};
    for (size_t k = 0; k < mesh.elements().size(); ++k) {
      const Eigen::VectorXd values = same ? outputs[k] : Eigen::VectorXd();
      Eigen::Index at = 0;
      for (size_t f = 0; f < layout_.fields.size(); ++f)
        for (int c = 0; c < layout_.fields[f].components; ++c, ++at) cells[f].push_back(same && at < values.size() ? values[at] : 0.0);
    }
  }
  auto put = [&](const std::string& set, const Rows& rows, int cols, const std::vector<double>& data) {
    write_rows(h5, group, set.c_str(), rows, cols, data.data(), xfer);
  };
  put(layout_.dataset("points"), points_, 3, pos);
  put(layout_.dataset("displacement"), points_, 3, disp);
  put(layout_.dataset("velocity"), points_, 3, vel);
  put(layout_.dataset("quaternion"), points_, 4, quat);
  put(layout_.dataset("axis2"), points_, 3, axis2);
  put(layout_.dataset("axis3"), points_, 3, axis3);
  for (size_t f = 0; f < layout_.fields.size(); ++f) put(layout_.dataset(layout_.fields[f].name), cells_, layout_.fields[f].components, cells[f]);
  if (layout_.modes() > 0) {
    put("modal_coordinates", modal_, 1, xi);
    put("modal_velocities", modal_, 1, xid);
  }
}

}  // namespace alphaflex::io_detail
