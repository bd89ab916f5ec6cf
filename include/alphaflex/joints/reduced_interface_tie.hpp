#pragma once
// The tie of an interface node to a reduced flexible body (docs/theory/reduced_bodies.md,
// "Interface points"): a Frame3D node B of the model held at the pose that the reduced body gives
// its block node a,
//   x_a = x_f + R_f (X_a + Φᵗ_a ξ),   R_a = R_f R̄_a exp((Φʳ_a ξ)^)
// (modal/superelement.hpp, ReducedBlock::node_pose; (x_f, R_f) the floating frame's node, ξ the
// elastic amplitudes, X_a, R̄_a the block node's pose in the frame at t = 0, Φᵗ_a, Φʳ_a its 6 rows
// of the basis), by the 6 equations of the fixed joint (joints/spatial_joints.cpp, row `fixed`)
// with marker A = (x_a, R_a) and marker B = the node's own frame:
//   x_B − x_a = 0  (3, world components),   a2·b3 = 0, a3·b1 = 0, a1·b2 = 0  (a_i = R_a e_i, b_i = R_B e_i),
// one Lagrange multiplier each. The three rotation equations are those of the fixed joint: they
// vanish to first order exactly when R_aᵀR_B = I near the identity, which holds at t = 0 (the node
// is made at the block node's pose) and throughout a small-strain motion.
//
// With the Craig–Bampton basis of an interface node its rows are [R_f0ᵀ 0; 0 I] on its own 6
// constraint coordinates and zero elsewhere (the constraint modes are unit there, the
// fixed-interface modes vanish), so the tie makes those coordinates the node's displacement and
// rotation relative to the frame, exactly.
//
// Derivatives: the equations depend on ξ only through z = [Φᵗ_a ξ; Φʳ_a ξ] (6 numbers, linear in
// ξ), so they are written as a kernel of B's and the frame's right-trivialized increments and z
// (18 variables), and chained to ξ exactly. Φ_z, needed at every Newton iteration, in closed form
// (reduced_interface_tie.cpp: the fixed joint's rows, ∂exp(ψ)/∂ψ by the right tangent operator
// T(ψ)); the second derivatives by fixed-size forward AD (first order, 18 variables) of that
// closed form at frames seeded as model/spatial_kernel.hpp's, ~18× cheaper than nested AD of the
// equations. Then:
// Φ_ξ = Φ_z S, K_Φ = Pᵀ H P with S = Φ_a (6 × m) and P = diag(I₁₂, S). Φ_q, the geometric stiffness
// ∂(Φ_qᵀλ)/∂δ' and the acceleration term are exact; they are checked against finite differences.
//
// With an offset (p, R_o) — a rigid body welded to the block node a, its own node B at the pose
// (x_a + R_a p, R_a R_o) it had relative to a at t = 0 (docs/theory/reduced_bodies.md, "Rigid
// bodies inside a reduced body") — marker A is that pose: the same 6 equations with x_a + R_a p and
// a_i = R_a R_o e_i; the Jacobian gains ∂(R_a p)/∂(δθ_f, ψ) and R_o's columns in place of e_i.
//
// Nodes, in order: B, the frame node, then the m scalar amplitude nodes (the local unknowns
// δx_B, δθ_B, δx_f, δθ_f, ξ). The joint sees plain data only (X_a, R̄_a, Φ_a), never a model.
// Method `rigid` is the same tie with m = 0.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "alphaflex/model/constraint.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

class ReducedInterfaceTie final : public Constraint {
 public:
  /// `tied`: the Frame3D node B; `frame`: the reduced body's frame node; `amplitudes`: its m scalar
  /// nodes (ξ); `position` X_a (m, frame axes), `rotation` R̄_a (the block node's frame in the
  /// floating frame), `shape` Φ_a (6 × m: δx in the frame's axes, then δθ in the node frame).
  /// Throws std::invalid_argument if the shape does not have 6 rows and one column per amplitude.
  /// `offset_position` p (m) and `offset_rotation` R_o: B's pose in the block node's frame (zero
  /// and identity: B is held at the block node itself).
  ReducedInterfaceTie(std::string name, int tied, int frame, const std::vector<int>& amplitudes, const Eigen::Vector3d& position,
                      const Eigen::Matrix3d& rotation, Eigen::MatrixXd shape,
                      const Eigen::Vector3d& offset_position = Eigen::Vector3d::Zero(),
                      const Eigen::Matrix3d& offset_rotation = Eigen::Matrix3d::Identity());

  const char* type() const override { return "reduced_interface_tie"; }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<ReducedInterfaceTie>(*this); }
  int size() const override { return 6; }
  /// "x", "y", "z", "a2·b3", "a3·b1", "a1·b2" (the fixed joint's names).
  std::string equation_name(int k) const override;
  int amplitudes() const { return static_cast<int>(shape_.cols()); }
  /// X_a (m, frame axes) and R̄_a: the tied point's pose in the floating frame at ξ = 0.
  const Eigen::Vector3d& position() const { return position_; }
  const Eigen::Matrix3d& rotation() const { return rotation_; }
  /// p (m, block node frame) and R_o: the tied node's pose relative to the block node.
  const Eigen::Vector3d& offset_position() const { return offset_position_; }
  const Eigen::Matrix3d& offset_rotation() const { return offset_rotation_; }

  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t, Eigen::VectorXd& c) const override;
  /// The load of the reduced body on node B (world), about x_B, in B's frame.
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

  /// The 6 equations at the poses of B and the frame and z = [Φᵗ_a ξ; Φʳ_a ξ], for any scalar.
  template <class S>
  void equations(const Pose<S>& b, const Pose<S>& f, const Vec3<S>& u, const Vec3<S>& psi, S* out) const {
    const Mat3<S> Rn = f.R * Mat3<S>(rotation_.template cast<S>() * exp_so3<S>(psi));  // the block node's R_a
    const Vec3<S> xa = f.x + f.R * (Vec3<S>(position_.template cast<S>()) + u) + Rn * Vec3<S>(offset_position_.template cast<S>());
    const Mat3<S> Ra = Rn * Mat3<S>(offset_rotation_.template cast<S>());
    const Vec3<S> d = b.x - xa;
    out[0] = d[0];
    out[1] = d[1];
    out[2] = d[2];
    out[3] = Ra.col(1).dot(b.R.col(2));
    out[4] = Ra.col(2).dot(b.R.col(0));
    out[5] = Ra.col(0).dot(b.R.col(1));
  }

 private:
  /// z = Φ_a ξ from the local configuration (the last m numbers); checks the size of q.
  Eigen::Matrix<double, 6, 1> z_of(const Eigen::VectorXd& q) const;

  Eigen::Vector3d position_;
  Eigen::Matrix3d rotation_;
  Eigen::MatrixXd shape_;
  Eigen::Vector3d offset_position_;
  Eigen::Matrix3d offset_rotation_;
};

}  // namespace alphaflex
