#pragma once
// What a rigid body looks like in the results (issue 21): a surface fixed to the body — a box, a
// cylinder, a sphere (tessellated here) or a surface mesh file — placed in the body frame. It has
// no mass and no contact: the body's mass and inertia are the scene's `mass` and `inertia`.
// The results draw it at every output step at x + R·X (X in the body frame; a planar body's pose
// is (x, y, 0) and the rotation θ about z).
#include <Eigen/Core>
#include <string>

#include "alphaflex/mesh/surface_mesh.hpp"

namespace alphaflex {

struct BodyShape {
  int node = -1;        ///< the body's model node (a RigidBody2D or Frame3D node)
  std::string what;     ///< for messages and docs: "box", "cylinder", "sphere", "mesh FILE"
  SurfaceMesh surface;  ///< in the body frame (m)
};

/// Points around a circle of a cylinder and a sphere's meridians: the polygon's area is
/// sin(2π/n)/(2π/n) of the circle's, 0.6 % less for n = 32.
inline constexpr int kShapeSegments = 32;

/// A box of edge lengths size (m, along the body axes), centred at the origin: 8 points,
/// 6 quadrilaterals, outward.
SurfaceMesh box_surface(const Eigen::Vector3d& size);
/// A cylinder of radius r and length l about body axis `axis` (0 x, 1 y, 2 z), centred at the
/// origin: `segments` quadrilaterals around, each end a fan of triangles about its centre; the
/// inscribed prism (its area and volume are those of the regular `segments`-gon).
SurfaceMesh cylinder_surface(double radius, double length, int axis, int segments = kShapeSegments);
/// A sphere of radius r about the origin: a latitude-longitude net of `segments` meridians and
/// segments/2 bands, quadrilaterals with triangle fans at the poles, every point on the sphere.
/// The area and volume converge to 4πr², 4πr³/3 at second order in 1/segments.
SurfaceMesh sphere_surface(double radius, int segments = kShapeSegments);
/// Scales the points by `scale`, then rotates them by R and shifts them by `offset`: X ← offset +
/// R·(scale·X) (a shape's placement in the body frame).
void place_surface(SurfaceMesh& s, double scale, const Eigen::Matrix3d& R, const Eigen::Vector3d& offset);

}  // namespace alphaflex
