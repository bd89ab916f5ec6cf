#pragma once
// Forward-mode automatic differentiation for element and joint kernels (Eigen's AutoDiffScalar).
// A kernel written once as a template on the scalar gives its exact first derivatives (AD1) and,
// nested, its exact second derivatives (AD2): residuals are gradients of energies, tangents are
// derivatives of residuals, and nothing is differentiated by hand or by finite differences. The
// derivative vectors have a fixed capacity (kMaxVariables), so nothing is allocated on the heap.
#include <Eigen/Dense>
// After Eigen/Dense: the AutoDiff module needs Eigen's core declared first.
#include <unsupported/Eigen/AutoDiff>

namespace alphaflex::ad {

/// Largest number of independent variables of one kernel: two nodes with 6 motions each, plus time.
constexpr int kMaxVariables = 13;

using Derivatives1 = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxVariables, 1>;
using AD1 = Eigen::AutoDiffScalar<Derivatives1>;
using Derivatives2 = Eigen::Matrix<AD1, Eigen::Dynamic, 1, 0, kMaxVariables, 1>;
using AD2 = Eigen::AutoDiffScalar<Derivatives2>;

/// Plain value of a (possibly nested) scalar.
inline double value(double x) { return x; }
inline double value(const AD1& x) { return x.value(); }
inline double value(const AD2& x) { return x.value().value(); }

/// Independent variable i of n with value v (AD1).
inline AD1 variable1(double v, int n, int i) { return AD1(v, n, i); }

/// A constant AD1 with n (zero) derivatives.
inline AD1 constant1(double v, int n) { return AD1(v, Derivatives1::Zero(n)); }

/// AD2 variable for the outer derivative (index i of n_outer), inner derivatives zero (n_inner).
inline AD2 outer_variable(double v, int n_outer, int i, int n_inner) {
  Derivatives2 d(n_outer);
  for (int k = 0; k < n_outer; ++k) d[k] = constant1(k == i ? 1.0 : 0.0, n_inner);
  return AD2(constant1(v, n_inner), d);
}

/// AD2 variable for the inner derivative (index j of n_inner), outer derivatives zero (n_outer).
inline AD2 inner_variable(double v, int n_outer, int j, int n_inner) {
  Derivatives2 d(n_outer);
  for (int k = 0; k < n_outer; ++k) d[k] = constant1(0.0, n_inner);
  return AD2(variable1(v, n_inner, j), d);
}

/// A constant AD2.
inline AD2 constant2(double v, int n_outer, int n_inner) {
  Derivatives2 d(n_outer);
  for (int k = 0; k < n_outer; ++k) d[k] = constant1(0.0, n_inner);
  return AD2(constant1(v, n_inner), d);
}

/// ∂x/∂(inner j), ∂²x/∂(outer i)∂(inner j) of an AD2 value.
inline double inner_derivative(const AD2& x, int j) { return x.value().derivatives()[j]; }
inline double mixed_derivative(const AD2& x, int i, int j) { return x.derivatives()[i].derivatives()[j]; }

}  // namespace alphaflex::ad
