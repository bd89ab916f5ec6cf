#pragma once
// A reduced flexible body (docs/theory/reduced_bodies.md): a floating frame — the pose of the
// body's reference interface node, an ordinary Frame3D node that joints attach to unchanged —
// carrying small elastic deformations u = Φ ξ in a Craig–Bampton basis (constraint modes of the
// other interface nodes and fixed-interface normal modes, all computed with the reference node
// clamped), whose amplitudes ξ are scalar vector-space unknowns (one node each, like the joint
// coordinates of joints/joint_coordinate.hpp).
//
// Kinetic energy of the full mesh in the floating frame (Shabana, Dynamics of Multibody Systems,
// 4th ed. (2013), ch. 5; Cardona & Géradin, IJNME 32 (1991)): with w = [u; ω; ξ̇], u = Rᵀẋ,
//   T = ½ wᵀ 𝕄(ξ) w,  𝕄(ξ) = M₀ + Σᵢ ξᵢ (Cᵢ + Cᵢᵀ) + Σᵢⱼ ξᵢ ξⱼ M₂ᵢⱼ,
// where the matrices are projections of the block's consistent mass matrix (the "inertia
// invariants", computed by modal/superelement.hpp), V = ½ ξᵀ K̃ ξ. Euler–Poincaré equations on
// R³×SO(3)×Rᵐ (right-trivialized, h = 𝕄 w, ḣ = 𝕄 ẇ + Σ ξ̇ᵢ ∂𝕄/∂ξᵢ w, u̇ = Rᵀ(ẍ − g) − ω × u):
//   r_x = R (ḣ_u + ω × h_u)
//   r_θ = ḣ_ω + ω × h_ω + u × h_u
//   r_ξ = ḣ_ξ − ½ wᵀ ∂𝕄/∂ξ w + K̃ ξ
// All inertia coupling and gyroscopic (quadratic velocity) terms are kept; gravity enters as the
// uniform acceleration field −g of every mass particle (ẍ − g). r and its exact derivatives K, C, M
// (right-trivialized increments) are evaluated in closed form (docs/theory/reduced_bodies.md,
// "Closed-form residual and tangent": O((6 + m)² + m²) per call); the scalar-generic `residual`
// below, differentiated by forward AD (reduced_body_tangent_by_ad), is the reference the tests
// compare it with.
#include <memory>
#include <vector>

#include "alphaflex/model/element.hpp"
#include "alphaflex/model/mesh_reconstruction.hpp"

namespace alphaflex {

/// A fully symmetric tensor of order 3 or 4 on `dim` indices (the geometric stiffness's T and Q),
/// stored by its unique entries only — i ≤ j ≤ k (≤ l), lexicographic — C(m + 2, 3) and C(m + 3, 4)
/// numbers instead of m³ and m⁴ (m = 14: 560 and 2380 for 2744 and 38 416). Its contraction over
/// the last indices runs on the index pairs p ≤ q (P = m(m + 1)/2 of them): a P × m (order 3) or
/// symmetric P × P (order 4, the BLAS's symmetric product, the vector of pairs (k, l) weighted by
/// their multiplicity, 1 if k = l, else 2) matrix of the unique entries, made once
/// (docs/theory/reduced_bodies.md, "Geometric stiffness", cost).
class SymmetricTensor {
 public:
  SymmetricTensor() = default;
  /// The tensor whose unique entries are entry(i, j, k, l) for i ≤ j ≤ k (≤ l) (l = -1 for order 3).
  /// Throws std::invalid_argument unless order is 3 or 4 and dim ≥ 0.
  template <class F>
  SymmetricTensor(int order, int dim, F entry) : SymmetricTensor(order, dim) {
    size_t e = 0;
    for_each_unique([&](const int* x) { values_[e++] = entry(x[0], x[1], x[2], order_ == 4 ? x[3] : -1); });
    plan();
  }
  bool empty() const { return order_ == 0; }
  int order() const { return order_; }
  int dim() const { return dim_; }
  /// The unique entries, in the order above.
  const std::vector<double>& values() const { return values_; }
  /// The entry at any index (l = -1 for order 3): the unique entry of its sorted indices.
  double operator()(int i, int j, int k, int l = -1) const;
  /// Adds the contraction with x over the last order − 2 indices, G(p, q) += Σₖ t_pqk xₖ (order 3)
  /// or Σₖₗ t_pqkl xₖ xₗ (order 4), to the m × m matrix G (symmetric: the pairs p ≤ q computed,
  /// then mirrored): a matrix–vector product of P × m or P², about m³/2 or m⁴/4 products.
  void contract_into(const Eigen::VectorXd& x, Eigen::MatrixXd& G) const;

