// Rotations on SO(3) (core/rotation.hpp): exp/log, the tangent operator T of exp and its inverse,
// unit quaternions and frame_from, against independent references — Eigen's AngleAxis, Rodrigues
// with coefficients summed as long-double Taylor series, central differences of exp, and exact AD
// derivatives — in both branches of the series threshold (θ² = 1e-4, i.e. θ = 1e-2), at θ → 0,
// near π, and for T⁻¹ near 2π.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "alphaflex/core/autodiff.hpp"
#include "alphaflex/core/rotation.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::kPi;
constexpr double kEps = 2.220446049250313e-16;  // DBL_EPSILON

/// Angles that exercise both branches of every coefficient: 0, far below / just below / just above
/// θ = 1e-2 (the series switch of log and quaternion_exp, and formerly of the coefficients of exp,
/// T and T⁻¹) and θ = 0.5 (their series switch now), general, and near π.
const std::vector<double> kAngles = {0.0, 1e-12,     1e-9, 1e-7,   1e-3, 9.999e-3, 1e-2, 1.001e-2,   0.3,
                                     1.0, kPi / 2.0, 2.0,  0.4999, 0.5,  0.5001,   3.0,  kPi - 1e-5, kPi - 1e-9};

Eigen::Vector3d random_axis(std::mt19937& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Eigen::Vector3d n;
  do n = Eigen::Vector3d(g(rng), g(rng), g(rng));
  while (n.norm() < 1e-3);
  return n.normalized();
}

// ------------------------------------------------------------------ long-double references
using LMat3 = Eigen::Matrix<long double, 3, 3>;
using LVec3 = Eigen::Matrix<long double, 3, 1>;

/// Σ_k (−θ²)^k / (2k + p)!: p = 1 gives sinθ/θ, p = 2 (1 − cosθ)/θ², p = 3 (θ − sinθ)/θ³.
/// Summed to convergence in long double; independent of the code's truncated series and closed forms.
long double series(long double th2, int p) {
  long double term = 1.0L;
  for (int i = 2; i <= p; ++i) term /= i;  // 1/p!
  long double sum = 0.0L;
  for (int k = 0; k < 60; ++k) {
    sum += term;
    term *= -th2 / ((2.0L * k + p + 1) * (2.0L * k + p + 2));
  }
  return sum;
}

LMat3 lhat(const LVec3& w) {
  LMat3 m;
  m << 0, -w(2), w(1), w(2), 0, -w(0), -w(1), w(0), 0;
  return m;
}

/// Rodrigues exp(w) = I + a ŵ + b ŵ² in long double.
LMat3 reference_exp(const Eigen::Vector3d& w) {
  const LVec3 l = w.cast<long double>();
  const long double th2 = l.squaredNorm();
  const LMat3 W = lhat(l);
  return LMat3::Identity() + series(th2, 1) * W + series(th2, 2) * W * W;
}

/// T(w) = I − b ŵ + c ŵ² in long double.
LMat3 reference_tangent(const Eigen::Vector3d& w) {
  const LVec3 l = w.cast<long double>();
  const long double th2 = l.squaredNorm();
  const LMat3 W = lhat(l);
  return LMat3::Identity() - series(th2, 2) * W + series(th2, 3) * W * W;
}

template <class D>
double max_abs(const Eigen::MatrixBase<D>& m) {
  return static_cast<double>(m.cwiseAbs().maxCoeff());
}

// ------------------------------------------------------------------ AD helpers
using ad::AD1;
using ad::AD2;

Vec3<AD1> ad_point(const Eigen::Vector3d& w) {
  Vec3<AD1> x;
  for (int i = 0; i < 3; ++i) x[i] = ad::variable1(w[i], 3, i);
  return x;
}

double d_of(const AD1& x, int i) { return x.derivatives().size() ? x.derivatives()[i] : 0.0; }

/// ∂M/∂w_i of a matrix of AD1 entries.
Eigen::Matrix3d partial(const Mat3<AD1>& m, int i) {
  Eigen::Matrix3d d;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) d(r, c) = d_of(m(r, c), i);
  return d;
}

