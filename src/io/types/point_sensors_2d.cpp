// `point_position`, `point_displacement`, `point_velocity`, `point_acceleration` (planar): a world
// component of a body point's motion (m, m, m/s, m/s²); one schema, four quantities.
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_point_sensor_2d(const Item& it, Sensor& sn, Sensor::Kind kind) {
  sn.kind = kind;
  sn.node = it.sb.body(it.keys, "body", false);
  const Eigen::Vector2d local = it.keys.vec2("point");
  sn.local = Eigen::Vector3d(local.x(), local.y(), 0.0);
  it.sb.marker(sn.node, local, {sn.node}, it.node, it.at("point"));
  sn.component = it.keys.choice("component");
  const Eigen::Vector2d p0 = it.sb.initial_position(sn.node, local);
  sn.initial = Eigen::Vector3d(p0.x(), p0.y(), 0.0);
}

}  // namespace

void register_point_sensors_2d(SceneTypes& t) {
  const std::pair<const char*, Sensor::Kind> points[] = {
      {"point_position", Sensor::Kind::PointPosition}, {"point_displacement", Sensor::Kind::PointDisplacement},
      {"point_velocity", Sensor::Kind::PointVelocity}, {"point_acceleration", Sensor::Kind::PointAcceleration}};
  for (const auto& [name, kind] : points)
    t.sensors.add(name, type_schema(std::string("sensors.2d.") + name, std::string("`") + name + "` of a body point, world frame", {
        {"body", KeyType::Text, "–", kRequired, "a body; not `ground`"},
        {"point", KeyType::Vec2, "m", "[0, 0]", "body frame relative to the centre of mass; [0, 0] for particles"},
        {"component", KeyType::Choice, "–", kRequired, "world component", {}, "", "", {"x", "y"}}}),
        [kind = kind](const Item& it, Sensor& sn) { read_point_sensor_2d(it, sn, kind); });
}

}  // namespace alphaflex::scene_detail
