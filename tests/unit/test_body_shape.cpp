// Bodies drawn as bodies (issue 21): the tessellated shapes (closed, outward, area and volume
// against closed forms), the `shape` key of the rigid bodies and its errors, and surface meshes
// read with gmsh (.stl, .msh).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "alphaflex/io/scene.hpp"
#include "alphaflex/model/body_shape.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using testing::kPi;

TEST(BodyShapeTessellation, BoxIsClosedWithExactAreaAndVolume) {
  const SurfaceMesh s = box_surface({0.3, 0.05, 0.02});
  EXPECT_EQ(closedness_error(s), "");
  EXPECT_EQ(s.points.size(), 8u);
  EXPECT_EQ(s.faces.size(), 6u);
  // A box is represented exactly: 2(ab + bc + ca), abc.
  EXPECT_NEAR(surface_area(s), 2.0 * (0.3 * 0.05 + 0.05 * 0.02 + 0.02 * 0.3), 1e-15);
  EXPECT_NEAR(enclosed_volume(s), 0.3 * 0.05 * 0.02, 1e-17);  // positive: the faces point outward
}

TEST(BodyShapeTessellation, CylinderIsTheInscribedPrism) {
  const double r = 0.02, l = 0.3;
  for (int axis = 0; axis < 3; ++axis)
    for (int n : {8, 32}) {
      const SurfaceMesh s = cylinder_surface(r, l, axis, n);
      EXPECT_EQ(closedness_error(s), "") << axis << " " << n;
      // The regular n-gon of circumradius r: area (n/2) r² sin(2π/n), perimeter 2 n r sin(π/n).
      const double polygon = 0.5 * n * r * r * std::sin(2.0 * kPi / n), perimeter = 2.0 * n * r * std::sin(kPi / n);
      EXPECT_NEAR(enclosed_volume(s), polygon * l, 1e-15);
      EXPECT_NEAR(surface_area(s), perimeter * l + 2.0 * polygon, 1e-15);
      // Against the cylinder: the volume is sin(2π/n)/(2π/n) of πr²l (0.6 % less for n = 32).
      EXPECT_NEAR(enclosed_volume(s) / (kPi * r * r * l), std::sin(2.0 * kPi / n) / (2.0 * kPi / n), 1e-12);
      // Its axis is body axis `axis`: the extent along it is the length, across it 2r.
      Eigen::Vector3d lo = s.points[0], hi = s.points[0];
      for (const auto& p : s.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
      EXPECT_NEAR(hi[axis] - lo[axis], l, 1e-15);
      EXPECT_NEAR(hi[(axis + 1) % 3] - lo[(axis + 1) % 3], 2.0 * r, 1e-15);
    }
}

TEST(BodyShapeTessellation, SphereAreaAndVolumeConvergeAtSecondOrder) {
  const double r = 0.05, area = 4.0 * kPi * r * r, volume = 4.0 / 3.0 * kPi * r * r * r;
  double last_area_error = 0.0, last_volume_error = 0.0;
  for (int n : {8, 16, 32, 64, 128}) {
    const SurfaceMesh s = sphere_surface(r, n);
    EXPECT_EQ(closedness_error(s), "") << n;
    for (const auto& p : s.points) EXPECT_NEAR(p.norm(), r, 1e-15);
    // Inscribed: below the sphere's area and volume, by O(1/n²): the chords of the meridians and
    // parallels (angle 2π/n) fall short of the arcs by 1 − sin(x)/x ≈ x²/6.
    const double ea = (area - surface_area(s)) / area, ev = (volume - enclosed_volume(s)) / volume;
    EXPECT_GT(ea, 0.0);
    EXPECT_GT(ev, 0.0);
    // Second order once the net is fine enough (n = 8 → 16 is not yet asymptotic: ratios 3.9, 3.7).
    if (n >= 32) {
      EXPECT_NEAR(last_area_error / ea, 4.0, 0.1) << n;
      EXPECT_NEAR(last_volume_error / ev, 4.0, 0.1) << n;
    }
    // The drawn sphere (n = kShapeSegments = 32): 0.80 % of the area and 1.6 % of the volume short.
    if (n == kShapeSegments) {
      EXPECT_LT(ea, 0.0081);
      EXPECT_LT(ev, 0.0161);
    }
    last_area_error = ea;
    last_volume_error = ev;
  }
}

TEST(BodyShapeTessellation, PlacingKeepsTheVolumeAndMovesTheCentre) {
  SurfaceMesh s = box_surface({1.0, 2.0, 3.0});
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  place_surface(s, 0.5, R, {1.0, -2.0, 0.5});
  EXPECT_EQ(closedness_error(s), "");
  EXPECT_NEAR(enclosed_volume(s), 6.0 * 0.125, 1e-14);  // scaled by 0.5³, rotation keeps it
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (const auto& p : s.points) c += p / 8.0;
  EXPECT_NEAR((c - Eigen::Vector3d(1.0, -2.0, 0.5)).norm(), 0.0, 1e-15);
  const Eigen::Vector3d e = s.points[1] - s.points[0];  // the box's first edge, along its x
  EXPECT_NEAR((e - R * Eigen::Vector3d(0.5, 0.0, 0.0)).norm(), 0.0, 1e-15);
}

TEST(BodyShapeTessellation, OpenAndInconsistentSurfacesAreNamed) {
  SurfaceMesh s = box_surface({1.0, 1.0, 1.0});
  s.faces.pop_back();
  EXPECT_NE(closedness_error(s), "");
  s = box_surface({1.0, 1.0, 1.0});
  std::swap(s.faces[0][1], s.faces[0][3]);  // one face turned inward
  EXPECT_NE(closedness_error(s), "");
}

// ---- the `shape` key -----------------------------------------------------------------------------

const char* kBodies3d = R"(dimension: 3
solver: {h: 1.0e-3, t_end: 0.01}
bodies:
  - {name: a, type: rigid_body, mass: 1, inertia: [1, 1, 1], position: [0, 0, 0], shape: SHAPE}
)";
const char* kBodies2d = R"(solver: {h: 1.0e-3, t_end: 0.01}
bodies:
  - {name: a, type: rigid_body, mass: 1, inertia: 0.1, position: [0, 0], shape: SHAPE}
)";

