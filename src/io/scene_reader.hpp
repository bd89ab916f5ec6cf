#pragma once
// Private to the io module: the scene builder (named markers, mesh groups, mesh blocks, body
// references) and the type registries that the section reader (scene.cpp, scene_mesh.cpp) looks
// types up in and the files of types/ register into. The reading context itself (input::Reader,
// Section, schemas) is io/schema.hpp.
#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/time_function.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/io/schema.hpp"
#include "alphaflex/io/superelement_cache.hpp"
#include "alphaflex/mesh/gmsh_reader.hpp"
#include "alphaflex/model/planar_marker.hpp"

namespace alphaflex::scene_detail {


using input::MeshLoader;
using input::Reader;
using input::Section;
using input::Schema;
using input::Key;
using input::KeyType;
using input::Range;
using input::kRequired;

struct BodyRef {
  int node = -1;  // -1 = ground
};

/// A named frame fixed to a spatial body (3D `markers`): its node and its pose in the body frame.
struct NamedMarker {
  int node = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};

/// A physical group of the scene's mesh in terms of model nodes (joints and loads on groups).
struct MeshGroup {
  int dim = 0;                              ///< 0 point, 1 curve, 2 surface
  std::vector<int> nodes;                   ///< model nodes (−1: a mesh node no beam or shell uses), first-use order
  std::vector<std::vector<int>> elements;   ///< model node lists: segments (dim 1), shell elements (dim 2)
  std::vector<Eigen::Vector3d> points;      ///< reference position of each of `nodes`
  bool shells = false;                      ///< a surface group that `shells` use
};

/// The mesh that `beams` and `shells` blocks are cut from, and the model nodes made of its nodes
/// (shared where blocks meet).
struct MeshBlocks {
  MeshData mesh;
  std::vector<int> node_of;                ///< mesh node → model node (−1: none yet)
  std::map<int, std::string> point_name;   ///< mesh node → name of its named point
  std::set<std::string> groups_used;       ///< groups a block uses (one block per group)
  std::map<int, std::string> reduced;      ///< mesh nodes of reduced blocks that have no model node → the block (types/reduced_beams_3d.cpp)
  std::map<std::string, Eigen::Matrix3d> placement;  ///< rotation of each placed group (scene_initial.cpp)
  /// The items of the block list being read (`beams` or `shells`), by name (scene_mesh.cpp
  /// read_blocks): a reduced block that takes further blocks of its list into its body
  /// (`reduction.blocks`, types/reduced_beams_3d.cpp) builds their elements itself.
  struct ListedBlock {
    YAML::Node node;
    const std::string* path;
    const Section* keys;
  };
  std::map<std::string, ListedBlock> listed;
  std::map<std::string, std::string> absorbed;  ///< block → the reduced block whose body it is part of
  /// Mesh node → (velocity, angular velocity), world components, of an initial velocity field (scene_initial.cpp).
  std::map<int, std::array<Eigen::Vector3d, 2>> velocity;
  /// A direction given for a block on `group` (beam orientation, shell material axis), turned with the group's placement.
  Eigen::Vector3d placed(const std::string& group, const Eigen::Vector3d& d) const {
    const auto it = placement.find(group);
    return it == placement.end() ? d : Eigen::Vector3d(it->second * d);
  }
};

class SceneBuilder {
 public:
  SceneBuilder(Reader& rd, Model& model) : rd_(rd), model_(model) {}
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< (gx, gy, 0) in a planar scene
  std::map<std::string, NamedMarker> markers;  ///< 3D body markers by name
  std::string mesh_file;                       ///< the scene's mesh, for messages
  std::map<std::string, MeshGroup> mesh_groups;  ///< the mesh's physical groups by name
  MeshBlocks blocks;                           ///< while `beams` and `shells` are read
  std::map<std::string, std::string> reduced_points;  ///< named mesh points without a node → their reduced block
  SuperelementCache* superelements = nullptr;  ///< where reduced blocks are kept (types/reduced_beams_3d.cpp); none: computed
  YAML::Node root;                             ///< the scene's top level (a reduced body reads the bodies welded into it ahead)
  /// A rigid body welded into a reduced body (`reduction.bodies`, types/reduced_beams_3d.cpp): its
  /// mass is in the superelement, and the `fixed` joint that welds it becomes a ReducedInterfaceTie
  /// of the body's node at its pose relative to the block node it is welded to.
  struct Weld {
    std::string body, block;
    int frame = -1;
    std::vector<int> amplitudes;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();     ///< X_a (m, frame axes)
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< R̄_a
    Eigen::MatrixXd shape;                                   ///< Φ_a (6 × m)
    Eigen::Vector3d offset_position = Eigen::Vector3d::Zero();     ///< the body's node in the block node's frame (m)
    Eigen::Matrix3d offset_rotation = Eigen::Matrix3d::Identity();  ///< the body frame in the block node's frame
  };
  std::map<std::string, Weld> welds;                 ///< by the welding joint's name
  std::map<std::string, std::string> welded_bodies;  ///< body → the reduced block it is part of

