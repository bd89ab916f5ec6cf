// The scene's mesh (`mesh`) and its element blocks (`beams`, `shells`): the mesh is read (or meshed
// from a .geo) once, each block — a type registered by its file of src/io/types/ — makes its
// elements on a physical group, the mesh nodes become model nodes shared where blocks meet, named
// mesh points become nodes that joints, loads and sensors refer to by name, and every physical
// group is kept (as model nodes) for joints and loads given on a group.
#include <deque>
#include <filesystem>
#include <unordered_set>

#include "alphaflex/mesh/gmsh_reader.hpp"
#include "alphaflex/model/model.hpp"
#include "scene_reader.hpp"

namespace alphaflex::scene_detail {
namespace {

const Schema kMeshSchema{"mesh", {
    {"file", KeyType::Text, "–", kRequired, "a .geo or .msh, relative to the scene file's directory"},
    {"elements", KeyType::Integer, "–", "the .geo's own", "every curve of a .geo meshed with this many equal elements (not with `element_size`; not for .msh)", Range::closed(1, 10000000)},
    {"element_size", KeyType::Number, "m", "the .geo's own", "largest element length of a .geo", Range::positive(), "element size (m)"},
    {"parameters", KeyType::Map, "as the .geo says", "the .geo's defaults", "values of the .geo's `DefineConstant[ x = {v, Name \"x\"} ]`"}}};


/// Reads `mesh` (path relative to the scene file) with the scene's options.
MeshData load_mesh(Reader& rd, const YAML::Node& mn) {
  const Section m(rd, mn, "mesh", kMeshSchema);
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

/// Named points must be beam nodes: a point on no beam would be a node nothing holds.
void check_named_points(Reader& rd, const YAML::Node& mn, const MeshData& mesh, const std::vector<int>& node_of, const std::map<int, std::string>& reduced) {
  for (const auto& [pname, id] : mesh.named_points)
    if (node_of[static_cast<size_t>(id)] < 0 && !reduced.count(id))
      rd.fail(mn["file"], "mesh.file",
              "named point '" + pname + "' is on none of the beams' or shells' groups (an unconnected node); put it on a beam's curve or a shell's surface, or remove it");
  for (const auto& [pname, ids] : mesh.point_groups)
    for (int id : ids)
      if (node_of[static_cast<size_t>(id)] < 0 && !reduced.count(id))
        rd.fail(mn["file"], "mesh.file",
                "point group '" + pname + "' holds mesh node " + std::to_string(mesh.node_tags[static_cast<size_t>(id)]) +
                    ", which is on none of the beams' or shells' groups (an unconnected node); every point of a point group must be on a beam's curve or a shell's surface");
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

/// Reads the list of a registered block type (`beams`, `shells`): each item's name (unique in the
/// list) and keys, checked against the type's schema, then the type's constructor. All items are
/// checked before any is built, so that a reduced block may take later blocks of the list into its
/// body (`reduction.blocks`: recorded in sb.blocks.absorbed here, built by the reduced block).
void read_blocks(Reader& rd, SceneBuilder& sb, const YAML::Node& list, const input::Registry<BlockBuild>::Type& type) {
  const std::string& section = type.name;
  if (!list.IsSequence() || list.size() == 0) rd.fail(list, section, "expected a list of " + section);
  std::set<std::string> names;
  std::deque<std::string> item_names, paths;  // stable: Item and ListedBlock hold references
  std::deque<YAML::Node> nodes;
  std::deque<Section> keys;
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node node = list[i];
    std::string path = section + "[" + std::to_string(i) + "]";
    if (!node.IsMap()) rd.fail(node, path, "expected a map with " + type.build.item_keys);
    const std::string name = Section(rd, node, path, type.schema).text("name");
    path = section + "[" + name + "]";
    if (!names.insert(name).second)
      rd.fail(node["name"], path + ".name", "a " + section.substr(0, section.size() - 1) + " named '" + name + "' exists already");
    nodes.push_back(node);
    item_names.push_back(name);
    paths.push_back(path);
    keys.emplace_back(rd, node, path, type.schema);
  }
  sb.blocks.listed.clear();
  sb.blocks.absorbed.clear();
  for (size_t i = 0; i < list.size(); ++i) sb.blocks.listed[item_names[i]] = {nodes[i], &paths[i], &keys[i]};
  // `reduction.blocks`: each named block is an item of this list, without a reduction of its own,
  // taken by one reduced block only.
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node& item = nodes[i];  // const: operator[] must not add keys
    const YAML::Node red = item["reduction"];
    if (!red.IsDefined() || !red.IsMap()) continue;
    const YAML::Node more = red["blocks"];
    if (!more.IsDefined() || !more.IsSequence()) continue;  // absent; a wrong type is the reduction schema's error
    const std::string at = paths[i] + ".reduction.blocks";
    for (const auto& b : more) {
      const std::string other = b.IsScalar() ? b.as<std::string>() : "";
      const auto l = sb.blocks.listed.find(other);
      if (l == sb.blocks.listed.end()) {
        std::string known;
        for (const std::string& n : item_names)
          if (n != item_names[i]) known += (known.empty() ? "" : ", ") + n;
        rd.fail(b, at, "'" + other + "' is not a block of `" + section + "` (the others: " + (known.empty() ? "none" : known) + ")");
      }
      if (other == item_names[i]) rd.fail(b, at, "names the block itself ('" + other + "'); list the further blocks of its body");
      const YAML::Node& taken = l->second.node;
      if (taken["reduction"])
        rd.fail(b, at, "'" + other + "' has a `reduction` of its own: a block is part of one reduced body (remove one of the two)");
      const auto [o, fresh] = sb.blocks.absorbed.emplace(other, item_names[i]);
      if (!fresh)
        rd.fail(b, at, "'" + other + "' is part of the reduced body of '" + o->second + "' already" +
                           (o->second == item_names[i] ? " (named twice)" : ""));
    }
  }
  for (size_t i = 0; i < list.size(); ++i)
    type.build.build(Item{rd, sb, sb.model_, nodes[i], item_names[i], paths[i], keys[i]});
  sb.blocks.listed.clear();
}

}  // namespace

void read_mesh_and_blocks(Reader& rd, SceneBuilder& sb, const YAML::Node& root, const SceneTypes& types, int dimension) {
  const YAML::Node mn = root["mesh"];
  std::string lists, lists_or, shapes;  // "beams and shells", "`beams` or `shells`", "beams: [{...}] or shells: [{...}]"
  const auto& blocks = types.blocks.types();
  std::vector<YAML::Node> given;
  size_t first = blocks.size();  // the first block list the scene gives
  for (const auto& type : blocks) {
    given.push_back(root[type.name]);
    if (given.back() && first == blocks.size()) first = given.size() - 1;
    lists += (lists.empty() ? "" : " and ") + type.name;
    lists_or += (lists_or.empty() ? "`" : " or `") + type.name + "`";
    shapes += (shapes.empty() ? "" : " or ") + type.name + ": [{" + type.build.item_keys + "}]";
  }
  if (!mn && root["initial_conditions"])
    rd.fail(root["initial_conditions"], "initial_conditions", "the scene has no `mesh`: initial conditions are given to mesh groups (rigid bodies have their own `velocity`, `angular_velocity`)");
  if (!mn && first == blocks.size()) return;
  if (!mn) rd.fail(given[first], blocks[first].name, lists + " need a `mesh` (a .geo or .msh file with their physical groups)");
  if (first == blocks.size()) rd.fail(mn, "mesh", "no " + lists_or + " use this mesh (give " + shapes + ")");
  sb.blocks.mesh = load_mesh(rd, mn);
  apply_initial_conditions(rd, sb.blocks, root, dimension);
  const MeshData& mesh = sb.blocks.mesh;
  if (dimension == 2)
    for (size_t k = 0; k < mesh.points.size(); ++k)
      if (std::fabs(mesh.points[k].z()) > 1e-12 * std::max(1.0, mesh.points[k].norm()))
        rd.fail(mn["file"], "mesh.file",
                "node " + std::to_string(mesh.node_tags[k]) + " is not in the x-y plane (z = " +
                    std::to_string(mesh.points[k].z()) + "); a planar scene needs a planar mesh (or use dimension: 3)");
  // Physical group names become node, group and result names: the scene's safe set (issue 24).
  auto check_name = [&](const std::string& name, const char* kind) {
    const std::string why = input::name_problem(name);
    if (!why.empty())
      rd.fail(mn["file"], "mesh.file", "mesh '" + mesh.file + "': the name of physical " + kind + " group '" +
                                           input::escaped_name(name) + "': " + why);
  };
  for (const auto& b : mesh.line_blocks) check_name(b.name, "curve");
  for (const auto& b : mesh.surface_blocks) check_name(b.name, "surface");
  for (const auto& p : mesh.named_points) check_name(p.first, "point");
  for (const auto& p : mesh.point_groups) check_name(p.first, "point");
  sb.mesh_file = mesh.file;
  sb.blocks.node_of.assign(mesh.points.size(), -1);
  for (const auto& [name, id] : mesh.named_points) sb.blocks.point_name[id] = name;
  for (size_t k = 0; k < given.size(); ++k)
    if (given[k]) read_blocks(rd, sb, given[k], blocks[k]);
  check_named_points(rd, mn, mesh, sb.blocks.node_of, sb.blocks.reduced);
  check_group_velocities(rd, sb.blocks, root);
  if (dimension == 3) keep_groups(sb, mesh, sb.blocks.node_of);
}

const Schema& mesh_schema() { return kMeshSchema; }

}  // namespace alphaflex::scene_detail
