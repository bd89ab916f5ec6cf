#pragma once
// One input reader for scenes and studies: a schema per section (each key with its type, SI unit,
// range, default and a one-line doc), the reading context through which every value is read and
// every error raised (FILE:LINE: key: what was expected, or FILE: --set ASSIGNMENT: ...), the one
// `--set`/`--study-set` override function, and the type registries (bodies, joints, loads,
// sensors: name → schema and constructor, in the manner of PETSc's TSRegister). docs/input.md's
// key tables are generated from the schemas (`alphaflex keys --update docs/input.md`).
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/time_function.hpp"
#include "alphaflex/mesh/gmsh_reader.hpp"

namespace alphaflex::input {

/// Why `name` cannot be an entity's name ("" if it can): names go to messages, the CSV header and
/// the results, so 1 to 100 printable ASCII characters without a leading or trailing space (a
/// newline, a tab, a NUL byte or 300 characters broke them; issue 24, docs/input.md "Names").
/// Entity names in the scene and physical group names of meshes alike.
std::string name_problem(const std::string& name);
/// `name` with control and non-ASCII bytes as \xNN (for a message about a bad name).
std::string escaped_name(const std::string& name);


/// What a key holds; it fixes how Section reads it and the type column of the docs.
enum class KeyType {
  Number,    ///< a number or an expression of `parameters`
  Integer,   ///< a whole number
  Flag,      ///< on/off, true/false, yes/no, 1/0
  Text,      ///< a string (a name, a file, a mode)
  Vec2,      ///< [x, y]
  Vec3,      ///< [x, y, z]
  Choice,    ///< one of `choices`
  Function,  ///< a number or a time function {type: ramp, ...}
  Interval,  ///< how often: a whole number of steps, or a wall time with its unit ("600 s", "10 min", "2 h")
  Numbers,   ///< a number or a list of numbers, each in the key's range
  Texts,     ///< a list of strings
  List,      ///< a list (of maps or values; read by the code that owns it)
  Map,       ///< a map (a sub-section with a schema of its own, or free form)
};

/// Allowed values of a number or an integer: [lo, hi], each end open or closed.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range open(double a, double b) { return {a, b, true, true}; }
  static Range at_least(double a) { return {a, std::numeric_limits<double>::infinity(), false, false}; }
  bool contains(double v) const {
    return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  bool bounded() const { return std::isfinite(lo) || std::isfinite(hi); }
  std::string text() const;  ///< "> 0", "≥ 0", "in [0, 1]", "0…30" (integers: see Key::type_text)
};

/// The default column of a required key.
inline const char* const kRequired = "**required**";

/// One key of a section.
struct Key {
  std::string name;
  KeyType type = KeyType::Number;
  std::string unit = "–";     ///< SI unit ("–": none, a pure number or a name)
  std::string fallback = "";  ///< the default as docs state it; kRequired: must be given; "": none
  std::string doc;            ///< meaning and constraints, one line
  Range range = {};           ///< numbers and integers
  std::string noun = "";      ///< range messages: "expected a positive NOUN, got …" (e.g. "step size (s)")
  std::string shape = "";     ///< the docs' type column when KeyType's name says too little ("[x, y]")
  std::vector<std::string> choices = {};  ///< KeyType::Choice
  bool required() const { return fallback == kRequired; }
  std::string type_text() const;  ///< the docs' type column
};

/// The keys of one section (or of one type of body, joint, load, sensor).
struct Schema {
  std::string name;  ///< "solver", "joints.2d.revolute", "study.settings": the docs marker
  std::vector<Key> keys;
  const Key* find(const std::string& key) const;
  /// "a, b, c": the keys in alphabetical order, for "unknown key (allowed here: …)".
  std::string allowed() const;
  /// The docs table: | key | type | unit | default | meaning, constraints |.
  std::string markdown() const;
};

/// How a scene's mesh is read: read_mesh itself, or (in parallel) rank 0 reads and sends it.
using MeshLoader = std::function<MeshData(const std::string& path, const MeshOptions&, const std::string& context)>;

/// Applies "a.b.2.c=value" to the tree `root` (maps created on the way, list items by index) and
/// returns the node it put there; "a.b=~" (null) removes the key b instead (an error if there is
/// none, or if it names a list entry). `option` ("--set", "--study-set") and `label` (the file)
/// head every message. One function for the scene's --set and the study's --study-set.
YAML::Node apply_override(YAML::Node root, const std::string& assignment, const std::string& option,
                          const std::string& label);

/// Reading context: file label, named parameters, the nodes that overrides put in the tree;
/// every error goes through fail().
class Reader {
 public:
  explicit Reader(std::string file, MeshLoader mesh_loader = read_mesh, std::string option = "--set")
      : file_(std::move(file)), option_(std::move(option)), mesh_loader_(std::move(mesh_loader)) {}