Eigen::Matrix3d values(const Mat3<AD1>& m) {
  Eigen::Matrix3d v;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) v(r, c) = m(r, c).value();
  return v;
}

void rotation_report(const char* what, double worst) { std::printf("[ worst    ] %.2e  %s\n", worst, what); }

}  // namespace

// =================================================================== hat / vee

TEST(RotationHatVee, HatIsTheCrossProductAndVeeInvertsIt) {
  std::mt19937 rng(1);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Vector3d w = 3.0 * random_axis(rng), v = random_axis(rng);
    EXPECT_LE((hat<double>(w) * v - w.cross(v)).norm(), 4 * kEps * w.norm());  // ŵ v = w × v
    EXPECT_EQ(hat<double>(w).transpose(), -hat<double>(w));                    // ŵᵀ = −ŵ
    EXPECT_EQ(vee<double>(hat<double>(w)), w);                                 // vee(ŵ) = w
  }
}

// =================================================================== exp

TEST(RotationExp, ExpEqualsRodriguesReferenceAndAngleAxisInBothBranches) {
  // exp(θ n) = I + sinθ n̂ + (1 − cosθ) n̂² (long-double series reference) = AngleAxis(θ, n).
  std::mt19937 rng(2);
  double worst_ref = 0.0, worst_aa = 0.0;
  for (double th : kAngles) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d n = random_axis(rng), w = th * n;
      const Eigen::Matrix3d R = exp_so3<double>(w);
      const double e_ref = max_abs(R.cast<long double>() - reference_exp(w));
      const double e_aa = max_abs(R - Eigen::AngleAxisd(th, n).toRotationMatrix());
      worst_ref = std::max(worst_ref, e_ref);
      worst_aa = std::max(worst_aa, e_aa);
      // Entries are O(1): a few units of round-off.
      EXPECT_LE(e_ref, 4 * kEps) << "θ = " << th;
      EXPECT_LE(e_aa, 8 * kEps) << "θ = " << th;
    }
  }
  rotation_report("exp(w) vs long-double Rodrigues", worst_ref);
  rotation_report("exp(w) vs Eigen::AngleAxis", worst_aa);
}

TEST(RotationExp, ExpIsOrthogonalWithUnitDeterminant) {
  // exp(w)ᵀ exp(w) = I, det exp(w) = 1, for every angle including beyond π and 2π.
  std::mt19937 rng(3);
  std::vector<double> angles = kAngles;
  for (double th : {4.0, 2 * kPi - 1e-3, 2 * kPi, 10.0, 100.0}) angles.push_back(th);
  double worst = 0.0;
  for (double th : angles) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Matrix3d R = exp_so3<double>(th * random_axis(rng));
      const double e_orth = max_abs(R.transpose() * R - Eigen::Matrix3d::Identity());
      const double e_det = std::abs(R.determinant() - 1.0);
      worst = std::max({worst, e_orth, e_det});
      EXPECT_LE(e_orth, 8 * kEps) << "θ = " << th;
      EXPECT_LE(e_det, 8 * kEps) << "θ = " << th;
    }
  }
  rotation_report("|RᵀR − I|, |det R − 1|", worst);
}

// =================================================================== log ∘ exp, exp ∘ log

TEST(RotationExpLog, LogOfExpIsIdentityForAnglesUpToPi) {
  // log(exp(w)) = w for |w| < π, relative to |w| (down to θ = 1e-12 and up to π − 1e-9).
  std::mt19937 rng(4);
  double worst = 0.0;
  for (double th : kAngles) {
    for (int k = 0; k < 6; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng);
      const Eigen::Vector3d l = log_so3<double>(exp_so3<double>(w));
      if (th == 0.0) {
        EXPECT_EQ(l, Eigen::Vector3d::Zero());
        continue;
      }
      const double e = (l - w).norm() / th;
      worst = std::max(worst, e);
      EXPECT_LE(e, 16 * kEps) << "θ = " << th << ": log(exp(w)) = " << l.transpose() << ", w = " << w.transpose();
    }
  }
  rotation_report("|log(exp(w)) − w| / |w|", worst);
}

