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
  rd.keys(n, key, {"axis", "angle"});
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

}  // namespace

void read_spatial_bodies(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model, const Eigen::Vector3d& gravity) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "bodies", "expected a list of bodies");
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node b = list[i];
    std::string path;
    const std::string name = rd.item_name(b, "bodies", i, "expected a map with name, type, ...", path);
    if (name == "ground") rd.fail(b["name"], path + ".name", "'ground' is reserved for the fixed frame");
    if (model.find_node(name) >= 0) rd.fail(b["name"], path + ".name", "a body or mesh point named '" + name + "' exists already");
    const std::string type = rd.text(rd.need(b, "type", path), path + ".type");
    if (type != "rigid_body")
      rd.fail(b["type"], path + ".type", "unknown body type '" + type + "' for dimension 3 (expected rigid_body; beams come from `beams`)");
    rd.keys(b, path, {"name", "type", "mass", "inertia", "position", "orientation", "velocity", "angular_velocity", "markers"});
    const double m = rd.positive(rd.need(b, "mass", path), path + ".mass", "mass (kg); a zero mass makes the mass matrix singular");
    const Eigen::Matrix3d J = read_inertia(rd, rd.need(b, "inertia", path), path + ".inertia");
    const Eigen::Vector3d x = rd.vec3(rd.need(b, "position", path), path + ".position");
    const Eigen::Matrix3d R = b["orientation"] ? read_orientation(rd, b["orientation"], path + ".orientation")
                                               : Eigen::Matrix3d::Identity();
    const Eigen::Vector3d v = rd.vec3(b, "velocity", path, Eigen::Vector3d::Zero());
    const Eigen::Vector3d w = rd.vec3(b, "angular_velocity", path, Eigen::Vector3d::Zero());  // world frame
    Node nd;
    nd.name = name;
    nd.kind = NodeKind::Frame3D;
    nd.q0.resize(7);
    store_pose(x, R, nd.q0.data());
    nd.v0.resize(6);
    nd.v0 << v, R.transpose() * w;  // Ω in the body frame
    const int id = model.add_node(nd);
    model.add_element(std::make_unique<RigidBody3D>(name, id, m, J, gravity));
    // Markers: named frames fixed to the body (position and orientation in the body frame), for
    // joints (marker1/marker2) and point sensors (marker).
    if (const YAML::Node ml = b["markers"]) {
      if (!ml.IsSequence()) rd.fail(ml, path + ".markers", "expected a list of {name, position, orientation}");
      for (size_t k = 0; k < ml.size(); ++k) {
        const YAML::Node mk = ml[k];
        std::string mp = path + ".markers[" + std::to_string(k) + "]";
        if (!mk.IsMap()) rd.fail(mk, mp, "expected a map {name, position, orientation}");
        rd.keys(mk, mp, {"name", "position", "orientation"});
        const std::string mname = rd.text(rd.need(mk, "name", mp), mp + ".name");
        if (sb.markers.count(mname) || model.find_node(mname) >= 0)
          rd.fail(mk["name"], mp + ".name", "the name '" + mname + "' is taken (marker names are unique in a scene)");
        NamedMarker nm;
        nm.node = id;
        nm.position = rd.vec3(rd.need(mk, "position", mp), mp + ".position");
        if (mk["orientation"]) nm.rotation = read_orientation(rd, mk["orientation"], mp + ".orientation");
        sb.markers[mname] = nm;
      }
    }
  }
}

