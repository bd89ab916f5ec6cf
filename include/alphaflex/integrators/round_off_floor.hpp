#pragma once
// The round-off floor of the index-3 formulation (Arnold & Brüls 2007, Sec. 3.3): positions carry
// round-off ε‖q‖, and the Newton update q̈ += β'Δq, λ += β'Δλ multiplies it by β' ~ 1/(βh²), so
// accelerations and multipliers (joint reactions) are known only to about ε‖q‖β' however well
// Newton converges. Positions are not amplified, velocities only by γ' ~ γ/(βh).
//
// Per reaction (issue 22): a position error δq at the coordinates a joint acts on unbalances the
// equations of motion by S_t δq, S_t = β'M + γ'C + K (the iteration matrix's dynamic block), and the
// joint's multiplier takes it up: its round-off is about ε‖q‖ (β' m_j + b_j), where m_j and b_j are
// the largest diagonal entries of M and of γ'C + K at the joint's coordinates. That is compared with
// the reaction's own size (its largest |λ| over the run), not with the accelerations.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/model/state.hpp"

namespace alphaflex {

class SaddlePointSystem;

/// ε‖q‖β'(h): the round-off floor of q̈ (and of λ, in the units of M q̈) at step size h.
double round_off_floor(const AlphaParameters& p, double h, double q_norm);

/// The warning a run prints after its steps when that floor exceeds 1e-3 of `acc_scale`, the
/// largest |q̈| the run had at its start and its end (the accelerations the reactions balance); an
/// empty string otherwise. It names what is affected (accelerations, reactions) and what is not
/// (positions, velocities), and the h from which the floor is below 1e-3 of the accelerations.
/// Used for runs without joints; runs with joints use reaction_round_off_warning.
std::string round_off_floor_warning(const AlphaParameters& p, double h, double q_norm, double acc_scale);

/// One joint's scales for its reactions' round-off (see the file comment).
struct ReactionScale {
  std::string joint;       ///< the joint's name
  double mass = 0.0;       ///< m_j: largest M_ii at the joint's coordinates (kg, kg·m²)
  double stiffness = 0.0;  ///< b_j: largest |γ'C_ii + K_ii| there at the run's h (N/m, N·m/rad)
  double reaction = 0.0;   ///< Λ_j: largest |λ| of the joint's multipliers over the run
};

/// ε‖q‖(β'(h) m_j + b_j): the estimated round-off of joint j's multipliers at step size h.
double reaction_round_off(const AlphaParameters& p, double h, double q_norm, const ReactionScale& r);

/// The warning for the joint whose estimate is the largest share of its own reaction, when that
/// share exceeds 1e-3; empty otherwise (also when no joint has a reaction > 0: nothing to compare).
/// It gives the share, the joint, and the h from which the share is below 1e-3 (or says that no h
/// gets there when b_j alone exceeds it).
std::string reaction_round_off_warning(const AlphaParameters& p, double h, double q_norm,
                                       const std::vector<ReactionScale>& joints);

/// The scales of this rank's joints at state `s`, from two assemblies of `sys` (M; γ'C + K at h),
/// with `max_lambda` the largest |λ_k| over the run of each local multiplier. Collective.
std::vector<ReactionScale> reaction_scales(SaddlePointSystem& sys, const MechanicalState& s, const AlphaParameters& p,
                                           double h, const Eigen::VectorXd& max_lambda);

}  // namespace alphaflex
