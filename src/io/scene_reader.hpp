#pragma once
// Private to the io module: the scene builder (named markers, mesh groups, body references) and
// the type registries shared by the planar (scene.cpp) and spatial (scene_spatial.cpp) parts of
// the reader. The reading context itself (input::Reader, schemas) is io/schema.hpp.
#include <yaml-cpp/yaml.h>

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

class SceneBuilder {
 public:
  SceneBuilder(Reader& rd, Model& model) : rd_(rd), model_(model) {}
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< (gx, gy, 0) in a planar scene
  std::map<std::string, NamedMarker> markers;  ///< 3D body markers by name
  std::string mesh_file;                       ///< the scene's mesh, for messages
  std::map<std::string, MeshGroup> mesh_groups;  ///< the mesh's physical groups by name

  /// The mesh group named by `n`, all of whose nodes are model nodes; clear errors otherwise.
  const MeshGroup& mesh_group(const YAML::Node& n, const std::string& key, int dim = -1) {
    const std::string name = rd_.text(n, key);
    if (mesh_groups.empty()) rd_.fail(n, key, "the scene has no `mesh` whose groups could be named");
    const auto it = mesh_groups.find(name);
    const char* what[] = {"point", "curve", "surface"};
    if (it == mesh_groups.end() || (dim >= 0 && it->second.dim != dim)) {
      std::string known;
      for (const auto& [g, mg] : mesh_groups)
        if (dim < 0 || mg.dim == dim) known += (known.empty() ? "" : ", ") + g;
      const std::string kind = dim >= 0 ? std::string(what[dim]) + " " : "";
      rd_.fail(n, key, "mesh '" + mesh_file + "' has no physical " + kind + "group '" + name + "' (its " + kind +
                           "groups: " + (known.empty() ? "none" : known) + ")" +
                           (it != mesh_groups.end() ? " ('" + name + "' is a " + what[it->second.dim] + " group)" : ""));
    }
    for (int nd : it->second.nodes)
      if (nd < 0)
        rd_.fail(n, key, "group '" + name + "' of mesh '" + mesh_file +
                             "' has nodes that are on no beam or shell (nothing holds them); name a group on the beams or shells");
    return it->second;
  }

  int body(const YAML::Node& map, const std::string& key, const std::string& path, bool ground_ok) {
    const YAML::Node n = rd_.need(map, key, path);
    const std::string name = rd_.text(n, path + "." + key);
    if (name == "ground") {
      if (!ground_ok) rd_.fail(n, path + "." + key, "'ground' cannot be used here (expected a body)");
      return -1;
    }
    const int id = model_.find_node(name);
    if (id < 0 && mesh_groups.count(name))
      rd_.fail(n, path + "." + key, "'" + name + "' is a mesh group of " + std::to_string(mesh_groups.at(name).nodes.size()) +
                                        " nodes, not one body: give it as `group` (a joint or load at each of its nodes)");
    if (id < 0) rd_.fail(n, path + "." + key, "no body named '" + name + "'" + known_bodies());
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

/// The types a scene of one dimension can name. Each type is registered by the file that reads
/// it, with one line: `types.joints.add("revolute", schema, read_revolute)`.
struct SceneTypes {
  input::Registry<ItemBuild> bodies, joints, loads;
  input::Registry<SensorBuild> sensors;
  std::string body_note;  ///< added to "unknown body type" messages
  std::vector<const Schema*> parts;  ///< schemas of maps inside the types' keys (markers, drivers)
};
const SceneTypes& planar_types();   ///< scene.cpp
const SceneTypes& spatial_types();  ///< scene_spatial.cpp
void add_spatial_force_types(SceneTypes& t);  ///< scene_forces.cpp: spring_damper, bushing (dimension 3)

/// The joint a sensor's `joint` key names (an error naming the key otherwise).
int sensor_joint(const Item& it);
/// The schemas of the scene's sections (top level, solver, output, mesh, ...) and time functions.
std::vector<const Schema*> section_schemas();
std::vector<const Schema*> mesh_schemas();  ///< scene_mesh.cpp
const Schema& modes_schema();               ///< scene_modes.cpp
const Schema& campbell_schema();            ///< scene_modes.cpp (modes.campbell)

/// The schema of a type: `name`, `type` and the type's own keys.
Schema type_schema(const std::string& name, const std::string& type_doc, std::vector<Key> keys);

/// Planar scenes: planar beams (x, y, θ nodes) from a mesh in the x-y plane.
void read_planar_mesh_and_beams(Reader& rd, const YAML::Node& root, Model& model, const Eigen::Vector2d& gravity);
/// Spatial scenes: beams and shells from the scene's mesh.
void read_mesh_and_beams(Reader& rd, SceneBuilder& sb, const YAML::Node& root, Model& model, const Eigen::Vector3d& gravity);

}  // namespace alphaflex::scene_detail
