#pragma once
// The full mesh of a reduced flexible body, rebuilt from the body's state (issue 19;
// docs/theory/reduced_bodies.md, "Reconstruction"): the block's mesh nodes are no nodes of the
// model (their motion is the floating frame's and the amplitudes'), so the results, the sensors
// and the section forces ask this object for them. A point a of the block (a mesh node) moves as
//   x_a = x_f + R_f (X_a + Φᵗ_a ξ),   R_a = R_f R⁰_a exp((Φʳ_a ξ)^)
// (the reduced body's kinematics, linear in ξ: modal/superelement.hpp, ReducedBlock), and the
// block's own elements, kept on the points' indices 0 … n−1, recover their section forces from
// these poses with their own output() — the same recovery as a full mesh's.
//
// Plain data and functions of the model layer: the elements module's ReducedBody holds one (shared,
// immutable) and offers it through the capability `Reconstructed` (a second base class, asked for
// by dynamic_cast, so that Element's interface, which every file includes, stays as it is); io
// draws it and sensors read it without knowing any element type.
#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "alphaflex/model/element.hpp"

namespace alphaflex {

/// x = x_f + R_f (X + Φᵗ ξ), R = R_f R₀ exp((Φʳ ξ)^) for a point with rest position X and rest
/// rotation R₀ in the floating frame and basis rows `shape` (6 × m: δx in the frame's axes, δθ in
/// the point's frame).
void reduced_point_pose(const Eigen::Vector3d& X, const Eigen::Matrix3d& R0, const Eigen::MatrixXd& shape, const Eigen::Vector3d& xf,
                        const Eigen::Matrix3d& Rf, const Eigen::VectorXd& xi, Eigen::Vector3d& x, Eigen::Matrix3d& R);

class MeshReconstruction {
 public:
  /// One mesh node of the block.
  struct Point {
    Eigen::Vector3d X = Eigen::Vector3d::Zero();         ///< rest position in the floating frame (m)
    Eigen::Matrix3d R0 = Eigen::Matrix3d::Identity();    ///< rest rotation relative to the floating frame
    Eigen::MatrixXd shape;                               ///< 6 × m basis rows
    Eigen::Vector3d initial = Eigen::Vector3d::Zero();   ///< world position at t = 0 (m), for displacements
  };
  /// `elements`: the block's elements on point indices (Frame3D points: 7 configuration numbers,
  /// 6 unknowns each); `names`: the named mesh points' names (empty for the others; none given:
  /// all empty). Throws std::invalid_argument if an element names a point out of range, the
  /// shapes' widths differ or the names are not one per point.
  /// `derived`: recomputes, in place, the results that are no linear function of the others from
  /// the recovered odd part (a shell's von Mises stresses from its resultants: the odd part of an
  /// even function of ξ would be zero); none: all results are recovered as the odd part.
  using Derived = std::function<void(Eigen::VectorXd& values)>;
  /// How element results are recovered (element_outputs): `odd_part` ½ [S(ξ) − S(−ξ)], for a body
  /// whose basis has no second-order shapes; `whole` S(ξ), for a basis with modal derivatives
  /// (modal/superelement.hpp add_modal_derivatives): their amplitudes carry the foreshortening that
  /// cancels the even strain of the bending shapes, so the even part is physical and the odd part
  /// alone would keep the derivatives' membrane strain without what it cancels.
  enum class Recovery { odd_part, whole };
  MeshReconstruction(std::vector<Point> points, std::vector<std::shared_ptr<const Element>> elements,
                     std::vector<std::string> names = {}, Derived derived = {}, Recovery recovery = Recovery::odd_part);

  size_t points() const { return points_.size(); }
  const Point& point(size_t a) const { return points_[a]; }
  const std::string& name(size_t a) const { return names_[a]; }
  const std::vector<std::shared_ptr<const Element>>& elements() const { return elements_; }
  int elastic() const { return m_; }
  /// The elements' structure ("beam") and result fields (the first element's).
  const char* structure() const;
  const std::vector<CellField>& cell_fields() const { return fields_; }

