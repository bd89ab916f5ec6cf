#include "alphaflex/elements/shell.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "alphaflex/core/rotation.hpp"

namespace alphaflex {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kStrains = 8;  // per quadrature point: 3 membrane, 3 bending, 2 transverse shear

Eigen::Matrix3d hat3(const Eigen::Vector3d& v) { return hat<double>(v); }

// ------------------------------------------------------------------ topologies (natural coordinates)

/// Shape functions and their natural derivatives at (ξ, η).
struct Shape {
  Eigen::VectorXd N, dN1, dN2;
};

Shape shape(int n, double xi, double eta) {
  Shape s;
  s.N.resize(n);
  s.dN1.resize(n);
  s.dN2.resize(n);
  if (n == 4) {
    static const double xs[4] = {-1, 1, 1, -1}, es[4] = {-1, -1, 1, 1};
    for (int I = 0; I < 4; ++I) {
      s.N[I] = 0.25 * (1 + xs[I] * xi) * (1 + es[I] * eta);
      s.dN1[I] = 0.25 * xs[I] * (1 + es[I] * eta);
      s.dN2[I] = 0.25 * es[I] * (1 + xs[I] * xi);
    }
  } else {
    s.N << 1 - xi - eta, xi, eta;
    s.dN1 << -1, 1, 0;
    s.dN2 << -1, 0, 1;
  }
  return s;
}

/// Natural coordinates of the nodes.
Eigen::Vector2d node_coordinates(int n, int I) {
  static const double q[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, t[3][2] = {{0, 0}, {1, 0}, {0, 1}};
  return n == 4 ? Eigen::Vector2d(q[I][0], q[I][1]) : Eigen::Vector2d(t[I][0], t[I][1]);
}

/// Edges (I → J) whose geodesic director differences E_e the bending strains use in the geodesic
/// interpolation: the quadrilateral's two edges along ξ (1→2, 4→3) and along η (1→4, 2→3), the
/// triangle's three edges.
constexpr int kQuadEdges[4][2] = {{0, 1}, {3, 2}, {0, 3}, {1, 2}};
constexpr int kTriEdges[3][2] = {{0, 1}, {0, 2}, {1, 2}};
int edge_node(int n, int e, int end) { return n == 4 ? kQuadEdges[e][end] : kTriEdges[e][end]; }

/// c(α, e): the director gradient d,α = Σ_e c(α, e) E_e at (ξ, η). With E_e = d_J − d_I this is the
/// linear interpolation's gradient exactly: the bilinear quadrilateral's d,ξ = ¼(1 − η)(d_2 − d_1) +
/// ¼(1 + η)(d_3 − d_4) (and d,η alike); the triangle's (d,r, d,s) is the least-squares fit to its
/// three edges, ⅓(2E_12 + E_13 − E_23, E_12 + 2E_13 + E_23), symmetric in the node order and equal to
/// (d_2 − d_1, d_3 − d_1) whenever E_23 = E_13 − E_12.
Eigen::MatrixXd edge_gradient(int n, double xi, double eta) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(2, n);
  if (n == 4) {
    c(0, 0) = 0.25 * (1 - eta);
    c(0, 1) = 0.25 * (1 + eta);
    c(1, 2) = 0.25 * (1 - xi);
    c(1, 3) = 0.25 * (1 + xi);
  } else {
    c << 2.0 / 3, 1.0 / 3, -1.0 / 3,  //
        1.0 / 3, 2.0 / 3, 1.0 / 3;
  }
  return c;
}

/// Quadrature: 2×2 Gauss on the square (exact for the bilinear products of the energy, the mass
/// and the EAS modes), the 3-point (edge-interior) rule on the triangle (exact for quadratics).
struct Quadrature {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> weights;
  std::vector<Shape> shapes;  ///< shape functions at the points (built once: no work per evaluation)
};

const Quadrature& quadrature(int n) {
  static const Quadrature quad = [] {
    Quadrature q;
    const double g = 1.0 / std::sqrt(3.0);
    for (double e : {-g, g})
      for (double x : {-g, g}) {
        q.points.emplace_back(x, e);
        q.weights.push_back(1.0);
        q.shapes.push_back(shape(4, x, e));
      }
    return q;
  }();
  static const Quadrature tri = [] {
    Quadrature q;
    q.points = {Eigen::Vector2d(1.0 / 6, 1.0 / 6), Eigen::Vector2d(2.0 / 3, 1.0 / 6), Eigen::Vector2d(1.0 / 6, 2.0 / 3)};
    q.weights = {1.0 / 6, 1.0 / 6, 1.0 / 6};
    for (const auto& p : q.points) q.shapes.push_back(shape(3, p[0], p[1]));
    return q;
  }();
  return n == 4 ? quad : tri;
}

/// The covariant strains as bilinear forms in U = (x_1 … x_n, d_1 … d_n, E_1 … E_n, Y_1 … Y_n):
/// s = ½ Σ_ab Q_ab U_a·U_b, E_e the geodesic edge differences of the directors and Y_e the edges'
/// arc vectors (n edges: 4 or 3; edge_arc_rows). Built at this full size; an element drops the rows
/// its options do not use (ReissnerMindlinShell).
using Form = Eigen::MatrixXd;

Form zero_form(int n) { return Form::Zero(4 * n, 4 * n); }

/// ½ w Y_e·Y_e: an edge's membrane stretch measured along its arc (membrane_edges: arc).
Form arc_edge_form(int n, int e, double w) {
  Form Q = zero_form(n);
  Q(3 * n + e, 3 * n + e) = w;
  return Q;
}

/// ε_αβ (2 × Voigt shear for α ≠ β): ½ (a_α·a_β) (× 2 for the shear entry).
Form membrane_form(const Shape& s, int n, int a, int b) {
  const Eigen::VectorXd& Da = a == 0 ? s.dN1 : s.dN2;
  const Eigen::VectorXd& Db = b == 0 ? s.dN1 : s.dN2;
  Form Q = zero_form(n);
  const double f = a == b ? 0.5 : 1.0;  // Voigt: 2ε12 = a1·a2
  for (int I = 0; I < n; ++I)
    for (int J = 0; J < n; ++J) Q(I, J) = f * (Da[I] * Db[J] + Db[I] * Da[J]);
  return Q;
}

/// κ_αβ = ½ (a_α·d,β + a_β·d,α) (Voigt: 2κ12 = a1·d,2 + a2·d,1), with d,α = Σ_J N_J,α d_J (linear)
/// or d,α = Σ_e c(α, e) E_e (geodesic: `geodesic` = edge_gradient at the point); a_α = Σ_I N_I,α x_I,
/// or with `arc` (= edge_gradient at the point) a_α = Σ_e c(α, e) Y_e, the same gradient of the
/// edges' arc vectors (the chords' gradient is a_α exactly, as for E_e = Δ_e above): the tangent
/// vectors that the membrane strains measure (membrane_edges: arc).
Form bending_form(const Shape& s, int n, int a, int b, const Eigen::MatrixXd* geodesic, const Eigen::MatrixXd* arc) {
  Form Q = zero_form(n);
  const double f = a == b ? 0.5 : 1.0;
  // the tangent a_α as Σ_i ta(α, i) over rows i (positions, or arc rows), d,α as Σ_j td(α, j)
  Eigen::MatrixXd dN(2, n);
  dN.row(0) = s.dN1.transpose();
  dN.row(1) = s.dN2.transpose();
  const Eigen::MatrixXd& ta = arc ? *arc : dN;
  const Eigen::MatrixXd& td = geodesic ? *geodesic : dN;
  const int row0 = arc ? 3 * n : 0, col0 = geodesic ? 2 * n : n;
  for (int I = 0; I < n; ++I)
    for (int J = 0; J < n; ++J) {
      // coefficient of (x_I or Y_I)·(d_J or E_J)
      const double c = f * (ta(a, I) * td(b, J) + ta(b, I) * td(a, J));
      Q(row0 + I, col0 + J) += c;
      Q(col0 + J, row0 + I) += c;
    }
  return Q;
}

/// γ_α = a_α·d at a point.
Form shear_form(const Shape& s, int n, int a) {
  const Eigen::VectorXd& Da = a == 0 ? s.dN1 : s.dN2;
  Form Q = zero_form(n);
  for (int I = 0; I < n; ++I)
    for (int J = 0; J < n; ++J) {
      Q(I, n + J) += Da[I] * s.N[J];
      Q(n + J, I) += Da[I] * s.N[J];
    }
  return Q;
}

/// The assumed transverse shear strains (γ_1, γ_2) at (ξ, η):
///  MITC4 (Dvorkin & Bathe 1984): tying points A(0, 1), B(−1, 0), C(0, −1), D(1, 0),
///    γ_ξ = ½(1 + η) γ_ξ^A + ½(1 − η) γ_ξ^C,   γ_η = ½(1 + ξ) γ_η^D + ½(1 − ξ) γ_η^B;
///  MITC3 (Lee & Bathe 2004): tangential strains at the edge midpoints (1) (½, 0), (2) (0, ½),
///    (3) (½, ½), with the field γ_r = a1 + c s, γ_s = a2 − c r: a1 = γ_r^(1), a2 = γ_s^(2) and
///    γ_s − γ_r at (3) equal to its tied value, c = γ_r^(3) − γ_s^(3) − γ_r^(1) + γ_s^(2).
/// Y_e·½(d_I + d_J): the tangential shear strain along edge e (I → J) at its midpoint, on the arc row
/// (membrane_edges: arc; on the chord c_e = x_J − x_I it is a_α·d at the tying point, a_α = c_e or ½c_e).
Form arc_shear_form(int n, int e, double w) {
  Form Q = zero_form(n);
  for (int end = 0; end < 2; ++end) {
    const int J = n + edge_node(n, e, end);
    Q(3 * n + e, J) += 0.5 * w;
    Q(J, 3 * n + e) += 0.5 * w;
  }
  return Q;
}

std::array<Form, 2> assumed_shear(int n, double xi, double eta, bool arc) {
  if (arc) {  // the same tied fields, on the edges' arc vectors (a_ξ = ½c_e at (0, ±1), a_η at (±1, 0))
    if (n == 4)
      return {0.5 * (1 + eta) * arc_shear_form(4, 1, 0.5) + 0.5 * (1 - eta) * arc_shear_form(4, 0, 0.5),
              0.5 * (1 + xi) * arc_shear_form(4, 3, 0.5) + 0.5 * (1 - xi) * arc_shear_form(4, 2, 0.5)};
    // γ_r(1) = c_0·d, γ_s(2) = c_1·d, γ_r(3) − γ_s(3) = −c_2·d (edge 2 = 2→3 = a_2 − a_1)
    const Form c = -arc_shear_form(3, 2, 1.0) - arc_shear_form(3, 0, 1.0) + arc_shear_form(3, 1, 1.0);
    return {arc_shear_form(3, 0, 1.0) + eta * c, arc_shear_form(3, 1, 1.0) - xi * c};
  }
  if (n == 4) {
    const Shape A = shape(4, 0, 1), B = shape(4, -1, 0), C = shape(4, 0, -1), D = shape(4, 1, 0);
    return {0.5 * (1 + eta) * shear_form(A, 4, 0) + 0.5 * (1 - eta) * shear_form(C, 4, 0),
            0.5 * (1 + xi) * shear_form(D, 4, 1) + 0.5 * (1 - xi) * shear_form(B, 4, 1)};
  }
  const Shape p1 = shape(3, 0.5, 0), p2 = shape(3, 0, 0.5), p3 = shape(3, 0.5, 0.5);
  const Form c = shear_form(p3, 3, 0) - shear_form(p3, 3, 1) - shear_form(p1, 3, 0) + shear_form(p2, 3, 1);
  return {shear_form(p1, 3, 0) + eta * c, shear_form(p2, 3, 1) - xi * c};
}

/// The 8 forms at one point: ε11, ε22, 2ε12, κ11, κ22, 2κ12, γ1, γ2 (natural, covariant). `X`: the
/// element's reference node positions (the quadrilateral's assumed membrane strains depend on its
/// geometry, below).
std::array<Form, kStrains> forms_at(int n, double xi, double eta, const Eigen::MatrixXd& X, bool geodesic, bool arc);

/// The quadrilateral's assumed membrane strains, against membrane locking in curved shells:
/// ε11 tied at the edge midpoints (0, ±1), ε22 at (±1, 0), ε12 at the centre (as the MITC4 shear,
/// Dvorkin & Bathe 1984; the constant ε12 also removes the in-plane parasitic shear), plus a
/// correction that restores the patch test on distorted elements: for a homogeneous strain Ē the
/// covariant components A_α(P)·Ē·A_β(P) vary over a non-parallelogram, and the tying would miss
/// that variation; adding f(P) − ANS[f](P) with f_αβ(P) = A_α(P)·Ē·A_β(P) and Ē the strain at the
/// centre makes every homogeneous deformation exact, and vanishes on parallelograms.
/// `arc`: the tied values ε11(0, ±1) = ⅛|x_2 − x_1|², ⅛|x_3 − x_4|² and ε22(±1, 0) are the edges'
/// stretches; they are measured along the edges' arcs, ⅛|Y_e|² (edge_arc_rows), instead of their
/// chords. The correction f − ANS[f] stays on the chords: it vanishes on parallelograms and
/// concerns the reference geometry only.
std::array<Form, 3> assumed_membrane(double xi, double eta, const Eigen::MatrixXd& X, bool arc) {
  auto plain = [](double x, double e) {
    const Shape s = shape(4, x, e);
    return std::array<Form, 3>{membrane_form(s, 4, 0, 0), membrane_form(s, 4, 1, 1), membrane_form(s, 4, 0, 1)};
  };
  const Shape sc = shape(4, 0, 0);
  const Eigen::Vector3d A1c = X.transpose() * sc.dN1, A2c = X.transpose() * sc.dN2;
  Eigen::Matrix2d G;
  G << A1c.dot(A1c), A1c.dot(A2c), A2c.dot(A1c), A2c.dot(A2c);
  const Eigen::Matrix2d Gi = G.inverse();
  const std::array<Eigen::Vector3d, 2> Ac = {Gi(0, 0) * A1c + Gi(0, 1) * A2c, Gi(1, 0) * A1c + Gi(1, 1) * A2c};
  const std::array<Form, 3> centre = plain(0, 0);
  // f at a point, as forms: Σ_γδ m_αγ m_βδ ε_γδ(0), m_αγ = A_α(P)·A^γ(0), ε12 = ½ (2ε12 form).
  auto f_at = [&](double x, double e) {
    const Shape s = shape(4, x, e);
    const std::array<Eigen::Vector3d, 2> A = {X.transpose() * s.dN1, X.transpose() * s.dN2};
    Eigen::Matrix2d m;
    for (int a = 0; a < 2; ++a)
      for (int g = 0; g < 2; ++g) m(a, g) = A[static_cast<size_t>(a)].dot(Ac[static_cast<size_t>(g)]);
    auto eps = [&](int g, int d) -> Form { return g == d ? centre[static_cast<size_t>(g)] : Form(0.5 * centre[2]); };
    auto comp = [&](int a, int b) {
      Form F = zero_form(4);
      for (int g = 0; g < 2; ++g)
        for (int d = 0; d < 2; ++d) F += m(a, g) * m(b, d) * eps(g, d);
      return F;
    };
    return std::array<Form, 3>{comp(0, 0), comp(1, 1), Form(2.0 * comp(0, 1))};
  };
  auto tied = [&](const auto& field) {
    const auto A = field(0, 1), C = field(0, -1), B = field(-1, 0), D = field(1, 0), O = field(0, 0);
    return std::array<Form, 3>{0.5 * (1 + eta) * A[0] + 0.5 * (1 - eta) * C[0],
                               0.5 * (1 + xi) * D[1] + 0.5 * (1 - xi) * B[1], O[2]};
  };
  auto ans = tied(plain);
  if (arc) {  // edges (kQuadEdges) 0: 1→2 at η = −1, 1: 4→3 at η = 1, 2: 1→4 at ξ = −1, 3: 2→3 at ξ = 1
    ans[0] = 0.5 * (1 + eta) * arc_edge_form(4, 1, 0.25) + 0.5 * (1 - eta) * arc_edge_form(4, 0, 0.25);
    ans[1] = 0.5 * (1 + xi) * arc_edge_form(4, 3, 0.25) + 0.5 * (1 - xi) * arc_edge_form(4, 2, 0.25);
    // 2ε12 at the centre: a_ξ·a_η with a_ξ(0) = ¼(c_0 + c_1), a_η(0) = ¼(c_2 + c_3), on the arc rows.
    ans[2] = zero_form(4);
    for (int e : {0, 1})
      for (int f : {2, 3}) ans[2](12 + e, 12 + f) = ans[2](12 + f, 12 + e) = 1.0 / 16;
  }
  const auto ans_f = tied(f_at), f = f_at(xi, eta);
  return {ans[0] + f[0] - ans_f[0], ans[1] + f[1] - ans_f[1], ans[2] + f[2] - ans_f[2]};
}

std::array<Form, kStrains> forms_at(int n, double xi, double eta, const Eigen::MatrixXd& X, bool geodesic, bool arc) {
  const Shape s = shape(n, xi, eta);
  const Eigen::MatrixXd c = edge_gradient(n, xi, eta);
  const Eigen::MatrixXd* edges = geodesic ? &c : nullptr;
  const auto g = assumed_shear(n, xi, eta, arc);
  // The triangle's (constant) metric from its three edges (kTriEdges: 0 = 1→2 = a_1, 1 = 1→3 = a_2,
  // 2 = 2→3 = a_2 − a_1): a_1·a_1 = |e_0|², a_2·a_2 = |e_1|², a_1·a_2 = ½(|e_0|² + |e_1|² − |e_2|²).
  const std::array<Form, 3> m =
      n == 4 ? assumed_membrane(xi, eta, X, arc)
      : arc  ? std::array<Form, 3>{arc_edge_form(3, 0, 1.0), arc_edge_form(3, 1, 1.0),
                                   Form(arc_edge_form(3, 0, 1.0) + arc_edge_form(3, 1, 1.0) - arc_edge_form(3, 2, 1.0))}
             : std::array<Form, 3>{membrane_form(s, n, 0, 0), membrane_form(s, n, 1, 1), membrane_form(s, n, 0, 1)};
  const Eigen::MatrixXd* arcs = arc ? &c : nullptr;
  return {m[0], m[1], m[2], bending_form(s, n, 0, 0, edges, arcs), bending_form(s, n, 1, 1, edges, arcs),
          bending_form(s, n, 0, 1, edges, arcs), g[0], g[1]};
}

/// All forms of an element, quadrature point by quadrature point: the triangle's are the same for
/// every element (shared), the quadrilateral's membrane forms depend on its reference geometry.
std::shared_ptr<const std::vector<Form>> element_forms(int n, const Eigen::MatrixXd& X, bool geodesic, bool arc) {
  auto build = [](int nn, const Eigen::MatrixXd& XX, bool geo, bool a) {
    auto f = std::make_shared<std::vector<Form>>();
    for (const auto& p : quadrature(nn).points)
      for (const Form& q : forms_at(nn, p[0], p[1], XX, geo, a)) f->push_back(q);
    return f;
  };
  if (n == 4) return build(4, X, geodesic, arc);
  static const std::shared_ptr<const std::vector<Form>> tri[4] = {
      build(3, Eigen::MatrixXd::Zero(3, 3), false, false), build(3, Eigen::MatrixXd::Zero(3, 3), true, false),
      build(3, Eigen::MatrixXd::Zero(3, 3), false, true), build(3, Eigen::MatrixXd::Zero(3, 3), true, true)};
  return tri[(geodesic ? 1 : 0) + (arc ? 2 : 0)];
}

/// The rows E_e = h(|Δ_e|²) Δ_e, Δ_e = d_J − d_I, of U (rows 2n … 2n + m − 1) from its director rows.
void geodesic_edge_rows(int n, int m, Eigen::MatrixXd& U) {
  for (int e = 0; e < m; ++e) {
    const Eigen::RowVector3d D = U.row(n + edge_node(n, e, 1)) - U.row(n + edge_node(n, e, 0));
    U.row(2 * n + e) = arc_over_chord(D.squaredNorm()).h * D;
  }
}

/// An edge's arc vector Y = h(p) c, c = x_J − x_I, p = (Δ·c)²/(c·c), Δ = d_J − d_I: the chord
/// lengthened to the circular arc whose end normals are the directors. For a plane arc through the
/// two nodes turning by φ, Δ = ±2 sin(φ/2) ĉ + (a part normal to the chord: none), so √p = 2 sin(φ/2)
/// and h(p) = φ/(2 sin(φ/2)) = arc/chord; a twist of the directors about the edge (Δ ⟂ c) leaves the
/// edge's length alone. The derivatives for the chain rule: J = ∂Y/∂(c, Δ) (3 × 6) and, for a weight
/// w = ∂W/∂Y, the Hessian of w·Y in (c, Δ) (6 × 6).
struct EdgeArc {
  Eigen::Vector3d Y;
  Eigen::Matrix<double, 3, 6> J;
  Eigen::Vector3d c, gp_c, gp_D;  // c and ∇p
  ArcOverChord h;
  double s = 0, nn = 0, p = 0;
};

/// p = (Δ·c)²/(c·c) of an edge, from s = Δ·c and n = c·c (one expression for the row and its chain).
double arc_parameter(double s, double n) { return s * s / n; }

EdgeArc edge_arc(const Eigen::Vector3d& c, const Eigen::Vector3d& D) {
  EdgeArc a;
  a.c = c;
  a.s = D.dot(c);
  a.nn = c.squaredNorm();
  a.p = arc_parameter(a.s, a.nn);
  a.h = arc_over_chord(std::min(a.p, 4.0));
  // ∇p = (2s/n) ∇s − (s²/n²) ∇n, ∇s = (Δ, c), ∇n = (2c, 0).
  a.gp_c = (2 * a.s / a.nn) * D - (2 * a.s * a.s / (a.nn * a.nn)) * c;
  a.gp_D = (2 * a.s / a.nn) * c;
  a.Y = a.h.h * c;
  a.J.leftCols<3>() = a.h.h * Eigen::Matrix3d::Identity() + a.h.dh * c * a.gp_c.transpose();
  a.J.rightCols<3>() = a.h.dh * c * a.gp_D.transpose();
  return a;
}

/// ∂²(w·Y)/∂(c, Δ)²: with u = w·c, w·Y = h(p) u and
/// ∇² = h'' u ∇p∇pᵀ + h' u ∇²p + h' (∇p ∇uᵀ + ∇u ∇pᵀ), ∇u = (w, 0),
/// ∇²p = (2/n) ∇s∇sᵀ − (2s/n²)(∇s∇nᵀ + ∇n∇sᵀ) + (2s²/n³) ∇n∇nᵀ + (2s/n) ∇²s − (s²/n²) ∇²n.
Eigen::Matrix<double, 6, 6> edge_arc_hessian(const EdgeArc& a, const Eigen::Vector3d& D, const Eigen::Vector3d& w) {
  using V6 = Eigen::Matrix<double, 6, 1>;
  using M6 = Eigen::Matrix<double, 6, 6>;
  const double n = a.nn, s = a.s, u = w.dot(a.c);
  V6 gs, gn, gp, gu;
  gs << D, a.c;
  gn << 2 * a.c, Eigen::Vector3d::Zero();
  gp << a.gp_c, a.gp_D;
  gu << w, Eigen::Vector3d::Zero();
  M6 H2s = M6::Zero(), H2n = M6::Zero();
  H2s.topRightCorner<3, 3>().setIdentity();
  H2s.bottomLeftCorner<3, 3>().setIdentity();
  H2n.topLeftCorner<3, 3>() = 2 * Eigen::Matrix3d::Identity();
  const M6 H2p = (2 / n) * gs * gs.transpose() - (2 * s / (n * n)) * (gs * gn.transpose() + gn * gs.transpose()) +
                 (2 * s * s / (n * n * n)) * gn * gn.transpose() + (2 * s / n) * H2s - (s * s / (n * n)) * H2n;
  return a.h.d2h * u * gp * gp.transpose() + a.h.dh * u * H2p + a.h.dh * (gp * gu.transpose() + gu * gp.transpose());
}

/// The rows Y_e (rows r0 … r0 + m − 1 of U) from its position and director rows: the arc vectors
/// only (edge_arc adds their derivatives where the tangent needs them).
void edge_arc_rows(int n, int m, int r0, Eigen::MatrixXd& U) {
  for (int e = 0; e < m; ++e) {
    const int I = edge_node(n, e, 0), J = edge_node(n, e, 1);
    const Eigen::RowVector3d c = U.row(J) - U.row(I), D = U.row(n + J) - U.row(n + I);
    U.row(r0 + e) = arc_over_chord(std::min(arc_parameter(D.dot(c), c.squaredNorm()), 4.0)).h * c;
  }
}

/// Values s_k = ½ Σ Q_ab U_a·U_b of all forms.
Eigen::VectorXd form_values(const std::vector<Form>& Q, const Eigen::MatrixXd& U) {
  Eigen::VectorXd s(static_cast<Eigen::Index>(Q.size()));
  const Eigen::MatrixXd G = U * U.transpose();  // Gram matrix U_a·U_b
  for (size_t k = 0; k < Q.size(); ++k) s[static_cast<Eigen::Index>(k)] = 0.5 * Q[k].cwiseProduct(G).sum();
  return s;
}

/// Voigt transformation of covariant natural strains (ε11, ε22, 2ε12) to Cartesian ones in the
/// basis e_i, with c(i, α) = e_i·A^α.
Eigen::Matrix3d voigt_transform(const Eigen::Matrix2d& c) {
  Eigen::Matrix3d T;
  T << c(0, 0) * c(0, 0), c(0, 1) * c(0, 1), c(0, 0) * c(0, 1),  //
      c(1, 0) * c(1, 0), c(1, 1) * c(1, 1), c(1, 0) * c(1, 1),  //
      2 * c(0, 0) * c(1, 0), 2 * c(0, 1) * c(1, 1), c(0, 0) * c(1, 1) + c(0, 1) * c(1, 0);
  return T;
}

/// c(i, α) = e_i·A^α for the reference tangents A_1, A_2 and the Cartesian axes e_1, e_2.
Eigen::Matrix2d contravariant_components(const Eigen::Vector3d& A1, const Eigen::Vector3d& A2,
                                         const Eigen::Vector3d& e1, const Eigen::Vector3d& e2) {
  Eigen::Matrix2d G;
  G << A1.dot(A1), A1.dot(A2), A2.dot(A1), A2.dot(A2);
  const Eigen::Matrix2d Gi = G.inverse();
  const Eigen::Vector3d a1 = Gi(0, 0) * A1 + Gi(0, 1) * A2, a2 = Gi(1, 0) * A1 + Gi(1, 1) * A2;
  Eigen::Matrix2d c;
  c << e1.dot(a1), e1.dot(a2), e2.dot(a1), e2.dot(a2);
  return c;
}

bool spd(const Eigen::MatrixXd& M) {
  if (!M.allFinite() || (M - M.transpose()).cwiseAbs().maxCoeff() > 1e-12 * M.cwiseAbs().maxCoeff()) return false;
  Eigen::LLT<Eigen::MatrixXd> llt(M);
  return llt.info() == Eigen::Success;
}

}  // namespace

