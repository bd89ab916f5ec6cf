#pragma once
// Component mode synthesis of a flexible block (docs/theory/reduced_bodies.md): the block's linear
// stiffness and mass at its undeformed state, assembled from its own element kernels, and their
// reduction by Craig–Bampton (Craig & Bampton, AIAA J. 6 (1968) 1313) — static constraint modes of
// the interface coordinates and the lowest fixed-interface normal modes — and the rigid-body mass
// properties of the block (method `rigid`). Everything here is plain dense data: the reduced-body
// element (elements module, upstream) receives matrices, never a model.
//
// Two paths for the fixed-interface problem, one result: small blocks (or many modes asked) by the
// dense generalized symmetric solver (Eigen's GeneralizedSelfAdjointEigenSolver: every mode,
// M-orthonormal to round-off, which the exactness test with all modes kept needs; O(n³)); blocks
// of 10³–10⁴ coordinates by a sparse LDLᵀ factorization of K_ii for the constraint modes and the
// k lowest modes from SLEPc's Krylov–Schur with shift-and-invert at 0 (MUMPS), followed by a
// Rayleigh–Ritz step that makes them M-orthonormal to round-off (O(n · bandwidth² + n k²)).
#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "alphaflex/elements/reduced_body.hpp"

namespace alphaflex {

class Model;

/// The linear K and M of a set of elements at the model's initial state (q0, zero velocities and
/// accelerations), on the unknowns of the nodes they touch, in the nodes' own increments (δx world,
/// δθ node frame for Frame3D nodes). Sparse always (a node couples to its elements' nodes only:
/// O(n · bandwidth) numbers); dense copies only if asked (n² numbers: 1.6 GB at n = 10⁴).
struct BlockMatrices {
  std::vector<int> nodes;    ///< model node ids, ascending
  std::vector<int> offsets;  ///< first row of each node in K, M
  Eigen::SparseMatrix<double> K_sparse, M_sparse;  ///< exact zeros not stored
  Eigen::MatrixXd K, M;      ///< dense copies (assemble_block's `dense`), else empty
  /// The number of coordinates (rows of K).
  int size() const { return static_cast<int>(K_sparse.rows()); }
  /// Row of unknown `k` of model node `node`; -1 if the node is not in the block.
  int row_of(int node, int k = 0) const;
};

/// Assembles the elements `element_ids` (indices into model.elements()) at the initial state: the
/// sparse K, M from the elements' triplets, and with `dense` the dense copies as well (the same
/// sums in the same order: equal bit for bit). The reduction itself (craig_bampton, reduce_block,
/// nonlinear_stiffness) needs only the sparse ones. Throws std::invalid_argument if the list is empty.
BlockMatrices assemble_block(const Model& model, const std::vector<int>& element_ids, bool dense = true);

/// A superelement: full coordinates u = T ξ with ξ = [u_b; η], u_b the interface (boundary)
/// coordinates in the order given (T's rows there are [I, 0]), η the amplitudes of the kept normal
/// modes, ascending frequency: Craig–Bampton's fixed-interface modes (M-orthonormal, K̃ diagonal
/// on them), or Herting's free-interface modes less their constraint-mode part, M-orthonormalized
/// (K̃'s modal block full, not diagonal). Either way the constraint modes are K-orthogonal to the
/// normal-mode columns (those vanish on the interface) and M-coupled to them.
struct Superelement {
  std::vector<int> boundary;     ///< rows of the full matrices that are interface coordinates
  Eigen::MatrixXd T;             ///< n × (n_b + k): constraint modes, then normal modes
  Eigen::MatrixXd K, M;          ///< Tᵀ K T, Tᵀ M T (symmetric)
  Eigen::VectorXd frequencies;   ///< Hz: the kept fixed-interface (Craig–Bampton) or free-interface (Herting) modes
  int interface_size() const { return static_cast<int>(boundary.size()); }
  int modes() const { return static_cast<int>(frequencies.size()); }
};

/// How many fixed-interface modes a block with `n` coordinates and `n_boundary` interface
/// coordinates has (the most `craig_bampton` accepts).
inline int available_modes(int n, int n_boundary) { return n - n_boundary; }

/// Craig–Bampton reduction of (K, M) with the interface rows `boundary` (distinct, in range) and
/// `modes` fixed-interface modes. Throws std::invalid_argument (message names what is wrong) if
/// `boundary` is empty (a free block has no constraint modes: give it an interface or a support),
/// repeats or leaves the range, if `modes` is negative or more than the block has, or if the
/// interior is not restrained by the interface (K_ii singular: a mechanism inside the block).
Superelement craig_bampton(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const std::vector<int>& boundary, int modes);

/// Which solver gives the fixed-interface modes: `automatic` takes the dense one for an interior
/// of at most 300 coordinates or when more than a quarter of the interior's modes are asked
/// (then the dense solver is the cheaper), the sparse one (LDLᵀ + SLEPc) otherwise.
enum class ModeSolver { automatic, dense, sparse };

/// craig_bampton on sparse K, M (same result and errors; each mode's sign is fixed by a rule both
/// paths share — its product with a fixed quasi-random vector is positive — so they can be compared).
Superelement craig_bampton(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M,
                           const std::vector<int>& boundary, int modes, ModeSolver solver = ModeSolver::automatic);

/// Herting's free-interface reduction (Herting, Finite Elem. Anal. Des. 1 (1985) 153; in the form of
/// Sonneville, Scapolan, Shan & Bauchau, Multibody Syst. Dyn. 51 (2021) 377; docs/theory/
/// reduced_bodies.md, "Herting's free-interface basis"): T = [[I, 0], [Ψ, V_i − Ψ V_b]] with Ψ the
/// static constraint modes (as craig_bampton) and V the `modes` lowest elastic normal modes of the
/// whole block (K v = ω² M v, interface free), so every kept free-interface mode is in the basis
/// (its first j columns span the first j modes less their constraint-mode parts, M-orthonormalized
/// in frequency order; a column that adds nothing to the span — below 1e-6 of its M-norm — gets no
/// amplitude, so `modes` may be up to n and the basis is then complete) and the interface
/// coordinates stay generalized coordinates. A free
/// block's rigid-body modes (ω² below 1e-12 of the largest on the dense path) are not counted:
/// the constraint modes hold them. `boundary` may be empty for a supported block (K positive
/// definite): then T is the modes. The same errors as craig_bampton ("free-interface modes"), and
/// an empty `boundary` on a free block ("no interface and no support"); the sparse path (LDLᵀ +
/// SLEPc shift-and-invert at 0) needs a supported block, a free block above its size is refused.
Superelement herting(const Eigen::MatrixXd& K, const Eigen::MatrixXd& M, const std::vector<int>& boundary, int modes);
/// herting on sparse K, M; `automatic` takes the dense path for a block of at most 300 coordinates
/// or when more than a quarter of its modes are asked.
Superelement herting(const Eigen::SparseMatrix<double>& K, const Eigen::SparseMatrix<double>& M, const std::vector<int>& boundary,
                     int modes, ModeSolver solver = ModeSolver::automatic);

/// The component modes a reduced block keeps (`reduction.method`).
enum class Reduction { craig_bampton, herting };

/// Rigid-body mass properties of a block: its kinetic energy under rigid motions of all its nodes,
/// Gᵀ M G with G the 6 rigid modes (translation, rotation about the world origin).
struct RigidMassProperties {
  double mass = 0.0;                                    ///< kg
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();     ///< m, world: centre of mass at t = 0
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();    ///< kg·m², world axes, about the centre
};

/// From the block matrices and the model's initial poses of the block's (Frame3D) nodes. Throws
/// std::invalid_argument if a node is not a spatial frame or the mass is not positive.
RigidMassProperties rigid_mass_properties(const Model& model, const BlockMatrices& block);

/// A block reduced on a floating frame (docs/theory/reduced_bodies.md): the frame is the pose of
/// the reference interface node, the basis the Craig–Bampton (or Herting) modes of the block with
/// that node clamped (constraint modes of the other interface nodes, then `modes` fixed-interface
/// (free-interface) modes).
struct ReducedBlock {
  int frame_node = -1;                 ///< model node id of the reference interface node
  Superelement superelement;           ///< on the block's coordinates without the frame node's
  ReducedBodyMatrices matrices;        ///< the element's plain data
  /// Per block node (BlockMatrices order): position in the frame at t = 0 (m), rotation of the
  /// node frame relative to the floating frame, and the node's 6 rows of the basis (δx in the
  /// floating frame's axes, δθ in the node frame) per elastic coordinate.
  std::vector<Eigen::Vector3d> positions;
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::MatrixXd> shapes;  ///< 6 × m each
  /// The pose (x, R) of block node `a` for the frame pose (x_f, R_f) and amplitudes ξ:
  /// x = x_f + R_f (X_a + Φᵗ_a ξ), R = R_f R_a exp((Φʳ_a ξ)^).
  void node_pose(size_t a, const Eigen::Vector3d& xf, const Eigen::Matrix3d& Rf, const Eigen::VectorXd& xi, Eigen::Vector3d& x,
                 Eigen::Matrix3d& R) const;
};

/// Reduces `block` (all its nodes Frame3D) on the frame of `frame_node` with the other interface
/// nodes `interface_nodes` (their 6 coordinates each become constraint-mode coordinates) and
/// `modes` fixed-interface modes; with `inertia_modes`, the static responses to the body-frame
/// inertia loads after them (up to 12 more coordinates: uniform and linear acceleration fields,
/// M-orthonormalized against the modes; docs/theory/reduced_bodies.md, "Geometric stiffness");
/// `method`: craig_bampton or herting (free-interface modes of the block with the frame node
/// clamped, the other interface nodes free; with no other interface node the two coincide).
/// Throws std::invalid_argument (craig_bampton's or herting's messages, or a node that is not in the block).
ReducedBlock reduce_block(const Model& model, const BlockMatrices& block, int frame_node, const std::vector<int>& interface_nodes,
                          int modes, bool inertia_modes = false, Reduction method = Reduction::craig_bampton);

/// Static modal derivatives (Idelsohn & Cardona, CMAME 49 (1985) 253; in a floating frame Wu &
/// Tiso, Multibody Syst. Dyn. 36 (2016) 405): for each pair i ≤ j of the first `columns` vectors of
/// the basis of `rb` (constraint modes first, then the normal modes, then any inertia modes), θᵢⱼ
/// with K θᵢⱼ = −∂²f/∂ξᵢ∂ξⱼ on the block's interior (frame node and interface held), f the
/// internal forces of the block's elements `element_ids` at the poses node_pose gives (central
/// differences, steps as nonlinear_stiffness). θᵢⱼ is the second-order static response to a
/// deformation along ξ: for a beam, the axial foreshortening that bending brings and a linear
/// basis lacks (membrane locking, docs/theory/reduced_bodies.md "Modal derivatives"). They are
/// M-orthonormalized against the normal modes and each other (a derivative below 10⁻⁶ of the
/// largest, or dependent to 10⁻⁶, is dropped), appended to the basis, and rb's node data and
/// inertia invariants recomputed; call before nonlinear_stiffness, which then takes them in.
/// Returns how many were appended. Throws std::invalid_argument if `columns` is negative or more
/// than the basis has.
int add_modal_derivatives(const Model& model, const std::vector<int>& element_ids, const BlockMatrices& block, int columns,
                          ReducedBlock& rb);

/// The cubic and quartic terms of the block's elastic energy along the basis of `rb`
/// (docs/theory/reduced_bodies.md, "Geometric stiffness"), stored in rb.matrices.T and .Q (their
/// unique entries): T(i, j, k) = ∂³U/∂ξᵢ∂ξⱼ∂ξₖ, Q(i, j, k, l) = ∂⁴U/∂ξᵢ∂ξⱼ∂ξₖ∂ξₗ at ξ = 0, U(ξ) the energy of the
/// block's own (nonlinear) elements `element_ids` at the poses ReducedBlock::node_pose gives (frame
/// at its initial pose). Computed once, by central second and third differences of the projected
/// internal force f̃ᵢ(ξ) = ∂U/∂ξᵢ (exact: the nodes' forces — Element::internal_force, the elastic
/// force alone, where the elements offer it (beams, shells); else evaluate() at rest — times the
/// derivative of node_pose, with the tangent operator of exp for the rotations), stencils whose even (second) or odd (third)
/// terms cancel: error O(h²), h = 10⁻³ of the block's size in each direction's largest
/// displacement; 2m² + 4m³/3 block evaluations. Both are made fully symmetric; `asymmetry` (if
/// given) receives T's max |T − T_sym| / max |T| before (a check of the differences). Throws
/// std::invalid_argument if the block is not stress-free at ξ = 0.
void nonlinear_stiffness(const Model& model, const std::vector<int>& element_ids, const BlockMatrices& block, ReducedBlock& rb,
                         double* asymmetry = nullptr);

}  // namespace alphaflex
