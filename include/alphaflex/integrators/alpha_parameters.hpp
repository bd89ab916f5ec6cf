#pragma once
// Parameters of the generalized-α family (Arnold & Brüls 2007, Sec. 2.3) and their checks.
#include <string>
#include <vector>

namespace alphaflex {

struct AlphaParameters {
  std::string scheme = "generalized-alpha";
  double alpha_m = 0.0, alpha_f = 0.0, beta = 0.25, gamma = 0.5;

  /// Chung & Hulbert's optimal parameters for a spectral radius at infinity ρ∞ ∈ [0, 1], eq. (21),
  /// with γ from the order-2 condition (17).
  static AlphaParameters from_rho_inf(double rho_inf);
  /// Hilber–Hughes–Taylor: α_m = 0, α_f = (1 − ρ∞)/(1 + ρ∞) ∈ [0, 1/3] for ρ∞ ∈ [1/2, 1],
  /// γ = 1/2 + α_f, β = (1 + α_f)²/4.
  static AlphaParameters hht(double rho_inf);
  /// Newmark: α_m = α_f = 0 with the given β, γ (trapezoidal rule: β = 1/4, γ = 1/2).
  static AlphaParameters newmark(double beta, double gamma);
  /// Explicit values.
  static AlphaParameters explicit_values(double alpha_m, double alpha_f, double beta, double gamma);

  /// Conditions that do not hold, each named by its equation: order 2 (17), zero stability
  /// (α_m ≤ 1/2, root of ρ(ζ), eq. 18), strict stability at infinity (20).
  std::vector<std::string> warnings() const;
  /// Throws InputError if the scheme is undefined (α_m = 1, α_f = 1, β ≤ 0, γ < 0).
  void validate() const;

  /// Spectral radius at infinity of the linear undamped oscillator, max |eigenvalue| of the
  /// amplification matrix as ωh → ∞ (for reporting).
  double rho_infinity() const;

  /// β' = (1 − α_m)/(βh²(1 − α_f)) and γ' = γ/(βh) of eq. (6): ∂q̈/∂q and ∂q̇/∂q of a Newton
  /// correction (the one place they are computed).
  double beta_prime(double h) const { return (1.0 - alpha_m) / (h * h * beta * (1.0 - alpha_f)); }
  double gamma_prime(double h) const { return gamma / (h * beta); }
  /// C of the local error of q in one step, q_{n+1} − q(t_{n+1}) ≈ C h² (a_{n+1} − a_n) with
  /// C = β + (α_m − α_f)/2 − 1/6 (docs/theory/adaptive_steps.md; Zienkiewicz & Xie 1991 for Newmark,
  /// where it is β − 1/6).
  double local_error_constant() const { return beta + 0.5 * (alpha_m - alpha_f) - 1.0 / 6.0; }
};

}  // namespace alphaflex
