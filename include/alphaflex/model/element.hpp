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

/// The shape of the cell an element adds to the results' mesh (XDMF topology).
enum class CellShape { none, line, triangle, quadrilateral };

/// An element's cell in the results: its shape and its corners, as positions in the element's
/// node list, in the cell's order (a line from the first to the second; a face counter-clockwise
/// about its normal, as XDMF and VTK expect).
struct OutputCell {
  CellShape shape = CellShape::none;
  std::vector<int> corners;
};

/// A named result field of an element and its number of components (1: a scalar).
struct CellField {
  std::string name;
  int components = 1;
  bool operator==(const CellField& o) const { return name == o.name && components == o.components; }
  bool operator!=(const CellField& o) const { return !(*this == o); }
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

  // ---- Capabilities: what the results and the studies ask of an element (none of them tests an
  // element's type, so a new element type is drawn, written and measured through these alone).

  /// The kind of structure the element is part of: "beam", "shell", …; nullptr for elements that
  /// store no strain (rigid bodies, point masses, loads). A scene block of such elements is a
  /// flexible part (study/strain_energy.hpp), and its cells are drawn in the results' grid of that
  /// structure (io/results_writer.hpp: grid "beams", datasets "beam_<field>").
  virtual const char* structure() const { return nullptr; }
  /// The cell it adds to the results' mesh, with its corners in the cell's node order.
  virtual OutputCell output_cell() const { return {}; }
  /// Its result fields (constant over its cell: cell data), in the order of output(); empty if it
  /// has none.
  virtual std::vector<CellField> cell_fields() const { return {}; }
  /// Their values at state `s`: the components of every field, field after field.
  virtual void output(const LocalState& /*s*/, Eigen::VectorXd& values) const { values.resize(0); }
  /// One name per value of output(), for sensors: a field's name, or NAME[k] (k from 0) for the
  /// components of a field of several.
  std::vector<std::string> output_names() const;
  /// The elastic (strain) energy W (J) stored at the configuration q of its nodes; 0 for elements
  /// that store none.
  virtual double elastic_energy(const Eigen::VectorXd& /*q*/) const { return 0.0; }
  /// Its internal (elastic) force r = ∂W/∂δ at the configuration q, into r (resized; the
  /// residual's order and increments): no inertia, damping or loads, so none of them is computed.
  /// What a reduction differentiates (modal/superelement.hpp, nonlinear_stiffness). Returns false,
  /// r untouched, if the element does not offer it: the caller evaluates the whole element at rest.
  virtual bool internal_force(const Eigen::VectorXd& /*q*/, Eigen::VectorXd& /*r*/) const { return false; }
  /// M(q) w, the residual's derivative with respect to q̈ applied to w (r is affine in q̈), into Mw
  /// (resized): what the filtered error estimate of the adaptive steps multiplies by at every
  /// application (docs/theory/adaptive_steps.md §3b), so that it costs no elastic forces. Returns
  /// false, Mw untouched, if the element does not offer it: the caller then takes the difference of
  /// two residuals at q̈ + w and q̈, which is the same vector up to round-off.
  virtual bool mass_action(const LocalState& /*s*/, const Eigen::VectorXd& /*w*/, Eigen::VectorXd& /*Mw*/) const {
    return false;
  }
  /// Whether a model with this element iterates with modified Newton under the default policy
  /// whatever its size (NewtonOptions::uses_modified): an element whose tangent costs several
  /// residuals and changes little from one step to the next, so that the iterations modified
  /// Newton adds cost less than the tangents it saves. Measured on every dynamic scene of inputs/
  /// (docs/performance.md, "Modified Newton by default"): true for a reduced body and for a motor
  /// whose law reads sensors; nullptr (the size decides) for every other element. Returns why,
  /// in words for the run's summary ("a reduced body, …").
  virtual const char* favours_modified_newton() const { return nullptr; }

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
  /// mass_action of an element without inertia (its residual does not depend on q̈): M w = 0.
  static bool no_mass_action(const Eigen::VectorXd& w, Eigen::VectorXd& Mw) {
    Mw.setZero(w.size());
    return true;
  }
  virtual std::unique_ptr<Element> clone() const = 0;

 private:
  std::string name_;
  std::vector<int> nodes_;
};

}  // namespace alphaflex