  /// The mesh group named by the section's key `key` (of dimension `dim`, if ≥ 0), all of whose
  /// nodes are model nodes; clear errors otherwise.
  const MeshGroup& mesh_group(const Section& s, const std::string& key, int dim = -1) {
    const YAML::Node n = s.node(key);
    const std::string name = s.text(key);
    const std::string at = s.key_path(key);
    if (mesh_groups.empty()) rd_.fail(n, at, "the scene has no `mesh` whose groups could be named");
    const auto it = mesh_groups.find(name);
    const char* what[] = {"point", "curve", "surface"};
    if (it == mesh_groups.end() || (dim >= 0 && it->second.dim != dim)) {
      std::string known;
      for (const auto& [g, mg] : mesh_groups)
        if (dim < 0 || mg.dim == dim) known += (known.empty() ? "" : ", ") + g;
      const std::string kind = dim >= 0 ? std::string(what[dim]) + " " : "";
      rd_.fail(n, at, "mesh '" + mesh_file + "' has no physical " + kind + "group '" + name + "' (its " + kind +
                          "groups: " + (known.empty() ? "none" : known) + ")" +
                          (it != mesh_groups.end() ? " ('" + name + "' is a " + what[it->second.dim] + " group)" : ""));
    }
    for (int nd : it->second.nodes)
      if (nd < 0)
        rd_.fail(n, at, "group '" + name + "' of mesh '" + mesh_file +
                            "' has nodes that are on no beam or shell (nothing holds them); name a group on the beams or shells");
    return it->second;
  }

  /// The body named by the section's key `key` (−1 for `ground` where `ground_ok`); clear errors
  /// for a missing key, an unknown body, a mesh group given as a body.
  int body(const Section& s, const std::string& key, bool ground_ok) {
    if (!s.has(key)) rd_.fail(s.map(), s.key_path(key), "missing (required)");
    const YAML::Node n = s.node(key);
    const std::string name = s.text(key);
    if (name == "ground") {
      if (!ground_ok) rd_.fail(n, s.key_path(key), "'ground' cannot be used here (expected a body)");
      return -1;
    }
    const int id = model_.find_node(name);
    if (id < 0 && reduced_points.count(name))
        rd_.fail(n, s.key_path(key), "'" + name + "' is a point inside the reduced beam block '" + reduced_points.at(name) +
                                         "': only its interface points have nodes, so joints and loads attach there only (add the point to the block's `reduction.interface`); "
                                         "sensors read other points from the rebuilt mesh (point_position, point_displacement)");
    if (id < 0 && mesh_groups.count(name))
      rd_.fail(n, s.key_path(key), "'" + name + "' is a mesh group of " + std::to_string(mesh_groups.at(name).nodes.size()) +
                                       " nodes, not one body: give it as `group` (a joint or load at each of its nodes)");
    if (id < 0) rd_.fail(n, s.key_path(key), "no body named '" + name + "'" + known_bodies());
    return id;
  }

  /// The bodies a reference could name, for messages: the first 20 (a meshed model has thousands
  /// of nodes, all of which were listed: a message of 10⁴ names, found by tests/fuzz).
  std::string known_bodies() const {
    constexpr size_t kShown = 20;
    std::string s = " (bodies: ";
    const auto& nodes = model_.nodes();
    for (size_t i = 0; i < nodes.size() && i < kShown; ++i) s += nodes[i].name + " ";
    if (nodes.size() > kShown) s += "... (" + std::to_string(nodes.size() - kShown) + " more) ";
    return s + "ground)";
  }

  /// Marker of `node` (or the ground) at `local` (world point for the ground).
  PlanarMarker marker(int node, const Eigen::Vector2d& local, const std::vector<int>& nodes, const YAML::Node& at,
                      const std::string& key) {
    if (node < 0) return PlanarMarker::ground(local);
    try {
      return PlanarMarker::on_node(model_.node(node), local, model_.local_offset(nodes, node));
    } catch (const std::invalid_argument& e) {
      rd_.fail(at, key, "body '" + model_.node(node).name + "': " + e.what());
    }
  }

