#include "alphaflex/io/scene.hpp"

#include "scene_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/time_function.hpp"
#include "alphaflex/elements/applied_load_2d.hpp"
#include "alphaflex/elements/rigid_body_2d.hpp"
#include "alphaflex/elements/spring_damper_2d.hpp"
#include "alphaflex/joints/planar_joints.hpp"

namespace alphaflex {
namespace {

using scene_detail::MeshLoader;
using scene_detail::Reader;
using scene_detail::SceneBuilder;
using scene_detail::BodyRef;

void read_solver(Reader& rd, const YAML::Node& s, RunSettings& rs, std::vector<std::string>& warnings) {
  if (!s) return;
  rd.keys(s, "solver", {"analysis", "scheme", "rho_inf", "alpha_m", "alpha_f", "beta", "gamma", "h", "t_end", "scaling",
                        "consistent_start", "newton", "static", "initial_static", "step_cuts"});
  if (s["analysis"]) {
    const std::string a = rd.text(s["analysis"], "solver.analysis");
    if (a == "static") rs.analysis = Analysis::Static;
    else if (a != "dynamic") rd.fail(s["analysis"], "solver.analysis", "expected dynamic or static, got '" + a + "'");
  }
  if (s["initial_static"]) rs.initial_static = rd.flag(s["initial_static"], "solver.initial_static");
  if (s["step_cuts"]) rs.step_cuts = rd.integer(s["step_cuts"], "solver.step_cuts", 0, 30);
  if (const YAML::Node st = s["static"]) {
    rd.keys(st, "solver.static", {"steps", "max_cuts"});
    if (st["steps"]) rs.statics.steps = rd.integer(st["steps"], "solver.static.steps", 1, 1000000);
    if (st["max_cuts"]) rs.statics.max_cuts = rd.integer(st["max_cuts"], "solver.static.max_cuts", 0, 50);
  }
  const std::string scheme = s["scheme"] ? rd.text(s["scheme"], "solver.scheme") : "generalized-alpha";
  const bool explicit_any = s["alpha_m"] || s["alpha_f"] || s["beta"] || s["gamma"];
  double rho = scheme == "hht" ? 0.9 : 0.7;
  if (s["rho_inf"]) {
    rho = rd.number(s["rho_inf"], "solver.rho_inf");
    const double lo = scheme == "hht" ? 0.5 : 0.0;
    if (!(rho >= lo && rho <= 1.0))
      rd.fail(s["rho_inf"], "solver.rho_inf",
              "expected a spectral radius in [" + std::string(scheme == "hht" ? "0.5" : "0") + ", 1]" +
                  (scheme == "hht" ? " for HHT (α = (1 − ρ∞)/(1 + ρ∞) ∈ [0, 1/3])" : "") + ", got " + s["rho_inf"].Scalar());
  }
  if (scheme == "generalized-alpha") {
    if (explicit_any) {
      if (s["rho_inf"]) rd.fail(s["rho_inf"], "solver.rho_inf", "give either rho_inf or alpha_m/alpha_f/beta/gamma, not both");
      for (const char* k : {"alpha_m", "alpha_f", "beta", "gamma"})
        if (!s[k]) rd.fail(s, std::string("solver.") + k, "missing: explicit parameters need all of alpha_m, alpha_f, beta, gamma");
      rs.parameters = AlphaParameters::explicit_values(rd.number(s["alpha_m"], "solver.alpha_m"),
                                                       rd.number(s["alpha_f"], "solver.alpha_f"),
                                                       rd.number(s["beta"], "solver.beta"),
                                                       rd.number(s["gamma"], "solver.gamma"));
    } else {
      rs.parameters = AlphaParameters::from_rho_inf(rho);
    }
  } else if (scheme == "hht") {
    if (explicit_any) rd.fail(s, "solver", "scheme hht takes rho_inf only (alpha_m, alpha_f, beta, gamma follow from it)");
    rs.parameters = AlphaParameters::hht(rho);
  } else if (scheme == "newmark") {
    if (s["alpha_m"] || s["alpha_f"])
      rd.fail(s, "solver", "scheme newmark has alpha_m = alpha_f = 0: give rho_inf, or beta and gamma");
    if (s["rho_inf"] && (s["beta"] || s["gamma"]))
      rd.fail(s["rho_inf"], "solver.rho_inf", "give either rho_inf or beta/gamma for scheme newmark, not both");
    if (s["rho_inf"])  // damped Newmark with spectral radius ρ∞: γ = (3 − ρ∞)/(2(1 + ρ∞)), β = 1/(1 + ρ∞)²
      rs.parameters = AlphaParameters::newmark(1.0 / ((1.0 + rho) * (1.0 + rho)), (3.0 - rho) / (2.0 * (1.0 + rho)));
    else
      rs.parameters = AlphaParameters::newmark(rd.number(s, "beta", "solver", 0.25), rd.number(s, "gamma", "solver", 0.5));
  } else {
    rd.fail(s["scheme"], "solver.scheme", "unknown scheme '" + scheme + "' (expected generalized-alpha, hht, newmark)");
  }
  try {
    rs.parameters.validate();
  } catch (const InputError& e) {
    rd.fail(s, "solver", e.what());
  }
  warnings = rs.parameters.warnings();
  if (s["h"]) rs.h = rd.positive(s["h"], "solver.h", "step size (s)");
  if (s["t_end"]) rs.t_end = rd.positive(s["t_end"], "solver.t_end", "final time (s)");
  if (rs.h > rs.t_end) rd.fail(s["h"] ? s["h"] : s, "solver.h", "the step size exceeds solver.t_end");
  if (rs.t_end / rs.h > 1e10)
    rd.fail(s["h"] ? s["h"] : s, "solver.h", "t_end/h exceeds 1e10 steps; choose a larger step size");
  if (s["scaling"]) rs.integrator.scaling = rd.flag(s["scaling"], "solver.scaling");
  if (s["consistent_start"]) rs.integrator.consistent_start = rd.flag(s["consistent_start"], "solver.consistent_start");
  if (const YAML::Node n = s["newton"]) {
    rd.keys(n, "solver.newton", {"max_iter", "rtol", "atol", "atol_lambda", "modified", "max_contraction"});
    NewtonOptions& o = rs.integrator.newton;
    if (n["max_iter"]) o.max_iterations = rd.integer(n["max_iter"], "solver.newton.max_iter", 1);
    if (n["rtol"]) o.rtol = rd.positive(n["rtol"], "solver.newton.rtol", "tolerance");
    if (n["atol"]) o.atol = rd.non_negative(n["atol"], "solver.newton.atol", "tolerance (m, rad)");
    if (n["atol_lambda"]) o.atol_lambda = rd.non_negative(n["atol_lambda"], "solver.newton.atol_lambda", "tolerance (N)");
    if (n["modified"]) o.modified = rd.flag(n["modified"], "solver.newton.modified");
    if (n["max_contraction"]) {
      o.max_contraction = rd.positive(n["max_contraction"], "solver.newton.max_contraction", "contraction rate");
      if (o.max_contraction >= 1.0)
        rd.fail(n["max_contraction"], "solver.newton.max_contraction", "a contraction rate in (0, 1)");
    }
  }
  rs.statics.newton = rs.integrator.newton;
}

void read_bodies(Reader& rd, const YAML::Node& list, Model& model, const Eigen::Vector2d& gravity) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "bodies", "expected a list of bodies");
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node b = list[i];
    std::string path;
    const std::string name = rd.item_name(b, "bodies", i, "expected a map with name, type, ...", path);
    if (name == "ground") rd.fail(b["name"], path + ".name", "'ground' is reserved for the fixed frame");
    if (model.find_node(name) >= 0) rd.fail(b["name"], path + ".name", "a body named '" + name + "' exists already");
    const std::string type = rd.text(rd.need(b, "type", path), path + ".type");
    Node nd;
    nd.name = name;
    if (type == "rigid_body") {
      rd.keys(b, path, {"name", "type", "mass", "inertia", "position", "angle", "velocity", "angular_velocity"});
      const double m = rd.positive(rd.need(b, "mass", path), path + ".mass", "mass (kg); a zero mass makes the mass matrix singular");
      const double J = rd.positive(rd.need(b, "inertia", path), path + ".inertia",
                                   "moment of inertia about the centre of mass (kg m^2); zero makes the mass matrix singular");
      nd.kind = NodeKind::RigidBody2D;
      const Eigen::Vector2d p = rd.vec2(rd.need(b, "position", path), path + ".position");
      const Eigen::Vector2d v = rd.vec2(b, "velocity", path, Eigen::Vector2d::Zero());
      nd.q0 = Eigen::Vector3d(p.x(), p.y(), rd.number(b, "angle", path, 0.0));
      nd.v0 = Eigen::Vector3d(v.x(), v.y(), rd.number(b, "angular_velocity", path, 0.0));
      const int id = model.add_node(nd);
      model.add_element(std::make_unique<RigidBody2D>(name, id, m, J, gravity));
    } else if (type == "particle") {
      rd.keys(b, path, {"name", "type", "mass", "position", "velocity"});
      const double m = b["mass"] ? rd.non_negative(b["mass"], path + ".mass", "mass (kg)") : 0.0;
      nd.kind = NodeKind::Particle2D;
      nd.q0 = rd.vec2(rd.need(b, "position", path), path + ".position");
      nd.v0 = rd.vec2(b, "velocity", path, Eigen::Vector2d::Zero());
      const int id = model.add_node(nd);
      if (m > 0.0) model.add_element(std::make_unique<PointMass>(name, id, model.node(id), m, gravity));
    } else if (type == "line_particle") {
      rd.keys(b, path, {"name", "type", "mass", "origin", "direction", "position", "velocity"});
      const double m = b["mass"] ? rd.non_negative(b["mass"], path + ".mass", "mass (kg)") : 0.0;
      nd.kind = NodeKind::LineParticle2D;
      nd.line_origin = rd.vec2(b, "origin", path, Eigen::Vector2d::Zero());
      const Eigen::Vector2d d = rd.vec2(rd.need(b, "direction", path), path + ".direction");
      if (d.norm() == 0.0) rd.fail(b["direction"], path + ".direction", "expected a non-zero direction");
      nd.line_direction = d.normalized();
      const Eigen::Vector2d p = rd.vec2(rd.need(b, "position", path), path + ".position");
      const Eigen::Vector2d rel = p - nd.line_origin;
      const double s = rel.dot(nd.line_direction);
      if ((rel - s * nd.line_direction).norm() > 1e-9 * std::max(1.0, rel.norm()))
        rd.fail(b["position"], path + ".position", "the point is not on the line through `origin` along `direction`");
      nd.q0 = Eigen::VectorXd::Constant(1, s);
      nd.v0 = Eigen::VectorXd::Constant(1, b["velocity"] ? rd.number(b["velocity"], path + ".velocity") : 0.0);
      const int id = model.add_node(nd);
      if (m > 0.0) model.add_element(std::make_unique<PointMass>(name, id, model.node(id), m, gravity));
    } else {
      rd.fail(b["type"], path + ".type", "unknown body type '" + type + "' (expected rigid_body, particle, line_particle)");
    }
  }
}

