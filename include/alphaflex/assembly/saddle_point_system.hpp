#pragma once
// Assembly of the saddle-point system of a constrained mechanical model into PETSc objects:
//
//     S = [ s·(c_M M + c_C C + c_K (K + K_Φ) + c_I I)   s·μ·Φ_qᵀ ]     r = [ s·(Σ_e r_e + Φ_qᵀ λ) ]
//         [ Φ_q                                           0     ]         [ constraint rows      ]
//
// with the row scale s and the multiplier scale μ (the unknown of the multiplier rows is Δλ/μ).
// The integrator chooses the coefficients; this module knows nothing of time integration nor of
// what the elements are. Each rank evaluates the elements and joints of its Subdomain (the ones it
// owns) on its local state and adds into MATAIJ/VECMPI; rows of ghost nodes travel to their owner
// through PETSc's stash. The preallocation is exact on any number of ranks: one pass of the
// pattern through a MATPREALLOCATOR (which collects the off-rank rows too) before the first
// assembly. Solutions come back to each rank's owned and ghost unknowns by one VecScatter.
#include <petscmat.h>
#include <petscvec.h>

#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

struct AssemblyCoefficients {
  double mass = 0.0, damping = 0.0, stiffness = 0.0, identity = 0.0;
  double row_scale = 1.0;         ///< s: multiplies every dynamic row (Bottasso scaling: βh²)
  double multiplier_scale = 1.0;  ///< μ: Δλ = μ × (solution component); Bottasso: 1/(βh²)
  /// Lie-group step (Brüls, Cardona & Arnold 2012): the increment x = hΔq of the step in model
  /// order. When set, the position derivatives K + K_Φ and Φ_q are multiplied on the right by the
  /// tangent operator T(x) of each group node, since q_{n+1} = q_n ∘ exp(x). Identity on vector
  /// spaces, where nothing is done.
  const Eigen::VectorXd* increment = nullptr;
  double load_factor = 1.0;       ///< passed to the elements (quasi-static load stepping)
};

/// What the multiplier rows of the residual contain (and whether element residuals are added).
enum class ConstraintRows {
  Position,      ///< Φ(q, t); elements left out (projection of q0 onto Φ = 0)
  Velocity,      ///< Φ_q q̇ + Φ_t; elements left out (projection of q̇0)
  Acceleration,  ///< Φ_q q̈ + (Φ_q q̇)_q q̇ + …; elements in (consistent q̈0, λ0)
  Dynamic,       ///< Φ(q, t); elements in (generalized-α step)
};

/// Residual and iterate split by kind, in the subdomain's local order (owned and ghost node
/// coordinates, then the local multipliers).
struct ModelVector {
  Eigen::VectorXd dofs, multipliers;
};

class SaddlePointSystem {
 public:
  explicit SaddlePointSystem(const Subdomain& subdomain);
  ~SaddlePointSystem();
  SaddlePointSystem(const SaddlePointSystem&) = delete;
  SaddlePointSystem& operator=(const SaddlePointSystem&) = delete;

  /// Assembles r (always) and S (if `matrix`) at state `s`. An exception from an element or a
  /// joint on any rank becomes a SolverError with that message on every rank (no rank hangs).
  PetscErrorCode assemble(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows, bool matrix);

  Mat matrix() const { return S_; }
  Vec residual() const { return r_; }
  /// A vector with the layout of the residual (for solutions).
  Vec solution() const { return x_; }

  /// The entries of a distributed vector with this layout that this rank's subdomain holds (its
  /// owned and ghost unknowns), in local order.
  PetscErrorCode to_model(Vec v, ModelVector& out);

  const Subdomain& subdomain() const { return sub_; }
  const DofMap& dof_map() const { return sub_.dof_map(); }
  /// The local model (this rank's subdomain).
  const Model& model() const { return model_; }

 private:
  PetscErrorCode preallocate();
  PetscErrorCode add_local_contributions(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows,
                                         bool matrix);
  PetscErrorCode raise_if_any_rank_failed(const std::string& local_error, bool configuration);

  const Subdomain& sub_;
  const Model& model_;
  MPI_Comm comm_;
  Mat S_ = nullptr;
  Vec r_ = nullptr, x_ = nullptr, local_ = nullptr;
  VecScatter to_local_ = nullptr;
  // Cached per element / joint: local unknowns and their PETSc indices.
  std::vector<std::vector<int>> elem_dofs_, elem_rows_, con_dofs_, con_rows_, con_mults_;
  std::vector<std::vector<int>> elem_confs_, con_confs_;  // configuration indices
};

}  // namespace alphaflex
