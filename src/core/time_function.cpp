#include "alphaflex/core/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace alphaflex {
namespace {

class Scaled final : public TimeFunction {
 public:
  Scaled(TimeFunctionPtr f, double c) : f_(std::move(f)), c_(c) {}
  double value(double t) const override { return c_ * f_->value(t); }
  double derivative(double t) const override { return c_ * f_->derivative(t); }
  double second_derivative(double t) const override { return c_ * f_->second_derivative(t); }

 private:
  TimeFunctionPtr f_;
  double c_;
};

class Constant final : public TimeFunction {
 public:
  explicit Constant(double c) : c_(c) {}
  double value(double) const override { return c_; }
  double derivative(double) const override { return 0.0; }
  double second_derivative(double) const override { return 0.0; }

 private:
  double c_;
};

class Ramp final : public TimeFunction {
 public:
  Ramp(double t0, double t1, double v0, double v1) : t0_(t0), t1_(t1), v0_(v0), v1_(v1) {}
  double value(double t) const override {
    if (t <= t0_) return v0_;
    if (t >= t1_) return v1_;
    return v0_ + (v1_ - v0_) * (t - t0_) / (t1_ - t0_);
  }
  double derivative(double t) const override {
    return (t > t0_ && t < t1_) ? (v1_ - v0_) / (t1_ - t0_) : 0.0;
  }
  double second_derivative(double) const override { return 0.0; }

 private:
  double t0_, t1_, v0_, v1_;
};

class SmoothStep final : public TimeFunction {
 public:
  SmoothStep(double t0, double t1, double v0, double v1) : t0_(t0), t1_(t1), v0_(v0), v1_(v1) {}
  // s(x) = 10x³ − 15x⁴ + 6x⁵ on x ∈ [0,1]: C² at both ends.
  double value(double t) const override {
    const double x = clamp(t);
    return v0_ + (v1_ - v0_) * x * x * x * (10.0 - 15.0 * x + 6.0 * x * x);
  }
  double derivative(double t) const override {
    if (t <= t0_ || t >= t1_) return 0.0;
    const double x = clamp(t);
    return (v1_ - v0_) / (t1_ - t0_) * 30.0 * x * x * (1.0 - x) * (1.0 - x);
  }
  double second_derivative(double t) const override {
    if (t <= t0_ || t >= t1_) return 0.0;
    const double x = clamp(t), d = t1_ - t0_;
    return (v1_ - v0_) / (d * d) * 60.0 * x * (1.0 - x) * (1.0 - 2.0 * x);
  }

 private:
  double clamp(double t) const { return std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0); }
  double t0_, t1_, v0_, v1_;
};

/// Angle of a hub spun up smoothly to the rate ω in time T (Simo & Vu-Quoc 1986):
/// θ = ω/T [t²/2 + (T/2π)²(cos(2πt/T) − 1)] for t < T, ω(t − T/2) after; θ̇ and θ̈ continuous.
class SpinUp final : public TimeFunction {
 public:
  SpinUp(double omega, double T) : w_(omega), T_(T) {}
  double value(double t) const override {
    if (t <= 0.0) return 0.0;
    if (t >= T_) return w_ * (t - T_ / 2.0);
    const double c = T_ / (2.0 * kPi);
    return w_ / T_ * (t * t / 2.0 + c * c * (std::cos(t / c) - 1.0));
  }
  double derivative(double t) const override {
    if (t <= 0.0) return 0.0;
    if (t >= T_) return w_;
    const double c = T_ / (2.0 * kPi);
    return w_ / T_ * (t - c * std::sin(t / c));
  }
  double second_derivative(double t) const override {
    if (t <= 0.0 || t >= T_) return 0.0;
    const double c = T_ / (2.0 * kPi);
    return w_ / T_ * (1.0 - std::cos(t / c));
  }

 private:
  static constexpr double kPi = 3.14159265358979323846;
  double w_, T_;
};

/// f(t) = offset + rate · t.
class Linear final : public TimeFunction {
 public:
  Linear(double rate, double offset) : k_(rate), c_(offset) {}
  double value(double t) const override { return c_ + k_ * t; }
  double derivative(double) const override { return k_; }
  double second_derivative(double) const override { return 0.0; }

 private:
  double k_, c_;
};

class Sine final : public TimeFunction {
 public:
  Sine(double a, double f, double p, double o) : a_(a), w_(2.0 * M_PI * f), p_(p), o_(o) {}
  double value(double t) const override { return o_ + a_ * std::sin(w_ * t + p_); }
  double derivative(double t) const override { return a_ * w_ * std::cos(w_ * t + p_); }
  double second_derivative(double t) const override { return -a_ * w_ * w_ * std::sin(w_ * t + p_); }

 private:
  double a_, w_, p_, o_;
};

class Table final : public TimeFunction {
 public:
  Table(std::vector<double> t, std::vector<double> v) : t_(std::move(t)), v_(std::move(v)) {}
  double value(double t) const override {
    if (t <= t_.front()) return v_.front();
    if (t >= t_.back()) return v_.back();
    const size_t i = segment(t);
    return v_[i] + (v_[i + 1] - v_[i]) * (t - t_[i]) / (t_[i + 1] - t_[i]);
  }
  double derivative(double t) const override {
    if (t <= t_.front() || t >= t_.back()) return 0.0;
    const size_t i = segment(t);
    return (v_[i + 1] - v_[i]) / (t_[i + 1] - t_[i]);
  }
  double second_derivative(double) const override { return 0.0; }

 private:
  size_t segment(double t) const {
    return static_cast<size_t>(std::upper_bound(t_.begin(), t_.end(), t) - t_.begin()) - 1;
  }
  std::vector<double> t_, v_;
};

}  // namespace

TimeFunctionPtr make_constant(double c) { return std::make_shared<Constant>(c); }
TimeFunctionPtr make_ramp(double t0, double t1, double v0, double v1) {
  if (!(t1 > t0)) throw std::invalid_argument("ramp needs t1 > t0");
  return std::make_shared<Ramp>(t0, t1, v0, v1);
}
TimeFunctionPtr make_smooth_step(double t0, double t1, double v0, double v1) {
  if (!(t1 > t0)) throw std::invalid_argument("smooth_step needs t1 > t0");
  return std::make_shared<SmoothStep>(t0, t1, v0, v1);
}
TimeFunctionPtr make_spin_up(double omega, double T) {
  if (!(T > 0.0)) throw std::invalid_argument("spin_up: the spin-up time must be positive");
  return std::make_shared<SpinUp>(omega, T);
}
TimeFunctionPtr make_linear(double rate, double offset) { return std::make_shared<Linear>(rate, offset); }
TimeFunctionPtr make_sine(double a, double f, double p, double o) { return std::make_shared<Sine>(a, f, p, o); }
TimeFunctionPtr make_scaled(TimeFunctionPtr f, double c) { return std::make_shared<Scaled>(std::move(f), c); }
TimeFunctionPtr make_table(std::vector<double> t, std::vector<double> v) {
  if (t.size() < 2 || t.size() != v.size())
    throw std::invalid_argument("table needs t and values of equal length >= 2");
  for (size_t i = 1; i < t.size(); ++i)
    if (!(t[i] > t[i - 1])) throw std::invalid_argument("table times must increase strictly");
  return std::make_shared<Table>(std::move(t), std::move(v));
}

}  // namespace alphaflex