  /// World position at t = 0 of a marker.
  Eigen::Vector2d initial_position(int node, const Eigen::Vector2d& local) {
    if (node < 0) return local;
    const PlanarMarker m = PlanarMarker::on_node(model_.node(node), local, 0);
    return m.position(model_.node(node).q0);
  }

  /// Local coordinates on `node` of the world point p at t = 0.
  Eigen::Vector2d to_local(int node, const Eigen::Vector2d& p) {
    if (node < 0) return p;
    const Node& nd = model_.node(node);
    if (nd.kind != NodeKind::RigidBody2D) return Eigen::Vector2d::Zero();
    return rotate(-nd.q0[2], p - Eigen::Vector2d(nd.q0[0], nd.q0[1]));
  }

  Reader& rd_;
  Model& model_;
};


}  // namespace alphaflex::scene_detail

namespace alphaflex::scene_detail {

/// One item of a list (a body, joint, load or sensor) being read: its node, its name, its path
/// ("joints[NAME]") for messages and its keys, checked against its type's schema.
struct Item {
  Reader& rd;
  SceneBuilder& sb;
  Model& model;
  const YAML::Node& node;
  const std::string& name;
  const std::string& path;
  const Section& keys;
  /// The key path "PATH.key" for messages.
  std::string at(const std::string& key) const { return path + "." + key; }
};
/// Constructors of bodies, joints and loads (they add nodes, elements, constraints to the model)
/// and of sensors (they fill in the sensor, whose name is set; the reader adds it).
using ItemBuild = std::function<void(const Item&)>;
using SensorBuild = std::function<void(const Item&, Sensor&)>;
/// A block of elements on a mesh group (`beams`, `shells`): the keys an item has ("name, group,
/// section"), for messages, and the constructor of its elements (one kind of cell).
struct BlockBuild {
  std::string item_keys;
  ItemBuild build;
};

/// The types a scene of one dimension can name: bodies, joints, loads and sensors by their `type`,
/// element blocks by their list (`beams`, `shells`). Each type is registered by its own file of
/// src/io/types/ (one line in register_all.cpp lists that file).
struct SceneTypes {
  input::Registry<ItemBuild> bodies, joints, loads;
  input::Registry<SensorBuild> sensors;
  input::Registry<BlockBuild> blocks;
  std::string body_note;  ///< added to "unknown body type" messages
  std::vector<const Schema*> parts;  ///< schemas of maps inside the types' keys (markers, drivers, sections)
};
const SceneTypes& planar_types();   ///< types/register_all.cpp
const SceneTypes& spatial_types();  ///< types/register_all.cpp

/// The schema of a type: `name`, `type` and the type's own keys (types/common.cpp).
Schema type_schema(const std::string& name, const std::string& type_doc, std::vector<Key> keys);
/// `keys` followed by `more`.
std::vector<Key> with(std::vector<Key> keys, std::vector<Key> more);
/// The joint a sensor's `joint` key names (an error naming the key otherwise).
int sensor_joint(const Item& it);

/// The schemas of the scene's sections (top level, solver, output, mesh, ...) and time functions.
std::vector<const Schema*> section_schemas();
const Schema& mesh_schema();                ///< scene_mesh.cpp
const Schema& modes_schema();               ///< scene_modes.cpp
const Schema& campbell_schema();            ///< scene_modes.cpp (modes.campbell)
const Schema& initial_conditions_schema();  ///< scene_initial.cpp

/// `initial_conditions`, before the blocks are read: moves the mesh points of the placed groups and
/// sets each velocity field's (v, ω) at its mesh points (MeshBlocks::velocity).
void apply_initial_conditions(Reader& rd, MeshBlocks& blocks, const YAML::Node& root, int dimension);
/// After the blocks: every mesh point given a velocity is a node of a block (else an error).
void check_group_velocities(const Reader& rd, const MeshBlocks& blocks, const YAML::Node& root);

/// Reads `mesh` and the element blocks the scene's dimension registers (`beams`, `shells`): the
/// blocks' nodes and elements, then every physical group as model nodes (sb.mesh_groups).
void read_mesh_and_blocks(Reader& rd, SceneBuilder& sb, const YAML::Node& root, const SceneTypes& types, int dimension);

}  // namespace alphaflex::scene_detail
