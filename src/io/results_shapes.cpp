#include "results_shapes.hpp"

#include <Eigen/Geometry>

#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex::io_detail {

ShapeLayout shape_layout(const Model& global) {
  ShapeLayout L;
  if (global.shapes().empty()) return L;
  L.point_offset = L.face_offset = L.connectivity_offset = {0};
  for (const BodyShape& b : global.shapes()) {
    unsigned long long entries = 0;
    for (const auto& f : b.surface.faces) entries += 1 + f.size();
    L.point_offset.push_back(L.point_offset.back() + b.surface.points.size());
    L.face_offset.push_back(L.face_offset.back() + b.surface.faces.size());
    L.connectivity_offset.push_back(L.connectivity_offset.back() + entries);
  }
  return L;
}

ShapeRows::ShapeRows(const Subdomain& sub, const ShapeLayout& layout) : sub_(sub), layout_(layout) {
  const auto& shapes = sub.global_model().shapes();
  points_.total = layout.points();
  connectivity_.total = layout.connectivity_size();
  std::vector<int> local(sub.global_model().nodes().size(), -1);  // global node → owned local node
  for (int i = 0; i < sub.num_owned_nodes(); ++i) local[static_cast<size_t>(sub.global_node(i))] = i;
  for (size_t k = 0; k < shapes.size(); ++k) {
    const int n = local[static_cast<size_t>(shapes[k].node)];
    if (n < 0) continue;
    mine_.emplace_back(static_cast<int>(k), n);
    points_.add(layout.point_offset[k], layout.point_offset[k + 1] - layout.point_offset[k]);
    connectivity_.add(layout.connectivity_offset[k], layout.connectivity_offset[k + 1] - layout.connectivity_offset[k]);
  }
}

void ShapeRows::write_topology(H5Calls& h5, hid_t topo, hid_t xfer) const {
  if (layout_.points() == 0) return;
  std::vector<int> ids;
  for (const auto& [k, node] : mine_) {
    const int first = static_cast<int>(layout_.point_offset[static_cast<size_t>(k)]);
    for (const auto& f : sub_.global_model().shapes()[static_cast<size_t>(k)].surface.faces) {
      ids.push_back(f.size() == 3 ? 4 : 5);  // XDMF Mixed: triangle, quadrilateral
      for (int p : f) ids.push_back(first + p);
    }
  }
  write_int_rows(h5, topo, "shapes", connectivity_, ids.data(), xfer);
}

namespace {

/// A body's pose: its frame's (x, R), a planar body's ((x, y, 0), rotation θ about z).
struct BodyPose {
  Eigen::Vector3d x;
  Eigen::Matrix3d R;
};

BodyPose body_pose(const Node& n, const double* q) {
  if (n.spatial()) {
    const Pose<double> p = pose_of(q);
    return {p.x, p.R};
  }
  return {Eigen::Vector3d(q[0], q[1], 0.0), Eigen::AngleAxisd(q[2], Eigen::Vector3d::UnitZ()).toRotationMatrix()};
}

}  // namespace

void ShapeRows::write_step(H5Calls& h5, hid_t group, const MechanicalState& s, hid_t xfer) const {
  if (layout_.points() == 0) return;
  std::vector<double> pos, disp, vel;
  for (const auto& [k, local] : mine_) {
    const Node& n = sub_.model().nodes()[static_cast<size_t>(local)];
    const BodyPose now = body_pose(n, s.q.data() + n.first_conf), start = body_pose(n, n.q0.data());
    // Velocity of a body point: ẋ + ω × R·X, ω in the world frame (a frame's unknowns are the
    // world velocity and the body-frame angular velocity Ω, ω = R·Ω; a planar body's θ̇ about z).
    const Eigen::Vector3d v = n.spatial() ? Eigen::Vector3d(s.v.segment<3>(n.first_dof))
                                          : Eigen::Vector3d(s.v[n.first_dof], s.v[n.first_dof + 1], 0.0);
    const Eigen::Vector3d w = n.spatial() ? Eigen::Vector3d(now.R * s.v.segment<3>(n.first_dof + 3))
                                          : Eigen::Vector3d(0.0, 0.0, s.v[n.first_dof + 2]);
    for (const Eigen::Vector3d& X : sub_.global_model().shapes()[static_cast<size_t>(k)].surface.points) {
      const Eigen::Vector3d r = now.R * X, x = now.x + r, x0 = start.x + start.R * X, u = x - x0, xd = v + w.cross(r);
      pos.insert(pos.end(), x.data(), x.data() + 3);
      disp.insert(disp.end(), u.data(), u.data() + 3);
      vel.insert(vel.end(), xd.data(), xd.data() + 3);
    }
  }
  write_rows(h5, group, "shape_points", points_, 3, pos.data(), xfer);
  write_rows(h5, group, "shape_displacement", points_, 3, disp.data(), xfer);
  write_rows(h5, group, "shape_velocity", points_, 3, vel.data(), xfer);
}

}  // namespace alphaflex::io_detail
