#include "alphaflex/mesh/surface_mesh.hpp"

#include <Eigen/Geometry>
#include <map>
#include <utility>

namespace alphaflex {

namespace {

/// Calls f(a, b, c) for the triangles of each face (a quadrilateral as 0-1-2 and 0-2-3).
template <class F>
void for_each_triangle(const SurfaceMesh& s, F f) {
  for (const auto& face : s.faces)
    for (size_t k = 1; k + 1 < face.size(); ++k)
      f(s.points[static_cast<size_t>(face[0])], s.points[static_cast<size_t>(face[k])], s.points[static_cast<size_t>(face[k + 1])]);
}

}  // namespace

double surface_area(const SurfaceMesh& s) {
  double a = 0.0;
  for_each_triangle(s, [&](const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
    a += 0.5 * (p1 - p0).cross(p2 - p0).norm();
  });
  return a;
}

double enclosed_volume(const SurfaceMesh& s) {
  double v = 0.0;
  for_each_triangle(s, [&](const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2) {
    v += p0.dot(p1.cross(p2)) / 6.0;
  });
  return v;
}

std::string closedness_error(const SurfaceMesh& s) {
  std::map<std::pair<int, int>, int> directed;  // edge a → b: how many faces use it this way
  for (const auto& face : s.faces)
    for (size_t k = 0; k < face.size(); ++k) ++directed[{face[k], face[(k + 1) % face.size()]}];
  for (const auto& [edge, n] : directed) {
    const auto back = directed.find({edge.second, edge.first});
    const int m = back == directed.end() ? 0 : back->second;
    if (n != 1 || m != 1)
      return "edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) + " is used " + std::to_string(n) +
             " time(s) in this direction and " + std::to_string(m) + " in the other (a closed, consistently oriented "
             "surface uses each edge once each way)";
  }
  return {};
}

}  // namespace alphaflex
