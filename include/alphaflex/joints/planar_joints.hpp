#pragma once
// Planar joints in absolute coordinates. Each constrains points (PlanarMarker) of two bodies, of
// which the second may be the ground. Sign convention of the reactions: the force and moment the
// joint exerts on body 1, f = −Φ_{r1}ᵀ λ (world frame).
#include "alphaflex/model/constraint.hpp"
#include "alphaflex/model/planar_marker.hpp"

namespace alphaflex {

/// Pin: point 1 of body 1 and point 2 of body 2 coincide, Φ = r1 − r2 (2 equations).
/// A point fixed to the ground is a revolute joint whose body 2 is the ground.
class RevoluteJoint2D final : public Constraint {
 public:
  RevoluteJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2);
  const char* type() const override { return "revolute"; }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<RevoluteJoint2D>(*this); }
  int size() const override { return 2; }
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
class PointOnLineJoint2D : public Constraint {
 public:
  PointOnLineJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2,
                     const Eigen::Vector2d& axis);
  const char* type() const override { return "point_on_line"; }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<PointOnLineJoint2D>(*this); }
  int size() const override { return 1; }
  void evaluate(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi, Eigen::MatrixXd& phi_q) const override;
  void geometric_stiffness(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda,
                           Eigen::MatrixXd& k) const override;
  void acceleration_term(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t,
                         Eigen::VectorXd& c) const override;
  JointReaction reaction(const Eigen::VectorXd& q, double t, const Eigen::VectorXd& lambda) const override;

 protected:
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
  const char* type() const override { return "prismatic"; }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<PrismaticJoint2D>(*this); }
  int size() const override { return 2; }
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
class FixedJoint2D final : public Constraint {
 public:
  FixedJoint2D(std::string name, std::vector<int> nodes, PlanarMarker p1, PlanarMarker p2, double relative_angle);
  const char* type() const override { return "fixed"; }
  std::unique_ptr<Constraint> clone() const override { return std::make_unique<FixedJoint2D>(*this); }
  int size() const override { return 3; }
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
