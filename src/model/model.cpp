#include "alphaflex/model/model.hpp"

#include <stdexcept>

namespace alphaflex {

void LocalResidual::reset(int n, bool tangent) {
  r = Eigen::VectorXd::Zero(n);
  if (tangent) {
    K = Eigen::MatrixXd::Zero(n, n);
    C = Eigen::MatrixXd::Zero(n, n);
    M = Eigen::MatrixXd::Zero(n, n);
  }
}

void Constraint::time_derivative(const Eigen::VectorXd&, double, Eigen::VectorXd& phi_t) const {
  phi_t = Eigen::VectorXd::Zero(size());
}

int Model::add_node(Node node) {
  node.ndof = Node::dofs_of(node.kind);
  if (node.q0.size() != node.ndof || node.v0.size() != node.ndof)
    throw std::invalid_argument("node '" + node.name + "': initial state has the wrong size");
  node.first_dof = num_dofs_;
  num_dofs_ += node.ndof;
  nodes_.push_back(std::move(node));
  return static_cast<int>(nodes_.size()) - 1;
}

void Model::add_element(std::unique_ptr<Element> e) { elements_.push_back(std::move(e)); }

void Model::add_constraint(std::unique_ptr<Constraint> c) {
  first_multiplier_.push_back(num_multipliers_);
  num_multipliers_ += c->size();
  constraints_.push_back(std::move(c));
}

int Model::find_node(const std::string& name) const {
  for (size_t i = 0; i < nodes_.size(); ++i)
    if (nodes_[i].name == name) return static_cast<int>(i);
  return -1;
}

int Model::find_constraint(const std::string& name) const {
  for (size_t i = 0; i < constraints_.size(); ++i)
    if (constraints_[i]->name() == name) return static_cast<int>(i);
  return -1;
}

std::vector<int> Model::dofs_of(const std::vector<int>& nodes) const {
  std::vector<int> idx;
  for (int n : nodes) {
    const Node& nd = node(n);
    for (int k = 0; k < nd.ndof; ++k) idx.push_back(nd.first_dof + k);
  }
  return idx;
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
  s.q = Eigen::VectorXd::Zero(num_dofs_);
  s.v = Eigen::VectorXd::Zero(num_dofs_);
  s.qdd = Eigen::VectorXd::Zero(num_dofs_);
  s.lambda = Eigen::VectorXd::Zero(num_multipliers_);
  for (const Node& n : nodes_) {
    s.q.segment(n.first_dof, n.ndof) = n.q0;
    s.v.segment(n.first_dof, n.ndof) = n.v0;
  }
  return s;
}

Eigen::VectorXd gather(const Eigen::VectorXd& global, const std::vector<int>& idx) {
  Eigen::VectorXd local(static_cast<Eigen::Index>(idx.size()));
  for (size_t i = 0; i < idx.size(); ++i) local[static_cast<Eigen::Index>(i)] = global[idx[i]];
  return local;
}

}  // namespace alphaflex