// ------------------------------------------------------------------ section

ShellSection ShellSection::isotropic(double E, double nu, double rho, double t) {
  if (!(E > 0) || !(t > 0) || !(rho >= 0) || !(nu > -1 && nu < 0.5))
    throw std::invalid_argument("a shell needs E > 0, thickness > 0, rho >= 0 and -1 < nu < 0.5");
  ShellSection s;
  const double c = E * t / (1 - nu * nu);
  s.A << c, c * nu, 0, c * nu, c, 0, 0, 0, c * (1 - nu) / 2;
  s.D = s.A * (t * t / 12.0);
  s.shear_modulus = E / (2 * (1 + nu));
  s.As = Eigen::Matrix2d::Identity() * (5.0 / 6.0) * s.shear_modulus * t;
  s.thickness = t;
  s.mass = rho * t;
  s.rotary = rho * t * t * t / 12.0;
  s.homogeneous = true;
  return s;
}

ShellSection ShellSection::laminate(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B, const Eigen::Matrix3d& D,
                                    const Eigen::Matrix2d& As, double thickness, double mass, double rotary) {
  Eigen::Matrix<double, 6, 6> abd;
  abd << A, B, B.transpose(), D;
  if (!spd(abd)) throw std::invalid_argument("the ABD matrix [[A, B], [B^T, D]] is not symmetric positive definite");
  if (!spd(As)) throw std::invalid_argument("the transverse shear stiffness As is not symmetric positive definite");
  if (!(thickness > 0) || !(mass >= 0) || !(rotary >= 0))
    throw std::invalid_argument("a laminate needs thickness > 0, mass >= 0 and rotary >= 0");
  ShellSection s;
  s.A = A;
  s.B = B;
  s.D = D;
  s.As = As;
  s.thickness = thickness;
  s.mass = mass;
  s.rotary = rotary;
  // A mean in-plane shear modulus for the drilling penalty: A66 / t.
  s.shear_modulus = A(2, 2) / thickness;
  return s;
}

