#pragma once
// The planar geometrically exact (Reissner 1972, Simo 1985) beam as a two-node element on SE(2),
// the planar restriction of the SE(3) beam (Sonneville, Cardona & Brüls, Comput. Methods Appl.
// Mech. Engrg. 268, 2014; geometrically_exact_beam.hpp). Theory and measured numbers:
// docs/theory/planar_beam.md.
//
// Nodes: two RigidBody2D nodes A, B with unknowns (x, y, θ) on a vector space (θ additive, never
// wrapped). The section angle at end i is α_i = θ_i + φ_i with a constant offset
// φ_i = (section angle at i in the reference) − θ_i0, so that a node may be shared by elements at
// an angle, or be a rigid body's centre of mass whose angle is not the section's.
//
// Strain (SE(2) strain measure): with H_i = (R(α_i), x_i) ∈ SE(2),
//   d = log_SE(2)(H_A⁻¹ H_B) = (U1, U2, Δθ),  Δθ = α_B − α_A  (no wrapping: additive here),
//   p = R(α_A)ᵀ (x_B − x_A) = V(Δθ) U,  V(α) = [[sin α/α, −(1 − cos α)/α], [(1 − cos α)/α, sin α/α]],
//   ε = (d − d0)/L0 = (axial strain, shear strain, curvature),
// where d0 is d in the reference and L0 = |U0| the reference arc length (the chord of a straight
// element). Since V(α) = sinc(α/2) R(α/2) (a rotation by half the angle times a stretch),
//   U = g(Δθ) R(ᾱ)ᵀ (x_B − x_A),  ᾱ = (α_A + α_B)/2,  g(α) = (α/2)/sin(α/2):
// the chord in the frame of the mean section, lengthened from chord to arc. ε is constant on the
// element, the strain of the unique constant-strain (circular-arc) beam through the two end frames:
// objective, exact for every constant-strain state, and free of shear locking (the shear strain is
// the chord's tilt relative to the mean section).
//
// Residual (element.hpp: r = M q̈ − g, internal forces positive), with f = C ε = (N, V, M) and
// B = ∂d/∂q (3 × 6):
//   W = (L0/2) εᵀ C ε,  C = diag(EA, GA, EI),
//   r = ∂W/∂q + M q̈ − f_gravity = Bᵀ f + M q̈ − f_gravity,
//   K = ∂r/∂q = Bᵀ C B / L0 + Σ_k f_k ∂²d_k/∂q²   (analytic, exact; see planar_beam.cpp),
//   M = consistent mass of linear interpolation: ρA L0/6 [[2, 1], [1, 2]] on (x_A, x_B) and on
//       (y_A, y_B), ρI L0/6 [[2, 1], [1, 2]] on (θ_A, θ_B); constant, so C = ∂r/∂q̇ = 0 (planar
//       rotary inertia has no gyroscopic term),
//   gravity: −ρA L0/2 g on each node's (x, y), times LocalState::load_factor.
//
// Material damping (Kelvin–Voigt, as the SE(3) beam; docs/theory/beam.md, Material damping): with
// η > 0 the section forces are f = C (ε + η ε̇), ε̇ = B q̇ / L0 (objective: ε is invariant
// under rigid motions, so ε̇ = 0 along every one), so that r gains Bᵀ η C ε̇, C_t = ∂r/∂q̇ = η Bᵀ C B / L0 and K gains
// η Bᵀ C (∂B/∂q q̇) / L0 besides the geometric term Σ_k f_k ∂²d_k/∂q² of the whole f.
//
// Limitations: g has a pole at |Δθ| = 2π; the reference must have |Δθ0| < π (checked; use shorter
// elements for tighter curves) and the deformed element must keep |Δθ| well below 2π.
#include <memory>
#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "alphaflex/core/autodiff.hpp"
#include "alphaflex/model/element.hpp"

namespace alphaflex {

class PlanarBeam final : public Element {
 public:
  /// `state_a`, `state_b`: the nodes' (x, y, θ) in the reference (stress-free) configuration;
  /// `section_angle_a`, `section_angle_b`: the angles of the sections' axis 1 (along the beam) at
  /// the two ends in that configuration (for a straight element, the chord's direction); stiffnesses
  /// EA, GA (shear, the shear coefficient included), EI in N, N, N·m²; mass per length ρA (kg/m) and
  /// rotary inertia per length ρI (kg·m); `gravity` in m/s². Throws std::invalid_argument for a
  /// non-positive or non-finite property, equal node ids, non-finite states or angles, a zero
  /// reference length, or end sections turned by π or more relative to each other.
  /// `damping`: η ≥ 0 (s), the Kelvin–Voigt material damping (header comment).
  PlanarBeam(std::string name, int node_a, int node_b, double EA, double GA, double EI, double rhoA, double rhoI,
             const Eigen::Vector3d& state_a, const Eigen::Vector3d& state_b, double section_angle_a,
             double section_angle_b, const Eigen::Vector2d& gravity, double damping = 0.0);

