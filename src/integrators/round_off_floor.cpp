#include "alphaflex/integrators/round_off_floor.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/core/petsc_error.hpp"

namespace alphaflex {

namespace {
/// Relative noise of accelerations and reactions a run warns about (0.1 %).
constexpr double kRelativeFloor = 1e-3;
constexpr double kEps = std::numeric_limits<double>::epsilon();
}  // namespace

double round_off_floor(const AlphaParameters& p, double h, double q_norm) {
  return kEps * std::max(q_norm, 1e-300) * p.beta_prime(h);
}

std::string round_off_floor_warning(const AlphaParameters& p, double h, double q_norm, double acc_scale) {
  const double floor = round_off_floor(p, h, q_norm);
  if (!(floor > kRelativeFloor * acc_scale)) return {};
  std::ostringstream os;
  os.precision(3);
  os << "at h = " << h << " s the accelerations may carry round-off of up to " << floor
     << " in q̈ units, the estimate ε‖q‖/(βh²) of the index-3 formulation (docs/performance.md)";
  if (acc_scale > 0.0) {
    // floor ∝ 1/h²: the h at which it is kRelativeFloor of the accelerations.
    const double h_ok = h * std::sqrt(floor / (kRelativeFloor * acc_scale));
    os << ", " << 100.0 * floor / acc_scale << " % of the largest |q̈| at the start and the end of the run (" << acc_scale
       << "); positions and velocities are not affected. For accelerations to 0.1 %, use h >= " << h_ok << " s";
  } else {
    os << " (q̈ = 0 at the start and the end of the run); positions and velocities are not affected";
  }
  os << ".";
  return os.str();
}

double reaction_round_off(const AlphaParameters& p, double h, double q_norm, const ReactionScale& r) {
  return kEps * std::max(q_norm, 1e-300) * (p.beta_prime(h) * r.mass + r.stiffness);
}

std::string reaction_round_off_warning(const AlphaParameters& p, double h, double q_norm,
                                       const std::vector<ReactionScale>& joints) {
  const ReactionScale* worst = nullptr;
  double share = 0.0;
  for (const ReactionScale& r : joints) {
    if (!(r.reaction > 0.0)) continue;  // a joint that carried no load: no size to compare with
    const double s = reaction_round_off(p, h, q_norm, r) / r.reaction;
    if (s > share) share = s, worst = &r;
  }
  if (!worst || !(share > kRelativeFloor)) return {};
  const double q = kEps * std::max(q_norm, 1e-300);
  std::ostringstream os;
  os.precision(3);
  os << "at h = " << h << " s the reactions of joint '" << worst->joint << "' may carry round-off of "
     << 100.0 * share << " % of their largest |λ| over the run (" << worst->reaction
     << "): the estimate ε‖q‖(β'm + b) of the index-3 formulation, with m and b the largest mass and "
        "stiffness entries at the joint's coordinates (docs/performance.md); positions and velocities are "
        "not affected.";
  // β'(h) m + b = kRelativeFloor Λ / (ε‖q‖) with β' ∝ 1/h² (b taken at this h: γ'C changes little).
  const double beta_needed = (kRelativeFloor * worst->reaction / q - worst->stiffness) / worst->mass;
  if (worst->mass > 0.0 && beta_needed > 0.0)
    os << " For this joint's reactions to 0.1 %, use h >= " << h * std::sqrt(p.beta_prime(h) / beta_needed) << " s.";
  else
    os << " No step size brings it below 0.1 %: the stiffness at the joint alone gives ε‖q‖b = "
       << q * worst->stiffness << ".";
  return os.str();
}

std::vector<ReactionScale> reaction_scales(SaddlePointSystem& sys, const MechanicalState& s, const AlphaParameters& p,
                                           double h, const Eigen::VectorXd& max_lambda) {
  // diag(M), then diag(γ'C + K), each gathered to this rank's unknowns (owned and ghost).
  auto diagonal = [&](const AssemblyCoefficients& c) {
    check_petsc(sys.assemble(s, c, ConstraintRows::Dynamic, true), "assembly for the round-off estimate");
    check_petsc(MatGetDiagonal(sys.matrix(), sys.solution()), "diagonal for the round-off estimate");
    ModelVector d;
    check_petsc(sys.to_model(sys.solution(), d), "diagonal gather for the round-off estimate");
    return d.dofs;
  };
  AssemblyCoefficients mass, rest;
  mass.mass = 1.0;
  rest.damping = p.gamma_prime(h);
  rest.stiffness = 1.0;
  const Eigen::VectorXd m = diagonal(mass), b = diagonal(rest);
  const Model& model = sys.model();
  std::vector<ReactionScale> out;
  for (size_t c = 0; c < model.constraints().size(); ++c) {
    const Constraint& joint = *model.constraints()[c];
    ReactionScale r;
    r.joint = joint.name();
    for (int i : model.dofs_of(joint.nodes())) {
      r.mass = std::max(r.mass, std::abs(m[i]));
      r.stiffness = std::max(r.stiffness, std::abs(b[i]));
    }
    const int first = model.first_multiplier(static_cast<int>(c));
    for (int k = 0; k < joint.size(); ++k)
      if (first + k < max_lambda.size()) r.reaction = std::max(r.reaction, max_lambda[first + k]);
    out.push_back(r);
  }
  return out;
}

}  // namespace alphaflex
