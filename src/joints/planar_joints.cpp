#include "alphaflex/joints/planar_joints.hpp"

namespace alphaflex {
namespace {

int local_size(const PlanarMarker& a, const PlanarMarker& b) { return a.ndof() + b.ndof(); }

Eigen::MatrixXd relative_jacobian(const PlanarMarker& p1, const PlanarMarker& p2, const Eigen::VectorXd& q) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2, q.size());
  p1.add_jacobian(q, 1.0, B);
  p2.add_jacobian(q, -1.0, B);
  return B;
}

Eigen::Vector3d as3(const Eigen::Vector2d& a) { return {a.x(), a.y(), 0.0}; }

}  // namespace

const std::vector<PlanarJointKind>& planar_joint_kinds() {
  // Φ's rows, named as the spatial joints name theirs: "x", "y" the components of r1 − r2; n the
  // line's normal; θ1 − θ2 the relative rotation (less its initial value).
  static const std::vector<PlanarJointKind> kinds{
      {"revolute", {"x", "y"}},
      {"point_on_line", {"n·(r1 − r2)"}},
      {"prismatic", {"n·(r1 − r2)", "θ1 − θ2"}},
      {"fixed", {"x", "y", "θ1 − θ2"}},
  };
  return kinds;
}

// ---------------------------------------------------------------- revolute
RevoluteJoint2D::RevoluteJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2)
    : PlanarJoint(std::move(name), std::move(nodes), PlanarJointType::revolute), p1_(p1), p2_(p2) {}

void RevoluteJoint2D::evaluate(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  phi = p1_.position(q) - p2_.position(q);
  phi_q = relative_jacobian(p1_, p2_, q);
}

void RevoluteJoint2D::geometric_stiffness(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda,
                                          Eigen::MatrixXd& k) const {
  k = Eigen::MatrixXd::Zero(local_size(p1_, p2_), local_size(p1_, p2_));
  p1_.add_hessian(q, lambda.head<2>(), 1.0, k);
  p2_.add_hessian(q, lambda.head<2>(), -1.0, k);
}

void RevoluteJoint2D::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double,
                                        Eigen::VectorXd& c) const {
  c = p1_.convective_acceleration(q, v) - p2_.convective_acceleration(q, v);
}

JointReaction RevoluteJoint2D::reaction(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda) const {
  JointReaction r;
  r.location = as3(p1_.position(q));
  r.force = as3(-lambda.head<2>());
  return r;
}

// ---------------------------------------------------------------- point on line
PointOnLineJoint2D::PointOnLineJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                                       const Eigen::Vector2d& axis)
    : PointOnLineJoint2D(std::move(name), std::move(nodes), p1, p2, axis, PlanarJointType::point_on_line) {}

PointOnLineJoint2D::PointOnLineJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                                       const Eigen::Vector2d& axis, PlanarJointType type)
    : PlanarJoint(std::move(name), std::move(nodes), type), p1_(p1), p2_(p2), axis_(axis.normalized()) {}

void PointOnLineJoint2D::frame(const Eigen::VectorXd& q, Eigen::Vector2d& n, Eigen::Vector2d& t) const {
  t = rotate(p2_.angle(q), axis_);
  n = perp(t);
}

// Φ = n(θ2)·D(q), D = r1 − r2, n' = −t, n'' = −n (derivatives w.r.t. θ2). Then
// Φ_q = nᵀB + e_θ (n'·D)  and  ∂²Φ/∂q² = H(n) + e_θ (n'ᵀB) + (Bᵀn') e_θᵀ + e_θ e_θᵀ (n''·D).
void PointOnLineJoint2D::evaluate(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  Eigen::Vector2d n, t;
  frame(q, n, t);
  const Eigen::Vector2d D = p1_.position(q) - p2_.position(q);
  phi.resize(1);
  phi[0] = n.dot(D);
  phi_q = n.transpose() * relative_jacobian(p1_, p2_, q);
  if (p2_.has_angle()) phi_q(0, p2_.angle_index()) -= t.dot(D);
}

void PointOnLineJoint2D::geometric_stiffness(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda,
                                             Eigen::MatrixXd& k) const {
  const int m = local_size(p1_, p2_);
  k = Eigen::MatrixXd::Zero(m, m);
  Eigen::Vector2d n, t;
  frame(q, n, t);
  const double l = lambda[0];
  p1_.add_hessian(q, l * n, 1.0, k);
  p2_.add_hessian(q, l * n, -1.0, k);
  if (p2_.has_angle()) {
    const int a = p2_.angle_index();
    const Eigen::RowVectorXd tB = -(t.transpose() * relative_jacobian(p1_, p2_, q));
    k.row(a) += l * tB;
    k.col(a) += l * tB.transpose();
    k(a, a) -= l * n.dot(p1_.position(q) - p2_.position(q));
  }
}

