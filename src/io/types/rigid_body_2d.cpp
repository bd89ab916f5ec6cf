// `rigid_body` (planar): x, y, θ of the centre of mass.
#include "alphaflex/elements/rigid_body_2d.hpp"
#include "body_shape.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_rigid_body_2d(const Item& it) {
  const Section& k = it.keys;
  Node nd;
  nd.name = it.name;
  nd.kind = NodeKind::RigidBody2D;
  const double m = k.number("mass"), J = k.number("inertia");
  const Eigen::Vector2d p = k.vec2("position"), v = k.vec2("velocity");
  nd.q0 = Eigen::Vector3d(p.x(), p.y(), k.number("angle", 0.0));
  nd.v0 = Eigen::Vector3d(v.x(), v.y(), k.number("angular_velocity", 0.0));
  const int id = it.model.add_node(nd);
  it.model.add_element(std::make_unique<RigidBody2D>(it.name, id, m, J, it.sb.gravity.head<2>()));
  read_body_shape(it, id);
}

}  // namespace

void register_rigid_body_2d(SceneTypes& t) {
  t.bodies.add("rigid_body", type_schema("bodies.2d.rigid_body", "`rigid_body`: x, y, θ of the centre of mass", {
      {"mass", KeyType::Number, "kg", kRequired, "positive (zero makes the mass matrix singular)",
       Range::positive(), "mass (kg); a zero mass makes the mass matrix singular"},
      {"inertia", KeyType::Number, "kg·m²", kRequired, "moment of inertia about the centre of mass", Range::positive(),
       "moment of inertia about the centre of mass (kg m^2); zero makes the mass matrix singular"},
      {"position", KeyType::Vec2, "m", kRequired, "world position of the centre of mass at t = 0"},
      {"angle", KeyType::Number, "rad", "0", "angle of the body frame at t = 0"},
      {"velocity", KeyType::Vec2, "m/s", "[0, 0]", "velocity at t = 0"},
      {"angular_velocity", KeyType::Number, "rad/s", "0", "at t = 0, counter-clockwise positive"},
      shape_key()}), read_rigid_body_2d);
}

}  // namespace alphaflex::scene_detail
