// `fixed` (planar): a clamp or weld, r1 − r2 = 0 and θ1 − θ2 = θ0 (3 equations).
#include "alphaflex/joints/planar_joints.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_fixed_2d(const Item& it) {
  const TwoPoints tp = two_points(it, true);
  for (int b : {tp.b1, tp.b2})
    if (b >= 0 && !it.model.node(b).has_angle())
      it.rd.fail(it.node, it.path, "a fixed joint locks the rotation: '" + it.model.node(b).name + "' must be a rigid_body or beam node");
  it.model.add_constraint(std::make_unique<FixedJoint2D>(it.name, tp.nodes, tp.marker1(it), tp.marker2(it), tp.relative_angle(it.model)));
}

}  // namespace

void register_fixed_2d(SceneTypes& t) {
  t.joints.add("fixed", type_schema("joints.2d.fixed", "`fixed`: clamp or weld, 3 equations; point2 defaults to the point of body2 at point1", two_point_keys()), read_fixed_2d);
}

}  // namespace alphaflex::scene_detail
