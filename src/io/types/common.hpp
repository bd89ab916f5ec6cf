#pragma once
// Private to the io module: what the files of src/io/types/ share. Each file of this folder reads
// one type of the scene (or a small family: the four point sensors) and registers its name, schema
// and constructor with one function `void register_FILE(SceneTypes&)`; register_all.cpp lists
// those functions, one line each (PETSc's TSRegisterAll). Here: the schema of a type, and the keys
// and readings that several types use (two-point planar joints, spatial body references,
// rotations, vectors of time functions, the nodes of mesh blocks). type_schema, with and
// sensor_joint are declared in scene_reader.hpp.
#include <array>
#include <string>
#include <vector>

#include "../scene_reader.hpp"
#include "alphaflex/elements/beam_section.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex::scene_detail {

/// The nodes of a two-body item (−1, the ground, left out).
std::vector<int> node_list(int a, int b);
/// The point sensors' type names and the quantity each reads (m, m, m/s, m/s²), in both dimensions.
const std::array<std::pair<const char*, Sensor::Kind>, 4>& point_sensor_kinds();

// ---- planar two-point joints (revolute, fixed, point_on_line, prismatic) ------------------------

/// body1/point1, body2/point2 or location: the keys shared by the two-point joints.
std::vector<Key> two_point_keys();

/// The two markers of a two-point joint (body2 absent: ground).
struct TwoPoints {
  int b1 = -1, b2 = -1;
  std::vector<int> nodes;
  Eigen::Vector2d s1, s2;
  PlanarMarker marker1(const Item& it) const { return it.sb.marker(b1, s1, nodes, it.node, it.at("point1")); }
  PlanarMarker marker2(const Item& it) const { return it.sb.marker(b2, s2, nodes, it.node, it.at("point2")); }
  /// The initial relative angle θ1 − θ2 that a fixed or prismatic joint keeps.
  double relative_angle(const Model& model) const {
    return model.node(b1).q0[2] - (b2 >= 0 ? model.node(b2).q0[2] : 0.0);
  }
};
/// body1, body2 and the points (point2 defaults to [0, 0], or with `default_point2_coincident` to
/// the point of body2 at point1 at t = 0).
TwoPoints two_points(const Item& it, bool default_point2_coincident);

// ---- spatial bodies and loads ---------------------------------------------------------------------

/// `orientation`: a rotation vector [rx, ry, rz] (rad) or {axis: [..], angle: ..}.
Eigen::Matrix3d read_orientation(const Reader& rd, const YAML::Node& n, const std::string& key);
/// The keys of a rotation given as {axis, angle} (registered with the spatial rigid body).
const Schema& rotation_schema();
/// A spatial `rigid_body` item's mass (kg), inertia (kg·m², body frame, about the centre of mass),
/// pose at t = 0 and the names of its markers (types/rigid_body_3d.cpp).
struct RigidBodyInput {
  double mass = 0.0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d orientation = Eigen::Matrix3d::Identity();
  std::vector<std::string> markers;
};
/// Reads those keys of a `rigid_body` item checked against rigid_body_schema() (the same checks
/// and messages as the body's own reader: a reduced body reads the bodies welded into it first).
RigidBodyInput rigid_body_input(const Reader& rd, const Section& keys);
/// The schema of the spatial `rigid_body` type.
const Schema& rigid_body_schema();
/// A spatial body or beam/shell node named by the item's key `key` (−1: the ground, if allowed).
int spatial_node(const Item& it, const std::string& key, bool ground_ok);
/// Initial pose of a node (the identity for the ground).
Pose<double> initial_pose(const Model& m, int node);
/// The `component` key (x, y, z) of the spatial point and rotation sensors.
Key xyz_component();
/// The `follower` key of loads that are dead by default.
Key follower_off();
/// [x, y, z] of time functions at `key` (absent: none).
std::array<TimeFunctionPtr, 3> vector_function(const Item& it, const char* key, const char* unit);

// ---- element blocks (beams, shells) -------------------------------------------------------------

/// The model node of mesh node `m` of the block being read: made on first use (named after its
/// mesh point, else BLOCK:TAG) with the initial state (q0, v0), shared by the blocks that meet there.
/// A mesh point's name for messages: its physical point name, else "node TAG" (gmsh's tag).
std::string mesh_point_label(const MeshBlocks& b, int m);
int block_node(const Item& it, int m, NodeKind kind, const Eigen::VectorXd& q0, const Eigen::VectorXd& v0);
/// The block of `blocks` (the mesh's line or surface blocks) named by the item's `group`, or a
/// clear error listing them ("curve", "surface"); the group is then used (one block per group,
/// `users`: "beam", "beam or shell").
template <class Block>
const Block& mesh_block(const Item& it, const std::vector<Block>& blocks, const char* kind, const char* users) {
  const std::string group = it.keys.text("group");
  for (const Block& b : blocks)
    if (b.name == group) {
      if (!it.sb.blocks.groups_used.insert(group).second)
        it.rd.fail(it.keys.node("group"), it.at("group"), "group '" + group + "' is used by another " + users + " already");
      return b;
    }
  std::string known;
  for (const Block& b : blocks) known += (known.empty() ? "" : ", ") + b.name;
  it.rd.fail(it.keys.node("group"), it.at("group"), "mesh '" + it.sb.blocks.mesh.file + "' has no physical " + kind + " group '" + group +
                                                        "' (its " + kind + " groups: " + (known.empty() ? "none" : known) + ")");
}
/// The beam section of `section`: a material and a shape, or the stiffness and inertia properties
/// (types/beams_3d.cpp; the planar beams read a material section with it too).
BeamSection read_beam_section(const Reader& rd, const YAML::Node& n, const std::string& key);

/// An energy sum (Sensor::Kind::EnergySum, component `component`) over the elements the item's
/// `of` names (energy_sensors.cpp).
void read_energy_of(const Item& it, Sensor& sn, int component);
/// The `of` and `kind` keys of the `energy` sensor.
Key energy_of_key();
Key energy_kind();

/// A size×size matrix key: `size` numbers (the diagonal) or `size` rows of `size`; symmetric and
/// positive semi-definite (a bushing's stiffness or damping, of (u, γ)); zero when absent.
Eigen::MatrixXd read_psd_matrix(const Item& it, const std::string& key, int size, const char* units);

}  // namespace alphaflex::scene_detail
