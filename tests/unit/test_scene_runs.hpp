#pragma once
// Helpers of the tests that run small scenes given as YAML text (force elements, energies,
// initial conditions): the run, and the period of an oscillating sensor.
#include <vector>

#include "test_support.hpp"

namespace alphaflex::testing {

/// Runs a scene given as YAML text (`label` stands for its file: relative mesh paths start there),
/// no files written, every output step's sensors kept.
inline RunSummary run_text(const std::string& yaml, const std::string& label) {
  Scene scene = read_scene_text(yaml, label);
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  opt.keep_history = true;
  return run_simulation(scene, opt, PETSC_COMM_WORLD);
}

/// The times where sensor `column` crosses zero upward (linear interpolation between output steps).
inline std::vector<double> upward_zero_crossings(const RunSummary& r, size_t column) {
  std::vector<double> up;
  for (size_t i = 1; i < r.times_out.size(); ++i) {
    const double a = r.sensor_history[i - 1][column], b = r.sensor_history[i][column];
    if (a < 0.0 && b >= 0.0) up.push_back(r.times_out[i - 1] + (r.times_out[i] - r.times_out[i - 1]) * a / (a - b));
  }
  return up;
}

}  // namespace alphaflex::testing
