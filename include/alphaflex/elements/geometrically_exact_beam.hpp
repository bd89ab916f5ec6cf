#pragma once
// The geometrically exact (Simo–Reissner) beam as a two-node element on SE(3) (Sonneville,
// Cardona & Brüls, Comput. Methods Appl. Mech. Engrg. 268, 2014; docs/theory/beam.md).
//
// Nodes: two Frame3D nodes A, B (node.hpp), pose (x_i, R_i), unknowns δx (world) and δθ (body).
// The section frame at end i is R_i O_i with a constant offset O_i = R_i0ᵀ R_sec,i fixed in the
// reference configuration, so that node frames (e.g. a rigid body's principal axes) need not be
// section frames. Section axes: 1 along the beam, 2 and 3 in the section (beam_section.hpp).
//
// Strain (Sonneville et al. 2014, Sec. 4): with H_i = (R_i O_i, x_i) ∈ SE(3),
//   d = log_SE(3)(H_A⁻¹ H_B) = (U, θ),  θ = log_SO(3)(O_Aᵀ R_Aᵀ R_B O_B),
//   p = O_Aᵀ R_Aᵀ (x_B − x_A) = J_l(θ) U,  J_l(θ) = T(θ)ᵀ (rotation.hpp),
//   ε = (d − d0)/L0 = (axial, shear 2, shear 3, twist, curvature 2, curvature 3),
// where d0 is d in the reference and L0 = |U0| is the reference arc length (the chord of a straight
// element). ε is constant on the element: it is the strain of the unique constant-strain (helical)
// beam through the two end frames, hence objective, exact for every constant-strain state (pure
// bending, torsion, helices) and free of shear locking (the shear strain is the chord's tilt
// relative to the mean section, not an interpolated field).
//
// Residual (convention of element.hpp, r = M q̈ − g with internal forces positive):
//   r = ∂W/∂δ + r_inertia − r_gravity,   W = (L0/2) εᵀ C ε,  C = diag(EA, GA2, GA3, GJ, EI2, EI3).
// The elastic part is computed in closed form, r_el = Bᵀ f with f = C ε (section forces) and
// B = ∂d/∂δ: a perturbation δ_i of node i moves its section frame by the SE(3) twist
// ξ_i = P_i δ_i, P_i = diag((R_i O_i)ᵀ, O_iᵀ), and log(exp(−ξ_A) exp(d) exp(ξ_B)) =
// d + T_SE(3)(d)⁻¹ (ξ_B − Ad(H_AB⁻¹) ξ_A) + O(ξ²) (core/se3.hpp), so that with
// g = T_SE(3)(d)⁻ᵀ f = (g_U, g_θ) (the section forces carried to the twist of the relative motion):
//   r_el,B = (R_B O_B g_U,  O_B g_θ),
//   r_el,A = −P_Aᵀ Ad(H_AB⁻¹)ᵀ g = (−R_B O_B g_U,  −O_A (p × R_rel g_U + R_rel g_θ)).
// The tangent K = ∂r_el/∂δ' is the exact first derivative of that residual on the group by
// forward AD (kernel_jacobian of a 12-output kernel, spatial_kernel.hpp). The same r and K are
// also available as nested-AD derivatives of W (elastic_forces_from_energy, the reference the
// tests compare with: equal to round-off); the closed form costs ~1/25 of it (docs/theory/beam.md,
// Cost).
//
// Inertia (consistent, with rotary inertia; velocities interpolated linearly, N_A = 1 − s/L0,
// N_B = s/L0):
//   translation: r_x,i = Σ_j ρA L0 m_ij ẍ_j,  m = [[1/3, 1/6], [1/6, 1/3]];
//   rotation:    Ω̄_i = O_iᵀ Ω_i (section components), Ω̄(s) = N_A Ω̄_A + N_B Ω̄_B,
//                r̄_i = ∫₀^L0 N_i (J̄ Ω̄̇(s) + Ω̄(s) × J̄ Ω̄(s)) ds,  r_θ,i = O_i r̄_i,
//                J̄ = diag(ρI_polar, ρI2, ρI3) (BeamSection::rotary_inertia),
// integrated exactly (the integrand is a cubic in s: 2-point Gauss). M and C are exact.
// Approximation: Ω̄_A and Ω̄_B are components in two different section frames; interpolating them
// as if both ends shared one frame ignores the element's relative rotation θ. The error is
// O(|θ|) = O(L0 κ) and vanishes under mesh refinement; for a rigid motion of a straight element
// (θ = 0) the kinetic energy is exact.
//
// Material damping (Kelvin–Voigt, stiffness-proportional in the section; docs/theory/beam.md,
// Material damping): with η = damping() > 0 the section forces are f = C (ε + η ε̇),
// ε̇ the objective rate of the strain measure,
//   ε̇ = B_ε v,  B_ε = ∂ε/∂δ = T_SE(3)(d)⁻¹ [−Ad(H_AB⁻¹) P_A, P_B] / L0,
// (the derivative of d above along the nodes' velocities v = (ẋ_A, Ω_A, ẋ_B, Ω_B)), so that
// r_d = L0 B_εᵀ η C ε̇, C_t = ∂r/∂v = η L0 B_εᵀ C B_ε and K gains the derivative of B_εᵀ C ε̇ in q
// at fixed v (the AD1 Jacobian of the same closed-form kernel with the velocities as constants).
// It dissipates L0 η ε̇ᵀ C ε̇ ≥ 0 and vanishes for every rigid motion (ε̇ = 0).
//
// Gravity: lumped consistently for the linear interpolation, −ρA L0/2 g on each node's translation,
// times the load factor.
//
// Limitation: log_SO(3) is continuous for |θ| < π; the element's relative rotation between its end
// sections must stay below π (refine the mesh well before).
#include <memory>
#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/core/se3.hpp"
#include "alphaflex/elements/beam_section.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

