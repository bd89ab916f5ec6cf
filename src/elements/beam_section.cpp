#include "alphaflex/elements/beam_section.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace alphaflex {

namespace {

constexpr double kPi = 3.14159265358979323846;

/// Throws unless x is finite and positive (NaN fails the comparison too).
void require_positive(double x, const char* what) {
  if (!(std::isfinite(x) && x > 0.0)) {
    std::ostringstream m;
    m << what << " must be positive and finite (got " << x << ")";
    throw std::invalid_argument(m.str());
  }
}

/// Saint-Venant's torsion constant of a rectangle with long side a and short side c:
/// J = a c³ [1/3 − (64/π⁵)(c/a) Σ_{n odd} tanh(nπa/(2c))/n⁵] (Timoshenko & Goodier §109). The
/// terms fall like n⁻⁵ (tanh ≤ 1): 500 odd terms leave a remainder below 1e-13 of the sum.
double rectangle_torsion(double a, double c) {
  double sum = 0.0;
  for (int k = 0; k < 500; ++k) {
    const double n = 2.0 * k + 1.0;
    sum += std::tanh(n * kPi * a / (2.0 * c)) / std::pow(n, 5);
  }
  return a * c * c * c * (1.0 / 3.0 - 64.0 / std::pow(kPi, 5) * (c / a) * sum);
}

}  // namespace

SectionShape SectionShape::rectangle(double width, double height) {
  require_positive(width, "rectangle width (along section axis 2)");
  require_positive(height, "rectangle height (along section axis 3)");
  SectionShape s;
  s.kind = Kind::Rectangle;
  s.width = width;
  s.height = height;
  return s;
}

SectionShape SectionShape::circle(double diameter) {
  require_positive(diameter, "circle diameter");
  SectionShape s;
  s.kind = Kind::Circle;
  s.diameter = diameter;
  return s;
}

SectionShape SectionShape::tube(double outer_diameter, double wall_thickness) {
  require_positive(outer_diameter, "tube outer diameter");
  require_positive(wall_thickness, "tube wall thickness");
  if (wall_thickness > 0.5 * outer_diameter) {
    std::ostringstream m;
    m << "tube wall thickness " << wall_thickness << " exceeds the outer radius " << 0.5 * outer_diameter;
    throw std::invalid_argument(m.str());
  }
  SectionShape s;
  s.kind = Kind::Tube;
  s.diameter = outer_diameter;
  s.wall_thickness = wall_thickness;
  return s;
}

SectionGeometry section_geometry(const SectionShape& shape) {
  SectionGeometry g;
  switch (shape.kind) {
    case SectionShape::Kind::Rectangle: {
      const double b = shape.width, h = shape.height;
      require_positive(b, "rectangle width (along section axis 2)");
      require_positive(h, "rectangle height (along section axis 3)");
      g.area = b * h;
      g.I2 = b * h * h * h / 12.0;  // ∫ x3² dA, x3 across the height
      g.I3 = h * b * b * b / 12.0;  // ∫ x2² dA, x2 across the width
      g.torsion = rectangle_torsion(std::max(b, h), std::min(b, h));
      break;
    }
    case SectionShape::Kind::Circle: {
      const double d = shape.diameter;
      require_positive(d, "circle diameter");
      g.area = kPi * d * d / 4.0;
      g.I2 = g.I3 = kPi * std::pow(d, 4) / 64.0;
      g.torsion = 2.0 * g.I2;  // no warping: J is the polar moment
      break;
    }
    case SectionShape::Kind::Tube: {
      const SectionShape checked = SectionShape::tube(shape.diameter, shape.wall_thickness);
      const double ro = 0.5 * checked.diameter, ri = ro - checked.wall_thickness;
      g.area = kPi * (ro * ro - ri * ri);
      g.I2 = g.I3 = kPi * (std::pow(ro, 4) - std::pow(ri, 4)) / 4.0;
      g.torsion = 2.0 * g.I2;  // closed circular section: no warping
      break;
    }
  }
  return g;
}

double cowper_shear_coefficient(const SectionShape& shape, double nu) {
  if (!(nu > -1.0 && nu < 0.5)) {
    std::ostringstream m;
    m << "Poisson's ratio must lie in (-1, 0.5) (got " << nu << ")";
    throw std::invalid_argument(m.str());
  }
  switch (shape.kind) {
    case SectionShape::Kind::Rectangle:
      return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
    case SectionShape::Kind::Circle:
      return 6.0 * (1.0 + nu) / (7.0 + 6.0 * nu);
    case SectionShape::Kind::Tube: {
      const double ro = 0.5 * shape.diameter, ri = ro - shape.wall_thickness;
      const double m = ri / ro, p = (1.0 + m * m) * (1.0 + m * m);
      return 6.0 * (1.0 + nu) * p / ((7.0 + 6.0 * nu) * p + (20.0 + 12.0 * nu) * m * m);
    }
  }
  return 0.0;  // unreachable: every kind is handled above
}

BeamSection BeamSection::from_properties(double EA, double GA2, double GA3, double GJ, double EI2, double EI3,
                                         double rhoA, double rhoI2, double rhoI3, std::optional<double> rhoI_polar) {
  require_positive(EA, "EA");
  require_positive(GA2, "GA2");
  require_positive(GA3, "GA3");
  require_positive(GJ, "GJ");
  require_positive(EI2, "EI2");
  require_positive(EI3, "EI3");
  require_positive(rhoA, "rhoA");
  require_positive(rhoI2, "rhoI2");
  require_positive(rhoI3, "rhoI3");
  if (rhoI_polar) require_positive(*rhoI_polar, "rhoI_polar");
  BeamSection s;
  s.c_ << EA, GA2, GA3, GJ, EI2, EI3;
  s.rhoA_ = rhoA;
  s.rhoI2_ = rhoI2;
  s.rhoI3_ = rhoI3;
  s.rhoIp_ = rhoI_polar ? *rhoI_polar : rhoI2 + rhoI3;
  return s;
}

BeamSection BeamSection::from_material(double E, double nu, double rho, const SectionShape& shape) {
  require_positive(E, "Young's modulus E");
  require_positive(rho, "density rho");
  const double k = cowper_shear_coefficient(shape, nu);  // validates ν
  const SectionGeometry g = section_geometry(shape);     // validates the sizes
  const double G = E / (2.0 * (1.0 + nu));
  return from_properties(E * g.area, k * G * g.area, k * G * g.area, G * g.torsion, E * g.I2, E * g.I3, rho * g.area,
                         rho * g.I2, rho * g.I3);
}

}  // namespace alphaflex
