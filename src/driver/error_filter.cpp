#include "alphaflex/driver/error_filter.hpp"

namespace alphaflex {

Eigen::VectorXd ErrorFilter::apply(const MechanicalState& s, const Eigen::VectorXd& e, double h, const Eigen::VectorXd& increment,
                                   int applications, PhaseTimes& times) {
  // The coefficients of the step's residual and S_t (GeneralizedAlpha::step_coefficients); the loads
  // cancel in the difference, the load factor is kept only so that the two residuals are those of
  // the step.
  const AssemblyCoefficients c = integrator_.step_coefficients(h, increment);
  lin_.times() = PhaseTimes();
  const ModelVector x0 = lin_.solve_with_last_factorization(s, c, ConstraintRows::Dynamic, nullptr);
  MechanicalState moved = s;
  Eigen::VectorXd w = e;
  for (int k = 0; k < applications; ++k) {
    moved.qdd = s.qdd + c.mass * w;
    const ModelVector x1 = lin_.solve_with_last_factorization(moved, c, ConstraintRows::Dynamic, nullptr);
    w = x1.dofs - x0.dofs;
  }
  times.assembly += lin_.times().assembly;
  times.solve += lin_.times().solve;
  return w;
}

}  // namespace alphaflex