std::string with_shape(const char* scene, const std::string& shape) {
  std::string s = scene;
  return s.replace(s.find("SHAPE"), 5, shape);
}

const BodyShape& only_shape(const Scene& sc) {
  EXPECT_EQ(sc.model->shapes().size(), 1u);
  return sc.model->shapes().at(0);
}

TEST(BodyShapeScene, ShapesArePlacedInTheBodyFrame) {
  // A cylinder along y, shifted by [0.1, 0, 0] and turned a quarter about z: its axis is −x.
  const Scene sc = read_scene_text(
      with_shape(kBodies3d, "{type: cylinder, radius: 0.01, length: 0.2, axis: y, position: [0.1, 0, 0], orientation: [0, 0, pi/2]}"),
      "scene.yaml");
  const BodyShape& b = only_shape(sc);
  EXPECT_EQ(b.node, 0);
  Eigen::Vector3d lo = b.surface.points[0], hi = lo;
  for (const auto& p : b.surface.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  EXPECT_NEAR(hi.x() - lo.x(), 0.2, 1e-12);
  EXPECT_NEAR(0.5 * (hi.x() + lo.x()), 0.1, 1e-12);
  EXPECT_NEAR(hi.y() - lo.y(), 0.02, 1e-12);
  const Scene planar = read_scene_text(with_shape(kBodies2d, "{type: sphere, radius: 0.05}"), "scene.yaml");
  EXPECT_NEAR(enclosed_volume(only_shape(planar).surface), enclosed_volume(sphere_surface(0.05)), 1e-18);
}

TEST(BodyShapeScene, BadShapesAreNamed) {
  using testing::input_error_of;
  auto error = [](const char* scene, const std::string& shape) {
    return input_error_of([&] { read_scene_text(with_shape(scene, shape), "scene.yaml"); });
  };
  auto expect = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << message;
  };
  expect(error(kBodies3d, "{type: cone, radius: 1}"), "bodies[a].shape.type");
  expect(error(kBodies3d, "{type: cone, radius: 1}"), "box, cylinder, sphere, mesh");
  expect(error(kBodies3d, "{type: box, size: [1, 0, 1]}"), "bodies[a].shape.size: expected edge lengths > 0");
  expect(error(kBodies2d, "{type: sphere, radius: -1}"), "bodies[a].shape.radius");
  expect(error(kBodies3d, "{type: cylinder, radius: 1, length: 0}"), "bodies[a].shape.length");
  expect(error(kBodies3d, "{type: cylinder, radius: 1}"), "bodies[a].shape.length: missing (required for a cylinder shape)");
  expect(error(kBodies3d, "{type: box, size: [1, 1, 1], radius: 1}"), "bodies[a].shape.radius: not a key of a box shape");
  expect(error(kBodies3d, "{type: sphere, radius: 1, colour: red}"), "unknown key");
  expect(error(kBodies3d, "box"), "bodies[a].shape: expected a map");
  const std::string missing = error(kBodies3d, "{type: mesh, file: no_such_part.stl}");
  expect(missing, "bodies[a].shape.file");
  expect(missing, "no_such_part.stl");
  expect(missing, "file not found");
  expect(error(kBodies3d, "{type: mesh, file: part.obj}"), "expected a surface mesh file ending in .stl or .msh");
}