TEST(RotationExpLog, LogAtExactlyPiGivesAnAxisOfLengthPiEitherSign) {
  // At θ = π, w and −w give the same rotation: log(exp(π n)) = ±π n, and exp(log R) = R.
  std::mt19937 rng(5);
  std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  for (int k = 0; k < 10; ++k) axes.push_back(random_axis(rng));
  for (const Eigen::Vector3d& n : axes) {
    const Eigen::Matrix3d R = exp_so3<double>(kPi * n);
    const Eigen::Vector3d l = log_so3<double>(R);
    EXPECT_LE(std::abs(l.norm() - kPi), 8 * kEps) << "n = " << n.transpose();
    EXPECT_LE(std::min((l - kPi * n).norm(), (l + kPi * n).norm()), 16 * kEps) << "n = " << n.transpose();
    EXPECT_LE(max_abs(exp_so3<double>(l) - R), 8 * kEps);
  }
  // The exact half-turns about the coordinate axes (R symmetric, sinθ n = 0 exactly).
  for (int i = 0; i < 3; ++i) {
    Eigen::Matrix3d R = -Eigen::Matrix3d::Identity();
    R(i, i) = 1.0;
    const Eigen::Vector3d l = log_so3<double>(R);
    EXPECT_LE(std::abs(std::abs(l[i]) - kPi), 2 * kEps) << "axis " << i;
    EXPECT_EQ(l.norm(), std::abs(l[i])) << "axis " << i;
    EXPECT_LE(max_abs(exp_so3<double>(l) - R), 4 * kEps);
  }
}

TEST(RotationExpLog, ExpOfLogIsIdentityForRandomRotations) {
  // exp(log(R)) = R for R from random unit quaternions, near the identity and near half-turns.
  std::mt19937 rng(6);
  std::normal_distribution<double> g(0.0, 1.0);
  double worst = 0.0;
  std::vector<Eigen::Matrix3d> Rs;
  for (int k = 0; k < 50; ++k)
    Rs.push_back(Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix());
  for (double th : kAngles)
    for (int k = 0; k < 3; ++k) Rs.push_back(Eigen::AngleAxisd(th, random_axis(rng)).toRotationMatrix());
  for (const Eigen::Matrix3d& R : Rs) {
    const Eigen::Vector3d l = log_so3<double>(R);
    EXPECT_LE(l.norm(), kPi * (1 + kEps));
    const double e = max_abs(exp_so3<double>(l) - R);
    worst = std::max(worst, e);
    EXPECT_LE(e, 8 * kEps) << "R =\n" << R << "\nlog R = " << l.transpose();
  }
  rotation_report("|exp(log R) − R|", worst);
}

TEST(RotationExpLog, JacobianOfLogOfExpIsTheIdentityViaAD) {
  // d/dw log(exp(w)) = I exactly (AD), in the small-angle series, the asin branch and the
  // symmetric-part branch (θ ≥ π/2) of log, including at w = 0.
  std::mt19937 rng(7);
  double worst = 0.0;
  for (double th : {0.0, 1e-9, 1e-3, 1e-2, 1.001e-2, 0.5, 1.5, 2.0, 3.0, kPi - 1e-5}) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng);
      const Vec3<AD1> l = log_so3<AD1>(exp_so3<AD1>(ad_point(w)));
      Eigen::Matrix3d J;
      for (int r = 0; r < 3; ++r)
        for (int i = 0; i < 3; ++i) J(r, i) = d_of(l[r], i);
      // Conditioning near π: the axis is read from R + Rᵀ, whose derivative ∝ sinθ degrades like 1/(π − θ).
      const double tol = 64 * kEps * std::max(1.0, 1.0 / (kPi - th));
      const double e = max_abs(J - Eigen::Matrix3d::Identity());
      worst = std::max(worst, e * std::min(1.0, kPi - th));
      EXPECT_LE(e, tol) << "θ = " << th << "\n" << J;
    }
  }
  rotation_report("|∂log(exp(w))/∂w − I| (× min(1, π − θ))", worst);
}

