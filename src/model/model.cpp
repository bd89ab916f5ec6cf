#include "alphaflex/model/model.hpp"

#include <stdexcept>

#include "alphaflex/core/rotation.hpp"

namespace alphaflex {

void LocalResidual::reset(int n, bool tangent) {
  r = Eigen::VectorXd::Zero(n);
  if (tangent) {
    K = Eigen::MatrixXd::Zero(n, n);
    C = Eigen::MatrixXd::Zero(n, n);
    M = Eigen::MatrixXd::Zero(n, n);
  }
}

std::vector<std::string> Element::output_names() const {
  std::vector<std::string> names;
  for (const CellField& f : cell_fields()) {
    if (f.components == 1) names.push_back(f.name);
    else
      for (int k = 0; k < f.components; ++k) names.push_back(f.name + "[" + std::to_string(k) + "]");
  }
  return names;
}

void Constraint::time_derivative(const Eigen::VectorXd&, double, Eigen::VectorXd& phi_t) const {
  phi_t = Eigen::VectorXd::Zero(size());
}

int Model::add_node(Node node) {
  node.ndof = Node::dofs_of(node.kind);
  node.nconf = Node::confs_of(node.kind);
  if (node.q0.size() != node.nconf || node.v0.size() != node.ndof)
    throw std::invalid_argument("node '" + node.name + "': initial state has the wrong size");
  node.first_dof = num_dofs_;
  node.first_conf = num_conf_;
  num_dofs_ += node.ndof;
  num_conf_ += node.nconf;
  lie_nodes_ = lie_nodes_ || is_lie_group(node.kind);
  node_index_.emplace(node.name, static_cast<int>(nodes_.size()));  // keeps the first of a name
  nodes_.push_back(std::move(node));
  return static_cast<int>(nodes_.size()) - 1;
}

void Model::add_element(std::unique_ptr<Element> e) { elements_.push_back(std::move(e)); }

void Model::add_constraint(std::unique_ptr<Constraint> c) {
  first_multiplier_.push_back(num_multipliers_);
  num_multipliers_ += c->size();
  constraint_index_.emplace(c->name(), static_cast<int>(constraints_.size()));
  constraints_.push_back(std::move(c));
}

int Model::find_node(const std::string& name) const {
  const auto it = node_index_.find(name);
  return it == node_index_.end() ? -1 : it->second;
}

int Model::find_constraint(const std::string& name) const {
  const auto it = constraint_index_.find(name);
  return it == constraint_index_.end() ? -1 : it->second;
}

std::vector<int> Model::dofs_of(const std::vector<int>& nodes) const {
  std::vector<int> idx;
  for (int n : nodes) {
    const Node& nd = node(n);
    for (int k = 0; k < nd.ndof; ++k) idx.push_back(nd.first_dof + k);
  }
  return idx;
}

std::vector<int> Model::confs_of(const std::vector<int>& nodes) const {
  std::vector<int> idx;
  for (int n : nodes) {
    const Node& nd = node(n);
    for (int k = 0; k < nd.nconf; ++k) idx.push_back(nd.first_conf + k);
  }
  return idx;
}

void Model::retract(Eigen::VectorXd& q, const Eigen::VectorXd& dx) const {
  for (const Node& n : nodes_) alphaflex::retract(n.kind, q.data() + n.first_conf, dx.data() + n.first_dof, q.data() + n.first_conf);
}

void Model::advance(const Eigen::VectorXd& q_n, const Eigen::VectorXd& x, const Eigen::VectorXd& dx,
                    Eigen::VectorXd& q) const {
  if (!lie_nodes_) {
    q += dx;  // all vector spaces: exactly Algorithm 1
    return;
  }
  for (const Node& n : nodes_) {
    if (is_lie_group(n.kind))
      alphaflex::retract(n.kind, q_n.data() + n.first_conf, x.data() + n.first_dof, q.data() + n.first_conf);
    else
      q.segment(n.first_conf, n.nconf) += dx.segment(n.first_dof, n.ndof);
  }
}

Eigen::VectorXd Model::difference(const Eigen::VectorXd& q_from, const Eigen::VectorXd& q_to) const {
  Eigen::VectorXd d(num_dofs_);
  for (const Node& n : nodes_) {
    if (n.kind == NodeKind::Frame3D) {
      const double* a = q_from.data() + n.first_conf;
      const double* b = q_to.data() + n.first_conf;
      for (int k = 0; k < 3; ++k) d[n.first_dof + k] = b[k] - a[k];
      const Eigen::Quaterniond qa(a[3], a[4], a[5], a[6]), qb(b[3], b[4], b[5], b[6]);
      d.segment<3>(n.first_dof + 3) = quaternion_log(qa.conjugate() * qb);
    } else {
      d.segment(n.first_dof, n.ndof) = q_to.segment(n.first_conf, n.nconf) - q_from.segment(n.first_conf, n.nconf);
    }
  }
  return d;
}

int Model::local_offset(const std::vector<int>& nodes, int n) const {
  int off = 0;
  for (int m : nodes) {
    if (m == n) return off;
    off += node(m).ndof;
  }
  throw std::logic_error("node not in list");
}

MechanicalState Model::initial_state() const {
  MechanicalState s;
  s.q = Eigen::VectorXd::Zero(num_conf_);
  s.v = Eigen::VectorXd::Zero(num_dofs_);
  s.qdd = Eigen::VectorXd::Zero(num_dofs_);
  s.lambda = Eigen::VectorXd::Zero(num_multipliers_);
  for (const Node& n : nodes_) {
    s.q.segment(n.first_conf, n.nconf) = n.q0;
    s.v.segment(n.first_dof, n.ndof) = n.v0;
  }
  return s;
}

LocalState Model::local_state(const Element& e, const MechanicalState& s) const {
  LocalState ls;
  const std::vector<int> idx = dofs_of(e.nodes());
  ls.q = gather(s.q, confs_of(e.nodes()));
  ls.v = gather(s.v, idx);
  ls.qdd = gather(s.qdd, idx);
  ls.t = s.t;
  return ls;
}

Eigen::VectorXd gather(const Eigen::VectorXd& global, const std::vector<int>& idx) {
  Eigen::VectorXd local(static_cast<Eigen::Index>(idx.size()));
  for (size_t i = 0; i < idx.size(); ++i) local[static_cast<Eigen::Index>(i)] = global[idx[i]];
  return local;
}

}  // namespace alphaflex
