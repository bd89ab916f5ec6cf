#pragma once
// The special Euclidean group SE(3): exponential and logarithm, and the tangent operator of the
// exponential and its inverse in closed form. Templated on the scalar like core/rotation.hpp, so
// that elements can differentiate through it (core/autodiff.hpp).
//
// Conventions: H = (R, p) acts as x ↦ R x + p; a twist ξ = (u, φ) ∈ R⁶ has the translation first,
// ξ^ = [[φ̂, u], [0, 0]], and ad(ξ) = [[φ̂, û], [0, φ̂]] (so that ad(ξ)η = [ξ, η]);
// Ad(H) = [[R, p̂ R], [0, R]] (H ξ^ H⁻¹ = (Ad(H) ξ)^). The tangent operator is right-trivialized,
// as T of SO(3) in core/rotation.hpp:
//   d/dε exp(ξ + ε η)|₀ = exp(ξ) (T_SE(3)(ξ) η)^,   T_SE(3)(ξ) = Σ_k (−ad ξ)^k / (k + 1)!,
// so that log(exp(ξ) exp(η)) = ξ + T_SE(3)(ξ)⁻¹ η + O(|η|²). In closed form (Barfoot, State
// Estimation for Robotics, 2017, eqs. 7.86 and 7.95, there for the left Jacobian J_l(ξ); the
// right one is J_l(−ξ); also Sonneville, Cardona & Brüls 2014, App. A):
//   T_SE(3)(ξ)  = [[T(φ), Q_r(u, φ)], [0, T(φ)]],
//   T_SE(3)⁻¹(ξ) = [[T⁻¹(φ), −T⁻¹(φ) Q_r(u, φ) T⁻¹(φ)], [0, T⁻¹(φ)]],
//   Q_r(u, φ)ᵀ = Q_l(u, φ) = ½ û + c1 (ûφ̂ + φ̂û + φ̂ûφ̂) + c2 (ûφ̂² + φ̂²û − 3 φ̂ûφ̂)
//                           + c3 (φ̂²ûφ̂ + φ̂ûφ̂²),      Q_r(u, φ) = Q_l(−u, −φ),
//   c1 = (θ − sin θ)/θ³,  c2 = (θ² + 2 cos θ − 2)/(2θ⁴),  c3 = (2θ − 3 sin θ + θ cos θ)/(2θ⁵),  θ = |φ|,
// with T(φ) and T⁻¹(φ) those of core/rotation.hpp. c1, c2, c3 are evaluated from θ² by their
// Taylor series for θ² < 1 (eight terms, the first omitted term is below 1e-16 of the leading one
// there) and the coefficient of T⁻¹ for θ² < 0.25 (as core/rotation.hpp), so that values and AD
// derivatives stay exact at and near θ = 0, where the closed forms are 0/0.
// tests/unit/test_se3.cpp checks T_SE(3) against the series of ad and against differences of exp,
// and the inverse and the vector forms against the matrices.
#include <Eigen/Dense>
#include <cmath>

#include "alphaflex/core/rotation.hpp"

namespace alphaflex {

template <class S> using Vec6 = Eigen::Matrix<S, 6, 1>;
template <class S> using Mat6 = Eigen::Matrix<S, 6, 6>;

namespace se3_detail {

/// Σ_k coef[k] x^k by Horner's rule.
template <class S, int N>
S polynomial(const S& x, const double (&coef)[N]) {
  S r = S(coef[N - 1]);
  for (int k = N - 2; k >= 0; --k) r = S(coef[k]) + x * r;
  return r;
}

/// c1, c2, c3 of Q (header comment) as functions of θ².
template <class S>
void q_coefficients(const S& th2, S& c1, S& c2, S& c3) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (th2 < S(1.0)) {
    // c1 = Σ (−θ²)^m/(2m + 3)!, c2 = Σ (−θ²)^m/(2m + 4)!, c3 = Σ (−θ²)^m (m + 1)/(2m + 5)!.
    static constexpr double k1[8] = {1.0 / 6.0,        -1.0 / 120.0,          1.0 / 5040.0,
                                     -1.0 / 362880.0,  1.0 / 39916800.0,      -1.0 / 6227020800.0,
                                     1.0 / 1307674368000.0, -1.0 / 355687428096000.0};
    static constexpr double k2[8] = {1.0 / 24.0,          -1.0 / 720.0,           1.0 / 40320.0,
                                     -1.0 / 3628800.0,    1.0 / 479001600.0,      -1.0 / 87178291200.0,
                                     1.0 / 20922789888000.0, -1.0 / 6402373705728000.0};
    static constexpr double k3[8] = {1.0 / 120.0,           -2.0 / 5040.0,          3.0 / 362880.0,
                                     -4.0 / 39916800.0,     5.0 / 6227020800.0,     -6.0 / 1307674368000.0,
                                     7.0 / 355687428096000.0, -8.0 / 121645100408832000.0};
    c1 = polynomial<S>(th2, k1);
    c2 = polynomial<S>(th2, k2);
    c3 = polynomial<S>(th2, k3);
  } else {
    const S th = sqrt(th2), s = sin(th), c = cos(th);
    c1 = (th - s) / (th2 * th);
    c2 = (th2 + S(2) * c - S(2)) / (S(2) * th2 * th2);
    c3 = (S(2) * th - S(3) * s + th * c) / (S(2) * th2 * th2 * th);
  }
}

/// (1 − (θ/2) cot(θ/2))/θ², the coefficient of φ̂² in T⁻¹(φ) (core/rotation.hpp, same series).
template <class S>
S inverse_coefficient(const S& th2) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  if (th2 < S(rotation_detail::coefficient_series_below)) {
    static constexpr double coef[8] = {1.0 / 12.0,          1.0 / 720.0,         1.0 / 30240.0,
                                       1.0 / 1209600.0,     1.0 / 47900160.0,    691.0 / 1307674368000.0,
                                       1.0 / 74724249600.0, 3617.0 / 10670622842880000.0};
    return polynomial<S>(th2, coef);
  }
  const S th = sqrt(th2);
  return (S(1) - th / S(2) * cos(th / S(2)) / sin(th / S(2))) / th2;
}

