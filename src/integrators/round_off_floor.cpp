#include "alphaflex/integrators/round_off_floor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace alphaflex {

namespace {
/// Relative noise of accelerations and reactions a run warns about (0.1 %).
constexpr double kRelativeFloor = 1e-3;
}  // namespace

double round_off_floor(const AlphaParameters& p, double h, double q_norm) {
  return std::numeric_limits<double>::epsilon() * std::max(q_norm, 1e-300) * p.beta_prime(h);
}

std::string round_off_floor_warning(const AlphaParameters& p, double h, double q_norm, double acc_scale) {
  const double floor = round_off_floor(p, h, q_norm);
  if (!(floor > kRelativeFloor * acc_scale)) return {};
  std::ostringstream os;
  os.precision(3);
  os << "at h = " << h << " s the accelerations and joint reactions (multipliers) may carry round-off of up to " << floor
     << " in q̈ units, the estimate ε‖q‖/(βh²) of the index-3 formulation (on the beam spin-up the noise measured in "
        "the reactions is 10³–10⁴ times smaller: docs/performance.md)";
  if (acc_scale > 0.0) {
    // floor ∝ 1/h²: the h at which it is kRelativeFloor of the accelerations.
    const double h_ok = h * std::sqrt(floor / (kRelativeFloor * acc_scale));
    os << ", " << 100.0 * floor / acc_scale << " % of the largest |q̈| at the start and the end of the run (" << acc_scale
       << "); positions and velocities are not affected. For accelerations or reactions to 0.1 %, use h >= " << h_ok << " s";
  } else {
    os << " (q̈ = 0 at the start and the end of the run); positions and velocities are not affected";
  }
  os << ".";
  return os.str();
}

}  // namespace alphaflex
