#pragma once
// Private to the io module: the scene reading context (file label, parameters, --set overrides)
// through which every value is read and every error is raised (file:line: key: what was expected),
// shared by the planar (scene.cpp) and spatial (scene_spatial.cpp) parts of the reader.
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
#include "alphaflex/mesh/gmsh_reader.hpp"
#include "alphaflex/model/planar_marker.hpp"

namespace alphaflex::scene_detail {


/// How a scene's mesh is read: read_mesh itself, or (in parallel) rank 0 reads and sends it.
using MeshLoader = std::function<MeshData(const std::string& path, const MeshOptions&, const std::string& context)>;

/// Reading context: file label and named parameters; every error goes through fail().
class Reader {
 public:
  explicit Reader(std::string file, MeshLoader mesh_loader = read_mesh)
      : file_(std::move(file)), mesh_loader_(std::move(mesh_loader)) {}

  /// Reads (or receives) the mesh at `path`; InputError messages start with `context`.
  MeshData mesh(const std::string& path, const MeshOptions& options, const std::string& context) const {
    return mesh_loader_(path, options, context);
  }

  /// Remembers the nodes a --set put in the tree, so that errors in them point at the option.
  void add_override(const YAML::Node& value, const std::string& assignment) {
    overrides_.emplace_back(value, assignment);
    if (value.IsSequence() || value.IsMap())
      for (const auto& child : value) add_override(value.IsMap() ? child.second : child, assignment);
  }

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
    std::ostringstream os;
    const std::string* from_set = nullptr;
    for (const auto& [node, text] : overrides_)
      if (at.IsDefined() && node.is(at)) from_set = &text;
    if (from_set) {
      os << file_ << ": --set " << *from_set;
    } else {
      os << file_;
      if (at.IsDefined() && at.Mark().line >= 0) os << ":" << (at.Mark().line + 1);
    }
    os << ": " << key << ": " << what;
    throw InputError(os.str());
  }

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  void keys(const YAML::Node& map, const std::string& path, const std::set<std::string>& allowed) const {
    if (!map.IsMap()) fail(map, path, "expected a map of keys");
    std::set<std::string> seen;
    for (const auto& kv : map) {
      const std::string k = key_name(kv.first, path);
      if (!allowed.count(k)) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(kv.first, join(path, k), "unknown key (allowed here: " + list + ")");
      }
      // yaml-cpp keeps both entries of a repeated key and reads the first: refuse it.
      if (!seen.insert(k).second) fail(kv.first, join(path, k), "given twice");
    }
  }

  /// A map's key as text. YAML allows lists and maps as keys (`? [a, b]: 1`); a scene has none.
  std::string key_name(const YAML::Node& key, const std::string& path) const {
    if (!key.IsScalar()) fail(key, path.empty() ? "(top level)" : path, "expected key names, found a list or a map used as a key");
    return key.Scalar();
  }

  YAML::Node need(const YAML::Node& map, const std::string& key, const std::string& path) const {
    const YAML::Node n = map[key];
    if (!n) fail(map, join(path, key), "missing (required)");
    return n;
  }

  double number(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) fail(n, key, "expected a number or an expression");
    const std::string text = n.Scalar();
    try {
      const double v = evaluate_expression(text, scope_);
      if (!std::isfinite(v)) fail(n, key, "'" + text + "' is not a finite number");
      // The model multiplies values (k·L², m·v², E·I): a value whose square is not a normal double
      // overflows or vanishes there (a mass of 1e308 made the first matrix singular: tests/fuzz).
      if (v != 0.0 && !(std::fabs(v) >= 1e-150 && std::fabs(v) <= 1e150))
        fail(n, key, "'" + text.substr(0, 60) + "' is out of range: expected 0 or a magnitude from 1e-150 to 1e150");
      return v;
    } catch (const std::invalid_argument& e) {
      fail(n, key, std::string("expected a number, ") + e.what());
    }
  }
  double number(const YAML::Node& map, const std::string& k, const std::string& path, double fallback) const {
    return map[k] ? number(map[k], join(path, k)) : fallback;
  }
  double positive(const YAML::Node& n, const std::string& key, const std::string& what) const {
    const double v = number(n, key);
    if (!(v > 0.0)) fail(n, key, "expected a positive " + what + ", got " + n.Scalar());
    return v;
  }
  double non_negative(const YAML::Node& n, const std::string& key, const std::string& what) const {
    const double v = number(n, key);
    if (!(v >= 0.0)) fail(n, key, "expected a non-negative " + what + ", got " + n.Scalar());
    return v;
  }
  int integer(const YAML::Node& n, const std::string& key, int min, int max = 1000000) const {
    const double v = number(n, key);
    if (v != std::floor(v) || v < min || v > max)
      fail(n, key, "expected an integer from " + std::to_string(min) + " to " + std::to_string(max));
    return static_cast<int>(v);
  }
  bool flag(const YAML::Node& n, const std::string& key) const {
    if (n.IsScalar()) {
      const std::string s = n.Scalar();
      if (s == "true" || s == "on" || s == "yes" || s == "1") return true;
      if (s == "false" || s == "off" || s == "no" || s == "0") return false;
    }
    fail(n, key, "expected on/off (or true/false)");
  }
  std::string text(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) fail(n, key, "expected a string");
    // Names, types and file names are quoted in later messages: none longer than a path may be
    // (PATH_MAX), so that no message repeats kilobytes of a damaged file.
    constexpr size_t kMaxText = 4096;
    if (n.Scalar().size() > kMaxText)
      fail(n, key, "expected a string of at most " + std::to_string(kMaxText) + " characters, got " +
                       std::to_string(n.Scalar().size()));
    return n.Scalar();
  }
  Eigen::Vector2d vec2(const YAML::Node& n, const std::string& key) const {
    if (!n.IsSequence() || n.size() != 2) fail(n, key, "expected a list of 2 numbers [x, y]");
    return {number(n[0], key + "[0]"), number(n[1], key + "[1]")};
  }
  Eigen::Vector3d vec3(const YAML::Node& n, const std::string& key) const {
    if (!n.IsSequence() || n.size() != 3) fail(n, key, "expected a list of 3 numbers [x, y, z]");
    return {number(n[0], key + "[0]"), number(n[1], key + "[1]"), number(n[2], key + "[2]")};
  }
  Eigen::Vector3d vec3(const YAML::Node& map, const std::string& k, const std::string& path,
                       const Eigen::Vector3d& fallback) const {
    return map[k] ? vec3(map[k], join(path, k)) : fallback;
  }
  /// A non-zero direction, normalized.
  Eigen::Vector3d direction(const YAML::Node& n, const std::string& key) const {
    const Eigen::Vector3d d = vec3(n, key);
    if (!(d.norm() > 0.0)) fail(n, key, "expected a non-zero direction");
    return d.normalized();
  }
  const std::string& file() const { return file_; }

  /// Opens item i of the list `list` (bodies, joints, forces, beams, sensors): checks that it is a
  /// map (else `not_a_map`), reads its required `name`, and sets `path` to "list[NAME]" for the
  /// messages that follow.
  std::string item_name(const YAML::Node& item, const char* list, size_t i, const char* not_a_map,
                        std::string& path) const {
    path = std::string(list) + "[" + std::to_string(i) + "]";
    if (!item.IsMap()) fail(item, path, not_a_map);
    const std::string name = text(need(item, "name", path), path + ".name");
    path = std::string(list) + "[" + name + "]";
    return name;
  }

  /// Opens item i of `sensors`: its checked name (unique, not `t`, no commas or quotes, so that it
  /// can head a CSV column) and its path "sensors[NAME]" for later messages.
  std::string sensor_name(const YAML::Node& s, size_t i, std::set<std::string>& names, std::string& path) const {
    const std::string name = item_name(s, "sensors", i, "expected a map with name, type, ...", path);
    if (name == "t") fail(s["name"], path + ".name", "'t' is reserved for the time column of the CSV");
    if (!names.insert(name).second) fail(s["name"], path + ".name", "another sensor is named '" + name + "' already");
    if (name.find_first_of(",\"\n") != std::string::npos)
      fail(s["name"], path + ".name", "a sensor name may not contain commas or quotes");
    return name;
  }

  /// The index of map[key] among `allowed`, or an error listing them.
  int choice(const YAML::Node& map, const std::string& key, const std::string& path,
             std::initializer_list<const char*> allowed) const {
    const std::string c = text(need(map, key, path), path + "." + key);
    int k = 0;
    for (const char* a : allowed) {
      if (c == a) return k;
      ++k;
    }
    std::string l;
    for (const char* a : allowed) l += std::string(l.empty() ? "" : ", ") + a;
    fail(map[key], path + "." + key, "expected one of " + l);
  }
  ExpressionScope& scope() { return scope_; }

  Eigen::Vector2d vec2(const YAML::Node& map, const std::string& k, const std::string& path,
                       const Eigen::Vector2d& fallback) const {
    return map[k] ? vec2(map[k], join(path, k)) : fallback;
  }

  TimeFunctionPtr function(const YAML::Node& n, const std::string& key) const {
    if (n.IsScalar()) return make_constant(number(n, key));
    if (!n.IsMap()) fail(n, key, "expected a number or a time function {type: ...}");
    const std::string type = text(need(n, "type", key), key + ".type");
    try {
      if (type == "constant") {
        keys(n, key, {"type", "value"});
        return make_constant(number(need(n, "value", key), key + ".value"));
      }
      if (type == "ramp" || type == "smooth_step") {
        keys(n, key, {"type", "t0", "t1", "from", "to"});
        const double t0 = number(need(n, "t0", key), key + ".t0"), t1 = number(need(n, "t1", key), key + ".t1");
        const double v0 = number(n, "from", key, 0.0), v1 = number(need(n, "to", key), key + ".to");
        return type == "ramp" ? make_ramp(t0, t1, v0, v1) : make_smooth_step(t0, t1, v0, v1);
      }
      if (type == "linear") {
        keys(n, key, {"type", "rate", "offset"});
        return make_linear(number(need(n, "rate", key), key + ".rate"), number(n, "offset", key, 0.0));
      }
      if (type == "spin_up") {
        keys(n, key, {"type", "rate", "time"});
        return make_spin_up(number(need(n, "rate", key), key + ".rate"), number(need(n, "time", key), key + ".time"));
      }
      if (type == "sine") {
        keys(n, key, {"type", "amplitude", "frequency", "phase", "offset"});
        return make_sine(number(need(n, "amplitude", key), key + ".amplitude"),
                         number(need(n, "frequency", key), key + ".frequency"), number(n, "phase", key, 0.0),
                         number(n, "offset", key, 0.0));
      }
      if (type == "table") {
        keys(n, key, {"type", "t", "values"});
        std::vector<double> t, v;
        const YAML::Node nt = need(n, "t", key), nv = need(n, "values", key);
        if (!nt.IsSequence() || !nv.IsSequence()) fail(n, key, "t and values must be lists of numbers");
        for (size_t i = 0; i < nt.size(); ++i) t.push_back(number(nt[i], key + ".t"));
        for (size_t i = 0; i < nv.size(); ++i) v.push_back(number(nv[i], key + ".values"));
        return make_table(t, v);
      }
    } catch (const std::invalid_argument& e) {
      fail(n, key, e.what());
    }
    fail(n, key + ".type", "unknown time function '" + type + "' (expected constant, ramp, smooth_step, linear, spin_up, sine, table)");
  }

  void read_parameters(const YAML::Node& p) {
    if (!p) return;
    if (!p.IsMap()) fail(p, "parameters", "expected a map name: value");
    for (const auto& kv : p) {
      const std::string name = key_name(kv.first, "parameters");
      scope_[name] = number(kv.second, "parameters." + name);
    }
  }

 private:
  std::string file_;
  MeshLoader mesh_loader_;
  ExpressionScope scope_;
  std::vector<std::pair<YAML::Node, std::string>> overrides_;
};

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

/// Spatial scenes (`dimension: 3`), scene_spatial.cpp.
void read_spatial_bodies(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model, const Eigen::Vector3d& gravity);
void read_mesh_and_beams(Reader& rd, SceneBuilder& sb, const YAML::Node& root, Model& model, const Eigen::Vector3d& gravity);
/// Planar scenes: planar beams (x, y, θ nodes) from a mesh in the x-y plane.
void read_planar_mesh_and_beams(Reader& rd, const YAML::Node& root, Model& model, const Eigen::Vector2d& gravity);
void read_spatial_joints(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model);
void read_spatial_forces(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model);
void read_spatial_sensors(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model);

}  // namespace alphaflex::scene_detail
