// `shells` (spatial): a block of Reissner–Mindlin shells (MITC4 quadrilaterals, MITC3 triangles)
// on a physical surface group of the mesh, isotropic (thickness and material) or a laminate.
#include <sstream>

#include "alphaflex/elements/shell.hpp"
#include "common.hpp"
#include "reduced_beams_3d.hpp"

namespace alphaflex::scene_detail {
namespace {

const Schema& material_schema() {
  static const Schema s{"shells.material", {
      {"E", KeyType::Number, "Pa", kRequired, "Young's modulus", Range::positive(), "Young's modulus (Pa)"},
      {"nu", KeyType::Number, "–", kRequired, "Poisson's ratio; −1 < ν < 0.5"},
      {"rho", KeyType::Number, "kg/m³", kRequired, "density; ≥ 0"}}};
  return s;
}

const Schema& laminate_schema() {
  static const Schema s{"shells.section", {
      {"A", KeyType::List, "N/m", kRequired, "membrane stiffness, 3×3 rows, Voigt order (11, 22, 12)", {}, "", "3×3 list of rows"},
      {"B", KeyType::List, "N", "zero", "membrane–bending coupling, 3×3 rows", {}, "", "3×3 list of rows"},
      {"D", KeyType::List, "N·m", kRequired, "bending stiffness, 3×3 rows", {}, "", "3×3 list of rows"},
      {"As", KeyType::List, "N/m", kRequired, "transverse shear stiffness, 2×2 rows", {}, "", "2×2 list of rows"},
      {"thickness", KeyType::Number, "m", kRequired, "laminate thickness", Range::positive(), "thickness (m)"},
      {"mass", KeyType::Number, "kg/m²", kRequired, "mass per area"},
      {"rotary", KeyType::Number, "kg", kRequired, "rotary inertia per area"}}};
  return s;
}

/// The shell section: `thickness` and `material: {E, nu, rho}`, or a laminate
/// `section: {A, B, D, As, thickness, mass, rotary}` (matrices as nested lists).
ShellSection read_shell_section(const Item& it) {
  const Reader& rd = it.rd;
  const Section& k = it.keys;
  auto matrix = [&](const YAML::Node& n, const std::string& key, int size, const char* unit) {
    Eigen::MatrixXd M(size, size);
    if (!n || !n.IsSequence() || static_cast<int>(n.size()) != size)
      rd.fail(n, key, "expected a " + std::to_string(size) + "x" + std::to_string(size) + " matrix as a list of rows (" + unit + ")");
    for (int r = 0; r < size; ++r) {
      const YAML::Node row = n[static_cast<size_t>(r)];
      if (!row.IsSequence() || static_cast<int>(row.size()) != size)
        rd.fail(row, key, "row " + std::to_string(r + 1) + ": expected " + std::to_string(size) + " numbers");
      for (int c = 0; c < size; ++c) M(r, c) = rd.number(row[static_cast<size_t>(c)], key + "[" + std::to_string(r) + "][" + std::to_string(c) + "]");
    }
    return M;
  };
  try {
    if (k.has("section")) {
      const YAML::Node sec = k.node("section");
      if (k.has("material") || k.has("thickness"))
        rd.fail(sec, it.at("section"), "give either thickness and material, or a laminate section (with its own thickness)");
      const std::string key = it.at("section");
      if (!sec.IsMap()) rd.fail(sec, key, "expected a map {A, B, D, As, thickness, mass, rotary}");
      const Section laminate(rd, sec, key, laminate_schema());
      const Eigen::Matrix3d A = matrix(laminate.node("A"), key + ".A", 3, "N/m");
      const Eigen::Matrix3d B = laminate.has("B") ? Eigen::Matrix3d(matrix(laminate.node("B"), key + ".B", 3, "N")) : Eigen::Matrix3d::Zero();
      const Eigen::Matrix3d D = matrix(laminate.node("D"), key + ".D", 3, "N m");
      const Eigen::Matrix2d As = matrix(laminate.node("As"), key + ".As", 2, "N/m");
      const double t = laminate.number("thickness"), mass = laminate.number("mass"), rotary = laminate.number("rotary");
      return ShellSection::laminate(A, B, D, As, t, mass, rotary);
    }
    auto need = [&](const char* key) {  // required unless `section`
      if (!k.has(key)) rd.fail(it.node, it.at(key), "missing (required)");
    };
    need("thickness");
    const double t = k.number("thickness");
    need("material");
    const YAML::Node m = k.node("material");
    if (!m.IsMap()) rd.fail(m, it.at("material"), "expected a map {E, nu, rho}");
    const Section material(rd, m, it.at("material"), material_schema());
    const double E = material.number("E"), nu = material.number("nu"), rho = material.number("rho");
    return ShellSection::isotropic(E, nu, rho, t);
  } catch (const std::invalid_argument& e) {
    rd.fail(k.has("section") ? k.node("section") : k.has("material") ? k.node("material") : it.node, it.path, e.what());
  }
}

/// Adds the shell elements of `block` to `model` (named ITEM[e], in the group's order), their nodes
/// given by `node_of`; returns their indices in model.elements().
std::vector<int> add_shell_elements(const Item& it, const MeshSurfaceBlock& block, const ShellSection& section, Model& model,
                                    const BlockNodeOf& node_of) {
  constexpr double kPi = 3.14159265358979323846;
  const Section& k = it.keys;
  std::vector<int> ids;
  ShellOptions options;
  options.drilling_factor = k.number("drilling", options.drilling_factor);
  options.director_interpolation = k.choice("director_interpolation", 0) == 0 ? DirectorInterpolation::linear
                                                                            : DirectorInterpolation::geodesic;
  options.membrane_edges = k.choice("membrane_edges", 0) == 0 ? MembraneEdges::chord : MembraneEdges::arc;
  const double kink = k.number("kink_angle", 20.0);
  const bool axis_given = k.has("material_axis");
  const Eigen::Vector3d axis = it.sb.blocks.placed(k.text("group"), k.direction("material_axis", Eigen::Vector3d::UnitX()));
  const MeshData& mesh = it.sb.blocks.mesh;
  std::vector<std::vector<Eigen::Vector3d>> dirs;
  try {
    dirs = shell_directors(mesh.points, block.elements, kink * kPi / 180.0);
  } catch (const std::invalid_argument& e) {
    it.rd.fail(k.node("group"), it.at("group"), e.what());
  }
  for (size_t e = 0; e < block.elements.size(); ++e) {
    std::vector<int> nodes;
    for (int m : block.elements[e]) {
      Eigen::VectorXd q0(7);
      store_pose(mesh.points[static_cast<size_t>(m)], Eigen::Matrix3d::Identity(), q0.data());
      nodes.push_back(node_of(m, q0));
    }
    std::vector<Pose<double>> ref;
    for (int n : nodes) ref.push_back(pose_of(model.node(n).q0.data()));
    auto make = [&](const Eigen::Vector3d& a) {
      return std::make_unique<ReissnerMindlinShell>(it.name + "[" + std::to_string(e) + "]", nodes, section, ref, dirs[e], a,
                                                    it.sb.gravity, options);
    };
    try {
      std::unique_ptr<ReissnerMindlinShell> el;
      try {
        el = make(axis);
      } catch (const std::invalid_argument&) {
        // The default axis (x) along an element's normal: y, then z, unless the user gave one.
        if (axis_given) throw;
        try {
          el = make(Eigen::Vector3d::UnitY());
        } catch (const std::invalid_argument&) {
          el = make(Eigen::Vector3d::UnitZ());
        }
      }
      ids.push_back(static_cast<int>(model.elements().size()));
      model.add_element(std::move(el));
    } catch (const std::invalid_argument& ex) {
      std::ostringstream os;
      os << "element " << block.element_tags[e] << " of group '" << block.name << "': " << ex.what();
      const bool axis_error = axis_given && std::string(ex.what()).find("material axis") != std::string::npos;
      it.rd.fail(axis_error ? k.node("material_axis") : k.node("group"), it.at(axis_error ? "material_axis" : "group"), os.str());
    }
  }
  return ids;
}

// The part of a shell block in a reduced body (types/reduced_beams_3d.hpp).
BlockPart shell_part(const Item& it) {
  const MeshSurfaceBlock& block = mesh_block(it, it.sb.blocks.mesh.surface_blocks, "surface", "beam or shell");
  const ShellSection section = read_shell_section(it);
  return {mesh_nodes_of(block.elements), block.name, [&it, &block, section](Model& model, const BlockNodeOf& node_of) {
            return add_shell_elements(it, block, section, model, node_of);
          }};
}

void read_shell_block(const Item& it) {
  // A block that `reduction.blocks` of another names is built by that reduced block (its part).
  if (it.sb.blocks.absorbed.count(it.name)) return;
  // `reduction` (issue 19): the shell block as one reduced body, the superelement from the
  // shell mesh's own M and K at the reference (types/reduced_beams_3d.cpp).
  if (it.keys.has("reduction")) return read_reduced_block_3d(it, shell_part);
  const MeshSurfaceBlock& block = mesh_block(it, it.sb.blocks.mesh.surface_blocks, "surface", "beam or shell");
  const ShellSection section = read_shell_section(it);
  add_shell_elements(it, block, section, it.model,
                     [&](int m, const Eigen::VectorXd& q0) { return block_node(it, m, NodeKind::Frame3D, q0, Eigen::VectorXd::Zero(6)); });
}

}  // namespace

void register_shells_3d(SceneTypes& t) {
  t.blocks.add("shells", Schema{"shells", {
      {"name", KeyType::Text, "–", kRequired, "elements are named NAME[0], NAME[1], … in the group's element order"},
      {"group", KeyType::Text, "–", kRequired, "a physical surface group, used by one beam or shell block only"},
      {"thickness", KeyType::Number, "m", "**required** (unless `section`)", "shell thickness", Range::positive(), "thickness (m)"},
      {"material", KeyType::Map, "Pa, –, kg/m³", "**required** (unless `section`)", "`{E, nu, rho}`: isotropic, E > 0, −1 < ν < 0.5, ρ ≥ 0"},
      {"section", KeyType::Map, "–", "–", "a laminate instead of `thickness` and `material` (`shells.section`)"},
      {"material_axis", KeyType::Vec3, "–", "[1, 0, 0]", "material axis 1, projected onto each element"},
      {"drilling", KeyType::Number, "–", "1e-3", "drilling penalty stiffness as a fraction of G·t per area (docs/theory/shell.md)", Range::positive(), "drilling stiffness factor (of G t)"},
      {"kink_angle", KeyType::Number, "°", "20", "an element whose normal at a node is further than this from the nodes' mean normal keeps its own director there (folds, T-junctions)", Range::positive(), "angle (degrees)"},
      {"director_interpolation", KeyType::Choice, "–", "linear", "how the bending strains see the director's turn between nodes: `geodesic` (arc length along each edge, exact for constant curvature) or `linear` (chord: curvature 2 sin(φ/2)/L_e for a turn φ per element; docs/theory/shell.md)", {}, "", "", {"linear", "geodesic"}},
      {"membrane_edges", KeyType::Choice, "–", "chord", "how the element measures its edges, in the membrane strains and in the tangents of the bending and shear strains: `chord` (the distance between the nodes: bending by a turn φ per element shortens it by ≈ φ²/24) or `arc` (the circular arc whose end normals are the directors: inextensible bending leaves the membrane unstrained; best with `director_interpolation: geodesic`; docs/theory/shell.md)", {}, "", "", {"chord", "arc"}},
      {"reduction", KeyType::Map, "–", "– (the full mesh)", "`beams.reduction` (the same keys; interface points: named mesh points of the surface): the block as one reduced flexible body (docs/theory/reduced_bodies.md)"}}},
      {"name, group, thickness, material", read_shell_block});
  t.parts.push_back(&material_schema());
  t.parts.push_back(&laminate_schema());
}

}  // namespace alphaflex::scene_detail
