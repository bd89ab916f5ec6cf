#pragma once
// An element maps the local state of its nodes to a local residual and its tangents. It knows
// nothing of PETSc, MPI, the DofMap or the integrator.
//
// Residual convention (Arnold & Brüls 2007, eq. 1): r = M(q) q̈ − g(q, q̇, t); the equations of
// motion are Σ_e r_e + Φ_qᵀ λ = 0. Tangents: K = ∂r/∂q, C = ∂r/∂q̇, M = ∂r/∂q̈, from which the
// integrator forms S_t = M β' + C γ' + K (eq. 7).
#include <Eigen/Dense>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace alphaflex {

/// Coordinates, velocities and accelerations of an element's nodes, concatenated in node order.
struct LocalState {
  Eigen::VectorXd q, v, qdd;  ///< configuration (nconf per node), velocities and accelerations (ndof)
  double t = 0.0;
  /// Multiplies every applied load (forces, moments, gravity): 1 in dynamics, stepped from 0 to 1
  /// by the quasi-static analysis.
  double load_factor = 1.0;
};

struct LocalResidual {
  Eigen::VectorXd r;
  Eigen::MatrixXd K, C, M;
  /// Sizes every block to n and zeroes it (tangents only if requested).
  void reset(int n, bool tangent);
};

class Element {
 public:
  Element(std::string name, std::vector<int> nodes) : name_(std::move(name)), nodes_(std::move(nodes)) {}
  virtual ~Element() = default;

  const std::string& name() const { return name_; }
  const std::vector<int>& nodes() const { return nodes_; }
  virtual const char* type() const = 0;

  /// Adds this element's r (and K, C, M if `tangent`) into `out`, which the caller has reset.
  virtual void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const = 0;

  /// Names of the element's result fields (a beam: section forces and strains), for sensors and
  /// the HDF5/XDMF cell data; empty if it has none.
  virtual std::vector<std::string> output_names() const { return {}; }
  /// Their values at state `s` (one per name).
  virtual void output(const LocalState& /*s*/, Eigen::VectorXd& values) const { values.resize(0); }

  /// The same element on other indices of the same nodes: a subdomain's local numbering
  /// (partition/subdomain.hpp). An element holds no reference to the model, so the copy is whole.
  std::unique_ptr<Element> renumbered(std::vector<int> nodes) const {
    if (nodes.size() != nodes_.size()) throw std::logic_error("Element::renumbered: wrong number of nodes");
    std::unique_ptr<Element> e = clone();
    e->nodes_ = std::move(nodes);
    return e;
  }

 protected:
  Element(const Element&) = default;
  virtual std::unique_ptr<Element> clone() const = 0;

 private:
  std::string name_;
  std::vector<int> nodes_;
};

}  // namespace alphaflex