// ------------------------------------------------------------------ geodesic edges

ArcOverChord arc_over_chord(double q) {
  // h(q) = g(q/4), g(v) = asin(√v)/√v: its Taylor series Σ c_k v^k, c_{k+1} = c_k (2k + 1)²/((2k + 2)(2k + 3)),
  // for v < ¼ (a turn below 60°; 40 terms leave < 1e-24), the closed forms beyond (no cancellation there).
  const double v = 0.25 * q;
  double g = 0.0, g1 = 0.0, g2 = 0.0;
  if (v < 0.25) {
    static const std::array<double, 42> c = [] {
      std::array<double, 42> t{};
      t[0] = 1.0;
      for (size_t k = 0; k + 1 < t.size(); ++k) t[k + 1] = t[k] * (2.0 * k + 1) * (2.0 * k + 1) / ((2.0 * k + 2) * (2.0 * k + 3));
      return t;
    }();
    for (int k = 39; k >= 0; --k) {  // Horner: g = Σ c_k v^k, g' = Σ (k+1) c_{k+1} v^k, g'' = Σ (k+2)(k+1) c_{k+2} v^k
      const auto K = static_cast<size_t>(k);
      g = g * v + c[K];
      g1 = g1 * v + (k + 1) * c[K + 1];
      g2 = g2 * v + (k + 2) * (k + 1) * c[K + 2];
    }
  } else {
    // x = √v = c/2 ≤ 1: g = asin x / x, g' = A/(2x³), g'' = 1/(4x²(1 − x²)^{3/2}) − 3A/(4x⁵), A = x/√(1 − x²) − asin x.
    const double x = std::sqrt(v), s = std::sqrt(std::max(0.0, 1 - v)), A = x / s - std::asin(std::min(x, 1.0));
    g = std::asin(std::min(x, 1.0)) / x;
    g1 = A / (2 * x * x * x);
    g2 = 1.0 / (4 * x * x * s * s * s) - 3 * A / (4 * x * x * x * x * x);
  }
  return {g, g1 / 4, g2 / 16};
}