/// T⁻ᵀ(φ) v = v − ½ φ × v + d φ × (φ × v), d = inverse_coefficient(|φ|²).
template <class S>
Vec3<S> tangent_inverse_transpose_times(const Vec3<S>& phi, const S& d, const Vec3<S>& v) {
  const Vec3<S> a = phi.cross(v);
  return v - a / S(2) + d * phi.cross(a);
}

/// Q_l(u, φ) v = Q_r(u, φ)ᵀ v with c1, c2, c3 given (header comment), by cross products.
template <class S>
Vec3<S> q_left_times(const Vec3<S>& u, const Vec3<S>& phi, const S& c1, const S& c2, const S& c3,
                     const Vec3<S>& v) {
  const Vec3<S> pv = phi.cross(v), ppv = phi.cross(pv);  // φ̂v, φ̂²v
  const Vec3<S> uv = u.cross(v), upv = u.cross(pv), uppv = u.cross(ppv);
  const Vec3<S> puv = phi.cross(uv), pupv = phi.cross(upv);  // φ̂ûv, φ̂ûφ̂v
  const Vec3<S> ppuv = phi.cross(puv), ppupv = phi.cross(pupv), puppv = phi.cross(uppv);
  return uv / S(2) + c1 * (upv + puv + pupv) + c2 * (uppv + ppuv - S(3) * pupv) + c3 * (ppupv + puppv);
}

/// T⁻¹(φ) v = v + ½ φ × v + d φ × (φ × v) (the transpose of tangent_inverse_transpose_times).
template <class S>
Vec3<S> tangent_inverse_times(const Vec3<S>& phi, const S& d, const Vec3<S>& v) {
  const Vec3<S> a = phi.cross(v);
  return v + a / S(2) + d * phi.cross(a);
}

/// Q_r(u, φ) v with c1, c2, c3 given (se3_tangent_coupling's matrix), by cross products: with
/// Û = (−u)^ and P̂ = (−φ)^, Q_r = Û/2 + c1 (ÛP̂ + P̂Û + P̂ÛP̂) + c2 (ÛP̂² + P̂²Û − 3 P̂ÛP̂) + c3 (P̂²ÛP̂ + P̂ÛP̂²).
template <class S>
Vec3<S> q_right_times(const Vec3<S>& u, const Vec3<S>& phi, const S& c1, const S& c2, const S& c3, const Vec3<S>& v) {
  // (−a)^ x = x × a.
  const Vec3<S> Pv = v.cross(phi), Uv = v.cross(u);
  const Vec3<S> UPv = Pv.cross(u), PUv = Uv.cross(phi), PPv = Pv.cross(phi);
  const Vec3<S> PUPv = UPv.cross(phi), UPPv = PPv.cross(u), PPUv = PUv.cross(phi);
  const Vec3<S> PPUPv = PUPv.cross(phi), PUPPv = UPPv.cross(phi);
  return Uv / S(2) + c1 * (UPv + PUv + PUPv) + c2 * (UPPv + PPUv - S(3) * PUPv) + c3 * (PPUPv + PUPPv);
}

}  // namespace se3_detail

/// Q_r(u, φ), the upper right block of T_SE(3)(u, φ).
template <class S>
Mat3<S> se3_tangent_coupling(const Vec3<S>& u, const Vec3<S>& phi) {
  S c1, c2, c3;
  se3_detail::q_coefficients<S>(phi.squaredNorm(), c1, c2, c3);
  const Mat3<S> U = hat<S>(Vec3<S>(-u)), P = hat<S>(Vec3<S>(-phi)), PU = P * U, UP = U * P, PUP = PU * P;
  return U / S(2) + c1 * (UP + PU + PUP) + c2 * (UP * P + P * PU - S(3) * PUP) + c3 * (P * PUP + PUP * P);
}