// =================================================================== T and T⁻¹

TEST(RotationTangent, TangentEqualsLongDoubleReferenceInBothBranches) {
  // T(w) = I − (1 − cosθ)/θ² ŵ + (θ − sinθ)/θ³ ŵ²  (reference: long-double series).
  std::mt19937 rng(8);
  double worst = 0.0;
  std::vector<double> angles = kAngles;
  for (double th : {4.0, 2 * kPi - 1e-3}) angles.push_back(th);
  for (double th : angles) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng);
      // The closed form (θ − sinθ)/θ³ cancels to relative error ~ε/θ² just above θ = 1e-2; times
      // θ² in ŵ², that is a few ε in T.
      const double e = max_abs(tangent_so3<double>(w).cast<long double>() - reference_tangent(w));
      worst = std::max(worst, e);
      EXPECT_LE(e, 8 * kEps) << "θ = " << th;
    }
  }
  rotation_report("T(w) vs long-double reference", worst);
}

TEST(RotationTangent, TangentMatchesCentralDifferencesOfExpInBothBranches) {
  // d/dε exp(w + εδ)|₀ = exp(w) (T(w) δ)^, by central differences of exp (ε = 1e-6).
  std::mt19937 rng(9);
  double worst = 0.0;
  const double h = 1e-6;
  for (double th : {0.0, 1e-4, 1e-3, 5e-3, 2e-2, 0.3, 1.0, 2.5, kPi - 1e-3, 4.0}) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng), delta = random_axis(rng);
      const Eigen::Matrix3d fd = (exp_so3<double>(w + h * delta) - exp_so3<double>(w - h * delta)) / (2 * h);
      const Eigen::Matrix3d an = exp_so3<double>(w) * hat<double>(tangent_so3<double>(w) * delta);
      const double e = (fd - an).norm() / an.norm();
      worst = std::max(worst, e);
      EXPECT_LE(e, 1e-6) << "θ = " << th << "\nFD:\n" << fd << "\nexp(w)(Tδ)^:\n" << an;
    }
  }
  rotation_report("exp(w)(T(w)δ)^ vs central differences", worst);
}

TEST(RotationTangent, TangentIsTheExactADDerivativeOfExp) {
  // The same identity with AD in place of differences: ∂exp/∂w_i = exp(w) (T(w) e_i)^ to round-off.
  std::mt19937 rng(10);
  double worst = 0.0;
  for (double th : kAngles) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng);
      const Mat3<AD1> R = exp_so3<AD1>(ad_point(w));
      const Eigen::Matrix3d R0 = exp_so3<double>(w), T = tangent_so3<double>(w);
      for (int i = 0; i < 3; ++i) {
        const Eigen::Matrix3d expected = R0 * hat<double>(T.col(i));
        const double e = max_abs(partial(R, i) - expected);
        worst = std::max(worst, e);
        EXPECT_LE(e, 16 * kEps) << "θ = " << th << ", i = " << i << "\nAD:\n"
                                << partial(R, i) << "\nexpected:\n"
                                << expected;
      }
    }
  }
  rotation_report("∂exp/∂w_i (AD) vs exp(w)(T e_i)^", worst);
}

TEST(RotationTangentInverse, InverseTimesTangentIsIdentityInBothBranchesAndNearTwoPi) {
  // T⁻¹(w) T(w) = T(w) T⁻¹(w) = I; near 2π, T is nearly singular and the round-off grows like ‖T⁻¹‖.
  std::mt19937 rng(11);
  std::vector<double> angles = kAngles;
  for (double th : {kPi, 4.0, 5.5, 6.0, 2 * kPi - 1e-3, 2 * kPi - 1e-6}) angles.push_back(th);
  double worst = 0.0;
  for (double th : angles) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng);
      const Eigen::Matrix3d T = tangent_so3<double>(w), Ti = tangent_so3_inverse<double>(w);
      const double scale = Ti.norm() * T.norm();
      const double e =
          std::max(max_abs(Ti * T - Eigen::Matrix3d::Identity()), max_abs(T * Ti - Eigen::Matrix3d::Identity())) /
          scale;
      worst = std::max(worst, e);
      EXPECT_LE(e, 8 * kEps) << "θ = " << th << ", ‖T⁻¹‖ = " << Ti.norm();
    }
  }
  rotation_report("|T⁻¹T − I| / (‖T‖‖T⁻¹‖)", worst);
}

