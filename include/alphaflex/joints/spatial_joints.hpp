#pragma once
// Spatial joints between frames on R³×SO(3) (rigid bodies, beam nodes) or the ground, with
// position-level (index-3) constraints and one Lagrange multiplier per equation (design §5).
//
// Every joint is defined by two markers — frames fixed to node 1 and to node 2 (or the ground) —
// that coincide at the assembled position. With A = (p_A, a1, a2, a3) the marker on node 1 and
// B = (p_B, b1, b2, b3) the one on node 2, the joint axis is the third marker axis, and every joint
// equation is a sum of dot products of a1, a2, a3, b1, b2, b3, d = p_B − p_A and the world axes
// e_x, e_y, e_z (e.g. revolute: e_x·d, e_y·d, e_z·d, a3·b1, a3·b2). The joint types are the rows of
// one table, spatial_joint_kinds() (spatial_joints.cpp): name, equations, scene keys and drivers.
// The constraint evaluation (Φ, and by AD Φ_q, Φ_t, the acceleration term), the closed-form
// geometric stiffness, the equation count and the equation names all read that table, so adding a
// joint type is one row there.
// Drivers (prescribed motion as a time function) add to a joint whose row allows it the angle
// ϕ of node 1's marker relative to node 2's about the axis, a1·(cos φ(t) b2 − sin φ(t) b1) =
// sin(ϕ − φ(t)) = 0, and the translation of node 1's marker relative to node 2's along the axis,
// (p_A − p_B)·b3 − u(t) = 0 — body1 moving relative to body2 (usually the ground), as a user reads
// "crank driven at angle φ(t)". They are equations of the same form with a time-dependent weight.
// Φ_q, the geometric stiffness ∂(Φ_qᵀλ)/∂q, Φ_t and the acceleration term are exact derivatives
// of these equations (model/spatial_kernel.hpp); they are checked against finite differences.
//
// Reactions: the force and moment the joint exerts on node 1, F = −(Φ_qᵀλ)_x (world) and, about
// the joint point p_A, M = R₁(−(Φ_qᵀλ)_θ) − (p_A − x₁) × F, reported in the frame of marker A.
#include <string>
#include <vector>

#include "alphaflex/core/time_function.hpp"
#include "alphaflex/model/constraint.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

// SpatialMarker (a frame fixed to a joint's node or the ground) is in model/spatial_kernel.hpp,
// shared with the spatial force elements.

/// The vectors joint equations are written in: the axes of marker A (node 1) and of marker B
/// (node 2 or the ground), d = p_B − p_A, and the fixed world axes.
enum class MarkerVector : unsigned char { a1, a2, a3, b1, b2, b3, d, e_x, e_y, e_z };

/// coefficient · (u·v).
struct SpatialJointTerm {
  MarkerVector u, v;
  double coefficient = 1.0;
};

/// One joint equation, Σ coefficient · (u·v) = 0, and its name in messages and output ("a3·b1";
/// "x", "y", "z" for e_x·d, e_y·d, e_z·d: the components of p_B − p_A).
struct SpatialJointEquation {
  std::vector<SpatialJointTerm> terms;
  std::string name;
};
/// u·v, named after its vectors.
SpatialJointEquation dot(MarkerVector u, MarkerVector v);
/// Sums and multiples of equations (the name follows: "a1·b2 + a2·b1", "−b3·d").
SpatialJointEquation operator+(SpatialJointEquation f, const SpatialJointEquation& g);
SpatialJointEquation operator*(double c, SpatialJointEquation f);

/// A joint type: one row of spatial_joint_kinds().
struct SpatialJointKind {
  enum Keys : unsigned { no_keys = 0, axis = 1, axis2 = 2, reference = 4 };
  enum Drivers : unsigned { no_drivers = 0, angle = 1, displacement = 2 };
  /// A row with its names and count filled in; throws std::logic_error on an equation without
  /// terms, a product of two world axes (a constant) or two equations of the same name.
  static SpatialJointKind make(std::string name, std::string doc, std::vector<SpatialJointEquation> equations,
                               unsigned keys, unsigned drivers);

  std::string name;  ///< the scene's `type`, and Constraint::type()
  std::string doc;   ///< one line: the relative motion it allows
  std::vector<SpatialJointEquation> equations;
  std::vector<std::string> equation_names;  ///< equations[k].name
  bool needs_axis = false;           ///< scene key `axis` (a3; the joint frame of a marker otherwise)
  bool needs_axis2 = false;          ///< scene key `axis2` (a2, with a1 = axis: universal)
  bool takes_reference = false;      ///< scene key `reference` (a1 with an axis, the frame without)
  bool angle_driver = false;         ///< driver `angle` (rotation about a3)
  bool displacement_driver = false;  ///< driver `displacement` (translation along a3)
  int num_equations = 0;             ///< equations.size(), without drivers
};

/// Every spatial joint type, in the order of the scene reader's messages.
const std::vector<SpatialJointKind>& spatial_joint_kinds();
/// The row named `name`, nullptr if there is none.
const SpatialJointKind* find_spatial_joint_kind(const std::string& name);
/// "spherical, universal, …": the names of the rows, for messages.
std::string spatial_joint_kind_names();

class SpatialJoint final : public Constraint {
 public:
  /// `nodes` are the joint's spatial nodes (one or two); the markers refer to them by slot.
  /// `kind` must outlive the joint (the rows of spatial_joint_kinds() do); a driver the row does
  /// not allow throws std::invalid_argument.
  SpatialJoint(std::string name, std::vector<int> nodes, const SpatialJointKind& kind, SpatialMarker a,
               SpatialMarker b, TimeFunctionPtr angle = nullptr, TimeFunctionPtr displacement = nullptr);

  const char* type() const override { return kind_->name.c_str(); }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<SpatialJoint>(*this); }
  const SpatialJointKind& kind() const { return *kind_; }
  int size() const override { return size_; }
  /// The row's equation names, then "angle" and "displacement" for the drivers.
  std::string equation_name(int k) const override;
  const SpatialMarker& marker_a() const { return a_; }
  const SpatialMarker& marker_b() const { return b_; }

  /// Φ, and Φ_q in closed form (the first derivatives of the marker vectors: spatial_joints.cpp).
  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  /// The same by forward AD of the equations (model/spatial_kernel.hpp): the check of the closed
  /// form in the tests.
  void evaluate_by_ad(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const;
  /// K_Φ = ∂(Φ_qᵀλ)/∂δ' in closed form (every equation is a sum of dot products of marker axes,
  /// d and world axes: spatial_joints.cpp), ~20× cheaper than nested AD.
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  /// The same by nested forward AD of the equations (model/spatial_kernel.hpp): the check of the
  /// closed form in the tests.
  void geometric_stiffness_by_ad(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                                 Eigen::MatrixXd& k) const;
  void time_derivative(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi_t) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                         Eigen::VectorXd& c) const override;
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

  /// The constraint equations Φ(frames, t) (the kernel of the derivatives above).
  template <class S>
  void operator()(const Pose<S>* frames, const S& t, KernelVector<S>& out) const;

 private:
  const SpatialJointKind* kind_;
  SpatialMarker a_, b_;
  TimeFunctionPtr angle_, displacement_;
  int size_;
  unsigned uses_ = 0;  // bit k: the equations (with drivers) use MarkerVector k
};

}  // namespace alphaflex
