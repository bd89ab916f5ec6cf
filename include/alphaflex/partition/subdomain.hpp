#pragma once
// Subdomain: the part of the model one MPI rank works on. The DofMap partitions the nodes with
// METIS; a rank owns its nodes, the elements, joints and sensors whose first node it owns, and the
// unknowns of both. Its subdomain is a Model of its own in a local numbering:
//
//   local nodes  = owned nodes (in global order), then ghost nodes (in global order): the nodes
//                  that its elements, joints and sensors need and another rank owns;
//   elements, joints, sensors = the owned ones, renumbered onto the local nodes.
//
// The state of a rank (MechanicalState on the local model) therefore holds only owned and ghost
// nodes; the assembly exchanges ghost values with a PETSc VecScatter after every solve, and every
// rank applies the same integrator updates to its ghost copies as their owner does, so ghost
// copies stay equal to the owner's values. Element kernels see only local data. On one rank the
// local numbering is the model's own (identity), so a one-rank run does exactly what it did with
// the whole model.
//
// What stays replicated (documented in docs/architecture.md and docs/performance.md): every rank
// holds the scene's whole Model (its description: nodes, element and joint objects), from which
// the subdomain is cut; it gives names for messages, layouts for the HDF5 file and the diagnosis
// of singular models. Per-iteration work and communication are local.
#include <mpi.h>

#include <string>
#include <vector>

#include "alphaflex/model/model.hpp"
#include "alphaflex/partition/dof_map.hpp"

namespace alphaflex {

class Subdomain {
 public:
  /// Partitions `global` over the ranks of `comm` (METIS, DofMap) and cuts this rank's part.
  /// Collective: every rank must pass the same model.
  Subdomain(const Model& global, MPI_Comm comm);
  Subdomain(const Subdomain&) = delete;
  Subdomain& operator=(const Subdomain&) = delete;

  /// This rank's part, in the local numbering (owned nodes first, then ghosts).
  const Model& model() const { return local_; }
  /// The whole model, in model order (the scene's numbering).
  const Model& global_model() const { return global_; }
  const DofMap& dof_map() const { return map_; }
  MPI_Comm comm() const { return comm_; }
  int rank() const { return map_.rank(); }
  int size() const { return map_.size(); }

  int num_owned_nodes() const { return owned_nodes_; }
  int num_ghost_nodes() const { return static_cast<int>(node_global_.size()) - owned_nodes_; }
  /// Owned unknowns (coordinates) come first in the local vectors: [0, num_owned_dofs()).
  int num_owned_dofs() const { return owned_dofs_; }
  int num_owned_conf() const { return owned_conf_; }
  bool owns_node(int local) const { return local < owned_nodes_; }

  /// Global (model-order) index of local node / element / joint / sensor i.
  int global_node(int i) const { return node_global_[static_cast<size_t>(i)]; }
  int global_element(int i) const { return element_global_[static_cast<size_t>(i)]; }
  int global_constraint(int i) const { return constraint_global_[static_cast<size_t>(i)]; }
  int global_sensor(int i) const { return sensor_global_[static_cast<size_t>(i)]; }
  /// PETSc (parallel) index of every local unknown: the local node coordinates in local order,
  /// then the local multipliers (all owned).
  const std::vector<int>& dof_indices() const { return dof_petsc_; }
  const std::vector<int>& multiplier_indices() const { return mult_petsc_; }

  // Collective reductions: every rank gets the same value, so every rank takes the same decision.
  /// max |v_i| over all ranks (ghost copies equal their owner's values and do not change a max).
  double max_abs(const Eigen::VectorXd& v) const;
  /// ‖·‖₂ of a local vector of node coordinates, over the owned entries only (ghosts counted once).
  double dof_norm(const Eigen::VectorXd& dofs) const;
  /// ‖·‖₂ of a local vector of multipliers (all owned).
  double multiplier_norm(const Eigen::VectorXd& multipliers) const;
  /// Sum over ranks, element by element (sensor values: each is non-zero on its owner only).
  void sum(std::vector<double>& values) const;
  /// The rank holding the largest `local` value (the lowest such rank on ties).
  int rank_of_max(double local) const;
  /// `text` from rank `root` on every rank.
  std::string broadcast(const std::string& text, int root) const;
  /// The message of the lowest rank whose `local_error` is not empty, on every rank; empty if no
  /// rank failed (collective: so that failed anywhere means failed everywhere, and no rank goes on
  /// into a collective call alone).
  std::string first_error(const std::string& local_error) const;

  /// The whole state in model order, on every rank (O(model) per rank: for diagnostics, messages
  /// and the final state of a run, not for the step loop).
  MechanicalState gather(const MechanicalState& local) const;
  /// A vector of node coordinates (ndof per node) or of multipliers in model order, on every rank.
  Eigen::VectorXd gather_dofs(const Eigen::VectorXd& local) const;
  Eigen::VectorXd gather_multipliers(const Eigen::VectorXd& local) const;
  /// The local part of a state in model order (no communication).
  MechanicalState restrict(const MechanicalState& global) const;

 private:
  const Model& global_;
  MPI_Comm comm_;
  DofMap map_;
  Model local_;
  int owned_nodes_ = 0, owned_dofs_ = 0, owned_conf_ = 0;
  std::vector<int> node_global_, element_global_, constraint_global_, sensor_global_;
  std::vector<int> dof_petsc_, mult_petsc_;
  // For gather: every rank's owned nodes and joints in global order, rank after rank, and the
  // number of values each rank contributes.
  std::vector<int> gather_nodes_, gather_constraints_;
  std::vector<int> conf_counts_, dof_counts_, mult_counts_;
};

}  // namespace alphaflex