TEST(RotationTangentInverse, InverseAgreesWithLongDoubleInverseOfReferenceTangent) {
  // A sharper check of the coefficient (1 − (θ/2)cot(θ/2))/θ² in its series branch: the series
  // error would show as |T⁻¹ − (T_ref)⁻¹| ≈ θ² |Δd|.
  std::mt19937 rng(12);
  double worst = 0.0;
  for (double th : kAngles) {
    if (th > 3.0) continue;  // T⁻¹ is well conditioned here
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng);
      const LMat3 Tinv_ref = reference_tangent(w).inverse();
      const double e = max_abs(tangent_so3_inverse<double>(w).cast<long double>() - Tinv_ref);
      worst = std::max(worst, e);
      EXPECT_LE(e, 8 * kEps) << "θ = " << th;
    }
  }
  rotation_report("T⁻¹(w) vs long-double inverse of T_ref", worst);
}

// =================================================================== series threshold

namespace {

/// Value, first and second derivatives of a matrix function of w (nested AD), flattened.
struct Derivs {
  Eigen::Matrix<double, 9, 1> v;
  Eigen::Matrix<double, 9, 3> d1;
  Eigen::Matrix<double, 9, 9> d2;  // column 3 i + j: ∂²/∂w_i∂w_j
};

template <class F>
Derivs derivatives_of(F f, const Eigen::Vector3d& w) {
  Vec3<AD2> x;
  for (int i = 0; i < 3; ++i) {
    ad::Derivatives2 d(3);
    for (int k = 0; k < 3; ++k) d[k] = ad::constant1(k == i ? 1.0 : 0.0, 3);
    x[i] = AD2(ad::variable1(w[i], 3, i), d);
  }
  const Mat3<AD2> m = f(x);
  Derivs out;
  out.d1.setZero();
  out.d2.setZero();
  for (int e = 0; e < 9; ++e) {
    const AD2& y = m(e % 3, e / 3);
    out.v[e] = y.value().value();
    for (int j = 0; j < 3; ++j) {
      if (y.value().derivatives().size()) out.d1(e, j) = y.value().derivatives()[j];
      for (int i = 0; i < 3; ++i)
        if (y.derivatives().size() && y.derivatives()[i].derivatives().size())
          out.d2(e, 3 * i + j) = y.derivatives()[i].derivatives()[j];
    }
  }
  return out;
}

/// Points on either side of |w|² = bound along n, a few ulps apart (the true change of any
/// function between them is ~1e-16 of its derivative, far below round-off).
void straddle(const Eigen::Vector3d& n, double theta, double bound, Eigen::Vector3d& below, Eigen::Vector3d& above) {
  below = theta * n;
  above = theta * n;
  while (below.squaredNorm() >= bound) below *= 1.0 - kEps;
  while (above.squaredNorm() < bound) above *= 1.0 + kEps;
}

}  // namespace