std::vector<int> node_list(int a, int b) {
  std::vector<int> v;
  if (a >= 0) v.push_back(a);
  if (b >= 0) v.push_back(b);
  return v;
}

void read_joints(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "joints", "expected a list of joints");
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node j = list[i];
    std::string path;
    const std::string name = rd.item_name(j, "joints", i, "expected a map with name, type, ...", path);
    if (model.find_constraint(name) >= 0) rd.fail(j["name"], path + ".name", "a joint named '" + name + "' exists already");
    const std::string type = rd.text(rd.need(j, "type", path), path + ".type");

    if (type == "fixed_point") {
      rd.keys(j, path, {"name", "type", "body", "point", "location"});
      const int b1 = sb.body(j, "body", path, false);
      const Eigen::Vector2d s1 = rd.vec2(j, "point", path, Eigen::Vector2d::Zero());
      const Eigen::Vector2d loc = j["location"] ? rd.vec2(j["location"], path + ".location") : sb.initial_position(b1, s1);
      const auto nodes = node_list(b1, -1);
      model.add_constraint(std::make_unique<RevoluteJoint2D>(name, nodes, sb.marker(b1, s1, nodes, j, path + ".point"),
                                                             PlanarMarker::ground(loc)));
      continue;
    }
    if (type == "fixed") {
      rd.keys(j, path, {"name", "type", "body1", "point1", "body2", "point2", "location"});
      const int b1 = sb.body(j, "body1", path, false);
      const int b2 = j["body2"] ? sb.body(j, "body2", path, true) : -1;
      if (b1 == b2) rd.fail(j["body2"], path + ".body2", "a joint needs two different bodies");
      for (int b : {b1, b2})
        if (b >= 0 && !model.node(b).has_angle())
          rd.fail(j, path, "a fixed joint locks the rotation: '" + model.node(b).name + "' must be a rigid_body or beam node");
      Eigen::Vector2d s1, s2;
      if (j["location"]) {
        if (j["point1"] || j["point2"]) rd.fail(j["location"], path + ".location", "give either location or point1/point2");
        const Eigen::Vector2d loc = rd.vec2(j["location"], path + ".location");
        s1 = sb.to_local(b1, loc);
        s2 = sb.to_local(b2, loc);
      } else {
        s1 = rd.vec2(j, "point1", path, Eigen::Vector2d::Zero());
        s2 = j["point2"] ? rd.vec2(j["point2"], path + ".point2")
                         : (b2 < 0 ? sb.initial_position(b1, s1) : sb.to_local(b2, sb.initial_position(b1, s1)));
      }
      const auto nodes = node_list(b1, b2);
      const double th0 = model.node(b1).q0[2] - (b2 >= 0 ? model.node(b2).q0[2] : 0.0);
      model.add_constraint(std::make_unique<FixedJoint2D>(name, nodes, sb.marker(b1, s1, nodes, j, path + ".point1"),
                                                          sb.marker(b2, s2, nodes, j, path + ".point2"), th0));
      continue;
    }
    if (type != "revolute" && type != "point_on_line" && type != "prismatic")
      rd.fail(j["type"], path + ".type",
              "unknown joint type '" + type + "' (expected revolute, fixed_point, fixed, point_on_line, prismatic)");
    const bool line = type != "revolute";
    std::set<std::string> allowed{"name", "type", "body1", "point1", "body2", "point2", "location"};
    if (line) allowed.insert("axis");
    rd.keys(j, path, allowed);
    const int b1 = sb.body(j, "body1", path, false);
    const int b2 = j["body2"] ? sb.body(j, "body2", path, true) : -1;
    if (b1 == b2) rd.fail(j["body2"], path + ".body2", "a joint needs two different bodies");
    Eigen::Vector2d s1, s2;
    if (j["location"]) {
      if (j["point1"] || j["point2"]) rd.fail(j["location"], path + ".location", "give either location or point1/point2");
      const Eigen::Vector2d loc = rd.vec2(j["location"], path + ".location");
      s1 = sb.to_local(b1, loc);
      s2 = sb.to_local(b2, loc);
    } else {
      s1 = rd.vec2(j, "point1", path, Eigen::Vector2d::Zero());
      s2 = rd.vec2(j, "point2", path, Eigen::Vector2d::Zero());
    }
    const auto nodes = node_list(b1, b2);
    const PlanarMarker m1 = sb.marker(b1, s1, nodes, j, path + ".point1");
    const PlanarMarker m2 = sb.marker(b2, s2, nodes, j, path + ".point2");
    if (type == "revolute") {
      model.add_constraint(std::make_unique<RevoluteJoint2D>(name, nodes, m1, m2));
      continue;
    }
    const Eigen::Vector2d axis = rd.vec2(rd.need(j, "axis", path), path + ".axis");
    if (axis.norm() == 0.0) rd.fail(j["axis"], path + ".axis", "expected a non-zero direction");
    if (type == "point_on_line") {
      model.add_constraint(std::make_unique<PointOnLineJoint2D>(name, nodes, m1, m2, axis));
    } else {
      if (!model.node(b1).has_angle())
        rd.fail(j["body1"], path + ".body1", "a prismatic joint fixes the relative rotation: body1 must be a rigid_body");
      if (b2 >= 0 && !model.node(b2).has_angle())
        rd.fail(j["body2"], path + ".body2", "a prismatic joint fixes the relative rotation: body2 must be a rigid_body or ground");
      const double th0 = model.node(b1).q0[2] - (b2 >= 0 ? model.node(b2).q0[2] : 0.0);
      model.add_constraint(std::make_unique<PrismaticJoint2D>(name, nodes, m1, m2, axis, th0));
    }
  }
}

