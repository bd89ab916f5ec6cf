#include "common.hpp"

#include "alphaflex/core/rotation.hpp"

namespace alphaflex::scene_detail {

Schema type_schema(const std::string& name, const std::string& type_doc, std::vector<Key> keys) {
  keys.insert(keys.begin(), {{"name", KeyType::Text, "–", kRequired, "unique in its list"},
                             {"type", KeyType::Text, "–", kRequired, type_doc}});
  return Schema{name, std::move(keys)};
}

std::vector<Key> with(std::vector<Key> keys, std::vector<Key> more) {
  keys.insert(keys.end(), more.begin(), more.end());
  return keys;
}

std::vector<int> node_list(int a, int b) {
  std::vector<int> v;
  if (a >= 0) v.push_back(a);
  if (b >= 0) v.push_back(b);
  return v;
}

int sensor_joint(const Item& it) {
  const std::string jn = it.keys.text("joint");
  const int c = it.model.find_constraint(jn);
  if (c < 0) it.rd.fail(it.node["joint"], it.at("joint"), "no joint named '" + jn + "'");
  return c;
}

std::vector<Key> two_point_keys() {
  return {{"body1", KeyType::Text, "–", kRequired, "the first body; not `ground`"},
          {"point1", KeyType::Vec2, "m", "[0, 0]", "point of body1, body frame relative to its centre of mass"},
          {"body2", KeyType::Text, "–", "`ground`", "the second body or `ground`; different from body1"},
          {"point2", KeyType::Vec2, "m", "[0, 0]", "point of body2 in its body frame; a world point when body2 is `ground`"},
          {"location", KeyType::Vec2, "m", "–",
           "instead of `point1`/`point2`: the world point of the joint at t = 0, converted to point1 and point2 with the bodies' initial positions and angles"}};
}

TwoPoints two_points(const Item& it, bool default_point2_coincident) {
  const Section& k = it.keys;
  TwoPoints tp;
  tp.b1 = it.sb.body(k, "body1", false);
  tp.b2 = k.has("body2") ? it.sb.body(k, "body2", true) : -1;
  if (tp.b1 == tp.b2) it.rd.fail(k.node("body2"), it.at("body2"), "a joint needs two different bodies");
  if (k.has("location")) {
    if (k.has("point1") || k.has("point2")) it.rd.fail(k.node("location"), it.at("location"), "give either location or point1/point2");
    const Eigen::Vector2d loc = k.vec2("location");
    tp.s1 = it.sb.to_local(tp.b1, loc);
    tp.s2 = it.sb.to_local(tp.b2, loc);
  } else {
    tp.s1 = k.vec2("point1");
    const Eigen::Vector2d p1 = it.sb.initial_position(tp.b1, tp.s1);
    tp.s2 = k.has("point2") || !default_point2_coincident ? k.vec2("point2")
                                                          : (tp.b2 < 0 ? p1 : it.sb.to_local(tp.b2, p1));
  }
  tp.nodes = node_list(tp.b1, tp.b2);
  return tp;
}

Eigen::Matrix3d read_orientation(const Reader& rd, const YAML::Node& n, const std::string& key) {
  if (n.IsSequence()) return exp_so3<double>(rd.vec3(n, key));
  if (!n.IsMap()) rd.fail(n, key, "expected a rotation vector [rx, ry, rz] (rad) or {axis: [x, y, z], angle: a}");
  static const Schema rotation{"rotation", {{"axis", KeyType::Vec3, "–", kRequired, "rotation axis; non-zero"},
                                           {"angle", KeyType::Number, "rad", kRequired, "rotation angle about `axis`"}}};
  rd.keys(n, key, rotation);
  const Eigen::Vector3d axis = rd.direction(rd.need(n, "axis", key), key + ".axis");
  return exp_so3<double>(Eigen::Vector3d(axis * rd.number(rd.need(n, "angle", key), key + ".angle")));
}

int spatial_node(const Item& it, const std::string& key, bool ground_ok) {
  const int id = it.sb.body(it.keys, key, ground_ok);
  if (id >= 0 && !it.model.node(id).spatial()) it.rd.fail(it.keys.node(key), it.at(key), "expected a spatial body or beam node");
  return id;
}

Pose<double> initial_pose(const Model& m, int node) {
  if (node < 0) return Pose<double>{Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()};
  return pose_of(m.node(node).q0.data());
}

Key xyz_component() { return {"component", KeyType::Choice, "–", kRequired, "component", {}, "", "", {"x", "y", "z"}}; }

Key follower_off() {
  return {"follower", KeyType::Flag, "–", "off", "off: world components (dead load); on: body-frame components (follower)"};
}

std::array<TimeFunctionPtr, 3> vector_function(const Item& it, const char* key, const char* unit) {
  std::array<TimeFunctionPtr, 3> v;
  const YAML::Node n = it.keys.node(key);
  if (!n) return v;
  if (!n.IsSequence() || n.size() != 3)
    it.rd.fail(n, it.at(key), std::string("expected [x, y, z], each a number or a time function (") + unit + ")");
  for (int k = 0; k < 3; ++k) v[static_cast<size_t>(k)] = it.rd.function(n[k], it.at(key) + "[" + std::to_string(k) + "]");
  return v;
}

int block_node(const Item& it, int m, NodeKind kind, const Eigen::VectorXd& q0, const Eigen::VectorXd& v0) {
  MeshBlocks& b = it.sb.blocks;
  const size_t i = static_cast<size_t>(m);
  if (b.node_of[i] >= 0) return b.node_of[i];
  Node nd;
  nd.kind = kind;
  const auto pn = b.point_name.find(m);
  nd.name = pn != b.point_name.end() ? pn->second : it.name + ":" + std::to_string(b.mesh.node_tags[i]);
  if (it.model.find_node(nd.name) >= 0) it.rd.fail(it.node, it.path, "mesh point '" + nd.name + "' has the name of another node or body");
  nd.q0 = q0;
  nd.v0 = v0;
  b.node_of[i] = it.model.add_node(nd);
  return b.node_of[i];
}

const MeshLineBlock& line_group(const Item& it) {
  const MeshData& mesh = it.sb.blocks.mesh;
  const std::string group = it.keys.text("group");
  const MeshLineBlock* block = mesh.find_line_block(group);
  if (!block) {
    std::string known;
    for (const auto& lb : mesh.line_blocks) known += (known.empty() ? "" : ", ") + lb.name;
    it.rd.fail(it.keys.node("group"), it.at("group"),
               "mesh '" + mesh.file + "' has no physical curve group '" + group + "' (its curve groups: " +
                   (known.empty() ? "none" : known) + ")");
  }
  if (!it.sb.blocks.groups_used.insert(group).second)
    it.rd.fail(it.keys.node("group"), it.at("group"), "group '" + group + "' is used by another beam already");
  return *block;
}

}  // namespace alphaflex::scene_detail
