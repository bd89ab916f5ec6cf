// `initial_conditions` (3D): a rigid placement (rotation, then translation) of a mesh group, applied
// to the mesh's points before the blocks make their nodes, so that the nodes' frames, the beams'
// section frames and the shells' directors are built in the placed position exactly as if the
// .geo had been drawn there; and a rigid initial velocity field v(x) = v0 + ω0 × (x − x_ref),
// Ω = Rᵀ ω0 on the nodes of a mesh group (beam and shell nodes on R³×SO(3)), given to each node
// when its block makes it (types/common.cpp, block_node).
#include <set>
#include <sstream>

#include "alphaflex/core/rotation.hpp"
#include "scene_reader.hpp"
#include "types/common.hpp"

namespace alphaflex::scene_detail {
namespace {

const Schema kInitial{"initial_conditions", {
    {"group", KeyType::Text, "–", kRequired, "a physical group of the mesh: placement: a curve or surface group; velocity: any group (curve, surface, points)"},
    {"rotation", KeyType::Map, "rad", "identity", "placement: a rotation vector [rx, ry, rz], {axis, angle} or a 3×3 rotation matrix (list of rows), about the world origin", {}, "", "rotation"},
    {"translation", KeyType::Vec3, "m", "[0, 0, 0]", "placement: added after the rotation, x ↦ R x + translation"},
    {"velocity", KeyType::Vec3, "m/s", "[0, 0, 0]", "v0: velocity at t = 0 of the point `about`"},
    {"angular_velocity", KeyType::Vec3, "rad/s", "[0, 0, 0]", "ω0, world components: the group turns rigidly, v(x) = v0 + ω0 × (x − about); rotation unknowns get Ω = Rᵀω0"},
    {"about", KeyType::Vec3, "m", "[0, 0, 0]", "x_ref of the velocity field, world coordinates at t = 0 (after the placement)"}}};

/// A 3×3 list of rows that is a rotation (orthonormal to 1e-9, determinant +1), or a rotation vector
/// or {axis, angle} (common.cpp).
Eigen::Matrix3d read_rotation(const Reader& rd, const YAML::Node& n, const std::string& key) {
  if (!(n.IsSequence() && n.size() == 3 && n[0].IsSequence())) return read_orientation(rd, n, key);
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i) R.row(i) = rd.vec3(n[static_cast<size_t>(i)], key + "[" + std::to_string(i) + "]").transpose();
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(off <= 1e-9) || !(R.determinant() > 0.0)) {
    std::ostringstream os;
    os << "expected a rotation matrix (RᵀR = I to 1e-9, det R = +1); max |RᵀR − I| = " << off << ", det R = " << R.determinant();
    rd.fail(n, key, os.str());
  }
  return R;
}

/// The mesh node ids of a physical group (curves and surfaces: `surfaces_and_curves_only`), or an error.
std::set<int> group_points(const Reader& rd, const MeshData& mesh, const Section& s, bool surfaces_and_curves_only) {
  const std::string name = s.text("group");
  std::set<int> out;
  if (const MeshLineBlock* b = mesh.find_line_block(name)) {
    for (const auto& e : b->elements) out.insert(e.begin(), e.end());
  } else if (const MeshSurfaceBlock* b = mesh.find_surface_block(name)) {
    for (const auto& e : b->elements) out.insert(e.begin(), e.end());
  } else if (!surfaces_and_curves_only && mesh.named_points.count(name)) {
    out.insert(mesh.named_points.at(name));
  } else if (!surfaces_and_curves_only && mesh.point_groups.count(name)) {
    const auto& ids = mesh.point_groups.at(name);
    out.insert(ids.begin(), ids.end());
  } else {
    rd.fail(s.node("group"), s.key_path("group"),
            "mesh '" + mesh.file + "' has no physical " + (surfaces_and_curves_only ? "curve or surface group '" + name + "' (a placement moves a curve or surface group)" : "group '" + name + "'"));
  }
  return out;
}

std::string item_path(size_t i) { return "initial_conditions[" + std::to_string(i) + "]"; }
bool places(const Section& s) { return s.has("rotation") || s.has("translation"); }
bool moves(const Section& s) { return s.has("velocity") || s.has("angular_velocity"); }

