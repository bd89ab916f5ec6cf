// Reduced flexible body on a floating frame (header; docs/theory/reduced_bodies.md).
#include "alphaflex/elements/reduced_body.hpp"

#include <cblas.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unsupported/Eigen/AutoDiff>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

namespace alphaflex {
namespace {

template <class S>
using VecS = Eigen::Matrix<S, Eigen::Dynamic, 1>;
template <class S>
using MatS = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <class S>
using V3 = Eigen::Matrix<S, 3, 1>;

// 𝕄(ξ) (header) for any scalar.
template <class S>
MatS<S> mass_of(const ReducedBodyMatrices& d, const VecS<S>& xi) {
  const int m = d.elastic(), n = 6 + m;
  MatS<S> A = d.M0.template cast<S>();
  for (int i = 0; i < m; ++i)
    for (int c = 0; c < n; ++c)
      for (int r = 0; r < 3; ++r) {
        A(3 + r, c) += xi[i] * d.C[static_cast<size_t>(i)](r, c);
        A(c, 3 + r) += xi[i] * d.C[static_cast<size_t>(i)](r, c);
      }
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) A(3 + r, 3 + c) += xi[i] * xi[j] * d.M2[static_cast<size_t>(i * m + j)](r, c);
  return A;
}

// (∂𝕄/∂ξᵢ) w = Ĉᵢ w + Ĉᵢᵀ w + Σⱼ ξⱼ (M₂ᵢⱼ + M₂ⱼᵢ) w_ω (Ĉᵢ: Cᵢ in the ω rows).
template <class S>
VecS<S> mass_derivative_times(const ReducedBodyMatrices& d, const VecS<S>& xi, int i, const VecS<S>& w) {
  const int m = d.elastic(), n = 6 + m;
  const Eigen::MatrixXd& Ci = d.C[static_cast<size_t>(i)];
  VecS<S> out = VecS<S>::Zero(n);
  for (int c = 0; c < n; ++c)
    for (int r = 0; r < 3; ++r) {
      out[3 + r] += Ci(r, c) * w[c];
      out[c] += Ci(r, c) * w[3 + r];
    }
  for (int j = 0; j < m; ++j) {
    const Eigen::Matrix3d B = d.M2[static_cast<size_t>(i * m + j)] + d.M2[static_cast<size_t>(j * m + i)];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) out[3 + r] += xi[j] * B(r, c) * w[3 + c];
  }
  return out;
}

template <class S>
V3<S> cross(const V3<S>& a, const V3<S>& b) {
  return V3<S>(a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]);
}

}  // namespace

Eigen::MatrixXd ReducedBodyMatrices::mass_matrix(const Eigen::VectorXd& xi) const { return mass_of<double>(*this, xi); }

namespace {
// Nondecreasing sequences of length `len` over `n` values: C(n + len − 1, len).
size_t multisets(int n, int len) {
  double c = 1.0;
  for (int i = 1; i <= len; ++i) c = c * (n + i - 1) / i;
  return static_cast<size_t>(std::llround(c));
}
}  // namespace

SymmetricTensor::SymmetricTensor(int order, int dim) : order_(order), dim_(dim) {
  if ((order != 3 && order != 4) || dim < 0)
    throw std::invalid_argument("symmetric tensor: order " + std::to_string(order) + " on " + std::to_string(dim) +
                                " indices (order 3 or 4 expected)");
  values_.assign(multisets(dim, order), 0.0);
}

double SymmetricTensor::operator()(int i, int j, int k, int l) const {
  int x[4] = {i, j, k, l};
  // Constant bounds (order_ is 3 or 4, checked above): with x + order_ GCC 12 cannot see that the
  // sort stays within x and warns (-Warray-bounds) from its unrolled insertion sort.
  if (order_ == 3)
    std::sort(x, x + 3);
  else
    std::sort(x, x + 4);
  // Lexicographic rank among the nondecreasing tuples: at each position p, the tuples that agree
  // before p and have a smaller value v there, with the rest ≥ v.
  size_t rank = 0;
  for (int p = 0, lo = 0; p < order_; lo = x[p], ++p)
    for (int v = lo; v < x[p]; ++v) rank += multisets(dim_ - v, order_ - p - 1);
  return values_[rank];
}