TEST(RotationSeriesThreshold, ValuesAndFirstAndSecondDerivativesAreContinuousAcrossTheThresholds) {
  // On either side of the coefficients' switch θ² = 0.25 from series to closed forms (and of the
  // former switch θ² = 1e-4), exp, T and T⁻¹ and their AD first and second derivatives agree to
  // round-off: entries and derivatives are O(1) sums of a few products, so a few ε.
  std::mt19937 rng(13);
  double worst[3] = {0.0, 0.0, 0.0};
  for (double th2 : {rotation_detail::coefficient_series_below, 1e-4}) {
    for (int k = 0; k < 10; ++k) {
      const Eigen::Vector3d n = random_axis(rng);
      Eigen::Vector3d below, above;
      straddle(n, std::sqrt(th2), th2, below, above);
      auto check = [&](const char* name, auto f) {
        const Derivs b = derivatives_of(f, below), a = derivatives_of(f, above);
        const double e[3] = {max_abs(b.v - a.v), max_abs(b.d1 - a.d1), max_abs(b.d2 - a.d2)};
        for (int o = 0; o < 3; ++o) worst[o] = std::max(worst[o], e[o]);
        EXPECT_LE(e[0], 4 * kEps) << name << " at θ² = " << th2 << ": values jump by " << e[0];
        EXPECT_LE(e[1], 8 * kEps) << name << " at θ² = " << th2 << ": first derivatives jump by " << e[1]
                                  << "\nbelow:\n"
                                  << b.d1 << "\nabove:\n"
                                  << a.d1;
        EXPECT_LE(e[2], 16 * kEps) << name << " at θ² = " << th2 << ": second derivatives jump by " << e[2];
      };
      check("exp", [](const Vec3<AD2>& w) { return exp_so3<AD2>(w); });
      check("T", [](const Vec3<AD2>& w) { return tangent_so3<AD2>(w); });
      check("T⁻¹", [](const Vec3<AD2>& w) { return tangent_so3_inverse<AD2>(w); });
    }
  }
  rotation_report("jump of exp, T, T⁻¹ at the series thresholds", worst[0]);
  rotation_report("jump of their AD first derivatives", worst[1]);
  rotation_report("jump of their AD second derivatives", worst[2]);
  // log's series is in σ² = sin²θ with its own switch at σ² = 1e-4: values and first derivatives
  // of log(exp(w)) are continuous there.
  double worst_v = 0.0, worst_d = 0.0;
  for (int k = 0; k < 10; ++k) {
    const Eigen::Vector3d n = random_axis(rng);
    const double ths = std::asin(1e-2);
    Eigen::Vector3d below, above;
    straddle(n, ths, ths * ths, below, above);
    // Make sure the rotation's own sin²θ straddles 1e-4 (exp and vee may shift it by an ulp).
    auto sigma2 = [](const Eigen::Vector3d& w) { return vee<double>(exp_so3<double>(w)).squaredNorm(); };
    while (sigma2(below) >= rotation_detail::series_below) below *= 1.0 - kEps;
    while (sigma2(above) < rotation_detail::series_below) above *= 1.0 + kEps;
    const Vec3<AD1> lb = log_so3<AD1>(exp_so3<AD1>(ad_point(below)));
    const Vec3<AD1> la = log_so3<AD1>(exp_so3<AD1>(ad_point(above)));
    for (int r = 0; r < 3; ++r) {
      const double ev = std::abs(lb[r].value() - la[r].value());
      worst_v = std::max(worst_v, ev);
      EXPECT_LE(ev, 4 * kEps * ths) << "log at sin²θ = 1e-4";
      for (int i = 0; i < 3; ++i) {
        const double ed = std::abs(d_of(lb[r], i) - d_of(la[r], i));
        worst_d = std::max(worst_d, ed);
        EXPECT_LE(ed, 8 * kEps) << "log at sin²θ = 1e-4";
      }
    }
  }
  rotation_report("jump of log(exp(w)) at sin²θ = 1e-4 (relative to θ)", worst_v / std::asin(1e-2));
  rotation_report("jump of its AD first derivatives", worst_d);
}

// =================================================================== AD at exactly w = 0

