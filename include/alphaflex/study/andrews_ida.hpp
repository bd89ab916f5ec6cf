#pragma once
// A classical stiff DAE solver on Andrews' squeezing mechanism, for the work–precision chart:
// SUNDIALS IDA (variable-order, variable-step BDF, Hindmarsh et al. 2005) on the test set's 7
// relative coordinates (shared/andrews.md §1.3) in the stabilized index-2 form of Gear, Gupta &
// Leimkuhler (1985):
//     q' = v − G(q)ᵀμ,   M(q) v' = f(q, v) − G(q)ᵀλ,   0 = g(q),   0 = G(q) v,
// with the multipliers λ, μ algebraic and left out of IDA's error test (IDASetSuppressAlg, as
// recommended for index 2), the Jacobian by IDA's difference quotients and a dense LU — how the
// solver is used out of the box. μ vanishes on exact solutions (it only keeps q on g = 0).
#include <string>
#include <vector>

namespace alphaflex::study {

struct PeerResult {
  std::string method;            ///< e.g. "IDA (GGL index 2)"
  double rtol = 0.0, atol = 0.0; ///< tolerances given to the solver
  bool ok = false;
  std::string failure;           ///< the solver's message when !ok
  double cpu = 0.0;              ///< process CPU seconds of the solve (set-up included)
  long steps = 0, residual_evals = 0, jacobian_evals = 0, nonlinear_iterations = 0, error_test_failures = 0;
  /// Values at t_end named like the sensors of inputs/andrews.yaml: the test set's relative angles
  /// beta, Theta, gamma, Phi, delta, Omega, epsilon (rad) and its multipliers lambda1..lambda6 (N).
  std::vector<std::string> names;
  std::vector<double> values;
};

/// Integrates Andrews' mechanism from the consistent state of andrews.md §1.4 (at rest) to t_end
/// with IDA at the given tolerances (relative, absolute). Never throws on solver failure: the
/// result says why.
PeerResult andrews_ida(double rtol, double atol, double t_end = 0.03);

}  // namespace alphaflex::study
