#include "alphaflex/joints/joint_coordinate.hpp"

#include <cmath>

namespace alphaflex {
namespace {

/// The configuration numbers of the link's spatial frames and of ψ (the last one).
kernel_detail::Poses frames_of(const Eigen::VectorXd& q, int nf) { return kernel_detail::poses(q, nf); }

/// Φ and its gradient (AD1 over the frames' increments and ψ: N = 6 nf + 1 variables).
template <int N, class Link>
void first(const Link& link, const Eigen::VectorXd& q, double& phi, Eigen::RowVectorXd& grad) {
  using A = ad::FixedAD1<N>;
  constexpr int nf = N / 6;
  const auto p = frames_of(q, nf);
  std::array<Pose<A>, nf> ps;
  for (int k = 0; k < nf; ++k) ps[static_cast<size_t>(k)] = kernel_detail::seeded_pose1<N>(p[static_cast<size_t>(k)], 6 * k);
  const A psi(q[7 * nf], A::DerType::Unit(N - 1));
  const A f = link.equation(ps.data(), psi);
  phi = f.value();
  grad = f.derivatives().transpose();
}

/// H(i, j) = ∂/∂δ'_j ∂Φ/∂δ_i (outer perturbation first, as model/spatial_kernel.hpp's `second`).
template <int N, class Link>
void second(const Link& link, const Eigen::VectorXd& q, Eigen::MatrixXd& H) {
  using A1 = ad::FixedAD1<N>;
  using A2 = ad::FixedAD2<N>;
  constexpr int nf = N / 6;
  const auto p = frames_of(q, nf);
  std::array<Pose<A2>, nf> ps;
  for (int k = 0; k < nf; ++k) ps[static_cast<size_t>(k)] = kernel_detail::seeded_pose2<N>(p[static_cast<size_t>(k)], 6 * k);
  typename A2::DerType outer;
  for (int o = 0; o < N; ++o) outer[o] = A1(o == N - 1 ? 1.0 : 0.0, A1::DerType::Zero());
  const A2 psi(A1(q[7 * nf], A1::DerType::Unit(N - 1)), outer);
  const A2 f = link.equation(ps.data(), psi);
  H.resize(N, N);
  for (int j = 0; j < N; ++j) H.col(j) = f.derivatives()[j].derivatives();
}

/// d²/dτ² Φ(q ∘ exp(τ v)) at τ = 0 (frames R(I + τv̂ + τ²v̂²/2), ψ + τ ψ̇).
template <class Link>
double along_motion(const Link& link, const Eigen::VectorXd& q, const Eigen::VectorXd& v, int nf) {
  using A1 = ad::FixedAD1<1>;
  using A2 = ad::FixedAD2<1>;
  auto number = [](double a, double b, double c) {
    return A2(A1(a, A1::DerType(b)), A2::DerType(A1(b, A1::DerType(c))));
  };
  const auto p = frames_of(q, nf);
  std::array<Pose<A2>, kernel_detail::kMaxFrames> ps;
  for (int k = 0; k < nf; ++k) {
    const Pose<double>& pk = p[static_cast<size_t>(k)];
    const Eigen::Vector3d vx = v.segment<3>(6 * k), vth = v.segment<3>(6 * k + 3);
    const Eigen::Matrix3d Rv = pk.R * hat<double>(vth), Rvv = Rv * hat<double>(vth);
    for (int i = 0; i < 3; ++i) ps[static_cast<size_t>(k)].x[i] = number(pk.x[i], vx[i], 0.0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) ps[static_cast<size_t>(k)].R(i, j) = number(pk.R(i, j), Rv(i, j), Rvv(i, j));
  }
  const A2 f = link.equation(ps.data(), number(q[7 * nf], v[6 * nf], 0.0));
  return f.derivatives()[0].derivatives()[0];
}

}  // namespace

JointCoordinateLink::JointCoordinateLink(std::string name, std::vector<int> nodes, SpatialMarker a, SpatialMarker b,
                                         Coordinate c)
    : Constraint(std::move(name), std::move(nodes)), a_(std::move(a)), b_(std::move(b)), coordinate_(c) {
  if (frames() < 1 || frames() > 2) throw std::invalid_argument("a joint coordinate links one or two frames and its scalar node");
}

void JointCoordinateLink::evaluate(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  double f;
  Eigen::RowVectorXd g;
  if (frames() == 1) first<7>(*this, q, f, g);
  else first<13>(*this, q, f, g);
  phi = Eigen::VectorXd::Constant(1, f);
  phi_q = g;
}

void JointCoordinateLink::geometric_stiffness(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda,
                                              Eigen::MatrixXd& k) const {
  if (frames() == 1) second<7>(*this, q, k);
  else second<13>(*this, q, k);
  k *= lambda[0];
}

void JointCoordinateLink::acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double,
                                            Eigen::VectorXd& c) const {
  c = Eigen::VectorXd::Constant(1, along_motion(*this, q, v, frames()));
}

JointReaction JointCoordinateLink::reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const {
  Eigen::VectorXd phi;
  Eigen::MatrixXd J;
  evaluate(q, t, phi, J);
  const Eigen::VectorXd g = -J.transpose() * lambda;  // generalized force of the link on its nodes
  const auto p = frames_of(q, frames());
  const Pose<double> A = a_.pose<double>(p.data());
  JointReaction r;
  r.location = A.x;
  r.force = g.segment<3>(0);
  r.moment = p[0].R * g.segment<3>(3) - (A.x - p[0].x).cross(r.force);
  r.frame = A.R;
  return r;
}

double JointCoordinateLink::frame_value(const Eigen::VectorXd& q_frames) const {
  const auto p = frames_of(q_frames, frames());
  const Pose<double> A = a_.pose<double>(p.data()), B = b_.pose<double>(p.data());
  switch (coordinate_) {
    case Coordinate::rotation: return std::atan2(A.R.col(0).dot(B.R.col(1)), A.R.col(0).dot(B.R.col(0)));
    case Coordinate::universal_axis: return -std::atan2(A.R.col(2).dot(B.R.col(1)), A.R.col(1).dot(B.R.col(1)));
    case Coordinate::universal_axis2: return -std::atan2(A.R.col(0).dot(B.R.col(2)), A.R.col(0).dot(B.R.col(0)));
    case Coordinate::translation: break;
  }
  return (A.x - B.x).dot(B.R.col(2));
}

std::string JointCoordinateLink::equation_name(int) const {
  switch (coordinate_) {
    case Coordinate::rotation: return "sin(angle − ψ)";
    case Coordinate::universal_axis: return "sin(angle1 − ψ)";
    case Coordinate::universal_axis2: return "sin(angle2 − ψ)";
    case Coordinate::translation: break;
  }
  return "displacement − ψ";
}

}  // namespace alphaflex
