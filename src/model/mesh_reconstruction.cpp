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
                                       std::vector<std::string> names, Derived derived, Recovery recovery)
    : points_(std::move(points)), elements_(std::move(elements)), names_(std::move(names)), derived_(std::move(derived)), recovery_(recovery) {
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
  if (!elements_.empty()) fields_ = elements_.front()->cell_fields();
}

const char* MeshReconstruction::structure() const { return elements_.empty() ? nullptr : elements_.front()->structure(); }

namespace {

/// The floating frame's pose and velocities and the amplitudes, read once from the body's state.
struct FrameState {
  explicit FrameState(const LocalState& body, int m)
      : f(pose_of(body.q.data())), xi(body.q.segment(7, m)), xid(body.v.segment(6, m)), xfd(body.v.head<3>()), Wf(body.v.segment<3>(3)) {}
  Pose<double> f;
  Eigen::VectorXd xi, xid;
  Eigen::Vector3d xfd, Wf;
};

/// Point p's 7 configuration numbers and 6 velocities (header, state()): the one place they are
/// computed, so that the whole mesh and one element's points agree to the last bit.
void point_state(const FrameState& b, const MeshReconstruction::Point& p, double* q, double* v) {
  const Eigen::VectorXd d = p.shape * b.xi, dd = p.shape * b.xid;
  const Eigen::Vector3d phi = d.tail<3>(), r = p.X + d.head<3>();
  const Eigen::Matrix3d E = exp_so3(phi);
  const Eigen::Vector3d x = b.f.x + b.f.R * r;
  const Eigen::Quaterniond quat(b.f.R * p.R0 * E);
  Eigen::Map<Eigen::Vector3d> qx(q), vx(v), vw(v + 3);
  qx = x;
  q[3] = quat.w();
  q[4] = quat.x();
  q[5] = quat.y();
  q[6] = quat.z();
  vx = b.xfd + b.f.R * (b.Wf.cross(r) + dd.head<3>());
  vw = E.transpose() * p.R0.transpose() * b.Wf + tangent_so3(phi) * dd.tail<3>();
}

}  // namespace

LocalState MeshReconstruction::state(const LocalState& body) const {
  const FrameState b(body, m_);
  const size_t n = points_.size();
  LocalState s;
  s.t = body.t;
  s.load_factor = body.load_factor;
  s.q.resize(7 * static_cast<Eigen::Index>(n));
  s.v.resize(6 * static_cast<Eigen::Index>(n));
  s.qdd = Eigen::VectorXd::Zero(6 * static_cast<Eigen::Index>(n));
  for (size_t a = 0; a < n; ++a) point_state(b, points_[a], s.q.data() + 7 * a, s.v.data() + 6 * a);
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

namespace {

/// ½ [S(ξ) − S(−ξ)] of one element from its local states at ξ and −ξ (element_outputs()), the
/// derived results then recomputed from it.
Eigen::VectorXd odd_part(const Element& e, const LocalState& plus, const LocalState& minus, const MeshReconstruction::Derived& derived) {
  Eigen::VectorXd a, b;
  e.output(plus, a);
  e.output(minus, b);
  Eigen::VectorXd out = 0.5 * (a - b);
  if (derived) derived(out);
  return out;
}

/// S(ξ) of one element (Recovery::whole).
Eigen::VectorXd whole(const Element& e, const LocalState& plus) {
  Eigen::VectorXd a;
  e.output(plus, a);
  return a;
}

LocalState mirrored(const LocalState& body, int m) {
  LocalState s = body;
  s.q.segment(7, m) = -body.q.segment(7, m);
  return s;
}

}  // namespace

std::vector<Eigen::VectorXd> MeshReconstruction::element_outputs(const LocalState& body) const {
  const LocalState plus = state(body);
  std::vector<Eigen::VectorXd> out(elements_.size());
  if (recovery_ == Recovery::whole) {
    for (size_t k = 0; k < elements_.size(); ++k) out[k] = whole(*elements_[k], element_state(plus, k));
    return out;
  }
  const LocalState minus = state(mirrored(body, m_));
  for (size_t k = 0; k < elements_.size(); ++k)
    out[k] = odd_part(*elements_[k], element_state(plus, k), element_state(minus, k), derived_);
  return out;
}

Eigen::VectorXd MeshReconstruction::element_output(const LocalState& body, size_t k) const {
  const Element& e = *elements_.at(k);
  // The element's own points at ξ and −ξ, in its node order: element_state() of state()'s.
  auto points = [&](const LocalState& at) {
    const FrameState b(at, m_);
    const Eigen::Index nn = static_cast<Eigen::Index>(e.nodes().size());
    LocalState s;
    s.t = at.t;
    s.load_factor = at.load_factor;
    s.q.resize(7 * nn);
    s.v.resize(6 * nn);
    s.qdd = Eigen::VectorXd::Zero(6 * nn);
    for (Eigen::Index i = 0; i < nn; ++i)
      point_state(b, points_[static_cast<size_t>(e.nodes()[static_cast<size_t>(i)])], s.q.data() + 7 * i, s.v.data() + 6 * i);
    return s;
  };
  if (recovery_ == Recovery::whole) return whole(e, points(body));
  return odd_part(e, points(body), points(mirrored(body, m_)), derived_);
}

Eigen::Index MeshReconstruction::output_size() const {
  Eigen::Index width = 0;
  for (const CellField& f : fields_) width += f.components;
  return 6 * static_cast<Eigen::Index>(points_.size()) + width * static_cast<Eigen::Index>(elements_.size());
}

Eigen::Index MeshReconstruction::output_index(size_t k, int c) const {
  const Eigen::Index ne = static_cast<Eigen::Index>(elements_.size());
  Eigen::Index at = 6 * static_cast<Eigen::Index>(points_.size());
  int first = 0;  // the field's first value in the element's own output
  for (const CellField& f : fields_) {
    if (c < first + f.components) return at + f.components * static_cast<Eigen::Index>(k) + (c - first);
    at += f.components * ne;
    first += f.components;
  }
  throw std::out_of_range("mesh reconstruction: an element has no output value " + std::to_string(c));
}

bool MeshReconstruction::output_cell(Eigen::Index index, size_t& k, int& c) const {
  const Eigen::Index ne = static_cast<Eigen::Index>(elements_.size());
  Eigen::Index i = index - 6 * static_cast<Eigen::Index>(points_.size());
  if (i < 0) return false;
  int first = 0;
  for (const CellField& f : fields_) {
    if (i < f.components * ne) {
      k = static_cast<size_t>(i / f.components);
      c = first + static_cast<int>(i % f.components);
      return true;
    }
    i -= f.components * ne;
    first += f.components;
  }
  return false;
}

}  // namespace alphaflex
