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
    if (L.elements.empty()) L.modal_offset = {0};
    const std::string structure = mesh->structure() ? mesh->structure() : "cell";
    auto g = std::find_if(L.grids.begin(), L.grids.end(), [&](const ReducedGrid& r) { return r.structure == structure; });
    if (g == L.grids.end()) {
      L.grids.emplace_back();
      g = L.grids.end() - 1;
      g->structure = structure;
      g->fields = mesh->cell_fields();
    }
    g->bodies.push_back(L.elements.size());
    L.elements.push_back(static_cast<int>(e));
    L.names.push_back(elements[e]->name());
    for (const auto& c : mesh->elements()) g->lines = g->lines && c->output_cell().shape == CellShape::line;
    g->point_offset.push_back(g->point_offset.back() + mesh->points());
    g->cell_offset.push_back(g->cell_offset.back() + mesh->elements().size());
    L.modal_offset.push_back(L.modal_offset.back() + static_cast<unsigned long long>(mesh->elastic()));
  }
  // Connectivity sizes once `lines` is known for each whole grid.
  for (ReducedGrid& g : L.grids)
    for (size_t b : g.bodies) {
      unsigned long long n = 0;
      for (const auto& c : reconstruction_of(*elements[static_cast<size_t>(L.elements[b])])->elements())
        n += cell_size(c->output_cell().shape, g.lines);
      g.connectivity_offset.push_back(g.connectivity_offset.back() + n);
    }
  return L;
}

ReducedRows::ReducedRows(const Subdomain& sub, const ReducedLayout& layout)
    : sub_(sub), layout_(layout), points_(layout.grids.size()), cells_(layout.grids.size()), connectivity_(layout.grids.size()) {
  for (size_t g = 0; g < layout.grids.size(); ++g) {
    points_[g].total = layout.grids[g].points();
    cells_[g].total = layout.grids[g].cells();
    connectivity_[g].total = layout.grids[g].connectivity_size();
  }
  modal_.total = layout.modes();
  if (layout.empty()) return;
  const auto& elements = sub.model().elements();
  for (size_t e = 0; e < elements.size(); ++e) {
    const int id = sub.global_element(static_cast<int>(e));
    const auto it = std::lower_bound(layout.elements.begin(), layout.elements.end(), id);
    if (it == layout.elements.end() || *it != id) continue;
    const size_t b = static_cast<size_t>(it - layout.elements.begin());
    for (size_t g = 0; g < layout.grids.size(); ++g) {
      const ReducedGrid& grid = layout.grids[g];
      const auto at = std::find(grid.bodies.begin(), grid.bodies.end(), b);
      if (at == grid.bodies.end()) continue;
      const size_t k = static_cast<size_t>(at - grid.bodies.begin());
      mine_.push_back({b, g, k, static_cast<int>(e)});
      points_[g].add(grid.point_offset[k], grid.point_offset[k + 1] - grid.point_offset[k]);
      cells_[g].add(grid.cell_offset[k], grid.cell_offset[k + 1] - grid.cell_offset[k]);
      connectivity_[g].add(grid.connectivity_offset[k], grid.connectivity_offset[k + 1] - grid.connectivity_offset[k]);
    }
    modal_.add(layout.modal_offset[b], layout.modal_offset[b + 1] - layout.modal_offset[b]);
  }
}

void ReducedRows::write_topology(H5Calls& h5, hid_t topo, hid_t xfer) const {
  if (layout_.empty()) return;
  for (size_t g = 0; g < layout_.grids.size(); ++g) {
    const ReducedGrid& rg = layout_.grids[g];
    std::vector<int> ids;
    ElementGrid grid;
    grid.lines = rg.lines;
    for (const Mine& m : mine_) {
      if (m.g != g) continue;
      const int first = static_cast<int>(rg.point_offset[m.k]);
      for (const auto& c : reconstruction_of(*sub_.model().elements()[static_cast<size_t>(m.element)])->elements())
        append_cell(grid, *c, [&](int n) { return first + n; }, ids);
    }
    write_int_rows(h5, topo, ("reduced_" + rg.structure + "_connectivity").c_str(), connectivity_[g], ids.data(), xfer);
  }
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
  const Model& model = sub_.model();
  auto put = [&](const std::string& set, const Rows& rows, int cols, const std::vector<double>& data) {
    write_rows(h5, group, set.c_str(), rows, cols, data.data(), xfer);
  };
  std::vector<double> xi, xid;
  for (const Mine& m : mine_) {  // in body order: the modal rows
    const Element& el = *model.elements()[static_cast<size_t>(m.element)];
    const LocalState body = model.local_state(el, s);
    const int n = reconstruction_of(el)->elastic();
    xi.insert(xi.end(), body.q.data() + 7, body.q.data() + 7 + n);
    xid.insert(xid.end(), body.v.data() + 6, body.v.data() + 6 + n);
  }
  for (size_t g = 0; g < layout_.grids.size(); ++g) {
    const ReducedGrid& rg = layout_.grids[g];
    std::vector<double> pos, disp, vel, quat, axis2, axis3;
    std::vector<std::vector<double>> cells(rg.fields.size());
    for (const Mine& m : mine_) {
      if (m.g != g) continue;
      const Element& el = *model.elements()[static_cast<size_t>(m.element)];
      const MeshReconstruction& mesh = *reconstruction_of(el);
      const LocalState body = model.local_state(el, s);
      const LocalState p = mesh.state(body);
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
      const bool same = mesh.cell_fields() == rg.fields;
      const std::vector<Eigen::VectorXd> outputs = same ? mesh.element_outputs(body) : std::vector<Eigen::VectorXd>{};
      for (size_t k = 0; k < mesh.elements().size(); ++k) {
        const Eigen::VectorXd values = same ? outputs[k] : Eigen::VectorXd();
        Eigen::Index at = 0;
        for (size_t f = 0; f < rg.fields.size(); ++f)
          for (int c = 0; c < rg.fields[f].components; ++c, ++at) cells[f].push_back(same && at < values.size() ? values[at] : 0.0);
      }
    }
    put(rg.dataset("points"), points_[g], 3, pos);
    put(rg.dataset("displacement"), points_[g], 3, disp);
    put(rg.dataset("velocity"), points_[g], 3, vel);
    put(rg.dataset("quaternion"), points_[g], 4, quat);
    put(rg.dataset("axis2"), points_[g], 3, axis2);
    put(rg.dataset("axis3"), points_[g], 3, axis3);
    for (size_t f = 0; f < rg.fields.size(); ++f) put(rg.dataset(rg.fields[f].name), cells_[g], rg.fields[f].components, cells[f]);
  }
  if (layout_.modes() > 0) {
    put("modal_coordinates", modal_, 1, xi);
    put("modal_velocities", modal_, 1, xid);
  }
}

}  // namespace alphaflex::io_detail
