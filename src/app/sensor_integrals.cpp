#include "alphaflex/app/sensor_integrals.hpp"

namespace alphaflex {

SensorIntegrals::SensorIntegrals(const std::vector<Sensor>& sensors) {
  for (size_t k = 0; k < sensors.size(); ++k)
    if (sensors[k].kind == Sensor::Kind::ElementEnergy && sensors[k].component >= 4) which_.push_back(k);
  power_.assign(which_.size(), 0.0);
  integral_.assign(which_.size(), 0.0);
}

void SensorIntegrals::integrate(double t, std::vector<double>& values) {
  for (size_t i = 0; i < which_.size(); ++i) {
    const double p = values[which_[i]];
    if (started_) integral_[i] += 0.5 * (t - t_) * (power_[i] + p);
    power_[i] = p;
    values[which_[i]] = integral_[i];
  }
  t_ = t;
  started_ = true;
}

std::vector<double> SensorIntegrals::state() const {
  if (which_.empty()) return {};
  std::vector<double> s{t_};
  s.insert(s.end(), integral_.begin(), integral_.end());
  s.insert(s.end(), power_.begin(), power_.end());
  return s;
}

bool SensorIntegrals::restore(const std::vector<double>& state) {
  if (state.size() != 1 + 2 * which_.size()) return false;
  t_ = state[0];
  std::copy(state.begin() + 1, state.begin() + 1 + which_.size(), integral_.begin());
  std::copy(state.begin() + 1 + which_.size(), state.end(), power_.begin());
  started_ = true;
  return true;
}

}  // namespace alphaflex
