#pragma once
// The work sensors (`work`: the work of the loads, the energy the force elements dissipate) are
// time integrals of powers that model/sensor.cpp evaluates at each state (energy sums of
// components 4 and 5). This integrates them over the accepted steps by the trapezoidal rule,
// W_n = W_{n−1} + (t_n − t_{n−1}) (P_{n−1} + P_n) / 2, W_0 = 0 — second order in h, like the
// scheme (docs/theory/force_elements.md, energy balance).
#include <vector>

#include "alphaflex/model/sensor.hpp"

namespace alphaflex {

class SensorIntegrals {
 public:
  explicit SensorIntegrals(const std::vector<Sensor>& sensors);
  bool empty() const { return which_.empty(); }
  /// Replaces the work sensors' powers in `values` (scene order) at time t by their integrals.
  void integrate(double t, std::vector<double>& values);
  /// What a restart needs to go on as if uninterrupted (kept in the checkpoint, RunPosition::
  /// accumulated): [t, the integrals, the last powers]; empty if there is nothing to integrate.
  std::vector<double> state() const;
  /// Continues from `state()` of a checkpoint; false if it is not of these sensors (another count).
  bool restore(const std::vector<double>& state);

 private:
  std::vector<size_t> which_;
  std::vector<double> power_, integral_;
  double t_ = 0.0;
  bool started_ = false;
};

}  // namespace alphaflex
