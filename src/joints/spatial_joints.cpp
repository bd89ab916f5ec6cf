#include "alphaflex/joints/spatial_joints.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

namespace alphaflex {

const char* to_string(SpatialJointType t) {
  switch (t) {
    case SpatialJointType::Spherical: return "spherical";
    case SpatialJointType::Universal: return "universal";
    case SpatialJointType::Revolute: return "revolute";
    case SpatialJointType::Cylindrical: return "cylindrical";
    case SpatialJointType::Prismatic: return "prismatic";
    case SpatialJointType::Planar: return "planar";
    case SpatialJointType::Fixed: return "fixed";
    case SpatialJointType::PointOnLine: return "point_on_line";
    case SpatialJointType::PointOnPlane: return "point_on_plane";
  }
  return "?";
}

int equations_of(SpatialJointType t) {
  switch (t) {
    case SpatialJointType::Spherical: return 3;
    case SpatialJointType::Universal: return 4;
    case SpatialJointType::Revolute: return 5;
    case SpatialJointType::Cylindrical: return 4;
    case SpatialJointType::Prismatic: return 5;
    case SpatialJointType::Planar: return 3;
    case SpatialJointType::Fixed: return 6;
    case SpatialJointType::PointOnLine: return 2;
    case SpatialJointType::PointOnPlane: return 1;
  }
  return 0;
}

SpatialJoint::SpatialJoint(std::string name, std::vector<int> nodes, SpatialJointType type, SpatialMarker a,
                           SpatialMarker b, TimeFunctionPtr angle, TimeFunctionPtr displacement)
    : Constraint(std::move(name), std::move(nodes)), type_(type), a_(a), b_(b), angle_(std::move(angle)),
      displacement_(std::move(displacement)) {
  if (angle_ && type_ != SpatialJointType::Revolute && type_ != SpatialJointType::Cylindrical)
    throw std::invalid_argument("an angle driver needs a revolute or cylindrical joint");
  if (displacement_ && type_ != SpatialJointType::Prismatic && type_ != SpatialJointType::Cylindrical)
    throw std::invalid_argument("a displacement driver needs a prismatic or cylindrical joint");
  size_ = equations_of(type_) + (angle_ ? 1 : 0) + (displacement_ ? 1 : 0);
}

template <class S>
void SpatialJoint::operator()(const Pose<S>* frames, const S& t, KernelVector<S>& out) const {
  const Pose<S> A = a_.pose<S>(frames), B = b_.pose<S>(frames);
  const Vec3<S> d = B.x - A.x;
  const auto a1 = A.R.col(0), a2 = A.R.col(1), a3 = A.R.col(2);
  const auto b1 = B.R.col(0), b2 = B.R.col(1), b3 = B.R.col(2);
  out.resize(size_);
  int k = 0;
  auto put = [&](const S& v) { out[k++] = v; };
  switch (type_) {
    case SpatialJointType::Spherical:
      for (int i = 0; i < 3; ++i) put(d[i]);
      break;
    case SpatialJointType::Universal:
      for (int i = 0; i < 3; ++i) put(d[i]);
      put(a1.dot(b2));
      break;
    case SpatialJointType::Revolute:
      for (int i = 0; i < 3; ++i) put(d[i]);
      put(a3.dot(b1));
      put(a3.dot(b2));
      break;
    case SpatialJointType::Cylindrical:
      put(a1.dot(d));
      put(a2.dot(d));
      put(a3.dot(b1));
      put(a3.dot(b2));
      break;
    case SpatialJointType::Prismatic:
      put(a1.dot(d));
      put(a2.dot(d));
      put(a3.dot(b1));
      put(a3.dot(b2));
      put(a1.dot(b2));
      break;
    case SpatialJointType::Planar:
      put(a3.dot(d));
      put(a3.dot(b1));
      put(a3.dot(b2));
      break;
    case SpatialJointType::Fixed:
      for (int i = 0; i < 3; ++i) put(d[i]);
      put(a2.dot(b3));
      put(a3.dot(b1));
      put(a1.dot(b2));
      break;
    case SpatialJointType::PointOnLine:
      put(a1.dot(d));
      put(a2.dot(d));
      break;
    case SpatialJointType::PointOnPlane:
      put(a3.dot(d));
      break;
  }
  if (angle_) {
    using std::cos;
    using std::sin;
    const S phi = time_value<S>(*angle_, t);
    put(a1.dot(cos(phi) * b2 - sin(phi) * b1));  // sin(ϕ − φ(t)), ϕ: angle of A from B about b3
  }
  if (displacement_) put(-b3.dot(d) - time_value<S>(*displacement_, t));  // (p_A − p_B)·b3 = u(t)
}

void SpatialJoint::evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  kernel_jacobian(*this, q, t, phi, phi_q);
}

