#pragma once
// Conditioning of the iteration matrix S_t of a generalized-α step (Arnold & Brüls 2007, eq. 7):
//     S_t = [[M β' + C γ' + K, Φ_qᵀ], [Φ_q, 0]],   β' = (1 − α_m)/(h²β(1 − α_f)),  γ' = γ/(hβ),
// as alphaflex assembles it, with or without the scaling of Bottasso, Dopico & Trainelli (2006)
// (dynamic rows × βh², multiplier unknown βh²Δλ). Unscaled, the mass block grows like h⁻² while
// Φ_q stays O(1), so the 2-norm condition number grows like h⁻⁴ (the Schur complement
// Φ_q (M β')⁻¹ Φ_qᵀ is O(h²)); scaled, every block is O(1).
#include <mpi.h>

#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/model/model.hpp"

namespace alphaflex::study {

struct ConditionNumbers {
  /// ‖S_t‖₂ ‖S_t⁻¹‖₂ from dense SVDs on rank 0, the inverse formed through the scaled matrix so that
  /// it stays accurate beyond 1/ε (NaN above `dense_limit` unknowns).
  double two_norm = 0.0;
  /// MUMPS' error analysis (ICNTL(11) = 1): RINFOG(10), RINFOG(11), the condition numbers of
  /// Arioli, Demmel & Duff (1989) for componentwise perturbations. They are invariant under row
  /// scaling, so they see less of the Bottasso scaling than the 2-norm number does.
  double mumps_cond1 = 0.0, mumps_cond2 = 0.0;
  int unknowns = 0;
};

/// Assembles S_t at state `s` for a step of size h with parameters `p` (scaled or not) and
/// returns its condition numbers; collective over `comm`, the result on every rank. On Lie-group
/// nodes the tangent operator is taken at a zero increment (T(0) = I): the estimate of a step
/// from `s`. Throws SolverError if assembly or factorization fails.
ConditionNumbers iteration_matrix_condition(const Model& model, const MechanicalState& s, const AlphaParameters& p,
                                            double h, bool scaling, MPI_Comm comm, int dense_limit = 2000);

}  // namespace alphaflex::study
