// Planar force elements on coordinates of two bodies (elements/planar_coordinate_force.hpp): a
// `bushing` (3×3 stiffness and damping between two frames that coincide at t = 0), and a
// `joint_spring_damper` or `joint_motor` on the relative angle of a planar revolute joint or the
// displacement along a planar prismatic joint (ε − ε0: 0 at t = 0; the angle is a difference of the
// bodies' θ, so it counts turns without an extra unknown).
#include "alphaflex/elements/planar_coordinate_force.hpp"
#include "alphaflex/model/model.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

using Geometry = PlanarCoordinateForce::Geometry;

/// A side of the element: a planar rigid body (x, y, θ), or the ground (−1).
int rigid_side(const Item& it, const std::string& key, bool ground_ok) {
  const int id = it.sb.body(it.keys, key, ground_ok);
  if (id >= 0 && it.model.node(id).kind != NodeKind::RigidBody2D)
    it.rd.fail(it.keys.node(key), it.at(key), "'" + it.model.node(id).name + "' is not a rigid body (a bushing turns with its bodies: it needs their angle)");
  return id;
}

Eigen::Vector3d pose0(const Model& m, int id) { return id < 0 ? Eigen::Vector3d::Zero() : Eigen::Vector3d(m.node(id).q0.head<3>()); }

void read_bushing_2d(const Item& it) {
  const Section& k = it.keys;
  const int a = rigid_side(it, "body1", false);
  const int b = k.has("body2") ? rigid_side(it, "body2", true) : -1;
  if (a == b) it.rd.fail(k.node("body2"), it.at("body2"), "a bushing needs two different bodies (or one body and ground)");
  const Eigen::Vector3d pa = pose0(it.model, a), pb = pose0(it.model, b);
  const Eigen::Vector2d location = k.has("location") ? k.vec2("location") : Eigen::Vector2d(pa.head<2>());
  Geometry g;
  g.coordinates = PlanarCoordinateForce::Coordinates::bushing;
  g.body_a = true;
  g.body_b = b >= 0;
  // Both markers at `location` at t = 0, in their bodies' frames (a world point on the ground).
  g.point_a = rotate(-pa[2], location - pa.head<2>());
  g.point_b = rotate(-pb[2], location - pb.head<2>());
  g.alpha = k.number("angle", 0.0) - pa[2];
  g.gamma0 = pb[2] - pa[2];
  it.model.add_element(std::make_unique<PlanarCoordinateForce>(it.name, node_list(a, b), g, read_psd_matrix(it, "stiffness", 3, "N/m, N·m/rad"),
                                                               read_psd_matrix(it, "damping", 3, "N·s/m, N·m·s/rad")));
}

/// The coordinate of the planar revolute or prismatic joint named by `joint` and the element's
/// geometry (A = the joint's body 1, B = its body 2), found from the joint's Jacobian at t = 0:
/// Φ = r1 − r2 (revolute), [n·(r1 − r2); θ1 − θ2 − θ0] (prismatic), whose signs tell body 1 from
/// body 2 and whose first row gives the line's normal n.
struct PlanarJointCoordinate {
  Geometry geometry;
  std::vector<int> nodes;
  double eps0 = 0.0;
  const char* variable = "angle";
};
PlanarJointCoordinate planar_joint_coordinate(const Item& it) {
  const int ci = sensor_joint(it);
  const Constraint& c = *it.model.constraints()[static_cast<size_t>(ci)];
  const std::string type = c.type();
  const bool rotation = type == "revolute";
  if (!rotation && type != "prismatic")
    it.rd.fail(it.keys.node("joint"), it.at("joint"), "'" + c.name() + "' is a " + type + " joint; planar joint springs, dampers and motors act on revolute (angle) and prismatic (displacement) joints");
  const std::vector<int>& nodes = c.nodes();
  Eigen::VectorXd q;
  std::vector<int> offset;
  for (int n : nodes) {
    offset.push_back(static_cast<int>(q.size()));
    const Eigen::VectorXd& q0 = it.model.node(n).q0;
    q.conservativeResize(q.size() + q0.size());
    q.tail(q0.size()) = q0;
    if (it.model.node(n).kind != NodeKind::RigidBody2D)
      it.rd.fail(it.keys.node("joint"), it.at("joint"), "joint '" + c.name() + "' holds '" + it.model.node(n).name +
                                                           "', which is not a rigid body: it has no angle for a joint spring or motor");
  }
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  c.evaluate(q, 0.0, phi, phi_q);
  PlanarJointCoordinate out;
  int body1 = -1, body2 = -1;
  Eigen::Vector2d normal = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < nodes.size(); ++k) {
    const int o = offset[k];
    const double sign = rotation ? phi_q(0, o) : phi_q(1, o + 2);  // +1 on body 1, −1 on body 2
    (sign > 0 ? body1 : body2) = nodes[k];
    if (!rotation) normal = sign * Eigen::Vector2d(phi_q(0, o), phi_q(0, o + 1));
  }
  Geometry& g = out.geometry;
  g.body_a = body1 >= 0;
  g.body_b = body2 >= 0;
  out.nodes = node_list(body1, body2);
  const Eigen::Vector3d p1 = pose0(it.model, body1), p2 = pose0(it.model, body2);
  if (rotation) {
    g.coordinates = PlanarCoordinateForce::Coordinates::rotation;
    out.eps0 = p1[2] - p2[2];
  } else {
    g.coordinates = PlanarCoordinateForce::Coordinates::translation;
    g.axis_b = rotate(-p2[2], Eigen::Vector2d(-perp(normal)));  // n = R(θ2) perp(axis)
    out.eps0 = rotate(p2[2], g.axis_b).dot(p1.head<2>() - p2.head<2>());
    out.variable = "displacement";
  }
  return out;
}

