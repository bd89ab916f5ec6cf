#pragma once
// The model: nodes (unknowns), elements (inertia, forces), constraints (joints with multipliers)
// and sensors. Model order numbers unknowns node by node, then multipliers joint by joint; the
// DofMap maps this order to the parallel (PETSc) one.
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "alphaflex/model/body_shape.hpp"
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
  /// A body's shape for the results (model/body_shape.hpp); no effect on the dynamics.
  void add_shape(BodyShape s) { shapes_.push_back(std::move(s)); }

  const std::vector<Node>& nodes() const { return nodes_; }
  const Node& node(int i) const { return nodes_.at(static_cast<size_t>(i)); }
  const std::vector<std::unique_ptr<Element>>& elements() const { return elements_; }
  const std::vector<std::unique_ptr<Constraint>>& constraints() const { return constraints_; }
  const std::vector<Sensor>& sensors() const { return sensors_; }
  const std::vector<BodyShape>& shapes() const { return shapes_; }

  int num_dofs() const { return num_dofs_; }
  /// Stored configuration numbers (≥ num_dofs(): 7 per spatial frame).
  int num_conf() const { return num_conf_; }
  /// True if some node lives on a Lie group (spatial frames).
  bool has_lie_group_nodes() const { return lie_nodes_; }
  int num_multipliers() const { return num_multipliers_; }
  /// Index of constraint c's first multiplier in model order.
  int first_multiplier(int c) const { return first_multiplier_.at(static_cast<size_t>(c)); }
  /// -1 if no node has this name (the first one if several have it). Constant time: scenes with
  /// 10⁵ nodes look names up once per node.
  int find_node(const std::string& name) const;
  int find_constraint(const std::string& name) const;

  /// Model-order unknown indices of a node list (an element's or a constraint's local vector).
  std::vector<int> dofs_of(const std::vector<int>& nodes) const;
  /// Model-order configuration indices of a node list (what an element's LocalState::q holds).
  std::vector<int> confs_of(const std::vector<int>& nodes) const;
  /// Offset of node `n` inside the local vector of `nodes`.
  int local_offset(const std::vector<int>& nodes, int n) const;

  /// Element e's local (q, q̇, q̈, t) at the model-order state s (load factor 1).
  LocalState local_state(const Element& e, const MechanicalState& s) const;

  /// Initial state from the nodes' q0, v0 (accelerations and multipliers zero).
  MechanicalState initial_state() const;

  /// q ← q ∘ exp(dx), node by node (q += dx on vector spaces).
  void retract(Eigen::VectorXd& q, const Eigen::VectorXd& dx) const;
  /// One Newton update of the Lie-group generalized-α (Brüls, Cardona & Arnold 2012): `x` is the
  /// increment hΔq of the step (already including dx). Vector-space nodes: q += dx, so that they
  /// follow Algorithm 1 of Arnold & Brüls operation by operation; group nodes: q = q_n ∘ exp(x),
  /// recomputed from the start of the step so that round-off does not accumulate.
  void advance(const Eigen::VectorXd& q_n, const Eigen::VectorXd& x, const Eigen::VectorXd& dx,
               Eigen::VectorXd& q) const;
  /// The inverse of retract on each node: dx with q_to = q_from ∘ exp(dx) (log on SO(3)).
  Eigen::VectorXd difference(const Eigen::VectorXd& q_from, const Eigen::VectorXd& q_to) const;

 private:
  std::vector<Node> nodes_;
  std::vector<std::unique_ptr<Element>> elements_;
  std::vector<std::unique_ptr<Constraint>> constraints_;
  std::vector<Sensor> sensors_;
  std::vector<BodyShape> shapes_;
  std::vector<int> first_multiplier_;
  std::unordered_map<std::string, int> node_index_, constraint_index_;
  int num_dofs_ = 0;
  int num_conf_ = 0;
  int num_multipliers_ = 0;
  bool lie_nodes_ = false;
};

/// Gathers the entries `idx` of a global vector into a local one.
Eigen::VectorXd gather(const Eigen::VectorXd& global, const std::vector<int>& idx);

}  // namespace alphaflex