TEST(RotationAD, DerivativesOfExpAtExactlyZeroAreHatOfTheDirection) {
  // d/dε exp(εδ)|₀ = δ^ and d²/dε² exp(εδ)|₀ = (δ^)², exactly (AD1 and nested AD2 at w = 0, where
  // the closed forms are 0/0); likewise T(εδ) has derivative −½ δ^ and T⁻¹(εδ) has +½ δ^.
  std::mt19937 rng(14);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Vector3d delta = k < 3 ? Eigen::Vector3d::Unit(k) : random_axis(rng);
    const Eigen::Matrix3d D = hat<double>(delta);
    // AD1 in the direction δ: w = ε δ.
    Vec3<AD1> w;
    for (int i = 0; i < 3; ++i) w[i] = AD1(0.0, Eigen::Matrix<double, 1, 1>::Constant(delta[i]));
    const Mat3<AD1> R = exp_so3<AD1>(w), T = tangent_so3<AD1>(w), Ti = tangent_so3_inverse<AD1>(w);
    EXPECT_EQ(values(R), Eigen::Matrix3d::Identity());
    EXPECT_EQ(partial(R, 0), D);
    EXPECT_EQ(values(T), Eigen::Matrix3d::Identity());
    EXPECT_EQ(partial(T, 0), (-0.5 * D).eval());
    EXPECT_EQ(partial(Ti, 0), (0.5 * D).eval());
    // AD2: the mixed derivative ∂²/∂ε'∂ε exp((ε' + ε) δ) = (δ^)².
    Vec3<AD2> w2;
    for (int i = 0; i < 3; ++i) {
      ad::Derivatives2 d(1);
      d[0] = ad::constant1(delta[i], 1);
      w2[i] = AD2(AD1(0.0, Eigen::Matrix<double, 1, 1>::Constant(delta[i])), d);
    }
    const Mat3<AD2> R2 = exp_so3<AD2>(w2);
    Eigen::Matrix3d second, first_inner, first_outer;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) {
        const AD2& x = R2(r, c);
        first_inner(r, c) = x.value().derivatives().size() ? x.value().derivatives()[0] : 0.0;
        first_outer(r, c) = x.derivatives().size() ? x.derivatives()[0].value() : 0.0;
        second(r, c) = (x.derivatives().size() && x.derivatives()[0].derivatives().size())
                           ? x.derivatives()[0].derivatives()[0]
                           : 0.0;
      }
    EXPECT_EQ(first_inner, D);
    EXPECT_EQ(first_outer, D);
    EXPECT_LE(max_abs(second - D * D), 2 * kEps) << "second derivative:\n" << second << "\n(δ^)²:\n" << D * D;
  }
}

// =================================================================== quaternions

TEST(RotationQuaternion, QuaternionExpIsExpSO3AndQuaternionLogIsLogSO3) {
  // quaternion_exp(w) is a unit quaternion with rotation matrix exp_so3(w);
  // quaternion_log(q) = log_so3(R(q)) (|w| ≤ π), in both series branches (θ² < 1e-4 and σ < 1e-8).
  std::mt19937 rng(15);
  double worst_exp = 0.0, worst_log = 0.0;
  std::vector<double> angles = kAngles;
  angles.push_back(kPi);
  for (double th : angles) {
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d w = th * random_axis(rng);
      const Eigen::Quaterniond q = quaternion_exp(w);
      EXPECT_LE(std::abs(q.norm() - 1.0), 2 * kEps) << "θ = " << th;
      const double e_exp = max_abs(q.toRotationMatrix() - exp_so3<double>(w));
      worst_exp = std::max(worst_exp, e_exp);
      EXPECT_LE(e_exp, 8 * kEps) << "θ = " << th;
      // Against the half-angle closed form (cos θ/2, sin θ/2 n).
      EXPECT_LE(std::abs(q.w() - std::cos(th / 2)), 2 * kEps) << "θ = " << th;
      EXPECT_LE((q.vec() - std::sin(th / 2) * (th > 0 ? w / th : w)).norm(), 2 * kEps * std::max(th, 1e-300) + 1e-300)
          << "θ = " << th;
      if (th < kPi) {
        const Eigen::Vector3d l = quaternion_log(q);
        const double e_log = th == 0.0 ? l.norm() : (l - w).norm() / th;
        worst_log = std::max(worst_log, e_log);
        EXPECT_LE(e_log, 8 * kEps) << "θ = " << th << ": quaternion_log(quaternion_exp(w)) = " << l.transpose();
        EXPECT_LE((l - log_so3<double>(q.toRotationMatrix())).norm(), 32 * kEps * std::max(th, 1e-300)) << "θ = " << th;
      }
    }
  }
  rotation_report("quaternion_exp vs exp_so3", worst_exp);
  rotation_report("|quaternion_log(quaternion_exp(w)) − w| / |w|", worst_log);
}