void add_joint_force(const Item& it, const PlanarJointCoordinate& jc, const ScalarForceLaw& law, bool motor) {
  it.model.add_element(std::make_unique<PlanarCoordinateForce>(it.name, jc.nodes, jc.geometry, law, motor, jc.eps0));
}

ScalarForceLaw expression_law(const Item& it, const char* key, const char* variable, double rest) {
  try {
    return ScalarForceLaw::expression(
        std::make_shared<ExpressionFunction>(it.keys.text(key), it.rd.scope(), std::vector<std::string>{variable, "speed", "t"}), rest);
  } catch (const std::invalid_argument& e) {
    it.rd.fail(it.keys.node(key), it.at(key), e.what());
  }
}

void read_joint_spring_damper_2d(const Item& it) {
  const Section& k = it.keys;
  const PlanarJointCoordinate jc = planar_joint_coordinate(it);
  const int laws = int(k.has("stiffness")) + int(k.has("force")) + int(k.has("damping") && !k.has("stiffness"));
  if (laws != 1)
    it.rd.fail(it.node, it.path, laws == 0 ? "give the law: stiffness and/or damping (linear), or force (an expression)"
                                           : "give one law: stiffness/damping or force, not both");
  const double rest = k.number("rest", 0.0);
  add_joint_force(it, jc,
                  k.has("force") ? expression_law(it, "force", jc.variable, rest)
                                 : ScalarForceLaw::linear(k.number("stiffness", 0.0), k.number("damping", 0.0), rest, k.number("preload", 0.0)),
                  false);
}

void read_joint_motor_2d(const Item& it) {
  const PlanarJointCoordinate jc = planar_joint_coordinate(it);
  const bool rotation = jc.geometry.coordinates == PlanarCoordinateForce::Coordinates::rotation;
  const char* key = rotation ? "torque" : "force";
  const char* other = rotation ? "force" : "torque";
  if (it.keys.has(other))
    it.rd.fail(it.keys.node(other), it.at(other), std::string("this motor drives a ") + (rotation ? "rotation: give `torque`" : "translation: give `force`"));
  if (!it.keys.has(key)) it.rd.fail(it.node, it.at(key), "missing (required): the motor's " + std::string(key) + " (an expression)");
  add_joint_force(it, jc, expression_law(it, key, jc.variable, 0.0), true);
}

