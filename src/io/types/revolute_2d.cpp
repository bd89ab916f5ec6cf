// `revolute` (a pin between two bodies, or a body and the ground) and `fixed_point` (a body point
// pinned to the world): planar joints of 2 equations, r1 − r2 = 0.
#include "alphaflex/joints/planar_joints.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_revolute_2d(const Item& it) {
  const TwoPoints tp = two_points(it, false);
  it.model.add_constraint(std::make_unique<RevoluteJoint2D>(it.name, tp.nodes, tp.marker1(it), tp.marker2(it)));
}

void read_fixed_point_2d(const Item& it) {
  const Section& k = it.keys;
  const int b1 = it.sb.body(k, "body", false);
  const Eigen::Vector2d s1 = k.vec2("point");
  const Eigen::Vector2d loc = k.has("location") ? k.vec2("location") : it.sb.initial_position(b1, s1);
  const auto nodes = node_list(b1, -1);
  it.model.add_constraint(std::make_unique<RevoluteJoint2D>(it.name, nodes, it.sb.marker(b1, s1, nodes, it.node, it.at("point")),
                                                            PlanarMarker::ground(loc)));
}

}  // namespace

void register_revolute_2d(SceneTypes& t) {
  t.joints.add("revolute", type_schema("joints.2d.revolute", "`revolute`: pin, 2 equations", two_point_keys()), read_revolute_2d);
  t.joints.add("fixed_point", type_schema("joints.2d.fixed_point", "`fixed_point`: a body point pinned to the world, 2 equations", {
      {"body", KeyType::Text, "–", kRequired, "a body; not `ground`"},
      {"point", KeyType::Vec2, "m", "[0, 0]", "point of the body, body frame relative to its centre of mass"},
      {"location", KeyType::Vec2, "m", "the point's world position at t = 0", "world point it is pinned to"}}), read_fixed_point_2d);
}

}  // namespace alphaflex::scene_detail
