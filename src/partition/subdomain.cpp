#include "alphaflex/partition/subdomain.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace alphaflex {

Subdomain::Subdomain(const Model& global, MPI_Comm comm) : global_(global), comm_(comm), map_(global, comm) {
  const int me = map_.rank();
  const int nn = static_cast<int>(global.nodes().size());
  local_.name = global.name;

  // Owned nodes in global order, then the ghosts: nodes that owned elements, joints and sensors
  // touch and another rank owns.
  std::vector<int> local_of(static_cast<size_t>(nn), -1);
  for (int n = 0; n < nn; ++n)
    if (map_.node_owner(n) == me) node_global_.push_back(n);
  owned_nodes_ = static_cast<int>(node_global_.size());
  std::vector<char> ghost(static_cast<size_t>(nn), 0);
  auto need = [&](int n) {
    if (n >= 0 && map_.node_owner(n) != me) ghost[static_cast<size_t>(n)] = 1;
  };
  for (size_t e = 0; e < global.elements().size(); ++e)
    if (map_.element_owner(static_cast<int>(e)) == me)
      for (int n : global.elements()[e]->nodes()) need(n);
  for (size_t c = 0; c < global.constraints().size(); ++c)
    if (map_.constraint_owner(static_cast<int>(c)) == me)
      for (int n : global.constraints()[c]->nodes()) need(n);
  // An energy sum over the element range [element, node2) (model/sensor.cpp) needs no nodes beyond
  // its elements'; it is on every rank, over the range's elements this rank owns.
  auto is_sum = [](const Sensor& sn) { return sn.kind == Sensor::Kind::ElementEnergy && sn.node2 > sn.element; };
  for (size_t s = 0; s < global.sensors().size(); ++s) {
    if (map_.sensor_owner(static_cast<int>(s)) != me || is_sum(global.sensors()[s])) continue;
    const Sensor& sn = global.sensors()[s];
    need(sn.node);
    need(sn.node2);
    need(sn.frame_node);
  }
  for (int n = 0; n < nn; ++n)
    if (ghost[static_cast<size_t>(n)]) node_global_.push_back(n);
  for (size_t i = 0; i < node_global_.size(); ++i) {
    const int g = node_global_[i];
    local_of[static_cast<size_t>(g)] = static_cast<int>(i);
    local_.add_node(global.node(g));
    if (static_cast<int>(i) < owned_nodes_) {
      owned_dofs_ += global.node(g).ndof;
      owned_conf_ += global.node(g).nconf;
    }
  }
  auto local_nodes = [&](const std::vector<int>& nodes) {
    std::vector<int> out;
    out.reserve(nodes.size());
    for (int n : nodes) out.push_back(local_of[static_cast<size_t>(n)]);
    return out;
  };
  std::vector<int> element_local(global.elements().size(), -1), constraint_local(global.constraints().size(), -1);
  for (size_t e = 0; e < global.elements().size(); ++e) {
    if (map_.element_owner(static_cast<int>(e)) != me) continue;
    element_local[e] = static_cast<int>(element_global_.size());
    element_global_.push_back(static_cast<int>(e));
    local_.add_element(global.elements()[e]->renumbered(local_nodes(global.elements()[e]->nodes())));
  }
  for (size_t c = 0; c < global.constraints().size(); ++c) {
    if (map_.constraint_owner(static_cast<int>(c)) != me) continue;
    constraint_local[c] = static_cast<int>(constraint_global_.size());
    constraint_global_.push_back(static_cast<int>(c));
    local_.add_constraint(global.constraints()[c]->renumbered(local_nodes(global.constraints()[c]->nodes())));
  }
  for (size_t s = 0; s < global.sensors().size(); ++s) {
    Sensor sn = global.sensors()[s];
    if (is_sum(sn)) {
      // The owned elements of a global range are a range of the local ones (both in global order).
      int first = -1, end = -1;
      for (int e = sn.element; e < sn.node2; ++e)
        if (const int l = element_local[static_cast<size_t>(e)]; l >= 0) {
          if (first < 0) first = l;
          end = l + 1;
        }
      sn.element = first;
      sn.node2 = end;
      sensor_global_.push_back(static_cast<int>(s));
      local_.add_sensor(std::move(sn));
      continue;
    }
    if (map_.sensor_owner(static_cast<int>(s)) != me) continue;
    auto remap = [&](int& n) {
      if (n >= 0) n = local_of[static_cast<size_t>(n)];
    };
    remap(sn.node);
    remap(sn.node2);
    remap(sn.frame_node);
    if (sn.constraint >= 0) sn.constraint = constraint_local[static_cast<size_t>(sn.constraint)];
    if (sn.element >= 0) sn.element = element_local[static_cast<size_t>(sn.element)];
    sensor_global_.push_back(static_cast<int>(s));
    local_.add_sensor(std::move(sn));
  }

  // PETSc indices of the local unknowns.
  for (int g : node_global_) {
    const Node& nd = global.node(g);
    for (int k = 0; k < nd.ndof; ++k) dof_petsc_.push_back(map_.dof(nd.first_dof + k));
  }
  for (int c : constraint_global_) {
    const int first = global.first_multiplier(c);
    for (int k = 0; k < global.constraints()[static_cast<size_t>(c)]->size(); ++k)
      mult_petsc_.push_back(map_.multiplier(first + k));
  }

  // Layout of gather(): rank after rank, each rank's owned nodes and joints in global order.
  const int np = map_.size();
  conf_counts_.assign(static_cast<size_t>(np), 0);
  dof_counts_.assign(static_cast<size_t>(np), 0);
  mult_counts_.assign(static_cast<size_t>(np), 0);
  for (int r = 0; r < np; ++r) {
    for (int n = 0; n < nn; ++n)
      if (map_.node_owner(n) == r) {
        gather_nodes_.push_back(n);
        conf_counts_[static_cast<size_t>(r)] += global.node(n).nconf;
        dof_counts_[static_cast<size_t>(r)] += global.node(n).ndof;
      }
    for (size_t c = 0; c < global.constraints().size(); ++c)
      if (map_.constraint_owner(static_cast<int>(c)) == r) {
        gather_constraints_.push_back(static_cast<int>(c));
        mult_counts_[static_cast<size_t>(r)] += global.constraints()[c]->size();
      }
  }
}

