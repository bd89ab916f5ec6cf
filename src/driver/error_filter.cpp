#include "alphaflex/driver/error_filter.hpp"

namespace alphaflex {

Eigen::VectorXd ErrorFilter::apply(const MechanicalState& s, const Eigen::VectorXd& e, double h, const Eigen::VectorXd& increment,
                                   int applications, PhaseTimes& times) {
  // The coefficients of the step's residual and S_t (GeneralizedAlpha::step_coefficients); the loads
  // cancel in the difference, the load factor is kept only so that the two residuals are those of
  // the step.
  const AssemblyCoefficients c = integrator_.step_coefficients(h, increment);
  lin_.times() = PhaseTimes();
  // W w = S_t⁻¹ β'M w: the residuals at q̈ + β'w and q̈ differ by exactly s_r β'M w (the residual is
  // affine in q̈), which the elements give without the forces that cancel (Element::mass_action).
  Eigen::VectorXd w = e;
  for (int k = 0; k < applications; ++k) w = lin_.solve_mass_action_with_last_factorization(s, c, w).dofs;
  times.assembly += lin_.times().assembly;
  times.solve += lin_.times().solve;
  return w;
}

}  // namespace alphaflex