void read_spatial_joints(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "joints", "expected a list of joints");
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node j = list[i];
    std::string path;
    const std::string name = rd.item_name(j, "joints", i, "expected a map with name, type, ...", path);
    if (model.find_constraint(name) >= 0) rd.fail(j["name"], path + ".name", "a joint named '" + name + "' exists already");
    const std::string tname = rd.text(rd.need(j, "type", path), path + ".type");
    // The joint types and the keys and drivers each takes: the table of joints/spatial_joints.cpp.
    const SpatialJointKind* kind = find_spatial_joint_kind(tname);
    if (!kind)
      rd.fail(j["type"], path + ".type", "unknown joint type '" + tname + "' (expected " + spatial_joint_kind_names() + ")");
    std::set<std::string> allowed{"name", "type", "body1", "body2", "location", "marker1", "marker2", "group", "group2"};
    const bool has_axis = kind->needs_axis;
    if (has_axis) allowed.insert("axis");
    if (kind->needs_axis2) allowed.insert("axis2");
    if (kind->takes_reference) allowed.insert("reference");
    if (kind->angle_driver || kind->displacement_driver) allowed.insert("driver");
    rd.keys(j, path, allowed);
    // A marker (a named frame of a body) stands for the body, the location and the joint frame.
    auto marker_of = [&](const char* key) -> const NamedMarker* {
      if (!j[key]) return nullptr;
      const std::string mn = rd.text(j[key], path + "." + key);
      const auto it = sb.markers.find(mn);
      if (it == sb.markers.end()) rd.fail(j[key], path + "." + key, "no marker named '" + mn + "' (markers are listed under a body's `markers`)");
      return &it->second;
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
      } else if (kind->needs_axis2) {
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
        rd.keys(d, path + ".driver", {"angle", "displacement"});
        if (d["angle"]) {
          if (!kind->angle_driver)
            rd.fail(d["angle"], path + ".driver.angle", "a " + kind->name + " joint has no rotation to drive (use displacement)");
          angle = rd.function(d["angle"], path + ".driver.angle");
        }
        if (d["displacement"]) {
          if (!kind->displacement_driver)
            rd.fail(d["displacement"], path + ".driver.displacement",
                    "a " + kind->name + " joint has no translation to drive (use angle)");
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
        model.add_constraint(std::make_unique<SpatialJoint>(jname, nodes, *kind, A, B, angle, displacement));
      } catch (const std::invalid_argument& e) {
        rd.fail(j, path, e.what());
      }
    }
  }
}


/// `pressure` on the shell elements of a surface group (ShellPressure per element) and `edge_load`
/// (force and moment per length) on a curve group, as consistent nodal loads of its linear
/// segments: each node carries half the reference length of each adjacent segment.
void read_surface_load(Reader& rd, SceneBuilder& sb, const YAML::Node& f, const std::string& path, const std::string& name,
                       const std::string& type, Model& model) {
  if (type == "pressure") {
    rd.keys(f, path, {"name", "type", "group", "value", "follower"});
    const MeshGroup& g = sb.mesh_group(rd.need(f, "group", path), path + ".group", 2);
    if (!g.shells) rd.fail(f["group"], path + ".group", "a pressure acts on shells: no `shells` block uses this surface group");
    const TimeFunctionPtr p = rd.function(rd.need(f, "value", path), path + ".value");
    const bool follower = f["follower"] ? rd.flag(f["follower"], path + ".follower") : true;
    for (size_t e = 0; e < g.elements.size(); ++e) {
      std::vector<Eigen::Vector3d> X;
      for (int n : g.elements[e]) X.push_back(initial_pose(model, n).x);
      model.add_element(std::make_unique<ShellPressure>(name + "[" + std::to_string(e) + "]", g.elements[e], X, p, follower));
    }
    return;
  }
  rd.keys(f, path, {"name", "type", "group", "force", "moment", "follower"});
  const MeshGroup& g = sb.mesh_group(rd.need(f, "group", path), path + ".group", 1);
  if (!f["force"] && !f["moment"]) rd.fail(f, path, "an edge_load needs force (N/m) or moment (N m/m), or both");
  auto per_length = [&](const char* key, const char* unit) {
    std::array<TimeFunctionPtr, 3> v;
    const YAML::Node n = f[key];
    if (!n) return v;
    if (!n.IsSequence() || n.size() != 3)
      rd.fail(n, path + "." + key, std::string("expected [x, y, z], each a number or a time function (") + unit + ")");
    for (int k = 0; k < 3; ++k) v[static_cast<size_t>(k)] = rd.function(n[k], path + "." + key + "[" + std::to_string(k) + "]");
    return v;
  };
  const std::array<TimeFunctionPtr, 3> force = per_length("force", "N/m"), moment = per_length("moment", "N m/m");
  const bool follower = f["follower"] ? rd.flag(f["follower"], path + ".follower") : false;
  std::map<int, double> length;  // node → length it carries
  for (const auto& seg : g.elements) {
    const double l = (initial_pose(model, seg[1]).x - initial_pose(model, seg[0]).x).norm();
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
    model.add_element(std::make_unique<SpatialLoad>(name + "[" + model.node(n).name + "]", n, Eigen::Vector3d::Zero(),
                                                    scaled(force), scaled(moment), follower));
  }
}