void SymmetricTensor::plan() {
  const int m = dim_, P = m * (m + 1) / 2;
  pairs_.resize(P, order_ == 3 ? m : P);
  for (int p = 0, a = 0; p < m; ++p)
    for (int q = p; q < m; ++q, ++a) {
      if (order_ == 3) {
        for (int k = 0; k < m; ++k) pairs_(a, k) = (*this)(p, q, k);
      } else {
        for (int k = 0, b = 0; k < m; ++k)
          for (int l = k; l < m; ++l, ++b) pairs_(a, b) = (*this)(p, q, k, l);
      }
    }
}

void SymmetricTensor::contract_into(const Eigen::VectorXd& x, Eigen::MatrixXd& G) const {
  const int m = dim_;
  Eigen::VectorXd u;
  if (order_ == 3) {
    u.noalias() = pairs_ * x;
  } else {
    // u = W z with W the symmetric P × P matrix of the entries t_pqkl over the pairs and z the
    // products xₖxₗ (k ≤ l) times their multiplicity. The BLAS's symmetric product reads one
    // triangle of W: half the memory traffic of a general product, which bounds this O(m⁴) step
    // (2.0× Eigen's general product at P = 210 with OpenBLAS on this machine, docs/benchmarks/reduced.md).
    const int P = static_cast<int>(pairs_.rows());
    Eigen::VectorXd z(P);
    for (int k = 0, b = 0; k < m; ++k)
      for (int l = k; l < m; ++l, ++b) z[b] = (k == l ? 1.0 : 2.0) * x[k] * x[l];
    u.resize(P);
    if (P > 0) cblas_dsymv(CblasColMajor, CblasLower, P, 1.0, pairs_.data(), P, z.data(), 1, 0.0, u.data(), 1);
  }
  for (int p = 0, a = 0; p < m; ++p) {
    G(p, p) += u[a++];
    for (int q = p + 1; q < m; ++q, ++a) {
      G(p, q) += u[a];
      G(q, p) += u[a];
    }
  }
}

void ReducedBodyMatrices::geometric_terms(const Eigen::VectorXd& xi, Eigen::MatrixXd& G1, Eigen::MatrixXd& G2) const {
  const int m = elastic();
  G1 = Eigen::MatrixXd::Zero(m, m);
  G2 = Eigen::MatrixXd::Zero(m, m);
  if (!T.empty()) T.contract_into(xi, G1);  // ~m³/2 products
  if (!Q.empty()) Q.contract_into(xi, G2);  // ~m⁴/4 products
}

Eigen::VectorXd ReducedBodyMatrices::elastic_force(const Eigen::VectorXd& xi) const {
  Eigen::MatrixXd G1, G2;
  geometric_terms(xi, G1, G2);
  return K * xi + (0.5 * G1 + G2 / 6.0) * xi;
}

void ReducedBodyMatrices::check() const {
  const int m = elastic(), n = 6 + m;
  if (K.cols() != m || M0.rows() != n || M0.cols() != n || static_cast<int>(C.size()) != m || static_cast<int>(M2.size()) != m * m)
    throw std::invalid_argument("reduced body: the matrices' sizes do not agree with " + std::to_string(m) + " elastic coordinates");
  for (const Eigen::MatrixXd& c : C)
    if (c.rows() != 3 || c.cols() != n) throw std::invalid_argument("reduced body: a coupling matrix is not 3 x (6 + m)");
  if ((M0 - M0.transpose()).norm() > 1e-12 * M0.norm() || (K - K.transpose()).norm() > 1e-12 * (K.norm() + 1e-300))
    throw std::invalid_argument("reduced body: M0 and K must be symmetric");
  if (!T.empty() && (T.order() != 3 || T.dim() != m))
    throw std::invalid_argument("reduced body: the geometric stiffness is of order " + std::to_string(T.order()) + " on " +
                                std::to_string(T.dim()) + " indices for " + std::to_string(m) + " elastic coordinates (order 3 expected)");
  if (!Q.empty() && (T.empty() || Q.order() != 4 || Q.dim() != m))
    throw std::invalid_argument("reduced body: the quartic stiffness needs the cubic one and order 4 on the elastic coordinates");
  // M₂ᵢⱼ = DᵢᵀM̄Dⱼ, so M₂ᵢⱼᵀ = M₂ⱼᵢ: 𝕄's quadratic part is symmetric (the closed-form tangent uses it).
  double scale = 0.0, asym = 0.0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) {
      scale = std::max(scale, M2[static_cast<size_t>(i * m + j)].norm());
      asym = std::max(asym, (M2[static_cast<size_t>(i * m + j)] - M2[static_cast<size_t>(j * m + i)].transpose()).norm());
    }
  if (asym > 1e-12 * scale) throw std::invalid_argument("reduced body: the quadratic inertia blocks must satisfy M2[i][j] = M2[j][i]^T");
}