// ------------------------------------------------------------------ element

ReissnerMindlinShell::ReissnerMindlinShell(std::string name, std::vector<int> nodes, const ShellSection& section,
                                           const std::vector<Pose<double>>& reference,
                                           const std::vector<Eigen::Vector3d>& directors,
                                           const Eigen::Vector3d& material_axis, const Eigen::Vector3d& gravity,
                                           const ShellOptions& options)
    : Element(std::move(name), std::move(nodes)), section_(section), options_(options), g_(gravity) {
  n_ = static_cast<int>(this->nodes().size());
  if (n_ != 3 && n_ != 4) throw std::invalid_argument("a shell element has 3 or 4 nodes");
  if (static_cast<int>(reference.size()) != n_ || static_cast<int>(directors.size()) != n_)
    throw std::invalid_argument("a shell element needs one reference pose and one director per node");
  for (int I = 0; I < n_; ++I)
    for (int J = I + 1; J < n_; ++J)
      if (this->nodes()[static_cast<size_t>(I)] == this->nodes()[static_cast<size_t>(J)])
        throw std::invalid_argument("a shell element has a repeated node");
  if (!(section.thickness > 0)) throw std::invalid_argument("the shell section has no thickness");

  Eigen::MatrixXd X(n_, 3), D0(n_, 3);
  for (int I = 0; I < n_; ++I) X.row(I) = reference[static_cast<size_t>(I)].x.transpose();

  // Centre frame: tangents, normal, material axes.
  const Eigen::Vector2d centre = n_ == 4 ? Eigen::Vector2d(0, 0) : Eigen::Vector2d(1.0 / 3, 1.0 / 3);
  const Shape sc = shape(n_, centre[0], centre[1]);
  const Eigen::Vector3d A1c = X.transpose() * sc.dN1, A2c = X.transpose() * sc.dN2;
  const Eigen::Vector3d nc_raw = A1c.cross(A2c);
  const double scale = std::max(1e-300, (X.rowwise() - X.row(0)).norm());
  if (!(nc_raw.norm() > 1e-12 * scale * scale)) throw std::invalid_argument("the shell element is degenerate (zero area)");
  const Eigen::Vector3d nc = nc_raw.normalized();
  Eigen::Vector3d e1 = material_axis - material_axis.dot(nc) * nc;
  if (!(e1.norm() > 1e-6 * material_axis.norm()))
    throw std::invalid_argument("the material axis is along the element normal");
  e1.normalize();
  const Eigen::Vector3d e2 = nc.cross(e1);
  frame_.col(0) = e1;
  frame_.col(1) = e2;
  frame_.col(2) = nc;

  // Directors: unit, on the normal's side, within 60° of the element normal.
  for (int I = 0; I < n_; ++I) {
    const Eigen::Vector3d d = directors[static_cast<size_t>(I)];
    if (!(std::fabs(d.norm() - 1.0) < 1e-8)) throw std::invalid_argument("a shell director is not a unit vector");
    if (d.dot(nc) < std::cos(kPi / 3)) {
      std::ostringstream m;
      m << "the director at node " << I + 1 << " is " << std::acos(std::clamp(d.dot(nc), -1.0, 1.0)) * 180 / kPi
        << " degrees from the element normal (at most 60; are the normals consistent?)";
      throw std::invalid_argument(m.str());
    }
    D0.row(I) = d.transpose();
    dbar_[static_cast<size_t>(I)] = reference[static_cast<size_t>(I)].R.transpose() * d;
  }

  // Quadrature points: Jacobians and Cartesian transformations.
  const Quadrature& quad = quadrature(n_);
  const int ngp = static_cast<int>(quad.points.size()), nforms = kStrains * ngp;
  Eigen::MatrixXd S = Eigen::MatrixXd::Zero(kStrains, kStrains);  // section stiffness on (ε, κ, γ)
  S.block<3, 3>(0, 0) = section.A;
  S.block<3, 3>(0, 3) = section.B;
  S.block<3, 3>(3, 0) = section.B.transpose();
  S.block<3, 3>(3, 3) = section.D;
  S.block<2, 2>(6, 6) = section.As;

  const bool eas = n_ == 4 && options.eas;
  const int neas = eas ? 4 : 0;
  const double j0 = nc_raw.norm();
  const Eigen::Matrix3d T0 = voigt_transform(contravariant_components(A1c, A2c, e1, e2));
  T_ = Eigen::MatrixXd::Zero(kStrains * ngp, kStrains);  // per point, stacked: natural → Cartesian
  EasOut_ = Eigen::MatrixXd::Zero(kStrains * ngp, std::max(neas, 1));
  mass_ = Eigen::MatrixXd::Zero(n_, n_);
  wj_.assign(static_cast<size_t>(ngp), 0.0);
  area_ = 0.0;
  for (int p = 0; p < ngp; ++p) {
    const Eigen::Vector2d xp = quad.points[static_cast<size_t>(p)];
    const Shape s = shape(n_, xp[0], xp[1]);
    const Eigen::Vector3d A1 = X.transpose() * s.dN1, A2 = X.transpose() * s.dN2;
    const double j = A1.cross(A2).dot(nc);
    if (!(j > 1e-10 * j0)) throw std::invalid_argument("the shell element is inverted or degenerate (Jacobian <= 0)");
    const double w = quad.weights[static_cast<size_t>(p)] * j;
    wj_[static_cast<size_t>(p)] = w;
    area_ += w;
    mass_ += w * s.N * s.N.transpose();
    const Eigen::Matrix2d c = contravariant_components(A1, A2, e1, e2);
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(kStrains, kStrains);
    T.block<3, 3>(0, 0) = voigt_transform(c);
    T.block<3, 3>(3, 3) = voigt_transform(c);
    T.block<2, 2>(6, 6) = c;
    T_.block(kStrains * p, 0, kStrains, kStrains) = T;
    if (eas) {
      // Enhanced membrane strain (Cartesian Voigt): (j0/j) T0 M(ξ, η) α, M = [ξ 0 0 0; 0 η 0 0; 0 0 ξ η]
      // (Andelfinger & Ramm 1993): orthogonal to constant stresses, so the patch test holds.
      Eigen::Matrix<double, 3, 4> M;
      M << xp[0], 0, 0, 0, 0, xp[1], 0, 0, 0, 0, xp[0], xp[1];
      EasOut_.block(kStrains * p, 0, 3, 4) = (j0 / j) * T0 * M;
    }
  }

  // The strain forms; for the quadrilateral the membrane ones become Cartesian here: the assumed
  // (tied) strain is the compatible one plus Δ(P) = T_P (ε̃(P) − ε(P)), less Δ's mean over the
  // element, so that ∫ δε̂ dA = ∫ δε dA: constant stresses see no difference (the second half of the
  // patch test; the first, exact homogeneous strains, is assumed_membrane's correction).
  const bool geodesic = options.director_interpolation == DirectorInterpolation::geodesic;
  const bool arc = options.membrane_edges == MembraneEdges::arc;
  m_ = geodesic ? n_ : 0;
  k_ = arc ? n_ : 0;
  // membrane_edges: arc. The triangle's membrane strains are its edges' stretches: they take the arcs
  // directly. The quadrilateral's tied strains take them as an increment (arc − chord, at the tying
  // points) added after the correction below, which is built on the chords: subtracting the
  // element mean of the increment too would leave the element's mean membrane strain on the chords.
  auto forms = element_forms(n_, X, geodesic, arc && n_ == 3);
  if (n_ == 4) {
    const auto arc_forms = arc ? element_forms(4, X, geodesic, true) : nullptr;
    auto own = std::make_shared<std::vector<Form>>(*forms);
    std::vector<std::array<Form, 3>> delta(static_cast<size_t>(ngp));
    std::array<Form, 3> mean = {zero_form(4), zero_form(4), zero_form(4)};
    for (int p = 0; p < ngp; ++p) {
      const Eigen::Vector2d xp = quad.points[static_cast<size_t>(p)];
      const Shape s = shape(4, xp[0], xp[1]);
      const std::array<Form, 3> plain = {membrane_form(s, 4, 0, 0), membrane_form(s, 4, 1, 1), membrane_form(s, 4, 0, 1)};
      const Eigen::Matrix3d Tm = T_.block<3, 3>(kStrains * p, 0);
      for (int i = 0; i < 3; ++i) {
        Form d = zero_form(4), c = zero_form(4);
        for (int k = 0; k < 3; ++k) {
          const auto K = static_cast<size_t>(kStrains * p + k);
          d += Tm(i, k) * ((*forms)[K] - plain[static_cast<size_t>(k)]);
          c += Tm(i, k) * plain[static_cast<size_t>(k)];
          if (arc_forms) c += Tm(i, k) * ((*arc_forms)[K] - (*forms)[K]);
        }
        delta[static_cast<size_t>(p)][static_cast<size_t>(i)] = d;
        mean[static_cast<size_t>(i)] += (wj_[static_cast<size_t>(p)] / area_) * d;
        (*own)[static_cast<size_t>(kStrains * p + i)] = c;
      }
    }
    for (int p = 0; p < ngp; ++p) {
      for (int i = 0; i < 3; ++i)
        (*own)[static_cast<size_t>(kStrains * p + i)] += delta[static_cast<size_t>(p)][static_cast<size_t>(i)] - mean[static_cast<size_t>(i)];
      if (arc_forms)  // the bending and shear strains on the arc rows too
        for (int i = 3; i < kStrains; ++i) (*own)[static_cast<size_t>(kStrains * p + i)] = (*arc_forms)[static_cast<size_t>(kStrains * p + i)];
      T_.block<3, 3>(kStrains * p, 0).setIdentity();
    }
    forms = own;
  }
  if (!geodesic || !arc) {  // drop the E or Y rows an option leaves unused (the forms' cost grows with their size squared)
    std::vector<int> keep;
    for (int a = 0; a < 2 * n_; ++a) keep.push_back(a);
    for (int e = 0; e < m_; ++e) keep.push_back(2 * n_ + e);
    for (int e = 0; e < k_; ++e) keep.push_back(3 * n_ + e);
    auto own = std::make_shared<std::vector<Form>>();
    for (const Form& f : *forms) own->push_back(f(keep, keep));
    forms = own;
  }
  forms_ = forms;

  // Energy: W = ½ Σ_P w_P (T_P s_P + E_P α)ᵀ S (T_P s_P + E_P α) = ½ sᵀK s + sᵀL α + ½ αᵀH α, quadratic
  // in α: α = −H⁻¹Lᵀ s exactly (no element history), C = K − L H⁻¹ Lᵀ.
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nforms, nforms), L = Eigen::MatrixXd::Zero(nforms, neas),
                  H = Eigen::MatrixXd::Zero(neas, neas);
  for (int p = 0; p < ngp; ++p) {
    const Eigen::MatrixXd T = T_.block(kStrains * p, 0, kStrains, kStrains);
    const double w = wj_[static_cast<size_t>(p)];
    K.block(kStrains * p, kStrains * p, kStrains, kStrains) = w * T.transpose() * S * T;
    if (eas) {
      const Eigen::MatrixXd E = EasOut_.block(kStrains * p, 0, kStrains, 4);
      L.block(kStrains * p, 0, kStrains, 4) = w * T.transpose() * S * E;
      H += w * E.transpose() * S * E;
    }
  }
  C_ = K;
  if (eas) {
    Hinv_Lt_ = -H.ldlt().solve(L.transpose());
    C_ += L * Hinv_Lt_;
  }
  S_ = S;

  // Reference values of the forms.
  Eigen::MatrixXd U0(2 * n_ + m_ + k_, 3);
  U0.topRows(n_) = X;
  U0.middleRows(n_, n_) = D0;
  geodesic_edge_rows(n_, m_, U0);
  edge_arc_rows(n_, k_, 2 * n_ + m_, U0);
  s0_ = form_values(*forms_, U0);

  // Drilling: ω_I = Σ_J x_J·R_I g_IJ (header), g_IJ = ½ (c_J1 P_I2 − c_J2 P_I1), c_Jβ = N_J,α(centre) (A^α·e_β),
  // P_Ik = R_I0ᵀ e_k.
  const Eigen::Matrix2d cc = contravariant_components(A1c, A2c, e1, e2);  // c(β, α) = e_β·A^α
  for (int I = 0; I < n_; ++I) {
    const Eigen::Matrix3d& R0 = reference[static_cast<size_t>(I)].R;
    const Eigen::Vector3d P1 = R0.transpose() * e1, P2 = R0.transpose() * e2;
    double w0 = 0.0;
    for (int J = 0; J < n_; ++J) {
      const double cJ1 = sc.dN1[J] * cc(0, 0) + sc.dN2[J] * cc(0, 1);
      const double cJ2 = sc.dN1[J] * cc(1, 0) + sc.dN2[J] * cc(1, 1);
      drill_g_[static_cast<size_t>(I)][static_cast<size_t>(J)] = 0.5 * (cJ1 * P2 - cJ2 * P1);
      w0 += X.row(J).dot(R0 * drill_g_[static_cast<size_t>(I)][static_cast<size_t>(J)]);
    }
    drill_w0_[static_cast<size_t>(I)] = w0;
    drill_k_[static_cast<size_t>(I)] = options.drilling_factor * section.shear_modulus * section.thickness * area_ / n_;
  }
}

