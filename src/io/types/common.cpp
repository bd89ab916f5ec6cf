#include "common.hpp"

#include <Eigen/Eigenvalues>
#include <sstream>

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

const std::array<std::pair<const char*, Sensor::Kind>, 4>& point_sensor_kinds() {
  static const std::array<std::pair<const char*, Sensor::Kind>, 4> kinds{{{"point_position", Sensor::Kind::PointPosition},
                                                                           {"point_displacement", Sensor::Kind::PointDisplacement},
                                                                           {"point_velocity", Sensor::Kind::PointVelocity},
                                                                           {"point_acceleration", Sensor::Kind::PointAcceleration}}};
  return kinds;
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
  const Section rotation(rd, n, key, rotation_schema());
  const Eigen::Vector3d axis = rotation.direction("axis");
  return exp_so3<double>(Eigen::Vector3d(axis * rotation.number("angle")));
}

const Schema& rotation_schema() {
  static const Schema s{"rotation", {{"axis", KeyType::Vec3, "–", kRequired, "rotation axis; non-zero"},
                                     {"angle", KeyType::Number, "rad", kRequired, "rotation angle about `axis`"}}};
  return s;
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

std::string mesh_point_label(const MeshBlocks& b, int m) {
  const auto pn = b.point_name.find(m);
  return pn != b.point_name.end() ? pn->second : "node " + std::to_string(b.mesh.node_tags[static_cast<size_t>(m)]);
}

int block_node(const Item& it, int m, NodeKind kind, const Eigen::VectorXd& q0, const Eigen::VectorXd& v0) {
  MeshBlocks& b = it.sb.blocks;
  const size_t i = static_cast<size_t>(m);
  if (b.node_of[i] >= 0) return b.node_of[i];
  // An inner point of a reduced block has no node (its motion is the body's): a block that shares
  // it would be left unconnected (types/reduced_beams_3d.cpp).
  const auto red = b.reduced.find(m);
  if (red != b.reduced.end())
    it.rd.fail(it.node, it.path, "mesh point '" + mesh_point_label(b, m) + "' is an inner point of the reduced block '" + red->second +
                                     "': add it to that block's reduction.interface (a named point) so that the blocks stay connected, or this block "
                                     "to its reduction.blocks (one reduced body)");
  Node nd;
  nd.kind = kind;
  const auto pn = b.point_name.find(m);
  nd.name = pn != b.point_name.end() ? pn->second : it.name + ":" + std::to_string(b.mesh.node_tags[i]);
  if (it.model.find_node(nd.name) >= 0) it.rd.fail(it.node, it.path, "mesh point '" + nd.name + "' has the name of another node or body");
  nd.q0 = q0;
  nd.v0 = v0;
  const auto v = b.velocity.find(m);  // an initial velocity field (scene_initial.cpp): Ω in the node frame
  if (v != b.velocity.end() && kind == NodeKind::Frame3D) {
    nd.v0.resize(6);
    nd.v0 << v->second[0], pose_of(q0.data()).R.transpose() * v->second[1];
  }
  b.node_of[i] = it.model.add_node(nd);
  return b.node_of[i];
}

Eigen::MatrixXd read_psd_matrix(const Item& it, const std::string& key, int size, const char* units) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(size, size);
  if (!it.keys.has(key)) return m;
  const YAML::Node n = it.keys.node(key);
  const std::string at = it.at(key);
  const std::string expected = "expected " + std::to_string(size) + " numbers (the diagonal) or " + std::to_string(size) + " rows of " + std::to_string(size) + " numbers (" + units + ")";
  if (!n.IsSequence() || n.size() != static_cast<size_t>(size)) it.rd.fail(n, at, expected);
  if (n[0].IsScalar()) {
    for (int i = 0; i < size; ++i) m(i, i) = it.rd.number(n[i], at + "[" + std::to_string(i) + "]");
  } else {
    for (int i = 0; i < size; ++i) {
      const YAML::Node row = n[i];
      const std::string rp = at + "[" + std::to_string(i) + "]";
      if (!row.IsSequence() || row.size() != static_cast<size_t>(size)) it.rd.fail(row, rp, expected);
      for (int j = 0; j < size; ++j) m(i, j) = it.rd.number(row[j], rp + "[" + std::to_string(j) + "]");
    }
  }
  const double scale = m.cwiseAbs().maxCoeff();
  if ((m - m.transpose()).cwiseAbs().maxCoeff() > 1e-12 * scale)
    it.rd.fail(n, at, "the matrix must be symmetric (a bushing stores the energy ½ εᵀKε and dissipates ½ ε̇ᵀCε̇)");
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(m);
  const double lowest = es.eigenvalues().minCoeff();
  if (lowest < -1e-12 * scale) {
    std::ostringstream os;
    os << "the matrix must be positive semi-definite, but it has the eigenvalue " << lowest
       << " (direction [" << es.eigenvectors().col(0).transpose().format(Eigen::IOFormat(4, Eigen::DontAlignCols, ", ", ", "))
       << "] of (u, γ)): it would push the bodies apart instead of holding them";
    it.rd.fail(n, at, os.str());
  }
  return m;
}

}  // namespace alphaflex::scene_detail
