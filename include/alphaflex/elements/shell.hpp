#pragma once
// Geometrically nonlinear Reissner–Mindlin shells with finite rotations: the 4-node MITC4 + EAS4
// quadrilateral and the 3-node MITC3 triangle (docs/theory/shell.md).
//
// Kinematics (degenerated solid with an inextensible director, Simo & Fox 1989; Betsch, Gruttmann
// & Stein 1996): the nodes are spatial frames (node.hpp) with pose (x_I, R_I); each element keeps
// its reference director at node I in the node's frame, D̄_I = R_I0ᵀ D_I, so that the current
// director is d_I = R_I D̄_I. Mid-surface and director are interpolated with the element's shape
// functions N_I(ξ, η): x̄ = Σ N_I x_I, d = Σ N_I d_I, and with a_α = x̄,α:
//   membrane   ε_αβ = ½ (a_α·a_β − A_α·A_β)
//   bending    κ_αβ = ½ (a_α·d,β + a_β·d,α) − (same in the reference)
//   shear      γ_α  = a_α·d − A_α·D          (assumed: MITC4, Dvorkin & Bathe 1984; MITC3, Lee & Bathe 2004)
// Green–Lagrange strains of a degenerated solid, linear through the thickness; small strain, linear
// (St. Venant–Kirchhoff) material given by its ABD matrices. Every strain component is a constant
// bilinear form in the nodal vectors U = (x_1 … x_n, d_1 … d_n): s = ½ Uᵀ Q U, the same Q for
// every element of a topology (natural coordinates). The element stores the constant matrix C_e
// that maps them to energy, W = ½ (s − s0)ᵀ C_e (s − s0), with the Cartesian transformation, the
// quadrature weights and the statically condensed EAS4 membrane modes (Andelfinger & Ramm 1993;
// exact condensation because W is quadratic in the enhanced parameters) folded in once. Then
//   r_U = Σ_k σ_k Q_k U,    σ = C_e (s − s0),
//   K_UU = Bᵀ C_e B + Σ_k σ_k Q_k,   B_k = (Q_k U)ᵀ,
// exactly, and the rotations enter through δd_I = −R_I D̄_I^ δθ_I (and its second derivative).
//
// Drilling rotation (about the director), which the kinematics above does not see, is tied to the
// element's in-plane rotation by a penalty on ω_I = ½ (t2_I·F e1 − t1_I·F e2) at each node, with
// t_k the element's reference in-plane axes carried by the node's rotation and F the mid-surface
// deformation gradient at the centre (objective; Hughes & Brezzi 1989 in spirit), stiffness
// drilling_factor · G t per unit area.
//
// Inertia: consistent translational mass ∫ ρt N_I N_J dA, consistent director (rotary) inertia
// ∫ (ρt³/12) N_I N_J ḋ_I·ḋ_J dA, and a lumped inertia about each director (the drilling rotation
// has none physically; drilling_inertia_factor × the node's rotary inertia) so that M is regular.
#include <Eigen/Dense>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "alphaflex/core/time_function.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {

/// Through-thickness properties of a shell, in its material axes (1, 2 in the surface, 3 normal).
/// Resultants: n = A ε + B κ (N/m), m = Bᵀ ε + D κ (N), q = As γ (N/m), with Voigt strains
/// ε = (ε11, ε22, 2ε12), κ = (κ11, κ22, 2κ12) (1/m), γ = (γ13, γ23).
struct ShellSection {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();  ///< membrane stiffness (N/m)
  Eigen::Matrix3d B = Eigen::Matrix3d::Zero();  ///< membrane–bending coupling (N)
  Eigen::Matrix3d D = Eigen::Matrix3d::Zero();  ///< bending stiffness (N·m)
  Eigen::Matrix2d As = Eigen::Matrix2d::Zero(); ///< transverse shear stiffness (N/m)
  double thickness = 0.0;   ///< t (m): stresses for output, drilling penalty
  double mass = 0.0;        ///< ρt, mass per area (kg/m²)
  double rotary = 0.0;      ///< ρt³/12, rotary inertia per area (kg)
  double shear_modulus = 0.0;  ///< G (Pa) for the drilling penalty (laminates: a mean value)
  bool homogeneous = false; ///< isotropic single layer (von Mises output is exact through t)

  /// Isotropic homogeneous plate: A = Et/(1−ν²) [[1, ν, 0], [ν, 1, 0], [0, 0, (1−ν)/2]],
  /// D = A t²/12, As = k G t I with k = 5/6. Throws std::invalid_argument for E, t ≤ 0, ρ < 0,
  /// ν outside (−1, ½).
  static ShellSection isotropic(double E, double nu, double rho, double thickness);
  /// General laminate. Throws std::invalid_argument unless [[A, B], [Bᵀ, D]] and As are
  /// symmetric positive definite and t > 0, mass ≥ 0, rotary ≥ 0.
  static ShellSection laminate(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B, const Eigen::Matrix3d& D,
                               const Eigen::Matrix2d& As, double thickness, double mass, double rotary);
};