 private:
  SymmetricTensor(int order, int dim);
  // Calls f(x) for each sorted index tuple x (order_ entries), in the storage order.
  template <class F>
  void for_each_unique(F f) const {
    int x[4] = {0, 0, 0, 0};
    const int r = order_;
    if (dim_ == 0) return;
    while (true) {
      f(x);
      int p = r - 1;
      while (p >= 0 && x[p] == dim_ - 1) --p;
      if (p < 0) return;
      ++x[p];
      for (int q = p + 1; q < r; ++q) x[q] = x[p];
    }
  }
  void plan();
  int order_ = 0, dim_ = 0;
  std::vector<double> values_;
  // The contraction's matrix: rows the pairs (p ≤ q), columns the indices k (order 3) or the pairs
  // (k ≤ l) (order 4: symmetric), in lexicographic pair order.
  Eigen::MatrixXd pairs_;
};

/// The plain data of a reduced body, for m elastic coordinates (the element sees nothing else).
struct ReducedBodyMatrices {
  Eigen::MatrixXd M0;                 ///< (6 + m)²: 𝕄 at ξ = 0
  std::vector<Eigen::MatrixXd> C;     ///< m matrices 3 × (6 + m): the ω rows of ∂𝕄/∂ξᵢ's one-sided part
  std::vector<Eigen::Matrix3d> M2;    ///< m² matrices (i·m + j): the ω–ω block of 𝕄's quadratic part
  Eigen::MatrixXd K;                  ///< m × m: K̃, the elastic stiffness in the basis
  /// Geometric stiffness (docs/theory/reduced_bodies.md, "Geometric stiffness"): empty (a linear
  /// elastic force K̃ξ), or T(i, j, k) = ∂³U/∂ξᵢ∂ξⱼ∂ξₖ at ξ = 0 of the block's own nonlinear elastic
  /// energy and Q(i, j, k, l) = ∂⁴U/∂ξᵢ∂ξⱼ∂ξₖ∂ξₗ (empty: none), both fully symmetric and stored by
  /// their unique entries: U = ½ ξᵀK̃ξ + ⅙ T[ξ,ξ,ξ] + ¹⁄₂₄ Q[ξ,ξ,ξ,ξ], the elastic force
  /// K̃ξ + ½ T[ξ,ξ] + ⅙ Q[ξ,ξ,ξ] and its tangent K̃ + T[ξ] + ½ Q[ξ,ξ] (stress stiffening; the quartic
  /// term keeps U bounded below when the stretch is in the basis).
  SymmetricTensor T, Q;
  int elastic() const { return static_cast<int>(K.rows()); }
  /// 𝕄(ξ) (6 + m)².
  Eigen::MatrixXd mass_matrix(const Eigen::VectorXd& xi) const;
  /// G₁ = T[ξ] = Σₖ T(·, ·, k) ξₖ and G₂ = Q[ξ,ξ] = Σₖₗ Q(·, ·, k, l) ξₖ ξₗ (m × m; zero without
  /// them): the elastic force is K̃ξ + (½ G₁ + ⅙ G₂) ξ, its tangent K̃ + G₁ + ½ G₂. O(m⁴/4) with Q
  /// (SymmetricTensor::contract_into).
  void geometric_terms(const Eigen::VectorXd& xi, Eigen::MatrixXd& G1, Eigen::MatrixXd& G2) const;
  /// The elastic force K̃ξ + ½ T[ξ,ξ] + ⅙ Q[ξ,ξ,ξ].
  Eigen::VectorXd elastic_force(const Eigen::VectorXd& xi) const;
  /// Throws std::invalid_argument unless the sizes agree, M0 and K are symmetric and M2[i·m+j] = M2[j·m+i]ᵀ
  /// (to round-off: they are DᵢᵀM̄Dⱼ), T is empty or of order 3 on m indices, and Q empty or of
  /// order 4 on m indices with T.
  void check() const;
};

class ReducedBody final : public Element, public Reconstructed {
 public:
  /// `frame`: the reference Frame3D node; `coordinates`: the m scalar nodes of ξ (vector spaces
  /// with one unknown); `gravity` in m/s².
  ReducedBody(std::string name, int frame, const std::vector<int>& coordinates, ReducedBodyMatrices matrices,
              const Eigen::Vector3d& gravity);
  const char* type() const override { return "reduced_body"; }
  /// Its tangent (the quartic geometric term, O(m⁴) in the amplitudes) costs 2–5 residuals, and the
  /// small deformations a reduction is chosen for keep it nearly constant from step to step: modified
  /// Newton gained 1.16–4.5× on the reduced scenes of inputs/ (23–64 unknowns; docs/performance.md).
  const char* favours_modified_newton() const override {
    return "a reduced body, whose tangent costs several residuals and changes little from step to step";
  }
  std::unique_ptr<Element> clone() const override { return std::make_unique<ReducedBody>(*this); }
  void evaluate(const LocalState& s, LocalResidual& out, bool tangent) const override;
  /// ½ ξᵀ K̃ ξ (+ ⅙ T[ξ,ξ,ξ] with geometric stiffness) (J).
  double elastic_energy(const Eigen::VectorXd& q) const override;
  const ReducedBodyMatrices& matrices() const { return m_; }