double Subdomain::max_abs(const Eigen::VectorXd& v) const {
  double mine = v.size() ? v.cwiseAbs().maxCoeff() : 0.0, all = mine;
  if (size() > 1) MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return all;
}

double Subdomain::dof_norm(const Eigen::VectorXd& dofs) const {
  double mine = dofs.head(owned_dofs_).squaredNorm(), all = mine;
  if (size() > 1) MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return std::sqrt(all);
}

double Subdomain::multiplier_norm(const Eigen::VectorXd& multipliers) const {
  double mine = multipliers.squaredNorm(), all = mine;
  if (size() > 1) MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return std::sqrt(all);
}

void Subdomain::sum(std::vector<double>& values) const {
  if (size() > 1 && !values.empty())
    MPI_Allreduce(MPI_IN_PLACE, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, comm_);
}

int Subdomain::rank_of_max(double local) const {
  struct {
    double value;
    int rank;
  } mine{local, rank()}, all = mine;
  if (size() > 1) MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, comm_);
  return all.rank;
}

std::string Subdomain::first_error(const std::string& local_error) const {
  const int mine = local_error.empty() ? size() : rank();
  int first = mine;
  if (size() > 1) MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm_);
  return first == size() ? std::string() : broadcast(local_error, first);
}

std::string Subdomain::broadcast(const std::string& text, int root) const {
  if (size() == 1) return text;
  int len = static_cast<int>(text.size());
  MPI_Bcast(&len, 1, MPI_INT, root, comm_);
  std::string out = text;
  out.resize(static_cast<size_t>(len));
  MPI_Bcast(out.data(), len, MPI_CHAR, root, comm_);
  return out;
}

namespace {

/// Allgatherv of `mine` with `counts` values per rank, rank after rank.
std::vector<double> allgather(const double* mine, const std::vector<int>& counts, int rank, MPI_Comm comm) {
  std::vector<int> displ(counts.size(), 0);
  for (size_t r = 1; r < counts.size(); ++r) displ[r] = displ[r - 1] + counts[r - 1];
  std::vector<double> all(static_cast<size_t>(std::accumulate(counts.begin(), counts.end(), 0)));
  MPI_Allgatherv(mine, counts[static_cast<size_t>(rank)], MPI_DOUBLE, all.data(), counts.data(), displ.data(),
                 MPI_DOUBLE, comm);
  return all;
}

}  // namespace

Eigen::VectorXd Subdomain::gather_dofs(const Eigen::VectorXd& local) const {
  if (size() == 1) return local;
  const std::vector<double> all = allgather(local.data(), dof_counts_, rank(), comm_);
  Eigen::VectorXd out(global_.num_dofs());
  size_t k = 0;
  for (int n : gather_nodes_) {
    const Node& nd = global_.node(n);
    for (int d = 0; d < nd.ndof; ++d) out[nd.first_dof + d] = all[k++];
  }
  return out;
}

Eigen::VectorXd Subdomain::gather_multipliers(const Eigen::VectorXd& local) const {
  if (size() == 1) return local;
  const std::vector<double> all = allgather(local.data(), mult_counts_, rank(), comm_);
  Eigen::VectorXd out(global_.num_multipliers());
  size_t k = 0;
  for (int c : gather_constraints_) {
    const int first = global_.first_multiplier(c);
    for (int j = 0; j < global_.constraints()[static_cast<size_t>(c)]->size(); ++j) out[first + j] = all[k++];
  }
  return out;
}

MechanicalState Subdomain::gather(const MechanicalState& local) const {
  if (size() == 1) return local;
  MechanicalState g;
  g.t = local.t;
  const std::vector<double> q = allgather(local.q.data(), conf_counts_, rank(), comm_);
  g.q.resize(global_.num_conf());
  size_t k = 0;
  for (int n : gather_nodes_) {
    const Node& nd = global_.node(n);
    for (int d = 0; d < nd.nconf; ++d) g.q[nd.first_conf + d] = q[k++];
  }
  g.v = gather_dofs(local.v);
  g.qdd = gather_dofs(local.qdd);
  g.lambda = gather_multipliers(local.lambda);
  return g;
}

MechanicalState Subdomain::restrict(const MechanicalState& global) const {
  MechanicalState s = local_.initial_state();
  s.t = global.t;
  for (size_t i = 0; i < node_global_.size(); ++i) {
    const Node& g = global_.node(node_global_[i]);
    const Node& l = local_.node(static_cast<int>(i));
    s.q.segment(l.first_conf, l.nconf) = global.q.segment(g.first_conf, g.nconf);
    s.v.segment(l.first_dof, l.ndof) = global.v.segment(g.first_dof, g.ndof);
    s.qdd.segment(l.first_dof, l.ndof) = global.qdd.segment(g.first_dof, g.ndof);
  }
  for (size_t c = 0; c < constraint_global_.size(); ++c) {
    const int m = local_.constraints()[c]->size();
    s.lambda.segment(local_.first_multiplier(static_cast<int>(c)), m) =
        global.lambda.segment(global_.first_multiplier(constraint_global_[c]), m);
  }
  return s;
}

}  // namespace alphaflex
