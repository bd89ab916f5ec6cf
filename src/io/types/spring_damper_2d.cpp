// `spring_damper` (planar): tension T = k·(L − L0) + c·L̇ between two points, or along a fixed
// direction.
#include "alphaflex/elements/spring_damper_2d.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_spring_damper_2d(const Item& it) {
  const Section& k = it.keys;
  const int b1 = it.sb.body(k, "body1", true);
  const int b2 = k.has("body2") ? it.sb.body(k, "body2", true) : -1;
  if (b1 == b2) it.rd.fail(k.node("body2"), it.at("body2"), "a spring needs two different bodies (or one body and ground)");
  const Eigen::Vector2d s1 = k.vec2("point1"), s2 = k.vec2("point2");
  const auto nodes = node_list(b1, b2);
  const PlanarMarker m1 = it.sb.marker(b1, s1, nodes, it.node, it.at("point1"));
  const PlanarMarker m2 = it.sb.marker(b2, s2, nodes, it.node, it.at("point2"));
  const double stiffness = k.number("stiffness"), damping = k.number("damping", 0.0);
  std::optional<Eigen::Vector2d> axis;
  if (k.has("direction")) {
    const Eigen::Vector2d d = k.vec2("direction");
    if (d.norm() == 0.0) it.rd.fail(k.node("direction"), it.at("direction"), "expected a non-zero direction");
    axis = d.normalized();
  }
  const Eigen::Vector2d d0 = it.sb.initial_position(b1, s1) - it.sb.initial_position(b2, s2);
  const double initial = axis ? axis->dot(d0) : d0.norm();
  double l0 = initial;
  if (k.has("rest_length")) {
    l0 = k.number("rest_length");
    if (!axis && l0 < 0.0) it.rd.fail(k.node("rest_length"), it.at("rest_length"), "expected a non-negative length (m)");
  }
  if (!axis && initial < 1e-12)
    it.rd.fail(it.node, it.path, "the two points coincide at t = 0, so a point-to-point spring has no direction; "
                                 "give `direction` for a spring along a fixed axis");
  it.model.add_element(std::make_unique<SpringDamper2D>(it.name, nodes, m1, m2, stiffness, damping, l0, axis));
}

}  // namespace

void register_spring_damper_2d(SceneTypes& t) {
  t.loads.add("spring_damper", type_schema("forces.2d.spring_damper", "`spring_damper`: tension T = k·(L − L0) + c·L̇", {
      {"body1", KeyType::Text, "–", kRequired, "a body or `ground`"},
      {"point1", KeyType::Vec2, "m", "[0, 0]", "point of body1 (body frame; world point for `ground`)"},
      {"body2", KeyType::Text, "–", "`ground`", "a body or `ground`; different from body1"},
      {"point2", KeyType::Vec2, "m", "[0, 0]", "point of body2 (body frame; world point for `ground`)"},
      {"stiffness", KeyType::Number, "N/m", kRequired, "k", Range::non_negative(), "stiffness (N/m)"},
      {"damping", KeyType::Number, "N·s/m", "0", "c", Range::non_negative(), "damping (N s/m)"},
      {"rest_length", KeyType::Number, "m", "the length L at t = 0", "L0; ≥ 0 for a point-to-point spring, any sign with `direction`"},
      {"direction", KeyType::Vec2, "–", "none", "a spring along this fixed world direction d (normalized), L = d·(r1 − r2); non-zero"}}),
              read_spring_damper_2d);
}

}  // namespace alphaflex::scene_detail
