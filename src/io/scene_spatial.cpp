// Spatial scenes (`dimension: 3`): rigid bodies on R³×SO(3), beams from gmsh meshes, 3D joints,
// loads and sensors. Every key is documented in docs/input.md.
#include <Eigen/Geometry>
#include <algorithm>
#include <set>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/shell.hpp"
#include "alphaflex/elements/spatial_elements.hpp"
#include "alphaflex/joints/spatial_joints.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "scene_reader.hpp"

namespace alphaflex::scene_detail {
namespace {

/// `orientation`: a rotation vector [rx, ry, rz] (rad) or {axis: [..], angle: ..}.
Eigen::Matrix3d read_orientation(Reader& rd, const YAML::Node& n, const std::string& key) {
  if (n.IsSequence()) return exp_so3<double>(rd.vec3(n, key));
  if (!n.IsMap()) rd.fail(n, key, "expected a rotation vector [rx, ry, rz] (rad) or {axis: [x, y, z], angle: a}");
  static const Schema rotation{"rotation", {{"axis", KeyType::Vec3, "–", kRequired, "rotation axis; non-zero"},
                                           {"angle", KeyType::Number, "rad", kRequired, "rotation angle about `axis`"}}};
  rd.keys(n, key, rotation);
  const Eigen::Vector3d axis = rd.direction(rd.need(n, "axis", key), key + ".axis");
  return exp_so3<double>(Eigen::Vector3d(axis * rd.number(rd.need(n, "angle", key), key + ".angle")));
}

/// Inertia tensor: [Ixx, Iyy, Izz] (principal, body axes) or a symmetric 3×3 list of rows.
Eigen::Matrix3d read_inertia(Reader& rd, const YAML::Node& n, const std::string& key) {
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  if (n.IsSequence() && n.size() == 3 && n[0].IsScalar()) {
    J.diagonal() = rd.vec3(n, key);
  } else if (n.IsSequence() && n.size() == 3) {
    for (int i = 0; i < 3; ++i) J.row(i) = rd.vec3(n[i], key + "[" + std::to_string(i) + "]").transpose();
    if ((J - J.transpose()).norm() > 1e-12 * J.norm()) rd.fail(n, key, "the inertia tensor must be symmetric");
  } else {
    rd.fail(n, key, "expected [Ixx, Iyy, Izz] or a 3x3 list of rows (kg m^2, body frame, about the centre of mass)");
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(J);
  const Eigen::Vector3d e = es.eigenvalues();
  if (!(e.minCoeff() > 0.0)) rd.fail(n, key, "the inertia tensor must be positive definite (a zero makes the mass matrix singular)");
  // Triangle inequality of principal moments (a physical mass distribution).
  if (e[0] + e[1] < e[2] * (1.0 - 1e-12)) rd.fail(n, key, "principal moments violate I1 + I2 >= I3: no body has this inertia");
  return J;
}

int spatial_node(SceneBuilder& sb, const YAML::Node& map, const std::string& key, const std::string& path, bool ground_ok) {
  const int id = sb.body(map, key, path, ground_ok);
  if (id >= 0 && !sb.model_.node(id).spatial())
    sb.rd_.fail(map[key], path + "." + key, "expected a spatial body or beam node");
  return id;
}

/// The pairs (node of a, node of b) at the same reference position (to 1e-9 of the groups'
/// extent): for joints between two meshed parts, e.g. the beams of a grid that cross at hinges.
/// Nodes of `a` with no partner are left out; two partners, or no pair at all, is an error.
std::vector<std::pair<int, int>> coincident_nodes(Reader& rd, const MeshGroup& a, const MeshGroup& b, const YAML::Node& at,
                                                  const std::string& key) {
  Eigen::AlignedBox3d box;
  for (const auto& p : a.points) box.extend(p);
  for (const auto& p : b.points) box.extend(p);
  const double tol = 1e-9 * std::max(1.0, box.diagonal().norm());
  // b's nodes sorted by x; each node of a looks at the slice within tol in x.
  std::vector<size_t> order(b.nodes.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t i, size_t k) { return b.points[i].x() < b.points[k].x(); });
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    if (a.nodes[i] < 0) continue;
    const Eigen::Vector3d& p = a.points[i];
    auto it = std::lower_bound(order.begin(), order.end(), p.x() - tol, [&](size_t k, double x) { return b.points[k].x() < x; });
    int partner = -1;
    for (; it != order.end() && b.points[*it].x() <= p.x() + tol; ++it) {
      const int n = b.nodes[*it];
      if (n < 0 || n == a.nodes[i] || (b.points[*it] - p).norm() > tol) continue;
      if (partner >= 0 && partner != n)
        rd.fail(at, key, "two nodes of this group lie at (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " +
                             std::to_string(p.z()) + "): a node of `group` must have at most one coincident node here");
      partner = n;
    }
    if (partner >= 0) pairs.emplace_back(a.nodes[i], partner);
  }
  if (pairs.empty())
    rd.fail(at, key, "no node of this group is at the place of a node of `group` (a joint per pair of coincident nodes; are the meshes' points distinct but coincident, e.g. Geometry.AutoCoherence = 0 in the .geo?)");
  return pairs;
}

/// Initial pose of a node (the identity for the ground).
Pose<double> initial_pose(const Model& m, int node) {
  if (node < 0) return Pose<double>{Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  return pose_of(m.node(node).q0.data());
}

/// A marker on `node` (slot in the joint's node list) that coincides with the world frame
/// (position p, rotation R) at t = 0.
SpatialMarker marker_at(const Model& m, int node, int slot, const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  SpatialMarker mk;
  mk.slot = node < 0 ? -1 : slot;
  const Pose<double> f = initial_pose(m, node);
  mk.position = f.R.transpose() * (p - f.x);
  mk.rotation = f.R.transpose() * R;
  return mk;
}


const Schema& marker_schema() {
  static const Schema s{"bodies.3d.markers", {
      {"name", KeyType::Text, "–", kRequired, "unique in the scene (among markers, bodies and mesh points)"},
      {"position", KeyType::Vec3, "m", kRequired, "origin of the marker in the body frame"},
      {"orientation", KeyType::Map, "rad", "identity", "rotation of the marker frame in the body frame", {}, "", "rotation"}}};
  return s;
}

void read_rigid_body_3d(const Item& it) {
  Reader& rd = it.rd;
  const Section& k = it.keys;
  const double m = k.number("mass");
  const Eigen::Matrix3d J = read_inertia(rd, k.node("inertia"), it.at("inertia"));
  const Eigen::Vector3d x = k.vec3("position");
  const Eigen::Matrix3d R = k.has("orientation") ? read_orientation(rd, k.node("orientation"), it.at("orientation"))
                                                 : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d v = k.vec3("velocity"), w = k.vec3("angular_velocity");  // w: world frame
  Node nd;
  nd.name = it.name;
  nd.kind = NodeKind::Frame3D;
  nd.q0.resize(7);
  store_pose(x, R, nd.q0.data());
  nd.v0.resize(6);
  nd.v0 << v, R.transpose() * w;  // Ω in the body frame
  const int id = it.model.add_node(nd);
  it.model.add_element(std::make_unique<RigidBody3D>(it.name, id, m, J, it.sb.gravity));
  // Markers: named frames fixed to the body (position and orientation in the body frame), for
  // joints (marker1/marker2) and point sensors (marker).
  if (const YAML::Node ml = k.node("markers")) {
    if (!ml.IsSequence()) rd.fail(ml, it.at("markers"), "expected a list of {name, position, orientation}");
    for (size_t i = 0; i < ml.size(); ++i) {
      const YAML::Node mk = ml[i];
      const std::string mp = it.at("markers[" + std::to_string(i) + "]");
      if (!mk.IsMap()) rd.fail(mk, mp, "expected a map {name, position, orientation}");
      const Section ms(rd, mk, mp, marker_schema());
      const std::string mname = ms.text("name");
      if (it.sb.markers.count(mname) || it.model.find_node(mname) >= 0)
        rd.fail(mk["name"], mp + ".name", "the name '" + mname + "' is taken (marker names are unique in a scene)");
      NamedMarker nm;
      nm.node = id;
      nm.position = ms.vec3("position");
      if (ms.has("orientation")) nm.rotation = read_orientation(rd, ms.node("orientation"), mp + ".orientation");
      it.sb.markers[mname] = nm;
    }
  }
}

Schema spatial_joint_schema(const SpatialJointKind& kind) {
  std::vector<Key> keys{
      {"body1", KeyType::Text, "–", "– (or `marker1`, or `group`)", "the first body or beam/shell node; not `ground`"},
      {"body2", KeyType::Text, "–", "`ground`", "the second body, node or `ground`; different from body1"},
      {"location", KeyType::Vec3, "m", "body1's reference point", "world point of the joint at t = 0"},
      {"marker1", KeyType::Text, "–", "–", "a marker of a body: stands for body1, the location and (without `axis`) the joint frame"},
      {"marker2", KeyType::Text, "–", "–", "a marker of a body at the joint's location at t = 0: stands for body2"},
      {"group", KeyType::Text, "–", "–", "a mesh group instead of body1: one joint NAME[k] per node of the group"},
      {"group2", KeyType::Text, "–", "–", "with `group`: a second mesh group; one joint per pair of coincident nodes"}};
  if (kind.needs_axis) keys.push_back({"axis", KeyType::Vec3, "–", kRequired + std::string(" (unless `marker1`)"), "joint axis (world, t = 0); non-zero"});
  if (kind.needs_axis2) keys.push_back({"axis2", KeyType::Vec3, "–", kRequired, "second axis (world, t = 0), perpendicular to `axis`"});
  if (kind.takes_reference)
    keys.push_back(kind.needs_axis ? Key{"reference", KeyType::Vec3, "–", "any ⊥ axis", "direction ⊥ axis where a driver's angle is zero; not parallel to the axis"}
                             : Key{"reference", KeyType::Map, "rad", "body1's frame", "rotation of the joint frame", {}, "", "rotation"});
  if (kind.angle_driver || kind.displacement_driver)
    keys.push_back({"driver", KeyType::Map, "rad, m", "none",
                    std::string("prescribed relative motion: ") + (kind.angle_driver ? "`angle` (rad)" : "") +
                        (kind.angle_driver && kind.displacement_driver ? ", " : "") +
                        (kind.displacement_driver ? "`displacement` (m)" : "") + ", each a number or a time function"});
  return type_schema("joints.3d." + kind.name,
                     "`" + kind.name + "`: " + std::to_string(kind.num_equations) + " equations; " + kind.doc, keys);
}

const Schema& driver_schema() {
  static const Schema s{"joints.3d.driver", {
      {"angle", KeyType::Function, "rad", "none", "relative rotation about the axis from `reference` (revolute, cylindrical)"},
      {"displacement", KeyType::Function, "m", "none", "relative translation along the axis (cylindrical, prismatic)"}}};
  return s;
}

/// Every spatial joint kind: one reader, the kind's row of spatial_joint_kinds() (joints/spatial_joints.hpp) says what it takes.
void read_spatial_joint(const Item& it, const SpatialJointKind& kind) {
  Reader& rd = it.rd;
  SceneBuilder& sb = it.sb;
  Model& model = it.model;
  const YAML::Node& j = it.node;
  const std::string& path = it.path;
  const std::string& name = it.name;
  const bool has_axis = kind.needs_axis;
  // A marker (a named frame of a body) stands for the body, the location and the joint frame.
  auto marker_of = [&](const char* key) -> const NamedMarker* {
    if (!j[key]) return nullptr;
    const std::string mn = rd.text(j[key], path + "." + key);
    const auto found = sb.markers.find(mn);
    if (found == sb.markers.end()) rd.fail(j[key], path + "." + key, "no marker named '" + mn + "' (markers are listed under a body's `markers`)");
    return &found->second;
  };
  const NamedMarker* mk1 = marker_of("marker1");
  const NamedMarker* mk2 = marker_of("marker2");
  if (mk1 && j["body1"]) rd.fail(j["body1"], path + ".body1", "give either body1 or marker1");
  if (mk2 && j["body2"]) rd.fail(j["body2"], path + ".body2", "give either body2 or marker2");
  if (mk1 && j["location"]) rd.fail(j["location"], path + ".location", "marker1 fixes the location; remove one of them");
  // `group`: one joint per node of a mesh group (a clamped or supported edge), named name[k],
  // each at its node with that node as body1.
  const MeshGroup* group = nullptr;
  if (const YAML::Node g = j["group"]) {
    for (const char* k : {"body1", "marker1", "location"})
      if (j[k]) rd.fail(j[k], path + "." + k, "give either group (a joint at every node of a mesh group) or " + std::string(k));
    group = &sb.mesh_group(g, path + ".group");
  }
  if (!mk1 && !j["body1"] && !group) rd.fail(j, path + ".body1", "missing (required): body1, marker1 or group");
  if (j["group2"] && !group) rd.fail(j["group2"], path + ".group2", "group2 pairs the nodes of `group` with coincident ones: give group too");
  if (j["group2"] && (j["body2"] || mk2))
    rd.fail(j["group2"], path + ".group2", "give either group2 (the coincident node of another mesh group) or body2/marker2");
  const int fixed_b2 = mk2 ? mk2->node : (j["body2"] ? spatial_node(sb, j, "body2", path, true) : -1);
  // (body1, body2) of each joint: one joint, or one per node of `group` (with body2, or with the
  // node of `group2` at the same place: a hinge between two meshed parts that cross or touch).
  std::vector<std::pair<int, int>> pairs;
  if (!group) {
    pairs.emplace_back(mk1 ? mk1->node : spatial_node(sb, j, "body1", path, false), fixed_b2);
  } else if (!j["group2"]) {
    for (int n : group->nodes) pairs.emplace_back(n, fixed_b2);
  } else {
    const MeshGroup& other = sb.mesh_group(j["group2"], path + ".group2");
    pairs = coincident_nodes(rd, *group, other, j["group2"], path + ".group2");
  }
  for (size_t k = 0; k < pairs.size(); ++k) {
    const auto [b1, b2] = pairs[k];
    const std::string jname = group ? name + "[" + std::to_string(k) + "]" : name;
    if (group && k == 0)  // name[0], name[1], …: checked once per group, not once per joint
      for (const auto& c : model.constraints())
        if (c->name().rfind(name + "[", 0) == 0) rd.fail(j["name"], path + ".name", "a joint named '" + c->name() + "' exists already");
    if (b1 == b2) rd.fail(j["body2"] ? j["body2"] : j, path + ".body2", "a joint needs two different bodies");
    const Pose<double> p1 = initial_pose(model, b1);
    const Eigen::Vector3d loc = mk1                ? Eigen::Vector3d(p1.x + p1.R * mk1->position)
                                : j["location"] ? rd.vec3(j["location"], path + ".location")
                                                : p1.x;
    // Joint frame (world, t = 0): a3 along the axis; universal: a1 = axis (on body 1), a2 = axis2.
    // Without an axis key, a marker's frame is the joint frame (its z axis is the joint axis).
    Eigen::Matrix3d R = mk1 ? Eigen::Matrix3d(p1.R * mk1->rotation) : p1.R;
    if (mk1 && has_axis && !j["axis"]) {
      R = p1.R * mk1->rotation;
    } else if (kind.needs_axis2) {
      const Eigen::Vector3d a1 = rd.direction(rd.need(j, "axis", path), path + ".axis");
      const Eigen::Vector3d a2 = rd.direction(rd.need(j, "axis2", path), path + ".axis2");
      if (std::fabs(a1.dot(a2)) > 1e-9)
        rd.fail(j["axis2"], path + ".axis2", "the two axes of a universal joint must be perpendicular");
      R.col(0) = a1;
      R.col(1) = a2;
      R.col(2) = a1.cross(a2);
    } else if (has_axis) {
      const Eigen::Vector3d a3 = rd.direction(rd.need(j, "axis", path), path + ".axis");
      // a1: the `reference` direction (where a driver's angle is zero), else any perpendicular.
      Eigen::Vector3d ref = j["reference"] ? rd.direction(j["reference"], path + ".reference")
                                           : (std::fabs(a3.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
      ref -= a3.dot(ref) * a3;
      if (ref.norm() < 1e-9) rd.fail(j["reference"], path + ".reference", "must not be parallel to the axis");
      R.col(0) = ref.normalized();
      R.col(2) = a3;
      R.col(1) = a3.cross(R.col(0));
    } else if (j["reference"]) {
      R = read_orientation(rd, j["reference"], path + ".reference");
    }
    TimeFunctionPtr angle, displacement;
    if (const YAML::Node d = j["driver"]) {
      rd.keys(d, path + ".driver", driver_schema());
      if (d["angle"]) {
        if (!kind.angle_driver)
          rd.fail(d["angle"], path + ".driver.angle", "a " + kind.name + " joint has no rotation to drive (use displacement)");
        angle = rd.function(d["angle"], path + ".driver.angle");
      }
      if (d["displacement"]) {
        if (!kind.displacement_driver)
          rd.fail(d["displacement"], path + ".driver.displacement", "a " + kind.name + " joint has no translation to drive (use angle)");
        displacement = rd.function(d["displacement"], path + ".driver.displacement");
      }
    }
    if (mk2) {
      const Pose<double> p2 = initial_pose(model, b2);
      const Eigen::Vector3d at2 = p2.x + p2.R * mk2->position;
      if ((at2 - loc).norm() > 1e-9 * std::max(1.0, loc.norm()))
        rd.fail(j["marker2"], path + ".marker2",
                "is not at the joint's location at t = 0 (distance " + std::to_string((at2 - loc).norm()) + " m)");
    }
    std::vector<int> nodes{b1};
    if (b2 >= 0) nodes.push_back(b2);
    const SpatialMarker A = marker_at(model, b1, 0, loc, R);
    const SpatialMarker B = marker_at(model, b2, 1, loc, R);
    try {
      model.add_constraint(std::make_unique<SpatialJoint>(jname, nodes, kind, A, B, angle, displacement));
    } catch (const std::invalid_argument& e) {
      rd.fail(j, path, e.what());
    }
  }
}

/// `pressure` on the shell elements of a surface group (ShellPressure per element).
void read_pressure(const Item& it) {
  const MeshGroup& g = it.sb.mesh_group(it.keys.node("group"), it.at("group"), 2);
  if (!g.shells) it.rd.fail(it.node["group"], it.at("group"), "a pressure acts on shells: no `shells` block uses this surface group");
  const TimeFunctionPtr p = it.keys.function("value");
  const bool follower = it.keys.flag("follower", true);
  for (size_t e = 0; e < g.elements.size(); ++e) {
    std::vector<Eigen::Vector3d> X;
    for (int n : g.elements[e]) X.push_back(initial_pose(it.model, n).x);
    it.model.add_element(std::make_unique<ShellPressure>(it.name + "[" + std::to_string(e) + "]", g.elements[e], X, p, follower));
  }
}

/// [x, y, z] of time functions at `key` (absent: none).
std::array<TimeFunctionPtr, 3> vector_function(const Item& it, const char* key, const char* unit) {
  std::array<TimeFunctionPtr, 3> v;
  const YAML::Node n = it.keys.node(key);
  if (!n) return v;
  if (!n.IsSequence() || n.size() != 3)
    it.rd.fail(n, it.at(key), std::string("expected [x, y, z], each a number or a time function (") + unit + ")");
  for (int k = 0; k < 3; ++k) v[static_cast<size_t>(k)] = it.rd.function(n[k], it.at(key) + "[" + std::to_string(k) + "]");
  return v;
}

/// `edge_load` (force and moment per length) on a curve group, as consistent nodal loads of its
/// linear segments: each node carries half the reference length of each adjacent segment.
void read_edge_load(const Item& it) {
  const MeshGroup& g = it.sb.mesh_group(it.keys.node("group"), it.at("group"), 1);
  if (!it.keys.has("force") && !it.keys.has("moment")) it.rd.fail(it.node, it.path, "an edge_load needs force (N/m) or moment (N m/m), or both");
  const std::array<TimeFunctionPtr, 3> force = vector_function(it, "force", "N/m"), moment = vector_function(it, "moment", "N m/m");
  const bool follower = it.keys.flag("follower", false);
  std::map<int, double> length;  // node → length it carries
  for (const auto& seg : g.elements) {
    const double l = (initial_pose(it.model, seg[1]).x - initial_pose(it.model, seg[0]).x).norm();
    length[seg[0]] += 0.5 * l;
    length[seg[1]] += 0.5 * l;
  }
  for (int n : g.nodes) {
    auto scaled = [&](const std::array<TimeFunctionPtr, 3>& v) {
      std::array<TimeFunctionPtr, 3> out;
      for (size_t k = 0; k < 3; ++k)
        if (v[k]) out[k] = make_scaled(v[k], length[n]);
      return out;
    };
    it.model.add_element(std::make_unique<SpatialLoad>(it.name + "[" + it.model.node(n).name + "]", n, Eigen::Vector3d::Zero(),
                                                       scaled(force), scaled(moment), follower));
  }
}

/// `force` (at a body point) and `moment`: dead (world components) or follower (body frame).
void read_point_load(const Item& it, bool moment) {
  const int b = spatial_node(it.sb, it.node, "body", it.path, false);
  const Eigen::Vector3d s = moment ? Eigen::Vector3d::Zero() : it.keys.vec3("point");
  const std::array<TimeFunctionPtr, 3> value = vector_function(it, "value", moment ? "N m" : "N"), none;
  const bool follower = it.keys.flag("follower", false);
  it.model.add_element(std::make_unique<SpatialLoad>(it.name, b, s, moment ? none : value, moment ? value : none, follower));
}

void read_point_sensor_3d(const Item& it, Sensor& sn, Sensor::Kind kind) {
  Reader& rd = it.rd;
  const Section& k = it.keys;
  sn.kind = kind;
  if (k.has("marker")) {
    if (k.has("body") || k.has("point")) rd.fail(k.node("marker"), it.at("marker"), "give either marker or body/point");
    const std::string mn = k.text("marker");
    const auto found = it.sb.markers.find(mn);
    if (found == it.sb.markers.end()) rd.fail(k.node("marker"), it.at("marker"), "no marker named '" + mn + "'");
    sn.node = found->second.node;
    sn.local = found->second.position;
  } else {
    sn.node = spatial_node(it.sb, it.node, "body", it.path, false);
    sn.local = k.vec3("point");
  }
  sn.component = k.choice("component");
  const Pose<double> p0 = initial_pose(it.model, sn.node);
  sn.initial = p0.x + p0.R * sn.local;
  if (k.has("relative_to")) {
    sn.frame_node = spatial_node(it.sb, it.node, "relative_to", it.path, false);
    if (sn.kind == Sensor::Kind::PointDisplacement) {
      // Displacement seen in the moving frame: position in that frame minus its initial value.
      const Pose<double> f0 = initial_pose(it.model, sn.frame_node);
      sn.initial = f0.R.transpose() * (sn.initial - f0.x);
    }
  }
}

void read_body_rotation(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::BodyRotation;
  sn.node = spatial_node(it.sb, it.node, "body", it.path, false);
  sn.component = it.keys.choice("component");
}

void read_joint_reaction_3d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::JointReaction;
  sn.constraint = sensor_joint(it);
  sn.component = it.keys.choice("component");
}

/// A result field of one element of a beam or shell block (elements name[k], mesh order).
void read_element_output(const Item& it, Sensor& sn, bool beam) {
  Reader& rd = it.rd;
  const char* block = beam ? "beam" : "shell";
  sn.kind = Sensor::Kind::ElementOutput;
  const std::string bn = it.keys.text(block);
  const int idx = it.keys.integer("element");
  const std::string ename = bn + "[" + std::to_string(idx) + "]";
  const auto& elements = it.model.elements();
  for (size_t e = 0; e < elements.size(); ++e)
    if (elements[e]->name() == ename && !elements[e]->output_names().empty()) sn.element = static_cast<int>(e);
  if (sn.element < 0)
    rd.fail(it.node["element"], it.at("element"), std::string(block) + " '" + bn + "' has no element " + std::to_string(idx) +
                                                      (beam ? " (elements are numbered from 0 along the mesh)"
                                                            : " (elements are numbered from 0 in the mesh group's order)"));
  sn.component = rd.choice(it.keys.node("component"), it.at("component"), elements[static_cast<size_t>(sn.element)]->output_names());
}

}  // namespace

const SceneTypes& spatial_types() {
  static const SceneTypes t = [] {
    SceneTypes t{{"body type", " for dimension 3"}, {"joint type", ""}, {"load type", " for dimension 3"},
                 {"sensor type", " for dimension 3"}, "; beams come from `beams`", {&marker_schema(), &driver_schema()}};
    t.bodies.add("rigid_body", type_schema("bodies.3d.rigid_body", "`rigid_body`: a frame on R³×SO(3)", {
        {"mass", KeyType::Number, "kg", kRequired, "positive", Range::positive(), "mass (kg); a zero mass makes the mass matrix singular"},
        {"inertia", KeyType::List, "kg·m²", kRequired, "about the centre of mass in the body frame; symmetric positive definite with I1 + I2 ≥ I3",
         {}, "", "[Ixx, Iyy, Izz] or 3×3 list of rows"},
        {"position", KeyType::Vec3, "m", kRequired, "centre of mass at t = 0"},
        {"orientation", KeyType::Map, "rad", "identity", "body frame at t = 0: a rotation vector [rx, ry, rz] or {axis, angle}", {}, "", "rotation"},
        {"velocity", KeyType::Vec3, "m/s", "[0, 0, 0]", "velocity of the centre of mass at t = 0"},
        {"angular_velocity", KeyType::Vec3, "rad/s", "[0, 0, 0]", "world components at t = 0"},
        {"markers", KeyType::List, "m, rad", "none", "frames fixed to the body, `{name, position, orientation}` in the body frame"}}),
                  read_rigid_body_3d);
    for (const SpatialJointKind& kind : spatial_joint_kinds())  // one registration per row of the joints' table
      t.joints.add(kind.name, spatial_joint_schema(kind), [&kind](const Item& it) { read_spatial_joint(it, kind); });

    const Key follower_off{"follower", KeyType::Flag, "–", "off", "off: world components (dead load); on: body-frame components (follower)"};
    t.loads.add("force", type_schema("forces.3d.force", "`force` at a body point", {
        {"body", KeyType::Text, "–", kRequired, "a body or beam/shell node; not `ground`"},
        {"point", KeyType::Vec3, "m", "[0, 0, 0]", "point of application, body frame"},
        {"value", KeyType::List, "N", kRequired, "[fx, fy, fz], each a number or a time function", {}, "", "[x, y, z] of time functions"},
        follower_off}), [](const Item& it) { read_point_load(it, false); });
    t.loads.add("moment", type_schema("forces.3d.moment", "`moment` on a body", {
        {"body", KeyType::Text, "–", kRequired, "a body or beam/shell node; not `ground`"},
        {"value", KeyType::List, "N·m", kRequired, "[mx, my, mz], each a number or a time function", {}, "", "[x, y, z] of time functions"},
        follower_off}), [](const Item& it) { read_point_load(it, true); });
    t.loads.add("pressure", type_schema("forces.3d.pressure", "`pressure` on the shells of a surface group", {
        {"group", KeyType::Text, "–", kRequired, "a surface group used by `shells`"},
        {"value", KeyType::Function, "Pa", kRequired, "positive against the element normal"},
        {"follower", KeyType::Flag, "–", "on", "on: along the current normal, per current area; off: fixed direction"}}), read_pressure);
    t.loads.add("edge_load", type_schema("forces.3d.edge_load", "`edge_load`: a load per length along a curve group", {
        {"group", KeyType::Text, "–", kRequired, "a curve group whose nodes are on beams or shells"},
        {"force", KeyType::List, "N/m", "none", "[fx, fy, fz] per length, each a number or a time function", {}, "", "[x, y, z] of time functions"},
        {"moment", KeyType::List, "N·m/m", "none", "[mx, my, mz] per length (force or moment, or both)", {}, "", "[x, y, z] of time functions"},
        follower_off}), read_edge_load);

    const Key xyz{"component", KeyType::Choice, "–", kRequired, "component", {}, "", "", {"x", "y", "z"}};
    const std::pair<const char*, Sensor::Kind> points[] = {
        {"point_position", Sensor::Kind::PointPosition}, {"point_displacement", Sensor::Kind::PointDisplacement},
        {"point_velocity", Sensor::Kind::PointVelocity}, {"point_acceleration", Sensor::Kind::PointAcceleration}};
    for (const auto& [name, kind] : points)  // one schema, four quantities (m, m, m/s, m/s²)
      t.sensors.add(name, type_schema(std::string("sensors.3d.") + name, std::string("`") + name + "` of a body point: world components, or in the frame of `relative_to`", {
          {"body", KeyType::Text, "–", kRequired + std::string(" (unless `marker`)"), "a body or beam/shell node; not `ground`"},
          {"point", KeyType::Vec3, "m", "[0, 0, 0]", "point of the body, body frame"},
          {"marker", KeyType::Text, "–", "–", "a marker instead of body and point"},
          xyz,
          {"relative_to", KeyType::Text, "–", "none", "a body whose frame the point is seen in"}}),
          [kind = kind](const Item& it, Sensor& sn) { read_point_sensor_3d(it, sn, kind); });
    t.sensors.add("body_rotation", type_schema("sensors.3d.body_rotation", "`body_rotation`: component of the rotation vector log(R) (rad)", {
        {"body", KeyType::Text, "–", kRequired, "a body or beam/shell node"}, xyz}), read_body_rotation);
    t.sensors.add("joint_reaction", type_schema("sensors.3d.joint_reaction", "`joint_reaction`: force / moment on body1 in the joint frame (N, N·m)", {
        {"joint", KeyType::Text, "–", kRequired, "a joint of `joints`"},
        {"component", KeyType::Choice, "–", kRequired, "component", {}, "", "", {"fx", "fy", "fz", "mx", "my", "mz"}}}), read_joint_reaction_3d);
    for (const bool beam : {true, false}) {
      const char* block = beam ? "beam" : "shell";
      t.sensors.add(std::string(block) + "_output", type_schema(std::string("sensors.3d.") + block + "_output",
                    std::string("`") + block + "_output`: a result of one element of a " + block + " block", {
          {block, KeyType::Text, "–", kRequired, std::string("the name of a `") + block + "s` block"},
          {"element", KeyType::Integer, "–", kRequired, beam ? "index from 0 along the mesh" : "index from 0 in the group's element order", Range::at_least(0)},
          {"component", KeyType::Text, "–", kRequired, beam ? "`N V2 V3 T M2 M3` (N, N·m) or `axial_strain shear_strain_2 shear_strain_3 twist curvature_2 curvature_3` (1, 1/m)"
                                                            : "a shell result: `n11 n22 n12` (N/m), `m11 m22 m12` (N·m/m), `q1 q2` (N/m), stresses (Pa)"}}),
          [beam](const Item& it, Sensor& sn) { read_element_output(it, sn, beam); });
    }
    add_spatial_force_types(t);
    return t;
  }();
  return t;
}

}  // namespace alphaflex::scene_detail