void read_forces(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "forces", "expected a list of force elements");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node f = list[i];
    std::string path;
    const std::string name = rd.item_name(f, "forces", i, "expected a map with name, type, ...", path);
    if (!names.insert(name).second) rd.fail(f["name"], path + ".name", "a force named '" + name + "' exists already");
    const std::string type = rd.text(rd.need(f, "type", path), path + ".type");
    if (type == "spring_damper") {
      rd.keys(f, path, {"name", "type", "body1", "point1", "body2", "point2", "stiffness", "damping", "rest_length", "direction"});
      const int b1 = sb.body(f, "body1", path, true);
      const int b2 = f["body2"] ? sb.body(f, "body2", path, true) : -1;
      if (b1 == b2) rd.fail(f["body2"], path + ".body2", "a spring needs two different bodies (or one body and ground)");
      const Eigen::Vector2d s1 = rd.vec2(f, "point1", path, Eigen::Vector2d::Zero());
      const Eigen::Vector2d s2 = rd.vec2(f, "point2", path, Eigen::Vector2d::Zero());
      const auto nodes = node_list(b1, b2);
      const PlanarMarker m1 = sb.marker(b1, s1, nodes, f, path + ".point1");
      const PlanarMarker m2 = sb.marker(b2, s2, nodes, f, path + ".point2");
      const double k = rd.non_negative(rd.need(f, "stiffness", path), path + ".stiffness", "stiffness (N/m)");
      const double c = f["damping"] ? rd.non_negative(f["damping"], path + ".damping", "damping (N s/m)") : 0.0;
      std::optional<Eigen::Vector2d> axis;
      if (f["direction"]) {
        const Eigen::Vector2d d = rd.vec2(f["direction"], path + ".direction");
        if (d.norm() == 0.0) rd.fail(f["direction"], path + ".direction", "expected a non-zero direction");
        axis = d.normalized();
      }
      const Eigen::Vector2d d0 = sb.initial_position(b1, s1) - sb.initial_position(b2, s2);
      const double initial = axis ? axis->dot(d0) : d0.norm();
      double l0 = initial;
      if (f["rest_length"]) {
        l0 = rd.number(f["rest_length"], path + ".rest_length");
        if (!axis && l0 < 0.0) rd.fail(f["rest_length"], path + ".rest_length", "expected a non-negative length (m)");
      }
      if (!axis && initial < 1e-12)
        rd.fail(f, path, "the two points coincide at t = 0, so a point-to-point spring has no direction; "
                         "give `direction` for a spring along a fixed axis");
      model.add_element(std::make_unique<SpringDamper2D>(name, nodes, m1, m2, k, c, l0, axis));
    } else if (type == "force") {
      rd.keys(f, path, {"name", "type", "body", "point", "value"});
      const int b = sb.body(f, "body", path, false);
      const Eigen::Vector2d s = rd.vec2(f, "point", path, Eigen::Vector2d::Zero());
      const YAML::Node v = rd.need(f, "value", path);
      if (!v.IsSequence() || v.size() != 2) rd.fail(v, path + ".value", "expected [fx, fy], each a number or a time function (N)");
      model.add_element(std::make_unique<PointForce2D>(name, b, sb.marker(b, s, {b}, f, path + ".point"),
                                                       rd.function(v[0], path + ".value[0]"),
                                                       rd.function(v[1], path + ".value[1]")));
    } else if (type == "torque") {
      rd.keys(f, path, {"name", "type", "body", "value"});
      const int b = sb.body(f, "body", path, false);
      if (!model.node(b).has_angle()) rd.fail(f["body"], path + ".body", "a torque needs a rigid_body (a particle has no rotation)");
      model.add_element(std::make_unique<Torque2D>(name, b, rd.function(rd.need(f, "value", path), path + ".value")));
    } else {
      rd.fail(f["type"], path + ".type", "unknown force type '" + type + "' (expected spring_damper, force, torque)");
    }
  }
}

