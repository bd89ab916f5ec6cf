#include "alphaflex/elements/spatial_elements.hpp"

#include "alphaflex/core/rotation.hpp"

namespace alphaflex {

RigidBody3D::RigidBody3D(std::string name, int node, double mass, const Eigen::Matrix3d& inertia,
                         const Eigen::Vector3d& gravity, const Eigen::Vector3d& offset)
    : Element(std::move(name), {node}), m_(mass), j_(inertia), g_(gravity), c_(offset) {}

bool RigidBody3D::internal_force(const Eigen::VectorXd&, Eigen::VectorXd& r) const {
  r = Eigen::VectorXd::Zero(6);
  return true;
}

void RigidBody3D::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  const Eigen::Vector3d W = s.v.segment<3>(3);
  if (c_.isZero(0.0)) {  // about the centre of mass: Brüls, Cardona & Arnold (2012), eq. 56
    const Eigen::Vector3d JW = j_ * W;
    out.r.segment<3>(0) += m_ * (s.qdd.segment<3>(0) - s.load_factor * g_);
    out.r.segment<3>(3) += j_ * s.qdd.segment<3>(3) + W.cross(JW);
    if (tangent) {
      out.M.block<3, 3>(0, 0) += m_ * Eigen::Matrix3d::Identity();
      out.M.block<3, 3>(3, 3) += j_;
      out.C.block<3, 3>(3, 3) += hat<double>(W) * j_ - hat<double>(JW);
    }
    return;
  }
  // About the node P, the centre at c in the node frame (the header's equations).
  const Pose<double> p = pose_of(s.q.data());
  const Eigen::Vector3d Wd = s.qdd.segment<3>(3);
  const Eigen::Matrix3d Jp = j_ + m_ * (c_.squaredNorm() * Eigen::Matrix3d::Identity() - c_ * c_.transpose());
  const Eigen::Vector3d JW = Jp * W, Wc = W.cross(c_);
  const Eigen::Vector3d a = Wd.cross(c_) + W.cross(Wc);
  const Eigen::Vector3d b = p.R.transpose() * (s.qdd.segment<3>(0) - s.load_factor * g_);  // ẍ − g, node axes
  out.r.segment<3>(0) += m_ * (s.qdd.segment<3>(0) - s.load_factor * g_ + p.R * a);
  out.r.segment<3>(3) += Jp * Wd + W.cross(JW) + m_ * c_.cross(b);
  if (tangent) {
    const Eigen::Matrix3d C = hat<double>(c_);
    out.M.block<3, 3>(0, 0) += m_ * Eigen::Matrix3d::Identity();
    out.M.block<3, 3>(0, 3) -= m_ * p.R * C;
    out.M.block<3, 3>(3, 0) += m_ * C * p.R.transpose();
    out.M.block<3, 3>(3, 3) += Jp;
    out.C.block<3, 3>(0, 3) -= m_ * p.R * (hat<double>(Wc) + hat<double>(W) * C);
    out.C.block<3, 3>(3, 3) += hat<double>(W) * Jp - hat<double>(JW);
    out.K.block<3, 3>(0, 3) -= m_ * p.R * hat<double>(a);
    out.K.block<3, 3>(3, 3) += m_ * C * hat<double>(b);
  }
}

bool RigidBody3D::mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const {
  // The M of evaluate(): [m I, −m R ĉ; m ĉ Rᵀ, J_P] about the node P (J_P = J about the centre, c = 0).
  Mw.resize(6);
  const Eigen::Vector3d wx = w.segment<3>(0), wt = w.segment<3>(3);
  if (c_.isZero(0.0)) {
    Mw << m_ * wx, j_ * wt;
    return true;
  }
  const Eigen::Matrix3d R = pose_of(s.q.data()).R;
  const Eigen::Matrix3d Jp = j_ + m_ * (c_.squaredNorm() * Eigen::Matrix3d::Identity() - c_ * c_.transpose());
  Mw << m_ * (wx - R * c_.cross(wt)), Jp * wt + m_ * c_.cross(R.transpose() * wx);
  return true;
}

SpatialLoad::SpatialLoad(std::string name, int node, const Eigen::Vector3d& point, std::array<TimeFunctionPtr, 3> force,
                         std::array<TimeFunctionPtr, 3> moment, bool follower)
    : Element(std::move(name), {node}), point_(point), force_(std::move(force)), moment_(std::move(moment)),
      follower_(follower) {}

template <class S>
void SpatialLoad::residual(const Pose<S>* frames, const S& t, double factor, KernelVector<S>& out) const {
  const Pose<S>& f = frames[0];
  const double tv = ad::value(t);
  Vec3<S> F, M;
  for (int i = 0; i < 3; ++i) {
    F[i] = S(factor * (force_[i] ? force_[i]->value(tv) : 0.0));
    M[i] = S(factor * (moment_[i] ? moment_[i]->value(tv) : 0.0));
  }
  // Generalized force: δW = F_w·(δx + R (δθ × s)) + M_w·(R δθ), F_w and M_w in the world frame.
  const Vec3<S> Fw = follower_ ? Vec3<S>(f.R * F) : F;
  const Vec3<S> Mb = follower_ ? M : Vec3<S>(f.R.transpose() * M);  // moment in body components
  const Vec3<S> Fb = f.R.transpose() * Fw;
  const Vec3<S> s = point_.cast<S>();
  out.resize(6);
  out.template segment<3>(0) = -Fw;
  out.template segment<3>(3) = -(s.cross(Fb) + Mb);
}

void SpatialLoad::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  // The kernel carries the load factor of this evaluation (no state in the element).
  const double factor = s.load_factor;
  const auto kernel = [this, factor](const auto* frames, const auto& t, auto& out) { residual(frames, t, factor, out); };
  KernelValue r;  // fixed capacity: no heap allocation per element
  KernelJacobian K;
  if (tangent) {
    kernel_jacobian(kernel, s.q, s.t, r, K);
    out.K += K;
  } else {
    kernel_value(kernel, s.q, s.t, r);
  }
  out.r += r;
}

}  // namespace alphaflex