  /// The state of every point (7 configuration numbers, 6 velocities each; accelerations zero:
  /// nothing read from here needs them) from the reduced body's local state `body` (the frame
  /// node's 7 numbers then ξ; velocities ẋ_f, Ω_f, ξ̇). Velocities are the time derivatives of
  /// the pose map: ẋ_a = ẋ_f + R_f (Ω_f × (X_a + Φᵗ_a ξ) + Φᵗ_a ξ̇),
  /// Ω_a = exp(−φ_a) R⁰_aᵀ Ω_f + T(φ_a) Φʳ_a ξ̇, φ_a = Φʳ_a ξ (T: core/rotation.hpp's tangent_so3).
  LocalState state(const LocalState& body) const;
  /// Point a's position x_a alone (state()'s, to the last bit: the same expressions), for a sensor
  /// of one point: rebuilding the whole mesh per sensor and step costs O(points) instead.
  Eigen::Vector3d point_position(const LocalState& body, size_t a) const;
  /// Element k's local state, cut from the points' state.
  LocalState element_state(const LocalState& points, size_t k) const;
  /// Every element's results (its output(): a beam's section forces and strains) recovered from
  /// the modes at the body's state: the part of the element's own recovery at the rebuilt poses
  /// that is odd in ξ, ½ [S(ξ) − S(−ξ)] (the frame pose and velocities as given). Why not S(ξ)
  /// alone: the body is linear elastic (V = ½ ξᵀ K̃ ξ, K̃ from the stress-free block), so its
  /// section forces are linear in ξ; the element's strain measure is exact (nonlinear), and at
  /// poses linear in ξ it adds even terms of second order — an axial strain ½ θ² per element for
  /// a rotation θ, an axial force EA θ²/2 that on a slender beam exceeds the bending loads (tested:
  /// 0.33 N on a 1 N tip-loaded cantilever). The odd part keeps the linear term exactly and
  /// leaves O(|ξ|³); S(0) = 0 (stress-free reference).
  std::vector<Eigen::VectorXd> element_outputs(const LocalState& body) const;
  /// Element k's results alone (element_outputs()[k], to the last bit: the same expressions on
  /// the same numbers), for a sensor of one element's section force: only the element's own points
  /// are rebuilt (at ξ and −ξ) and only it recovers, O(1) per sensor and step instead of O(mesh).
  Eigen::VectorXd element_output(const LocalState& body, size_t k) const;

  /// The layout of a reduced body's output (elements/reduced_body.hpp, ReducedBody::output):
  /// point_position (3 per point), point_displacement (3 per point), then each of the elements'
  /// result fields over all elements — value j of field f of element k at
  /// 6 n_points + Σ_{g<f} c_g n_elements + c_f k + j. `output_size`: its length; `output_index`:
  /// where value c of element k's own output (its fields in turn) goes; `output_cell`: the
  /// inverse for an index past the points' part (false for a point's index).
  Eigen::Index output_size() const;
  Eigen::Index output_index(size_t k, int c) const;
  bool output_cell(Eigen::Index index, size_t& k, int& c) const;

 private:
  std::vector<Point> points_;
  std::vector<std::shared_ptr<const Element>> elements_;
  std::vector<std::string> names_;
  std::vector<CellField> fields_;  // the first element's result fields (cell_fields())
  Derived derived_;
  Recovery recovery_ = Recovery::odd_part;
  int m_ = 0;
};

/// The capability of an element that stands for a mesh it does not hold (a reduced body): io asks
/// `dynamic_cast<const Reconstructed*>(&element)`.
class Reconstructed {
 public:
  virtual ~Reconstructed() = default;
  /// The mesh, or nullptr if none was attached (a rigid body without its mesh).
  virtual const MeshReconstruction* reconstruction() const = 0;
};

/// The mesh an element stands for, nullptr if none.
inline const MeshReconstruction* reconstruction_of(const Element& e) {
  const auto* r = dynamic_cast<const Reconstructed*>(&e);
  return r ? r->reconstruction() : nullptr;
}

}  // namespace alphaflex
