#include "alphaflex/io/sensor_schedule.hpp"

#include <cmath>

namespace alphaflex {

SensorSchedule::SensorSchedule(bool on, double dt, double t_start, bool initial_row)
    : on_(on), dt_(dt), t_prev_(t_start), pending_initial_(initial_row) {}

bool SensorSchedule::due(double t, bool last) {
  if (!on_) return false;
  if (pending_initial_) {
    pending_initial_ = false;
    return true;
  }
  if (dt_ <= 0.0) return true;
  // The interval index of t, with a margin of 1e-9 dt: a step that lands on k·dt up to round-off
  // (t = t_anchor + k·h; adaptive steps landing on output.dt) counts as reaching it.
  const double margin = 1e-9 * dt_;
  const bool crossed = std::floor((t + margin) / dt_) > std::floor((t_prev_ + margin) / dt_);
  t_prev_ = t;
  return crossed || last;
}

}  // namespace alphaflex
