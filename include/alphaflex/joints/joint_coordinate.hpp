#pragma once
// The coordinate of a spatial joint as an unknown of the model: the relative angle of a revolute
// (or cylindrical) joint, unwrapped over any number of turns, or the relative displacement of a
// prismatic (or cylindrical) joint. Joint springs, dampers and motors act on it
// (elements/joint_coordinate_force.hpp) and the joint sensors read it.
//
// Why an unknown rather than an angle computed from the frames: the frames give the angle only
// modulo 2π (modulo 4π from the quaternions), so unwrapping it would need a turn count kept from
// step to step — state outside q that checkpoints, step cuts, restarts and every rank would have to
// carry. A scalar node ψ (NodeKind::LineParticle2D, massless) tied to the joint by one equation
// carries the unwrapped value in q itself, so all of that holds by construction (the integrator
// restores q on a step cut, the checkpoint stores q, the ghost copies follow q). Cost: one unknown
// and one multiplier per joint that has a spring, motor or sensor. The multiplier is then the
// generalized force on the coordinate (the torque or force the spring or motor passes to the
// bodies).
//
// Equations, with the joint's markers A (node 1) and B (node 2 or the ground), as the drivers of
// joints/spatial_joints.hpp define the joint's angle and displacement:
//   rotation:     a1·(cos ψ b2 − sin ψ b1) = sin(ϕ − ψ) = 0,  ϕ the angle of A relative to B about b3;
//   translation:  (p_A − p_B)·b3 − ψ = 0;
// and the two angles of a universal joint (the cross turns about a1 in body 1 and about b2 in body
// 2; the relative rotation is R_Bᵀ R_A = R_y(ψ2) R_x(ψ1) in the joint frame, both angles those of
// body 1 relative to body 2 as for a revolute joint):
//   about a1 (1): −b2·(cos ψ a3 + sin ψ a2) = sin(ϕ1 − ψ) = 0,  ϕ1 = −atan2(a3·b2, a2·b2);
//   about b2 (2): −a1·(cos ψ b3 + sin ψ b1) = sin(ϕ2 − ψ) = 0,  ϕ2 = −atan2(a1·b3, a1·b1).
// Neither degenerates: the joint keeps a1 ⊥ b2, so b2 stays in the plane of a2, a3 and a1 in that
// of b1, b3 (unit projections), whatever the angles.
// Φ_q, the geometric stiffness and the acceleration term are exact: Φ_q in closed form (the first
// derivatives of marker axes and points, as joints/spatial_joints.cpp), the geometric stiffness by
// forward AD1 of that closed form at frames seeded as model/spatial_kernel.hpp's (ψ a 13th, or 7th,
// variable on a vector space), the acceleration term by AD along the motion. The `_by_ad` variants
// (forward and nested AD of the equation, the former implementation) check them in the tests.
#include "alphaflex/model/constraint.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

class JointCoordinateLink final : public Constraint {
 public:
  enum class Coordinate { rotation, translation, universal_axis, universal_axis2 };
  /// `nodes`: the joint's one or two spatial nodes, then the coordinate's scalar node; the markers'
  /// slots refer to the spatial nodes.
  JointCoordinateLink(std::string name, std::vector<int> nodes, SpatialMarker a, SpatialMarker b, Coordinate c);
  const char* type() const override { return "joint_coordinate"; }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<JointCoordinateLink>(*this); }
  int size() const override { return 1; }
  std::string equation_name(int) const override;
  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t, Eigen::VectorXd& c) const override;
  /// Φ and Φ_q by forward AD of the equation, and K_Φ by nested AD (the tests' check of the closed forms).
  void evaluate_by_ad(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const;
  void geometric_stiffness_by_ad(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda, Eigen::MatrixXd& k) const;
  /// The load on node 1 (world), about p_A, in the frame of marker A.
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

  /// The joint's coordinate from the frames alone (the angle in (−π, π]), at a stored configuration
  /// of the spatial nodes (7 numbers each): the initial value of ψ.
  double frame_value(const Eigen::VectorXd& q_frames) const;

  template <class S>
  S equation(const Pose<S>* frames, const S& psi) const {
    using std::cos;
    using std::sin;
    const Pose<S> A = a_.pose(frames), B = b_.pose(frames);
    switch (coordinate_) {
      case Coordinate::rotation: return A.R.col(0).dot(Vec3<S>(cos(psi) * B.R.col(1) - sin(psi) * B.R.col(0)));
      case Coordinate::universal_axis: return -B.R.col(1).dot(Vec3<S>(cos(psi) * A.R.col(2) + sin(psi) * A.R.col(1)));
      case Coordinate::universal_axis2: return -A.R.col(0).dot(Vec3<S>(cos(psi) * B.R.col(2) + sin(psi) * B.R.col(0)));
      case Coordinate::translation: break;
    }
    return (A.x - B.x).dot(B.R.col(2)) - psi;
  }

  /// ∂Φ/∂(δ, ψ) in closed form at any frame matrices (N = 6 frames + 1 variables, ψ last; defined
  /// and instantiated in joint_coordinate.cpp).
  template <int N, class S>
  Eigen::Matrix<S, 1, N> gradient(const Pose<S>* frames, const S& psi) const;

 private:
  int frames() const { return static_cast<int>(nodes().size()) - 1; }
  SpatialMarker a_, b_;
  Coordinate coordinate_;
};

}  // namespace alphaflex
