#pragma once
// The numbers a study reports: convergence orders, oscillation measures of multiplier histories,
// and the growth factor of an unstable scheme against the roots that predict it (Arnold & Brüls
// 2007, eq. 18 and 19).
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "alphaflex/integrators/alpha_parameters.hpp"

namespace alphaflex::study {

/// Least-squares slope of log(err) against log(h) over the pairs with a finite positive error
/// (NaN if fewer than two): the observed order of convergence.
double loglog_slope(const std::vector<double>& h, const std::vector<double>& err);

/// A convergence slope and whether it means anything. Below some error the error of a run no
/// longer measures its truncation error: round-off (relative errors of ~1e-16 to 1e-12: a driven
/// crank's angle is exact up to its last bits) or the reference's own accuracy (an independent
/// solution at rtol 1e-13, a reference run at a finer h, joint forces levelling off at 1e-6). A
/// slope fitted through such points is noise ("slope 0.65" of errors at 1e-17 says nothing about
/// an order 2). fit_convergence() finds them from the small-h end of the line: an error at or below
/// `roundoff`, or one that is not smaller than the next larger h's by at least (ratio of h)^0.5 —
/// a local order under 0.5, where the scheme's order is 1 or 2 — is at the floor; the slope is
/// fitted over the points above it, or not at all when fewer than two remain or when their slope is
/// itself under 1/2.
struct SlopeFit {
  double slope = std::numeric_limits<double>::quiet_NaN();  ///< NaN: no order to measure
  int points = 0;          ///< errors the slope is fitted over (those above the floor)
  int at_floor = 0;        ///< errors left out: at round-off or levelled off
  bool roundoff = false;   ///< every error is at or below `roundoff`
  double floor = 0.0;      ///< the largest error left out (the level the errors sit at)
  double h_floor = 0.0;    ///< the largest h whose error is left out
  /// The slope of the points above the floor when it is under 1/2 (then `slope` is NaN): errors
  /// that scatter or grow as h decreases.
  double rising = std::numeric_limits<double>::quiet_NaN();
  /// The sentence for the log, the CSV and the charts: "2.01", "2.01 over the 4 larger h; for
  /// h <= 0.0005 the errors stop decreasing (at 1e-06): ...", "none: errors at round-off (<= 8e-17)".
  std::string describe() const;
};
SlopeFit fit_convergence(const std::vector<double>& h, const std::vector<double>& err, double roundoff = 1e-12);

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