// ------------------------------------------------------------------ elastic forces

void ReissnerMindlinShell::nodal_vectors(const Eigen::VectorXd& q, Eigen::MatrixXd& U,
                                         std::array<Eigen::Matrix3d, kMaxNodes>& R) const {
  U.resize(2 * n_ + m_ + k_, 3);
  for (int I = 0; I < n_; ++I) {
    const Pose<double> p = pose_of(q.data() + 7 * I);
    R[static_cast<size_t>(I)] = p.R;
    U.row(I) = p.x.transpose();
    U.row(n_ + I) = (p.R * dbar_[static_cast<size_t>(I)]).transpose();
  }
  geodesic_edge_rows(n_, m_, U);
  edge_arc_rows(n_, k_, 2 * n_ + m_, U);
}

double ReissnerMindlinShell::elastic_energy(const Eigen::VectorXd& q) const {
  Eigen::MatrixXd U;
  std::array<Eigen::Matrix3d, kMaxNodes> R;
  nodal_vectors(q, U, R);
  const Eigen::VectorXd e = form_values(*forms_, U) - s0_;
  double W = 0.5 * e.dot(C_ * e);
  for (int I = 0; I < n_; ++I) {
    double w = -drill_w0_[static_cast<size_t>(I)];
    for (int J = 0; J < n_; ++J) w += U.row(J).dot(R[static_cast<size_t>(I)] * drill_g_[static_cast<size_t>(I)][static_cast<size_t>(J)]);
    W += 0.5 * drill_k_[static_cast<size_t>(I)] * w * w;
  }
  return W;
}