void read_sensors(Reader& rd, SceneBuilder& sb, const YAML::Node& list, Model& model) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, "sensors", "expected a list of sensors");
  std::set<std::string> names;
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node s = list[i];
    std::string path;
    Sensor sn;
    sn.name = rd.sensor_name(s, i, names, path);
    const std::string type = rd.text(rd.need(s, "type", path), path + ".type");
    auto rigid = [&](const char* key) {
      const int b = sb.body(s, key, path, false);
      if (!model.node(b).has_angle()) rd.fail(s[key], path + "." + key, "expected a rigid_body (it has no angle)");
      return b;
    };
    auto component = [&](std::initializer_list<const char*> allowed) { return rd.choice(s, "component", path, allowed); };
    if (type == "body_angle") {
      rd.keys(s, path, {"name", "type", "body"});
      sn.kind = Sensor::Kind::BodyAngle;
      sn.node = rigid("body");
    } else if (type == "relative_angle") {
      rd.keys(s, path, {"name", "type", "body", "relative_to"});
      sn.kind = Sensor::Kind::RelativeAngle;
      sn.node = rigid("body");
      sn.node2 = rigid("relative_to");
    } else if (type == "point_position" || type == "point_displacement" || type == "point_velocity" ||
               type == "point_acceleration") {
      rd.keys(s, path, {"name", "type", "body", "point", "component"});
      sn.kind = type == "point_position" ? Sensor::Kind::PointPosition
                : type == "point_velocity"   ? Sensor::Kind::PointVelocity
                : type == "point_acceleration" ? Sensor::Kind::PointAcceleration
                                               : Sensor::Kind::PointDisplacement;
      sn.node = sb.body(s, "body", path, false);
      const Eigen::Vector2d local = rd.vec2(s, "point", path, Eigen::Vector2d::Zero());
      sn.local = Eigen::Vector3d(local.x(), local.y(), 0.0);
      sb.marker(sn.node, local, {sn.node}, s, path + ".point");
      sn.component = component({"x", "y"});
      const Eigen::Vector2d p0 = sb.initial_position(sn.node, local);
      sn.initial = Eigen::Vector3d(p0.x(), p0.y(), 0.0);
    } else if (type == "joint_reaction") {
      rd.keys(s, path, {"name", "type", "joint", "component"});
      sn.kind = Sensor::Kind::JointReaction;
      const std::string jn = rd.text(rd.need(s, "joint", path), path + ".joint");
      sn.constraint = model.find_constraint(jn);
      if (sn.constraint < 0) rd.fail(s["joint"], path + ".joint", "no joint named '" + jn + "'");
      sn.component = component({"fx", "fy", "mz"});
      if (sn.component == 2) sn.component = 5;  // mz
    } else {
      rd.fail(s["type"], path + ".type",
              "unknown sensor type '" + type +
                  "' (expected body_angle, relative_angle, point_position, point_displacement, point_velocity, "
                  "point_acceleration, joint_reaction)");
    }
    model.add_sensor(sn);
  }
}

