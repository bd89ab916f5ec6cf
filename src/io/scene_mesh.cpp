// Beams and shells from gmsh meshes (`mesh`, `beams`, `shells`): physical line groups become beam
// blocks (two-node geometrically exact beams), physical surface groups shell blocks (MITC4/MITC3
// Reissner–Mindlin shells), their mesh nodes become spatial frame nodes shared where beams and
// shells meet, named mesh points become nodes that joints, loads and sensors refer to by name, and
// every physical group is kept (as model nodes) for joints and loads given on a group.
#include <filesystem>
#include <unordered_set>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "alphaflex/elements/planar_beam.hpp"
#include "alphaflex/elements/shell.hpp"
#include "alphaflex/mesh/gmsh_reader.hpp"
#include "alphaflex/model/model.hpp"
#include "scene_reader.hpp"

namespace alphaflex::scene_detail {
namespace {

// Key schemas of the mesh sections (docs/input.md, generated tables).
const Schema kBeamMaterial{"beams.section.material", {
    {"E", KeyType::Number, "Pa", kRequired, "Young's modulus", Range::positive(), "Young's modulus (Pa)"},
    {"nu", KeyType::Number, "–", kRequired, "Poisson's ratio (G = E/(2(1 + ν))), in (−1, 0.5)"},
    {"rho", KeyType::Number, "kg/m³", kRequired, "density", Range::positive(), "density (kg/m^3)"},
    {"shape", KeyType::Choice, "–", kRequired, "cross-section shape", {}, "", "", {"rectangle", "circle", "tube"}},
    {"width", KeyType::Number, "m", "– (**required** for `rectangle`)", "along section axis 2", Range::positive(), "width (m)"},
    {"height", KeyType::Number, "m", "– (**required** for `rectangle`)", "along section axis 3", Range::positive(), "height (m)"},
    {"diameter", KeyType::Number, "m", "– (**required** for `circle`, `tube`)", "outer diameter", Range::positive(), "diameter (m)"},
    {"wall_thickness", KeyType::Number, "m", "– (**required** for `tube`)", "at most the radius", Range::positive(), "wall thickness (m)"}}};
const Schema kBeamProperties{"beams.section.properties", {
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
const Schema kPlanarSection{"beams.2d.section", {
    {"EA", KeyType::Number, "N", kRequired, "axial stiffness", Range::positive(), "axial stiffness (N)"},
    {"GA", KeyType::Number, "N", kRequired, "in-plane shear stiffness", Range::positive(), "shear stiffness (N)"},
    {"EI", KeyType::Number, "N·m²", kRequired, "bending stiffness in the plane", Range::positive(), "bending stiffness (N m^2)"},
    {"rhoA", KeyType::Number, "kg/m", kRequired, "mass per length", Range::positive(), "mass per length (kg/m)"},
    {"rhoI", KeyType::Number, "kg·m", kRequired, "rotary inertia per length", Range::positive(), "rotary inertia per length (kg m)"}}};
const Schema kMesh{"mesh", {
    {"file", KeyType::Text, "–", kRequired, "a .geo or .msh, relative to the scene file's directory"},
    {"elements", KeyType::Integer, "–", "the .geo's own", "every curve of a .geo meshed with this many equal elements (not with `element_size`; not for .msh)", Range::closed(1, 10000000)},
    {"element_size", KeyType::Number, "m", "the .geo's own", "largest element length of a .geo", Range::positive(), "element size (m)"},
    {"parameters", KeyType::Map, "as the .geo says", "the .geo's defaults", "values of the .geo's `DefineConstant[ x = {v, Name \"x\"} ]`"}}};
const Schema kBeams3d{"beams.3d", {
    {"name", KeyType::Text, "–", kRequired, "elements are named NAME[0], NAME[1], … in mesh order"},
    {"group", KeyType::Text, "–", kRequired, "a physical curve group of the mesh, used by one beam only"},
    {"section", KeyType::Map, "–", kRequired, "`beams.section.material` or `beams.section.properties`"},
    {"orientation", KeyType::Vec3, "–", kRequired, "direction of the section's axis 2 (projected ⊥ to each element); not parallel to an element"}}};
const Schema kBeams2d{"beams.2d", {
    {"name", KeyType::Text, "–", kRequired, "elements are named NAME[0], NAME[1], … in mesh order"},
    {"group", KeyType::Text, "–", kRequired, "a physical curve group of the mesh (in the x-y plane), used by one beam only"},
    {"section", KeyType::Map, "–", kRequired, "`beams.2d.section` or `beams.section.material`"}}};
const Schema kShells{"shells", {
    {"name", KeyType::Text, "–", kRequired, "elements are named NAME[0], NAME[1], … in the group's element order"},
    {"group", KeyType::Text, "–", kRequired, "a physical surface group, used by one beam or shell block only"},
    {"thickness", KeyType::Number, "m", "**required** (unless `section`)", "shell thickness", Range::positive(), "thickness (m)"},
    {"material", KeyType::Map, "Pa, –, kg/m³", "**required** (unless `section`)", "`{E, nu, rho}`: isotropic, E > 0, −1 < ν < 0.5, ρ ≥ 0"},
    {"section", KeyType::Map, "–", "–", "a laminate instead of `thickness` and `material` (`shells.section`)"},
    {"material_axis", KeyType::Vec3, "–", "[1, 0, 0]", "material axis 1, projected onto each element"},
    {"drilling", KeyType::Number, "–", "1e-3", "drilling penalty stiffness as a fraction of G·t per area (docs/theory/shell.md)", Range::positive(), "drilling stiffness factor (of G t)"},
    {"kink_angle", KeyType::Number, "°", "20", "an element whose normal at a node is further than this from the nodes' mean normal keeps its own director there (folds, T-junctions)", Range::positive(), "angle (degrees)"}}};
const Schema kShellMaterial{"shells.material", {
    {"E", KeyType::Number, "Pa", kRequired, "Young's modulus", Range::positive(), "Young's modulus (Pa)"},
    {"nu", KeyType::Number, "–", kRequired, "Poisson's ratio; −1 < ν < 0.5"},
    {"rho", KeyType::Number, "kg/m³", kRequired, "density; ≥ 0"}}};
const Schema kShellLaminate{"shells.section", {
    {"A", KeyType::List, "N/m", kRequired, "membrane stiffness, 3×3 rows, Voigt order (11, 22, 12)", {}, "", "3×3 list of rows"},
    {"B", KeyType::List, "N", "zero", "membrane–bending coupling, 3×3 rows", {}, "", "3×3 list of rows"},
    {"D", KeyType::List, "N·m", kRequired, "bending stiffness, 3×3 rows", {}, "", "3×3 list of rows"},
    {"As", KeyType::List, "N/m", kRequired, "transverse shear stiffness, 2×2 rows", {}, "", "2×2 list of rows"},
    {"thickness", KeyType::Number, "m", kRequired, "laminate thickness", Range::positive(), "thickness (m)"},
    {"mass", KeyType::Number, "kg/m²", kRequired, "mass per area"},
    {"rotary", KeyType::Number, "kg", kRequired, "rotary inertia per area"}}};


BeamSection read_section(Reader& rd, const YAML::Node& n, const std::string& key) {
  if (!n.IsMap()) rd.fail(n, key, "expected a map of section properties");
  try {
    if (n["E"] || n["shape"]) {
      const Section m(rd, n, key, kBeamMaterial);
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
    const Section p(rd, n, key, kBeamProperties);
    std::optional<double> polar;
    if (p.has("rhoI_polar")) polar = p.number("rhoI_polar");
    return BeamSection::from_properties(p.number("EA"), p.number("GA2"), p.number("GA3"), p.number("GJ"), p.number("EI2"),
                                        p.number("EI3"), p.number("rhoA"), p.number("rhoI2"), p.number("rhoI3"), polar);
  } catch (const std::invalid_argument& e) {
    rd.fail(n, key, e.what());
  }
}

/// Reads `mesh` (path relative to the scene file) with the scene's options.
MeshData load_mesh(Reader& rd, const YAML::Node& mn) {
  const Section m(rd, mn, "mesh", kMesh);
  const YAML::Node fn = m.node("file");
  const std::string given = m.text("file");
  // Relative to the scene file's directory (inputs/x.yaml names ../meshes/y.geo).
  std::filesystem::path path(given);
  if (path.is_relative()) path = std::filesystem::path(rd.file()).parent_path() / path;
  MeshOptions opt;
  if (m.has("elements")) opt.elements_per_curve = m.integer("elements");
  if (m.has("element_size")) opt.element_size = m.number("element_size");
  if (const YAML::Node p = mn["parameters"]) {
    if (!p.IsMap()) rd.fail(p, "mesh.parameters", "expected a map name: value (DefineConstant names of the .geo)");
    for (const auto& kv : p) {
      const std::string k = rd.key_name(kv.first, "mesh.parameters");
      // yaml-cpp keeps both entries of a repeated key; the last would silently win here.
      if (opt.parameters.count(k)) rd.fail(kv.first, "mesh.parameters." + k, "given twice");
      opt.parameters[k] = rd.number(kv.second, "mesh.parameters." + k);
    }
  }
  std::ostringstream ctx;
  ctx << rd.file() << ":" << (fn.Mark().line + 1) << ": mesh.file";
  return rd.mesh(path.string(), opt, ctx.str());
}

/// The line block named by a beam's `group`, or a clear error listing the mesh's curve groups.
const MeshLineBlock& find_group(Reader& rd, const MeshData& mesh, const YAML::Node& b, const std::string& path_b,
                                const std::string& group) {
  const MeshLineBlock* block = mesh.find_line_block(group);
  if (!block) {
    std::string known;
    for (const auto& lb : mesh.line_blocks) known += (known.empty() ? "" : ", ") + lb.name;
    rd.fail(b["group"], path_b + ".group",
            "mesh '" + mesh.file + "' has no physical curve group '" + group + "' (its curve groups: " +
                (known.empty() ? "none" : known) + ")");
  }
  return *block;
}

/// Named points must be beam nodes: a point on no beam would be a node nothing holds.
void check_named_points(Reader& rd, const YAML::Node& mn, const MeshData& mesh, const std::vector<int>& node_of) {
  for (const auto& [pname, id] : mesh.named_points)
    if (node_of[static_cast<size_t>(id)] < 0)
      rd.fail(mn["file"], "mesh.file",
              "named point '" + pname + "' is on none of the beams' or shells' groups (an unconnected node); put it on a beam's curve or a shell's surface, or remove it");
  for (const auto& [pname, ids] : mesh.point_groups)
    for (int id : ids)
      if (node_of[static_cast<size_t>(id)] < 0)
        rd.fail(mn["file"], "mesh.file",
                "point group '" + pname + "' holds mesh node " + std::to_string(mesh.node_tags[static_cast<size_t>(id)]) +
                    ", which is on none of the beams' or shells' groups (an unconnected node); every point of a point group must be on a beam's curve or a shell's surface");
}


/// The shell section of a `shells` entry: `thickness` and `material: {E, nu, rho}`, or a laminate
/// `section: {A, B, D, As, thickness, mass, rotary}` (matrices as nested lists).
ShellSection read_shell_section(Reader& rd, const YAML::Node& s, const std::string& path) {
  auto matrix = [&](const YAML::Node& n, const std::string& key, int size, const char* unit) {
    Eigen::MatrixXd M(size, size);
    if (!n || !n.IsSequence() || static_cast<int>(n.size()) != size)
      rd.fail(n ? n : s, key, "expected a " + std::to_string(size) + "x" + std::to_string(size) + " matrix as a list of rows (" + unit + ")");
    for (int r = 0; r < size; ++r) {
      const YAML::Node row = n[static_cast<size_t>(r)];
      if (!row.IsSequence() || static_cast<int>(row.size()) != size)
        rd.fail(row, key, "row " + std::to_string(r + 1) + ": expected " + std::to_string(size) + " numbers");
      for (int c = 0; c < size; ++c) M(r, c) = rd.number(row[static_cast<size_t>(c)], key + "[" + std::to_string(r) + "][" + std::to_string(c) + "]");
    }
    return M;
  };
  try {
    if (const YAML::Node sec = s["section"]) {
      if (s["material"] || s["thickness"])
        rd.fail(sec, path + ".section", "give either thickness and material, or a laminate section (with its own thickness)");
      const std::string key = path + ".section";
      if (!sec.IsMap()) rd.fail(sec, key, "expected a map {A, B, D, As, thickness, mass, rotary}");
      const Section laminate(rd, sec, key, kShellLaminate);
      const Eigen::Matrix3d A = matrix(sec["A"], key + ".A", 3, "N/m");
      const Eigen::Matrix3d B = sec["B"] ? Eigen::Matrix3d(matrix(sec["B"], key + ".B", 3, "N")) : Eigen::Matrix3d::Zero();
      const Eigen::Matrix3d D = matrix(sec["D"], key + ".D", 3, "N m");
      const Eigen::Matrix2d As = matrix(sec["As"], key + ".As", 2, "N/m");
      const double t = laminate.number("thickness"), mass = laminate.number("mass"), rotary = laminate.number("rotary");
      return ShellSection::laminate(A, B, D, As, t, mass, rotary);
    }
    const Section shell(rd, s, path, kShells);
    rd.need(s, "thickness", path);  // required unless `section`
    const double t = shell.number("thickness");
    const YAML::Node m = rd.need(s, "material", path);
    if (!m.IsMap()) rd.fail(m, path + ".material", "expected a map {E, nu, rho}");
    const Section material(rd, m, path + ".material", kShellMaterial);
    const double E = material.number("E"), nu = material.number("nu"), rho = material.number("rho");
    return ShellSection::isotropic(E, nu, rho, t);
  } catch (const std::invalid_argument& e) {
    rd.fail(s["section"] ? s["section"] : s["material"] ? s["material"] : s, path, e.what());
  }
}

/// `shells`: one block of ReissnerMindlinShell elements per physical surface group.
void read_shells(Reader& rd, const YAML::Node& sl, const MeshData& mesh, Model& model, const Eigen::Vector3d& gravity,
                 std::vector<int>& node_of, const std::map<int, std::string>& point_name,
                 std::set<std::string>& groups_used) {
  constexpr double kPi = 3.14159265358979323846;
  if (!sl.IsSequence() || sl.size() == 0) rd.fail(sl, "shells", "expected a list of shells");
  std::set<std::string> names;
  for (size_t i = 0; i < sl.size(); ++i) {
    const YAML::Node s = sl[i];
    std::string path = "shells[" + std::to_string(i) + "]";
    if (!s.IsMap()) rd.fail(s, path, "expected a map with name, group, thickness, material");
    rd.keys(s, path, kShells);
    const std::string name = rd.text(rd.need(s, "name", path), path + ".name");
    path = "shells[" + name + "]";
    if (!names.insert(name).second) rd.fail(s["name"], path + ".name", "a shell named '" + name + "' exists already");
    const std::string group = rd.text(rd.need(s, "group", path), path + ".group");
    const MeshSurfaceBlock* block = mesh.find_surface_block(group);
    if (!block) {
      std::string known;
      for (const auto& b : mesh.surface_blocks) known += (known.empty() ? "" : ", ") + b.name;
      rd.fail(s["group"], path + ".group", "mesh '" + mesh.file + "' has no physical surface group '" + group +
                                               "' (its surface groups: " + (known.empty() ? "none" : known) + ")");
    }
    if (!groups_used.insert(group).second) rd.fail(s["group"], path + ".group", "group '" + group + "' is used by another beam or shell already");
    const ShellSection section = read_shell_section(rd, s, path);
    ShellOptions options;
    const Section shell(rd, s, path, kShells);
    options.drilling_factor = shell.number("drilling", options.drilling_factor);
    const double kink = shell.number("kink_angle", 20.0);
    const bool axis_given = static_cast<bool>(s["material_axis"]);
    const Eigen::Vector3d axis = axis_given ? rd.direction(s["material_axis"], path + ".material_axis") : Eigen::Vector3d::UnitX();
    std::vector<std::vector<Eigen::Vector3d>> dirs;
    try {
      dirs = shell_directors(mesh.points, block->elements, kink * kPi / 180.0);
    } catch (const std::invalid_argument& e) {
      rd.fail(s["group"], path + ".group", e.what());
    }
    for (size_t e = 0; e < block->elements.size(); ++e) {
      std::vector<int> nodes;
      for (int m : block->elements[e]) {
        if (node_of[static_cast<size_t>(m)] < 0) {
          Node nd;
          nd.kind = NodeKind::Frame3D;
          const auto pn = point_name.find(m);
          nd.name = pn != point_name.end() ? pn->second : name + ":" + std::to_string(mesh.node_tags[static_cast<size_t>(m)]);
          if (model.find_node(nd.name) >= 0) rd.fail(s, path, "mesh point '" + nd.name + "' has the name of another node or body");
          nd.q0.resize(7);
          store_pose(mesh.points[static_cast<size_t>(m)], Eigen::Matrix3d::Identity(), nd.q0.data());
          nd.v0 = Eigen::VectorXd::Zero(6);
          node_of[static_cast<size_t>(m)] = model.add_node(nd);
        }
        nodes.push_back(node_of[static_cast<size_t>(m)]);
      }
      std::vector<Pose<double>> ref;
      for (int n : nodes) ref.push_back(pose_of(model.node(n).q0.data()));
      auto make = [&](const Eigen::Vector3d& a) {
        return std::make_unique<ReissnerMindlinShell>(name + "[" + std::to_string(e) + "]", nodes, section, ref, dirs[e], a,
                                                      gravity, options);
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
        model.add_element(std::move(el));
      } catch (const std::invalid_argument& ex) {
        std::ostringstream os;
        os << "element " << block->element_tags[e] << " of group '" << group << "': " << ex.what();
        rd.fail(axis_given && std::string(ex.what()).find("material axis") != std::string::npos ? s["material_axis"] : s["group"],
                path + (axis_given && std::string(ex.what()).find("material axis") != std::string::npos ? ".material_axis" : ".group"),
                os.str());
      }
    }
  }
}

/// Every physical group of the mesh in terms of model nodes (−1 for nodes nothing uses).
void keep_groups(SceneBuilder& sb, const MeshData& mesh, const std::vector<int>& node_of) {
  // Which model nodes each group holds already (a set per group: groups of 10⁵ nodes are read in
  // linear time).
  std::map<const MeshGroup*, std::unordered_set<int>> seen;
  auto add_nodes = [&](MeshGroup& g, const std::vector<int>& mesh_nodes) {
    std::vector<int> el;
    std::unordered_set<int>& in = seen[&g];
    for (int m : mesh_nodes) {
      const int n = node_of[static_cast<size_t>(m)];
      el.push_back(n);
      if (n < 0 || in.insert(n).second) {
        g.nodes.push_back(n);
        g.points.push_back(mesh.points[static_cast<size_t>(m)]);
      }
    }
    return el;
  };
  for (const auto& b : mesh.line_blocks) {
    MeshGroup& g = sb.mesh_groups[b.name];
    g.dim = 1;
    for (const auto& seg : b.elements) g.elements.push_back(add_nodes(g, {seg[0], seg[1]}));
  }
  for (const auto& b : mesh.surface_blocks) {
    MeshGroup& g = sb.mesh_groups[b.name];
    g.dim = 2;
    for (const auto& el : b.elements) g.elements.push_back(add_nodes(g, el));
    g.shells = true;
    for (const auto& el : g.elements)
      for (int n : el) g.shells = g.shells && n >= 0;
  }
  for (const auto& [name, m] : mesh.named_points) {
    MeshGroup& g = sb.mesh_groups[name];
    g.dim = 0;
    add_nodes(g, {m});
  }
  for (const auto& [name, ids] : mesh.point_groups) {
    MeshGroup& g = sb.mesh_groups[name];
    g.dim = 0;
    add_nodes(g, ids);
  }
}

}  // namespace

void read_mesh_and_beams(Reader& rd, SceneBuilder& sb, const YAML::Node& root, Model& model,
                         const Eigen::Vector3d& gravity) {
  const YAML::Node mn = root["mesh"], bl = root["beams"], sl = root["shells"];
  if (!mn && !bl && !sl) return;
  if (!mn) rd.fail(bl ? bl : sl, bl ? "beams" : "shells", "beams and shells need a `mesh` (a .geo or .msh file with their physical groups)");
  if (!bl && !sl)
    rd.fail(mn, "mesh", "no `beams` or `shells` use this mesh (give beams: [{name, group, section, orientation}] or shells: [{name, group, thickness, material}])");
  const MeshData mesh = load_mesh(rd, mn);
  sb.mesh_file = mesh.file;
  if (bl && (!bl.IsSequence() || bl.size() == 0)) rd.fail(bl, "beams", "expected a list of beams");
  std::vector<int> node_of(mesh.points.size(), -1);  // mesh node → model node
  std::map<int, std::string> point_name;
  for (const auto& [name, id] : mesh.named_points) point_name[id] = name;
  std::set<std::string> beam_names, groups_used;
  for (size_t i = 0; bl && i < bl.size(); ++i) {
    const YAML::Node b = bl[i];
    std::string path_b = "beams[" + std::to_string(i) + "]";
    if (!b.IsMap()) rd.fail(b, path_b, "expected a map with name, group, section, orientation");
    rd.keys(b, path_b, kBeams3d);
    const std::string name = rd.text(rd.need(b, "name", path_b), path_b + ".name");
    path_b = "beams[" + name + "]";
    if (!beam_names.insert(name).second) rd.fail(b["name"], path_b + ".name", "a beam named '" + name + "' exists already");
    const std::string group = rd.text(rd.need(b, "group", path_b), path_b + ".group");
    const MeshLineBlock* block = &find_group(rd, mesh, b, path_b, group);
    if (!groups_used.insert(group).second)
      rd.fail(b["group"], path_b + ".group", "group '" + group + "' is used by another beam already");
    const BeamSection section = read_section(rd, rd.need(b, "section", path_b), path_b + ".section");
    const Eigen::Vector3d orient = rd.direction(rd.need(b, "orientation", path_b), path_b + ".orientation");
    for (size_t e = 0; e < block->elements.size(); ++e) {
      const int ma = block->elements[e][0], mb = block->elements[e][1];
      const Eigen::Vector3d xa = mesh.points[static_cast<size_t>(ma)], xb = mesh.points[static_cast<size_t>(mb)];
      Eigen::Matrix3d sec;
      if (!frame_from(xb - xa, orient, sec)) {
        std::ostringstream os;
        os << "is parallel to element " << block->element_tags[e] << " of group '" << group << "' (or the element has zero length); "
           << "the orientation vector fixes section axis 2 and must not lie along the beam";
        rd.fail(b["orientation"], path_b + ".orientation", os.str());
      }
      // Model nodes for the mesh nodes (once each; a node's frame is the section frame of the
      // first element that reaches it, and each element keeps its own offset from it).
      for (int m : {ma, mb}) {
        if (node_of[static_cast<size_t>(m)] >= 0) continue;
        Node nd;
        nd.kind = NodeKind::Frame3D;
        const auto pn = point_name.find(m);
        nd.name = pn != point_name.end() ? pn->second : name + ":" + std::to_string(mesh.node_tags[static_cast<size_t>(m)]);
        if (model.find_node(nd.name) >= 0)
          rd.fail(b, path_b, "mesh point '" + nd.name + "' has the name of another node or body");
        nd.q0.resize(7);
        store_pose(mesh.points[static_cast<size_t>(m)], sec, nd.q0.data());
        nd.v0 = Eigen::VectorXd::Zero(6);
        node_of[static_cast<size_t>(m)] = model.add_node(nd);
      }
      const int na = node_of[static_cast<size_t>(ma)], nb = node_of[static_cast<size_t>(mb)];
      try {
        model.add_element(std::make_unique<GeometricallyExactBeam>(
            name + "[" + std::to_string(e) + "]", na, nb, section, pose_of(model.node(na).q0.data()),
            pose_of(model.node(nb).q0.data()), sec, sec, gravity));
      } catch (const std::invalid_argument& ex) {
        std::ostringstream os;
        os << "element " << block->element_tags[e] << " of group '" << group << "': " << ex.what();
        rd.fail(b["group"], path_b + ".group", os.str());
      }
    }
  }
  if (sl) read_shells(rd, sl, mesh, model, gravity, node_of, point_name, groups_used);
  check_named_points(rd, mn, mesh, node_of);
  keep_groups(sb, mesh, node_of);
}

void read_planar_mesh_and_beams(Reader& rd, const YAML::Node& root, Model& model, const Eigen::Vector2d& gravity) {
  const YAML::Node mn = root["mesh"], bl = root["beams"];
  if (!mn && !bl) return;
  if (!mn) rd.fail(bl, "beams", "beams need a `mesh` (a .geo or .msh file with their physical groups)");
  if (!bl) rd.fail(mn, "mesh", "no `beams` use this mesh (give beams: [{name, group, section}])");
  const MeshData mesh = load_mesh(rd, mn);
  for (size_t k = 0; k < mesh.points.size(); ++k)
    if (std::fabs(mesh.points[k].z()) > 1e-12 * std::max(1.0, mesh.points[k].norm()))
      rd.fail(mn["file"], "mesh.file",
              "node " + std::to_string(mesh.node_tags[k]) + " is not in the x-y plane (z = " +
                  std::to_string(mesh.points[k].z()) + "); a planar scene needs a planar mesh (or use dimension: 3)");
  if (!bl.IsSequence() || bl.size() == 0) rd.fail(bl, "beams", "expected a list of beams");
  std::vector<int> node_of(mesh.points.size(), -1);
  std::map<int, std::string> point_name;
  for (const auto& [name, id] : mesh.named_points) point_name[id] = name;
  std::set<std::string> beam_names, groups_used;
  for (size_t i = 0; i < bl.size(); ++i) {
    const YAML::Node b = bl[i];
    std::string path_b = "beams[" + std::to_string(i) + "]";
    if (!b.IsMap()) rd.fail(b, path_b, "expected a map with name, group, section");
    rd.keys(b, path_b, kBeams2d);
    const std::string name = rd.text(rd.need(b, "name", path_b), path_b + ".name");
    path_b = "beams[" + name + "]";
    if (!beam_names.insert(name).second) rd.fail(b["name"], path_b + ".name", "a beam named '" + name + "' exists already");
    const std::string group = rd.text(rd.need(b, "group", path_b), path_b + ".group");
    const MeshLineBlock& block = find_group(rd, mesh, b, path_b, group);
    if (!groups_used.insert(group).second)
      rd.fail(b["group"], path_b + ".group", "group '" + group + "' is used by another beam already");
    // Planar section: EA, GA (in-plane shear), EI (bending in the plane), rhoA, rhoI; or a material
    // and a shape whose axis 3 is z (the section's in-plane properties GA2, EI3, rhoI3).
    const YAML::Node sn = rd.need(b, "section", path_b);
    double EA, GA, EI, rhoA, rhoI;
    if (sn.IsMap() && (sn["E"] || sn["shape"])) {
      const BeamSection sec = read_section(rd, sn, path_b + ".section");
      EA = sec.EA(), GA = sec.GA2(), EI = sec.EI3(), rhoA = sec.rhoA(), rhoI = sec.rhoI3();
    } else {
      const std::string key = path_b + ".section";
      if (!sn.IsMap()) rd.fail(sn, key, "expected a map of section properties");
      const Section p(rd, sn, key, kPlanarSection);
      EA = p.number("EA"), GA = p.number("GA"), EI = p.number("EI"), rhoA = p.number("rhoA"), rhoI = p.number("rhoI");
    }
    for (size_t e = 0; e < block.elements.size(); ++e) {
      const int ma = block.elements[e][0], mb = block.elements[e][1];
      const Eigen::Vector3d d = mesh.points[static_cast<size_t>(mb)] - mesh.points[static_cast<size_t>(ma)];
      const double angle = std::atan2(d.y(), d.x());  // section axis 1 along the element
      for (int m : {ma, mb}) {
        if (node_of[static_cast<size_t>(m)] >= 0) continue;
        Node nd;
        nd.kind = NodeKind::RigidBody2D;
        const auto pn = point_name.find(m);
        nd.name = pn != point_name.end() ? pn->second : name + ":" + std::to_string(mesh.node_tags[static_cast<size_t>(m)]);
        if (model.find_node(nd.name) >= 0) rd.fail(b, path_b, "mesh point '" + nd.name + "' has the name of another node or body");
        const Eigen::Vector3d x = mesh.points[static_cast<size_t>(m)];
        nd.q0 = Eigen::Vector3d(x.x(), x.y(), angle);
        nd.v0 = Eigen::Vector3d::Zero();
        node_of[static_cast<size_t>(m)] = model.add_node(nd);
      }
      const int na = node_of[static_cast<size_t>(ma)], nb = node_of[static_cast<size_t>(mb)];
      try {
        model.add_element(std::make_unique<PlanarBeam>(name + "[" + std::to_string(e) + "]", na, nb, EA, GA, EI, rhoA,
                                                       rhoI, model.node(na).q0, model.node(nb).q0, angle, angle, gravity));
      } catch (const std::invalid_argument& ex) {
        std::ostringstream os;
        os << "element " << block.element_tags[e] << " of group '" << group << "': " << ex.what();
        rd.fail(b["group"], path_b + ".group", os.str());
      }
    }
  }
  check_named_points(rd, mn, mesh, node_of);
}

std::vector<const Schema*> mesh_schemas() {
  return {&kMesh, &kBeams3d, &kBeams2d, &kBeamMaterial, &kBeamProperties, &kPlanarSection, &kShells, &kShellMaterial, &kShellLaminate};
}

}  // namespace alphaflex::scene_detail
