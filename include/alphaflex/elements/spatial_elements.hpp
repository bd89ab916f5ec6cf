#pragma once
// Spatial rigid bodies and applied loads on frames of R³×SO(3) (node.hpp). Unknowns per node:
// δx (world frame) and δθ (body frame); velocities ẋ and Ω (body angular velocity).
#include <array>

#include "alphaflex/core/time_function.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

/// Newton–Euler equations of a rigid body about its centre of mass (the node):
///   r = [ m (ẍ − g) ;  J Ω̇ + Ω × J Ω ]   (Brüls, Cardona & Arnold 2012, eq. 56)
/// with the inertia tensor J in the body frame. M = diag(m I, J), C = [0; Ω̂J − (JΩ)^], K = 0.
///
/// With an `offset` c (the centre of mass in the node frame; a body carried by a point that is not
/// its centre of mass, e.g. a rigid body welded to a mesh node of a reduced flexible body,
/// docs/theory/reduced_bodies.md "Rigid bodies inside a reduced body") the equations are those of
/// the same body about the node P, from the virtual work of its inertia and weight at
/// x_G = x + R c, δx_G = δx − R ĉ δθ:
///   r = [ m (ẍ_G − g) ;  J_P Ω̇ + Ω × J_P Ω + m c × Rᵀ(ẍ − g) ],  ẍ_G = ẍ + R (Ω̇ × c + Ω × (Ω × c)),
/// J_P = J + m (|c|² I − c cᵀ) (J about the centre, node axes), and
///   M = [m I, −m R ĉ; m ĉ Rᵀ, J_P],  C = [0, −m R ((Ω × c)^ + Ω̂ ĉ); 0, Ω̂ J_P − (J_P Ω)^],
///   K = [0, −m R â; 0, m ĉ (Rᵀ(ẍ − g))^],  a = Ω̇ × c + Ω × (Ω × c)
/// (δx world, δθ node frame, R → R exp(δθ̂)). c = 0 is the equations above (their code path).
class RigidBody3D final : public Element {
 public:
  RigidBody3D(std::string name, int node, double mass, const Eigen::Matrix3d& inertia, const Eigen::Vector3d& gravity,
              const Eigen::Vector3d& offset = Eigen::Vector3d::Zero());
  const char* type() const override { return "rigid_body"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<RigidBody3D>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override;
  /// No elastic force (zero): a reduction's internal-force differences skip the inertia terms.
  bool internal_force(const Eigen::VectorXd& q, Eigen::VectorXd& r) const override;
  double mass() const { return m_; }
  /// About the centre of mass, node axes.
  const Eigen::Matrix3d& inertia() const { return j_; }
  /// The centre of mass in the node frame (m).
  const Eigen::Vector3d& offset() const { return c_; }

 private:
  double m_;
  Eigen::Matrix3d j_;
  Eigen::Vector3d g_;
  Eigen::Vector3d c_;
};

/// A force applied at a point of a frame (position `point` in the node frame) and a moment, each
/// component a time function (N, N·m), either fixed in the world (dead load) or turning with the
/// node (follower load, components in the node frame). r = −(generalized force) × load factor;
/// K is the exact derivative (non-zero for a dead force at an offset point and for a dead moment,
/// whose generalized moment Rᵀ M turns with the body).
class SpatialLoad final : public Element {
 public:
  SpatialLoad(std::string name, int node, const Eigen::Vector3d& point, std::array<TimeFunctionPtr, 3> force,
              std::array<TimeFunctionPtr, 3> moment, bool follower);
  const char* type() const override { return "load"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<SpatialLoad>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }

  /// The residual kernel (model/spatial_kernel.hpp) at load factor `factor`.
  template <class S>
  void residual(const Pose<S>* frames, const S& t, double factor, KernelVector<S>& out) const;

 private:
  Eigen::Vector3d point_;
  std::array<TimeFunctionPtr, 3> force_, moment_;
  bool follower_;
};

}  // namespace alphaflex
