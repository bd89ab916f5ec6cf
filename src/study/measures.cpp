#include "alphaflex/study/measures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>

namespace alphaflex::study {

double loglog_slope(const std::vector<double>& h, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (size_t i = 0; i < h.size() && i < err.size(); ++i) {
    if (!(err[i] > 0.0) || !std::isfinite(err[i]) || !(h[i] > 0.0)) continue;
    const double x = std::log(h[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    ++n;
  }
  const double den = n * sxx - sx * sx;
  if (n < 2 || !(std::fabs(den) > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / den;
}

SlopeFit fit_convergence(const std::vector<double>& h, const std::vector<double>& err, double roundoff) {
  std::vector<std::pair<double, double>> pts;  // (h, error), finite positive errors only
  for (size_t i = 0; i < h.size() && i < err.size(); ++i)
    if (err[i] > 0.0 && std::isfinite(err[i]) && h[i] > 0.0) pts.emplace_back(h[i], err[i]);
  std::sort(pts.begin(), pts.end());
  SlopeFit fit;
  if (pts.empty()) return fit;
  double largest = 0.0;
  for (const auto& p : pts) largest = std::max(largest, p.second);
  if (largest <= roundoff) {
    fit.roundoff = true;
    fit.at_floor = static_cast<int>(pts.size());
    fit.floor = largest;
    fit.h_floor = pts.back().first;
    return fit;
  }
  // From the smallest h up: a point is at the floor while its error is at round-off or while going
  // to the next larger h does not raise the error by (h ratio)^0.5 (a local order below 1/2).
  size_t first = 0;
  while (first + 1 < pts.size()) {
    const auto& [h0, e0] = pts[first];
    const auto& [h1, e1] = pts[first + 1];
    const bool flat = std::log(e1 / e0) < 0.5 * std::log(h1 / h0);
    if (!(e0 <= roundoff || flat)) break;
    fit.floor = std::max(fit.floor, e0);
    fit.h_floor = h0;
    ++first;
  }
  if (first + 1 == pts.size()) {  // no step up anywhere: the last point is as flat as the others
    fit.floor = std::max(fit.floor, pts.back().second);
    fit.h_floor = pts.back().first;
    first = pts.size();
  }
  fit.at_floor = static_cast<int>(first);
  std::vector<double> hs, es;
  for (size_t i = first; i < pts.size(); ++i) {
    hs.push_back(pts[i].first);
    es.push_back(pts[i].second);
  }
  fit.points = static_cast<int>(hs.size());
  if (hs.size() >= 2) fit.slope = loglog_slope(hs, es);
  // What is left must still fall with h: a slope under 1/2 (scattered or rising errors) is no order.
  if (fit.slope < 0.5) {
    fit.rising = fit.slope;
    fit.slope = std::numeric_limits<double>::quiet_NaN();
  }
  return fit;
}

std::string SlopeFit::describe() const {
  auto g = [](double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2g", x);
    return std::string(buf);
  };
  char slope_text[32];
  std::snprintf(slope_text, sizeof slope_text, "%.2f", slope);
  if (roundoff) return "none: errors at round-off (<= " + g(floor) + ")";
  if (!std::isnan(rising))
    return "none: errors do not decrease as h decreases (least-squares slope " + g(rising) + ")" +
           (at_floor ? "; for h <= " + g(h_floor) + " they stop decreasing (at " + g(floor) + ")" : std::string());
  if (at_floor == 0) return std::isnan(slope) ? "none: fewer than two errors" : slope_text;
  const std::string level = "for h <= " + g(h_floor) + " the errors stop decreasing (at " + g(floor) +
                            "): round-off, the reference's accuracy or an error that h does not reduce";
  if (std::isnan(slope)) return "none: " + level;
  return std::string(slope_text) + " over the " + std::to_string(points) + " larger h; " + level;
}

double total_variation(const std::vector<double>& x) {
  double tv = 0.0;
  for (size_t i = 1; i < x.size(); ++i) tv += std::fabs(x[i] - x[i - 1]);
  return tv;
}

double rms_second_difference(const std::vector<double>& x) {
  if (x.size() < 3) return 0.0;
  double s = 0.0;
  for (size_t i = 1; i + 1 < x.size(); ++i) {
    const double d = x[i + 1] - 2.0 * x[i] + x[i - 1];
    s += d * d;
  }
  return std::sqrt(s / static_cast<double>(x.size() - 2));
}

std::vector<std::complex<double>> rho_roots(const AlphaParameters& p) {
  // ϱ(ζ) = −α_m + (2α_m − 1)ζ + (1 − α_m)ζ² = (ζ − 1)((1 − α_m)ζ + α_m).
  return {1.0, -p.alpha_m / (1.0 - p.alpha_m)};
}

std::vector<std::complex<double>> sigma_roots(const AlphaParameters& p) {
  // Lemma 1: σ(ζ) = β((1 − α_f)ζ + α_f)(ζ² + ((1/2 + γ − 2β)/β) ζ + (1/2 − γ + β)/β).
  const double b = p.beta, g = p.gamma;
  const std::complex<double> z1 = -p.alpha_f / (1.0 - p.alpha_f);
  const double B = (0.5 + g - 2.0 * b) / b, C = (0.5 - g + b) / b;
  const std::complex<double> disc = std::sqrt(std::complex<double>(B * B - 4.0 * C, 0.0));
  return {z1, 0.5 * (-B + disc), 0.5 * (-B - disc)};
}

double predicted_growth(const AlphaParameters& p) {
  double m = std::abs(rho_roots(p)[1]);  // the parasitic root (ζ = 1 is the solution itself)
  for (const auto& z : sigma_roots(p)) m = std::max(m, std::abs(z));
  return m;
}

double geometric_growth(const std::vector<double>& g, double scale) {
  std::vector<double> lg;
  for (double v : g) lg.push_back(v > 0.0 && std::isfinite(v) ? std::log(v) : -std::numeric_limits<double>::infinity());
  if (lg.size() < 10) return std::numeric_limits<double>::quiet_NaN();
  std::vector<double> head(lg.begin(), lg.begin() + static_cast<long>(std::max<size_t>(3, lg.size() / 10)));
  std::nth_element(head.begin(), head.begin() + static_cast<long>(head.size() / 2), head.end());
  const double lo = head[head.size() / 2];
  size_t imax = 0;
  for (size_t i = 0; i < lg.size(); ++i)
    if (lg[i] > lg[imax]) imax = i;
  const double hi = lg[imax];
  if (!std::isfinite(lo) || !(hi - lo > std::log(1e3))) return std::numeric_limits<double>::quiet_NaN();
  const double top = std::min(hi - std::log(1e2), std::log(10.0 * scale));
  // The window: after the last time g was within 1e2 of its start-up level (which would bias the
  // rate by its share), up to `top`.
  size_t start = 0;
  for (size_t i = 0; i <= imax; ++i)
    if (lg[i] < lo + std::log(1e2)) start = i;
  std::vector<double> x, y;
  for (size_t i = start + 1; i <= imax; ++i)
    if (lg[i] <= top && std::isfinite(lg[i])) {
      x.push_back(static_cast<double>(i));
      y.push_back(lg[i]);
    }
  if (x.size() < 3) return std::numeric_limits<double>::quiet_NaN();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  return std::exp((n * sxy - sx * sy) / (n * sxx - sx * sx));
}

}  // namespace alphaflex::study
