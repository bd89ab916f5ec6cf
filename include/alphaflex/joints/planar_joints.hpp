#pragma once
// Planar joints in absolute coordinates. Each constrains points (PlanarMarker) of two bodies, of
// which the second may be the ground. Sign convention of the reactions: the force and moment the
// joint exerts on body 1, f = −Φ_{r1}ᵀ λ (world frame).
//
// The joint types are the rows of one table, planar_joint_kinds() (planar_joints.cpp): the scene
// name and the names of the equations in the order of Φ, which Constraint::type(), size() and
// equation_name() read (redundancy and Newton messages: "equation 3 (θ1 − θ2)").
#include <string>
#include <vector>

#include "alphaflex/model/constraint.hpp"
#include "alphaflex/model/planar_marker.hpp"

namespace alphaflex {

/// A planar joint type: one row of planar_joint_kinds().
struct PlanarJointKind {
  std::string name;                    ///< the scene's `type`, and Constraint::type()
  std::vector<std::string> equations;  ///< the equations' names, in the order of Φ
};

/// The rows of planar_joint_kinds().
enum class PlanarJointType { revolute, point_on_line, prismatic, fixed };
/// Every planar joint type, indexed by PlanarJointType.
const std::vector<PlanarJointKind>& planar_joint_kinds();

/// What every planar joint takes from its row: its type name, its equation count and names.
class PlanarJoint : public Constraint {
 public:
  const char* type() const override { return kind_->name.c_str(); }
  int size() const override { return static_cast<int>(kind_->equations.size()); }
  std::string equation_name(int k) const override { return kind_->equations.at(static_cast<size_t>(k)); }

 protected:
  PlanarJoint(std::string name, std::vector<int> nodes, PlanarJointType type)
      : Constraint(std::move(name), std::move(nodes)), kind_(&planar_joint_kinds()[static_cast<size_t>(type)]) {}

 private:
  const PlanarJointKind* kind_;
};

/// Pin: point 1 of body 1 and point 2 of body 2 coincide, Φ = r1 − r2 (2 equations).
/// A point fixed to the ground is a revolute joint whose body 2 is the ground.
class RevoluteJoint2D final : public PlanarJoint {
 public:
  RevoluteJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2);
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<RevoluteJoint2D>(*this); }
  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                         Eigen::VectorXd& c) const override;
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

 private:
  PlanarMarker p1_, p2_;
};

/// Point 1 of body 1 stays on the line through point 2 of body 2 with direction `axis` (body-2
/// frame): Φ = n·(r1 − r2) with n = R(θ2)·perp(axis) (1 equation).
class PointOnLineJoint2D : public PlanarJoint {
 public:
  PointOnLineJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                     const Eigen::Vector2d& axis);
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<PointOnLineJoint2D>(*this); }
  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                         Eigen::VectorXd& c) const override;
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

 protected:
  /// A point-on-line joint with the equations of `type` (prismatic: and the angle).
  PointOnLineJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                     const Eigen::Vector2d& axis, PlanarJointType type);
  /// World unit normal n and tangent t of the line.
  void frame(const Eigen::VectorXd& q, Eigen::Vector2d& n, Eigen::Vector2d& t) const;
  PlanarMarker p1_, p2_;
  Eigen::Vector2d axis_;
};

/// Slider: point on line plus fixed relative rotation, Φ = [n·(r1 − r2); θ1 − θ2 − θ0] (2 equations).
class PrismaticJoint2D final : public PointOnLineJoint2D {
 public:
  PrismaticJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                   const Eigen::Vector2d& axis, double relative_angle);
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<PrismaticJoint2D>(*this); }
  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                         Eigen::VectorXd& c) const override;
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

 private:
  double theta0_;
};

/// Clamp: point 1 of body 1 and point 2 of body 2 coincide and their relative rotation keeps its
/// initial value, Φ = [r1 − r2; θ1 − θ2 − θ0] (3 equations). Holds a beam end or welds two bodies.
class FixedJoint2D final : public PlanarJoint {
 public:
  FixedJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2, double relative_angle);
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<FixedJoint2D>(*this); }
  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                         Eigen::VectorXd& c) const override;
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

 private:
  PlanarMarker p1_, p2_;
  double theta0_;
};

}  // namespace alphaflex