/// Every group a block is made of is moved whole by one placement or not at all.
void check_whole_blocks(const Reader& rd, const MeshData& mesh, const YAML::Node& root, const std::vector<int>& placed_by) {
  for (const char* section : {"beams", "shells"}) {
    const YAML::Node bl = root[section];
    if (!bl || !bl.IsSequence()) continue;
    for (size_t b = 0; b < bl.size(); ++b) {
      const YAML::Node g = bl[b].IsMap() ? bl[b]["group"] : YAML::Node();
      if (!g || !g.IsScalar()) continue;  // the block's reader names the error
      std::set<int> pts;
      if (const MeshLineBlock* lb = mesh.find_line_block(g.Scalar()))
        for (const auto& e : lb->elements) pts.insert(e.begin(), e.end());
      if (const MeshSurfaceBlock* sb = mesh.find_surface_block(g.Scalar()))
        for (const auto& e : sb->elements) pts.insert(e.begin(), e.end());
      if (pts.empty()) continue;
      const int first = placed_by[static_cast<size_t>(*pts.begin())];
      for (int p : pts)
        if (placed_by[static_cast<size_t>(p)] != first)
          rd.fail(g, std::string(section) + "[" + std::to_string(b) + "].group",
                  "group '" + g.Scalar() + "' is moved in part by `initial_conditions` (mesh node " +
                      std::to_string(mesh.node_tags[static_cast<size_t>(p)]) +
                      " is placed differently from the group's other nodes): place the whole group, or the groups it shares nodes with, by one placement");
    }
  }
}

}  // namespace

const Schema& initial_conditions_schema() { return kInitial; }

void apply_initial_conditions(Reader& rd, MeshBlocks& blocks, const YAML::Node& root, int dimension) {
  const YAML::Node list = root["initial_conditions"];
  if (!list) return;
  if (dimension != 3)
    rd.fail(list, "initial_conditions", "mesh groups have initial conditions in 3D scenes only (dimension: 3); planar bodies take `velocity` and `angular_velocity`");
  if (!list.IsSequence()) rd.fail(list, "initial_conditions", "expected a list of {group, rotation, translation, velocity, angular_velocity, about}");
  MeshData& mesh = blocks.mesh;
  // Placements first (the velocity field's `about` is a placed position). A node moved twice, or
  // a block moved in part, would tear the mesh.
  std::vector<int> placed_by(mesh.points.size(), -1);
  for (size_t i = 0; i < list.size(); ++i) {
    const Section s(rd, list[i], item_path(i), kInitial);
    if (!places(s)) continue;
    const std::string name = s.text("group");
    const std::set<int> pts = group_points(rd, mesh, s, true);
    if (blocks.placement.count(name)) rd.fail(s.node("group"), s.key_path("group"), "group '" + name + "' is placed twice");
    for (int p : pts) {
      const int other = placed_by[static_cast<size_t>(p)];
      if (other >= 0)
        rd.fail(s.node("group"), s.key_path("group"),
                "mesh node " + std::to_string(mesh.node_tags[static_cast<size_t>(p)]) + " of group '" + name + "' is also in the group placed by " +
                    item_path(static_cast<size_t>(other)) + " (a node is placed once; place the union as one group)");
      placed_by[static_cast<size_t>(p)] = static_cast<int>(i);
    }
    blocks.placement[name] = s.has("rotation") ? read_rotation(rd, s.node("rotation"), s.key_path("rotation")) : Eigen::Matrix3d::Identity();
  }
  check_whole_blocks(rd, mesh, root, placed_by);
  for (size_t i = 0; i < list.size(); ++i) {
    const Section s(rd, list[i], item_path(i), kInitial);
    if (!places(s)) continue;
    const Eigen::Matrix3d& R = blocks.placement.at(s.text("group"));
    const Eigen::Vector3d t = s.vec3("translation");
    for (size_t p = 0; p < mesh.points.size(); ++p)
      if (placed_by[p] == static_cast<int>(i)) mesh.points[p] = R * mesh.points[p] + t;
  }
  // Velocity fields, in the placed positions; a node in two fields is refused (which would win?).
  for (size_t i = 0; i < list.size(); ++i) {
    const Section s(rd, list[i], item_path(i), kInitial);
    if (!moves(s)) continue;
    const Eigen::Vector3d v0 = s.vec3("velocity"), w0 = s.vec3("angular_velocity"), xref = s.vec3("about");
    for (int p : group_points(rd, mesh, s, false)) {
      if (blocks.velocity.count(p))
        rd.fail(s.node("group"), s.key_path("group"), "mesh node " + std::to_string(mesh.node_tags[static_cast<size_t>(p)]) + " of group '" +
                                                          s.text("group") + "' has a velocity from an earlier item already");
      blocks.velocity[p] = {Eigen::Vector3d(v0 + w0.cross(mesh.points[static_cast<size_t>(p)] - xref)), w0};
    }
  }
}

void check_group_velocities(const Reader& rd, const MeshBlocks& blocks, const YAML::Node& root) {
  const YAML::Node list = root["initial_conditions"];
  if (!list) return;
  for (size_t i = 0; i < list.size(); ++i) {
    const Section s(rd, list[i], item_path(i), kInitial);
    if (!moves(s)) continue;
    for (int p : group_points(rd, blocks.mesh, s, false))
      if (blocks.node_of[static_cast<size_t>(p)] < 0)
        rd.fail(s.node("group"), s.key_path("group"), "mesh node " + std::to_string(blocks.mesh.node_tags[static_cast<size_t>(p)]) + " of group '" +
                                                          s.text("group") + "' is on no beam or shell, so its velocity would be lost; name a group of the beams or shells");
  }
}

}  // namespace alphaflex::scene_detail
