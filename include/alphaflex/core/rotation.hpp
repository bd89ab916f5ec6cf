#pragma once
// Rotations on SO(3): the exponential and logarithm maps, the tangent operator of the exponential
// and its inverse, and unit quaternions as the stored state. Everything is templated on the scalar
// so that elements and joints can differentiate through it exactly (core/autodiff.hpp).
//
// Conventions (Brüls, Cardona & Arnold, Mech. Mach. Theory 48, 2012, Sec. 2 and App. A):
//   exp(w) = I + sinθ/θ ŵ + (1 − cosθ)/θ² ŵ²,        θ = |w|            (Rodrigues)
//   T(w)   = I − (1 − cosθ)/θ² ŵ + (θ − sinθ)/θ³ ŵ²                      (eq. A.9)
//   so that  d/dε exp(w + ε δ)|₀ = exp(w) · (T(w) δ)^   (right-trivialized tangent of exp),
//   T⁻¹(w) = I + ½ ŵ + (1 − (θ/2) cot(θ/2))/θ² ŵ².
// The coefficients of exp, T and T⁻¹ are evaluated from θ² by their Taylor series when
// θ² < 0.25 (eight terms; the first omitted term is below 1e-17 there), so that values and first
// and second derivatives (AD) stay exact at and near θ = 0, where the closed forms are 0/0: the
// closed forms lose ~ε/θ² in first and ~ε/θ⁴ in second derivatives to cancellation, which is
// round-off only from θ ≈ 0.5 on. The logarithm is exact up to θ = π, where the axis is taken from
// the symmetric part of R.
#include <Eigen/Dense>
#include <cmath>

namespace alphaflex {

template <class S> using Vec3 = Eigen::Matrix<S, 3, 1>;
template <class S> using Mat3 = Eigen::Matrix<S, 3, 3>;

/// ŵ: the skew matrix with ŵ v = w × v.
template <class S>
Mat3<S> hat(const Vec3<S>& w) {
  Mat3<S> m;
  m << S(0), -w(2), w(1), w(2), S(0), -w(0), -w(1), w(0), S(0);
  return m;
}

/// The axial vector of the skew part of m: vee(ŵ) = w.
template <class S>
Vec3<S> vee(const Mat3<S>& m) {
  return Vec3<S>((m(2, 1) - m(1, 2)) / S(2), (m(0, 2) - m(2, 0)) / S(2), (m(1, 0) - m(0, 1)) / S(2));
}

namespace rotation_detail {
/// log_so3 (in sin²θ) and quaternion_exp (in θ²) switch to their series below this value
/// (|next term| < 1e-16 · leading term).
constexpr double series_below = 1e-4;
/// Below this θ² the coefficients of exp, T and T⁻¹ use their series (8 terms, |next term| < 1e-17
/// · leading term). Above it the closed forms' cancellation (~ε/θ² in first derivatives, ~ε/θ⁴ in
/// second) is at round-off; at θ² = 1e-4 it reached 1e-13 in ∂T/∂w and 3e-11 in ∂²T/∂w².
constexpr double coefficient_series_below = 0.25;

/// Σ_{k=0..7} lead · Π_{i<k} (−x / divisor_i), evaluated by Horner's rule.
template <class S>
S alternating_series(const S& x, double lead, const double (&divisor)[7]) {
  S r = S(1);
  for (int k = 6; k >= 0; --k) r = S(1) - x / S(divisor[k]) * r;
  return S(lead) * r;
}

/// sinθ/θ, (1 − cosθ)/θ², (θ − sinθ)/θ³ as functions of θ².
template <class S>
void coefficients(const S& th2, S& a, S& b, S& c) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (th2 < S(coefficient_series_below)) {
    // Σ (−θ²)^k / (2k + p)!, p = 1, 2, 3: term ratios −θ² / ((2k + p + 1)(2k + p + 2)).
    static constexpr double da[7] = {6, 20, 42, 72, 110, 156, 210};
    static constexpr double db[7] = {12, 30, 56, 90, 132, 182, 240};
    static constexpr double dc[7] = {20, 42, 72, 110, 156, 210, 272};
    a = alternating_series<S>(th2, 1.0, da);
    b = alternating_series<S>(th2, 0.5, db);
    c = alternating_series<S>(th2, 1.0 / 6.0, dc);
  } else {
    const S th = sqrt(th2);
    a = sin(th) / th;
    b = (S(1) - cos(th)) / th2;
    c = (th - sin(th)) / (th2 * th);
  }
}
}  // namespace rotation_detail

/// exp(w) ∈ SO(3) (Rodrigues).
template <class S>
Mat3<S> exp_so3(const Vec3<S>& w) {
  S a, b, c;
  rotation_detail::coefficients<S>(w.squaredNorm(), a, b, c);
  const Mat3<S> W = hat<S>(w);
  return Mat3<S>::Identity() + a * W + b * W * W;
}