  /// Reads (or receives) the mesh at `path`; InputError messages start with `context`.
  MeshData mesh(const std::string& path, const MeshOptions& options, const std::string& context) const {
    return mesh_loader_(path, options, context);
  }

  /// Remembers the nodes an override put in the tree, so that errors in them point at the option.
  void add_override(const YAML::Node& value, const std::string& assignment);

  [[noreturn]] void fail(const YAML::Node& at, const std::string& key, const std::string& what) const;
  /// "FILE:LINE: key" (for messages raised later, e.g. by a run of a study setting).
  std::string where(const YAML::Node& at, const std::string& key) const;

  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }

  /// Checks that `map` is a map whose keys are all in `schema`, none given twice.
  void keys(const YAML::Node& map, const std::string& path, const Schema& schema) const;

  /// A map's key as text. YAML allows lists and maps as keys (`? [a, b]: 1`); an input has none.
  std::string key_name(const YAML::Node& key, const std::string& path) const;

  YAML::Node need(const YAML::Node& map, const std::string& key, const std::string& path) const {
    const YAML::Node n = map[key];
    if (!n) fail(map, join(path, key), "missing (required)");
    return n;
  }

  double number(const YAML::Node& n, const std::string& key) const;
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
  bool flag(const YAML::Node& n, const std::string& key) const;
  std::string text(const YAML::Node& n, const std::string& key) const;
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
  Eigen::Vector2d vec2(const YAML::Node& map, const std::string& k, const std::string& path,
                       const Eigen::Vector2d& fallback) const {
    return map[k] ? vec2(map[k], join(path, k)) : fallback;
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
                        std::string& path) const;

  /// Opens item i of `sensors`: its checked name (unique, not `t`, no commas or quotes, so that it
  /// can head a CSV column) and its path "sensors[NAME]" for later messages.
  std::string sensor_name(const YAML::Node& s, size_t i, std::set<std::string>& names, std::string& path) const;

  /// The index of the text `n` among `allowed`, or an error listing them.
  int choice(const YAML::Node& n, const std::string& key, const std::vector<std::string>& allowed) const;
  /// The index of map[key] (required) among `allowed`, or an error listing them.
  int choice(const YAML::Node& map, const std::string& key, const std::string& path,
             std::initializer_list<const char*> allowed) const {
    return choice(need(map, key, path), join(path, key), std::vector<std::string>(allowed.begin(), allowed.end()));
  }
  ExpressionScope& scope() { return scope_; }

  /// A number, or a time function {type: ..., ...} (the schemas of `time_function_schemas()`).
  TimeFunctionPtr function(const YAML::Node& n, const std::string& key) const;
  /// The times where the time functions read so far have a kink or a change of formula (ramp and
  /// smooth_step t0, t1; spin_up T; table t): adaptive steps land on them, so that a short pulse
  /// is not stepped over (driver/step_controller.hpp).
  const std::vector<double>& breakpoints() const { return breakpoints_; }

  void read_parameters(const YAML::Node& p);

 private:
  mutable std::vector<double> breakpoints_;
  std::string file_;
  std::string option_;
  MeshLoader mesh_loader_;
  ExpressionScope scope_;
  std::vector<std::pair<YAML::Node, std::string>> overrides_;
};

/// A map checked against its schema, whose values are read by key: types, ranges and messages
/// come from the schema ("unknown key (allowed here: …)", "expected one of …", "expected a
/// positive step size (s), got 0").
class Section {
 public:
  /// Checks that `map` is a map of the schema's keys (an absent map reads as empty).
  Section(const Reader& rd, const YAML::Node& map, std::string path, const Schema& schema);
  const YAML::Node& map() const { return map_; }
  const std::string& path() const { return path_; }
  std::string key_path(const std::string& key) const { return Reader::join(path_, key); }
  bool has(const std::string& key) const { return present_ && map_.IsMap() && map_[key].IsDefined(); }
  /// The node of `key` (an error if it is absent and required; an undefined node if it is absent).
  YAML::Node node(const std::string& key) const;

