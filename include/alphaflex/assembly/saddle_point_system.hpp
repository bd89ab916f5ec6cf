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
//
// Matrix entries go straight into the CSR value arrays of this rank's rows (the diagonal and
// off-diagonal SeqAIJ parts of MATMPIAIJ, or the SeqAIJ itself): the position of every entry of
// every element and joint block is found once, after the preallocation, so an assembly does no
// search and no MatSetValues call (whose column search per entry cost ~15 % of an assembly).
// Rows owned by another rank (a ghost node's) still go through MatSetValues and PETSc's stash.
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

  /// Assembles into the residual vector r = s_r c_m M(q) w in the coordinate rows (s_r = c.row_scale,
  /// c_m = c.mass) and 0 in the multiplier rows: the difference of the residuals at q̈ + c_m w and q̈,
  /// computed without the forces that cancel in it (Element::mass_action; an element without it is
  /// evaluated at both). `w` in the local order of s.qdd (owned and ghost coordinates). The
  /// filtered error estimate's right-hand side (driver/error_filter.hpp). Collective.
  PetscErrorCode assemble_mass_action(const MechanicalState& s, const AssemblyCoefficients& c, const Eigen::VectorXd& w);

  Mat matrix() const { return S_; }
  Vec residual() const { return r_; }
  /// A vector with the layout of the residual (for solutions).
  Vec solution() const { return x_; }

  /// The entries of a distributed vector with this layout that this rank's subdomain holds (its
  /// owned and ghost unknowns), in local order.
  PetscErrorCode to_model(Vec v, ModelVector& out);

  /// Memory of the iteration matrix on this rank (its CSR arrays, MatGetInfo), of the indices MUMPS
  /// receives and of the assembly's entry maps, in MB: the matrix part of the run's memory estimate.
  double matrix_megabytes() const { return matrix_mb_; }

  const Subdomain& subdomain() const { return sub_; }
  const DofMap& dof_map() const { return sub_.dof_map(); }
  /// The local model (this rank's subdomain).
  const Model& model() const { return model_; }

 private:
  PetscErrorCode preallocate();
  /// Finds, for every block the matrix receives, the position of each entry in this rank's CSR
  /// arrays: ≥ 0 in the diagonal part, ≤ −2 in the off-diagonal part (−2 − position), −1 if
  /// another rank owns the row.
  PetscErrorCode build_entry_maps();
  /// Adds value(i, j) for every entry of the block rows × cols whose positions are `pos`.
  template <class Value>
  PetscErrorCode add_mapped(const std::vector<PetscInt>& pos, const std::vector<int>& rows, const std::vector<int>& cols,
                            const Value& value);
  PetscErrorCode add_local_contributions(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows,
                                         bool matrix);
  PetscErrorCode add_mass_action(const MechanicalState& s, const AssemblyCoefficients& c, const Eigen::VectorXd& w);
  /// Runs `add` (which adds this rank's part), agrees on failure over all ranks (an exception on one
  /// rank is thrown on every rank), then assembles r (and S if `matrix`).
  template <class Add>
  PetscErrorCode assemble_guarded(bool matrix, const Add& add);
  /// What a failure of one rank becomes on every rank: kind 0 SolverError, 1 ConfigurationError,
  /// 2 MemoryError.
  enum class FailureKind { Solver = 0, Configuration = 1, Memory = 2 };
  PetscErrorCode raise_if_any_rank_failed(const std::string& local_error, FailureKind kind);
  /// An upper bound of the memory the preallocation takes at its peak on this rank (bytes).
  double preallocation_bytes() const;

  const Subdomain& sub_;
  const Model& model_;
  MPI_Comm comm_;
  Mat S_ = nullptr;
  double matrix_mb_ = 0.0;
  Vec r_ = nullptr, x_ = nullptr, local_ = nullptr;
  VecScatter to_local_ = nullptr;
  // Cached per element / joint: local unknowns and their PETSc indices.
  std::vector<std::vector<int>> elem_dofs_, elem_rows_, con_dofs_, con_rows_, con_mults_;
  std::vector<std::vector<int>> elem_confs_, con_confs_;  // configuration indices
  // Entry positions (build_entry_maps) of: each element's block; each joint's blocks q×q, q×λ,
  // λ×q and λ×λ (its diagonal); the diagonal of every owned node coordinate.
  std::vector<std::vector<PetscInt>> elem_pos_, con_qq_pos_, con_ql_pos_, con_lq_pos_, con_ll_pos_;
  std::vector<PetscInt> dof_diag_pos_;
  // This rank's parts of S (borrowed from S_, not destroyed here); their value arrays are held
  // during an assembly only.
  Mat diag_ = nullptr, offdiag_ = nullptr;
  PetscScalar *d_a_ = nullptr, *o_a_ = nullptr;
  std::vector<PetscScalar> row_buffer_;
  // Per-assembly work arrays (no allocation per element once sized).
  LocalState ls_;
  LocalResidual lr_;
  Eigen::VectorXd phi_, extra_, q_con_, v_con_, lam_con_, rc_, rq_, w_e_, mw_e_, r_shift_;
  Eigen::MatrixXd phi_q_, kc_;
};

}  // namespace alphaflex
