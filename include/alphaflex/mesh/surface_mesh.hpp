#pragma once
// A closed or open surface of triangles and quadrilaterals (a body's shape: tessellated box,
// cylinder, sphere, or a surface mesh file read with gmsh), and the measures its tests and checks
// use: area, enclosed volume (divergence theorem), closedness.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace alphaflex {

struct SurfaceMesh {
  std::vector<Eigen::Vector3d> points;    ///< m
  /// 3 or 4 point indices each, counter-clockwise seen from outside (outward normal) on a closed
  /// surface.
  std::vector<std::vector<int>> faces;
};

/// Σ of the faces' areas (a quadrilateral as two triangles 0-1-2, 0-2-3).
double surface_area(const SurfaceMesh& s);
/// The volume enclosed by a closed, outward-oriented surface: (1/3) ∮ x·n dA, summed exactly over
/// the triangles as (1/6) Σ x0·(x1 × x2) (divergence theorem; negative if the faces point inward).
double enclosed_volume(const SurfaceMesh& s);
/// "" if every edge is used by exactly two faces, once in each direction (a closed, consistently
/// oriented surface), else what is wrong (the first edge that is not).
std::string closedness_error(const SurfaceMesh& s);

}  // namespace alphaflex