void ReissnerMindlinShell::elastic_forces(const Eigen::VectorXd& q, Eigen::VectorXd& r, Eigen::MatrixXd* Kout) const {
  const std::vector<Form>& Q = *forms_;
  const int nf = static_cast<int>(Q.size()), nd = 6 * n_;
  Eigen::MatrixXd U;
  std::array<Eigen::Matrix3d, kMaxNodes> R;
  nodal_vectors(q, U, R);
  const Eigen::VectorXd sigma = C_ * (form_values(Q, U) - s0_);

  // r_U = (Σ σ_k Q_k) U.
  const int rows = 2 * n_ + m_ + k_, y0 = 2 * n_ + m_;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(rows, rows);
  for (int k = 0; k < nf; ++k) G += sigma[k] * Q[static_cast<size_t>(k)];
  const Eigen::MatrixXd rU = G * U;
  // Every row a of U varies with the nodal motions as δU_a = Σ_b M_ab δz_b over a few blocks
  // (column of δx_I or δθ_I, 3 × 3 matrix): a position row δx_I; a director row δd_I = Λ_I δθ_I,
  // Λ_I = −R_I D̄_I^; a geodesic edge row δE_e = J_e (δd_J − δd_I), J_e = h I + 2h' Δ Δᵀ
  // (E_e = h(|Δ|²) Δ, Δ = d_J − d_I); an arc row δY_e = J_c (δx_J − δx_I) + J_Δ (δd_J − δd_I) (edge_arc).
  struct Chain {
    int size = 0;
    std::array<std::pair<int, Eigen::Matrix3d>, 4> block;
    bool identity = false;  // a position row: one block, the identity (skips the products below)
    void add(int column, const Eigen::Matrix3d& M) { block[static_cast<size_t>(size++)] = {column, M}; }
  };
  std::array<Eigen::Matrix3d, kMaxNodes> Lam;
  for (int I = 0; I < n_; ++I) Lam[static_cast<size_t>(I)] = -R[static_cast<size_t>(I)] * hat3(dbar_[static_cast<size_t>(I)]);
  const bool chains = Kout != nullptr;  // the chains are for K only
  std::array<Chain, 4 * kMaxNodes> chain;
  std::array<Eigen::Vector3d, kMaxNodes> Dl, Dy;
  std::array<ArcOverChord, kMaxNodes> ac;
  std::array<Eigen::Matrix3d, kMaxNodes> Je;
  std::array<EdgeArc, kMaxNodes> arcs;
  for (int I = 0; chains && I < n_; ++I) {
    chain[static_cast<size_t>(I)].add(6 * I, Eigen::Matrix3d::Identity());
    chain[static_cast<size_t>(I)].identity = true;
    chain[static_cast<size_t>(n_ + I)].add(6 * I + 3, Lam[static_cast<size_t>(I)]);
  }
  // r_x, r_d: the residual on the positions and on the directors (before Λ), every row chained in.
  using NodeRows = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor, kMaxNodes, 3>;  // no heap
  NodeRows rx = rU.topRows(n_), rd = rU.middleRows(n_, n_);
  for (int e = 0; e < m_; ++e) {
    const auto E = static_cast<size_t>(e);
    const int I = edge_node(n_, e, 0), J = edge_node(n_, e, 1);
    Dl[E] = (U.row(n_ + J) - U.row(n_ + I)).transpose();
    ac[E] = arc_over_chord(Dl[E].squaredNorm());
    Je[E] = ac[E].h * Eigen::Matrix3d::Identity() + 2 * ac[E].dh * Dl[E] * Dl[E].transpose();
    if (chains) {
      chain[static_cast<size_t>(2 * n_ + e)].add(6 * J + 3, Je[E] * Lam[static_cast<size_t>(J)]);
      chain[static_cast<size_t>(2 * n_ + e)].add(6 * I + 3, -Je[E] * Lam[static_cast<size_t>(I)]);
    }
    const Eigen::RowVector3d rD = rU.row(2 * n_ + e) * Je[E];
    rd.row(J) += rD;
    rd.row(I) -= rD;
  }
  for (int e = 0; e < k_; ++e) {
    const auto E = static_cast<size_t>(e);
    const int I = edge_node(n_, e, 0), J = edge_node(n_, e, 1);
    Dy[E] = (U.row(n_ + J) - U.row(n_ + I)).transpose();
    arcs[E] = edge_arc((U.row(J) - U.row(I)).transpose(), Dy[E]);
    const Eigen::Matrix3d Jc = arcs[E].J.leftCols<3>(), JD = arcs[E].J.rightCols<3>();
    if (chains) {
      Chain& ch = chain[static_cast<size_t>(y0 + e)];
      ch.add(6 * J, Jc);
      ch.add(6 * I, -Jc);
      ch.add(6 * J + 3, JD * Lam[static_cast<size_t>(J)]);
      ch.add(6 * I + 3, -JD * Lam[static_cast<size_t>(I)]);
    }
    const Eigen::RowVector3d rc = rU.row(y0 + e) * Jc, rD = rU.row(y0 + e) * JD;
    rx.row(J) += rc;
    rx.row(I) -= rc;
    rd.row(J) += rD;
    rd.row(I) -= rD;
  }
  r = Eigen::VectorXd::Zero(nd);
  for (int I = 0; I < n_; ++I) {
    r.segment<3>(6 * I) = rx.row(I).transpose();
    r.segment<3>(6 * I + 3) = Lam[static_cast<size_t>(I)].transpose() * rd.row(I).transpose();
  }
  if (Kout) {
    Eigen::MatrixXd& K = *Kout;
    // B P: row k = (Q_k U) carried to (δx, δθ) through the rows' chains.
    Eigen::MatrixXd BP = Eigen::MatrixXd::Zero(nf, nd);
    for (int k = 0; k < nf; ++k) {
      const Eigen::MatrixXd QU = Q[static_cast<size_t>(k)] * U;
      for (int a = 0; a < rows; ++a) {
        const Chain& ch = chain[static_cast<size_t>(a)];
        if (ch.identity) {
          BP.block<1, 3>(k, ch.block[0].first) += QU.row(a);
          continue;
        }
        for (int c = 0; c < ch.size; ++c) {
          const auto& [col, M] = ch.block[static_cast<size_t>(c)];
          BP.block<1, 3>(k, col) += QU.row(a) * M;
        }
      }
    }
    K = BP.transpose() * C_ * BP;
    // Pᵀ (G ⊗ I₃) P: the forms' second derivatives, through the chains of both rows.
    for (int a = 0; a < rows; ++a)
      for (int b = 0; b < rows; ++b) {
        const double g = G(a, b);
        if (g == 0.0) continue;
        const Chain& ca = chain[static_cast<size_t>(a)];
        const Chain& cb = chain[static_cast<size_t>(b)];
        if (ca.identity && cb.identity) {
          K.block<3, 3>(ca.block[0].first, cb.block[0].first).diagonal().array() += g;
          continue;
        }
        if (ca.identity || cb.identity) {  // g M (column side) or g Mᵀ (row side)
          const Chain& other = ca.identity ? cb : ca;
          for (int j = 0; j < other.size; ++j) {
            const auto& [c, M] = other.block[static_cast<size_t>(j)];
            if (ca.identity)
              K.block<3, 3>(ca.block[0].first, c) += g * M;
            else
              K.block<3, 3>(c, cb.block[0].first) += g * M.transpose();
          }
          continue;
        }
        for (int i = 0; i < ca.size; ++i)
          for (int j = 0; j < cb.size; ++j) {
            const auto& [ci, Mi] = ca.block[static_cast<size_t>(i)];
            const auto& [cj, Mj] = cb.block[static_cast<size_t>(j)];
            K.block<3, 3>(ci, cj) += g * Mi.transpose() * Mj;
          }
      }
    // Second derivative of the director on the group: r_d·R ê_j ê_k D̄ = (w D̄ᵀ − (w·D̄) I)_kj, w = Rᵀ r_d.
    for (int I = 0; I < n_; ++I) {
      const Eigen::Vector3d w = R[static_cast<size_t>(I)].transpose() * rd.row(I).transpose();
      const Eigen::Vector3d& Db = dbar_[static_cast<size_t>(I)];
      K.block<3, 3>(6 * I + 3, 6 * I + 3) += w * Db.transpose() - w.dot(Db) * Eigen::Matrix3d::Identity();
    }
    // Second derivative of the geodesic edges: ∂²(w·E)/∂Δ² = 2h'(wΔᵀ + Δwᵀ + (w·Δ) I) + 4h''(w·Δ) ΔΔᵀ,
    // w = r_E, carried to the rotations by δΔ = Λ_J δθ_J − Λ_I δθ_I.
    for (int e = 0; e < m_; ++e) {
      const auto E = static_cast<size_t>(e);
      const int I = edge_node(n_, e, 0), J = edge_node(n_, e, 1);
      const Eigen::Vector3d w = rU.row(2 * n_ + e).transpose(), D = Dl[E];
      const double wD = w.dot(D);
      const Eigen::Matrix3d H = 2 * ac[E].dh * (w * D.transpose() + D * w.transpose() + wD * Eigen::Matrix3d::Identity()) +
                                4 * ac[E].d2h * wD * D * D.transpose();
      const Eigen::Matrix3d& LI = Lam[static_cast<size_t>(I)];
      const Eigen::Matrix3d& LJ = Lam[static_cast<size_t>(J)];
      K.block<3, 3>(6 * J + 3, 6 * J + 3) += LJ.transpose() * H * LJ;
      K.block<3, 3>(6 * I + 3, 6 * I + 3) += LI.transpose() * H * LI;
      K.block<3, 3>(6 * I + 3, 6 * J + 3) -= LI.transpose() * H * LJ;
      K.block<3, 3>(6 * J + 3, 6 * I + 3) -= LJ.transpose() * H * LI;
    }
    // Second derivative of the arc rows: ∂²(w·Y)/∂(c, Δ)² (edge_arc_hessian), w = r_Y, carried to the
    // motions by δc = δx_J − δx_I and δΔ = Λ_J δθ_J − Λ_I δθ_I.
    for (int e = 0; e < k_; ++e) {
      const auto E = static_cast<size_t>(e);
      const int I = edge_node(n_, e, 0), J = edge_node(n_, e, 1);
      const Eigen::Matrix<double, 6, 6> H = edge_arc_hessian(arcs[E], Dy[E], rU.row(y0 + e).transpose());
      const std::array<std::array<std::pair<int, Eigen::Matrix3d>, 2>, 2> var = {
          {{{{6 * J, Eigen::Matrix3d::Identity()}, {6 * I, -Eigen::Matrix3d::Identity()}}},
           {{{6 * J + 3, Lam[static_cast<size_t>(J)]}, {6 * I + 3, -Lam[static_cast<size_t>(I)]}}}}};
      for (int u = 0; u < 2; ++u)
        for (int v = 0; v < 2; ++v) {
          const Eigen::Matrix3d Huv = H.block<3, 3>(3 * u, 3 * v);
          for (const auto& [ci, Mi] : var[static_cast<size_t>(u)])
            for (const auto& [cj, Mj] : var[static_cast<size_t>(v)]) K.block<3, 3>(ci, cj) += Mi.transpose() * Huv * Mj;
        }
    }
  }

  // Drilling penalty ½ k ω², ω_I = Σ_J x_J·R_I g_IJ − ω0_I.
  for (int I = 0; I < n_; ++I) {
    const double k = drill_k_[static_cast<size_t>(I)];
    if (k == 0.0) continue;
    const Eigen::Matrix3d& RI = R[static_cast<size_t>(I)];
    Eigen::VectorXd grad = Eigen::VectorXd::Zero(nd);
    double w = -drill_w0_[static_cast<size_t>(I)];
    for (int J = 0; J < n_; ++J) {
      const Eigen::Vector3d& g = drill_g_[static_cast<size_t>(I)][static_cast<size_t>(J)];
      const Eigen::Vector3d xJ = U.row(J).transpose();
      w += xJ.dot(RI * g);
      grad.segment<3>(6 * J) += RI * g;
      grad.segment<3>(6 * I + 3) += g.cross(RI.transpose() * xJ);
    }
    r += k * w * grad;
    if (!Kout) continue;
    Eigen::MatrixXd& K = *Kout;
    K += k * grad * grad.transpose();
    for (int J = 0; J < n_; ++J) {
      const Eigen::Vector3d& g = drill_g_[static_cast<size_t>(I)][static_cast<size_t>(J)];
      const Eigen::Vector3d y = RI.transpose() * U.row(J).transpose();
      K.block<3, 3>(6 * J, 6 * I + 3) += k * w * (-RI * hat3(g));
      K.block<3, 3>(6 * I + 3, 6 * J) += k * w * (hat3(g) * RI.transpose());
      K.block<3, 3>(6 * I + 3, 6 * I + 3) += k * w * (y * g.transpose() - y.dot(g) * Eigen::Matrix3d::Identity());
    }
  }
}

