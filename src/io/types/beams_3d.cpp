// `beams` (spatial): a block of two-node geometrically exact beams on a physical curve group of
// the mesh, with its cross-section (material and shape, or stiffness and inertia properties).
#include <optional>
#include <sstream>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "reduced_beams_3d.hpp"

namespace alphaflex::scene_detail {
namespace {

const Schema& material_schema() {
  static const Schema s{"beams.section.material", {
      {"E", KeyType::Number, "Pa", kRequired, "Young's modulus", Range::positive(), "Young's modulus (Pa)"},
      {"nu", KeyType::Number, "–", kRequired, "Poisson's ratio (G = E/(2(1 + ν))), in (−1, 0.5)"},
      {"rho", KeyType::Number, "kg/m³", kRequired, "density", Range::positive(), "density (kg/m^3)"},
      {"shape", KeyType::Choice, "–", kRequired, "cross-section shape", {}, "", "", {"rectangle", "circle", "tube"}},
      {"width", KeyType::Number, "m", "– (**required** for `rectangle`)", "along section axis 2", Range::positive(), "width (m)"},
      {"height", KeyType::Number, "m", "– (**required** for `rectangle`)", "along section axis 3", Range::positive(), "height (m)"},
      {"diameter", KeyType::Number, "m", "– (**required** for `circle`, `tube`)", "outer diameter", Range::positive(), "diameter (m)"},
      {"wall_thickness", KeyType::Number, "m", "– (**required** for `tube`)", "at most the radius", Range::positive(), "wall thickness (m)"}}};
  return s;
}

const Schema& properties_schema() {
  static const Schema s{"beams.section.properties", {
      {"EA", KeyType::Number, "N", kRequired, "axial stiffness", Range::positive(), "axial stiffness (N)"},
      {"GA2", KeyType::Number, "N", kRequired, "shear stiffness along axis 2 (shear coefficient included)", Range::positive(), "shear stiffness (N)"},
      {"GA3", KeyType::Number, "N", kRequired, "shear stiffness along axis 3 (shear coefficient included)", Range::positive(), "shear stiffness (N)"},
      {"GJ", KeyType::Number, "N·m²", kRequired, "torsional stiffness", Range::positive(), "torsional stiffness (N m^2)"},
      {"EI2", KeyType::Number, "N·m²", kRequired, "bending stiffness about axis 2 (deflection along axis 3)", Range::positive(), "bending stiffness (N m^2)"},
      {"EI3", KeyType::Number, "N·m²", kRequired, "bending stiffness about axis 3", Range::positive(), "bending stiffness (N m^2)"},
      {"rhoA", KeyType::Number, "kg/m", kRequired, "mass per length", Range::positive(), "mass per length (kg/m)"},
      {"rhoI2", KeyType::Number, "kg·m", kRequired, "mass moment per length about axis 2", Range::positive(), "mass moment per length (kg m)"},
      {"rhoI3", KeyType::Number, "kg·m", kRequired, "mass moment per length about axis 3", Range::positive(), "mass moment per length (kg m)"},
      {"rhoI_polar", KeyType::Number, "kg·m", "rhoI2 + rhoI3", "polar mass moment per length", Range::positive(), "polar mass moment per length (kg m)"}}};
  return s;
}

void read_beam_block_3d(const Item& it) {
  const Section& k = it.keys;
  // A block that `reduction.blocks` of another names is built by that reduced block (its part).
  if (const auto owner = it.sb.blocks.absorbed.find(it.name); owner != it.sb.blocks.absorbed.end()) {
    if (k.has("damping"))
      it.rd.fail(k.node("damping"), it.at("damping"), "material damping is for a full-mesh block; this block is part of the reduced body '" +
                                                          owner->second + "' (remove one of the two)");
    return;
  }
  if (k.has("damping") && k.has("reduction"))
    it.rd.fail(k.node("damping"), it.at("damping"), "material damping is for a full-mesh block; a block with `reduction` has none (remove one of the two)");
  if (k.has("reduction")) return read_reduced_block_3d(it, beam_part);
  const MeshLineBlock& block = mesh_block(it, it.sb.blocks.mesh.line_blocks, "curve", "beam");
  const BeamSection section = read_beam_section(it.rd, k.node("section"), it.at("section"));
  const Eigen::Vector3d orient = it.sb.blocks.placed(k.text("group"), k.direction("orientation"));
  add_beam_elements(it, block, section, orient, it.model,
                    [&](int m, const Eigen::VectorXd& q0) { return block_node(it, m, NodeKind::Frame3D, q0, Eigen::VectorXd::Zero(6)); });
}

}  // namespace

BlockPart beam_part(const Item& it) {
  const MeshLineBlock& block = mesh_block(it, it.sb.blocks.mesh.line_blocks, "curve", "beam");
  const BeamSection section = read_beam_section(it.rd, it.keys.node("section"), it.at("section"));
  const Eigen::Vector3d orient = it.sb.blocks.placed(it.keys.text("group"), it.keys.direction("orientation"));
  return {mesh_nodes_of(block.elements), block.name, [&it, &block, section, orient](Model& model, const BlockNodeOf& node_of) {
            return add_beam_elements(it, block, section, orient, model, node_of);
          }};
}

std::vector<int> add_beam_elements(const Item& it, const MeshLineBlock& block, const BeamSection& section, const Eigen::Vector3d& orient,
                                   Model& model, const BlockNodeOf& node_of) {
  const Section& k = it.keys;
  const MeshData& mesh = it.sb.blocks.mesh;
  const double eta = k.number("damping", 0.0);  // a reduced block has none (read_beam_block_3d)
  std::vector<int> ids;
  for (size_t e = 0; e < block.elements.size(); ++e) {
    const int ma = block.elements[e][0], mb = block.elements[e][1];
    const Eigen::Vector3d xa = mesh.points[static_cast<size_t>(ma)], xb = mesh.points[static_cast<size_t>(mb)];
    Eigen::Matrix3d sec;
    if (!frame_from(xb - xa, orient, sec)) {
      std::ostringstream os;
      os << "is parallel to element " << block.element_tags[e] << " of group '" << block.name << "' (or the element has zero length); "
         << "the orientation vector fixes section axis 2 and must not lie along the beam";
      it.rd.fail(k.node("orientation"), it.at("orientation"), os.str());
    }
    // A node's frame is the section frame of the first element that reaches it; each element
    // keeps its own offset from it.
    int n[2];
    for (int a = 0; a < 2; ++a) {
      const int m = block.elements[e][static_cast<size_t>(a)];
      Eigen::VectorXd q0(7);
      store_pose(mesh.points[static_cast<size_t>(m)], sec, q0.data());
      n[a] = node_of(m, q0);
    }
    try {
      ids.push_back(static_cast<int>(model.elements().size()));
      model.add_element(std::make_unique<GeometricallyExactBeam>(
          it.name + "[" + std::to_string(e) + "]", n[0], n[1], section, pose_of(model.node(n[0]).q0.data()),
          pose_of(model.node(n[1]).q0.data()), sec, sec, it.sb.gravity, eta));
    } catch (const std::invalid_argument& ex) {
      std::ostringstream os;
      os << "element " << block.element_tags[e] << " of group '" << block.name << "': " << ex.what();
      it.rd.fail(k.node("group"), it.at("group"), os.str());
    }
  }
  return ids;
}

BeamSection read_beam_section(const Reader& rd, const YAML::Node& n, const std::string& key) {
  if (!n.IsMap()) rd.fail(n, key, "expected a map of section properties");
  try {
    if (n["E"] || n["shape"]) {
      const Section m(rd, n, key, material_schema());
      // Keys a shape requires (the schema marks them required only for that shape).
      auto shape_key = [&](const char* k) {
        rd.need(n, k, key);
        return m.number(k);
      };
      const double E = m.number("E"), nu = m.number("nu"), rho = m.number("rho");
      SectionShape s;
      switch (m.choice("shape")) {
        case 0: s = SectionShape::rectangle(shape_key("width"), shape_key("height")); break;
        case 1: s = SectionShape::circle(shape_key("diameter")); break;
        default: s = SectionShape::tube(shape_key("diameter"), shape_key("wall_thickness"));
      }
      return BeamSection::from_material(E, nu, rho, s);
    }
    const Section p(rd, n, key, properties_schema());
    std::optional<double> polar;
    if (p.has("rhoI_polar")) polar = p.number("rhoI_polar");
    return BeamSection::from_properties(p.number("EA"), p.number("GA2"), p.number("GA3"), p.number("GJ"), p.number("EI2"),
                                        p.number("EI3"), p.number("rhoA"), p.number("rhoI2"), p.number("rhoI3"), polar);
  } catch (const std::invalid_argument& e) {
    rd.fail(n, key, e.what());
  }
}

void register_beams_3d(SceneTypes& t) {
  t.blocks.add("beams", Schema{"beams.3d", {
      {"name", KeyType::Text, "–", kRequired, "elements are named NAME[0], NAME[1], … in mesh order"},
      {"group", KeyType::Text, "–", kRequired, "a physical curve group of the mesh, used by one beam only"},
      {"section", KeyType::Map, "–", kRequired, "`beams.section.material` or `beams.section.properties`"},
      {"orientation", KeyType::Vec3, "–", kRequired, "direction of the section's axis 2 (projected ⊥ to each element); not parallel to an element"},
      {"reduction", KeyType::Map, "–", "– (the full mesh)", "`beams.reduction`: the block as one reduced flexible body (docs/theory/reduced_bodies.md)"},
      {"damping", KeyType::Number, "s", "0", "η: Kelvin–Voigt material damping, section forces C (ε + η ε̇); a bending mode of frequency ω gets ζ = ηω/2 (docs/theory/beam.md); not with `reduction`", Range::non_negative(), "material damping (s)"}}},
      {"name, group, section, orientation", read_beam_block_3d});
  t.parts.push_back(&material_schema());
  t.parts.push_back(&properties_schema());
  t.parts.push_back(&reduction_schema());
}

}  // namespace alphaflex::scene_detail
