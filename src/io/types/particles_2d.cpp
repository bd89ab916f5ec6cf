// `particle` (x, y) and `line_particle` (s along a fixed line): planar point masses, or massless
// points.
#include "alphaflex/elements/rigid_body_2d.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

/// The node `nd` and, with a mass m > 0, its point mass.
void add_particle(const Item& it, Node& nd, double m) {
  nd.name = it.name;
  const int id = it.model.add_node(nd);
  if (m > 0.0) it.model.add_element(std::make_unique<PointMass>(it.name, id, it.model.node(id), m, it.sb.gravity.head<2>()));
}

void read_particle_2d(const Item& it) {
  const double m = it.keys.number("mass", 0.0);
  Node nd;
  nd.kind = NodeKind::Particle2D;
  nd.q0 = it.keys.vec2("position");
  nd.v0 = it.keys.vec2("velocity");
  add_particle(it, nd, m);
}

void read_line_particle_2d(const Item& it) {
  const Section& k = it.keys;
  const double m = k.number("mass", 0.0);
  Node nd;
  nd.kind = NodeKind::LineParticle2D;
  nd.line_origin = k.vec2("origin");
  const Eigen::Vector2d d = k.vec2("direction");
  if (d.norm() == 0.0) it.rd.fail(k.node("direction"), it.at("direction"), "expected a non-zero direction");
  nd.line_direction = d.normalized();
  const Eigen::Vector2d p = k.vec2("position");
  const Eigen::Vector2d rel = p - nd.line_origin;
  const double s = rel.dot(nd.line_direction);
  if ((rel - s * nd.line_direction).norm() > 1e-9 * std::max(1.0, rel.norm()))
    it.rd.fail(k.node("position"), it.at("position"), "the point is not on the line through `origin` along `direction`");
  nd.q0 = Eigen::VectorXd::Constant(1, s);
  nd.v0 = Eigen::VectorXd::Constant(1, k.number("velocity", 0.0));
  add_particle(it, nd, m);
}

}  // namespace

void register_particles_2d(SceneTypes& t) {
  const Key mass{"mass", KeyType::Number, "kg", "0", "0 = massless point (no inertia, no weight)", Range::non_negative(), "mass (kg)"};
  t.bodies.add("particle", type_schema("bodies.2d.particle", "`particle`: x, y", {
      mass, {"position", KeyType::Vec2, "m", kRequired, "world position at t = 0"},
      {"velocity", KeyType::Vec2, "m/s", "[0, 0]", "velocity at t = 0"}}), read_particle_2d);
  t.bodies.add("line_particle", type_schema("bodies.2d.line_particle", "`line_particle`: s along a fixed line", {
      mass,
      {"origin", KeyType::Vec2, "m", "[0, 0]", "a world point of the line (s = 0)"},
      {"direction", KeyType::Vec2, "–", kRequired, "direction of the line (normalized by the program); non-zero"},
      {"position", KeyType::Vec2, "m", kRequired, "world position at t = 0; on the line (to 1e-9·max(1, distance from origin))"},
      {"velocity", KeyType::Number, "m/s", "0", "speed along `direction` at t = 0 (a number, not a vector)"}}), read_line_particle_2d);
}

}  // namespace alphaflex::scene_detail
