#pragma once
// Why is the iteration matrix singular? Two causes a user can act on, each named by joint or node
// instead of a MUMPS error code:
//  - redundant constraints: Φ_q has dependent rows (a joint repeats what others impose);
//  - unconstrained massless motion: a direction in which neither the mass matrix nor any joint
//    acts (rank [M; Φ_q] < n), e.g. a massless point attached by too few joints.
// Every rank computes the same answer. Whether Φ_q has full rank is decided by a sparse
// rank-revealing QR (any size); naming the redundant joints and the massless search are dense
// (Φ_q up to 2e7 entries; [M; Φ_q] up to 2000 coordinates).
#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"
#include "alphaflex/partition/subdomain.hpp"

namespace alphaflex {

struct RedundantEquation {
  int constraint = -1;          ///< joint index
  int equation = -1;            ///< 0-based equation of that joint
  std::vector<int> depends_on;  ///< joints whose equations it is a combination of
};

/// Equations of Φ_q(q, t) that are linear combinations of earlier ones (relative tolerance `tol`).
std::vector<RedundantEquation> find_redundant_constraints(const Model& model, const MechanicalState& s,
                                                          double tol = 1e-10);

/// max |Φ(q, t)| over all joint equations (m or rad).
double constraint_violation(const Model& model, const MechanicalState& s);

/// Human-readable diagnosis of a singular saddle-point matrix at state s; empty if nothing was
/// found (above 2000 coordinates the dense search for massless motion is skipped: a note says so
/// next to other findings).
std::string diagnose_singular_system(const Model& model, const MechanicalState& s);

// The same on a distributed model, from each rank's local state (collective; every rank gets the
// same answer, in the global model's numbering and names). The checks need the whole Jacobian, so
// the state is gathered (O(model) per rank): they run at the start and after a failure only.
std::vector<RedundantEquation> find_redundant_constraints(const Subdomain& sub, const MechanicalState& local,
                                                          double tol = 1e-10);
double constraint_violation(const Subdomain& sub, const MechanicalState& local);
std::string diagnose_singular_system(const Subdomain& sub, const MechanicalState& local);
/// Statics: the motions that neither a joint nor a stiffness holds (null space of [K; Φ_q] at the
/// state, dense, up to 2000 coordinates), one line each ("\n  nothing holds body 'b' (x), …");
/// empty if there is none. Collective.
std::string find_unheld_motion(const Subdomain& sub, const MechanicalState& local);

}  // namespace alphaflex
