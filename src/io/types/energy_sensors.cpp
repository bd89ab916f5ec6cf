// Energy totals and the energy balance's integrals as sensors: `energy` with `of` (a block, a body,
// a force element or the whole model; kinds kinetic, strain, potential of gravity, total) and
// `work` (the work of the loads, the energy dissipated by the force elements, accumulated over the
// run by the trapezoidal rule: app/sensor_integrals.hpp). Each is a sum over a range of elements
// that every rank evaluates on the elements it owns (model/sensor.cpp); docs/theory/force_elements.md.
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

void read_work(const Item& it, Sensor& sn) {
  read_energy_of(it, sn, 4 + it.keys.choice("kind"));  // a power, which app/sensor_integrals.hpp integrates
}

Key of_key(const char* doc) { return {"of", KeyType::Text, "–", "`model`", doc}; }

Key work_kind() {
  return {"kind", KeyType::Choice, "–", kRequired,
          "external: ∫ P dt of the loads' power P = −vᵀr (forces, moments, torques, pressures, joint motors; not gravity, which is `energy` kind potential); "
          "dissipated: ∫ D dt of the force elements' damping, D = vᵀ(r(q, v) − r(q, 0)) ≥ 0 (spring-dampers, bushings, joint spring-dampers). Trapezoidal in time over the accepted steps",
          {}, "", "", {"external", "dissipated"}};
}

void add_work(SceneTypes& t, const char* schema) {
  t.sensors.add("work", type_schema(schema, "`work`: work done on the model since t = 0, accumulated over the steps (J)", {
      work_kind(), of_key("the loads or force elements summed: one by its name, or `model` (all)")}), read_work);
}

}  // namespace

void read_energy_of(const Item& it, Sensor& sn, int component) {
  const std::string of = it.keys.text("of", "model");
  const auto& elements = it.model.elements();
  // BLOCK[k] are a block's elements; a rigid body's and a force element's element has its name.
  const std::string prefix = of + "[";
  int first = -1, end = -1;
  for (size_t e = 0; e < elements.size(); ++e) {
    const std::string& n = elements[e]->name();
    if (of != "model" && n != of && n.compare(0, prefix.size(), prefix) != 0) continue;
    // A block's elements are made one after the other, so what `of` names is a range of elements.
    if (end >= 0 && end != static_cast<int>(e))
      it.rd.fail(it.keys.node("of"), it.at("of"), "the elements named '" + of + "…' are not one after the other (element '" + n + "')");
    if (first < 0) first = static_cast<int>(e);
    end = static_cast<int>(e) + 1;
  }
  // A body welded into a reduced body has no element of its own: its energy is the reduced body's.
  if (const auto w = it.sb.welded_bodies.find(of); w != it.sb.welded_bodies.end())
    it.rd.fail(it.keys.node("of"), it.at("of"), "'" + of + "' is welded into the reduced block '" + w->second +
                                                   "': its kinetic and potential energy are part of that body's (of: " + w->second + ")");
  if (first < 0)
    it.rd.fail(it.keys.node("of"), it.at("of"), "no block, body or force element named '" + of +
                                                   "' (give the name of a `beams` or `shells` block, a rigid body, a force element or load of `forces`, or `model`)");
  // An energy sum over the element range [element, node2) (model/sensor.cpp).
  sn.kind = Sensor::Kind::ElementEnergy;
  sn.element = first;
  sn.node2 = end;
  sn.component = component;
}

Key energy_of_key() {
  return {"of", KeyType::Text, "–", "– (this or `element`)", "sum over: a `beams` or `shells` block (all its elements), a rigid body, a force element, or `model` (every element); not with `element`"};
}

Key energy_kind() {
  return {"kind", KeyType::Choice, "–", kRequired, "kinetic: ½ vᵀMv with the elements' mass matrices; strain: the stored elastic energy (springs, bushings, joint springs, beams, shells); "
          "potential: of gravity, −Σ m g·x; total: kinetic + strain + potential",
          {}, "", "", {"kinetic", "strain", "potential", "total"}};
}

void register_energy_sensors_2d(SceneTypes& t) {
  t.sensors.add("energy", type_schema("sensors.2d.energy", "`energy`: a sum over a block, a body, a force element or the model (J)", {
      of_key("a `beams` block (all its elements), a body, a force element, or `model` (every element)"), energy_kind()}),
                [](const Item& it, Sensor& sn) { read_energy_of(it, sn, it.keys.choice("kind")); });
  add_work(t, "sensors.2d.work");
}

void register_energy_sensors_3d(SceneTypes& t) {
  add_work(t, "sensors.3d.work");
}

}  // namespace alphaflex::scene_detail
