// Every spatial joint type: one reader, one registration per row of spatial_joint_kinds()
// (joints/spatial_joints.hpp), whose row says which keys (axis, axis2, reference) and drivers it
// takes. A joint is given by bodies (body1, body2, location), by markers, or on a mesh group.
#include <Eigen/Geometry>
#include <algorithm>

#include "alphaflex/joints/reduced_interface_tie.hpp"
#include "alphaflex/joints/spatial_joints.hpp"
#include "common.hpp"

namespace alphaflex::scene_detail {
namespace {

/// The pairs (node of a, node of b) at the same reference position (to 1e-9 of the groups'
/// extent): for joints between two meshed parts, e.g. the beams of a grid that cross at hinges.
/// Nodes of `a` with no partner are left out; two partners, or no pair at all, is an error.
std::vector<std::pair<int, int>> coincident_nodes(const Reader& rd, const MeshGroup& a, const MeshGroup& b, const YAML::Node& at,
                                                  const std::string& key) {
  Eigen::AlignedBox3d box;
  for (const auto& p : a.points) box.extend(p);
  for (const auto& p : b.points) box.extend(p);
  const double tol = 1e-9 * std::max(1.0, box.diagonal().norm());
  // b's nodes sorted by x; each node of a looks at the slice within tol in x.
  std::vector<size_t> order(b.nodes.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t i, size_t k) { return b.points[i].x() < b.points[k].x(); });
  std::vector<std::pair<int, int>> pairs;
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    if (a.nodes[i] < 0) continue;
    const Eigen::Vector3d& p = a.points[i];
    auto it = std::lower_bound(order.begin(), order.end(), p.x() - tol, [&](size_t k, double x) { return b.points[k].x() < x; });
    int partner = -1;
    for (; it != order.end() && b.points[*it].x() <= p.x() + tol; ++it) {
      const int n = b.nodes[*it];
      if (n < 0 || n == a.nodes[i] || (b.points[*it] - p).norm() > tol) continue;
      if (partner >= 0 && partner != n)
        rd.fail(at, key, "two nodes of this group lie at (" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " +
                             std::to_string(p.z()) + "): a node of `group` must have at most one coincident node here");
      partner = n;
    }
    if (partner >= 0) pairs.emplace_back(a.nodes[i], partner);
  }
  if (pairs.empty())
    rd.fail(at, key, "no node of this group is at the place of a node of `group` (a joint per pair of coincident nodes; are the meshes' points distinct but coincident, e.g. Geometry.AutoCoherence = 0 in the .geo?)");
  return pairs;
}

/// A marker on `node` (slot in the joint's node list) that coincides with the world frame
/// (position p, rotation R) at t = 0.
SpatialMarker marker_at(const Model& m, int node, int slot, const Eigen::Vector3d& p, const Eigen::Matrix3d& R) {
  SpatialMarker mk;
  mk.slot = node < 0 ? -1 : slot;
  const Pose<double> f = initial_pose(m, node);
  mk.position = f.R.transpose() * (p - f.x);
  mk.rotation = f.R.transpose() * R;
  return mk;
}

Schema spatial_joint_schema(const SpatialJointKind& kind) {
  std::vector<Key> keys{
      {"body1", KeyType::Text, "–", "– (or `marker1`, or `group`)", "the first body or beam/shell node; not `ground`"},
      {"body2", KeyType::Text, "–", "`ground`", "the second body, node or `ground`; different from body1"},
      {"location", KeyType::Vec3, "m", "body1's reference point", "world point of the joint at t = 0"},
      {"marker1", KeyType::Text, "–", "–", "a marker of a body: stands for body1, the location and (without `axis`) the joint frame"},
      {"marker2", KeyType::Text, "–", "–", "a marker of a body at the joint's location at t = 0: stands for body2"},
      {"group", KeyType::Text, "–", "–", "a mesh group instead of body1: one joint NAME[k] per node of the group"},
      {"group2", KeyType::Text, "–", "–", "with `group`: a second mesh group; one joint per pair of coincident nodes"}};
  if (kind.needs_axis) keys.push_back({"axis", KeyType::Vec3, "–", kRequired + std::string(" (unless `marker1`)"), "joint axis (world, t = 0); non-zero"});
  if (kind.needs_axis2) keys.push_back({"axis2", KeyType::Vec3, "–", kRequired, "second axis (world, t = 0), perpendicular to `axis`"});
  if (kind.takes_reference)
    keys.push_back(kind.needs_axis ? Key{"reference", KeyType::Vec3, "–", "any ⊥ axis", "direction ⊥ axis where a driver's angle is zero; not parallel to the axis"}
                             : Key{"reference", KeyType::Map, "rad", "body1's frame", "rotation of the joint frame", {}, "", "rotation"});
  if (kind.angle_driver || kind.displacement_driver)
    keys.push_back({"driver", KeyType::Map, "rad, m", "none",
                    std::string("prescribed relative motion: ") + (kind.angle_driver ? "`angle` (rad)" : "") +
                        (kind.angle_driver && kind.displacement_driver ? ", " : "") +
                        (kind.displacement_driver ? "`displacement` (m)" : "") + ", each a number or a time function"});
  return type_schema("joints.3d." + kind.name,
                     "`" + kind.name + "`: " + std::to_string(kind.num_equations) + " equations; " + kind.doc, keys);
}

