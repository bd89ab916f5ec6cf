// `beams` and `shells` … `reduction:` (issue 19): a spatial beam or shell block modelled as one reduced flexible body — a
// floating frame (the pose of the first interface point, an ordinary Frame3D node) and elastic
// amplitudes in a Craig–Bampton (or Herting) basis computed from the block's own elements with that point
// clamped (docs/theory/reduced_bodies.md, modal/superelement.hpp). `rigid` keeps no amplitude: the
// block's rigid mass properties on the frame. Every other interface point is a Frame3D node tied
// to the body's pose there (joints/reduced_interface_tie.hpp), so joints, loads and sensors attach
// to it as on a full mesh.
#include <algorithm>
#include <deque>
#include <map>
#include <sstream>
#include <stdexcept>

#include "alphaflex/core/error.hpp"
#include "alphaflex/elements/reduced_body.hpp"
#include "alphaflex/elements/spatial_elements.hpp"
#include "alphaflex/joints/reduced_interface_tie.hpp"
#include "alphaflex/modal/superelement.hpp"
#include "alphaflex/model/mesh_reconstruction.hpp"
#include "reduced_beams_3d.hpp"
#include "reduced_mesh_3d.hpp"

namespace alphaflex::scene_detail {

const Schema& reduction_schema() {
  static const Schema s{"beams.reduction", {
      {"method", KeyType::Choice, "–", kRequired, "`craig_bampton`: constraint modes of the other interface points and `modes` "
                                                  "fixed-interface normal modes (all interface points clamped; exact for the lowest "
                                                  "frequencies of the block held at its interface); `herting`: the same constraint modes "
                                                  "and `modes` free-interface normal modes (only the first point clamped, the others free; "
                                                  "exact for the lowest frequencies of the block free at its other interface points), "
                                                  "the interface points staying coordinates (docs/theory/reduced_bodies.md); `rigid`: no "
                                                  "elastic amplitude", {}, "", "", {"craig_bampton", "rigid", "herting"}},
      {"modes", KeyType::Integer, "–", "– (**required** for `craig_bampton` and `herting`)", "normal modes kept: `craig_bampton` at most "
                                                                             "the block's coordinates minus the interface's; `herting` at most the "
                                                                             "block's coordinates less the first point's 6 (a mode that adds nothing "
                                                                             "to the basis gets no amplitude)", Range::non_negative()},
      {"interface", KeyType::Texts, "–", kRequired, "named mesh points of the block (or of its further `blocks`); the first carries the "
                                                 "floating frame, each other one gets a node tied to the body (joints, loads, sensors attach to all of them)"},
      {"blocks", KeyType::Texts, "–", "– (none)", "further blocks of the same list (`beams` or `shells`) that are part of this body: each keeps "
                                               "its own group, section and orientation, has no `reduction` of its own, and the mesh points it shares "
                                               "with the others become inner points of the one reduced body (docs/input.md, \"Reduced beam blocks\")"},
      {"bodies", KeyType::Texts, "–", "– (none)", "spatial `rigid_body` items of `bodies` that are part of this body: each is welded to "
                                               "a named mesh point of its blocks by one `fixed` joint (body1/marker1 and body2 the point, or "
                                               "the reverse); its mass and inertia join the block's mass matrix before the reduction (the "
                                               "modes carry it), its node stays (markers, joints, sensors, shape) held at its pose "
                                               "relative to that point by a tie that replaces the joint (docs/input.md, \"Reduced beam blocks\")"},
      {"geometric_stiffness", KeyType::Flag, "–", "off", "on: the elastic force gets the cubic and quartic terms of the block's own "
                                                        "nonlinear beam energy along the basis, ½ T[ξ,ξ] + ⅙ Q[ξ,ξ,ξ] (stress stiffening; "
                                                        "docs/theory/reduced_bodies.md); "
                                                        "off: linear K ξ"},
      {"static_modes", KeyType::Choice, "–", "none", "`inertia`: append the static responses of the block (interface held) to the "
                                                     "body-frame inertia loads — 3 uniform accelerations and 9 fields linear in position "
                                                     "(centrifugal, angular) — M-orthonormalized against the modes: up to 12 more "
                                                     "amplitudes, the axial stretch a spinning link's stiffening needs; `none`", {}, "", "",
       {"none", "inertia"}},
      {"derivatives", KeyType::Integer, "–", "0", "with `geometric_stiffness: on`: append the static modal derivatives of the first N "
                                                 "basis vectors (the constraint modes first, then the normal modes), one per pair i ≤ j, "
                                                 "M-orthonormalized and dependent ones dropped: the second-order static response to the "
                                                 "deformation (for a beam, the foreshortening that bending brings), without which a "
                                                 "truncated basis of a slender block locks under geometric stiffness "
                                                 "(docs/theory/reduced_bodies.md, \"Modal derivatives\"); up to N(N+1)/2 more amplitudes",
       Range::non_negative()}}};
  return s;
}

namespace {

/// A rigid body of `reduction.bodies`: its item, mass properties and pose, the `fixed` joint that
/// welds it and the mesh node it is welded to.
struct BodyWeld {
  std::string body, joint;
  YAML::Node item;
  int mesh = -1;
  double mass = 0.0;
  Eigen::Matrix3d inertia, orientation;
  Eigen::Vector3d position;
};

/// The `name` of a list item (empty if it has none).
std::string listed_name(const YAML::Node& n) { return n.IsMap() && n["name"] && n["name"].IsScalar() ? n["name"].Scalar() : ""; }

/// The bodies `reduction.bodies` names (at `bn`, path `at`), read ahead of the scene's `bodies`
/// (their own reader later makes their nodes without a mass, types/rigid_body_3d.cpp), each with
/// the one `fixed` joint between it (or one of its markers) and a named mesh point of the blocks
/// (`in_block`: the body's mesh nodes).
std::vector<BodyWeld> read_body_welds(const Item& it, const Section& r, const YAML::Node& bn, const std::string& at,
                                      const std::map<int, int>& in_block, const std::string& group) {
  Reader& rd = it.rd;
  const YAML::Node bodies = it.sb.root["bodies"], joints = it.sb.root["joints"];
  if (bodies && !bodies.IsSequence()) rd.fail(bodies, "bodies", "expected a list of bodies");
  if (joints && !joints.IsSequence()) rd.fail(joints, "joints", "expected a list of joints");
  std::vector<BodyWeld> out;
  for (const std::string& name : r.texts("bodies")) {
    for (const BodyWeld& w : out)
      if (w.body == name) rd.fail(bn, at, "'" + name + "' is given twice");
    if (it.sb.welded_bodies.count(name))
      rd.fail(bn, at, "'" + name + "' is part of the reduced block '" + it.sb.welded_bodies.at(name) + "' already");
    BodyWeld w;
    w.body = name;
    bool found = false;  // (a default YAML::Node counts as defined: a flag, not the node, says whether one was found)
    if (bodies && bodies.IsSequence())
      for (size_t i = 0; i < bodies.size() && !found; ++i)
        if (listed_name(bodies[i]) == name) {
          w.item = bodies[i];
          found = true;
        }
    if (!found) rd.fail(bn, at, "no body named '" + name + "' in `bodies` (a reduced body takes spatial rigid bodies welded to its blocks)");
    const YAML::Node type = w.item["type"];
    if (!type || !type.IsScalar() || type.Scalar() != "rigid_body")
      rd.fail(bn, at, "'" + name + "' is not a `rigid_body` (bodies[" + name + "]): only a rigid body can be welded into a reduced body");
    const Section keys(rd, w.item, "bodies[" + name + "]", rigid_body_schema());
    const RigidBodyInput in = rigid_body_input(rd, keys);
    // Its mass moves with the blocks and its node is held by the tie: a velocity of its own would
    // be dropped (the full mesh would project it onto the weld instead).
    for (const char* v : {"velocity", "angular_velocity"})
      if (keys.has(v) && keys.vec3(v).squaredNorm() > 0.0)
        rd.fail(keys.node(v), keys.key_path(v), "'" + name + "' is welded into the reduced block '" + it.name +
                                                    "': it moves with its blocks from their initial velocity; leave its own out");
    w.mass = in.mass;
    w.inertia = in.inertia;
    w.position = in.position;
    w.orientation = in.orientation;
    // The weld: a `fixed` joint with the body (or a marker of it) on one side and a named mesh
    // point of the blocks on the other.
    const auto is_body = [&](const YAML::Node& j, const char* body_key, const char* marker_key) {
      if (j[body_key] && j[body_key].IsScalar() && j[body_key].Scalar() == name) return true;
      return j[marker_key] && j[marker_key].IsScalar() &&
             std::find(in.markers.begin(), in.markers.end(), j[marker_key].Scalar()) != in.markers.end();
    };
    const auto mesh_point = [&](const YAML::Node& j, const char* body_key) {
      if (!j[body_key] || !j[body_key].IsScalar()) return -1;
      for (const auto& [m, pn] : it.sb.blocks.point_name)
        if (pn == j[body_key].Scalar() && in_block.count(m)) return m;
      return -1;
    };
    std::string others;
    if (joints && joints.IsSequence())
      for (const YAML::Node& j : joints) {
        if (!j.IsMap() || !j["type"] || !j["type"].IsScalar() || j["type"].Scalar() != "fixed") continue;
        if (j["group"]) continue;  // a joint per node of a group: not a weld at one point
        int m = -1;
        if (is_body(j, "body1", "marker1")) m = mesh_point(j, "body2");
        if (m < 0 && is_body(j, "body2", "marker2")) m = mesh_point(j, "body1");
        if (m < 0) continue;
        if (w.mesh >= 0)
          rd.fail(bn, at, "'" + name + "' is welded to " + group + " by two `fixed` joints ('" + w.joint + "' and '" + listed_name(j) +
                              "'): a rigid body inside a reduced body is welded at one point (weld the blocks at a shared point instead)");
        w.mesh = m;
        w.joint = listed_name(j);
      }
    if (w.mesh < 0)
      rd.fail(bn, at, "'" + name + "' is welded to no point of " + group + ": give a `fixed` joint with body1 (or marker1) '" + name +
                          "' and body2 a named mesh point of the block (not a `group` joint)");
    out.push_back(w);
  }
  return out;
}

}  // namespace

void read_reduced_block_3d(const Item& it, const BlockPartOf& part_of) {
  const YAML::Node rn = it.keys.node("reduction");
  const std::string at = it.at("reduction");
  if (!rn.IsMap()) it.rd.fail(rn, at, "expected a map {method: craig_bampton | herting | rigid, modes: k, interface: [points]}");
  const Section r(it.rd, rn, at, reduction_schema());
  const int method = r.choice("method");
  const bool rigid = method == 1;
  const Reduction basis = method == 2 ? Reduction::herting : Reduction::craig_bampton;
  if (!rigid) it.rd.need(rn, "modes", at);
  const int modes = rigid ? 0 : r.integer("modes");
  const std::vector<std::string> names = r.texts("interface");
  const bool geometric = r.flag("geometric_stiffness", false);
  const bool inertia_modes = r.choice("static_modes", 0) == 1;
  const int derivatives = r.integer("derivatives", 0);
  if (derivatives > 0 && !geometric)
    it.rd.fail(rn["derivatives"], at + ".derivatives", "needs `geometric_stiffness: on` (the derivatives are the basis of its quadratic energy)");
  if (inertia_modes && rigid) it.rd.fail(rn["static_modes"], at + ".static_modes", "needs elastic amplitudes: method rigid keeps none");
  if (geometric && rigid) it.rd.fail(rn["geometric_stiffness"], at + ".geometric_stiffness", "needs elastic amplitudes: method rigid keeps none");
  if (names.empty()) it.rd.fail(rn["interface"], at + ".interface", "names no point: the first interface point carries the body's frame");
  // The body's blocks: this one, then those of `blocks` (scene_mesh.cpp read_blocks checked that
  // each is another block of the list, without a reduction, taken once), each built by its own
  // type with its own section; the elements of all are reduced together.
  std::deque<std::string> more_names;
  std::deque<Item> more;  // stable: the parts' builders hold them
  for (const std::string& other : r.has("blocks") ? r.texts("blocks") : std::vector<std::string>{}) {
    const MeshBlocks::ListedBlock& lb = it.sb.blocks.listed.at(other);
    more_names.push_back(other);
    more.push_back(Item{it.rd, it.sb, it.model, lb.node, more_names.back(), *lb.path, *lb.keys});
  }
  std::vector<BlockPart> parts{part_of(it)};
  for (const Item& m : more) parts.push_back(part_of(m));
  std::vector<int> block_nodes;
  std::string group = "group '" + parts.front().group + "'";
  for (size_t p = 0; p < parts.size(); ++p) {
    block_nodes.insert(block_nodes.end(), parts[p].nodes.begin(), parts[p].nodes.end());
    if (p > 0) group = (p == 1 ? "groups '" + parts.front().group + "'" : group) + ", '" + parts[p].group + "'";
  }
  std::sort(block_nodes.begin(), block_nodes.end());
  block_nodes.erase(std::unique(block_nodes.begin(), block_nodes.end()), block_nodes.end());
  const BlockElementsOf add_elements = [&](Model& model, const BlockNodeOf& node_of) {
    std::vector<int> ids;
    for (const BlockPart& p : parts) {
      const std::vector<int> e = p.add_elements(model, node_of);
      ids.insert(ids.end(), e.begin(), e.end());
    }
    return ids;
  };
  // The interface points: named mesh points on the body's blocks.
  std::map<int, int> in_block;  // mesh node → scratch node
  for (int m : block_nodes) in_block.emplace(m, -1);
  const MeshBlocks& mb = it.sb.blocks;  // NOLINT: read only here
  std::vector<int> mesh_interface;
  for (const std::string& name : names) {
    int found = -1;
    for (const auto& [m, pn] : mb.point_name)
      if (pn == name && in_block.count(m)) found = m;
    if (found < 0)
      it.rd.fail(rn["interface"], at + ".interface", "'" + name + "' is not a named mesh point of " + group);
    if (std::find(mesh_interface.begin(), mesh_interface.end(), found) != mesh_interface.end())
      it.rd.fail(rn["interface"], at + ".interface", "'" + name + "' is given twice (or names the same mesh point as another entry)");
    mesh_interface.push_back(found);
  }
  // The interface points' nodes of the run's model first, so that the scratch block is reduced
  // about their poses (a node may be shared with another block that made it): the first carries
  // the floating frame, the others are tied to the body (joints/reduced_interface_tie.hpp).
  std::map<int, int> interface_node;  // mesh node → run model node
  Model scratch;
  const int m0 = mesh_interface.front();
  const std::vector<int> elements = add_elements(scratch, [&](int m, const Eigen::VectorXd& q0) {
    int& id = in_block[m];
    if (id >= 0) return id;
    const bool on_interface = std::find(mesh_interface.begin(), mesh_interface.end(), m) != mesh_interface.end();
    // An inner point has no node of the run's model: a node another block made there already
    // (a weld of two blocks) would be left unconnected, so the point must be an interface point.
    if (!on_interface && mb.node_of[static_cast<size_t>(m)] >= 0)
      it.rd.fail(rn["interface"], at + ".interface", "mesh point '" + mesh_point_label(mb, m) +
                 "' of " + group + " is shared with another block: add it to reduction.interface (a named point) so that the blocks stay connected");
    Node nd;
    nd.kind = NodeKind::Frame3D;
    nd.name = std::to_string(m);
    nd.q0 = q0;
    if (on_interface) {
      const int run = interface_node[m] = block_node(it, m, NodeKind::Frame3D, q0, Eigen::VectorXd::Zero(6));
      nd.q0 = it.model.node(run).q0;
    }
    nd.v0 = Eigen::VectorXd::Zero(6);
    return id = scratch.add_node(nd);
  });
  const int frame = interface_node.at(m0);
  std::vector<int> others;
  for (size_t i = 1; i < mesh_interface.size(); ++i) others.push_back(in_block.at(mesh_interface[i]));
  // The rigid bodies welded into the body: masses at their weld points in the scratch model.
  const std::vector<BodyWeld> welds = r.has("bodies") ? read_body_welds(it, r, rn["bodies"], at + ".bodies", in_block, group) : std::vector<BodyWeld>{};
  std::vector<int> with_masses = elements;
  for (const BodyWeld& w : welds) {
    const int node = in_block.at(w.mesh);
    const Pose<double> p = pose_of(scratch.node(node).q0.data());
    const BodyWeld& bw = w;
    // The body's centre and inertia in the node frame; no gravity here (the reduced body's weight
    // comes from its M0, which the mass joins).
    const Eigen::Matrix3d Rrel = p.R.transpose() * bw.orientation;
    scratch.add_element(std::make_unique<RigidBody3D>(bw.body, node, bw.mass, Eigen::Matrix3d(Rrel * bw.inertia * Rrel.transpose()),
                                                      Eigen::Vector3d::Zero(), Eigen::Vector3d(p.R.transpose() * (bw.position - p.x))));
    with_masses.push_back(static_cast<int>(scratch.elements().size()) - 1);
  }
  const BlockMatrices matrices = assemble_block(scratch, with_masses, /*dense=*/false);  // sparse only: O(n) memory
  ReducedBlock rb;
  try {
    const auto reduce = [&] {
      ReducedBlock r = reduce_block(scratch, matrices, in_block.at(m0), rigid ? std::vector<int>{} : others, modes, inertia_modes, basis);
      if (derivatives > 0) add_modal_derivatives(scratch, elements, matrices, derivatives, r);
      if (geometric) nonlinear_stiffness(scratch, elements, matrices, r);
      return r;
    };
    // Read from OUTDIR/NAME.superelements.h5 when a run reduced this body before with the same key
    // (io/superelement_cache.hpp): the items' keys (this block's and those of `blocks`), its
    // interface points, the scratch nodes and elements, K and M.
    std::string settings = "block " + it.name + "\n" + YAML::Dump(it.node);
    for (const Item& m : more) settings += "\nwith block " + m.name + "\n" + YAML::Dump(m.node);
    // The evaluated reduction keys too: the text may be an expression of `parameters` (modes: nm),
    // whose value --set can change without changing the text (nor K and M).
    settings += "\nevaluated: method " + std::to_string(method) + " modes " + std::to_string(modes) + " static_modes " +
                std::to_string(inertia_modes ? 1 : 0) + " geometric_stiffness " + std::to_string(geometric ? 1 : 0) +
                " derivatives " + std::to_string(derivatives);
    settings += "\ninterface";
    for (int m : mesh_interface) settings += " " + std::to_string(m);
    for (const BodyWeld& w : welds) settings += "\nwith body " + w.body + " at mesh node " + std::to_string(w.mesh) + "\n" + YAML::Dump(w.item);
    rb = it.sb.superelements ? it.sb.superelements->find_or_reduce(it.name, SuperelementKey(settings, scratch, elements, matrices), reduce)
                             : reduce();
  } catch (const std::invalid_argument& e) {
    it.rd.fail(rn, at, "block '" + it.name + "': " + e.what());
  } catch (const SolverError& e) {
    // The eigensolver or MUMPS inside the reduction: every rank reduces the block identically, so
    // every rank gets here, and the message names the block instead of only the solver.
    it.rd.fail(rn, at, "block '" + it.name + "': the reduction failed: " + e.what());
  }
  // The block's other mesh nodes have no node in the run's model: their motion is the frame's and
  // the amplitudes' (ReducedBlock::node_pose).
  for (const auto& [m, id] : in_block)
    if (!interface_node.count(m)) {
      it.sb.blocks.reduced.emplace(m, it.name);
      const auto pn = mb.point_name.find(m);
      if (pn != mb.point_name.end()) it.sb.reduced_points.emplace(pn->second, it.name);
    }
  std::vector<int> amplitudes;
  for (int i = 0; i < rb.matrices.elastic(); ++i) {
    Node c;
    c.name = it.name + ":xi" + std::to_string(i);
    c.kind = NodeKind::LineParticle2D;  // one vector-space unknown
    c.q0 = Eigen::VectorXd::Zero(1);
    c.v0 = Eigen::VectorXd::Zero(1);
    if (it.model.find_node(c.name) >= 0) it.rd.fail(it.node, it.path, "node '" + c.name + "' exists already");
    amplitudes.push_back(it.model.add_node(c));
  }
  auto body = std::make_unique<ReducedBody>(it.name, frame, amplitudes, rb.matrices, it.sb.gravity);
  body->attach_reconstruction(reduced_block_mesh(it, scratch, elements, rb, in_block, derivatives > 0));  // the full mesh for output and sensors
  it.model.add_element(std::move(body));
  // Each other interface point: its node held at node_pose by 6 equations (docs/theory/reduced_bodies.md).
  for (size_t i = 1; i < mesh_interface.size(); ++i) {
    const int m = mesh_interface[i];
    const auto slot = std::lower_bound(matrices.nodes.begin(), matrices.nodes.end(), in_block.at(m));
    const size_t a = static_cast<size_t>(slot - matrices.nodes.begin());
    it.model.add_constraint(std::make_unique<ReducedInterfaceTie>(it.name + ":tie:" + names[i], interface_node.at(m), frame, amplitudes,
                                                                  rb.positions[a], rb.rotations[a], rb.shapes[a]));
  }
  // Each welded body: its weld joint becomes a tie of the body's node when the joints are read
  // (types/spatial_joints_3d.cpp), at its pose relative to the block node at t = 0.
  for (const BodyWeld& w : welds) {
    const int node = in_block.at(w.mesh);
    const auto slot = std::lower_bound(matrices.nodes.begin(), matrices.nodes.end(), node);
    const size_t a = static_cast<size_t>(slot - matrices.nodes.begin());
    const Pose<double> p = pose_of(scratch.node(node).q0.data());
    SceneBuilder::Weld weld;
    weld.body = w.body;
    weld.block = it.name;
    weld.frame = frame;
    weld.amplitudes = amplitudes;
    weld.position = rb.positions[a];
    weld.rotation = rb.rotations[a];
    weld.shape = rb.shapes[a];
    weld.offset_position = p.R.transpose() * (w.position - p.x);
    weld.offset_rotation = p.R.transpose() * w.orientation;
    it.sb.welds[w.joint] = weld;
    it.sb.welded_bodies[w.body] = it.name;
  }
}

}  // namespace alphaflex::scene_detail
