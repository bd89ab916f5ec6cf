// `joint_reaction`: a component of the force or moment a joint exerts on its body1 — planar: world
// frame (fx, fy, mz); spatial: joint frame (fx, fy, fz, mx, my, mz) (N, N·m).
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_joint_reaction(const Item& it, Sensor& sn, bool planar) {
  sn.kind = Sensor::Kind::JointReaction;
  sn.constraint = sensor_joint(it);
  // A weld into a reduced body is a tie of the body's massless node: the load it carries is inside
  // the reduced body, and the tie's multipliers see only the loads applied to the body's node.
  if (const auto w = it.sb.welds.find(it.keys.text("joint")); w != it.sb.welds.end())
    it.rd.fail(it.node["joint"], it.at("joint"), "'" + w->first + "' welds '" + w->second.body + "' into the reduced block '" +
                                                     w->second.block + "': its reaction is inside the reduced body and is not available (the body's "
                                                     "other joints' reactions are; the full mesh, --set BLOCK.reduction=~, has this one)");
  sn.component = it.keys.choice("component");
  if (planar && sn.component == 2) sn.component = 5;  // mz: the sixth component of a reaction
}

Schema reaction_schema(const char* dimension, const char* doc, std::vector<std::string> components) {
  return type_schema(std::string("sensors.") + dimension + ".joint_reaction", doc, {
      {"joint", KeyType::Text, "–", kRequired, "a joint of `joints`"},
      {"component", KeyType::Choice, "–", kRequired, *dimension == '2' ? "force or moment component" : "component", {}, "", "",
       std::move(components)}});
}

}  // namespace

void register_joint_reaction_2d(SceneTypes& t) {
  t.sensors.add("joint_reaction", reaction_schema("2d", "`joint_reaction`: what the joint exerts on its body1, world frame (N, N·m)", {"fx", "fy", "mz"}),
                [](const Item& it, Sensor& sn) { read_joint_reaction(it, sn, true); });
}

void register_joint_reaction_3d(SceneTypes& t) {
  t.sensors.add("joint_reaction", reaction_schema("3d", "`joint_reaction`: force / moment on body1 in the joint frame (N, N·m)",
                                                  {"fx", "fy", "fz", "mx", "my", "mz"}),
                [](const Item& it, Sensor& sn) { read_joint_reaction(it, sn, false); });
}

}  // namespace alphaflex::scene_detail