// ---- surface meshes read with gmsh -----------------------------------------------------------------

/// An ASCII STL of the unit cube [0, 1]³ (mm), 12 triangles with outward normals.
std::string cube_stl() {
  const SurfaceMesh box = box_surface({1.0, 1.0, 1.0});
  std::string s = "solid cube\n";
  for (const auto& f : box.faces)
    for (size_t k = 1; k + 1 < f.size(); ++k) {
      const Eigen::Vector3d a = box.points[f[0]], b = box.points[f[k]], c = box.points[f[k + 1]];
      const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
      s += "facet normal " + std::to_string(n.x()) + " " + std::to_string(n.y()) + " " + std::to_string(n.z()) + "\n outer loop\n";
      for (const Eigen::Vector3d& p : {a, b, c})
        s += "  vertex " + std::to_string(p.x() + 0.5) + " " + std::to_string(p.y() + 0.5) + " " + std::to_string(p.z() + 0.5) + "\n";
      s += " endloop\nendfacet\n";
    }
  return s + "endsolid cube\n";
}

TEST(BodyShapeScene, StlMeshIsReadScaledAndPlaced) {
  const testing::TestOutputDir dir("body_shape_stl");
  const std::string stl = dir.write("cube.stl", cube_stl());
  const Scene sc = read_scene_text(
      with_shape(kBodies3d, "{type: mesh, file: " + stl + ", scale: 0.001, position: [0, 0, 1]}"), dir.file("scene.yaml"));
  const SurfaceMesh& s = only_shape(sc).surface;
  EXPECT_EQ(s.faces.size(), 12u);
  EXPECT_EQ(s.points.size(), 8u);  // gmsh merges the facets' repeated vertices
  EXPECT_EQ(closedness_error(s), "");
  EXPECT_NEAR(enclosed_volume(s), 1e-9, 1e-18);  // 1 mm³
  for (const auto& p : s.points) EXPECT_NEAR(p.z(), 1.0 + (p.z() > 1.0005 ? 0.001 : 0.0), 1e-9);
  // Relative to the scene file's directory.
  const Scene rel = read_scene_text(with_shape(kBodies3d, "{type: mesh, file: cube.stl}"), dir.file("scene.yaml"));
  EXPECT_NEAR(enclosed_volume(only_shape(rel).surface), 1.0, 1e-12);
}

TEST(BodyShapeScene, MshSurfaceIsReadWithoutPhysicalGroups) {
  // The unit tetrahedron (0, e1, e2, e3) as 4 outward triangles of a MSH 2.2 file with no
  // physical names: volume 1/6, area 3/2 + √3/2.
  const testing::TestOutputDir dir("body_shape_tet");
  dir.write("tet.msh",
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"
            "$Elements\n4\n1 2 2 0 1 1 3 2\n2 2 2 0 1 1 2 4\n3 2 2 0 1 1 4 3\n4 2 2 0 1 2 3 4\n$EndElements\n");
  const Scene sc = read_scene_text(with_shape(kBodies3d, "{type: mesh, file: tet.msh}"), dir.file("scene.yaml"));
  const SurfaceMesh& s = only_shape(sc).surface;
  EXPECT_EQ(s.faces.size(), 4u);
  EXPECT_EQ(s.points.size(), 4u);
  EXPECT_EQ(closedness_error(s), "");
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(surface_area(s), 1.5 + std::sqrt(3.0) / 2.0, 1e-15);
}

TEST(BodyShapeScene, MeshWithoutSurfaceElementsIsNamed) {
  const testing::TestOutputDir dir("body_shape_msh");
  dir.write("line.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n"
                        "$Elements\n1\n1 1 2 1 1 1 2\n$EndElements\n");
  const std::string e = testing::input_error_of([&] {
    read_scene_text(with_shape(kBodies3d, "{type: mesh, file: line.msh}"), dir.file("scene.yaml"));
  });
  EXPECT_NE(e.find("bodies[a].shape.file"), std::string::npos) << e;
  EXPECT_NE(e.find("line.msh"), std::string::npos) << e;
  EXPECT_NE(e.find("no surface elements"), std::string::npos) << e;
  dir.write("empty.stl", "");
  const std::string empty = testing::input_error_of([&] {
    read_scene_text(with_shape(kBodies3d, "{type: mesh, file: empty.stl}"), dir.file("scene.yaml"));
  });
  EXPECT_NE(empty.find("empty.stl"), std::string::npos) << empty;
}

}  // namespace
}  // namespace alphaflex
