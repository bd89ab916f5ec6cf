// Parameters of the generalized-α family: Chung–Hulbert formulas (eq. 21), order-2 condition
// (eq. 17), zero stability (α_m ≤ 1/2, roots of ρ(ζ), eq. 18), strict stability at infinity
// (eq. 20, Lemma 1), and the HHT and Newmark presets.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <complex>

#include "alphaflex/core/error.hpp"
#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/io/scene.hpp"

namespace alphaflex {
namespace {

bool mentions(const std::vector<std::string>& w, const std::string& what) {
  for (const auto& s : w)
    if (s.find(what) != std::string::npos) return true;
  return false;
}

// Roots of σ(ζ) = Σ b'_k ζ^k with b' of eq. (16).
double max_sigma_root(const AlphaParameters& p) {
  const double af = p.alpha_f, b = p.beta, g = p.gamma;
  const double b0 = af * (0.5 + b - g);
  const double b1 = (1 - af) * (0.5 + b - g) + af * (0.5 - 2 * b + g);
  const double b2 = (1 - af) * (0.5 - 2 * b + g) + af * b;
  const double b3 = (1 - af) * b;
  Eigen::Matrix3d companion;
  companion << -b2 / b3, -b1 / b3, -b0 / b3, 1, 0, 0, 0, 1, 0;
  return companion.eigenvalues().cwiseAbs().maxCoeff();
}

TEST(AlphaParameters, ChungHulbertFormulasEq21) {
  const AlphaParameters p = AlphaParameters::from_rho_inf(0.7);
  EXPECT_DOUBLE_EQ(p.alpha_m, (2 * 0.7 - 1) / 1.7);
  EXPECT_DOUBLE_EQ(p.alpha_f, 0.7 / 1.7);
  EXPECT_DOUBLE_EQ(p.gamma, 0.5 + p.alpha_f - p.alpha_m);
  EXPECT_DOUBLE_EQ(p.beta, 0.25 * (p.gamma + 0.5) * (p.gamma + 0.5));
  // ρ∞ = 0.7: α_m = 0.4/1.7, α_f = 0.7/1.7, γ = 1/2 + 0.3/1.7.
  EXPECT_NEAR(p.alpha_m, 0.23529411764705882, 1e-15);
  EXPECT_NEAR(p.gamma, 0.67647058823529416, 1e-15);
}

// Chung & Hulbert choose the parameters so that the eigenvalue at infinity is a multiple root;
// eigenvalues of such a Jordan block are only resolved to about ε^(1/3) ≈ 6e-6, hence 2e-5.
TEST(AlphaParameters, SpectralRadiusAtInfinityEqualsRhoInf) {
  for (double r : {0.0, 0.3, 0.7, 0.9, 1.0}) EXPECT_NEAR(AlphaParameters::from_rho_inf(r).rho_infinity(), r, 2e-5) << r;
  for (double r : {0.5, 0.8, 1.0}) EXPECT_NEAR(AlphaParameters::hht(r).rho_infinity(), r, 2e-5) << r;
  EXPECT_NEAR(AlphaParameters::newmark(0.25, 0.5).rho_infinity(), 1.0, 1e-12);
}

// Sec. 2.3: for ρ∞ ∈ [0, 1) the CH parameters satisfy (17), α_m ≤ 1/2 and (20), and Lemma 1
// then guarantees |ζ'| < 1 for the roots of σ.
TEST(AlphaParameters, RhoInfBelowOneSatisfiesAllConditionsLemma1) {
  for (double r : {0.0, 0.2, 0.5, 0.7, 0.95}) {
    const AlphaParameters p = AlphaParameters::from_rho_inf(r);
    EXPECT_TRUE(p.warnings().empty()) << r;
    EXPECT_LT(max_sigma_root(p), 1.0) << r;
  }
}

// ρ∞ = 1 gives α_m = α_f = 1/2: (20) fails, and σ has a double root on the unit circle
// (resolved to ~√ε by the eigenvalue solver, hence 1e-5).
TEST(AlphaParameters, RhoInfOneIsNotStrictlyStableAtInfinity) {
  const AlphaParameters p = AlphaParameters::from_rho_inf(1.0);
  EXPECT_TRUE(mentions(p.warnings(), "eq. 20"));
  EXPECT_FALSE(mentions(p.warnings(), "eq. 17"));
  EXPECT_NEAR(max_sigma_root(p), 1.0, 1e-5);
}

TEST(AlphaParameters, OrderTwoConditionEq17IsChecked) {
  const AlphaParameters p = AlphaParameters::explicit_values(0.2, 0.4, 0.35, 0.6);
  EXPECT_TRUE(mentions(p.warnings(), "eq. 17"));
}

TEST(AlphaParameters, ZeroStabilityAlphaMAboveHalfIsChecked) {
  // α_m = 0.6 > 1/2: the root −α_m/(1−α_m) = −1.5 of ρ(ζ) lies outside the unit circle.
  const AlphaParameters p = AlphaParameters::explicit_values(0.6, 0.7, 0.5, 0.6);
  EXPECT_TRUE(mentions(p.warnings(), "zero stability"));
  EXPECT_FALSE(mentions(p.warnings(), "eq. 17"));
}

TEST(AlphaParameters, NewmarkTrapezoidalIsSecondOrderButNotStrictlyStable) {
  const AlphaParameters p = AlphaParameters::newmark(0.25, 0.5);
  EXPECT_FALSE(mentions(p.warnings(), "eq. 17"));
  EXPECT_TRUE(mentions(p.warnings(), "eq. 20"));
  // Damped Newmark (γ > 1/2) loses the order-2 condition.
  EXPECT_TRUE(mentions(AlphaParameters::newmark(0.3025, 0.6).warnings(), "eq. 17"));
}

// `scheme: newmark` with `rho_inf` is the damped Newmark γ = (3 − ρ∞)/(2(1 + ρ∞)),
// β = 1/(1 + ρ∞)², whose spectral radius at infinity is ρ∞ and which is first order for ρ∞ < 1.
TEST(AlphaParameters, DampedNewmarkFromRhoInfInAScene) {
  Scene sc = read_scene_text("solver: {scheme: newmark, rho_inf: 0.5}\nbodies: [{name: b, type: particle, mass: 1, position: [0, 0]}]\n",
                             "newmark.yaml");
  const AlphaParameters& p = sc.settings.parameters;
  EXPECT_DOUBLE_EQ(p.gamma, 2.5 / 3.0);
  EXPECT_DOUBLE_EQ(p.beta, 1.0 / 2.25);
  EXPECT_NEAR(p.rho_infinity(), 0.5, 2e-5);
  EXPECT_TRUE(mentions(p.warnings(), "eq. 17"));
}

TEST(AlphaParameters, HhtPresetSatisfiesEq17And20) {
  const AlphaParameters p = AlphaParameters::hht(0.8);
  EXPECT_DOUBLE_EQ(p.alpha_m, 0.0);
  EXPECT_NEAR(p.alpha_f, 0.2 / 1.8, 1e-15);
  EXPECT_TRUE(p.warnings().empty());
  EXPECT_THROW(AlphaParameters::hht(0.3), InputError);
}

TEST(AlphaParameters, UndefinedSchemesAreRefused) {
  EXPECT_THROW(AlphaParameters::explicit_values(1.0, 0.4, 0.3, 0.6).validate(), InputError);
  EXPECT_THROW(AlphaParameters::explicit_values(0.2, 1.0, 0.3, 0.6).validate(), InputError);
  EXPECT_THROW(AlphaParameters::explicit_values(0.2, 0.4, 0.0, 0.6).validate(), InputError);
  EXPECT_THROW(AlphaParameters::from_rho_inf(1.5), InputError);
}

}  // namespace
}  // namespace alphaflex
