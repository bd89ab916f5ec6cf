#pragma once
// Which accepted steps of a dynamic run write a row of NAME.csv (output.sensors, output.sensors_dt,
// issue 22: output that costs nothing when it is not wanted). Rows at a time interval rather than a
// step count, so that a row interval means the same at any h and with adaptive steps: a row at the
// first step at or after each multiple of dt (exactly at it when the steps land there), the
// initial state and the last step. The decision depends only on the times of this step and the
// previous one, so a restart from a checkpoint writes the rows the uninterrupted run writes.

namespace alphaflex {

class SensorSchedule {
 public:
  /// `on`: rows at all (output.sensors); `dt` > 0: at multiples of dt, 0: every step; `t_start`:
  /// the time the run starts from (0, or a checkpoint's time); `initial_row`: whether the state at
  /// t_start gets a row (a fresh run; a restart's rows up to its checkpoint are in the CSV already).
  SensorSchedule(bool on, double dt, double t_start, bool initial_row);
  /// Whether the state at time `t` gets a row; `last`: the run's last step. Call once per accepted
  /// step, in order (and first with the initial state when `initial_row`).
  bool due(double t, bool last);

 private:
  bool on_;
  double dt_;
  double t_prev_;
  bool pending_initial_;
};

}  // namespace alphaflex