/// Applies "a.b.2.c=value" to the tree and returns the node it put there.
YAML::Node apply_override(YAML::Node root, const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set " + assignment + ": expected key.path=value (e.g. solver.h=1e-3)");
  const std::string key = assignment.substr(0, eq), value = assignment.substr(eq + 1);
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  auto index = [&](const YAML::Node& seq, const std::string& part) {
    if (part.empty() || part.find_first_not_of("0123456789") != std::string::npos)
      throw InputError("--set " + assignment + ": '" + part + "' names an entry of a list: expected an index 0, 1, ...");
    const size_t idx = std::stoul(part);
    if (idx >= seq.size())
      throw InputError("--set " + assignment + ": index " + part + " is out of range (the list has " +
                       std::to_string(seq.size()) + " entries)");
    return idx;
  };
  YAML::Node cur = root;
  std::string walked;
  for (size_t i = 0; i + 1 < parts.size(); ++i) {
    if (cur.IsScalar())
      throw InputError("--set " + assignment + ": '" + walked + "' is a value, not a map: it has no key '" + parts[i] + "'");
    if (cur.IsSequence()) cur.reset(cur[index(cur, parts[i])]);
    else {
      if (!cur[parts[i]]) cur[parts[i]] = YAML::Node(YAML::NodeType::Map);
      cur.reset(cur[parts[i]]);
    }
    walked += (walked.empty() ? "" : ".") + parts[i];
  }
  if (cur.IsScalar())
    throw InputError("--set " + assignment + ": '" + walked + "' is a value, not a map: it has no key '" + parts.back() + "'");
  const YAML::Node v = YAML::Load(value);
  if (cur.IsSequence()) cur[index(cur, parts.back())] = v;
  else cur[parts.back()] = v;
  return v;
}

