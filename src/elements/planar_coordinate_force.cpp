#include "alphaflex/elements/planar_coordinate_force.hpp"

#include <array>
#include <cmath>

#include "alphaflex/core/autodiff.hpp"

namespace alphaflex {
namespace {

using ad::AD2;

/// ε of the geometry g at the planar coordinates (x, y, θ) of A and B (the ground: zeros).
template <class S>
void planar_coordinate_values(const PlanarCoordinateForce::Geometry& g, const S* a, const S* b, std::vector<S>& e) {
  using std::cos;
  using std::sin;
  auto point = [](const S* q, const Eigen::Vector2d& s, S& px, S& py) {  // x + R(θ) s
    px = q[0] + cos(q[2]) * s.x() - sin(q[2]) * s.y();
    py = q[1] + sin(q[2]) * s.x() + cos(q[2]) * s.y();
  };
  switch (g.coordinates) {
    case PlanarCoordinateForce::Coordinates::bushing: {
      S ax, ay, bx, by;
      point(a, g.point_a, ax, ay);
      point(b, g.point_b, bx, by);
      const S phi = a[2] + g.alpha, dx = bx - ax, dy = by - ay;
      e = {cos(phi) * dx + sin(phi) * dy, -sin(phi) * dx + cos(phi) * dy, b[2] - a[2] - g.gamma0};
      return;
    }
    case PlanarCoordinateForce::Coordinates::rotation: e = {a[2] - b[2]}; return;
    case PlanarCoordinateForce::Coordinates::translation: {
      const S tx = cos(b[2]) * g.axis_b.x() - sin(b[2]) * g.axis_b.y(), ty = sin(b[2]) * g.axis_b.x() + cos(b[2]) * g.axis_b.y();
      e = {tx * (a[0] - b[0]) + ty * (a[1] - b[1])};
      return;
    }
  }
}

}  // namespace

PlanarCoordinateForce::PlanarCoordinateForce(std::string name, std::vector<int> nodes, const Geometry& g, const Eigen::Matrix3d& K,
                                             const Eigen::Matrix3d& C)
    : Element(std::move(name), std::move(nodes)), g_(g), K_(K), C_(C) {}

PlanarCoordinateForce::PlanarCoordinateForce(std::string name, std::vector<int> nodes, const Geometry& g, ScalarForceLaw law,
                                             bool motor, double eps0)
    : Element(std::move(name), std::move(nodes)), g_(g), law_(std::move(law)), motor_(motor), eps0_(eps0) {}

const char* PlanarCoordinateForce::type() const {
  if (g_.coordinates == Coordinates::bushing) return "bushing";
  return motor_ ? "joint_motor" : "joint_spring_damper";
}

void PlanarCoordinateForce::coordinates(const Eigen::VectorXd& q, Eigen::VectorXd& eps, Eigen::MatrixXd& J,
                                        std::vector<Eigen::MatrixXd>* H) const {
  const int n = static_cast<int>(q.size());
  // Each coordinate is an inner and an outer variable of the nested AD: value, gradient, Hessian.
  std::vector<AD2> x(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    ad::Derivatives2 d(n);
    for (int k = 0; k < n; ++k) d[k] = ad::constant1(k == i ? 1.0 : 0.0, n);
    x[static_cast<size_t>(i)] = AD2(ad::variable1(q[i], n, i), d);
  }
  std::array<AD2, 3> ground{ad::constant2(0.0, n, n), ad::constant2(0.0, n, n), ad::constant2(0.0, n, n)};
  const AD2* a = g_.body_a ? x.data() : ground.data();
  const AD2* b = g_.body_b ? x.data() + (g_.body_a ? 3 : 0) : ground.data();
  std::vector<AD2> e;
  planar_coordinate_values<AD2>(g_, a, b, e);
  const int m = static_cast<int>(e.size());
  eps.resize(m);
  J.resize(m, n);
  if (H) H->assign(static_cast<size_t>(m), Eigen::MatrixXd(n, n));
  for (int k = 0; k < m; ++k) {
    const AD2& ek = e[static_cast<size_t>(k)];
    eps[k] = ad::value(ek);
    for (int i = 0; i < n; ++i) J(k, i) = ad::inner_derivative(ek, i);
    if (H)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) (*H)[static_cast<size_t>(k)](j, i) = ad::mixed_derivative(ek, j, i);
  }
}

void PlanarCoordinateForce::law(const Eigen::VectorXd& eps, const Eigen::VectorXd& rate, double t, double load_factor,
                                Eigen::VectorXd& f, Eigen::MatrixXd& f_eps, Eigen::MatrixXd& f_rate) const {
  if (!law_) {
    f = K_ * eps + C_ * rate;
    f_eps = K_;
    f_rate = C_;
    return;
  }
  double v, v_x, v_rate;
  law_->evaluate(eps[0] - eps0_, rate[0], t, v, v_x, v_rate);
  // A motor is a load (−T, scaled by the load factor); a spring-damper is part of the mechanism.
  const double sign = motor_ ? -load_factor : 1.0;
  f = Eigen::VectorXd::Constant(1, sign * v);
  f_eps = Eigen::MatrixXd::Constant(1, 1, sign * v_x);
  f_rate = Eigen::MatrixXd::Constant(1, 1, sign * v_rate);
}

void PlanarCoordinateForce::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  Eigen::VectorXd eps, f;
  Eigen::MatrixXd J, f_eps, f_rate;
  std::vector<Eigen::MatrixXd> H;
  coordinates(s.q, eps, J, tangent ? &H : nullptr);
  const Eigen::VectorXd rate = J * s.v;
  law(eps, rate, s.t, s.load_factor, f, f_eps, f_rate);
  out.r += J.transpose() * f;
  if (!tangent) return;
  Eigen::MatrixXd D(J.rows(), J.cols());
  for (Eigen::Index k = 0; k < J.rows(); ++k) {
    out.K += f[k] * H[static_cast<size_t>(k)];
    D.row(k) = (H[static_cast<size_t>(k)] * s.v).transpose();
  }
  out.K += J.transpose() * (f_eps * J + f_rate * D);
  out.C += J.transpose() * f_rate * J;
}

double PlanarCoordinateForce::elastic_energy(const Eigen::VectorXd& q) const {
  if (motor_) return 0.0;
  Eigen::VectorXd eps;
  Eigen::MatrixXd J;
  coordinates(q, eps, J, nullptr);
  return law_ ? law_->potential(eps[0] - eps0_) : 0.5 * eps.dot(K_ * eps);
}

std::vector<CellField> PlanarCoordinateForce::cell_fields() const {
  if (!law_) return {{"deflection", 3}, {"force", 3}};
  return {{"coordinate", 1}, {"speed", 1}, {motor_ ? "drive" : "force", 1}};
}

void PlanarCoordinateForce::output(const LocalState& s, Eigen::VectorXd& values) const {
  Eigen::VectorXd eps, f;
  Eigen::MatrixXd J, f_eps, f_rate;
  coordinates(s.q, eps, J, nullptr);
  const Eigen::VectorXd rate = J * s.v;
  law(eps, rate, s.t, s.load_factor, f, f_eps, f_rate);
  values.resize(6);
  if (!law_) {
    values << eps, f;
    return;
  }
  values.resize(3);
  values << eps[0] - eps0_, rate[0], -f[0];
}

}  // namespace alphaflex
