// The full mesh of a reduced beam block and the sensors that read it (reduced_mesh_3d.hpp;
// docs/theory/reduced_bodies.md, "Reconstruction").
#include "reduced_mesh_3d.hpp"

#include "alphaflex/elements/reduced_body.hpp"
#include "alphaflex/elements/shell.hpp"

namespace alphaflex::scene_detail {

std::shared_ptr<const MeshReconstruction> reduced_block_mesh(const Item& it, const Model& scratch, const std::vector<int>& elements,
                                                             const ReducedBlock& rb, const std::map<int, int>& in_block, bool whole) {
  std::vector<MeshReconstruction::Point> points(rb.positions.size());
  for (size_t a = 0; a < points.size(); ++a) {
    points[a].X = rb.positions[a];
    points[a].R0 = rb.rotations[a];
    points[a].shape = rb.shapes[a];
    points[a].initial = scratch.node(static_cast<int>(a)).q0.head<3>();
  }
  std::vector<std::string> names(points.size());
  for (const auto& [m, id] : in_block) {
    const auto pn = it.sb.blocks.point_name.find(m);
    if (pn != it.sb.blocks.point_name.end() && id >= 0) names[static_cast<size_t>(id)] = pn->second;
  }
  std::vector<std::shared_ptr<const Element>> cells;
  for (int e : elements) {
    const Element& el = *scratch.elements()[static_cast<size_t>(e)];
    cells.emplace_back(el.renumbered(el.nodes()));
  }
  // A shell's von Mises stresses from its recovered (odd-part) resultants (mesh_reconstruction.hpp).
  MeshReconstruction::Derived derived;
  if (!cells.empty()) {
    if (const auto* shell = dynamic_cast<const ReissnerMindlinShell*>(cells.front().get())) {
      const double t = shell->section().thickness;
      derived = [t](Eigen::VectorXd& values) { ReissnerMindlinShell::von_mises_from_resultants(values, t); };
    }
  }
  return std::make_shared<const MeshReconstruction>(std::move(points), std::move(cells), std::move(names), std::move(derived),
                                                    whole ? MeshReconstruction::Recovery::whole : MeshReconstruction::Recovery::odd_part);
}

namespace {

/// The reduced body named `block` and its mesh (−1 if there is none).
int reduced_body_of(const Model& model, const std::string& block) {
  const auto& elements = model.elements();
  for (size_t e = 0; e < elements.size(); ++e)
    if (elements[e]->name() == block && reconstruction_of(*elements[e])) return static_cast<int>(e);
  return -1;
}

}  // namespace

bool read_reduced_point_sensor(const Item& it, Sensor& sn) {
  const Section& k = it.keys;
  if (!k.has("body")) return false;
  const std::string name = k.text("body");
  const auto rp = it.sb.reduced_points.find(name);
  // A point with a node of its own (the frame point, a tied interface point) is read there.
  if (rp == it.sb.reduced_points.end() || it.model.find_node(name) >= 0) return false;
  const std::string at = it.at("body");
  const int body = reduced_body_of(it.model, rp->second);
  if (body < 0) return false;
  if (sn.kind != Sensor::Kind::PointPosition && sn.kind != Sensor::Kind::PointDisplacement)
    it.rd.fail(k.node("body"), at, "'" + name + "' is a point inside the reduced beam block '" + rp->second +
                                       "': its position and displacement are rebuilt from the modes, its velocity and acceleration are not available");
  if (k.has("relative_to")) it.rd.fail(k.node("relative_to"), it.at("relative_to"), "is not available for a point inside the reduced beam block '" + rp->second + "'");
  if (k.has("point") && k.vec3("point").squaredNorm() > 0.0)
    it.rd.fail(k.node("point"), it.at("point"), "must be [0, 0, 0] at a point inside the reduced beam block '" + rp->second +
                                                    "' (the mesh node itself is rebuilt)");
  const MeshReconstruction& mesh = *reconstruction_of(*it.model.elements()[static_cast<size_t>(body)]);
  int a = -1;
  for (size_t p = 0; p < mesh.points(); ++p)
    if (mesh.name(p) == name) a = static_cast<int>(p);
  if (a < 0) it.rd.fail(k.node("body"), at, "'" + name + "' is not a point of the rebuilt mesh of '" + rp->second + "'");
  const int component = k.choice("component");
  // ReducedBody::output(): point_position (3 per point), then point_displacement.
  const int first = sn.kind == Sensor::Kind::PointPosition ? 0 : 3 * static_cast<int>(mesh.points());
  sn.kind = Sensor::Kind::ElementOutput;
  sn.element = body;
  sn.component = first + 3 * a + component;
  return true;
}

bool read_reduced_element_output(const Item& it, Sensor& sn, const std::string& block, int element) {
  const int body = reduced_body_of(it.model, block);
  if (body < 0) return false;
  const Element& rb = *it.model.elements()[static_cast<size_t>(body)];
  const MeshReconstruction& mesh = *reconstruction_of(rb);
  const int ne = static_cast<int>(mesh.elements().size());
  if (element >= ne)
    it.rd.fail(it.node["element"], it.at("element"), std::string(mesh.structure() ? mesh.structure() : "block") + " '" + block + "' has no element " + std::to_string(element) + " (it has " +
                                                         std::to_string(ne) + ", numbered from 0 in mesh order; the block is reduced)");
  // The components of one of the block's elements (all alike): `N`, `M3`, …
  const int c = it.rd.choice(it.keys.node("component"), it.at("component"), mesh.elements().front()->output_names());
  // Its place in ReducedBody::output() (MeshReconstruction::output_index); a sensor reads it
  // through MeshReconstruction::element_output, that element alone (model/sensor.cpp).
  const Eigen::Index offset = mesh.output_index(static_cast<size_t>(element), c);
  sn.kind = Sensor::Kind::ElementOutput;
  sn.element = body;
  sn.component = static_cast<int>(offset);
  return true;
}

}  // namespace alphaflex::scene_detail
