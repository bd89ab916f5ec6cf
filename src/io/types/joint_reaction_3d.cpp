// `joint_reaction` (spatial): a component of the force or moment a joint exerts on its body1, in
// the joint frame (N, N·m).
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_joint_reaction_3d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::JointReaction;
  sn.constraint = sensor_joint(it);
  sn.component = it.keys.choice("component");
}

}  // namespace

void register_joint_reaction_3d(SceneTypes& t) {
  t.sensors.add("joint_reaction", type_schema("sensors.3d.joint_reaction", "`joint_reaction`: force / moment on body1 in the joint frame (N, N·m)", {
      {"joint", KeyType::Text, "–", kRequired, "a joint of `joints`"},
      {"component", KeyType::Choice, "–", kRequired, "component", {}, "", "", {"fx", "fy", "fz", "mx", "my", "mz"}}}), read_joint_reaction_3d);
}

}  // namespace alphaflex::scene_detail
