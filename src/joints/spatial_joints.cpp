#include "alphaflex/joints/spatial_joints.hpp"

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

void SpatialJoint::geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
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
