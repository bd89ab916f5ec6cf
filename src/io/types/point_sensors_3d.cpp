// `point_position`, `point_displacement`, `point_velocity`, `point_acceleration` (spatial): a
// component of a body point's motion (m, m, m/s, m/s²), world frame or the frame of
// `relative_to`; one schema, four quantities.
#include "common.hpp"
#include "reduced_mesh_3d.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_point_sensor_3d(const Item& it, Sensor& sn, Sensor::Kind kind) {
  Reader& rd = it.rd;
  const Section& k = it.keys;
  sn.kind = kind;
  if (read_reduced_point_sensor(it, sn)) return;  // a point inside a reduced block: rebuilt from the modes
  if (k.has("marker")) {
    if (k.has("body") || k.has("point")) rd.fail(k.node("marker"), it.at("marker"), "give either marker or body/point");
    const std::string mn = k.text("marker");
    const auto found = it.sb.markers.find(mn);
    if (found == it.sb.markers.end()) rd.fail(k.node("marker"), it.at("marker"), "no marker named '" + mn + "'");
    sn.node = found->second.node;
    sn.local = found->second.position;
  } else {
    sn.node = spatial_node(it, "body", false);
    sn.local = k.vec3("point");
  }
  sn.component = k.choice("component");
  const Pose<double> p0 = initial_pose(it.model, sn.node);
  sn.initial = p0.x + p0.R * sn.local;
  if (k.has("relative_to")) {
    sn.frame_node = spatial_node(it, "relative_to", false);
    if (sn.kind == Sensor::Kind::PointDisplacement) {
      // Displacement seen in the moving frame: position in that frame minus its initial value.
      const Pose<double> f0 = initial_pose(it.model, sn.frame_node);
      sn.initial = f0.R.transpose() * (sn.initial - f0.x);
    }
  }
}

}  // namespace

void register_point_sensors_3d(SceneTypes& t) {
  for (const auto& [name, kind] : point_sensor_kinds())
    t.sensors.add(name, type_schema(std::string("sensors.3d.") + name, std::string("`") + name + "` of a body point: world components, or in the frame of `relative_to`", {
        {"body", KeyType::Text, "–", kRequired + std::string(" (unless `marker`)"), "a body or beam/shell node; not `ground`"},
        {"point", KeyType::Vec3, "m", "[0, 0, 0]", "point of the body, body frame"},
        {"marker", KeyType::Text, "–", "–", "a marker instead of body and point"},
        xyz_component(),
        {"relative_to", KeyType::Text, "–", "none", "a body whose frame the point is seen in"}}),
        [kind = kind](const Item& it, Sensor& sn) { read_point_sensor_3d(it, sn, kind); });
}

}  // namespace alphaflex::scene_detail