ReducedBody::ReducedBody(std::string name, int frame, const std::vector<int>& coordinates, ReducedBodyMatrices matrices,
                         const Eigen::Vector3d& gravity)
    : Element(std::move(name), [&] {
        std::vector<int> n{frame};
        n.insert(n.end(), coordinates.begin(), coordinates.end());
        return n;
      }()),
      m_(std::move(matrices)), g_(gravity) {
  m_.check();
  if (static_cast<int>(coordinates.size()) != m_.elastic())
    throw std::invalid_argument("reduced body: " + std::to_string(coordinates.size()) + " coordinate nodes for " +
                                std::to_string(m_.elastic()) + " elastic coordinates");
  const int m = m_.elastic(), n = 6 + m;
  C_.resize(3 * m, n);
  S_.resize(3 * m, 3 * m);
  for (int i = 0; i < m; ++i) {
    C_.middleRows<3>(3 * i) = m_.C[static_cast<size_t>(i)];
    for (int j = 0; j < m; ++j)
      S_.block<3, 3>(3 * i, 3 * j) = m_.M2[static_cast<size_t>(i * m + j)] + m_.M2[static_cast<size_t>(j * m + i)];
  }
  S_ = 0.5 * (S_ + S_.transpose()).eval();  // symmetric to round-off (check()); exactly, for the tangent
}

template <class S>
Eigen::Matrix<S, Eigen::Dynamic, 1> ReducedBody::residual(const Eigen::Matrix<S, 3, 3>& R, const VecS<S>& xi, const VecS<S>& v,
                                                          const VecS<S>& a, double load_factor) const {
  const int m = m_.elastic(), n = 6 + m;
  const V3<S> xd = v.template head<3>(), om = v.template segment<3>(3);
  const V3<S> u = R.transpose() * xd;
  V3<S> acc = a.template head<3>();
  for (int k = 0; k < 3; ++k) acc[k] -= load_factor * g_[k];
  const V3<S> ud = V3<S>(R.transpose() * acc) - cross<S>(om, u);  // u̇ = Rᵀ(ẍ − g) − ω × u
  VecS<S> w(n), wd(n);
  w << u, om, v.tail(m);
  wd << ud, a.template segment<3>(3), a.tail(m);
  const MatS<S> Mx = mass_of<S>(m_, xi);
  const VecS<S> h = Mx * w;
  VecS<S> hd = Mx * wd;
  VecS<S> r(n);
  for (int i = 0; i < m; ++i) {
    const VecS<S> dMw = mass_derivative_times<S>(m_, xi, i, w);
    hd += v[6 + i] * dMw;  // Σ ξ̇ᵢ ∂𝕄/∂ξᵢ w
    r[6 + i] = -0.5 * w.dot(dMw);
  }
  const V3<S> hu = h.template head<3>(), hw = h.template segment<3>(3);
  r.template head<3>() = R * V3<S>(hd.template head<3>() + cross<S>(om, hu));
  r.template segment<3>(3) = hd.template segment<3>(3) + cross<S>(om, hw) + cross<S>(u, hu);
  for (int i = 0; i < m; ++i) {
    S k = S(0.0);
    for (int j = 0; j < m; ++j) k += m_.K(i, j) * xi[j];
    // Geometric stiffness: ∂(⅙ T[ξ,ξ,ξ])/∂ξᵢ = ½ Σⱼₖ T(i, j, k) ξⱼ ξₖ — every entry of the full
    // tensor, read through the packed storage: the reference the packed contraction is tested on.
    if (!m_.T.empty())
      for (int kk = 0; kk < m; ++kk)
        for (int j = 0; j < m; ++j) k += 0.5 * m_.T(i, j, kk) * xi[j] * xi[kk];
    // Quartic term: ⅙ Σⱼₖₗ Q(i, j, k, l) ξⱼ ξₖ ξₗ.
    if (!m_.Q.empty())
      for (int kk = 0; kk < m; ++kk)
        for (int l = 0; l < m; ++l)
          for (int j = 0; j < m; ++j) k += (1.0 / 6.0) * m_.Q(i, j, kk, l) * xi[j] * xi[kk] * xi[l];
    r[6 + i] += hd[6 + i] + k;
  }
  return r;
}

