// `force` (at a body point, world components) and `torque` (on a rigid body): planar applied
// loads, each a number or a time function.
#include "alphaflex/elements/applied_load_2d.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_force_2d(const Item& it) {
  const int b = it.sb.body(it.keys, "body", false);
  const Eigen::Vector2d s = it.keys.vec2("point");
  const YAML::Node v = it.keys.node("value");
  if (!v.IsSequence() || v.size() != 2) it.rd.fail(v, it.at("value"), "expected [fx, fy], each a number or a time function (N)");
  it.model.add_element(std::make_unique<PointForce2D>(it.name, b, it.sb.marker(b, s, {b}, it.node, it.at("point")),
                                                      it.rd.function(v[0], it.at("value[0]")), it.rd.function(v[1], it.at("value[1]"))));
}

void read_torque_2d(const Item& it) {
  const int b = it.sb.body(it.keys, "body", false);
  if (!it.model.node(b).has_angle()) it.rd.fail(it.node["body"], it.at("body"), "a torque needs a rigid_body (a particle has no rotation)");
  it.model.add_element(std::make_unique<Torque2D>(it.name, b, it.keys.function("value")));
}

}  // namespace

void register_applied_loads_2d(SceneTypes& t) {
  t.loads.add("force", type_schema("forces.2d.force", "`force`: a force at a body point", {
      {"body", KeyType::Text, "–", kRequired, "a body; not `ground`"},
      {"point", KeyType::Vec2, "m", "[0, 0]", "point of application, body frame relative to the centre of mass"},
      {"value", KeyType::List, "N", kRequired, "world components [fx, fy], each a number or a time function", {}, "", "[fx, fy]"}}), read_force_2d);
  t.loads.add("torque", type_schema("forces.2d.torque", "`torque`: a torque on a rigid body", {
      {"body", KeyType::Text, "–", kRequired, "a `rigid_body`"},
      {"value", KeyType::Function, "N·m", kRequired, "counter-clockwise positive"}}), read_torque_2d);
}

}  // namespace alphaflex::scene_detail
