// SE(3) (core/se3.hpp): the closed-form tangent operator T_SE(3) and its inverse against the
// series Σ (−ad ξ)^k/(k + 1)!, against exact (AD) derivatives of exp, and the vector form of
// T_SE(3)⁻ᵀ f against the matrices; exp and log against the 4×4 matrix exponential; the series
// branches of the coefficients at θ = 0 and across their switches (θ² = 0.25, θ² = 1).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/core/se3.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {
namespace {

using Eigen::Matrix3d;
using Eigen::Matrix4d;
using Eigen::Vector3d;
using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// ad(ξ) = [[φ̂, û], [0, φ̂]].
Matrix6d ad_of(const Vector6d& xi) {
  Matrix6d m = Matrix6d::Zero();
  m.topLeftCorner<3, 3>() = m.bottomRightCorner<3, 3>() = hat<double>(Vector3d(xi.tail<3>()));
  m.topRightCorner<3, 3>() = hat<double>(Vector3d(xi.head<3>()));
  return m;
}

/// Σ_{k<60} (−ad ξ)^k/(k + 1)! (converges fast for |φ| ≤ 3 and |u| ≤ 1).
Matrix6d tangent_series(const Vector6d& xi) {
  const Matrix6d A = -ad_of(xi);
  Matrix6d term = Matrix6d::Identity(), sum = Matrix6d::Identity();
  for (int k = 1; k < 60; ++k) {
    term = term * A / static_cast<double>(k + 1);
    sum += term;
  }
  return sum;
}

/// ξ^ as a 4×4 matrix.
Matrix4d wedge(const Vector6d& xi) {
  Matrix4d m = Matrix4d::Zero();
  m.topLeftCorner<3, 3>() = hat<double>(Vector3d(xi.tail<3>()));
  m.topRightCorner<3, 1>() = xi.head<3>();
  return m;
}

/// Twists with rotation angles at θ = 0, near 0, around the series switches and up to 3 rad.
std::vector<Vector6d> twists(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vector6d> out;
  for (double th : {0.0, 1e-8, 1e-4, 0.1, 0.4999, 0.5001, 0.9999, 1.0001, 1.5707, 2.0, 3.0}) {
    for (int k = 0; k < 3; ++k) {
      const Vector3d axis = Vector3d(u(rng), u(rng), u(rng)).normalized();
      Vector6d xi;
      xi << u(rng), u(rng), u(rng), th * axis;
      out.push_back(xi);
    }
  }
  return out;
}

double rel(const Eigen::MatrixXd& a, const Eigen::MatrixXd& ref) { return (a - ref).norm() / ref.norm(); }

// T_SE(3) in closed form equals the series of ad, its inverse is the inverse, and the vector forms
// T_SE(3)⁻ᵀ f and T_SE(3)⁻¹ f equal the matrix products.
TEST(SE3, TangentAndItsInverseEqualTheSeriesOfAd) {
  std::mt19937 rng(3);
  double worst_t = 0.0, worst_inv = 0.0, worst_vec = 0.0;
  for (const Vector6d& xi : twists(rng)) {
    const Matrix6d T = tangent_se3<double>(xi), Ti = tangent_se3_inverse<double>(xi);
    const double et = rel(T, tangent_series(xi));
    const double ei = (Ti * T - Matrix6d::Identity()).norm();
    const Vector6d f = Vector6d::Random();
    const double ev = std::max((tangent_se3_inverse_transpose_times<double>(xi, f) - Ti.transpose() * f).norm(),
                               (tangent_se3_inverse_times<double>(xi, f) - Ti * f).norm()) /
                      f.norm();
    EXPECT_LT(et, 1e-14) << xi.transpose();
    EXPECT_LT(ei, 1e-13) << xi.transpose();
    EXPECT_LT(ev, 1e-13) << xi.transpose();
    worst_t = std::max(worst_t, et);
    worst_inv = std::max(worst_inv, ei);
    worst_vec = std::max(worst_vec, ev);
    // The SO(3) blocks are those of core/rotation.hpp.
    EXPECT_LT((Ti.topLeftCorner<3, 3>() - tangent_so3_inverse<double>(Vector3d(xi.tail<3>()))).norm(), 1e-15);
  }
  std::printf("SE(3) tangent vs series of ad: %.1e; T^-1 T - I: %.1e; T^-T f, T^-1 f vector forms vs matrix: %.1e\n", worst_t,
              worst_inv, worst_vec);
}

// exp(ξ) (se3_exp) is the 4×4 matrix exponential of ξ^, log inverts it (|φ| < π), and
// d/dε exp(ξ + εη)|₀ = exp(ξ) (T_SE(3)(ξ) η)^ exactly: the columns of T are the twists
// exp(ξ)⁻¹ ∂exp(ξ)/∂ξ_j, here by forward AD of se3_exp.
TEST(SE3, TangentIsTheRightTrivializedDerivativeOfExp) {
  using A = ad::FixedAD1<6>;
  std::mt19937 rng(5);
  double worst_exp = 0.0, worst_log = 0.0, worst_d = 0.0;
  for (const Vector6d& xi : twists(rng)) {
    Matrix3d R;
    Vector3d p;
    se3_exp<double>(xi, R, p);
    const Matrix4d E = wedge(xi).exp();
    worst_exp = std::max(worst_exp, (E.topLeftCorner<3, 3>() - R).norm() + (E.topRightCorner<3, 1>() - p).norm());
    worst_log = std::max(worst_log, (se3_log<double>(R, p) - xi).norm() / std::max(1.0, xi.norm()));

    Vec6<A> xa;
    for (int i = 0; i < 6; ++i) xa[i] = A(xi[i], Eigen::Matrix<double, 6, 1>::Unit(i));
    Mat3<A> Ra;
    Vec3<A> pa;
    se3_exp<A>(xa, Ra, pa);
    Matrix6d D;
    for (int j = 0; j < 6; ++j) {
      Matrix3d dR;
      Vector3d dp;
      for (int r = 0; r < 3; ++r) {
        dp[r] = pa[r].derivatives()[j];
        for (int c = 0; c < 3; ++c) dR(r, c) = Ra(r, c).derivatives()[j];
      }
      D.col(j) << R.transpose() * dp, vee<double>(Matrix3d(R.transpose() * dR));
    }
    const double e = rel(D, tangent_se3<double>(xi));
    EXPECT_LT(e, 1e-13) << xi.transpose();
    worst_d = std::max(worst_d, e);
  }
  EXPECT_LT(worst_exp, 1e-13);
  EXPECT_LT(worst_log, 1e-12);
  std::printf("SE(3) exp vs 4x4 matrix exponential %.1e, log(exp) %.1e, T vs AD derivative of exp %.1e\n", worst_exp,
              worst_log, worst_d);
}

// log(exp(ξ) exp(εη)) = ξ + ε T⁻¹(ξ) η + O(ε²) and Ad: H exp(η) H⁻¹ = exp(Ad(H) η).
TEST(SE3, LogOfAPerturbedExpAndTheAdjoint) {
  std::mt19937 rng(9);
  for (const Vector6d& xi : twists(rng)) {
    if (xi.tail<3>().norm() > 2.5) continue;  // log needs |φ| < π after the perturbation
    const Vector6d eta = Vector6d::Random();
    const double h = 1e-5;
    Vector6d dlog;
    Matrix4d Hp, Hm;
    Hp = wedge(xi).exp() * wedge(Vector6d(h * eta)).exp();
    Hm = wedge(xi).exp() * wedge(Vector6d(-h * eta)).exp();
    dlog = (se3_log<double>(Hp.topLeftCorner<3, 3>(), Hp.topRightCorner<3, 1>()) -
            se3_log<double>(Hm.topLeftCorner<3, 3>(), Hm.topRightCorner<3, 1>())) /
           (2.0 * h);
    const Vector6d expected = tangent_se3_inverse<double>(xi) * eta;
    EXPECT_LT((dlog - expected).norm(), 1e-8 * expected.norm()) << xi.transpose();
    const Matrix4d H = wedge(xi).exp();
    const Matrix4d lhs = H * wedge(eta).exp() * H.inverse();
    const Matrix4d rhs =
        wedge(Vector6d(se3_adjoint<double>(H.topLeftCorner<3, 3>(), H.topRightCorner<3, 1>()) * eta)).exp();
    EXPECT_LT((lhs - rhs).norm(), 1e-12);
  }
}

// The coefficients c1, c2, c3 switch from their series to the closed forms at θ² = 1 and the
// coefficient of T⁻¹ at θ² = 0.25: values and first AD derivatives agree on both sides (to the
// closed forms' cancellation), and at θ = 0 exactly the derivatives are those of the series.
TEST(SE3, CoefficientsAreSmoothAcrossTheirSeriesSwitches) {
  using A = ad::FixedAD1<1>;
  auto eval = [](double x) {
    A c1, c2, c3;
    const A th2(x, Eigen::Matrix<double, 1, 1>(1.0));
    se3_detail::q_coefficients<A>(th2, c1, c2, c3);
    const A d = se3_detail::inverse_coefficient<A>(th2);
    return std::array<A, 4>{c1, c2, c3, d};
  };
  for (double sw : {1.0, 0.25}) {
    const auto lo = eval(std::nextafter(sw, 0.0)), hi = eval(sw);  // series below, closed form at sw
    for (int k = 0; k < 4; ++k) {
      EXPECT_NEAR(lo[k].value(), hi[k].value(), 1e-13 * std::fabs(lo[k].value())) << "coefficient " << k;
      EXPECT_NEAR(lo[k].derivatives()[0], hi[k].derivatives()[0], 1e-9 * std::fabs(lo[k].derivatives()[0]))
          << "coefficient " << k << " at the switch " << sw;
    }
  }
  const auto z = eval(0.0);
  EXPECT_DOUBLE_EQ(z[0].value(), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(z[1].value(), 1.0 / 24.0);
  EXPECT_DOUBLE_EQ(z[2].value(), 1.0 / 120.0);
  EXPECT_DOUBLE_EQ(z[3].value(), 1.0 / 12.0);
  EXPECT_DOUBLE_EQ(z[0].derivatives()[0], -1.0 / 120.0);
  EXPECT_DOUBLE_EQ(z[1].derivatives()[0], -1.0 / 720.0);
  EXPECT_DOUBLE_EQ(z[2].derivatives()[0], -1.0 / 2520.0);
  EXPECT_DOUBLE_EQ(z[3].derivatives()[0], 1.0 / 720.0);
}

}  // namespace
}  // namespace alphaflex