// Closed-form residual and exact tangent (docs/theory/reduced_bodies.md, "Closed-form residual
// and tangent"). Notation as there: w = [u; ω; ξ̇], ẇ = [u̇; ω̇; ξ̈], 𝕄 = M₀ + E_ω C(ξ) + C(ξ)ᵀE_ωᵀ
// + E_ω J(ξ) E_ωᵀ with C(ξ) = Σ ξᵢ Cᵢ and J(ξ) = ½ Σ ξᵢ ξⱼ Sᵢⱼ; Gᵢ = Σⱼ ξⱼ Sᵢⱼ, so that
// (∂𝕄/∂ξᵢ) x = E_ω (Cᵢ x + Gᵢ x_ω) + Cᵢᵀ x_ω is column i of A(x); Ṁ = N = Σ ξ̇ᵢ ∂𝕄/∂ξᵢ.
void ReducedBody::evaluate(const LocalState& s, LocalResidual& out, bool tangent) const {
  using Eigen::Matrix3d;
  using Eigen::MatrixXd;
  using Eigen::Vector3d;
  using Eigen::VectorXd;
  const int m = m_.elastic(), n = 6 + m;
  const Matrix3d R = pose_of(s.q.data()).R;
  const auto xi = s.q.segment(7, m);
  const auto xid = s.v.tail(m);
  const Vector3d om = s.v.segment<3>(3);
  const Vector3d u = R.transpose() * s.v.head<3>();
  const Vector3d b = R.transpose() * (s.qdd.head<3>() - s.load_factor * g_);  // Rᵀ(ẍ − g)
  VectorXd w(n), wd(n);
  w << u, om, xid;
  wd << b - om.cross(u), s.qdd.segment<3>(3), s.qdd.tail(m);
  // SX = S (ξ ⊗ I₃): its block i is Gᵢ; J = ½ Σ ξᵢ Gᵢ; C(ξ).
  MatrixXd kx = MatrixXd::Zero(3 * m, 3);
  for (int i = 0; i < m; ++i) kx.middleRows<3>(3 * i).diagonal().setConstant(xi[i]);
  const MatrixXd SX = S_ * kx;
  Matrix3d J = Matrix3d::Zero();
  Eigen::Matrix<double, 3, Eigen::Dynamic> Cx = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, n);
  for (int i = 0; i < m; ++i) {
    J += 0.5 * xi[i] * SX.middleRows<3>(3 * i);
    Cx += xi[i] * C_.middleRows<3>(3 * i);
  }
  MatrixXd Mm = m_.M0;
  Mm.middleRows<3>(3) += Cx;
  Mm.middleCols<3>(3) += Cx.transpose();
  Mm.block<3, 3>(3, 3) += J;
  const auto A_of = [&](const VectorXd& x) {
    MatrixXd A(n, m);
    const Vector3d xw = x.segment<3>(3);
    for (int i = 0; i < m; ++i) {
      A.col(i).noalias() = C_.middleRows<3>(3 * i).transpose() * xw;
      A.col(i).segment<3>(3) += C_.middleRows<3>(3 * i) * x + SX.middleRows<3>(3 * i) * xw;
    }
    return A;
  };
  const MatrixXd Aw = A_of(w);
  const VectorXd h = Mm * w;
  const VectorXd hd = Mm * wd + Aw * xid;  // ḣ = 𝕄 ẇ + Ṁ w
  const Vector3d hu = h.head<3>(), hw = h.segment<3>(3);
  const Vector3d y = hd.head<3>() + om.cross(hu);
  out.r.head<3>() += R * y;
  out.r.segment<3>(3) += hd.segment<3>(3) + om.cross(hw) + u.cross(hu);
  out.r.tail(m) += hd.tail(m) - 0.5 * Aw.transpose() * w + m_.K * xi;
  // Geometric stiffness (header): force (½ G₁ + ⅙ G₂) ξ, tangent G₁ + ½ G₂, from the packed tensors.
  MatrixXd G1, G2;
  if (!m_.T.empty()) {
    m_.geometric_terms(xi, G1, G2);
    out.r.tail(m) += (0.5 * G1 + G2 / 6.0) * xi;
  }
  if (!tangent) return;

  const Matrix3d om_h = hat<double>(om), u_h = hat<double>(u);
  // F_w = ∂(y, r_θ, r_ξ)/∂w at fixed ẇ, ξ: ∂ḣ/∂w = N + [0 | A(w)] (ξ̇ is part of w).
  Eigen::Matrix<double, 3, Eigen::Dynamic> Cd = Eigen::Matrix<double, 3, Eigen::Dynamic>::Zero(3, n);
  Matrix3d Gd = Matrix3d::Zero();
  for (int i = 0; i < m; ++i) {
    Cd += xid[i] * C_.middleRows<3>(3 * i);
    Gd += xid[i] * SX.middleRows<3>(3 * i);
  }
  MatrixXd Fw = MatrixXd::Zero(n, n);
  Fw.middleRows<3>(3) += Cd;
  Fw.middleCols<3>(3) += Cd.transpose();
  Fw.block<3, 3>(3, 3) += Gd;
  Fw.rightCols(m) += Aw;
  Fw.topRows<3>() += om_h * Mm.topRows<3>();
  Fw.block<3, 3>(0, 3) -= hat<double>(hu);
  Fw.middleRows<3>(3) += om_h * Mm.middleRows<3>(3) + u_h * Mm.topRows<3>();
  Fw.block<3, 3>(3, 3) -= hat<double>(hw);
  Fw.block<3, 3>(3, 0) -= hat<double>(hu);
  Fw.bottomRows(m) -= Aw.transpose();
  // F_ξ = ∂(y, r_θ, r_ξ)/∂ξ at fixed w, ẇ: ∂ḣ/∂ξⱼ = A(ẇ)ⱼ + E_ω (Σᵢ ξ̇ᵢ Sᵢⱼ) w_ω, ∂h/∂ξ = A(w),
  // ∂²(½ wᵀ𝕄w)/∂ξᵢ∂ξⱼ = ½ w_ωᵀ Sᵢⱼ w_ω.
  MatrixXd kxd = MatrixXd::Zero(3 * m, 3);
  for (int i = 0; i < m; ++i) kxd.middleRows<3>(3 * i).diagonal().setConstant(xid[i]);
  const MatrixXd SXd = S_ * kxd;
  MatrixXd Fx = A_of(wd);
  MatrixXd SW(3 * m, m);
  for (int j = 0; j < m; ++j) {
    Fx.col(j).segment<3>(3) += SXd.middleRows<3>(3 * j) * om;
    SW.col(j).noalias() = S_.middleCols<3>(3 * j) * om;
  }
  Fx.topRows<3>() += om_h * Aw.topRows<3>();
  Fx.middleRows<3>(3) += om_h * Aw.middleRows<3>(3) + u_h * Aw.topRows<3>();
  Fx.bottomRows(m) += m_.K;
  if (!m_.T.empty()) Fx.bottomRows(m) += G1 + 0.5 * G2;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) Fx(6 + i, j) -= 0.5 * om.dot(SW.col(j).segment<3>(3 * i));
  // Chain rule to the unknowns: ∂w/∂(ẋ, ω, ξ̇) = diag(Rᵀ, I, I); u̇ = b − ω × u with
  // ∂u/∂δθ = û, ∂b/∂δθ = b̂ (R → R(I + δθ^)), ∂u̇/∂ẋ = −ω̂Rᵀ, ∂u̇/∂ω = û; r_x = R y adds −R ŷ in δθ.
  const auto Mu = Mm.leftCols<3>();
  MatrixXd Kq(n, 3 + m);
  Kq.leftCols<3>() = Fw.leftCols<3>() * u_h + Mu * (hat<double>(b) - om_h * u_h);
  Kq.rightCols(m) = Fx;
  MatrixXd Cv(n, n);
  Cv.leftCols<3>() = (Fw.leftCols<3>() - Mu * om_h) * R.transpose();
  Cv.middleCols<3>(3) = Fw.middleCols<3>(3) + Mu * u_h;
  Cv.rightCols(m) = Fw.rightCols(m);
  MatrixXd Ma = Mm;
  Ma.leftCols<3>() = Mu * R.transpose();
  Kq.topRows<3>() = (R * Kq.topRows<3>()).eval();
  Kq.block<3, 3>(0, 0) -= R * hat<double>(y);
  Cv.topRows<3>() = (R * Cv.topRows<3>()).eval();
  Ma.topRows<3>() = (R * Ma.topRows<3>()).eval();
  out.K.rightCols(3 + m) += Kq;
  out.C += Cv;
  out.M += Ma;
}

