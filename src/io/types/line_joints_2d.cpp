// `point_on_line` (point 1 on the line through point 2 along `axis`, 1 equation) and `prismatic`
// (the same and a fixed relative rotation: a slider, 2 equations).
#include "alphaflex/joints/planar_joints.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

Eigen::Vector2d joint_axis_2d(const Item& it) {
  const Eigen::Vector2d axis = it.keys.vec2("axis");
  if (axis.norm() == 0.0) it.rd.fail(it.keys.node("axis"), it.at("axis"), "expected a non-zero direction");
  return axis;
}

void read_point_on_line_2d(const Item& it) {
  const TwoPoints tp = two_points(it, false);
  const PlanarMarker m1 = tp.marker1(it), m2 = tp.marker2(it);
  it.model.add_constraint(std::make_unique<PointOnLineJoint2D>(it.name, tp.nodes, m1, m2, joint_axis_2d(it)));
}

void read_prismatic_2d(const Item& it) {
  const TwoPoints tp = two_points(it, false);
  const PlanarMarker m1 = tp.marker1(it), m2 = tp.marker2(it);
  const Eigen::Vector2d axis = joint_axis_2d(it);
  if (!it.model.node(tp.b1).has_angle())
    it.rd.fail(it.node["body1"], it.at("body1"), "a prismatic joint fixes the relative rotation: body1 must be a rigid_body");
  if (tp.b2 >= 0 && !it.model.node(tp.b2).has_angle())
    it.rd.fail(it.node["body2"], it.at("body2"), "a prismatic joint fixes the relative rotation: body2 must be a rigid_body or ground");
  it.model.add_constraint(std::make_unique<PrismaticJoint2D>(it.name, tp.nodes, m1, m2, axis, tp.relative_angle(it.model)));
}

}  // namespace

void register_line_joints_2d(SceneTypes& t) {
  const Key axis{"axis", KeyType::Vec2, "–", kRequired, "direction in body2's frame (world when body2 is `ground`, a particle or a line particle); non-zero"};
  t.joints.add("point_on_line", type_schema("joints.2d.point_on_line", "`point_on_line`: point 1 on the line through point 2 along `axis`, 1 equation",
                                            with(two_point_keys(), {axis})), read_point_on_line_2d);
  t.joints.add("prismatic", type_schema("joints.2d.prismatic", "`prismatic`: slider, 2 equations", with(two_point_keys(), {axis})), read_prismatic_2d);
}

}  // namespace alphaflex::scene_detail
