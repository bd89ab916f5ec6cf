#include "alphaflex/model/body_shape.hpp"

#include <cmath>

namespace alphaflex {

SurfaceMesh box_surface(const Eigen::Vector3d& size) {
  SurfaceMesh s;
  // Corner k has coordinate ±size/2 along axis a as bit a of k is 0/1.
  for (int k = 0; k < 8; ++k)
    s.points.emplace_back((k & 1 ? 0.5 : -0.5) * size[0], (k & 2 ? 0.5 : -0.5) * size[1], (k & 4 ? 0.5 : -0.5) * size[2]);
  // Faces counter-clockwise seen from outside: −x, +x, −y, +y, −z, +z.
  s.faces = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  return s;
}

namespace {

/// The columns of a rotation taking the local (u, v, w) axes of a shape built about z to the
/// body axes with w along body axis `axis` (a cyclic permutation: proper).
Eigen::Matrix3d axis_frame(int axis) {
  Eigen::Matrix3d P = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) P((axis + 1 + k) % 3, k) = 1.0;
  return P;
}

}  // namespace

SurfaceMesh cylinder_surface(double radius, double length, int axis, int segments) {
  SurfaceMesh s;
  const int n = segments;
  const double pi = std::acos(-1.0);
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < n; ++k) {
      const double phi = 2.0 * pi * k / n;
      s.points.emplace_back(radius * std::cos(phi), radius * std::sin(phi), (end ? 0.5 : -0.5) * length);
    }
  const int bottom = 2 * n, top = 2 * n + 1;
  s.points.emplace_back(0.0, 0.0, -0.5 * length);
  s.points.emplace_back(0.0, 0.0, 0.5 * length);
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1) % n;
    s.faces.push_back({k, k1, n + k1, n + k});  // side, counter-clockwise about the outward radius
    s.faces.push_back({bottom, k1, k});          // −w end
    s.faces.push_back({top, n + k, n + k1});     // +w end
  }
  place_surface(s, 1.0, axis_frame(axis), Eigen::Vector3d::Zero());
  return s;
}

SurfaceMesh sphere_surface(double radius, int segments) {
  SurfaceMesh s;
  const int n = segments, bands = segments / 2;
  const double pi = std::acos(-1.0);
  // Rings 1 … bands−1 between the poles (polar angle j π / bands), n points each.
  for (int j = 1; j < bands; ++j) {
    const double th = pi * j / bands;
    for (int k = 0; k < n; ++k) {
      const double phi = 2.0 * pi * k / n;
      s.points.emplace_back(radius * std::sin(th) * std::cos(phi), radius * std::sin(th) * std::sin(phi), radius * std::cos(th));
    }
  }
  const int north = static_cast<int>(s.points.size()), south = north + 1;
  s.points.emplace_back(0.0, 0.0, radius);
  s.points.emplace_back(0.0, 0.0, -radius);
  auto at = [n](int ring, int k) { return (ring - 1) * n + (k % n); };
  for (int k = 0; k < n; ++k) {
    s.faces.push_back({north, at(1, k), at(1, k + 1)});
    for (int j = 1; j + 1 < bands; ++j) s.faces.push_back({at(j, k), at(j + 1, k), at(j + 1, k + 1), at(j, k + 1)});
    s.faces.push_back({south, at(bands - 1, k + 1), at(bands - 1, k)});
  }
  return s;
}

void place_surface(SurfaceMesh& s, double scale, const Eigen::Matrix3d& R, const Eigen::Vector3d& offset) {
  for (Eigen::Vector3d& p : s.points) p = offset + R * (scale * p);
}

}  // namespace alphaflex
