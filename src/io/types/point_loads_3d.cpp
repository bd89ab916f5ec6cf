// `force` (at a body point) and `moment` (spatial): dead loads (world components) or followers
// (body-frame components), each component a number or a time function.
#include "alphaflex/elements/spatial_elements.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_point_load(const Item& it, bool moment) {
  const int b = spatial_node(it, "body", false);
  const Eigen::Vector3d s = moment ? Eigen::Vector3d::Zero() : it.keys.vec3("point");
  const std::array<TimeFunctionPtr, 3> value = vector_function(it, "value", moment ? "N m" : "N"), none;
  const bool follower = it.keys.flag("follower", false);
  it.model.add_element(std::make_unique<SpatialLoad>(it.name, b, s, moment ? none : value, moment ? value : none, follower));
}

}  // namespace

void register_point_loads_3d(SceneTypes& t) {
  t.loads.add("force", type_schema("forces.3d.force", "`force` at a body point", {
      {"body", KeyType::Text, "–", kRequired, "a body or beam/shell node; not `ground`"},
      {"point", KeyType::Vec3, "m", "[0, 0, 0]", "point of application, body frame"},
      {"value", KeyType::List, "N", kRequired, "[fx, fy, fz], each a number or a time function", {}, "", "[x, y, z] of time functions"},
      follower_off()}), [](const Item& it) { read_point_load(it, false); });
  t.loads.add("moment", type_schema("forces.3d.moment", "`moment` on a body", {
      {"body", KeyType::Text, "–", kRequired, "a body or beam/shell node; not `ground`"},
      {"value", KeyType::List, "N·m", kRequired, "[mx, my, mz], each a number or a time function", {}, "", "[x, y, z] of time functions"},
      follower_off()}), [](const Item& it) { read_point_load(it, true); });
}

}  // namespace alphaflex::scene_detail