/// `force_output` (planar): a result of a bushing, joint spring-damper or joint motor.
void read_force_output_2d(const Item& it, Sensor& sn) {
  const std::string name = it.keys.text("element");
  const auto& elements = it.model.elements();
  std::string known;
  for (size_t e = 0; e < elements.size(); ++e) {
    if (!dynamic_cast<const PlanarCoordinateForce*>(elements[e].get())) continue;
    if (elements[e]->name() == name) sn.element = static_cast<int>(e);
    known += (known.empty() ? "" : ", ") + elements[e]->name();
  }
  if (sn.element < 0)
    it.rd.fail(it.keys.node("element"), it.at("element"), "no bushing, joint spring-damper or joint motor named '" + name + "' in `forces` (they are: " +
                                                            (known.empty() ? "none" : known) + ")");
  sn.kind = Sensor::Kind::ElementOutput;
  sn.component = it.rd.choice(it.keys.node("component"), it.at("component"), elements[static_cast<size_t>(sn.element)]->output_names());
}

const Key kJoint{"joint", KeyType::Text, "–", kRequired, "a planar revolute (angle θ1 − θ2) or prismatic (displacement along its axis) joint of `joints`"};

}  // namespace

void register_force_elements_2d(SceneTypes& t) {
  t.loads.add("bushing", type_schema("forces.2d.bushing", "`bushing`: 3×3 stiffness and damping between two frames that coincide at t = 0", {
      {"body1", KeyType::Text, "–", kRequired, "a rigid body; not `ground`"},
      {"body2", KeyType::Text, "–", "`ground`", "a rigid body or `ground`; different from body1"},
      {"location", KeyType::Vec2, "m", "body1's centre of mass", "origin of the bushing frame at t = 0 (world); both bodies' markers are there"},
      {"angle", KeyType::Number, "rad", "0", "the bushing frame's angle at t = 0 (world); the frame turns with body1"},
      {"stiffness", KeyType::List, "N/m, N·m/rad", "zero", "K of ε = (u_x, u_y in the frame, relative rotation γ): 3 numbers (the diagonal) or 3 rows of 3; symmetric positive semi-definite"},
      {"damping", KeyType::List, "N·s/m, N·m·s/rad", "zero", "C of ε̇, same form"}}),
              read_bushing_2d);
  t.loads.add("joint_spring_damper", type_schema("forces.2d.joint_spring_damper",
      "`joint_spring_damper` on a planar revolute joint's angle or a prismatic joint's displacement", {
      kJoint,
      {"stiffness", KeyType::Number, "N·m/rad or N/m", "0", "k: torque or force −k (ψ − rest) − c ψ̇ − preload on the coordinate ψ (0 at t = 0)", Range::non_negative(), "stiffness"},
      {"damping", KeyType::Number, "N·m·s/rad or N·s/m", "0", "c", Range::non_negative(), "damping"},
      {"rest", KeyType::Number, "rad or m", "0", "ψ at which the spring is unloaded"},
      {"preload", KeyType::Number, "N·m or N", "0", "the spring's resisting torque or force at ψ = rest"},
      {"force", KeyType::Text, "N·m or N", "–", "instead of stiffness/damping: the resisting torque or force, an expression of `angle` (or `displacement`) − rest, `speed`, `t`"}}),
              read_joint_spring_damper_2d);
  t.loads.add("joint_motor", type_schema("forces.2d.joint_motor", "`joint_motor` driving a planar revolute or prismatic joint", {
      kJoint,
      {"torque", KeyType::Text, "N·m", "– (revolute)", "driving torque, an expression of `t`, `angle` (ψ, 0 at t = 0), `speed`; e.g. `T_s*(1 - speed/w0)`"},
      {"force", KeyType::Text, "N", "– (prismatic)", "driving force, an expression of `t`, `displacement`, `speed`"}}),
              read_joint_motor_2d);
  t.sensors.add("force_output", type_schema("sensors.2d.force_output", "`force_output`: a result of a planar bushing, joint spring-damper or joint motor", {
      {"element", KeyType::Text, "–", kRequired, "the name of a `bushing`, `joint_spring_damper` or `joint_motor`"},
      {"component", KeyType::Text, "–", kRequired,
       "bushing: `deflection[0..2]` (u_x, u_y in m, γ in rad), `force[0..2]` (K ε + C ε̇: N, N·m); joint_spring_damper, joint_motor: `coordinate` (0 at t = 0), `speed`, `force` or `drive` (N·m or N on the coordinate)"}}),
                read_force_output_2d);
}

}  // namespace alphaflex::scene_detail
