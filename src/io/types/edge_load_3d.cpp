// `edge_load` (spatial): force and moment per length along a curve group, as consistent nodal
// loads of its linear segments (each node carries half the reference length of each adjacent one).
#include <map>

#include "alphaflex/elements/spatial_elements.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {

namespace {

void read_edge_load(const Item& it) {
  const MeshGroup& g = it.sb.mesh_group(it.keys, "group", 1);
  if (!it.keys.has("force") && !it.keys.has("moment")) it.rd.fail(it.node, it.path, "an edge_load needs force (N/m) or moment (N m/m), or both");
  const std::array<TimeFunctionPtr, 3> force = vector_function(it, "force", "N/m"), moment = vector_function(it, "moment", "N m/m");
  const bool follower = it.keys.flag("follower", false);
  std::map<int, double> length;  // node → length it carries
  for (const auto& seg : g.elements) {
    const double l = (initial_pose(it.model, seg[1]).x - initial_pose(it.model, seg[0]).x).norm();
    length[seg[0]] += 0.5 * l;
    length[seg[1]] += 0.5 * l;
  }
  for (int n : g.nodes) {
    auto scaled = [&](const std::array<TimeFunctionPtr, 3>& v) {
      std::array<TimeFunctionPtr, 3> out;
      for (size_t k = 0; k < 3; ++k)
        if (v[k]) out[k] = make_scaled(v[k], length[n]);
      return out;
    };
    it.model.add_element(std::make_unique<SpatialLoad>(it.name + "[" + it.model.node(n).name + "]", n, Eigen::Vector3d::Zero(),
                                                       scaled(force), scaled(moment), follower));
  }
}

}  // namespace

void register_edge_load_3d(SceneTypes& t) {
  t.loads.add("edge_load", type_schema("forces.3d.edge_load", "`edge_load`: a load per length along a curve group", {
      {"group", KeyType::Text, "–", kRequired, "a curve group whose nodes are on beams or shells"},
      {"force", KeyType::List, "N/m", "none", "[fx, fy, fz] per length, each a number or a time function", {}, "", "[x, y, z] of time functions"},
      {"moment", KeyType::List, "N·m/m", "none", "[mx, my, mz] per length (force or moment, or both)", {}, "", "[x, y, z] of time functions"},
      follower_off()}), read_edge_load);
}

}  // namespace alphaflex::scene_detail
