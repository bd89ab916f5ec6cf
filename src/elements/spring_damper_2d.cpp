#include "alphaflex/elements/spring_damper_2d.hpp"

#include "alphaflex/core/error.hpp"

namespace alphaflex {

SpringDamper2D::SpringDamper2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                               double stiffness, double damping, double rest_length,
                               std::optional<Eigen::Vector2d> axis)
    : Element(std::move(name), std::move(nodes)),
      p1_(p1), p2_(p2), k_(stiffness), c_(damping), l0_(rest_length), axis_(std::move(axis)) {}

double SpringDamper2D::length(const Eigen::VectorXd& q) const {
  const Eigen::Vector2d d = p1_.position(q) - p2_.position(q);
  return axis_ ? axis_->dot(d) : d.norm();
}

void SpringDamper2D::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  const int n = static_cast<int>(s.q.size());
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(2, n);
  p1_.add_jacobian(s.q, 1.0, B);
  p2_.add_jacobian(s.q, -1.0, B);
  const Eigen::Vector2d d = p1_.position(s.q) - p2_.position(s.q);
  const Eigen::Vector2d ddot = B * s.v;

  Eigen::Vector2d e;
  double len;
  if (axis_) {
    e = *axis_;
    len = e.dot(d);
  } else {
    len = d.norm();
    if (len < 1e-12 * std::max(1.0, l0_))
      throw ConfigurationError("spring_damper '" + name() +
                        "': its two points coincide, so the force has no direction; give the "
                        "spring a fixed `direction` if it acts along a rail");
    e = d / len;
  }
  const double len_rate = e.dot(ddot);
  const double tension = k_ * (len - l0_) + c_ * len_rate;
  const Eigen::VectorXd Bte = B.transpose() * e;
  out.r += tension * Bte;
  if (!tangent) return;

  // ∂(Jᵀ w)/∂q at fixed w, and ∂(B v)/∂q, both from the markers.
  Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n, n);
  p1_.add_hessian(s.q, e, 1.0, H);
  p2_.add_hessian(s.q, e, -1.0, H);
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(2, n);
  p1_.add_velocity_jacobian(s.q, s.v, 1.0, D);
  p2_.add_velocity_jacobian(s.q, s.v, -1.0, D);

  Eigen::RowVectorXd dlen_dq = e.transpose() * B;
  Eigen::RowVectorXd drate_dq = e.transpose() * D;
  Eigen::MatrixXd K = tension * H;
  if (!axis_) {
    // ∂e/∂q = (I − e eᵀ) B / L enters through e in Bᵀe and in L̇ = e·ḋ.
    const Eigen::Matrix2d P = (Eigen::Matrix2d::Identity() - e * e.transpose()) / len;
    K += tension * B.transpose() * P * B;
    drate_dq += ddot.transpose() * P * B;
  }
  out.K += Bte * (k_ * dlen_dq + c_ * drate_dq) + K;
  out.C += c_ * Bte * Bte.transpose();
}

}  // namespace alphaflex