double ReducedBody::elastic_energy(const Eigen::VectorXd& q) const {
  const Eigen::VectorXd xi = q.segment(7, m_.elastic());
  double e = 0.5 * xi.dot(m_.K * xi);
  if (!m_.T.empty()) {
    Eigen::MatrixXd G1, G2;
    m_.geometric_terms(xi, G1, G2);
    e += xi.dot(G1 * xi) / 6.0 + xi.dot(G2 * xi) / 24.0;
  }
  return e;
}

void reduced_body_tangent_by_ad(const ReducedBody& body, const LocalState& s, LocalResidual& out) {
  const int m = body.matrices().elastic(), n = 6 + m;
  const Pose<double> f = pose_of(s.q.data());
  // The variables are δθ (R → R(I + δθ^), the same first derivative as R exp(δθ^)), ξ, v and q̈;
  // r does not depend on the frame's position.
  using AD = Eigen::AutoDiffScalar<Eigen::VectorXd>;
  const int nv = 3 + m + 2 * n;
  Eigen::Matrix<AD, 3, 1> dth;
  for (int k = 0; k < 3; ++k) dth[k] = AD(0.0, nv, k);
  Eigen::Matrix<AD, 3, 3> W;
  W << AD(1.0), -dth[2], dth[1], dth[2], AD(1.0), -dth[0], -dth[1], dth[0], AD(1.0);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      if (W(i, j).derivatives().size() == 0) W(i, j).derivatives() = Eigen::VectorXd::Zero(nv);
    }
  const Eigen::Matrix<AD, 3, 3> R = f.R.cast<AD>() * W;
  VecS<AD> xa(m), va(n), aa(n);
  for (int i = 0; i < m; ++i) xa[i] = AD(s.q[7 + i], nv, 3 + i);
  for (int k = 0; k < n; ++k) {
    va[k] = AD(s.v[k], nv, 3 + m + k);
    aa[k] = AD(s.qdd[k], nv, 3 + m + n + k);
  }
  const VecS<AD> r = body.residual<AD>(R, xa, va, aa, s.load_factor);
  for (int i = 0; i < n; ++i) {
    out.r[i] += r[i].value();
    const Eigen::VectorXd& d = r[i].derivatives();
    if (d.size() == 0) continue;  // a constant entry
    for (int k = 0; k < 3; ++k) out.K(i, 3 + k) += d[k];
    for (int j = 0; j < m; ++j) out.K(i, 6 + j) += d[3 + j];
    for (int j = 0; j < n; ++j) {
      out.C(i, j) += d[3 + m + j];
      out.M(i, j) += d[3 + m + n + j];
    }
  }
}

template Eigen::Matrix<double, Eigen::Dynamic, 1> ReducedBody::residual<double>(const Eigen::Matrix3d&, const Eigen::VectorXd&,
                                                                                const Eigen::VectorXd&, const Eigen::VectorXd&,
                                                                                double) const;

}  // namespace alphaflex
