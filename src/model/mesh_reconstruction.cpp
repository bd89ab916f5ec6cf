// The full mesh of a reduced body from its state (header; docs/theory/reduced_bodies.md,
// "Reconstruction").
#include "alphaflex/model/mesh_reconstruction.hpp"

#include <stdexcept>
#include <string>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

void reduced_point_pose(const Eigen::Vector3d& X, const Eigen::Matrix3d& R0, const Eigen::MatrixXd& shape, const Eigen::Vector3d& xf,
                        const Eigen::Matrix3d& Rf, const Eigen::VectorXd& xi, Eigen::Vector3d& x, Eigen::Matrix3d& R) {
  const Eigen::VectorXd d = shape * xi;
  x = xf + Rf * (X + d.head<3>());
  R = Rf * R0 * exp_so3(Eigen::Vector3d(d.tail<3>()));
}

MeshReconstruction::MeshReconstruction(std::vector<Point> points, std::vector<std::shared_ptr<const Element>> elements,
                                       std::vector<std::string> names, Derived derived)
    : points_(std::move(points)), elements_(std::move(elements)), names_(std::move(names)), derived_(std::move(derived)) {
  if (points_.empty()) throw std::invalid_argument("mesh reconstruction: no points");
  if (names_.empty()) names_.resize(points_.size());
  if (names_.size() != points_.size()) throw std::invalid_argument("mesh reconstruction: not one name per point");
  m_ = static_cast<int>(points_.front().shape.cols());
  for (const Point& p : points_)
    if (p.shape.rows() != 6 || p.shape.cols() != m_) throw std::invalid_argument("mesh reconstruction: a point's basis rows are not 6 x m");
  for (const auto& e : elements_)
    for (int n : e->nodes())
      if (n < 0 || static_cast<size_t>(n) >= points_.size())
        throw std::invalid_argument("mesh reconstruction: element '" + e->name() + "' names point " + std::to_string(n) + " of " +
                                    std::to_string(points_.size()));
}

const char* MeshReconstruction::structure() const { return elements_.empty() ? nullptr : elements_.front()->structure(); }

std::vector<CellField> MeshReconstruction::cell_fields() const {
  return elements_.empty() ? std::vector<CellField>{} : elements_.front()->cell_fields();
}

LocalState MeshReconstruction::state(const LocalState& body) const {
  const Pose<double> f = pose_of(body.q.data());
  const Eigen::VectorXd xi = body.q.segment(7, m_), xid = body.v.segment(6, m_);
  const Eigen::Vector3d xfd = body.v.head<3>(), Wf = body.v.segment<3>(3);
  const size_t n = points_.size();
  LocalState s;
  s.t = body.t;
  s.load_factor = body.load_factor;
  s.q.resize(7 * static_cast<Eigen::Index>(n));
  s.v.resize(6 * static_cast<Eigen::Index>(n));
  s.qdd = Eigen::VectorXd::Zero(6 * static_cast<Eigen::Index>(n));
  for (size_t a = 0; a < n; ++a) {
    const Point& p = points_[a];
    const Eigen::VectorXd d = p.shape * xi, dd = p.shape * xid;
    const Eigen::Vector3d phi = d.tail<3>(), r = p.X + d.head<3>();
    const Eigen::Matrix3d E = exp_so3(phi);
    const Eigen::Vector3d x = f.x + f.R * r;
    const Eigen::Quaterniond quat(f.R * p.R0 * E);
    const Eigen::Index o = 7 * static_cast<Eigen::Index>(a), od = 6 * static_cast<Eigen::Index>(a);
    s.q.segment<3>(o) = x;
    s.q.segment<4>(o + 3) << quat.w(), quat.x(), quat.y(), quat.z();
    s.v.segment<3>(od) = xfd + f.R * (Wf.cross(r) + dd.head<3>());
    s.v.segment<3>(od + 3) = E.transpose() * p.R0.transpose() * Wf + tangent_so3(phi) * dd.tail<3>();
  }
  return s;
}

Eigen::Vector3d MeshReconstruction::point_position(const LocalState& body, size_t a) const {
  const Pose<double> f = pose_of(body.q.data());
  const Eigen::VectorXd xi = body.q.segment(7, m_);
  const Point& p = points_.at(a);
  const Eigen::VectorXd d = p.shape * xi;
  const Eigen::Vector3d r = p.X + d.head<3>();
  return f.x + f.R * r;
}

LocalState MeshReconstruction::element_state(const LocalState& points, size_t k) const {
  const Element& e = *elements_[k];
  const Eigen::Index nn = static_cast<Eigen::Index>(e.nodes().size());
  LocalState s;
  s.t = points.t;
  s.load_factor = points.load_factor;
  s.q.resize(7 * nn);
  s.v.resize(6 * nn);
  s.qdd.resize(6 * nn);
  for (Eigen::Index i = 0; i < nn; ++i) {
    const Eigen::Index a = e.nodes()[static_cast<size_t>(i)];
    s.q.segment<7>(7 * i) = points.q.segment<7>(7 * a);
    s.v.segment<6>(6 * i) = points.v.segment<6>(6 * a);
    s.qdd.segment<6>(6 * i) = points.qdd.segment<6>(6 * a);
  }
  return s;
}

std::vector<Eigen::VectorXd> MeshReconstruction::element_outputs(const LocalState& body) const {
  LocalState mirrored = body;
  mirrored.q.segment(7, m_) = -body.q.segment(7, m_);
  const LocalState plus = state(body), minus = state(mirrored);
  std::vector<Eigen::VectorXd> out(elements_.size());
  Eigen::VectorXd a, b;
  for (size_t k = 0; k < elements_.size(); ++k) {
    elements_[k]->output(element_state(plus, k), a);
    elements_[k]->output(element_state(minus, k), b);
    out[k] = 0.5 * (a - b);
    if (derived_) derived_(out[k]);
  }
  return out;
}

}  // namespace alphaflex