class GeometricallyExactBeam final : public Element {
 public:
  using Vector6d = Eigen::Matrix<double, 6, 1>;

  /// `pose_a`, `pose_b`: the nodes' poses in the reference (stress-free) configuration;
  /// `section_a`, `section_b`: the section frames at the two ends in that configuration (world
  /// components, column 1 along the beam axis); `gravity` in m/s². Throws std::invalid_argument for
  /// equal node ids, section frames that are not rotations, a zero reference length, or a relative
  /// rotation between the end sections of π or more; `damping`: η ≥ 0 (s), the Kelvin–Voigt material
  /// damping (header comment; a negative or non-finite η throws too).
  GeometricallyExactBeam(std::string name, int node_a, int node_b, const BeamSection& section,
                         const Pose<double>& pose_a, const Pose<double>& pose_b, const Eigen::Matrix3d& section_a,
                         const Eigen::Matrix3d& section_b, const Eigen::Vector3d& gravity, double damping = 0.0);

  const char* type() const override { return "beam"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<GeometricallyExactBeam>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  /// M w: the consistent translational mass and the sections' rotary inertia (add_inertia), which do
  /// not depend on q.
  bool mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override;

  /// Drawn as a line segment between its nodes in the results' "beams" grid.
  const char* structure() const override { return "beam"; }
  OutputCell output_cell() const override { return {CellShape::line, {0, 1}}; }
  /// {N, V2, V3, T, M2, M3, axial_strain, shear_strain_2, shear_strain_3, twist, curvature_2,
  /// curvature_3}, scalars: section forces C ε (N, N·m; C (ε + η ε̇) with material damping) and strains ε, constant on the element,
  /// section frame.
  std::vector<CellField> cell_fields() const override;
  void output(const LocalState& s, Eigen::VectorXd& values) const override;

  /// ε at the configuration q (14 numbers: two poses).
  Vector6d strain(const Eigen::VectorXd& q) const;
  /// W = (L0/2) εᵀ C ε (J).
  double elastic_energy(const Eigen::VectorXd& q) const override;
  /// r_el at q (elastic_forces without K): evaluate()'s residual at rest (v = q̈ = 0, no load),
  /// bit for bit, without the inertia and damping terms.
  bool internal_force(const Eigen::VectorXd& q, Eigen::VectorXd& r) const override {
    elastic_forces(q, r);
    return true;
  }

  /// ε at the given poses of nodes A and B; instantiated for double, ad::FixedAD1<12> and
  /// ad::FixedAD2<12> (spatial_kernel.hpp).
  template <class S>
  Vec6<S> strain_of(const Pose<S>& a, const Pose<S>& b) const;

  /// r_el = ∂W/∂δ = Bᵀ C ε at the given poses, in closed form (header comment); instantiated for
  /// double and ad::FixedAD1<12>.
  template <class S>
  Eigen::Matrix<S, 12, 1> elastic_residual_of(const Pose<S>& a, const Pose<S>& b) const {
    return section_residual_of<S>(a, b, nullptr);
  }
  /// Bᵀ f with f = C (ε + η ε̇) (header comment): the elastic and material-damping residual at the
  /// given poses and the nodes' velocities v (12 numbers; nullptr: f = C ε, the elastic residual).
  template <class S>
  Eigen::Matrix<S, 12, 1> section_residual_of(const Pose<S>& a, const Pose<S>& b, const double* v) const;
  /// B_ε = ∂ε/∂δ at q (6 × 12), so that ε̇ = B_ε v (header comment, Material damping).
  Eigen::Matrix<double, 6, 12> strain_rate_operator(const Eigen::VectorXd& q) const;

  /// r_el and, if K is given, K_el = ∂r_el/∂δ' at q (14 numbers): the closed-form residual and its
  /// AD1 Jacobian (what evaluate() uses).
  void elastic_forces(const Eigen::VectorXd& q, Eigen::VectorXd& r, Eigen::MatrixXd* K = nullptr) const;
  /// The same as exact derivatives of W by nested AD (kernel_jacobian and kernel_second of W):
  /// the independent reference for the tests, about ten times slower.
  void elastic_forces_from_energy(const Eigen::VectorXd& q, Eigen::VectorXd& r, Eigen::MatrixXd* K = nullptr) const;

  const BeamSection& section() const { return section_; }
  /// η (s), the material damping.
  double damping() const { return eta_; }
  double reference_length() const { return L0_; }
  /// O_i = R_i0ᵀ R_sec,i (end 0 = A, 1 = B): the section frame at end i is R_i O_i.
  const Eigen::Matrix3d& section_offset(int end) const { return offset_[static_cast<size_t>(end)]; }
  /// d0/L0, the strain measure of the reference configuration (its curvature and twist).
  const Vector6d& reference_strain() const { return eps0_; }
  const Eigen::Vector3d& gravity() const { return g_; }

 private:
  void add_inertia(const LocalState& s, LocalResidual& out, bool tangent) const;

  BeamSection section_;
  std::array<Eigen::Matrix3d, 2> offset_;
  double L0_ = 0.0;
  double eta_ = 0.0;
  Vector6d eps0_ = Vector6d::Zero();
  Eigen::Vector3d g_ = Eigen::Vector3d::Zero();
};

}  // namespace alphaflex