/// How the bending strains see the turn of the director between nodes (docs/theory/shell.md).
///  linear:   d,α of the linearly interpolated director d = Σ N_I d_I; a turn φ between two nodes
///            is seen as the chord 2 sin(φ/2), the curvature of a rolled strip is underestimated
///            by O(φ²).
///  geodesic: each edge's chord d_J − d_I replaced by the geodesic (great-circle) difference, the
///            chord's direction with the arc length φ: the derivative at the edge midpoint of the
///            geodesic interpolation of the two directors on S² (Sander 2012, Sander, Neff &
///            Bîrsan 2016; for a beam, the relative-rotation curvature of Crisfield & Jelenić
///            1999), so that a constant curvature is exact (κ = φ/L_e). Objective, path
///            independent, identical in the linear range.
enum class DirectorInterpolation { linear, geodesic };

/// How the element measures its edges: the stretches its membrane strains are tied to, and the
/// tangents of its bending and shear strains (docs/theory/shell.md, "Arc membrane edges").
///  chord: the distance between the nodes, |x_J − x_I|. A flat element bent by a turn φ between
///         its nodes' directors, without stretching its mid-surface, sees its chord shorten by
///         1 − sin(φ/2)/(φ/2) ≈ φ²/24: a membrane strain that resists bending (2.9 % at 48°).
///  arc:   the length of the circular arc through the nodes whose end normals are the directors,
///         h(p) |x_J − x_I| with √p = |(d_J − d_I)·ĉ| = 2 sin(φ/2), h = φ/(2 sin(φ/2)): inextensible
///         bending leaves the membrane unstrained at any turn per element (in the manner of the
///         helicoidal interpolation of beams, Borri & Bottasso 1994). Identical to the chord to
///         O(φ²) for a turn φ per element, objective, path independent.
enum class MembraneEdges { chord, arc };

struct ShellOptions {
  double drilling_factor = 1e-3;          ///< drilling stiffness / (G t), per area
  double drilling_inertia_factor = 1.0;   ///< drilling inertia / the node's rotary inertia
  bool eas = true;                        ///< EAS4 membrane modes (quadrilaterals)
  DirectorInterpolation director_interpolation = DirectorInterpolation::linear;  ///< bending strains
  MembraneEdges membrane_edges = MembraneEdges::chord;                          ///< edges: membrane, tangents
};

/// The geodesic distance φ = 2 asin(c/2) between two unit vectors over their chord c = |d_J − d_I|,
/// h(q) = φ/c as a function of q = c², and its derivatives dh/dq, d²h/dq² (smooth at q = 0:
/// h = 1 + q/24 + 3q²/640 + …). The geodesic difference of the directors is h(|Δ|²) Δ, Δ = d_J − d_I.
struct ArcOverChord {
  double h = 1.0, dh = 0.0, d2h = 0.0;
};
ArcOverChord arc_over_chord(double q);

/// A 4-node (MITC4 + EAS4) or 3-node (MITC3) shell element (header comment).
class ReissnerMindlinShell final : public Element {
 public:
  static constexpr int kMaxNodes = 4;

  /// `nodes` (3 or 4, counter-clockwise about the normal), their reference poses, the element's
  /// reference directors at its nodes (unit, world components, on the side of the element normal
  /// (X2 − X1) × (X3 − X1)), the material axis 1 (world; projected onto the element's tangent
  /// plane at its centre), gravity (m/s²). Throws std::invalid_argument for repeated nodes, a
  /// degenerate or inverted element (Jacobian ≤ 0 at a quadrature point), a director more than
  /// 60° from the element normal, or a material axis along the normal.
  ReissnerMindlinShell(std::string name, std::vector<int> nodes, const ShellSection& section,
                       const std::vector<Pose<double>>& reference, const std::vector<Eigen::Vector3d>& directors,
                       const Eigen::Vector3d& material_axis, const Eigen::Vector3d& gravity,
                       const ShellOptions& options = {});