void read_spatial_forces(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "forces", "expected a list of loads");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node f = list[i];
    std::string path;
    const std::string name = rd.item_name(f, "forces", i, "expected a map with name, type, ...", path);
    if (!names.insert(name).second) rd.fail(f["name"], path + ".name", "a force named '" + name + "' exists already");
    const std::string type = rd.text(rd.need(f, "type", path), path + ".type");
    if (type == "pressure" || type == "edge_load") {
      read_surface_load(rd, sb, f, path, name, type, model);
      continue;
    }
    if (type != "force" && type != "moment")
      rd.fail(f["type"], path + ".type", "unknown load type '" + type + "' for dimension 3 (expected force, moment, pressure, edge_load)");
    rd.keys(f, path, type == "force" ? std::set<std::string>{"name", "type", "body", "point", "value", "follower"}
                                     : std::set<std::string>{"name", "type", "body", "value", "follower"});
    const int b = spatial_node(sb, f, "body", path, false);
    const Eigen::Vector3d s = rd.vec3(f, "point", path, Eigen::Vector3d::Zero());
    const YAML::Node v = rd.need(f, "value", path);
    const char* unit = type == "force" ? "N" : "N m";
    if (!v.IsSequence() || v.size() != 3)
      rd.fail(v, path + ".value", std::string("expected [x, y, z], each a number or a time function (") + unit + ")");
    std::array<TimeFunctionPtr, 3> value, none;
    for (int k = 0; k < 3; ++k) value[static_cast<size_t>(k)] = rd.function(v[k], path + ".value[" + std::to_string(k) + "]");
    const bool follower = f["follower"] ? rd.flag(f["follower"], path + ".follower") : false;
    if (type == "force")
      model.add_element(std::make_unique<SpatialLoad>(name, b, s, value, none, follower));
    else
      model.add_element(std::make_unique<SpatialLoad>(name, b, Eigen::Vector3d::Zero(), none, value, follower));
  }
}