const Schema& driver_schema() {
  static const Schema s{"joints.3d.driver", {
      {"angle", KeyType::Function, "rad", "none", "relative rotation about the axis from `reference` (revolute, cylindrical)"},
      {"displacement", KeyType::Function, "m", "none", "relative translation along the axis (cylindrical, prismatic)"}}};
  return s;
}

/// Every spatial joint kind: one reader, the kind's row of spatial_joint_kinds() says what it takes.
void read_spatial_joint(const Item& it, const SpatialJointKind& kind) {
  Reader& rd = it.rd;
  SceneBuilder& sb = it.sb;
  Model& model = it.model;
  const Section& k = it.keys;
  const std::string& name = it.name;
  const bool has_axis = kind.needs_axis;
  // A marker (a named frame of a body) stands for the body, the location and the joint frame.
  auto marker_of = [&](const char* key) -> const NamedMarker* {
    if (!k.has(key)) return nullptr;
    const std::string mn = k.text(key);
    const auto found = sb.markers.find(mn);
    if (found == sb.markers.end()) rd.fail(k.node(key), it.at(key), "no marker named '" + mn + "' (markers are listed under a body's `markers`)");
    return &found->second;
  };
  const NamedMarker* mk1 = marker_of("marker1");
  const NamedMarker* mk2 = marker_of("marker2");
  if (mk1 && k.has("body1")) rd.fail(k.node("body1"), it.at("body1"), "give either body1 or marker1");
  if (mk2 && k.has("body2")) rd.fail(k.node("body2"), it.at("body2"), "give either body2 or marker2");
  if (mk1 && k.has("location")) rd.fail(k.node("location"), it.at("location"), "marker1 fixes the location; remove one of them");
  // `group`: one joint per node of a mesh group (a clamped or supported edge), named name[k],
  // each at its node with that node as body1.
  const MeshGroup* group = nullptr;
  if (k.has("group")) {
    for (const char* key : {"body1", "marker1", "location"})
      if (k.has(key)) rd.fail(k.node(key), it.at(key), "give either group (a joint at every node of a mesh group) or " + std::string(key));
    group = &sb.mesh_group(k, "group");
  }
  if (!mk1 && !k.has("body1") && !group) rd.fail(it.node, it.at("body1"), "missing (required): body1, marker1 or group");
  if (k.has("group2") && !group) rd.fail(k.node("group2"), it.at("group2"), "group2 pairs the nodes of `group` with coincident ones: give group too");
  if (k.has("group2") && (k.has("body2") || mk2))
    rd.fail(k.node("group2"), it.at("group2"), "give either group2 (the coincident node of another mesh group) or body2/marker2");
  // The weld of a rigid body into a reduced body (`reduction.bodies`, types/reduced_beams_3d.cpp),
  // after the checks of its keys (the full mesh runs the same joint):
  // the body's node held at its pose relative to the block node it is welded to.
  if (const auto weld = sb.welds.find(name); weld != sb.welds.end()) {
    const SceneBuilder::Weld& w = weld->second;
    model.add_constraint(std::make_unique<ReducedInterfaceTie>(name, model.find_node(w.body), w.frame, w.amplitudes, w.position,
                                                               w.rotation, w.shape, w.offset_position, w.offset_rotation));
    return;
  }
  const int fixed_b2 = mk2 ? mk2->node : (k.has("body2") ? spatial_node(it, "body2", true) : -1);
  // (body1, body2) of each joint: one joint, or one per node of `group` (with body2, or with the
  // node of `group2` at the same place: a hinge between two meshed parts that cross or touch).
  std::vector<std::pair<int, int>> pairs;
  if (!group) {
    pairs.emplace_back(mk1 ? mk1->node : spatial_node(it, "body1", false), fixed_b2);
  } else if (!k.has("group2")) {
    for (int n : group->nodes) pairs.emplace_back(n, fixed_b2);
  } else {
    const MeshGroup& other = sb.mesh_group(k, "group2");
    pairs = coincident_nodes(rd, *group, other, k.node("group2"), it.at("group2"));
  }
  // The axis keys: required with an axis unless marker1 gives the joint frame.
  auto axis_key = [&](const char* key) {
    if (!k.has(key)) rd.fail(it.node, it.at(key), "missing (required)");
    return k.direction(key);
  };
  TimeFunctionPtr angle, displacement;
  for (size_t n = 0; n < pairs.size(); ++n) {
    const auto [b1, b2] = pairs[n];
    const std::string jname = group ? name + "[" + std::to_string(n) + "]" : name;
    if (group && n == 0)  // name[0], name[1], …: checked once per group, not once per joint
      for (const auto& c : model.constraints())
        if (c->name().rfind(name + "[", 0) == 0) rd.fail(it.node["name"], it.at("name"), "a joint named '" + c->name() + "' exists already");
    if (b1 == b2) rd.fail(k.has("body2") ? k.node("body2") : it.node, it.at("body2"), "a joint needs two different bodies");
    const Pose<double> p1 = initial_pose(model, b1);
    const Eigen::Vector3d loc = mk1                  ? Eigen::Vector3d(p1.x + p1.R * mk1->position)
                                : k.has("location") ? k.vec3("location")
                                                    : p1.x;
    // Joint frame (world, t = 0): a3 along the axis; universal: a1 = axis (on body 1), a2 = axis2.
    // Without an axis key, a marker's frame is the joint frame (its z axis is the joint axis).
    Eigen::Matrix3d R = mk1 ? Eigen::Matrix3d(p1.R * mk1->rotation) : p1.R;
    if (mk1 && has_axis && !k.has("axis")) {
      R = p1.R * mk1->rotation;
    } else if (kind.needs_axis2) {
      const Eigen::Vector3d a1 = axis_key("axis");
      const Eigen::Vector3d a2 = k.direction("axis2");
      if (std::fabs(a1.dot(a2)) > 1e-9) rd.fail(k.node("axis2"), it.at("axis2"), "the two axes of a universal joint must be perpendicular");
      R.col(0) = a1;
      R.col(1) = a2;
      R.col(2) = a1.cross(a2);
    } else if (has_axis) {
      const Eigen::Vector3d a3 = axis_key("axis");
      // a1: the `reference` direction (where a driver's angle is zero), else any perpendicular.
      Eigen::Vector3d ref = k.has("reference") ? k.direction("reference")
                                               : (std::fabs(a3.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY());
      ref -= a3.dot(ref) * a3;
      if (ref.norm() < 1e-9) rd.fail(k.node("reference"), it.at("reference"), "must not be parallel to the axis");
      R.col(0) = ref.normalized();
      R.col(2) = a3;
      R.col(1) = a3.cross(R.col(0));
    } else if (k.has("reference")) {
      R = read_orientation(rd, k.node("reference"), it.at("reference"));
    }
    if (kind.angle_driver || kind.displacement_driver) {  // a row without drivers has no `driver` key
      const Section driver(rd, k.node("driver"), it.at("driver"), driver_schema());
      if (driver.has("angle")) {
        if (!kind.angle_driver)
          rd.fail(driver.node("angle"), driver.key_path("angle"), "a " + kind.name + " joint has no rotation to drive (use displacement)");
        angle = driver.function("angle");
      }
      if (driver.has("displacement")) {
        if (!kind.displacement_driver)
          rd.fail(driver.node("displacement"), driver.key_path("displacement"), "a " + kind.name + " joint has no translation to drive (use angle)");
        displacement = driver.function("displacement");
      }
    }
    if (mk2) {
      const Pose<double> p2 = initial_pose(model, b2);
      const Eigen::Vector3d at2 = p2.x + p2.R * mk2->position;
      if ((at2 - loc).norm() > 1e-9 * std::max(1.0, loc.norm()))
        rd.fail(k.node("marker2"), it.at("marker2"),
                "is not at the joint's location at t = 0 (distance " + std::to_string((at2 - loc).norm()) + " m)");
    }
    std::vector<int> nodes{b1};
    if (b2 >= 0) nodes.push_back(b2);
    const SpatialMarker A = marker_at(model, b1, 0, loc, R);
    const SpatialMarker B = marker_at(model, b2, 1, loc, R);
    try {
      model.add_constraint(std::make_unique<SpatialJoint>(jname, nodes, kind, A, B, angle, displacement));
    } catch (const std::invalid_argument& e) {
      rd.fail(it.node, it.path, e.what());
    }
  }
}

}  // namespace

void register_spatial_joints_3d(SceneTypes& t) {
  for (const SpatialJointKind& kind : spatial_joint_kinds())  // one registration per row of the joints' table
    t.joints.add(kind.name, spatial_joint_schema(kind), [&kind](const Item& it) { read_spatial_joint(it, kind); });
  t.parts.push_back(&driver_schema());
}

}  // namespace alphaflex::scene_detail
