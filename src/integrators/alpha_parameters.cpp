#include "alphaflex/integrators/alpha_parameters.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>

#include "alphaflex/core/error.hpp"

namespace alphaflex {

AlphaParameters AlphaParameters::from_rho_inf(double r) {
  if (!(r >= 0.0 && r <= 1.0)) throw InputError("solver.rho_inf must lie in [0, 1], got " + std::to_string(r));
  AlphaParameters p;
  p.scheme = "generalized-alpha";
  p.alpha_m = (2.0 * r - 1.0) / (r + 1.0);
  p.alpha_f = r / (r + 1.0);
  p.gamma = 0.5 + p.alpha_f - p.alpha_m;
  p.beta = 0.25 * (p.gamma + 0.5) * (p.gamma + 0.5);
  return p;
}

AlphaParameters AlphaParameters::hht(double r) {
  if (!(r >= 0.5 && r <= 1.0))
    throw InputError("HHT needs solver.rho_inf in [0.5, 1] (α ∈ [0, 1/3]), got " + std::to_string(r));
  AlphaParameters p;
  p.scheme = "hht";
  p.alpha_m = 0.0;
  p.alpha_f = (1.0 - r) / (1.0 + r);
  p.gamma = 0.5 + p.alpha_f;
  p.beta = 0.25 * (1.0 + p.alpha_f) * (1.0 + p.alpha_f);
  return p;
}

AlphaParameters AlphaParameters::newmark(double beta, double gamma) {
  AlphaParameters p;
  p.scheme = "newmark";
  p.beta = beta;
  p.gamma = gamma;
  return p;
}

AlphaParameters AlphaParameters::explicit_values(double am, double af, double beta, double gamma) {
  AlphaParameters p;
  p.scheme = "generalized-alpha";
  p.alpha_m = am;
  p.alpha_f = af;
  p.beta = beta;
  p.gamma = gamma;
  return p;
}

void AlphaParameters::validate() const {
  std::vector<std::string> why;
  if (std::fabs(1.0 - alpha_m) < 1e-12) why.push_back("alpha_m = 1 makes the recurrence (3) for a undefined");
  if (std::fabs(1.0 - alpha_f) < 1e-12) why.push_back("alpha_f = 1 makes beta' (eq. 6) undefined");
  if (!(beta > 0.0)) why.push_back("beta must be positive (beta' and gamma' of eq. 6 divide by it)");
  if (!(gamma >= 0.0)) why.push_back("gamma must be non-negative");
  if (why.empty()) return;
  std::string msg = "invalid generalized-alpha parameters: ";
  for (size_t i = 0; i < why.size(); ++i) msg += (i ? "; " : "") + why[i];
  throw InputError(msg);
}

std::vector<std::string> AlphaParameters::warnings() const {
  std::vector<std::string> w;
  auto fmt = [](double x) {
    std::ostringstream s;
    s.precision(6);
    s << x;
    return s.str();
  };
  const double g17 = 0.5 + alpha_f - alpha_m;
  if (std::fabs(gamma - g17) > 1e-12)
    w.push_back("order-2 condition (eq. 17) fails: γ = " + fmt(gamma) + " but 1/2 + α_f − α_m = " + fmt(g17) +
                "; the scheme is only first-order accurate");
  if (alpha_m > 0.5)
    w.push_back("zero stability fails: α_m = " + fmt(alpha_m) +
                " > 1/2, the root −α_m/(1−α_m) of ρ(ζ) (eq. 18) lies outside the unit circle; errors grow "
                "without bound as h → 0");
  const bool ordered = alpha_m < alpha_f && alpha_f < 0.5;
  const double beta_min = 0.25 + 0.5 * (alpha_f - alpha_m);
  if (!ordered || !(beta > beta_min)) {
    std::string why;
    if (!ordered) why += "α_m < α_f < 1/2 does not hold (α_m = " + fmt(alpha_m) + ", α_f = " + fmt(alpha_f) + ")";
    if (!(beta > beta_min)) {
      if (!why.empty()) why += " and ";
      why += "β = " + fmt(beta) + " is not > 1/4 + (α_f − α_m)/2 = " + fmt(beta_min);
    }
    w.push_back("strict stability at infinity (eq. 20) is not guaranteed: " + why +
                "; Lagrange multipliers may oscillate and their second order is not proven (Sec. 3.4)");
  }
  return w;
}

double AlphaParameters::rho_infinity() const {
  // Linear oscillator x'' = −ω²x in the variables y = (x, h v, h² a). Dividing the recurrence (3)
  // by ω²h² and letting ωh → ∞ leaves (1−α_f) x_{n+1} = −α_f x_n; with (4)–(5) this gives the
  // amplification matrix at infinity A⁻¹B, whose spectral radius is ρ∞.
  Eigen::Matrix3d A, B;
  A << 1, 0, -beta,
       0, 1, -gamma,
       1 - alpha_f, 0, 0;
  B << 1, 1, 0.5 - beta,
       0, 1, 1 - gamma,
       -alpha_f, 0, 0;
  return (A.inverse() * B).eigenvalues().cwiseAbs().maxCoeff();
}

}  // namespace alphaflex
