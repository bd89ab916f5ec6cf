#pragma once
// Spatial joints between frames on R³×SO(3) (rigid bodies, beam nodes) or the ground, with
// position-level (index-3) constraints and one Lagrange multiplier per equation (design §5).
//
// Every joint is defined by two markers — frames fixed to node 1 and to node 2 (or the ground) —
// that coincide at the assembled position. With A = (p_A, a1, a2, a3) the marker on node 1 and
// B = (p_B, b1, b2, b3) the one on node 2, the joint axis is the third marker axis:
//   spherical    p_B − p_A = 0                                              3 equations
//   universal    p_B − p_A = 0,  a1·b2 = 0                                 4 (cross axes a1, b2)
//   revolute     p_B − p_A = 0,  a3·b1 = 0, a3·b2 = 0                      5 (axis a3)
//   cylindrical  a1·d = 0, a2·d = 0 (d = p_B − p_A), a3·b1 = 0, a3·b2 = 0   4 (axis a3)
//   prismatic    cylindrical and a1·b2 = 0                                  5 (axis a3)
//   planar       a3·d = 0,  a3·b1 = 0, a3·b2 = 0                            3 (plane ⊥ a3)
//   fixed        p_B − p_A = 0,  a2·b3 = 0, a3·b1 = 0, a1·b2 = 0            6 (clamp, rigid link)
//   point_on_line   a1·d = 0, a2·d = 0                                      2 (B's point on A's axis a3)
//   point_on_plane  a3·d = 0                                                1 (B's point in the plane ⊥ a3;
//                   with planar, the supports and symmetry conditions of shells and plates)
// Drivers (prescribed motion as a time function) add to a revolute or cylindrical joint the angle
// ϕ of node 1's marker relative to node 2's about the axis, a1·(cos φ(t) b2 − sin φ(t) b1) =
// sin(ϕ − φ(t)) = 0, and to a prismatic or cylindrical joint the translation of node 1's marker
// relative to node 2's along the axis, (p_A − p_B)·b3 − u(t) = 0 — body1 moving relative to
// body2 (usually the ground), as a user reads "crank driven at angle φ(t)".
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

/// A frame fixed to node `slot` of a joint (0 or 1 in the joint's node list; −1: the ground),
/// given by its position and rotation in the node's frame (world frame for the ground).
struct SpatialMarker {
  int slot = -1;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();

  template <class S>
  Pose<S> pose(const Pose<S>* frames) const {
    if (slot < 0) return cast_pose<S>(Pose<double>{position, rotation});
    const Pose<S>& f = frames[slot];
    return Pose<S>{f.x + f.R * position.template cast<S>(), f.R * rotation.template cast<S>()};
  }
};

enum class SpatialJointType { Spherical, Universal, Revolute, Cylindrical, Prismatic, Planar, Fixed, PointOnLine, PointOnPlane };
const char* to_string(SpatialJointType t);
/// Number of equations of a joint type without drivers.
int equations_of(SpatialJointType t);

class SpatialJoint final : public Constraint {
 public:
  /// `nodes` are the joint's spatial nodes (one or two); the markers refer to them by slot.
  SpatialJoint(std::string name, std::vector<int> nodes, SpatialJointType type, SpatialMarker a, SpatialMarker b,
               TimeFunctionPtr angle = nullptr, TimeFunctionPtr displacement = nullptr);

  const char* type() const override { return to_string(type_); }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<SpatialJoint>(*this); }
  SpatialJointType joint_type() const { return type_; }
  int size() const override { return size_; }
  const SpatialMarker& marker_a() const { return a_; }
  const SpatialMarker& marker_b() const { return b_; }

  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  /// K_Φ = ∂(Φ_qᵀλ)/∂δ' in closed form (every equation is a sum of dot products of marker axes,
  /// points and d: spatial_joints.cpp), ~20× cheaper than nested AD.
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
  SpatialJointType type_;
  SpatialMarker a_, b_;
  TimeFunctionPtr angle_, displacement_;
  int size_;
};

}  // namespace alphaflex