TEST(RotationQuaternion, QuaternionLogIsSignInvariantAndReturnsTheShortRotation) {
  // q and −q are the same rotation; for |w| > π the log is w − 2π n (|log| ≤ π), like log_so3.
  std::mt19937 rng(16);
  for (double th : {1e-12, 1e-3, 1.0, 3.0, 4.0, 6.0}) {
    const Eigen::Vector3d n = random_axis(rng), w = th * n;
    const Eigen::Quaterniond q = quaternion_exp(w);
    Eigen::Quaterniond mq = q;
    mq.coeffs() = -q.coeffs();
    const Eigen::Vector3d l = quaternion_log(q), lm = quaternion_log(mq);
    EXPECT_EQ(l, lm) << "θ = " << th;
    const Eigen::Vector3d expected = th <= kPi ? w : ((th - 2 * kPi) * n).eval();
    EXPECT_LE((l - expected).norm(), 16 * kEps * th) << "θ = " << th << ": " << l.transpose();
    EXPECT_LE((l - log_so3<double>(exp_so3<double>(w))).norm(), 32 * kEps * th) << "θ = " << th;
  }
}

// =================================================================== frame_from

TEST(RotationFrameFrom, FrameIsOrthonormalRightHandedWithE1AlongTheDirection) {
  // Columns: e1/|e1|, the part of ref2 normal to e1 (normalized, positive along ref2), e1 × e2.
  // Also for a reference vector nearly parallel to e1 (sin∠ down to 1e-7, above the 1e-8 refusal),
  // where a single Gram–Schmidt projection would leave e2·e1 ~ ε/sin∠.
  std::mt19937 rng(17);
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector3d e1 = (0.1 + k) * random_axis(rng);
    Eigen::Vector3d ref = 2.5 * random_axis(rng);
    if (k >= 20) {
      const Eigen::Vector3d perp = (ref - ref.dot(e1) / e1.squaredNorm() * e1).normalized();
      ref = 3.0 * e1.normalized() + std::pow(10.0, -(k % 8)) * perp;
    }
    Eigen::Matrix3d R;
    ASSERT_TRUE(frame_from(e1, ref, R)) << k;
    EXPECT_LE(max_abs(R.transpose() * R - Eigen::Matrix3d::Identity()), 4 * kEps);
    EXPECT_LE(std::abs(R.determinant() - 1.0), 4 * kEps);
    EXPECT_LE((R.col(0) - e1.normalized()).norm(), 2 * kEps);
    EXPECT_GT(R.col(1).dot(ref), 0.0);
    EXPECT_LE(std::abs(R.col(2).dot(ref)), 8 * kEps * ref.norm());  // e3 ⊥ span(e1, ref2)
    EXPECT_LE((R.col(2) - R.col(0).cross(R.col(1))).norm(), 2 * kEps);
  }
  // A known case: e1 = z, ref2 = x + z → e2 = x, e3 = z × x = y.
  Eigen::Matrix3d R;
  ASSERT_TRUE(frame_from(Eigen::Vector3d(0, 0, 3), Eigen::Vector3d(1, 0, 1), R));
  Eigen::Matrix3d expected;
  expected << 0, 1, 0, 0, 0, 1, 1, 0, 0;
  EXPECT_EQ(R, expected);
}

TEST(RotationFrameFrom, FrameFromFailsForParallelOrZeroVectors) {
  Eigen::Matrix3d R;
  const Eigen::Vector3d e(0.3, -1.2, 0.7);
  EXPECT_FALSE(frame_from(e, 2.0 * e, R));
  EXPECT_FALSE(frame_from(e, -e, R));
  EXPECT_FALSE(frame_from(e, e + 1e-12 * Eigen::Vector3d(1.2, 0.3, 0.0), R));  // parallel to round-off
  EXPECT_FALSE(frame_from(Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), R));
  EXPECT_FALSE(frame_from(e, Eigen::Vector3d::Zero(), R));
  EXPECT_TRUE(frame_from(e, e + 1e-3 * Eigen::Vector3d(1.2, 0.3, 0.0), R));  // nearly, but not, parallel
}

}  // namespace alphaflex
