#pragma once
// The numbers a study reports: convergence orders, oscillation measures of multiplier histories,
// and the growth factor of an unstable scheme against the roots that predict it (Arnold & Brüls
// 2007, eq. 18 and 19).
#include <complex>
#include <limits>
#include <vector>

#include "alphaflex/integrators/alpha_parameters.hpp"

namespace alphaflex::study {

/// Least-squares slope of log(err) against log(h) over the pairs with a finite positive error
/// (NaN if fewer than two): the observed order of convergence.
double loglog_slope(const std::vector<double>& h, const std::vector<double>& err);

/// Σ |x_{n+1} − x_n|: total variation of a sampled history (divide by the time span for a rate).
double total_variation(const std::vector<double>& x);

/// RMS over n of x_{n+1} − 2x_n + x_{n−1}: small (O(h²) times x'') on a smooth history, of the
/// order of the amplitude on a step-to-step oscillation.
double rms_second_difference(const std::vector<double>& x);

/// Roots of ϱ(ζ) = Σ a_k ζ^k (eq. 18): 1 and −α_m/(1 − α_m). Zero stability needs |ζ| ≤ 1.
std::vector<std::complex<double>> rho_roots(const AlphaParameters& p);
/// Roots of σ(ζ) = Σ b'_k ζ^k (eq. 19, coefficients of eq. 16): strict stability at infinity
/// needs all |ζ'| < 1 (Lemma 1); they govern the multipliers' error recursion (eq. 35).
std::vector<std::complex<double>> sigma_roots(const AlphaParameters& p);
/// max |ζ| over the parasitic root −α_m/(1 − α_m) of ϱ and the roots of σ: the growth factor per
/// step that an instability of either kind should show (below 1: the factor a perturbation decays by) (errors in λ follow both, eq. 37: E^λ is driven by E^v with O(1) coupling).
double predicted_growth(const AlphaParameters& p);

/// Growth per step of a sequence that grows geometrically, g_n ≈ C γⁿ: exp of the least-squares
/// slope of log g_n over the steps where g_n has risen by 1e2 above its start-up level (the median
/// of its first tenth) and is still below min(1e-2 × its maximum, 10 × `scale`), i.e. while the
/// growing mode is a small perturbation of a solution of size `scale` (linear theory), before the
/// nonlinear blow-up and the Newton failure that end it. NaN if g grows by less than 1e3.
double geometric_growth(const std::vector<double>& g, double scale = std::numeric_limits<double>::infinity());

}  // namespace alphaflex::study
