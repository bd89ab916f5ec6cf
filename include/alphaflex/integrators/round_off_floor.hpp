#pragma once
// The round-off floor of the index-3 formulation (Arnold & Brüls 2007, Sec. 3.3): positions carry
// round-off ε‖q‖, and the Newton update q̈ += β'Δq, λ += β'Δλ multiplies it by β' ~ 1/(βh²), so
// accelerations and multipliers (joint reactions) are known only to about ε‖q‖β' however well
// Newton converges. Positions are not amplified, velocities only by γ' ~ γ/(βh).
#include <string>

#include "alphaflex/integrators/alpha_parameters.hpp"

namespace alphaflex {

/// ε‖q‖β'(h): the round-off floor of q̈ (and of λ, in the units of M q̈) at step size h.
double round_off_floor(const AlphaParameters& p, double h, double q_norm);

/// The warning a run prints after its steps when that floor exceeds 1e-3 of `acc_scale`, the
/// largest |q̈| the run had at its start and its end (the accelerations the reactions balance); an
/// empty string otherwise. It names what is affected (accelerations, reactions) and what is not
/// (positions, velocities), and the h from which the floor is below 1e-3 of the accelerations.
std::string round_off_floor_warning(const AlphaParameters& p, double h, double q_norm, double acc_scale);

}  // namespace alphaflex
