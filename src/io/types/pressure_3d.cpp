// `pressure` (spatial): on the shell elements of a surface group, one ShellPressure per element.
#include "alphaflex/elements/shell.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_pressure(const Item& it) {
  const MeshGroup& g = it.sb.mesh_group(it.keys, "group", 2);
  if (!g.shells) it.rd.fail(it.node["group"], it.at("group"), "a pressure acts on shells: no `shells` block uses this surface group");
  const TimeFunctionPtr p = it.keys.function("value");
  const bool follower = it.keys.flag("follower", true);
  for (size_t e = 0; e < g.elements.size(); ++e) {
    std::vector<Eigen::Vector3d> X;
    for (int n : g.elements[e]) X.push_back(initial_pose(it.model, n).x);
    it.model.add_element(std::make_unique<ShellPressure>(it.name + "[" + std::to_string(e) + "]", g.elements[e], X, p, follower));
  }
}

}  // namespace

void register_pressure_3d(SceneTypes& t) {
  t.loads.add("pressure", type_schema("forces.3d.pressure", "`pressure` on the shells of a surface group", {
      {"group", KeyType::Text, "–", kRequired, "a surface group used by `shells`"},
      {"value", KeyType::Function, "Pa", kRequired, "positive against the element normal"},
      {"follower", KeyType::Flag, "–", "on", "on: along the current normal, per current area; off: fixed direction"}}), read_pressure);
}

}  // namespace alphaflex::scene_detail
