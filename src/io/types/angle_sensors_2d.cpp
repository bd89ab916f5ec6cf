// `body_angle` (θ of a rigid body) and `relative_angle` (θ_body − θ_relative_to): planar angle
// sensors (rad, not wrapped).
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

int rigid_2d(const Item& it, const char* key) {
  const int b = it.sb.body(it.keys, key, false);
  if (!it.model.node(b).has_angle()) it.rd.fail(it.node[key], it.at(key), "expected a rigid_body (it has no angle)");
  return b;
}

void read_body_angle_2d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::BodyAngle;
  sn.node = rigid_2d(it, "body");
}

void read_relative_angle_2d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::RelativeAngle;
  sn.node = rigid_2d(it, "body");
  sn.node2 = rigid_2d(it, "relative_to");
}

}  // namespace

void register_angle_sensors_2d(SceneTypes& t) {
  t.sensors.add("body_angle", type_schema("sensors.2d.body_angle", "`body_angle`: θ of a `rigid_body` (rad, not wrapped)", {
      {"body", KeyType::Text, "–", kRequired, "a `rigid_body`"}}), read_body_angle_2d);
  t.sensors.add("relative_angle", type_schema("sensors.2d.relative_angle", "`relative_angle`: θ_body − θ_relative_to (rad)", {
      {"body", KeyType::Text, "–", kRequired, "a `rigid_body`"},
      {"relative_to", KeyType::Text, "–", kRequired, "a `rigid_body`"}}), read_relative_angle_2d);
}

}  // namespace alphaflex::scene_detail