void read_spatial_sensors(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "sensors", "expected a list of sensors");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node s = list[i];
    std::string path;
    Sensor sn;
    sn.name = rd.sensor_name(s, i, names, path);
    const std::string type = rd.text(rd.need(s, "type", path), path + ".type");
    auto component = [&](std::initializer_list<const char*> allowed) { return rd.choice(s, "component", path, allowed); };
    if (type == "point_position" || type == "point_displacement" || type == "point_velocity" ||
        type == "point_acceleration") {
      rd.keys(s, path, {"name", "type", "body", "point", "component", "relative_to", "marker"});
      sn.kind = type == "point_position"       ? Sensor::Kind::PointPosition
                : type == "point_velocity"     ? Sensor::Kind::PointVelocity
                : type == "point_acceleration" ? Sensor::Kind::PointAcceleration
                                               : Sensor::Kind::PointDisplacement;
      if (s["marker"]) {
        if (s["body"] || s["point"]) rd.fail(s["marker"], path + ".marker", "give either marker or body/point");
        const std::string mn = rd.text(s["marker"], path + ".marker");
        const auto it = sb.markers.find(mn);
        if (it == sb.markers.end()) rd.fail(s["marker"], path + ".marker", "no marker named '" + mn + "'");
        sn.node = it->second.node;
        sn.local = it->second.position;
      } else {
        sn.node = spatial_node(sb, s, "body", path, false);
        sn.local = rd.vec3(s, "point", path, Eigen::Vector3d::Zero());
      }
      sn.component = component({"x", "y", "z"});
      const Pose<double> p0 = initial_pose(model, sn.node);
      sn.initial = p0.x + p0.R * sn.local;
      if (s["relative_to"]) {
        sn.frame_node = spatial_node(sb, s, "relative_to", path, false);
        if (sn.kind == Sensor::Kind::PointDisplacement) {
          // Displacement seen in the moving frame: position in that frame minus its initial value.
          const Pose<double> f0 = initial_pose(model, sn.frame_node);
          sn.initial = f0.R.transpose() * (sn.initial - f0.x);
        }
      }
    } else if (type == "body_rotation") {
      rd.keys(s, path, {"name", "type", "body", "component"});
      sn.kind = Sensor::Kind::BodyRotation;
      sn.node = spatial_node(sb, s, "body", path, false);
      sn.component = component({"x", "y", "z"});
    } else if (type == "joint_reaction") {
      rd.keys(s, path, {"name", "type", "joint", "component"});
      sn.kind = Sensor::Kind::JointReaction;
      const std::string jn = rd.text(rd.need(s, "joint", path), path + ".joint");
      sn.constraint = model.find_constraint(jn);
      if (sn.constraint < 0) rd.fail(s["joint"], path + ".joint", "no joint named '" + jn + "'");
      sn.component = component({"fx", "fy", "fz", "mx", "my", "mz"});
    } else if (type == "beam_output" || type == "shell_output") {
      // A result field of one element of a beam or shell block (elements name[k], mesh order).
      const bool beam = type == "beam_output";
      const char* block = beam ? "beam" : "shell";
      rd.keys(s, path, {"name", "type", block, "element", "component"});
      sn.kind = Sensor::Kind::ElementOutput;
      const std::string bn = rd.text(rd.need(s, block, path), path + "." + block);
      const int idx = rd.integer(rd.need(s, "element", path), path + ".element", 0);
      const std::string ename = bn + "[" + std::to_string(idx) + "]";
      for (size_t e = 0; e < model.elements().size(); ++e)
        if (model.elements()[e]->name() == ename && !model.elements()[e]->output_names().empty()) sn.element = static_cast<int>(e);
      if (sn.element < 0)
        rd.fail(s["element"], path + ".element", std::string(block) + " '" + bn + "' has no element " + std::to_string(idx) +
                                                     (beam ? " (elements are numbered from 0 along the mesh)"
                                                           : " (elements are numbered from 0 in the mesh group's order)"));
      const auto outs = model.elements()[static_cast<size_t>(sn.element)]->output_names();
      const std::string c = rd.text(rd.need(s, "component", path), path + ".component");
      sn.component = -1;
      std::string l;
      for (size_t k = 0; k < outs.size(); ++k) {
        if (outs[k] == c) sn.component = static_cast<int>(k);
        l += (k ? ", " : "") + outs[k];
      }
      if (sn.component < 0) rd.fail(s["component"], path + ".component", "expected one of " + l);
    } else {
      rd.fail(s["type"], path + ".type",
              "unknown sensor type '" + type +
                  "' for dimension 3 (expected point_position, point_displacement, point_velocity, point_acceleration, "
                  "body_rotation, joint_reaction, beam_output, shell_output)");
    }
    model.add_sensor(sn);
  }
}

}  // namespace alphaflex::scene_detail