Scene build(const YAML::Node& root, const std::string& label, const MeshLoader& mesh_loader,
            const std::vector<std::pair<YAML::Node, std::string>>& overrides) {
  Reader rd(label, mesh_loader);
  for (const auto& [node, text] : overrides) rd.add_override(node, text);
  Scene scene;
  scene.file = label;
  if (!root.IsMap()) rd.fail(root, "(top level)", "expected a map of sections (solver, bodies, joints, ...)");
  rd.keys(root, "(top level)", {"name", "description", "parameters", "dimension", "gravity", "load", "solver", "output",
                                "mesh", "beams", "shells", "bodies", "joints", "forces", "sensors", "study", "modes"});
  // `study:` is read by `alphaflex study` (study/study_spec.hpp), `modes:` by `alphaflex modes`
  // (io/scene_modes.hpp); a run ignores them.
  rd.read_parameters(root["parameters"]);
  scene.name = root["name"] ? rd.text(root["name"], "name")
                            : std::filesystem::path(label).stem().string();
  if (scene.name.empty() || scene.name.find_first_of("/\\ ") != std::string::npos)
    rd.fail(root["name"], "name", "expected a plain file name (no spaces or slashes)");
  if (root["description"]) scene.description = rd.text(root["description"], "description");
  read_solver(rd, root["solver"], scene.settings, scene.warnings);
  if (const YAML::Node o = root["output"]) {
    rd.keys(o, "output", {"every", "hdf5", "progress", "commit_interval", "checkpoint_every", "checkpoint_keep"});
    if (o["commit_interval"]) {
      scene.settings.commit_interval = rd.number(o["commit_interval"], "output.commit_interval");
      if (!(scene.settings.commit_interval >= 0.0))
        rd.fail(o["commit_interval"], "output.commit_interval",
                "expected a wall-time interval >= 0 (s; 0: every output step is committed at once)");
    }
    if (const YAML::Node c = o["checkpoint_every"]) {
      // A whole number of steps, or a wall time with its unit: "600 s", "10 min", "2 h".
      const char* expected = "expected a number of steps (an integer >= 1) or a wall time with its unit, e.g. \"600 s\", \"10 min\", \"2 h\"";
      std::istringstream in(c.IsScalar() ? c.Scalar() : std::string());
      double value = 0.0;
      std::string unit, rest;
      in >> value >> unit;
      if (!unit.empty()) {
        in >> rest;
        if (!(value > 0.0) || !rest.empty() || (unit != "s" && unit != "min" && unit != "h"))
          rd.fail(c, "output.checkpoint_every", expected);
        scene.settings.checkpoint_wall = value * (unit == "s" ? 1.0 : unit == "min" ? 60.0 : 3600.0);
      } else {
        if (!c.IsScalar()) rd.fail(c, "output.checkpoint_every", expected);
        scene.settings.checkpoint_steps = rd.integer(c, "output.checkpoint_every", 1, 1000000000);
      }
    }
    if (o["checkpoint_keep"]) scene.settings.checkpoint_keep = rd.integer(o["checkpoint_keep"], "output.checkpoint_keep", 1, 1000);
    if (o["progress"]) {
      scene.settings.progress_interval = rd.number(o["progress"], "output.progress");
      if (!(scene.settings.progress_interval >= 0.0))
        rd.fail(o["progress"], "output.progress", "expected a wall-time interval >= 0 (s; 0: no progress lines in batch logs)");
    }
    if (o["every"]) scene.settings.output_every = rd.integer(o["every"], "output.every", 1);
    if (o["hdf5"]) scene.settings.hdf5 = rd.flag(o["hdf5"], "output.hdf5");
  }
  RunSettings& rs = scene.settings;
  if (root["dimension"]) {
    rs.dimension = rd.integer(root["dimension"], "dimension", 2, 3);
  }
  if (const YAML::Node l = root["load"]) {
    rd.keys(l, "load", {"factor"});
    if (l["factor"]) rs.load_factor = rd.number(l["factor"], "load.factor");
  }
  rs.statics.target = rs.load_factor;
  rs.integrator.load_factor = rs.load_factor;
  scene.model = std::make_unique<Model>();
  scene.model->name = scene.name;
  SceneBuilder sb(rd, *scene.model);
  if (rs.dimension == 2) {
    const Eigen::Vector2d gravity = rd.vec2(root, "gravity", "", Eigen::Vector2d::Zero());
    scene_detail::read_planar_mesh_and_beams(rd, root, *scene.model, gravity);
    read_bodies(rd, root["bodies"], *scene.model, gravity);
    if (scene.model->nodes().empty()) rd.fail(root, "bodies", "the scene has no bodies and no beams");
    read_joints(rd, sb, root["joints"], *scene.model);
    read_forces(rd, sb, root["forces"], *scene.model);
    read_sensors(rd, sb, root["sensors"], *scene.model);
  } else {
    const Eigen::Vector3d gravity = rd.vec3(root, "gravity", "", Eigen::Vector3d::Zero());
    scene_detail::read_mesh_and_beams(rd, sb, root, *scene.model, gravity);
    scene_detail::read_spatial_bodies(rd, sb, root["bodies"], *scene.model, gravity);
    if (scene.model->nodes().empty()) rd.fail(root, "bodies", "the scene has no bodies, beams or shells");
    scene_detail::read_spatial_joints(rd, sb, root["joints"], *scene.model);
    scene_detail::read_spatial_forces(rd, sb, root["forces"], *scene.model);
    scene_detail::read_spatial_sensors(rd, sb, root["sensors"], *scene.model);
  }
  return scene;
}

