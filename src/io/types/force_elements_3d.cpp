// Spatial force elements in scenes (`dimension: 3`, `forces:`): `spring_damper` and `bushing`
// (elements/spatial_force_elements.hpp). Registered into spatial_types() by register_force_elements_3d.
// Keys and units: docs/input.md; theory: docs/theory/force_elements.md.
#include <Eigen/Eigenvalues>
#include <memory>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/joint_coordinate_force.hpp"
#include "alphaflex/elements/spatial_force_elements.hpp"
#include "alphaflex/joints/joint_coordinate.hpp"
#include "alphaflex/joints/spatial_joints.hpp"
#include "alphaflex/model/model.hpp"
#include "common.hpp"
#include "joint_coordinates.hpp"
#include "sensor_feedback.hpp"

namespace alphaflex::scene_detail {
namespace {

/// One end of a force element: its node (−1: the ground) and its frame in the node's frame (world
/// frame for the ground), and the world pose of that frame at t = 0.
struct End {
  int node = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d world_position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d world_rotation = Eigen::Matrix3d::Identity();
  bool from_marker = false;
};

Pose<double> pose_at_start(const Model& m, int node) {
  if (node < 0) return {Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  return pose_of(m.node(node).q0.data());
}

/// End `i` (1 or 2) of an element: `markerI`, or `bodyI` (ground allowed for end 2) with `pointI`
/// in the body frame (world point for the ground), if `with_point`.
End read_end(const Item& it, int i, bool with_point) {
  const std::string n = std::to_string(i), marker = "marker" + n, body = "body" + n, point = "point" + n;
  End e;
  if (it.keys.has(marker)) {
    if (it.keys.has(body) || (with_point && it.keys.has(point)))
      it.rd.fail(it.keys.node(marker), it.at(marker), "give either " + marker + " or " + body + (with_point ? "/" + point : ""));
    const std::string name = it.keys.text(marker);
    const auto found = it.sb.markers.find(name);
    if (found == it.sb.markers.end()) it.rd.fail(it.keys.node(marker), it.at(marker), "no marker named '" + name + "'");
    e.node = found->second.node;
    e.position = found->second.position;
    e.rotation = found->second.rotation;
    e.from_marker = true;
  } else {
    if (i == 1 && !it.keys.has(body)) it.rd.fail(it.node, it.at(body), "missing (required): " + body + " or " + marker);
    if (it.keys.has(body)) {
      e.node = it.sb.body(it.keys, body, i == 2);
      if (e.node >= 0 && !it.model.node(e.node).spatial())
        it.rd.fail(it.keys.node(body), it.at(body), "expected a spatial body or beam/shell node");
    }
    if (with_point) e.position = it.keys.vec3(point);
  }
  const Pose<double> f = pose_at_start(it.model, e.node);
  e.world_position = f.x + f.R * e.position;
  e.world_rotation = f.R * e.rotation;
  return e;
}

/// The node list of an element between two ends and the markers' slots in it.
std::vector<int> element_nodes(const Item& it, const End& a, const End& b) {
  if (a.node == b.node)
    it.rd.fail(it.node, it.path, "both ends are on " + (a.node < 0 ? std::string("the ground") : "'" + it.model.node(a.node).name + "'") +
                                     ": a force element needs two different bodies (or one body and the ground)");
  std::vector<int> nodes;
  for (const End* e : {&a, &b})
    if (e->node >= 0) nodes.push_back(e->node);
  return nodes;
}

SpatialMarker marker_of(const End& e, int slot) {
  SpatialMarker m;
  m.slot = e.node < 0 ? -1 : slot;
  m.position = e.position;
  m.rotation = e.rotation;
  return m;
}

void read_spring_damper_3d(const Item& it) {
  const Section& k = it.keys;
  const End a = read_end(it, 1, true), b = read_end(it, 2, true);
  const std::vector<int> nodes = element_nodes(it, a, b);
  const double initial = (b.world_position - a.world_position).norm();
  if (!(initial > 1e-12))
    it.rd.fail(it.node, it.path, "the two points coincide at t = 0, so the spring has no direction (a spatial spring acts along the line of its points)");
  const double rest = k.has("rest_length") ? k.number("rest_length") : initial;
  const int laws = int(k.has("stiffness")) + int(k.has("force")) + int(k.has("table"));
  if (laws != 1)
    it.rd.fail(it.node, it.path, laws == 0 ? "give the force law: stiffness (linear), force (an expression of elongation, rate, t) or table"
                                           : "give one force law: stiffness, force or table, not several");
  if (k.has("preload") && !k.has("stiffness"))
    it.rd.fail(k.node("preload"), it.at("preload"), "a preload goes with `stiffness` (write it into the force expression or table otherwise)");
  if (k.has("force") && k.has("damping"))
    it.rd.fail(k.node("damping"), it.at("damping"), "the force expression gives the damping through `rate`; remove `damping`");
  ScalarForceLaw law;
  if (k.has("stiffness")) {
    law = ScalarForceLaw::linear(k.number("stiffness"), k.number("damping", 0.0), rest, k.number("preload", 0.0));
  } else if (k.has("force")) {
    try {
      law = ScalarForceLaw::expression(
          std::make_shared<ExpressionFunction>(k.text("force"), it.rd.scope(), std::vector<std::string>{"elongation", "rate", "t"}),
          rest);
    } catch (const std::invalid_argument& e) {
      it.rd.fail(k.node("force"), it.at("force"), e.what());
    }
  } else {
    const YAML::Node t = k.node("table");
    if (!t.IsSequence() || t.size() < 2)
      it.rd.fail(t, it.at("table"), "expected a list of at least 2 pairs [elongation (m), force (N)]");
    std::vector<double> x, f;
    for (size_t i = 0; i < t.size(); ++i) {
      const Eigen::Vector2d p = it.rd.vec2(t[i], it.at("table[" + std::to_string(i) + "]"));
      if (i > 0 && !(p.x() > x.back()))
        it.rd.fail(t[i], it.at("table[" + std::to_string(i) + "]"), "elongations must increase strictly from one pair to the next");
      x.push_back(p.x());
      f.push_back(p.y());
    }
    law = ScalarForceLaw::table(make_table(x, f), k.number("damping", 0.0), rest);
  }
  it.model.add_element(std::make_unique<SpatialSpringDamper>(it.name, nodes, marker_of(a, 0), marker_of(b, 1), law));
}

/// A 6×6 matrix: 6 numbers (the diagonal) or 6 rows of 6; symmetric and positive semi-definite.
Bushing::Matrix6 read_matrix6(const Item& it, const std::string& key, const char* units) {
  return read_psd_matrix(it, key, 6, units);
}

void read_bushing(const Item& it) {
  const Section& k = it.keys;
  const End a = read_end(it, 1, false), b = read_end(it, 2, false);
  const std::vector<int> nodes = element_nodes(it, a, b);
  // The bushing frame at t = 0: `location` and `orientation` (world), else marker1's frame, else
  // body1's reference point and the world axes.
  const Eigen::Vector3d location = k.has("location") ? k.vec3("location") : a.from_marker ? a.world_position
                                                                                          : pose_at_start(it.model, a.node).x;
  if (a.from_marker && k.has("location"))
    it.rd.fail(k.node("location"), it.at("location"), "marker1 fixes the location; remove one of them");
  Eigen::Matrix3d frame = a.from_marker ? a.world_rotation : Eigen::Matrix3d::Identity();
  if (k.has("orientation")) {
    if (a.from_marker) it.rd.fail(k.node("orientation"), it.at("orientation"), "marker1 fixes the orientation; remove one of them");
    frame = exp_so3<double>(k.vec3("orientation"));
  }
  if (b.from_marker && ((b.world_position - location).norm() > 1e-9 * std::max(1.0, location.norm()) ||
                        (b.world_rotation - frame).norm() > 1e-9))
    it.rd.fail(k.node("marker2"), it.at("marker2"), "must coincide with the bushing frame at t = 0 (a bushing is unloaded at t = 0)");
  // Both markers are the bushing frame at t = 0, each in its node's frame.
  const auto marker = [&](const End& e, int slot) {
    const Pose<double> f = pose_at_start(it.model, e.node);
    SpatialMarker m;
    m.slot = e.node < 0 ? -1 : slot;
    m.position = f.R.transpose() * (location - f.x);
    m.rotation = f.R.transpose() * frame;
    return m;
  };
  it.model.add_element(std::make_unique<Bushing>(it.name, nodes, marker(a, 0), marker(b, 1), read_matrix6(it, "stiffness", "N/m, N·m/rad"),
                                                 read_matrix6(it, "damping", "N·s/m, N·m·s/rad")));
}

}  // namespace

// ---- Joint coordinates: springs, dampers, motors and sensors on a joint's angle or displacement ----

namespace {

/// "unknown coordinate …": what `coordinate` may be on this joint.
[[noreturn]] void bad_coordinate(const Item& it, const std::string& w, const SpatialJointKind& kind) {
  it.rd.fail(it.keys.node("coordinate"), it.at("coordinate"),
             "unknown coordinate '" + w + "' (a " + kind.name + " joint has " +
                 (kind.needs_axis2 ? std::string("1 (the angle about axis) and 2 (the angle about axis2)") : "rotation or translation") + ")");
}

}  // namespace

Coordinate joint_coordinate_kind(const Item& it, const SpatialJoint& joint, const char* wanted) {
  const SpatialJointKind& kind = joint.kind();
  // A universal joint (the one row with two axes: a1 = axis in body 1, b2 = axis2 in body 2) turns
  // about both: coordinates 1 and 2 (joints/joint_coordinate.hpp).
  if (kind.needs_axis2) {
    if (wanted && std::string(wanted) == "translation")
      it.rd.fail(it.keys.node("joint"), it.at("joint"), "'" + joint.name() + "' is a universal joint, which has two rotations (coordinate 1 about axis, 2 about axis2) only");
    if (!it.keys.has("coordinate"))
      it.rd.fail(it.node, it.at("coordinate"), "missing (required for a universal joint): 1 (the angle about axis) or 2 (the angle about axis2)");
    const std::string w = it.keys.text("coordinate");
    if (w != "1" && w != "2") bad_coordinate(it, w, kind);
    return w == "1" ? Coordinate::universal_axis : Coordinate::universal_axis2;
  }
  std::string has;
  if (kind.angle_driver) has = "a rotation about its axis";
  if (kind.displacement_driver) has += std::string(has.empty() ? "" : " and ") + "a translation along its axis";
  if (has.empty())
    it.rd.fail(it.keys.node("joint"), it.at("joint"),
               "'" + joint.name() + "' is a " + kind.name + " joint, which has no single rotation or translation coordinate (joint springs, dampers, stops, motors and joint sensors act on revolute, cylindrical, prismatic and universal joints)");
  const bool both = kind.angle_driver && kind.displacement_driver;
  Coordinate c = kind.angle_driver ? Coordinate::rotation : Coordinate::translation;
  if (it.keys.has("coordinate")) {
    const std::string w = it.keys.text("coordinate");
    if (w != "rotation" && w != "translation") bad_coordinate(it, w, kind);
    c = w == "rotation" ? Coordinate::rotation : Coordinate::translation;
    if ((c == Coordinate::rotation && !kind.angle_driver) || (c == Coordinate::translation && !kind.displacement_driver))
      it.rd.fail(it.keys.node("coordinate"), it.at("coordinate"), "a " + kind.name + " joint has " + has + " only");
    if (wanted && w != wanted) it.rd.fail(it.keys.node("coordinate"), it.at("coordinate"), "this sensor reads a " + std::string(wanted));
  } else if (wanted) {
    c = std::string(wanted) == "rotation" ? Coordinate::rotation : Coordinate::translation;
    if ((c == Coordinate::rotation && !kind.angle_driver) || (c == Coordinate::translation && !kind.displacement_driver))
      it.rd.fail(it.keys.node("joint"), it.at("joint"), "'" + joint.name() + "' is a " + kind.name + " joint, which has " + has + " only");
  } else if (both) {
    it.rd.fail(it.node, it.at("coordinate"), "missing (required for a " + kind.name + " joint): rotation or translation");
  }
  return c;
}

JointCoordinateNode joint_coordinate_node(const Item& it, const char* wanted) {
  const int ci = sensor_joint(it);
  const auto* joint = dynamic_cast<const SpatialJoint*>(it.model.constraints()[static_cast<size_t>(ci)].get());
  if (!joint) it.rd.fail(it.keys.node("joint"), it.at("joint"), "'" + it.keys.text("joint") + "' is not a joint of `joints`");
  const Coordinate c = joint_coordinate_kind(it, *joint, wanted);
  const char* suffix = c == Coordinate::rotation ? ".angle" : c == Coordinate::universal_axis ? ".angle1" : c == Coordinate::universal_axis2 ? ".angle2" : ".displacement";
  const std::string name = joint->name() + suffix;
  if (const int id = it.model.find_node(name); id >= 0) return {id, c};
  Node nd;
  nd.name = name;
  nd.kind = NodeKind::LineParticle2D;
  nd.ndof = nd.nconf = 1;
  nd.line_direction = Eigen::Vector2d::Zero();  // drawn as a fixed point: it is a coordinate, not a place
  // ψ and ψ̇ at t = 0 from the frames (Φ = 0, Φ_q v = 0), so that the start is consistent.
  std::vector<int> nodes = joint->nodes();
  Eigen::VectorXd q(7 * nodes.size() + 1), v(6 * nodes.size() + 1);
  for (size_t k = 0; k < nodes.size(); ++k) {
    q.segment<7>(7 * static_cast<Eigen::Index>(k)) = it.model.node(nodes[k]).q0;
    v.segment<6>(6 * static_cast<Eigen::Index>(k)) = it.model.node(nodes[k]).v0;
  }
  std::vector<int> with_psi = nodes;
  with_psi.push_back(-1);  // the node is not made yet: only the count matters to the probe
  const JointCoordinateLink probe(name, with_psi, joint->marker_a(), joint->marker_b(), c);
  q[q.size() - 1] = probe.frame_value(q.head(q.size() - 1));
  v[v.size() - 1] = 0.0;
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  probe.evaluate(q, 0.0, phi, phi_q);
  nd.q0 = Eigen::VectorXd::Constant(1, q[q.size() - 1]);
  nd.v0 = Eigen::VectorXd::Constant(1, -phi_q.row(0).dot(v) / phi_q(0, phi_q.cols() - 1));
  const int id = it.model.add_node(nd);
  nodes.push_back(id);
  it.model.add_constraint(std::make_unique<JointCoordinateLink>(name, nodes, joint->marker_a(), joint->marker_b(), c));
  return {id, c};
}

namespace {

void read_joint_spring_damper(const Item& it) {
  const Section& k = it.keys;
  const JointCoordinateNode psi = joint_coordinate_node(it);
  const int laws = int(k.has("stiffness")) + int(k.has("force")) + int(k.has("damping") && !k.has("stiffness"));
  if (laws != 1)
    it.rd.fail(it.node, it.path, laws == 0 ? "give the law: stiffness and/or damping (linear), or force (an expression)"
                                           : "give one law: stiffness/damping or force, not both");
  const double rest = k.number("rest", 0.0);
  ScalarForceLaw law;
  if (k.has("force")) {
    try {
      law = ScalarForceLaw::expression(
          std::make_shared<ExpressionFunction>(k.text("force"), it.rd.scope(),
                                               std::vector<std::string>{psi.variable(), "speed", "t"}),
          rest);
    } catch (const std::invalid_argument& e) {
      it.rd.fail(k.node("force"), it.at("force"), e.what());
    }
  } else {
    law = ScalarForceLaw::linear(k.number("stiffness", 0.0), k.number("damping", 0.0), rest, k.number("preload", 0.0));
  }
  it.model.add_element(std::make_unique<JointCoordinateForce>(it.name, psi.node, law, JointCoordinateForce::Role::spring_damper));
}

void read_joint_motor(const Item& it) {
  const JointCoordinateNode psi = joint_coordinate_node(it);
  // `torque` drives a rotation, `force` a translation.
  const char* key = psi.rotation() ? "torque" : "force";
  const char* other = psi.rotation() ? "force" : "torque";
  if (it.keys.has(other))
    it.rd.fail(it.keys.node(other), it.at(other), std::string("this motor drives a ") +
                                                      (psi.rotation() ? "rotation: give `torque`" : "translation: give `force`"));
  if (!it.keys.has(key)) it.rd.fail(it.node, it.at(key), "missing (required): the motor's " + std::string(key) + " (an expression)");
  if (read_feedback_motor(it, psi, key)) return;  // names sensors: types/sensor_feedback_3d.cpp
  try {
    auto f = std::make_shared<ExpressionFunction>(it.keys.text(key), it.rd.scope(), std::vector<std::string>{psi.variable(), "speed", "t"});
    it.model.add_element(std::make_unique<JointCoordinateForce>(it.name, psi.node, ScalarForceLaw::expression(f, 0.0),
                                                                JointCoordinateForce::Role::motor));
  } catch (const std::invalid_argument& e) {
    it.rd.fail(it.keys.node(key), it.at(key), e.what());
  }
}

void read_joint_sensor(const Item& it, Sensor& sn, const char* wanted, bool speed) {
  sn.node = joint_coordinate_node(it, wanted).node;
  sn.kind = speed ? Sensor::Kind::NodeSpeed : Sensor::Kind::NodeCoordinate;
}

/// The force elements a `force_output` sensor can read (their element names are the scene's).
bool is_force_element(const Element& e) {
  const std::string type = e.type();
  return type == "spring_damper" || type == "bushing" || type == "joint_spring_damper" || type == "joint_motor" || type == "joint_stop";
}

void read_force_output(const Item& it, Sensor& sn) {
  const std::string name = it.keys.text("element");
  const auto& elements = it.model.elements();
  std::string known;
  for (size_t e = 0; e < elements.size(); ++e) {
    if (!is_force_element(*elements[e])) continue;
    if (elements[e]->name() == name) sn.element = static_cast<int>(e);
    known += (known.empty() ? "" : ", ") + elements[e]->name();
  }
  if (sn.element < 0 && (sn.element = pending_motor_element(it, name)) >= 0) {
    // A motor that reads sensors: its element is made once the sensors are read (sensor_feedback.hpp).
    sn.kind = Sensor::Kind::ElementOutput;
    sn.component = it.rd.choice(it.keys.node("component"), it.at("component"), {"coordinate", "speed", "drive"});
    return;
  }
  if (sn.element < 0)
    it.rd.fail(it.keys.node("element"), it.at("element"), "no force element named '" + name + "' in `forces` (its force elements: " +
                                                            (known.empty() ? "none" : known) + ")");
  sn.kind = Sensor::Kind::ElementOutput;
  sn.component = it.rd.choice(it.keys.node("component"), it.at("component"), elements[static_cast<size_t>(sn.element)]->output_names());
}

void read_energy(const Item& it, Sensor& sn) {
  if (it.keys.has("of") == it.keys.has("element"))
    it.rd.fail(it.node, it.path, "give either `element` (one element) or `of` (a block, a body, a force element or `model`)");
  if (it.keys.has("of")) return read_energy_of(it, sn, it.keys.choice("kind"));
  const std::string name = it.keys.text("element");
  const auto& elements = it.model.elements();
  for (size_t e = 0; e < elements.size(); ++e)
    if (elements[e]->name() == name) sn.element = static_cast<int>(e);
  // A body welded into a reduced body has no element of its own: its energy is the reduced body's.
  if (const auto w = it.sb.welded_bodies.find(name); w != it.sb.welded_bodies.end())
    it.rd.fail(it.keys.node("element"), it.at("element"), "'" + name + "' is welded into the reduced block '" + w->second +
                                                   "': its kinetic and potential energy are part of that body's (element: " + w->second + ")");
  if (sn.element < 0)
    it.rd.fail(it.keys.node("element"), it.at("element"), "no element named '" + name +
                                                            "' (a rigid body's name, a force element's, or BLOCK[k] for element k of a beam or shell block)");
  sn.kind = Sensor::Kind::ElementEnergy;
  sn.component = it.keys.choice("kind");
  if (sn.component > 1) sn.node2 = sn.element + 1;  // potential, total: the sum over this one element (model/sensor.cpp)
}

void read_constraint_violation(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::JointViolation;
  sn.constraint = sensor_joint(it);
}

}  // namespace

Key joint_coordinate_joint_key() {
  return {"joint", KeyType::Text, "–", kRequired, "a revolute, cylindrical, prismatic or universal joint of `joints`"};
}
Key joint_coordinate_key() {
  return {"coordinate", KeyType::Text, "–", "the joint's only one",
          "`rotation` or `translation` (required on a cylindrical joint); `1` (the angle about axis) or `2` (about axis2) on a universal joint (required)"};
}

void register_force_elements_3d(SceneTypes& t) {
  const auto ends = [](const char* what) -> std::vector<Key> {
    return {{"body1", KeyType::Text, "–", "– (or `marker1`)", "the first body or beam/shell node; not `ground`"},
            {"marker1", KeyType::Text, "–", "–", std::string("a marker of a body instead of body1") + what},
            {"body2", KeyType::Text, "–", "`ground`", "the second body, node or `ground`; different from body1"},
            {"marker2", KeyType::Text, "–", "–", std::string("a marker of a body instead of body2") + what}};
  };
  std::vector<Key> spring = ends(" and its point");
  spring.insert(spring.end(), {
      {"point1", KeyType::Vec3, "m", "[0, 0, 0]", "point of body1, body frame"},
      {"point2", KeyType::Vec3, "m", "[0, 0, 0]", "point of body2, body frame (a world point for the ground)"},
      {"stiffness", KeyType::Number, "N/m", "–", "linear law: tension k (L − L0) + c L̇ + preload", Range::non_negative()},
      {"damping", KeyType::Number, "N·s/m", "0", "c, with `stiffness` or `table`", Range::non_negative()},
      {"rest_length", KeyType::Number, "m", "the length at t = 0", "L0", Range::non_negative()},
      {"preload", KeyType::Number, "N", "0", "tension at L = L0, with `stiffness`"},
      {"force", KeyType::Text, "N", "–", "tension as an expression of `elongation` L − L0 (m), `rate` L̇ (m/s) and `t` (s), and `parameters`"},
      {"table", KeyType::List, "m, N", "–", "tension F(L − L0) through the pairs, linear between them, constant beyond; plus c L̇",
       {}, "", "[[elongation, force], ...]"}});
  t.loads.add("spring_damper", type_schema("forces.3d.spring_damper",
      "`spring_damper` between two points: tension along the line of the points, one law of stiffness, force or table", spring),
      read_spring_damper_3d);
  std::vector<Key> bushing = ends(" (marker2: at the bushing frame at t = 0)");
  bushing.insert(bushing.end(), {
      {"location", KeyType::Vec3, "m", "marker1's origin, else body1's reference point", "origin of the bushing frame at t = 0 (world)"},
      {"orientation", KeyType::Vec3, "rad", "marker1's axes, else the world axes", "bushing frame at t = 0: rotation vector [rx, ry, rz] (world)"},
      {"stiffness", KeyType::List, "N/m, N·m/rad", kRequired, "K on (u, γ) in the bushing frame of body1: 6 numbers (diagonal) or 6 rows of 6; symmetric, positive semi-definite",
       {}, "", "6 numbers or 6×6 rows"},
      {"damping", KeyType::List, "N·s/m, N·m·s/rad", "0", "C on (u̇, γ̇), as stiffness", {}, "", "6 numbers or 6×6 rows"}});
  t.loads.add("bushing", type_schema("forces.3d.bushing",
      "`bushing`: 6×6 stiffness and damping between two frames that coincide at t = 0 (a rubber mount, a compliant joint)", bushing),
      read_bushing);
  const Key joint = joint_coordinate_joint_key();
  const Key coordinate = joint_coordinate_key();
  t.loads.add("joint_spring_damper", type_schema("forces.3d.joint_spring_damper",
      "`joint_spring_damper` on a joint's unwrapped angle (rotational) or displacement (translational)", {
      joint, coordinate,
      {"stiffness", KeyType::Number, "N·m/rad or N/m", "0", "k: torque or force −k (ψ − rest) − c ψ̇ − preload on the coordinate ψ", Range::non_negative()},
      {"damping", KeyType::Number, "N·m·s/rad or N·s/m", "0", "c", Range::non_negative()},
      {"rest", KeyType::Number, "rad or m", "0", "ψ at which the spring is unloaded (the joint's coordinate is 0 at t = 0)"},
      {"preload", KeyType::Number, "N·m or N", "0", "the spring's resisting torque or force at ψ = rest"},
      {"force", KeyType::Text, "N·m or N", "–", "instead of stiffness/damping: the resisting torque or force as an expression of `angle` (rad) or `displacement` (m) minus rest, `speed` and `t`"}}),
      read_joint_spring_damper);
  t.loads.add("joint_motor", type_schema("forces.3d.joint_motor",
      "`joint_motor`: a torque or force driving a joint's coordinate, a function of time, coordinate and speed", {
      joint, coordinate,
      {"torque", KeyType::Text, "N·m", "– (rotation: required)",
       "torque in the sense of the angle: an expression of `t` (s), `angle` (rad), `speed` (rad/s), `parameters` and sensors by name (feedback), e.g. `T_stall*(1 - speed/w0)`"},
      {"force", KeyType::Text, "N", "– (translation: required)", "force in the sense of the displacement: an expression of `t`, `displacement` (m), `speed` (m/s), `parameters` and sensors"}}),
      read_joint_motor);
  const std::tuple<const char*, const char*, bool, const char*> joint_sensors[] = {
      {"joint_angle", "rotation", false, "`joint_angle`: relative angle of a revolute, cylindrical or universal joint (body 1 relative to body 2), unwrapped over any number of turns (rad)"},
      {"joint_displacement", "translation", false, "`joint_displacement`: relative displacement of a prismatic or cylindrical joint along its axis (m)"},
      {"joint_speed", nullptr, true, "`joint_speed`: rate of a joint's angle (rad/s) or displacement (m/s)"}};
  for (const auto& [name, wanted, speed, doc] : joint_sensors) {
    std::vector<Key> keys{joint};
    if (!wanted || std::string(wanted) == "rotation") keys.push_back(coordinate);  // joint_angle: 1 or 2 on a universal joint
    t.sensors.add(name, type_schema(std::string("sensors.3d.") + name, doc, keys),
                  [wanted = wanted, speed = speed](const Item& it, Sensor& sn) { read_joint_sensor(it, sn, wanted, speed); });
  }
  t.sensors.add("energy", type_schema("sensors.3d.energy", "`energy` of one element or a sum over a block, a body or the model (J)", {
      {"element", KeyType::Text, "–", "– (this or `of`)", "a rigid body, a force element, or BLOCK[k] (element k of a beam or shell block)"},
      energy_of_key(),
      energy_kind()}), read_energy);
  t.sensors.add("constraint_violation", type_schema("sensors.3d.constraint_violation",
      "`constraint_violation`: |Φ| of a joint's equations (m, and 1 for the products of axes)", {
      {"joint", KeyType::Text, "–", kRequired, "a joint of `joints` (or JOINT.angle, JOINT.displacement: a joint coordinate's link)"}}),
      read_constraint_violation);
  t.sensors.add("force_output", type_schema("sensors.3d.force_output", "`force_output`: a result of a force element of `forces`", {
      {"element", KeyType::Text, "–", kRequired, "the name of a `spring_damper`, `bushing`, `joint_spring_damper`, `joint_motor` or `joint_stop`"},
      {"component", KeyType::Text, "–", kRequired,
       "spring_damper: `length` (m), `elongation` (m), `rate` (m/s), `tension` (N); bushing: `deflection[0..5]` (u in m, γ in rad), `force[0..5]` (K ε + C ε̇: N, N·m); joint_spring_damper, joint_motor: `coordinate`, `speed`, `force` or `drive` (N·m or N on the coordinate); joint_stop: `coordinate`, `speed`, `penetration`, `force`"}}),
      read_force_output);
}

}  // namespace alphaflex::scene_detail