/// T(w), the tangent operator of exp (right trivialization).
template <class S>
Mat3<S> tangent_so3(const Vec3<S>& w) {
  S a, b, c;
  rotation_detail::coefficients<S>(w.squaredNorm(), a, b, c);
  const Mat3<S> W = hat<S>(w);
  return Mat3<S>::Identity() - b * W + c * W * W;
}

/// T⁻¹(w); defined for θ < 2π.
template <class S>
Mat3<S> tangent_so3_inverse(const Vec3<S>& w) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  const S th2 = w.squaredNorm();
  S d;  // (1 − (θ/2) cot(θ/2))/θ²
  if (th2 < S(rotation_detail::coefficient_series_below)) {
    // Σ_{n≥1} |B_2n| / (2n)! θ^(2n−2) (Bernoulli numbers), n = 1..8, by Horner's rule.
    static constexpr double coef[8] = {1.0 / 12.0,          1.0 / 720.0,         1.0 / 30240.0,
                                       1.0 / 1209600.0,     1.0 / 47900160.0,    691.0 / 1307674368000.0,
                                       1.0 / 74724249600.0, 3617.0 / 10670622842880000.0};
    d = S(coef[7]);
    for (int k = 6; k >= 0; --k) d = S(coef[k]) + th2 * d;
  } else {
    const S th = sqrt(th2);
    d = (S(1) - th / S(2) * cos(th / S(2)) / sin(th / S(2))) / th2;
  }
  const Mat3<S> W = hat<S>(w);
  return Mat3<S>::Identity() + W / S(2) + d * W * W;
}

/// log(R): the rotation vector w with |w| ≤ π and exp(w) = R.
template <class S>
Vec3<S> log_so3(const Mat3<S>& R) {
  using std::atan2;
  using std::sqrt;
  const Vec3<S> s = vee<S>(R);                    // sinθ · n
  const S c = (R.trace() - S(1)) / S(2);          // cosθ
  const S s2 = s.squaredNorm();
  if (c > S(0)) {
    // θ < π/2: w = θ/sinθ · s, with θ/sinθ = asin(σ)/σ as a series in σ² = sin²θ near 0.
    S f;
    if (s2 < S(rotation_detail::series_below)) {
      f = S(1) + s2 / S(6) + S(3.0 / 40.0) * s2 * s2 + S(5.0 / 112.0) * s2 * s2 * s2;
    } else {
      const S sn = sqrt(s2);
      f = atan2(sn, c) / sn;
    }
    return f * s;
  }
  // θ ≥ π/2: the axis from the symmetric part, R + Rᵀ − 2c I = 2(1 − c) n nᵀ, which stays well
  // conditioned up to θ = π; its sign from s (arbitrary at θ = π exactly, where both signs agree).
  const Mat3<S> B = (R + R.transpose() - S(2) * c * Mat3<S>::Identity()) / (S(2) * (S(1) - c));
  int k = 0;
  if (B(1, 1) > B(k, k)) k = 1;
  if (B(2, 2) > B(k, k)) k = 2;
  Vec3<S> n = B.col(k) / sqrt(B(k, k));
  if (n.dot(s) < S(0)) n = -n;
  const S th = atan2(sqrt(s2), c);
  return th * n;
}

/// Unit quaternion exp(w/2) as (w, x, y, z) coefficients: the rotation exp(w).
inline Eigen::Quaterniond quaternion_exp(const Eigen::Vector3d& w) {
  const double th2 = w.squaredNorm();
  double c, s;  // cos(θ/2), sin(θ/2)/θ
  if (th2 < rotation_detail::series_below) {
    c = 1.0 - th2 / 8.0 + th2 * th2 / 384.0;
    s = 0.5 - th2 / 48.0 + th2 * th2 / 3840.0;
  } else {
    const double th = std::sqrt(th2);
    c = std::cos(th / 2.0);
    s = std::sin(th / 2.0) / th;
  }
  return Eigen::Quaterniond(c, s * w.x(), s * w.y(), s * w.z());
}

/// Rotation vector of a unit quaternion (|w| ≤ π; q and −q give the same rotation).
inline Eigen::Vector3d quaternion_log(Eigen::Quaterniond q) {
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d v = q.vec();
  const double sn = v.norm();
  if (sn < 1e-8) return (2.0 / q.w()) * (1.0 - sn * sn / (3.0 * q.w() * q.w())) * v;  // 2 atan(σ/w)/σ ≈ 2/w (1 − σ²/(3w²))
  return (2.0 * std::atan2(sn, q.w()) / sn) * v;
}

/// Rotation matrix whose columns are the unit vectors e1, e2 = (e2' ⊥ e1), e3 = e1 × e2: the
/// frame of a beam section (e1 along the axis) or a joint (e3 along its axis), from a direction
/// and a reference vector not parallel to it. Returns false if they are parallel.
bool frame_from(const Eigen::Vector3d& e1, const Eigen::Vector3d& ref2, Eigen::Matrix3d& R);

}  // namespace alphaflex
