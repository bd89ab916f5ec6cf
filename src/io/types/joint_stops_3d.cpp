// `joint_stop` (spatial, `forces:`): friction-free stops on a joint's coordinate, a penalty spring-
// dashpot beyond `lower` and `upper` (elements/joint_stop.hpp; theory: docs/theory/force_elements.md).
#include <cmath>
#include <limits>
#include <memory>

#include "alphaflex/elements/joint_stop.hpp"
#include "joint_coordinates.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_joint_stop(const Item& it) {
  const Section& k = it.keys;
  if (!k.has("lower") && !k.has("upper")) it.rd.fail(it.node, it.path, "give `lower`, `upper` or both (the limits of the joint's coordinate)");
  const JointCoordinateNode psi = joint_coordinate_node(it);
  constexpr double inf = std::numeric_limits<double>::infinity();
  const double lower = k.number("lower", -inf), upper = k.number("upper", inf);
  if (!(lower < upper)) it.rd.fail(k.node("upper"), it.at("upper"), "must be above `lower`");
  // The stop acts from t = 0 on what lies beyond it: a joint that starts there would be kicked apart.
  const double psi0 = it.model.node(psi.node).q0[0];
  const char* unit = psi.rotation() ? " rad" : " m";
  if (psi0 < lower) it.rd.fail(k.node("lower"), it.at("lower"), "the joint starts below it (its coordinate is " + std::to_string(psi0) + unit + " at t = 0)");
  if (psi0 > upper) it.rd.fail(k.node("upper"), it.at("upper"), "the joint starts above it (its coordinate is " + std::to_string(psi0) + unit + " at t = 0)");
  it.model.add_element(std::make_unique<JointStop>(it.name, psi.node, lower, upper, k.number("stiffness"), k.number("damping", 0.0)));
}

}  // namespace

void register_joint_stops_3d(SceneTypes& t) {
  t.loads.add("joint_stop", type_schema("forces.3d.joint_stop",
      "`joint_stop`: friction-free stops on a joint's angle or displacement, a penalty spring-dashpot k δ + c δ̇ on the penetration δ beyond a limit", {
      joint_coordinate_joint_key(), joint_coordinate_key(),
      {"lower", KeyType::Number, "rad or m", "none", "the lowest coordinate (the joint's coordinate is 0 at t = 0)"},
      {"upper", KeyType::Number, "rad or m", "none", "the highest coordinate"},
      {"stiffness", KeyType::Number, "N·m/rad or N/m", kRequired, "k of the penalty, acting on the penetration only", Range::positive()},
      {"damping", KeyType::Number, "N·m·s/rad or N·s/m", "0", "c, acting only while penetrating: restitution e = exp(−ζπ/√(1 − ζ²)), ζ = c / (2√(k J))", Range::non_negative()}}),
      read_joint_stop);
}

}  // namespace alphaflex::scene_detail
