#include "alphaflex/joints/joint_coordinate.hpp"

#include <cmath>

namespace alphaflex {
namespace {

/// The configuration numbers of the link's spatial frames and of ψ (the last one).
kernel_detail::Poses frames_of(const Eigen::VectorXd& q, int nf) { return kernel_detail::poses(q, nf); }

/// A marker's axis or point as a function of the frames, with its derivative along the increments
/// (x + δx, R(I + δθ^)) of N variables (6 per frame, ψ last): ∂(R w)/∂δθ = −R ŵ, ∂(x + R s)/∂δx = I,
/// ∂/∂δθ = −R ŝ. These hold at any frame matrix R (no RᵀR = I is used), so `second` can
/// differentiate them once more at R(I + δθ'^) by forward AD.
template <class S, int N>
struct MarkerVectorAt {
  Vec3<S> value;
  Eigen::Matrix<S, 3, N> d;
};

template <class S, int N>
MarkerVectorAt<S, N> axis_at(const SpatialMarker& m, int k, const Pose<S>* frames) {
  MarkerVectorAt<S, N> u;
  u.d.setZero();
  const Vec3<S> w = m.rotation.col(k).template cast<S>();
  if (m.slot < 0) {
    u.value = w;
    return u;
  }
  const Mat3<S>& R = frames[m.slot].R;
  u.value = R * w;
  u.d.template block<3, 3>(0, 6 * m.slot + 3) = -R * hat<S>(w);
  return u;
}

template <class S, int N>
MarkerVectorAt<S, N> point_at(const SpatialMarker& m, const Pose<S>* frames) {
  MarkerVectorAt<S, N> p;
  p.d.setZero();
  const Vec3<S> s = m.position.template cast<S>();
  if (m.slot < 0) {
    p.value = s;
    return p;
  }
  const Pose<S>& f = frames[m.slot];
  p.value = f.x + f.R * s;
  p.d.template block<3, 3>(0, 6 * m.slot).setIdentity();
  p.d.template block<3, 3>(0, 6 * m.slot + 3) = -f.R * hat<S>(s);
  return p;
}

}  // namespace

/// ∂Φ/∂(δ, ψ) in closed form. Every rotation equation is σ u·(cos ψ v + ν sin ψ w) with marker axes
/// u, v, w and signs σ, ν = ±1 (header): its gradient is σ [(cos ψ v + ν sin ψ w)ᵀ u_δ +
/// uᵀ(cos ψ v_δ + ν sin ψ w_δ)] and ∂/∂ψ = σ u·(−sin ψ v + ν cos ψ w); the translation (p_A − p_B)·b3 − ψ has
/// b3ᵀ(p_A,δ − p_B,δ) + (p_A − p_B)ᵀ b3,δ and −1.
template <int N, class S>
Eigen::Matrix<S, 1, N> JointCoordinateLink::gradient(const Pose<S>* frames, const S& psi) const {
  using std::cos;
  using std::sin;
  using V = MarkerVectorAt<S, N>;
  Eigen::Matrix<S, 1, N> g;
  if (coordinate_ == Coordinate::translation) {
    const V pa = point_at<S, N>(a_, frames), pb = point_at<S, N>(b_, frames), b3 = axis_at<S, N>(b_, 2, frames);
    const Vec3<S> r = pa.value - pb.value;
    g.template head<N - 1>() = (b3.value.transpose() * (pa.d - pb.d) + r.transpose() * b3.d).template head<N - 1>();
    g[N - 1] = S(-1);
    return g;
  }
  // σ u·(cos ψ v + ν sin ψ w): rotation a1·(cos ψ b2 − sin ψ b1); universal_axis −b2·(cos ψ a3 + sin ψ a2);
  // universal_axis2 −a1·(cos ψ b3 + sin ψ b1).
  const SpatialMarker *mu = &a_, *mv = &b_;
  int ku = 0, kv = 1, kw = 0;
  double sigma = 1.0, nu = -1.0;
  if (coordinate_ == Coordinate::universal_axis) {
    mu = &b_, mv = &a_, ku = 1, kv = 2, kw = 1, sigma = -1.0, nu = 1.0;
  } else if (coordinate_ == Coordinate::universal_axis2) {
    kv = 2, kw = 0, sigma = -1.0, nu = 1.0;
  }
  const V u = axis_at<S, N>(*mu, ku, frames), v = axis_at<S, N>(*mv, kv, frames), w = axis_at<S, N>(*mv, kw, frames);
  const S c = cos(psi), s = S(nu) * sin(psi);
  const Vec3<S> cv = c * v.value + s * w.value;
  const Eigen::Matrix<S, 1, N> frames_part = cv.transpose() * u.d + u.value.transpose() * (c * v.d + s * w.d);
  g = S(sigma) * frames_part;
  g[N - 1] = S(sigma) * u.value.dot(Vec3<S>(-sin(psi) * v.value + S(nu) * cos(psi) * w.value));
  return g;
}

namespace {

/// The link's frames and ψ seeded for forward AD1 over its N = 6 nf + 1 variables (ψ last).
template <int N>
struct Seeded1 {
  using A = ad::FixedAD1<N>;
  std::array<Pose<A>, N / 6> frames;
  A psi;
  explicit Seeded1(const Eigen::VectorXd& q) {
    constexpr int nf = N / 6;
    const auto p = frames_of(q, nf);
    for (int k = 0; k < nf; ++k) frames[static_cast<size_t>(k)] = kernel_detail::seeded_pose1<N>(p[static_cast<size_t>(k)], 6 * k);
    psi = A(q[7 * nf], A::DerType::Unit(N - 1));
  }
};

/// Φ and its gradient in closed form (N = 6 nf + 1 variables, ψ last).
template <int N, class Link>
void first(const Link& link, const Eigen::VectorXd& q, double& phi, Eigen::RowVectorXd& grad) {
  constexpr int nf = N / 6;
  const auto p = frames_of(q, nf);
  phi = link.equation(p.data(), q[7 * nf]);
  grad = link.template gradient<N, double>(p.data(), q[7 * nf]);
}

/// Φ and its gradient by forward AD of the equation (the check of the closed form in the tests).
template <int N, class Link>
void first_by_ad(const Link& link, const Eigen::VectorXd& q, double& phi, Eigen::RowVectorXd& grad) {
  const Seeded1<N> x(q);
  const ad::FixedAD1<N> f = link.equation(x.frames.data(), x.psi);
  phi = f.value();
  grad = f.derivatives().transpose();
}

/// H(i, j) = ∂/∂δ'_j ∂Φ/∂δ_i (outer perturbation first, as model/spatial_kernel.hpp's `second`):
/// forward AD1 of the closed-form gradient at the frames (x + δx', R(I + δθ'^)) and ψ + δψ'.
template <int N, class Link>
void second(const Link& link, const Eigen::VectorXd& q, Eigen::MatrixXd& H) {
  using A = ad::FixedAD1<N>;
  const Seeded1<N> x(q);
  const Eigen::Matrix<A, 1, N> g = link.template gradient<N, A>(x.frames.data(), x.psi);
  H.resize(N, N);
  for (int i = 0; i < N; ++i) H.row(i) = g[i].derivatives().transpose();
}

/// The same by nested forward AD of the equation (the check in the tests).
template <int N, class Link>
void second_by_ad(const Link& link, const Eigen::VectorXd& q, Eigen::MatrixXd& H) {
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

namespace {
/// Φ and Φ_q of a link of one or two frames, in closed form or by AD (the tests' check).
void link_first(const JointCoordinateLink& link, int frames, bool by_ad, const Eigen::VectorXd& q, Eigen::VectorXd& phi,
                Eigen::MatrixXd& phi_q) {
  double f;
  Eigen::RowVectorXd g;
  if (frames == 1) by_ad ? first_by_ad<7>(link, q, f, g) : first<7>(link, q, f, g);
  else by_ad ? first_by_ad<13>(link, q, f, g) : first<13>(link, q, f, g);
  phi = Eigen::VectorXd::Constant(1, f);
  phi_q = g;
}

/// λ ∂Φ_q/∂δ' of a link of one or two frames, by AD1 of the closed form or by nested AD.
void link_second(const JointCoordinateLink& link, int frames, bool by_ad, const Eigen::VectorXd& q, double lambda,
                 Eigen::MatrixXd& k) {
  if (frames == 1) by_ad ? second_by_ad<7>(link, q, k) : second<7>(link, q, k);
  else by_ad ? second_by_ad<13>(link, q, k) : second<13>(link, q, k);
  k *= lambda;
}
}  // namespace

void JointCoordinateLink::evaluate(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  link_first(*this, frames(), false, q, phi, phi_q);
}

void JointCoordinateLink::geometric_stiffness(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda,
                                              Eigen::MatrixXd& k) const {
  link_second(*this, frames(), false, q, lambda[0], k);
}

void JointCoordinateLink::evaluate_by_ad(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const {
  link_first(*this, frames(), true, q, phi, phi_q);
}

void JointCoordinateLink::geometric_stiffness_by_ad(const Eigen::VectorXd& q, double, const Eigen::VectorXd& lambda,
                                                    Eigen::MatrixXd& k) const {
  link_second(*this, frames(), true, q, lambda[0], k);
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