  /// The residual at a state, for any scalar (double or AD): R the frame's rotation, the rest
  /// as in LocalState with the frame's 7 configuration numbers removed from q.
  template <class S>
  Eigen::Matrix<S, Eigen::Dynamic, 1> residual(const Eigen::Matrix<S, 3, 3>& R, const Eigen::Matrix<S, Eigen::Dynamic, 1>& xi,
                                               const Eigen::Matrix<S, Eigen::Dynamic, 1>& v,
                                               const Eigen::Matrix<S, Eigen::Dynamic, 1>& a, double load_factor) const;

  // ---- The full mesh it stands for (issue 19; reduced_body_output.cpp): the results draw it and
  // sensors read its points and section forces through output().

  /// Attaches the block's mesh (its points' basis rows must have m columns).
  void attach_reconstruction(std::shared_ptr<const MeshReconstruction> mesh);
  const MeshReconstruction* reconstruction() const override { return mesh_.get(); }
  /// With a mesh: `point_position` and `point_displacement` (3 per point, world, m), then each
  /// field of the block's elements over all elements (element k's components at k·c …), so that
  /// output_names() reads `point_position[3a+i]`, `M3[k]`. Without one: none.
  std::vector<CellField> cell_fields() const override;
  void output(const LocalState& s, Eigen::VectorXd& values) const override;

 private:
  ReducedBodyMatrices m_;
  Eigen::Vector3d g_;
  // The invariants packed for the closed form: C_ stacks the Cᵢ (3m × (6 + m)); S_ (3m × 3m,
  // symmetric) has the blocks Sᵢⱼ = M₂ᵢⱼ + M₂ⱼᵢ.
  Eigen::MatrixXd C_, S_;
  std::shared_ptr<const MeshReconstruction> mesh_;
};

/// The reference tangent: r, K, C, M of `body` at `s` by forward automatic differentiation of
/// ReducedBody::residual (the former evaluate(); ~1 ms at m = 14). For tests and benchmarks.
void reduced_body_tangent_by_ad(const ReducedBody& body, const LocalState& s, LocalResidual& out);

}  // namespace alphaflex
