#pragma once
// Modal analysis of the linearized constrained system (docs/theory/modes.md, docs/modes.md).
//
// About a state (q, q̇, q̈, λ) the assembly gives K (with the joints' geometric stiffness K_Φ),
// C and M of r = M q̈ − g and the constraint Jacobian Φ_q. The constrained eigenproblem is solved
// in saddle-point form, without any null-space basis:
//
//   undamped (C = 0):  [K  Φ_qᵀ] x = ω² [M 0] x          (SLEPc EPS, generalized non-Hermitian)
//                      [Φ_q  0 ]        [0 0]
//   damped/gyroscopic: ([K Φ_qᵀ; Φ_q 0] + s [C 0; 0 0] + s² [M 0; 0 0]) x = 0   (SLEPc PEP, TOAR)
//
// with shift-and-invert (MUMPS LU of the pencil at the shift): the multiplier block carries only
// infinite eigenvalues, which the shift-and-invert maps to 0 and never returns near a finite
// shift, so no spurious constraint mode appears. Parallel over the ranks of the Subdomain the
// assembly already uses; -eps_*, -pep_* and -st_* options pass through (EPSSetFromOptions).
#include <petscmat.h>

#include <string>
#include <vector>

#include "alphaflex/assembly/saddle_point_system.hpp"

namespace alphaflex {

/// The scene's `modes:` keys (docs/input.md, "Modal analysis").
struct ModalOptions {
  int count = 0;        ///< how many modes (the lowest, or the nearest the shift); 0: 10, or all if fewer
  double below = 0.0;   ///< Hz; > 0: report only the modes below this frequency
  double shift = 0.0;   ///< Hz; > 0: the modes nearest this frequency (undamped problems)
};

enum class ModeKind {
  Elastic,     ///< ω > 0 (undamped), or an oscillating pair of the damped problem
  RigidBody,   ///< zero frequency: a motion the joints and stiffness leave free
  Overdamped,  ///< damped problem: a real negative eigenvalue (no oscillation)
  Unstable,    ///< ω² < 0 (divergence) or Re s > 0 (flutter): the state is not a stable equilibrium
};
const char* to_string(ModeKind kind);

struct Mode {
  /// Undamped: ω² (rad²/s²) in `re`, `im` = 0. Damped: the eigenvalue s = re + i·im (1/s) with
  /// im ≥ 0 (its conjugate is the same mode).
  double re = 0.0, im = 0.0;
  double frequency = 0.0;      ///< Hz: √ω²/2π (undamped), |Im s|/2π (damped: the damped frequency)
  double natural_frequency = 0.0;  ///< Hz: |s|/2π (damped), = frequency (undamped)
  double damping_ratio = 0.0;  ///< −Re s/|s| (0 in the undamped problem)
  ModeKind kind = ModeKind::Elastic;
  /// Generalized mass x̄ᵀ M x (kg, or kg·m² for a pure rotation mode) of the shape normalized to a
  /// largest translation of 1 (or a largest rotation of 1 rad when no node translates).
  double modal_mass = 0.0;
  double largest_rotation = 0.0;  ///< rad: the largest |rotation| of the normalized shape
  std::vector<double> kinetic_share, strain_share;  ///< per part (ModalResult::parts), sum 1 (or all 0)
  int dominant_part = -1;                           ///< the part of the largest kinetic share
  std::string whirl;  ///< damped problem with spinning frames: "forward" or "backward"; else empty
  /// The normalized shape on this rank's owned and ghost coordinates (local order); `shape_im` is
  /// zero in the undamped problem.
  Eigen::VectorXd shape_re, shape_im;
};

struct ModalResult {
  bool damped = false;
  std::vector<std::string> parts;  ///< beam/shell blocks, bodies, joints, loads (element name up to '[')
  std::vector<Mode> modes;         ///< by increasing frequency (rigid-body modes first)
  int rigid_body_modes = 0;
  int requested = 0, converged = 0;
  double target = 0.0;             ///< the shift used: ω² (rad²/s², undamped) or s (1/s, damped)
  double spectral_scale = 0.0;     ///< max_i K_ii / max_i M_ii (rad²/s²): the scale of "zero"
  double model_size = 0.0;         ///< m: the diagonal of the nodes' bounding box
  int iterations = 0;
  std::vector<std::string> warnings;
};

/// The modes of the model of `system` linearized about the local state `state` (this rank's
/// subdomain), loads multiplied by `load_factor`. Collective. Throws InputError (more modes than
/// degrees of freedom, a coordinate that neither mass, stiffness nor a joint holds) or SolverError
/// (no convergence: the modes that did converge are listed).
ModalResult compute_modes(SaddlePointSystem& system, const MechanicalState& state, double load_factor,
                          const ModalOptions& options);

/// The state q ∘ exp(a·(x_re cos φ − x_im sin φ)) of the local model: mode shapes animated on the
/// model itself (the results writer draws it like any state).
MechanicalState displaced_state(const Model& model, const MechanicalState& state, const Mode& mode, double amplitude,
                                double phase);

}  // namespace alphaflex
