#pragma once
// Cross-section properties of a beam (SI units), in the section frame: axis 1 along the beam, axes
// 2 and 3 in the section (docs/theory/beam.md). A scene gives them either directly or from a
// homogeneous isotropic material and one of three shapes.
//
// Conventions: I2 = ∫ x3² dA and I3 = ∫ x2² dA are the second moments of area about axes 2 and 3,
// so EI2 resists curvature about axis 2 (deflection along axis 3) and EI3 curvature about axis 3
// (deflection along axis 2); GA2, GA3 are the effective shear stiffnesses k G A (the shear
// coefficient k included) for shear strain along axes 2 and 3; J is the torsion constant
// (GJ = torsional stiffness), not the polar moment of area. Mass per length ρA (kg/m) and mass
// moments of area per length ρI2, ρI3 (kg·m) about axes 2 and 3; the polar one about axis 1 is
// ρI2 + ρI3 (a plane section) unless given.
#include <Eigen/Dense>
#include <optional>

namespace alphaflex {

/// The geometry of a solid or hollow section, in metres.
struct SectionShape {
  enum class Kind { Rectangle, Circle, Tube };
  Kind kind = Kind::Circle;
  double width = 0.0;           ///< rectangle: side along axis 2 (b)
  double height = 0.0;          ///< rectangle: side along axis 3 (h)
  double diameter = 0.0;        ///< circle: diameter; tube: outer diameter
  double wall_thickness = 0.0;  ///< tube only (up to diameter/2, the solid circle)

  static SectionShape rectangle(double width, double height);
  static SectionShape circle(double diameter);
  static SectionShape tube(double outer_diameter, double wall_thickness);
};

/// Area properties of a shape (m², m⁴).
struct SectionGeometry {
  double area = 0.0;     ///< A
  double I2 = 0.0;       ///< ∫ x3² dA
  double I3 = 0.0;       ///< ∫ x2² dA
  double torsion = 0.0;  ///< torsion constant J (Saint-Venant)
};

/// A, I2, I3, J of a shape; throws std::invalid_argument for non-positive or inconsistent sizes.
///   rectangle b × h:  A = bh, I2 = bh³/12, I3 = hb³/12,
///                     J = a c³ [1/3 − (64/π⁵)(c/a) Σ_{n odd} tanh(nπa/(2c))/n⁵], a = max(b, h),
///                     c = min(b, h) (Saint-Venant's series, Timoshenko & Goodier, Theory of
///                     Elasticity, 3rd ed., §109; Roark's Formulas for Stress and Strain, Table 10.7)
///   circle d:         A = πd²/4, I2 = I3 = πd⁴/64, J = πd⁴/32 (polar moment)
///   tube Do, t:       A = π(Ro² − Ri²), I2 = I3 = π(Ro⁴ − Ri⁴)/4, J = π(Ro⁴ − Ri⁴)/2, Ri = Ro − t
SectionGeometry section_geometry(const SectionShape& shape);

/// Timoshenko shear coefficient k of Cowper (1966, J. Appl. Mech. 33, 335–340, Table 1), for
/// Poisson's ratio ν ∈ (−1, 0.5):
///   rectangle: 10(1 + ν)/(12 + 11ν);   circle: 6(1 + ν)/(7 + 6ν);
///   tube (m = Ri/Ro): 6(1 + ν)(1 + m²)² / [(7 + 6ν)(1 + m²)² + (20 + 12ν)m²],
///   which is the circle at m = 0 and the thin tube 2(1 + ν)/(4 + 3ν) at m → 1.
double cowper_shear_coefficient(const SectionShape& shape, double nu);

/// Stiffness and inertia of a section per unit length.
class BeamSection {
 public:
  /// Every value given (N, N, N, N·m², N·m², N·m², kg/m, kg·m, kg·m, kg·m); all must be positive
  /// and finite. `rhoI_polar` defaults to rhoI2 + rhoI3.
  static BeamSection from_properties(double EA, double GA2, double GA3, double GJ, double EI2, double EI3,
                                     double rhoA, double rhoI2, double rhoI3,
                                     std::optional<double> rhoI_polar = std::nullopt);
  /// A homogeneous isotropic material (Young's modulus E in Pa, Poisson's ratio ν ∈ (−1, 0.5),
  /// density ρ in kg/m³) and a shape: G = E/(2(1 + ν)), EA, GA2 = GA3 = kGA with Cowper's k, GJ,
  /// EI2, EI3, ρA, ρI2, ρI3.
  static BeamSection from_material(double E, double nu, double rho, const SectionShape& shape);

  double EA() const { return c_[0]; }
  double GA2() const { return c_[1]; }
  double GA3() const { return c_[2]; }
  double GJ() const { return c_[3]; }
  double EI2() const { return c_[4]; }
  double EI3() const { return c_[5]; }
  double rhoA() const { return rhoA_; }
  double rhoI2() const { return rhoI2_; }
  double rhoI3() const { return rhoI3_; }
  double rhoI_polar() const { return rhoIp_; }

  /// diag(EA, GA2, GA3, GJ, EI2, EI3): section forces (N, V2, V3, T, M2, M3) = C ε for the strains
  /// (axial, shear 2, shear 3, twist, curvature 2, curvature 3).
  const Eigen::Matrix<double, 6, 1>& stiffness() const { return c_; }
  /// J̄ = diag(ρI_polar, ρI2, ρI3): the rotary inertia per length in the section frame.
  Eigen::Matrix3d rotary_inertia() const { return Eigen::Vector3d(rhoIp_, rhoI2_, rhoI3_).asDiagonal(); }

 private:
  BeamSection() = default;
  Eigen::Matrix<double, 6, 1> c_ = Eigen::Matrix<double, 6, 1>::Zero();
  double rhoA_ = 0.0, rhoI2_ = 0.0, rhoI3_ = 0.0, rhoIp_ = 0.0;
};

}  // namespace alphaflex