namespace {

// Closed-form geometric stiffness. Every equation of a spatial joint is a sum of dot products u·v of
// vectors among: marker axes R_f w (w a fixed axis in node f's frame), marker points x_f + R_f s,
// d = p_B − p_A, and fixed world vectors; and every such vector is affine in the entries of (x_f, R_f).
// With the perturbations of model/spatial_kernel.hpp, (x + δx' + δx, R(I + δθ'^)(I + δθ^)), the
// mixed derivative of a dot product is
//     ∂²(u·v)/∂δ'_j∂δ_i = u_ji·v + u_i·v_j + u_j·v_i + u·v_ji,
// first derivatives of R_f w being R_f (e_m × w) = −R_f ŵ e_m, and the only second derivatives
// those of R_f w within one node's rotations: ∂²/∂δθ'_p∂δθ_m R_f w = R_f ê_p ê_m w
// = R_f (e_m w_p − δ_mp w), so that v·u_ji over that block is (R_fᵀv) wᵀ − (R_fᵀv · w) I
// (row m: inner, column p: outer). The same bits of K_Φ as nested AD up to round-off (tested
// against kernel_second and finite differences), at a small fraction of its cost.
struct JointVector {
  Eigen::Vector3d value = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 3, 12> d1 = Eigen::Matrix<double, 3, 12>::Zero();  // ∂/∂δ, 6 per node
  struct Rotating {
    int node = 0;
    Eigen::Vector3d w;  // in the node's frame
    double sign = 1.0;
  };
  std::array<Rotating, 2> parts{};
  int nparts = 0;
  bool varies = false;  // d1 ≠ 0 (false: a fixed world vector, on the ground)
};

/// R_f w: axis `k` of marker m (a fixed world vector on the ground).
JointVector marker_axis(const SpatialMarker& m, int k, const Pose<double>* frames) {
  JointVector u;
  if (m.slot < 0) {
    u.value = m.rotation.col(k);
    return u;
  }
  const Eigen::Matrix3d& R = frames[m.slot].R;
  const Eigen::Vector3d w = m.rotation.col(k);
  u.value = R * w;
  u.d1.block<3, 3>(0, 6 * m.slot + 3) = -R * hat<double>(w);
  u.parts[0] = {m.slot, w, 1.0};
  u.nparts = 1;
  u.varies = true;
  return u;
}

/// x_f + R_f s: the point of marker m.
JointVector marker_point(const SpatialMarker& m, const Pose<double>* frames) {
  JointVector u;
  if (m.slot < 0) {
    u.value = m.position;
    return u;
  }
  const Pose<double>& f = frames[m.slot];
  u.value = f.x + f.R * m.position;
  u.d1.block<3, 3>(0, 6 * m.slot) = Eigen::Matrix3d::Identity();
  u.d1.block<3, 3>(0, 6 * m.slot + 3) = -f.R * hat<double>(m.position);
  u.parts[0] = {m.slot, m.position, 1.0};
  u.nparts = 1;
  u.varies = true;
  return u;
}

JointVector difference(const JointVector& b, const JointVector& a) {
  JointVector d;
  d.value = b.value - a.value;
  d.d1 = b.d1 - a.d1;
  d.varies = a.varies || b.varies;
  for (int i = 0; i < b.nparts; ++i) d.parts[static_cast<size_t>(d.nparts++)] = b.parts[static_cast<size_t>(i)];
  for (int i = 0; i < a.nparts; ++i) {
    JointVector::Rotating r = a.parts[static_cast<size_t>(i)];
    r.sign = -r.sign;
    d.parts[static_cast<size_t>(d.nparts++)] = r;
  }
  return d;
}

JointVector world_axis(int i) {
  JointVector u;
  u.value = Eigen::Vector3d::Unit(i);
  return u;
}

/// H += c ∂²(u·v)/∂δ'∂δ on the n unknowns of the joint's nodes.
void add_dot_second(double c, const JointVector& u, const JointVector& v, const Pose<double>* frames, int n,
                    Eigen::MatrixXd& H) {
  if (c == 0.0) return;
  if (u.varies && v.varies) {  // (with a fixed vector, u_i·v_j + u_j·v_i = 0)
    const auto U = u.d1.leftCols(n), V = v.d1.leftCols(n);
    H.noalias() += c * (U.transpose() * V + V.transpose() * U);
  }
  auto rotating = [&](const JointVector& a, const JointVector& other) {
    for (int i = 0; i < a.nparts; ++i) {
      const JointVector::Rotating& r = a.parts[static_cast<size_t>(i)];
      const Eigen::Vector3d g = frames[r.node].R.transpose() * other.value;
      H.block<3, 3>(6 * r.node + 3, 6 * r.node + 3).noalias() +=
          (c * r.sign) * (g * r.w.transpose() - g.dot(r.w) * Eigen::Matrix3d::Identity());
    }
  };
  rotating(u, v);
  rotating(v, u);
}

}  // namespace