// ------------------------------------------------------------------ inertia, gravity

void ReissnerMindlinShell::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  {
    Eigen::VectorXd r;
    Eigen::MatrixXd K;
    elastic_forces(s.q, r, tangent ? &K : nullptr);
    out.r += r;
    if (tangent) out.K += K;
  }
  const double rhot = section_.mass, Ir = section_.rotary;
  std::array<Eigen::Matrix3d, kMaxNodes> R;
  for (int I = 0; I < n_; ++I) R[static_cast<size_t>(I)] = pose_of(s.q.data() + 7 * I).R;
  // Translation: consistent mass; gravity ∫ ρt N_I g dA.
  const Eigen::VectorXd Nint = mass_.rowwise().sum();  // ∫ N_I dA (Σ_J N_J = 1)
  for (int I = 0; I < n_; ++I) {
    for (int J = 0; J < n_; ++J) out.r.segment<3>(6 * I) += rhot * mass_(I, J) * s.qdd.segment<3>(6 * J);
    out.r.segment<3>(6 * I) -= s.load_factor * rhot * Nint[I] * g_;
  }
  // Director inertia: r_θI = Λ_Iᵀ Σ_J m_IJ d̈_J, d̈_J = R_J (Ω̇_J × D̄_J + Ω_J × (Ω_J × D̄_J)).
  std::array<Eigen::Vector3d, kMaxNodes> gJ, ddot;
  std::array<Eigen::Matrix3d, kMaxNodes> Lam;
  for (int J = 0; J < n_; ++J) {
    const Eigen::Vector3d W = s.v.segment<3>(6 * J + 3), Wd = s.qdd.segment<3>(6 * J + 3);
    const Eigen::Vector3d& Db = dbar_[static_cast<size_t>(J)];
    gJ[static_cast<size_t>(J)] = Wd.cross(Db) + W.cross(W.cross(Db));
    ddot[static_cast<size_t>(J)] = R[static_cast<size_t>(J)] * gJ[static_cast<size_t>(J)];
    Lam[static_cast<size_t>(J)] = -R[static_cast<size_t>(J)] * hat3(Db);
  }
  for (int I = 0; I < n_; ++I) {
    Eigen::Vector3d z = Eigen::Vector3d::Zero();
    for (int J = 0; J < n_; ++J) z += Ir * mass_(I, J) * ddot[static_cast<size_t>(J)];
    out.r.segment<3>(6 * I + 3) += Lam[static_cast<size_t>(I)].transpose() * z;
    // Drilling inertia about D̄_I (lumped), a rigid axisymmetric term J Ω̇ + Ω × J Ω.
    const Eigen::Vector3d& Db = dbar_[static_cast<size_t>(I)];
    const double jd = options_.drilling_inertia_factor * Ir * mass_.row(I).sum();
    const Eigen::Matrix3d Jd = jd * Db * Db.transpose();
    const Eigen::Vector3d W = s.v.segment<3>(6 * I + 3), Wd = s.qdd.segment<3>(6 * I + 3);
    out.r.segment<3>(6 * I + 3) += Jd * Wd + W.cross(Jd * W);
    if (!tangent) continue;
    for (int J = 0; J < n_; ++J) {
      const Eigen::Vector3d WJ = s.v.segment<3>(6 * J + 3);
      const Eigen::Vector3d& DJ = dbar_[static_cast<size_t>(J)];
      const double m = rhot * mass_(I, J), mr = Ir * mass_(I, J);
      out.M.block<3, 3>(6 * I, 6 * J).diagonal().array() += m;
      out.M.block<3, 3>(6 * I + 3, 6 * J + 3) += mr * Lam[static_cast<size_t>(I)].transpose() * Lam[static_cast<size_t>(J)];
      const Eigen::Matrix3d dg = WJ.dot(DJ) * Eigen::Matrix3d::Identity() + WJ * DJ.transpose() - 2.0 * DJ * WJ.transpose();
      out.C.block<3, 3>(6 * I + 3, 6 * J + 3) += mr * Lam[static_cast<size_t>(I)].transpose() * R[static_cast<size_t>(J)] * dg;
      out.K.block<3, 3>(6 * I + 3, 6 * J + 3) +=
          mr * Lam[static_cast<size_t>(I)].transpose() * (-R[static_cast<size_t>(J)] * hat3(gJ[static_cast<size_t>(J)]));
    }
    const Eigen::Vector3d w = R[static_cast<size_t>(I)].transpose() * z;
    out.K.block<3, 3>(6 * I + 3, 6 * I + 3) += w * Db.transpose() - w.dot(Db) * Eigen::Matrix3d::Identity();
    out.M.block<3, 3>(6 * I + 3, 6 * I + 3) += Jd;
    out.C.block<3, 3>(6 * I + 3, 6 * I + 3) += hat3(W) * Jd - hat3(Jd * W);
  }
}