  /// Read a present or required key with the schema's type and range; `fallback` when absent.
  double number(const std::string& key, double fallback = 0.0) const;
  int integer(const std::string& key, int fallback = 0) const;
  bool flag(const std::string& key, bool fallback = false) const;
  std::string text(const std::string& key, const std::string& fallback = "") const;
  Eigen::Vector2d vec2(const std::string& key, const Eigen::Vector2d& fallback = Eigen::Vector2d::Zero()) const;
  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback = Eigen::Vector3d::Zero()) const;
  /// A [x, y, z] key that is a direction: non-zero, normalized (`fallback` when absent).
  Eigen::Vector3d direction(const std::string& key, const Eigen::Vector3d& fallback = Eigen::Vector3d::UnitX()) const;
  /// The index of the key's value among the schema's choices (`fallback` when absent).
  int choice(const std::string& key, int fallback = 0) const;
  TimeFunctionPtr function(const std::string& key) const;
  /// An Interval key: a whole number of steps (in the key's range), or a wall time in seconds.
  struct Interval {
    int steps = 0;
    double seconds = 0.0;
  };
  Interval interval(const std::string& key) const;
  /// A Numbers key: one number or a non-empty list, each in the key's range.
  std::vector<double> numbers(const std::string& key) const;
  /// A Texts key: a list of non-empty strings (one string reads as a list of one).
  std::vector<std::string> texts(const std::string& key) const;

 private:
  const Key& key(const std::string& name, KeyType type) const;
  /// The key's value read by `read` (a Reader method) if present, else `fallback`.
  template <class T>
  T value(const std::string& name, KeyType type, const T& fallback,
          T (Reader::*read)(const YAML::Node&, const std::string&) const) const {
    key(name, type);
    const YAML::Node n = node(name);
    return n.IsDefined() ? (rd_.*read)(n, key_path(name)) : fallback;
  }
  /// v, or an error at `at` (default: the key's path) if it is outside the key's range.
  double checked(const Key& k, const YAML::Node& n, double v, const std::string& at = "") const;
  const Reader& rd_;
  YAML::Node map_;
  bool present_;  ///< the map is in the tree (an absent one, a zombie node, cannot even be asked its type)
  std::string path_;
  const Schema& schema_;
};

/// The time functions' schemas (`time_functions.constant`, …), in the order of the docs.
const std::vector<Schema>& time_function_schemas();

/// Types of one kind (bodies, joints, loads or sensors of one dimension): name → schema and
/// constructor. `Build` is the constructor's signature; lookup errors list the registered names.
template <class Build>
class Registry {
 public:
  struct Type {
    std::string name;
    Schema schema;
    Build build;
  };
  /// `what`: "joint type", `dimension`: "" or " for dimension 3" (for messages).
  Registry(std::string what, std::string dimension) : what_(std::move(what)), dimension_(std::move(dimension)) {}
  void add(std::string name, Schema schema, Build build) {
    types_.push_back({std::move(name), std::move(schema), std::move(build)});
  }
  /// The type named by item[type] (required), or "unknown joint type 'x' (expected one of …)".
  const Type& find(const Reader& rd, const YAML::Node& item, const std::string& path, const std::string& extra = "") const {
    const std::string t = rd.text(rd.need(item, "type", path), path + ".type");
    for (const auto& type : types_)
      if (type.name == t) return type;
    rd.fail(item["type"], path + ".type", "unknown " + what_ + " '" + t + "'" + dimension_ + " (expected " + names() + extra + ")");
  }
  /// The type named `name`, nullptr if none is.
  const Type* get(const std::string& name) const {
    for (const auto& type : types_)
      if (type.name == name) return &type;
    return nullptr;
  }
  std::string names() const {
    std::string l;
    for (const auto& type : types_) l += (l.empty() ? "" : ", ") + type.name;
    return l;
  }
  const std::vector<Type>& types() const { return types_; }

 private:
  std::string what_, dimension_;
  std::vector<Type> types_;
};

/// Every schema of the scene files (sections and registered types), for `alphaflex keys`.
std::vector<const Schema*> scene_schemas();

/// Rewrites the key tables of a document: the text between `<!-- keys:NAME -->` and
/// `<!-- /keys -->` becomes the markdown table of schema NAME; unknown NAMEs are an InputError.
/// `unused` (if given) receives the names of the schemas no marker names.
std::string update_key_tables(const std::string& document, const std::vector<const Schema*>& schemas,
                              const std::string& label, std::vector<std::string>* unused = nullptr);

}  // namespace alphaflex::input