void SpatialJoint::geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                                       Eigen::MatrixXd& k) const {
  const int nf = kernel_detail::frames_in(q);
  const int n = 6 * nf;
  const kernel_detail::Poses p = kernel_detail::poses(q, nf);
  const Pose<double>* frames = p.data();
  k.setZero(n, n);
  const JointVector a[3] = {marker_axis(a_, 0, frames), marker_axis(a_, 1, frames), marker_axis(a_, 2, frames)};
  const JointVector b[3] = {marker_axis(b_, 0, frames), marker_axis(b_, 1, frames), marker_axis(b_, 2, frames)};
  const JointVector d = difference(marker_point(b_, frames), marker_point(a_, frames));
  int e = 0;  // equation, in the order of operator()
  auto dot = [&](const JointVector& u, const JointVector& v, double c = 1.0) {
    add_dot_second(c * lambda[e], u, v, frames, n, k);
  };
  auto next = [&] { ++e; };
  auto position = [&] {
    for (int i = 0; i < 3; ++i) {
      dot(world_axis(i), d);
      next();
    }
  };
  switch (type_) {
    case SpatialJointType::Spherical: position(); break;
    case SpatialJointType::Universal:
      position();
      dot(a[0], b[1]), next();
      break;
    case SpatialJointType::Revolute:
      position();
      dot(a[2], b[0]), next();
      dot(a[2], b[1]), next();
      break;
    case SpatialJointType::Cylindrical:
      dot(a[0], d), next();
      dot(a[1], d), next();
      dot(a[2], b[0]), next();
      dot(a[2], b[1]), next();
      break;
    case SpatialJointType::Prismatic:
      dot(a[0], d), next();
      dot(a[1], d), next();
      dot(a[2], b[0]), next();
      dot(a[2], b[1]), next();
      dot(a[0], b[1]), next();
      break;
    case SpatialJointType::Planar:
      dot(a[2], d), next();
      dot(a[2], b[0]), next();
      dot(a[2], b[1]), next();
      break;
    case SpatialJointType::Fixed:
      position();
      dot(a[1], b[2]), next();
      dot(a[2], b[0]), next();
      dot(a[0], b[1]), next();
      break;
    case SpatialJointType::PointOnLine:
      dot(a[0], d), next();
      dot(a[1], d), next();
      break;
    case SpatialJointType::PointOnPlane: dot(a[2], d), next(); break;
  }
  if (angle_) {  // a1·(cos φ b2 − sin φ b1)
    const double phi = angle_->value(t);
    dot(a[0], b[1], std::cos(phi));
    dot(a[0], b[0], -std::sin(phi));
    next();
  }
  if (displacement_) dot(b[2], d, -1.0), next();  // −b3·d − u(t)
}

void SpatialJoint::geometric_stiffness_by_ad(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                                             Eigen::MatrixXd& k) const {
  kernel_second(*this, q, t, lambda, k);
}

void SpatialJoint::time_derivative(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi_t) const {
  if (!angle_ && !displacement_) {
    phi_t = Eigen::VectorXd::Zero(size_);
    return;
  }
  Eigen::VectorXd second;
  kernel_along_motion(*this, q, Eigen::VectorXd::Zero(q.size() / 7 * 6), t, 1.0, phi_t, second);
}

void SpatialJoint::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                                     Eigen::VectorXd& c) const {
  Eigen::VectorXd first;
  kernel_along_motion(*this, q, v, t, 1.0, first, c);
}

JointReaction SpatialJoint::reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const {
  Eigen::VectorXd phi;
  Eigen::MatrixXd J;
  kernel_jacobian(*this, q, t, phi, J);
  const Eigen::VectorXd g = -J.transpose() * lambda;  // generalized force of the joint on its nodes
  const Pose<double> node1 = pose_of(q.data());
  const Pose<double> frames[2] = {node1, q.size() >= 14 ? pose_of(q.data() + 7) : node1};
  const Pose<double> A = a_.pose<double>(frames);
  JointReaction r;
  r.location = A.x;
  r.force = g.segment<3>(0);
  r.moment = node1.R * g.segment<3>(3) - (A.x - node1.x).cross(r.force);
  r.frame = A.R;
  return r;
}

template void SpatialJoint::operator()(const Pose<double>*, const double&, KernelVector<double>&) const;

}  // namespace alphaflex