bool ReissnerMindlinShell::mass_action(const LocalState& s, const Eigen::VectorXd& w, Eigen::VectorXd& Mw) const {
  // The M of evaluate(): ρt m_IJ on the translations, Ir m_IJ Λ_Iᵀ Λ_J (Λ_J = −R_J D̄_J^) and the
  // lumped drilling inertia J_d on the rotations.
  const double rhot = section_.mass, Ir = section_.rotary;
  Mw.setZero(6 * n_);
  std::array<Eigen::Vector3d, kMaxNodes> dd;  // Λ_J w_θJ = R_J (w_θJ × D̄_J)
  std::array<Eigen::Matrix3d, kMaxNodes> R;
  for (int J = 0; J < n_; ++J) {
    R[static_cast<size_t>(J)] = pose_of(s.q.data() + 7 * J).R;
    dd[static_cast<size_t>(J)] = R[static_cast<size_t>(J)] * w.segment<3>(6 * J + 3).cross(dbar_[static_cast<size_t>(J)]);
  }
  for (int I = 0; I < n_; ++I) {
    Eigen::Vector3d z = Eigen::Vector3d::Zero();
    for (int J = 0; J < n_; ++J) {
      Mw.segment<3>(6 * I) += rhot * mass_(I, J) * w.segment<3>(6 * J);
      z += Ir * mass_(I, J) * dd[static_cast<size_t>(J)];
    }
    const Eigen::Vector3d& Db = dbar_[static_cast<size_t>(I)];
    const double jd = options_.drilling_inertia_factor * Ir * mass_.row(I).sum();
    // Λ_Iᵀ z = −D̄_I^ᵀ R_Iᵀ z = D̄_I × (R_Iᵀ z).
    Mw.segment<3>(6 * I + 3) = Db.cross(R[static_cast<size_t>(I)].transpose() * z) + jd * Db * Db.dot(w.segment<3>(6 * I + 3));
  }
  return true;
}

// ------------------------------------------------------------------ output

OutputCell ReissnerMindlinShell::output_cell() const {
  if (nodes().size() == 4) return {CellShape::quadrilateral, {0, 1, 2, 3}};
  return {CellShape::triangle, {0, 1, 2}};
}

std::vector<CellField> ReissnerMindlinShell::cell_fields() const {
  return {{"n11"}, {"n22"}, {"n12"}, {"m11"}, {"m22"}, {"m12"}, {"q1"}, {"q2"}, {"von_mises_top"}, {"von_mises_bottom"}};
}

void ReissnerMindlinShell::output(const LocalState& s, Eigen::VectorXd& values) const {
  Eigen::MatrixXd U;
  std::array<Eigen::Matrix3d, kMaxNodes> R;
  nodal_vectors(s.q, U, R);
  const Eigen::VectorXd e = form_values(*forms_, U) - s0_;
  Eigen::VectorXd alpha;
  if (Hinv_Lt_.size() > 0) alpha = Hinv_Lt_ * e;
  // Area-weighted mean of the resultants over the quadrature points.
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(kStrains);
  const int ngp = static_cast<int>(wj_.size());
  for (int p = 0; p < ngp; ++p) {
    Eigen::VectorXd strain = T_.block(kStrains * p, 0, kStrains, kStrains) * e.segment(kStrains * p, kStrains);
    if (alpha.size() > 0) strain += EasOut_.block(kStrains * p, 0, kStrains, 4) * alpha;
    mean += wj_[static_cast<size_t>(p)] * (S_ * strain);
  }
  mean /= area_;
  values.resize(10);
  values.head<8>() = mean;
  von_mises_from_resultants(values, section_.thickness);
}

void ReissnerMindlinShell::von_mises_from_resultants(Eigen::VectorXd& values, double t) {
  for (int side = 0; side < 2; ++side) {
    const double f = side == 0 ? 6.0 / (t * t) : -6.0 / (t * t);
    const double s11 = values[0] / t + f * values[3], s22 = values[1] / t + f * values[4], s12 = values[2] / t + f * values[5];
    values[8 + side] = std::sqrt(std::max(0.0, s11 * s11 + s22 * s22 - s11 * s22 + 3.0 * s12 * s12));
  }
}

// ------------------------------------------------------------------ pressure

ShellPressure::ShellPressure(std::string name, std::vector<int> nodes, const std::vector<Eigen::Vector3d>& X,
                             TimeFunctionPtr pressure, bool follower)
    : Element(std::move(name), std::move(nodes)), p_(std::move(pressure)), follower_(follower) {
  n_ = static_cast<int>(this->nodes().size());
  if ((n_ != 3 && n_ != 4) || static_cast<int>(X.size()) != n_)
    throw std::invalid_argument("a pressure load acts on a 3- or 4-node shell element");
  const Quadrature& quad = quadrature(n_);
  for (int I = 0; I < n_; ++I) fixed_[static_cast<size_t>(I)].setZero();
  for (size_t p = 0; p < quad.points.size(); ++p) {
    const Shape s = shape(n_, quad.points[p][0], quad.points[p][1]);
    Eigen::Vector3d A1 = Eigen::Vector3d::Zero(), A2 = Eigen::Vector3d::Zero();
    for (int J = 0; J < n_; ++J) {
      A1 += s.dN1[J] * X[static_cast<size_t>(J)];
      A2 += s.dN2[J] * X[static_cast<size_t>(J)];
    }
    for (int I = 0; I < n_; ++I) fixed_[static_cast<size_t>(I)] += quad.weights[p] * s.N[I] * A1.cross(A2);
  }
}

void ShellPressure::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  const double p = s.load_factor * p_->value(s.t);
  if (!follower_) {
    for (int I = 0; I < n_; ++I) out.r.segment<3>(6 * I) += p * fixed_[static_cast<size_t>(I)];
    return;
  }
  const Quadrature& quad = quadrature(n_);
  for (size_t q = 0; q < quad.points.size(); ++q) {
    const Shape& sh = quad.shapes[q];
    Eigen::Vector3d a1 = Eigen::Vector3d::Zero(), a2 = Eigen::Vector3d::Zero();
    for (int J = 0; J < n_; ++J) {
      const Eigen::Vector3d x(s.q[7 * J], s.q[7 * J + 1], s.q[7 * J + 2]);
      a1 += sh.dN1[J] * x;
      a2 += sh.dN2[J] * x;
    }
    const double w = quad.weights[q] * p;
    const Eigen::Vector3d n = a1.cross(a2);
    for (int I = 0; I < n_; ++I) {
      out.r.segment<3>(6 * I) += w * sh.N[I] * n;
      if (!tangent) continue;
      for (int J = 0; J < n_; ++J)
        out.K.block<3, 3>(6 * I, 6 * J) += w * sh.N[I] * (-sh.dN1[J] * hat3(a2) + sh.dN2[J] * hat3(a1));
    }
  }
}

// ------------------------------------------------------------------ directors

std::vector<std::vector<Eigen::Vector3d>> shell_directors(const std::vector<Eigen::Vector3d>& points,
                                                          const std::vector<std::vector<int>>& elements,
                                                          double kink_angle) {
  // Unit normal of each element at each of its nodes (a_1 × a_2 there).
  std::vector<std::vector<Eigen::Vector3d>> normal(elements.size());
  std::vector<Eigen::Vector3d> sum(points.size(), Eigen::Vector3d::Zero());
  for (size_t e = 0; e < elements.size(); ++e) {
    const int n = static_cast<int>(elements[e].size());
    if (n != 3 && n != 4) throw std::invalid_argument("a shell element has 3 or 4 nodes");
    for (int I = 0; I < n; ++I) {
      const Eigen::Vector2d xi = node_coordinates(n, I);
      const Shape s = shape(n, xi[0], xi[1]);
      Eigen::Vector3d A1 = Eigen::Vector3d::Zero(), A2 = Eigen::Vector3d::Zero();
      for (int J = 0; J < n; ++J) {
        const Eigen::Vector3d& X = points[static_cast<size_t>(elements[e][static_cast<size_t>(J)])];
        A1 += s.dN1[J] * X;
        A2 += s.dN2[J] * X;
      }
      Eigen::Vector3d nn = A1.cross(A2);
      if (nn.norm() > 0) nn.normalize();
      normal[e].push_back(nn);
      sum[static_cast<size_t>(elements[e][static_cast<size_t>(I)])] += nn;
    }
  }
  const double cos_kink = std::cos(kink_angle);
  std::vector<std::vector<Eigen::Vector3d>> d(elements.size());
  for (size_t e = 0; e < elements.size(); ++e)
    for (size_t I = 0; I < elements[e].size(); ++I) {
      const Eigen::Vector3d& m = sum[static_cast<size_t>(elements[e][I])];
      const Eigen::Vector3d& ne = normal[e][I];
      if (m.norm() > 1e-12 && m.normalized().dot(ne) >= cos_kink) d[e].push_back(m.normalized());
      else d[e].push_back(ne);
    }
  return d;
}

}  // namespace alphaflex
