#pragma once
// DofMap: every unknown (node coordinate or joint multiplier) has one owning MPI rank, and every
// rank owns a contiguous block of the global (PETSc) numbering: its nodes' unknowns, then the
// multipliers of the joints it owns. Nodes are partitioned with METIS over the graph of nodes
// coupled by elements and joints (weighted by their number of unknowns); an element or a joint
// belongs to the rank of its first node, a sensor to the owner of what it reads (its joint, its
// element or its node). Every rank computes the same map from the same model (METIS is
// deterministic with a fixed seed); the Subdomain (subdomain.hpp) cuts each rank's part from it.
#include <mpi.h>

#include <vector>

#include "alphaflex/model/model.hpp"

namespace alphaflex {

class DofMap {
 public:
  DofMap(const Model& model, MPI_Comm comm);

  int rank() const { return rank_; }
  int size() const { return size_; }
  int global_size() const { return global_size_; }
  int local_size() const { return owned_end_ - owned_begin_; }
  int owned_begin() const { return owned_begin_; }
  int owned_end() const { return owned_end_; }

  /// Global index of model-order unknown i (node coordinate) and multiplier j.
  int dof(int i) const { return dof_global_[static_cast<size_t>(i)]; }
  int multiplier(int j) const { return mult_global_[static_cast<size_t>(j)]; }
  int node_owner(int n) const { return node_part_[static_cast<size_t>(n)]; }
  int element_owner(int e) const { return element_owner_[static_cast<size_t>(e)]; }
  int constraint_owner(int c) const { return constraint_owner_[static_cast<size_t>(c)]; }
  int sensor_owner(int s) const { return sensor_owner_[static_cast<size_t>(s)]; }
  /// Unknowns owned by each rank (node coordinates + multipliers).
  const std::vector<int>& unknowns_per_rank() const { return per_rank_; }
  /// Number of element/joint couplings that cross a partition boundary (METIS edge cut).
  int edge_cut() const { return edge_cut_; }

 private:
  int rank_ = 0, size_ = 1;
  int global_size_ = 0, owned_begin_ = 0, owned_end_ = 0, edge_cut_ = 0;
  std::vector<int> node_part_, element_owner_, constraint_owner_, sensor_owner_;
  std::vector<int> dof_global_, mult_global_, per_rank_;
};

}  // namespace alphaflex
