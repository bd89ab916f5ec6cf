#include "alphaflex/elements/spatial_force_elements.hpp"

#include <cmath>

#include "alphaflex/core/error.hpp"

namespace alphaflex {

// ---- ScalarForceLaw -------------------------------------------------------------------------------

ScalarForceLaw ScalarForceLaw::linear(double stiffness, double damping, double rest, double preload) {
  ScalarForceLaw l;
  l.kind_ = Kind::linear;
  l.k_ = stiffness;
  l.c_ = damping;
  l.rest_ = rest;
  l.preload_ = preload;
  return l;
}

ScalarForceLaw ScalarForceLaw::table(TimeFunctionPtr force_of_deflection, double damping, double rest) {
  ScalarForceLaw l;
  l.kind_ = Kind::table;
  l.table_ = std::move(force_of_deflection);
  l.c_ = damping;
  l.rest_ = rest;
  return l;
}

ScalarForceLaw ScalarForceLaw::expression(std::shared_ptr<const ExpressionFunction> f, double rest) {
  if (!f || f->variables().size() != 3) throw std::logic_error("ScalarForceLaw::expression: needs 3 variables");
  ScalarForceLaw l;
  l.kind_ = Kind::expression;
  l.expression_ = std::move(f);
  l.rest_ = rest;
  return l;
}

void ScalarForceLaw::evaluate(double x, double rate, double t, double& f, double& f_x, double& f_rate) const {
  const double dx = x - rest_;
  switch (kind_) {
    case Kind::linear:
      f = k_ * dx + c_ * rate + preload_;
      f_x = k_;
      f_rate = c_;
      return;
    case Kind::table:
      f = table_->value(dx) + c_ * rate;
      f_x = table_->derivative(dx);
      f_rate = c_;
      return;
    case Kind::expression: {
      const double vars[3] = {dx, rate, t};
      double g[3];
      f = expression_->value(vars, g);
      f_x = g[0];
      f_rate = g[1];
      return;
    }
  }
}

double ScalarForceLaw::potential(double x) const {
  if (kind_ != Kind::linear) return 0.0;
  const double dx = x - rest_;
  return 0.5 * k_ * dx * dx + preload_ * dx;
}

// ---- SpatialSpringDamper --------------------------------------------------------------------------

namespace {

/// ε = |p_B − p_A| of a spring's markers.
struct SpringLength {
  const SpatialMarker& a;
  const SpatialMarker& b;
  template <class S>
  void operator()(const Pose<S>* frames, CoordinateValues<S>& eps) const {
    using std::sqrt;
    const Vec3<S> d = b.pose(frames).x - a.pose(frames).x;
    eps.resize(1);
    eps[0] = sqrt(d.squaredNorm());
  }
};

}  // namespace

SpatialSpringDamper::SpatialSpringDamper(std::string name, std::vector<int> nodes, SpatialMarker a, SpatialMarker b,
                                         ScalarForceLaw law)
    : Element(std::move(name), std::move(nodes)), a_(std::move(a)), b_(std::move(b)), law_(std::move(law)) {}

double SpatialSpringDamper::length(const Eigen::VectorXd& q) const {
  return coordinate_values(SpringLength{a_, b_}, q)[0];
}

void SpatialSpringDamper::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  // The length's derivatives are those of a norm: undefined where the points coincide.
  const double L = length(s.q);
  if (!(L > 1e-12 * std::max(1.0, std::fabs(law_.rest()))))
    throw ConfigurationError("spring_damper '" + name() + "': its two points coincide (length " + std::to_string(L) +
                             " m), so its force has no direction");
  const auto law = [this](const CoordinateVector& eps, const CoordinateVector& rate, const LocalState& st,
                          GeneralizedForce& g) {
    g.f.resize(1);
    g.f_eps.resize(1, 1);
    g.f_rate.resize(1, 1);
    law_.evaluate(eps[0], rate[0], st.t, g.f[0], g.f_eps(0, 0), g.f_rate(0, 0));
  };
  evaluate_coordinate_force(SpringLength{a_, b_}, law, s, out, tangent);
}

std::vector<CellField> SpatialSpringDamper::cell_fields() const {
  return {{"length", 1}, {"elongation", 1}, {"rate", 1}, {"tension", 1}};
}

void SpatialSpringDamper::output(const LocalState& s, Eigen::VectorXd& values) const {
  // L̇ = e·(ṗ_B − ṗ_A), the point velocities ẋ + R (Ω × s) of the markers.
  const auto p = kernel_detail::poses(s.q, kernel_detail::frames_in(s.q));
  const auto point = [&](const SpatialMarker& m, Eigen::Vector3d& x, Eigen::Vector3d& xd) {
    x = m.pose(p.data()).x;
    xd.setZero();
    if (m.slot < 0) return;
    const Pose<double>& f = p[static_cast<size_t>(m.slot)];
    xd = s.v.segment<3>(6 * m.slot) + f.R * s.v.segment<3>(6 * m.slot + 3).cross(m.position);
  };
  Eigen::Vector3d xa, va, xb, vb;
  point(a_, xa, va);
  point(b_, xb, vb);
  const double L = (xb - xa).norm();
  const double rate = L > 0.0 ? (xb - xa).dot(vb - va) / L : 0.0;
  double f, fx, fv;
  law_.evaluate(L, rate, s.t, f, fx, fv);
  values.resize(4);
  values << L, L - law_.rest(), rate, f;
}

double SpatialSpringDamper::elastic_energy(const Eigen::VectorXd& q) const { return law_.potential(length(q)); }

// ---- Bushing --------------------------------------------------------------------------------------

Bushing::Bushing(std::string name, std::vector<int> nodes, SpatialMarker a, SpatialMarker b, const Matrix6& stiffness,
                 const Matrix6& damping)
    : Element(std::move(name), std::move(nodes)), a_(std::move(a)), b_(std::move(b)), k_(stiffness), c_(damping) {}

namespace {
/// Bushing::coordinates as a functor of the coordinate-force kernels.
auto coordinates_of(const Bushing& b) {
  return [&b](const auto* frames, auto& eps) { b.coordinates(frames, eps); };
}
}  // namespace

void Bushing::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  const auto law = [this](const CoordinateVector& eps, const CoordinateVector& rate, const LocalState&,
                          GeneralizedForce& g) {
    g.f = k_ * eps + c_ * rate;
    g.f_eps = k_;
    g.f_rate = c_;
  };
  evaluate_coordinate_force(coordinates_of(*this), law, s, out, tangent);
}

std::vector<CellField> Bushing::cell_fields() const { return {{"deflection", 6}, {"force", 6}}; }

void Bushing::output(const LocalState& s, Eigen::VectorXd& values) const {
  // ε̇ = J_ε v from the same kernel as the residual (the residual's r is Jᵀ f, not needed here).
  LocalResidual probe;
  probe.reset(static_cast<int>(s.v.size()), false);
  CoordinateVector eps, rate;
  const auto law = [&](const CoordinateVector& e, const CoordinateVector& r, const LocalState&, GeneralizedForce& g) {
    eps = e;
    rate = r;
    g.f = CoordinateVector::Zero(6);
  };
  evaluate_coordinate_force(coordinates_of(*this), law, s, probe, false);
  values.resize(12);
  values.head<6>() = eps;
  values.tail<6>() = k_ * eps + c_ * rate;
}

double Bushing::elastic_energy(const Eigen::VectorXd& q) const {
  const CoordinateVector eps = coordinate_values(coordinates_of(*this), q);
  return 0.5 * eps.dot(k_ * eps);
}

}  // namespace alphaflex
