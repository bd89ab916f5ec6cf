// `rigid_body` (spatial): a frame on R³×SO(3) with its mass and inertia, and `markers`, named
// frames fixed to it that joints and sensors refer to.
#include <Eigen/Eigenvalues>

#include "alphaflex/elements/spatial_elements.hpp"
#include "body_shape.hpp"

namespace alphaflex::scene_detail {
namespace {

/// Inertia tensor: [Ixx, Iyy, Izz] (principal, body axes) or a symmetric 3×3 list of rows.
Eigen::Matrix3d read_inertia(const Reader& rd, const YAML::Node& n, const std::string& key) {
  Eigen::Matrix3d J = Eigen::Matrix3d::Zero();
  if (n.IsSequence() && n.size() == 3 && n[0].IsScalar()) {
    J.diagonal() = rd.vec3(n, key);
  } else if (n.IsSequence() && n.size() == 3) {
    for (int i = 0; i < 3; ++i) J.row(i) = rd.vec3(n[i], key + "[" + std::to_string(i) + "]").transpose();
    if ((J - J.transpose()).norm() > 1e-12 * J.norm()) rd.fail(n, key, "the inertia tensor must be symmetric");
  } else {
    rd.fail(n, key, "expected [Ixx, Iyy, Izz] or a 3x3 list of rows (kg m^2, body frame, about the centre of mass)");
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(J);
  const Eigen::Vector3d e = es.eigenvalues();
  if (!(e.minCoeff() > 0.0)) rd.fail(n, key, "the inertia tensor must be positive definite (a zero makes the mass matrix singular)");
  // Triangle inequality of principal moments (a physical mass distribution).
  if (e[0] + e[1] < e[2] * (1.0 - 1e-12)) rd.fail(n, key, "principal moments violate I1 + I2 >= I3: no body has this inertia");
  return J;
}

const Schema& marker_schema() {
  static const Schema s{"bodies.3d.markers", {
      {"name", KeyType::Text, "–", kRequired, "unique in the scene (among markers, bodies and mesh points)"},
      {"position", KeyType::Vec3, "m", kRequired, "origin of the marker in the body frame"},
      {"orientation", KeyType::Map, "rad", "identity", "rotation of the marker frame in the body frame", {}, "", "rotation"}}};
  return s;
}

void read_rigid_body_3d(const Item& it) {
  Reader& rd = it.rd;
  const Section& k = it.keys;
  const RigidBodyInput in = rigid_body_input(rd, k);
  const double m = in.mass;
  const Eigen::Matrix3d& J = in.inertia;
  const Eigen::Vector3d& x = in.position;
  const Eigen::Matrix3d& R = in.orientation;
  const Eigen::Vector3d v = k.vec3("velocity"), w = k.vec3("angular_velocity");  // w: world frame
  Node nd;
  nd.name = it.name;
  nd.kind = NodeKind::Frame3D;
  nd.q0.resize(7);
  store_pose(x, R, nd.q0.data());
  nd.v0.resize(6);
  nd.v0 << v, R.transpose() * w;  // Ω in the body frame
  const int id = it.model.add_node(nd);
  // A body welded into a reduced body (`reduction.bodies`): its mass and inertia are in the
  // superelement (types/reduced_beams_3d.cpp); its node is held by the weld's tie.
  if (!it.sb.welded_bodies.count(it.name)) it.model.add_element(std::make_unique<RigidBody3D>(it.name, id, m, J, it.sb.gravity));
  read_body_shape(it, id);
  // Markers: named frames fixed to the body (position and orientation in the body frame), for
  // joints (marker1/marker2) and point sensors (marker).
  if (const YAML::Node ml = k.node("markers")) {
    if (!ml.IsSequence()) rd.fail(ml, it.at("markers"), "expected a list of {name, position, orientation}");
    for (size_t i = 0; i < ml.size(); ++i) {
      const YAML::Node mk = ml[i];
      const std::string mp = it.at("markers[" + std::to_string(i) + "]");
      if (!mk.IsMap()) rd.fail(mk, mp, "expected a map {name, position, orientation}");
      const Section ms(rd, mk, mp, marker_schema());
      const std::string mname = ms.text("name");
      if (it.sb.markers.count(mname) || it.model.find_node(mname) >= 0)
        rd.fail(mk["name"], mp + ".name", "the name '" + mname + "' is taken (marker names are unique in a scene)");
      NamedMarker nm;
      nm.node = id;
      nm.position = ms.vec3("position");
      if (ms.has("orientation")) nm.rotation = read_orientation(rd, ms.node("orientation"), mp + ".orientation");
      it.sb.markers[mname] = nm;
    }
  }
}

}  // namespace

RigidBodyInput rigid_body_input(const Reader& rd, const Section& k) {
  RigidBodyInput in;
  in.mass = k.number("mass");
  in.inertia = read_inertia(rd, k.node("inertia"), k.key_path("inertia"));
  in.position = k.vec3("position");
  in.orientation = k.has("orientation") ? read_orientation(rd, k.node("orientation"), k.key_path("orientation"))
                                        : Eigen::Matrix3d::Identity();
  if (const YAML::Node ml = k.node("markers"); ml && ml.IsSequence())
    for (const YAML::Node& mk : ml)
      if (mk.IsMap() && mk["name"] && mk["name"].IsScalar()) in.markers.push_back(mk["name"].Scalar());
  return in;
}

const Schema& rigid_body_schema() {
  static const Schema s = type_schema("bodies.3d.rigid_body", "`rigid_body`: a frame on R³×SO(3)", {
      {"mass", KeyType::Number, "kg", kRequired, "positive", Range::positive(), "mass (kg); a zero mass makes the mass matrix singular"},
      {"inertia", KeyType::List, "kg·m²", kRequired, "about the centre of mass in the body frame; symmetric positive definite with I1 + I2 ≥ I3",
       {}, "", "[Ixx, Iyy, Izz] or 3×3 list of rows"},
      {"position", KeyType::Vec3, "m", kRequired, "centre of mass at t = 0"},
      {"orientation", KeyType::Map, "rad", "identity", "body frame at t = 0: a rotation vector [rx, ry, rz] or {axis, angle}", {}, "", "rotation"},
      {"velocity", KeyType::Vec3, "m/s", "[0, 0, 0]", "velocity of the centre of mass at t = 0"},
      {"angular_velocity", KeyType::Vec3, "rad/s", "[0, 0, 0]", "world components at t = 0"},
      {"markers", KeyType::List, "m, rad", "none", "frames fixed to the body, `{name, position, orientation}` in the body frame"},
      shape_key()});
  return s;
}

void register_rigid_body_3d(SceneTypes& t) {
  t.bodies.add("rigid_body", rigid_body_schema(), read_rigid_body_3d);
  t.parts.push_back(&marker_schema());
  t.parts.push_back(&rotation_schema());
  t.parts.push_back(&shape_schema());
}

}  // namespace alphaflex::scene_detail