Scene load(const std::function<YAML::Node()>& parse, const std::string& label,
           const std::vector<std::string>& overrides, const MeshLoader& mesh_loader = read_mesh) {
  YAML::Node root;
  try {
    root = parse();
  } catch (const YAML::Exception& e) {
    throw InputError(label + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  std::vector<std::pair<YAML::Node, std::string>> applied;
  for (const auto& o : overrides) {
    try {
      applied.emplace_back(apply_override(root, o), o);
    } catch (const YAML::Exception& e) {
      throw InputError(label + ": --set " + o + ": " + e.msg);
    }
  }
  try {
    return build(root, label, mesh_loader, applied);
  } catch (const YAML::Exception& e) {
    throw InputError(label + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

}  // namespace

namespace {

/// rank 0's scene file as text, or its reason for failing, on every rank.
std::string scene_text(const std::string& path, int rank, MPI_Comm comm, std::string& error) {
  std::string text;
  if (rank == 0) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) error = path + ": cannot open the scene file (no such file)";
    else if (!std::filesystem::is_regular_file(path, ec)) error = path + ": cannot open the scene file (not a file)";
    else {
      std::ifstream in(path, std::ios::binary);
      if (!in) error = path + ": cannot open the scene file";
      else text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  error = broadcast_text(error, comm);
  text = broadcast_text(text, comm);
  return text;
}

}  // namespace

std::string broadcast_text(const std::string& text, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size == 1) return text;
  unsigned long long len = text.size();
  MPI_Bcast(&len, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  std::string out = text;
  out.resize(static_cast<size_t>(len));
  MPI_Bcast(out.data(), static_cast<int>(len), MPI_CHAR, 0, comm);
  return out;
}

Scene read_scene(const std::string& path, const std::vector<std::string>& overrides, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": cannot open the scene file (no such file)");
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": cannot open the scene file (not a file)");
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open the scene file");
    return load([&] { return YAML::LoadFile(path); }, path, overrides);
  }
  // Rank 0 reads the file and the mesh; every rank parses the same text, so every rank reaches the
  // mesh (or fails with the same message) at the same point, and gmsh runs once per run.
  std::string error;
  const std::string text = scene_text(path, rank, comm, error);
  if (!error.empty()) throw InputError(error);
  const scene_detail::MeshLoader from_rank0 = [rank, comm](const std::string& file, const MeshOptions& options,
                                             const std::string& context) {
    std::string err;
    std::vector<char> bytes;
    if (rank == 0) {
      try {
        bytes = pack(read_mesh(file, options, context));
      } catch (const std::exception& e) {
        err = e.what();
      }
    }
    err = broadcast_text(err, comm);
    if (!err.empty()) throw InputError(err);
    const std::string b = broadcast_text(std::string(bytes.begin(), bytes.end()), comm);
    return rank == 0 ? unpack(bytes) : unpack(std::vector<char>(b.begin(), b.end()));
  };
  return load([&] { return YAML::Load(text); }, path, overrides, from_rank0);
}

Scene read_scene_text(const std::string& yaml, const std::string& label, const std::vector<std::string>& overrides) {
  return load([&] { return YAML::Load(yaml); }, label, overrides);
}

}  // namespace alphaflex
