#include "alphaflex/partition/dof_map.hpp"

#include <metis.h>

#include <set>
#include <stdexcept>

namespace alphaflex {
namespace {

// METIS partition of the node graph; deterministic, so every rank computes the same result.
std::vector<int> partition_nodes(const Model& model, int nparts, int& edge_cut) {
  const int nv = static_cast<int>(model.nodes().size());
  std::vector<int> part(static_cast<size_t>(nv), 0);
  edge_cut = 0;
  if (nparts <= 1 || nv == 0) return part;
  if (nv <= nparts) {
    for (int i = 0; i < nv; ++i) part[static_cast<size_t>(i)] = i;
    return part;
  }
  std::vector<std::set<int>> adj(static_cast<size_t>(nv));
  auto couple = [&](const std::vector<int>& nodes) {
    for (int a : nodes)
      for (int b : nodes)
        if (a != b) adj[static_cast<size_t>(a)].insert(b);
  };
  for (const auto& e : model.elements()) couple(e->nodes());
  for (const auto& c : model.constraints()) couple(c->nodes());

  std::vector<idx_t> xadj{0}, adjncy, vwgt;
  for (int i = 0; i < nv; ++i) {
    for (int j : adj[static_cast<size_t>(i)]) adjncy.push_back(j);
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
    vwgt.push_back(model.node(i).ndof);
  }
  idx_t n = nv, ncon = 1, np = nparts, objval = 0;
  std::vector<idx_t> result(static_cast<size_t>(nv), 0);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = 1;
  const int status = METIS_PartGraphRecursive(&n, &ncon, xadj.data(), adjncy.empty() ? nullptr : adjncy.data(),
                                              vwgt.data(), nullptr, nullptr, &np, nullptr, nullptr, options,
                                              &objval, result.data());
  if (status != METIS_OK) throw std::runtime_error("METIS_PartGraphRecursive failed with status " +
                                                   std::to_string(status));
  for (int i = 0; i < nv; ++i) part[static_cast<size_t>(i)] = static_cast<int>(result[static_cast<size_t>(i)]);
  edge_cut = static_cast<int>(objval);
  return part;
}

}  // namespace

DofMap::DofMap(const Model& model, MPI_Comm comm) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  node_part_ = partition_nodes(model, size_, edge_cut_);

  auto first_node_owner = [&](const std::vector<int>& nodes) { return nodes.empty() ? 0 : node_part_[static_cast<size_t>(nodes.front())]; };
  for (const auto& e : model.elements()) element_owner_.push_back(first_node_owner(e->nodes()));
  for (const auto& c : model.constraints()) constraint_owner_.push_back(first_node_owner(c->nodes()));
  for (const Sensor& s : model.sensors()) {
    // A sensor that reads a joint or an element is evaluated where it is assembled.
    // An energy sum over an element range (node2 > element, model/sensor.cpp) is on every rank:
    // each adds the elements it owns (subdomain.cpp); rank 0 is its nominal owner.
    if (s.kind == Sensor::Kind::ElementEnergy && s.node2 > s.element) sensor_owner_.push_back(0);
    else if (s.constraint >= 0) sensor_owner_.push_back(constraint_owner_[static_cast<size_t>(s.constraint)]);
    else if (s.element >= 0) sensor_owner_.push_back(element_owner_[static_cast<size_t>(s.element)]);
    else sensor_owner_.push_back(node_part_[static_cast<size_t>(s.node)]);
  }

  // Rank-major numbering: rank 0's node unknowns and multipliers, then rank 1's, ...
  dof_global_.assign(static_cast<size_t>(model.num_dofs()), -1);
  mult_global_.assign(static_cast<size_t>(model.num_multipliers()), -1);
  per_rank_.assign(static_cast<size_t>(size_), 0);
  int next = 0;
  for (int r = 0; r < size_; ++r) {
    const int begin = next;
    for (size_t n = 0; n < model.nodes().size(); ++n) {
      if (node_part_[n] != r) continue;
      const Node& nd = model.nodes()[n];
      for (int k = 0; k < nd.ndof; ++k) dof_global_[static_cast<size_t>(nd.first_dof + k)] = next++;
    }
    for (size_t c = 0; c < model.constraints().size(); ++c) {
      if (constraint_owner_[c] != r) continue;
      const int first = model.first_multiplier(static_cast<int>(c));
      for (int k = 0; k < model.constraints()[c]->size(); ++k) mult_global_[static_cast<size_t>(first + k)] = next++;
    }
    per_rank_[static_cast<size_t>(r)] = next - begin;
    if (r == rank_) {
      owned_begin_ = begin;
      owned_end_ = next;
    }
  }
  global_size_ = next;
}

}  // namespace alphaflex