  const char* type() const override { return "beam"; }
  std::unique_ptr<Element> clone() const override { return std::make_unique<PlanarBeam>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  bool mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const override;

  /// Drawn as a line segment between its nodes in the results' "beams" grid.
  const char* structure() const override { return "beam"; }
  OutputCell output_cell() const override { return {CellShape::line, {0, 1}}; }
  /// {N, V, M, axial_strain, shear_strain, curvature}, scalars: section forces C ε (N, N, N·m;
  /// C (ε + η ε̇) with material damping) and
  /// strains ε, constant on the element, in the section frame.
  std::vector<CellField> cell_fields() const override;
  void output(const LocalState& s, Eigen::VectorXd& values) const override;

  /// ε at the local configuration q = (x_A, y_A, θ_A, x_B, y_B, θ_B).
  Eigen::Vector3d strain(const Eigen::VectorXd& q) const { return strain_of<double>(q.data()); }
  /// W = (L0/2) εᵀ C ε (J).
  double elastic_energy(const Eigen::VectorXd& q) const override;

  /// ε for any scalar (tests differentiate it with automatic differentiation).
  template <class S>
  Eigen::Matrix<S, 3, 1> strain_of(const S* q) const {
    using std::cos;
    using std::sin;
    const S aA = q[2] + S(offset_[0]), aB = q[5] + S(offset_[1]);
    const S dth = aB - aA, mean = S(0.5) * (aA + aB);
    const S dx = q[3] - q[0], dy = q[4] - q[1];
    const S c = cos(mean), s = sin(mean), g = lengthening_of(dth);
    Eigen::Matrix<S, 3, 1> e;
    e[0] = g * (c * dx + s * dy) / S(L0_) - S(eps0_[0]);
    e[1] = g * (c * dy - s * dx) / S(L0_) - S(eps0_[1]);
    e[2] = dth / S(L0_) - S(eps0_[2]);
    return e;
  }

  double reference_length() const { return L0_; }
  /// d0/L0: the strain measure of the reference configuration ((1, 0, κ0) for a reference arc).
  const Eigen::Vector3d& reference_strain() const { return eps0_; }
  /// φ_i (end 0 = A, 1 = B): the section angle at end i is θ_i + φ_i.
  double section_offset(int end) const { return offset_[static_cast<size_t>(end)]; }
  /// (EA, GA, EI).
  const Eigen::Vector3d& stiffness() const { return c_; }
  double rhoA() const { return rhoA_; }
  double rhoI() const { return rhoI_; }
  /// η (s), the material damping.
  double damping() const { return eta_; }
  const Eigen::Vector2d& gravity() const { return g_; }

  /// g(α) = (α/2)/sin(α/2) (the arc-to-chord ratio of a circular arc turning by α) and its
  /// derivatives g', g'': Taylor series of G(h) = h/sin h, h = α/2, for |α| < kSeriesBelow (exact
  /// at α = 0), closed forms elsewhere.
  static void lengthening(double a, double& g, double& dg, double& ddg);

  /// Taylor coefficients of G(h) = h/sin h = Σ c_n h^{2n}, c_n = (−1)^{n+1} 2(2^{2n−1} − 1) B_2n/(2n)!
  /// (B_2n Bernoulli numbers; radius of convergence π): 1, 1/6, 7/360, 31/15120, 127/604800,
  /// 73/3421440, 1414477/653837184000, 8191/37362124800, 16931177/762187345920000,
  /// 5749691557/2554547108585472000, 91546277357/401428831349145600000,
  /// 3324754717/143888775912161280000. Used for |α| < kSeriesBelow (h < 1/2), where the next term
  /// changes g'' by less than 1e-15 relative; the closed forms lose about 12 ε there (cancellation
  /// in sin h − h cos h), so g, g', g'' are accurate to a few ε everywhere.
  static constexpr int kSeriesTerms = 12;
  static constexpr double kSeries[kSeriesTerms] = {1.0,
                                                   1.0 / 6.0,
                                                   7.0 / 360.0,
                                                   31.0 / 15120.0,
                                                   127.0 / 604800.0,
                                                   73.0 / 3421440.0,
                                                   1414477.0 / 653837184000.0,
                                                   8191.0 / 37362124800.0,
                                                   16931177.0 / 762187345920000.0,
                                                   5749691557.0 / 2554547108585472000.0,
                                                   91546277357.0 / 401428831349145600000.0,
                                                   3324754717.0 / 143888775912161280000.0};
  static constexpr double kSeriesBelow = 1.0;

 private:
  /// g(α) for any scalar (double, AD1, AD2), as lengthening() does for double.
  template <class S>
  static S lengthening_of(const S& a) {
    using std::sin;
    const S h = a / S(2);
    if (std::abs(ad::value(a)) < kSeriesBelow) {
      const S x = h * h;
      S G = S(kSeries[kSeriesTerms - 1]);
      for (int n = kSeriesTerms - 2; n >= 0; --n) G = S(kSeries[n]) + x * G;
      return G;
    }
    return h / sin(h);
  }

  Eigen::Vector3d c_;
  double rhoA_, rhoI_;
  double eta_ = 0.0;
  std::array<double, 2> offset_{};
  double L0_ = 0.0;
  Eigen::Vector3d eps0_ = Eigen::Vector3d::Zero();
  Eigen::Vector2d g_;
};

}  // namespace alphaflex
