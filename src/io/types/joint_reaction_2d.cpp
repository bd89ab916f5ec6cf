// `joint_reaction` (planar): what a joint exerts on its body1, world frame (N, N·m).
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_joint_reaction_2d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::JointReaction;
  sn.constraint = sensor_joint(it);
  sn.component = it.keys.choice("component");
  if (sn.component == 2) sn.component = 5;  // mz: the sixth component of a reaction
}

}  // namespace

void register_joint_reaction_2d(SceneTypes& t) {
  t.sensors.add("joint_reaction", type_schema("sensors.2d.joint_reaction", "`joint_reaction`: what the joint exerts on its body1, world frame (N, N·m)", {
      {"joint", KeyType::Text, "–", kRequired, "a joint of `joints`"},
      {"component", KeyType::Choice, "–", kRequired, "force or moment component", {}, "", "", {"fx", "fy", "mz"}}}), read_joint_reaction_2d);
}

}  // namespace alphaflex::scene_detail