void PointOnLineJoint2D::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double,
                                           Eigen::VectorXd& c) const {
  Eigen::Vector2d n, t;
  frame(q, n, t);
  c.resize(1);
  c[0] = n.dot(p1_.convective_acceleration(q, v) - p2_.convective_acceleration(q, v));
  if (p2_.has_angle()) {
    const double w = v[p2_.angle_index()];
    const Eigen::Vector2d Ddot = p1_.velocity(q, v) - p2_.velocity(q, v);
    const Eigen::Vector2d D = p1_.position(q) - p2_.position(q);
    c[0] += -2.0 * w * t.dot(Ddot) - w * w * n.dot(D);
  }
}

JointReaction PointOnLineJoint2D::reaction(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda) const {
  Eigen::Vector2d n, t;
  frame(q, n, t);
  JointReaction r;
  r.location = as3(p1_.position(q));
  r.force = as3(-lambda[0] * n);
  return r;
}

// ---------------------------------------------------------------- prismatic
PrismaticJoint2D::PrismaticJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                                   const Eigen::Vector2d& axis, double relative_angle)
    : PointOnLineJoint2D(std::move(name), std::move(nodes), p1, p2, axis, PlanarJointType::prismatic), theta0_(relative_angle) {}

void PrismaticJoint2D::evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  Eigen::VectorXd phi1;
  Eigen::MatrixXd phi1_q;
  PointOnLineJoint2D::evaluate(q, t, phi1, phi1_q);
  phi.resize(2);
  phi[0] = phi1[0];
  phi[1] = p1_.angle(q) - p2_.angle(q) - theta0_;
  phi_q = Eigen::MatrixXd::Zero(2, q.size());
  phi_q.row(0) = phi1_q.row(0);
  phi_q(1, p1_.angle_index()) += 1.0;
  if (p2_.has_angle()) phi_q(1, p2_.angle_index()) -= 1.0;
}

void PrismaticJoint2D::geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                                           Eigen::MatrixXd& k) const {
  // The angle equation is linear in q: only the line equation has curvature.
  PointOnLineJoint2D::geometric_stiffness(q, t, lambda.head<1>(), k);
}

void PrismaticJoint2D::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                                         Eigen::VectorXd& c) const {
  Eigen::VectorXd c1;
  PointOnLineJoint2D::acceleration_term(q, v, t, c1);
  c.resize(2);
  c[0] = c1[0];
  c[1] = 0.0;
}

JointReaction PrismaticJoint2D::reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const {
  JointReaction r = PointOnLineJoint2D::reaction(q, t, lambda.head<1>());
  r.moment = Eigen::Vector3d(0.0, 0.0, -lambda[1]);
  return r;
}

// ---------------------------------------------------------------- fixed (clamp)
FixedJoint2D::FixedJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                           double relative_angle)
    : PlanarJoint(std::move(name), std::move(nodes), PlanarJointType::fixed), p1_(p1), p2_(p2), theta0_(relative_angle) {}

void FixedJoint2D::evaluate(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  phi.resize(3);
  phi.head<2>() = p1_.position(q) - p2_.position(q);
  phi[2] = p1_.angle(q) - p2_.angle(q) - theta0_;
  phi_q = Eigen::MatrixXd::Zero(3, q.size());
  phi_q.topRows<2>() = relative_jacobian(p1_, p2_, q);
  if (p1_.has_angle()) phi_q(2, p1_.offset() + 2) += 1.0;
  if (p2_.has_angle()) phi_q(2, p2_.offset() + 2) -= 1.0;
}

void FixedJoint2D::geometric_stiffness(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda,
                                       Eigen::MatrixXd& k) const {
  k = Eigen::MatrixXd::Zero(local_size(p1_, p2_), local_size(p1_, p2_));
  p1_.add_hessian(q, lambda.head<2>(), 1.0, k);  // the angle equation is linear in q
  p2_.add_hessian(q, lambda.head<2>(), -1.0, k);
}

void FixedJoint2D::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double,
                                     Eigen::VectorXd& c) const {
  c = Eigen::VectorXd::Zero(3);
  c.head<2>() = p1_.convective_acceleration(q, v) - p2_.convective_acceleration(q, v);
}

JointReaction FixedJoint2D::reaction(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda) const {
  JointReaction r;
  r.location = as3(p1_.position(q));
  r.force = as3(-lambda.head<2>());
  r.moment.z() = -lambda[2];  // the forces act at the joint point: only the angle row gives a moment
  return r;
}

}  // namespace alphaflex