  const char* type() const override { return nodes().size() == 4 ? "shell_quad4" : "shell_tri3"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<ReissnerMindlinShell>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override;

  /// Drawn as a quadrilateral or a triangle (its nodes, counter-clockwise about the normal) in the
  /// results' "shells" grid.
  const char* structure() const override { return "shell"; }
  OutputCell output_cell() const override;
  /// {n11, n22, n12, m11, m22, m12, q1, q2, von_mises_top, von_mises_bottom}, scalars: resultants
  /// at the element centre in its material axes (N/m, N·m/m, N/m) and the von Mises stress (Pa) at
  /// ζ = ±t/2 from σ = n/t ± 6 m/t² (plane stress; exact for a homogeneous section).
  std::vector<CellField> cell_fields() const override;
  void output(const LocalState& s, Eigen::VectorXd& values) const override;
  /// values[8], values[9] (von Mises stress on the top and bottom faces, Pa) from the resultants
  /// values[0 … 5] of a layer of thickness t: σ = n/t ± 6 m/t². Also used on resultants recovered
  /// from a reduced body's modes, whose von Mises stress is not an odd function of the amplitudes
  /// (model/mesh_reconstruction.hpp).
  static void von_mises_from_resultants(Eigen::VectorXd& values, double t);

  /// Elastic energy W (J) and its exact derivatives r = ∂W/∂δ, K = ∂r/∂δ' (spatial_kernel.hpp's
  /// convention) at the configuration q (7 per node).
  double elastic_energy(const Eigen::VectorXd& q) const override;
  void elastic_forces(const Eigen::VectorXd& q, Eigen::VectorXd& r, Eigen::MatrixXd* K = nullptr) const;
  /// elastic_forces without K: evaluate()'s residual at rest (v = q̈ = 0, no load), bit for bit.
  bool internal_force(const Eigen::VectorXd& q, Eigen::VectorXd& r) const override {
    elastic_forces(q, r);
    return true;
  }

  /// Reference area (m²), centre frame (columns: material axis 1, axis 2, normal).
  double area() const { return area_; }
  const Eigen::Matrix3d& frame() const { return frame_; }
  const ShellSection& section() const { return section_; }

 private:
  /// U = (x_1 … x_n, d_1 … d_n, E_1 … E_m, Y_1 … Y_k) (rows) and the nodes' rotations at q; the E_e
  /// are the geodesic differences of the directors along the element's edges (geodesic
  /// interpolation only), the Y_e the edges' arc vectors (membrane_edges: arc only).
  void nodal_vectors(const Eigen::VectorXd& q, Eigen::MatrixXd& U, std::array<Eigen::Matrix3d, kMaxNodes>& R) const;

  int n_ = 0;                 // nodes
  int m_ = 0;                 // edges whose geodesic director difference the bending strains use (0: linear)
  int k_ = 0;                 // edges whose arc vector the membrane strains use (0: chord)
  ShellSection section_;
  ShellOptions options_;
  std::array<Eigen::Vector3d, kMaxNodes> dbar_;   // D̄_I = R_I0ᵀ D_I
  std::shared_ptr<const std::vector<Eigen::MatrixXd>> forms_;  // the strain forms Q_k (header)
  Eigen::MatrixXd C_;         // energy matrix on the natural strain forms (EAS condensed)
  Eigen::VectorXd s0_;        // natural strain forms in the reference
  Eigen::MatrixXd T_;         // per quadrature point (stacked 8 × 8): natural → Cartesian strains
  Eigen::MatrixXd EasOut_;    // per quadrature point (stacked 8 × 4): enhanced strain per EAS parameter
  Eigen::MatrixXd Hinv_Lt_;   // α = Hinv_Lt_ (s − s0), the condensed EAS parameters
  Eigen::MatrixXd S_;         // section stiffness on (ε, κ, γ), 8 × 8
  std::vector<double> wj_;    // quadrature weight × Jacobian
  Eigen::MatrixXd mass_;      // ∫ N_I N_J dA (n × n)
  std::array<double, kMaxNodes> drill_k_{};       // drilling penalty per node (N·m)
  std::array<std::array<Eigen::Vector3d, kMaxNodes>, kMaxNodes> drill_g_;  // g_IJ (header)
  std::array<double, kMaxNodes> drill_w0_{};
  Eigen::Vector3d g_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d frame_ = Eigen::Matrix3d::Identity();
  double area_ = 0.0;
};

/// Pressure on a shell element's surface, p (Pa, a time function × load factor). Positive p
/// pushes against the element normal (right-hand rule of the node order), as in Abaqus.
/// Follower: along the current normal, per current area (r = +p ∫ N_I a_1 × a_2 dξdη, K exact
/// and unsymmetric). Fixed: along the reference normal, per reference area (a dead load).
class ShellPressure final : public Element {
 public:
  ShellPressure(std::string name, std::vector<int> nodes, const std::vector<Eigen::Vector3d>& reference_points,
                TimeFunctionPtr pressure, bool follower);
  const char* type() const override { return "pressure"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<ShellPressure>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState&, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override {
    return no_mass_action(w, Mw);
  }

 private:
  int n_ = 0;
  TimeFunctionPtr p_;
  bool follower_;
  std::array<Eigen::Vector3d, ReissnerMindlinShell::kMaxNodes> fixed_;  // ∫ N_I n dA in the reference
};

/// Reference directors for the elements of a shell surface: at each node the mean of the unit
/// normals of the elements around it, unless an element's normal there is more than `kink_angle`
/// (rad) away from that mean (a fold), in which case that element keeps its own normal.
/// `elements` are node index lists (3 or 4, oriented consistently). Returns, per element, the
/// director at each of its nodes.
std::vector<std::vector<Eigen::Vector3d>> shell_directors(const std::vector<Eigen::Vector3d>& points,
                                                          const std::vector<std::vector<int>>& elements,
                                                          double kink_angle);

}  // namespace alphaflex