/// T_SE(3)(ξ), ξ = (u, φ).
template <class S>
Mat6<S> tangent_se3(const Vec6<S>& xi) {
  const Vec3<S> u = xi.template head<3>(), phi = xi.template tail<3>();
  const Mat3<S> T = tangent_so3<S>(phi);
  Mat6<S> m;
  m << T, se3_tangent_coupling<S>(u, phi), Mat3<S>::Zero(), T;
  return m;
}

/// T_SE(3)(ξ)⁻¹ (defined for |φ| < 2π).
template <class S>
Mat6<S> tangent_se3_inverse(const Vec6<S>& xi) {
  const Vec3<S> u = xi.template head<3>(), phi = xi.template tail<3>();
  const Mat3<S> Ti = tangent_so3_inverse<S>(phi);
  Mat6<S> m;
  m << Ti, -Ti * se3_tangent_coupling<S>(u, phi) * Ti, Mat3<S>::Zero(), Ti;
  return m;
}

/// T_SE(3)(ξ)⁻ᵀ f, by cross products (no 3×3 products): with v = T⁻ᵀ(φ) f_u,
/// (T_SE(3)⁻ᵀ f)_u = v and (T_SE(3)⁻ᵀ f)_φ = T⁻ᵀ(φ) (f_φ − Q_l(u, φ) v).
template <class S>
Vec6<S> tangent_se3_inverse_transpose_times(const Vec6<S>& xi, const Vec6<S>& f) {
  const Vec3<S> u = xi.template head<3>(), phi = xi.template tail<3>();
  const S th2 = phi.squaredNorm();
  S c1, c2, c3;
  se3_detail::q_coefficients<S>(th2, c1, c2, c3);
  const S d = se3_detail::inverse_coefficient<S>(th2);
  const Vec3<S> v = se3_detail::tangent_inverse_transpose_times<S>(phi, d, Vec3<S>(f.template head<3>()));
  const Vec3<S> w = f.template tail<3>() - se3_detail::q_left_times<S>(u, phi, c1, c2, c3, v);
  Vec6<S> g;
  g << v, se3_detail::tangent_inverse_transpose_times<S>(phi, d, w);
  return g;
}

/// T_SE(3)(ξ)⁻¹ w, by cross products (no 3×3 products): with z = T⁻¹(φ) w_φ,
/// (T_SE(3)⁻¹ w)_u = T⁻¹(φ) (w_u − Q_r(u, φ) z) and (T_SE(3)⁻¹ w)_φ = z.
template <class S>
Vec6<S> tangent_se3_inverse_times(const Vec6<S>& xi, const Vec6<S>& w) {
  const Vec3<S> u = xi.template head<3>(), phi = xi.template tail<3>();
  const S th2 = phi.squaredNorm();
  S c1, c2, c3;
  se3_detail::q_coefficients<S>(th2, c1, c2, c3);
  const S d = se3_detail::inverse_coefficient<S>(th2);
  const Vec3<S> z = se3_detail::tangent_inverse_times<S>(phi, d, Vec3<S>(w.template tail<3>()));
  const Vec3<S> y = w.template head<3>() - se3_detail::q_right_times<S>(u, phi, c1, c2, c3, z);
  Vec6<S> g;
  g << se3_detail::tangent_inverse_times<S>(phi, d, y), z;
  return g;
}

/// exp(ξ) = (exp(φ), T(φ)ᵀ u) = (R, p): the translation is J_l(φ) u, J_l(φ) = T(φ)ᵀ.
template <class S>
void se3_exp(const Vec6<S>& xi, Mat3<S>& R, Vec3<S>& p) {
  const Vec3<S> u = xi.template head<3>(), phi = xi.template tail<3>();
  R = exp_so3<S>(phi);
  p = tangent_so3<S>(phi).transpose() * u;
}

/// log_SE(3) of (R, p) in the (translation, rotation) order: θ = log(R), U = J_l(θ)⁻¹ p with
/// J_l(θ)⁻¹ = T⁻¹(θ)ᵀ = I − ½θ̂ + (1 − (θ/2)cot(θ/2))/θ² θ̂² (series near θ = 0, so values and first
/// and second AD derivatives are exact at θ = 0). Defined for |θ| < π.
template <class S>
Vec6<S> se3_log(const Mat3<S>& R, const Vec3<S>& p) {
  const Vec3<S> th = log_so3<S>(R);
  const S d = se3_detail::inverse_coefficient<S>(th.squaredNorm());
  Vec6<S> out;
  out << se3_detail::tangent_inverse_transpose_times<S>(th, d, p), th;
  return out;
}

/// Ad(H) = [[R, p̂ R], [0, R]].
template <class S>
Mat6<S> se3_adjoint(const Mat3<S>& R, const Vec3<S>& p) {
  Mat6<S> m;
  m << R, hat<S>(p) * R, Mat3<S>::Zero(), R;
  return m;
}

}  // namespace alphaflex
