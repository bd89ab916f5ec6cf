#pragma once
// Scalar functions of time f(t) with their first two derivatives, for time-dependent loads (and
// later prescribed motions, whose constraint derivatives Φ_t, Φ_tt need f' and f'').
#include <memory>
#include <string>
#include <vector>

namespace alphaflex {

class TimeFunction {
 public:
  virtual ~TimeFunction() = default;
  virtual double value(double t) const = 0;
  virtual double derivative(double t) const = 0;
  virtual double second_derivative(double t) const = 0;
};

using TimeFunctionPtr = std::shared_ptr<const TimeFunction>;

/// f(t) = c.
TimeFunctionPtr make_constant(double c);
/// Linear from v0 at t0 to v1 at t1, constant outside.
TimeFunctionPtr make_ramp(double t0, double t1, double v0, double v1);
/// Quintic smooth step from v0 at t0 to v1 at t1 (zero slope and curvature at both ends).
TimeFunctionPtr make_smooth_step(double t0, double t1, double v0, double v1);
/// Smooth spin-up to the rate ω (rad/s) in time T (s), Simo & Vu-Quoc (1986):
/// ω/T [t²/2 + (T/2π)²(cos(2πt/T) − 1)] for t < T, then ω(t − T/2).
TimeFunctionPtr make_spin_up(double omega, double T);
/// offset + rate · t.
TimeFunctionPtr make_linear(double rate, double offset);
/// offset + amplitude sin(2π frequency t + phase).
TimeFunctionPtr make_sine(double amplitude, double frequency, double phase, double offset);
/// Piecewise linear through (t_i, v_i), constant beyond the ends; t strictly increasing.
TimeFunctionPtr make_table(std::vector<double> t, std::vector<double> v);
/// c · f(t) (e.g. a load per length times the length a node carries).
TimeFunctionPtr make_scaled(TimeFunctionPtr f, double c);

}  // namespace alphaflex
