// `body_rotation` (spatial): a component of the rotation vector log(R) of a body or node (rad).
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_body_rotation(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::BodyRotation;
  sn.node = spatial_node(it, "body", false);
  sn.component = it.keys.choice("component");
}

}  // namespace

void register_body_rotation_3d(SceneTypes& t) {
  t.sensors.add("body_rotation", type_schema("sensors.3d.body_rotation", "`body_rotation`: component of the rotation vector log(R) (rad)", {
      {"body", KeyType::Text, "–", kRequired, "a body or beam/shell node"}, xyz_component()}), read_body_rotation);
}

}  // namespace alphaflex::scene_detail
