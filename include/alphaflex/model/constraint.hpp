#pragma once
// A joint: holonomic constraints Φ(q, t) = 0 at position level (index 3) with one Lagrange
// multiplier per equation. Like an element it sees only the local coordinates of its nodes.
#include <Eigen/Dense>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace alphaflex {

/// The load a joint exerts on its first body, in the world frame: force, and moment about the
/// joint point (planar joints use force.x, force.y and moment.z). `frame` holds the joint frame's
/// axes as columns (world components), so that frameᵀ force is the force in the joint frame.
struct JointReaction {
  Eigen::Vector3d location = Eigen::Vector3d::Zero();
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
};

class Constraint {
 public:
  Constraint(std::string name, std::vector<int> nodes) : name_(std::move(name)), nodes_(std::move(nodes)) {}
  virtual ~Constraint() = default;

  const std::string& name() const { return name_; }
  const std::vector<int>& nodes() const { return nodes_; }
  virtual const char* type() const = 0;
  /// Number of equations (and multipliers).
  virtual int size() const = 0;
  /// Name of equation k (0-based) in messages and output, e.g. "a3·b1"; empty if it has none.
  virtual std::string equation_name(int /*k*/) const { return ""; }
  /// "equation 4 (a3·b1)": equation k (0-based) as messages name it.
  std::string equation_label(int k) const {
    const std::string n = equation_name(k);
    return "equation " + std::to_string(k + 1) + (n.empty() ? "" : " (" + n + ")");
  }

  /// Φ(q, t) and Φ_q (size() × local dofs).
  virtual void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const = 0;
  /// ∂(Φ_qᵀ λ)/∂q, the constraint's contribution to the tangent stiffness.
  virtual void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                                   Eigen::MatrixXd& k) const = 0;
  /// Φ_t (zero for scleronomic joints).
  virtual void time_derivative(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi_t) const;
  /// (Φ_q q̇)_q q̇ + 2 Φ_qt q̇ + Φ_tt, so that Φ̈ = Φ_q q̈ + this (consistent start, design §3).
  virtual void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                                 Eigen::VectorXd& c) const = 0;
  /// The force and moment of the joint on its first body, from the multipliers.
  virtual JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const = 0;

  /// The same joint on other indices of the same nodes: a subdomain's local numbering.
  std::unique_ptr<Constraint> renumbered(std::vector<int> nodes) const {
    if (nodes.size() != nodes_.size()) throw std::logic_error("Constraint::renumbered: wrong number of nodes");
    std::unique_ptr<Constraint> c = clone();
    c->nodes_ = std::move(nodes);
    return c;
  }

 protected:
  Constraint(const Constraint&) = default;
  virtual std::unique_ptr<Constraint> clone() const = 0;

 private:
  std::string name_;
  std::vector<int> nodes_;
};

}  // namespace alphaflex
