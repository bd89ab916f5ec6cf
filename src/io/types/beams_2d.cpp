// `beams` (planar): a block of two-node planar beams (x, y, θ nodes) on a physical curve group of
// a mesh in the x-y plane.
#include <sstream>

#include "alphaflex/elements/planar_beam.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

const Schema& planar_section_schema() {
  static const Schema s{"beams.2d.section", {
      {"EA", KeyType::Number, "N", kRequired, "axial stiffness", Range::positive(), "axial stiffness (N)"},
      {"GA", KeyType::Number, "N", kRequired, "in-plane shear stiffness", Range::positive(), "shear stiffness (N)"},
      {"EI", KeyType::Number, "N·m²", kRequired, "bending stiffness in the plane", Range::positive(), "bending stiffness (N m^2)"},
      {"rhoA", KeyType::Number, "kg/m", kRequired, "mass per length", Range::positive(), "mass per length (kg/m)"},
      {"rhoI", KeyType::Number, "kg·m", kRequired, "rotary inertia per length", Range::positive(), "rotary inertia per length (kg m)"}}};
  return s;
}

void read_beam_block_2d(const Item& it) {
  // Reduced bodies (issue 19) are spatial: a planar scene that asks for one gets told what to do,
  // not "unknown key" (inputs/slider_crank_flexible_3d.yaml is the planar slider-crank in 3D).
  if (it.keys.has("reduction"))
    it.rd.fail(it.keys.node("reduction"), it.at("reduction"),
               "reduced bodies are spatial: a planar (dimension 2) beam block cannot be reduced; write the scene with "
               "`dimension: 3` (3D beam sections, spatial joints about z: e.g. inputs/slider_crank_flexible_3d.yaml)");
  const MeshLineBlock& block = mesh_block(it, it.sb.blocks.mesh.line_blocks, "curve", "beam");
  // Planar section: EA, GA (in-plane shear), EI (bending in the plane), rhoA, rhoI; or a material
  // and a shape whose axis 3 is z (the section's in-plane properties GA2, EI3, rhoI3).
  const YAML::Node sn = it.keys.node("section");
  const std::string key = it.at("section");
  double EA, GA, EI, rhoA, rhoI;
  if (sn.IsMap() && (sn["E"] || sn["shape"])) {
    const BeamSection sec = read_beam_section(it.rd, sn, key);
    EA = sec.EA(), GA = sec.GA2(), EI = sec.EI3(), rhoA = sec.rhoA(), rhoI = sec.rhoI3();
  } else {
    if (!sn.IsMap()) it.rd.fail(sn, key, "expected a map of section properties");
    const Section p(it.rd, sn, key, planar_section_schema());
    EA = p.number("EA"), GA = p.number("GA"), EI = p.number("EI"), rhoA = p.number("rhoA"), rhoI = p.number("rhoI");
  }
  const double eta = it.keys.number("damping", 0.0);
  const MeshData& mesh = it.sb.blocks.mesh;
  for (size_t e = 0; e < block.elements.size(); ++e) {
    const int ma = block.elements[e][0], mb = block.elements[e][1];
    const Eigen::Vector3d d = mesh.points[static_cast<size_t>(mb)] - mesh.points[static_cast<size_t>(ma)];
    const double angle = std::atan2(d.y(), d.x());  // section axis 1 along the element
    int n[2];
    for (int a = 0; a < 2; ++a) {
      const Eigen::Vector3d x = mesh.points[static_cast<size_t>(block.elements[e][static_cast<size_t>(a)])];
      n[a] = block_node(it, block.elements[e][static_cast<size_t>(a)], NodeKind::RigidBody2D, Eigen::Vector3d(x.x(), x.y(), angle),
                        Eigen::Vector3d::Zero());
    }
    try {
      it.model.add_element(std::make_unique<PlanarBeam>(it.name + "[" + std::to_string(e) + "]", n[0], n[1], EA, GA, EI, rhoA, rhoI,
                                                        it.model.node(n[0]).q0, it.model.node(n[1]).q0, angle, angle,
                                                        Eigen::Vector2d(it.sb.gravity.head<2>()), eta));
    } catch (const std::invalid_argument& ex) {
      std::ostringstream os;
      os << "element " << block.element_tags[e] << " of group '" << block.name << "': " << ex.what();
      it.rd.fail(it.keys.node("group"), it.at("group"), os.str());
    }
  }
}

}  // namespace

void register_beams_2d(SceneTypes& t) {
  t.blocks.add("beams", Schema{"beams.2d", {
      {"name", KeyType::Text, "–", kRequired, "elements are named NAME[0], NAME[1], … in mesh order"},
      {"group", KeyType::Text, "–", kRequired, "a physical curve group of the mesh (in the x-y plane), used by one beam only"},
      {"section", KeyType::Map, "–", kRequired, "`beams.2d.section` or `beams.section.material`"},
      {"damping", KeyType::Number, "s", "0", "η: Kelvin–Voigt material damping, section forces C (ε + η ε̇); a bending mode of frequency ω gets ζ = ηω/2 (docs/theory/beam.md)", Range::non_negative(), "material damping (s)"},
      {"reduction", KeyType::Map, "–", "–", "not in 2D: reduced bodies need `dimension: 3` (an error saying so)"}}},
      {"name, group, section", read_beam_block_2d});
  t.parts.push_back(&planar_section_schema());
}

}  // namespace alphaflex::scene_detail
