#pragma once
// The model: nodes (unknowns), elements (inertia, forces), constraints (joints with multipliers)
// and sensors. Model order numbers unknowns node by node, then multipliers joint by joint; the
// DofMap maps this order to the parallel (PETSc) one.
#include <memory>
#include <string>
#include <vector>

#include "alphaflex/model/constraint.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/node.hpp"
#include "alphaflex/model/sensor.hpp"
#include "alphaflex/model/state.hpp"

namespace alphaflex {

class Model {
 public:
  std::string name = "model";

  int add_node(Node node);
  void add_element(std::unique_ptr<Element> e);
  void add_constraint(std::unique_ptr<Constraint> c);
  void add_sensor(Sensor s) { sensors_.push_back(std::move(s)); }

  const std::vector<Node>& nodes() const { return nodes_; }
  const Node& node(int i) const { return nodes_.at(static_cast<size_t>(i)); }
  const std::vector<std::unique_ptr<Element>>& elements() const { return elements_; }
  const std::vector<std::unique_ptr<Constraint>>& constraints() const { return constraints_; }
  const std::vector<Sensor>& sensors() const { return sensors_; }

  int num_dofs() const { return num_dofs_; }
  int num_multipliers() const { return num_multipliers_; }
  /// Index of constraint c's first multiplier in model order.
  int first_multiplier(int c) const { return first_multiplier_.at(static_cast<size_t>(c)); }
  /// -1 if no node has this name.
  int find_node(const std::string& name) const;
  int find_constraint(const std::string& name) const;

  /// Model-order unknown indices of a node list (an element's or a constraint's local vector).
  std::vector<int> dofs_of(const std::vector<int>& nodes) const;
  /// Offset of node `n` inside the local vector of `nodes`.
  int local_offset(const std::vector<int>& nodes, int n) const;

  /// Initial state from the nodes' q0, v0 (accelerations and multipliers zero).
  MechanicalState initial_state() const;

 private:
  std::vector<Node> nodes_;
  std::vector<std::unique_ptr<Element>> elements_;
  std::vector<std::unique_ptr<Constraint>> constraints_;
  std::vector<Sensor> sensors_;
  std::vector<int> first_multiplier_;
  int num_dofs_ = 0;
  int num_multipliers_ = 0;
};

/// Gathers the entries `idx` of a global vector into a local one.
Eigen::VectorXd gather(const Eigen::VectorXd& global, const std::vector<int>& idx);

}  // namespace alphaflex
