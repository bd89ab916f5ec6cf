// mesh module, surfaces (shells): physical surface groups of 3-node triangles and 4-node
// quadrangles from a .geo (meshed in 2D) or a .msh, nodes shared with curve groups, consistent
// orientation (elements that disagree with their neighbours reversed, a non-orientable surface
// refused), second-order surface elements refused — every error with its message.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <map>
#include <fstream>
#include <string>

#include "alphaflex/core/error.hpp"
#include "alphaflex/mesh/gmsh_reader.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

namespace fs = std::filesystem;

using testing::mesh_path;

std::string write_temp(const std::string& name, const std::string& text) {
  static const testing::TestOutputDir dir("surf");  // removed at exit
  return dir.write(name, text);
}

std::string surface_error_of(const std::string& path) {
  try {
    read_mesh(path, {}, "ctx");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

/// Signed normal (z component) of a planar element from its node order.
double normal_z(const MeshData& m, const std::vector<int>& el) {
  const Eigen::Vector3d a = m.points[static_cast<size_t>(el[1])] - m.points[static_cast<size_t>(el[0])];
  const Eigen::Vector3d b = m.points[static_cast<size_t>(el.back())] - m.points[static_cast<size_t>(el[0])];
  return a.cross(b).z();
}

MeshOptions params(std::map<std::string, double> p) {
  MeshOptions o;
  o.parameters = std::move(p);
  return o;
}

TEST(MeshSurfaces, TransfiniteQuadrilateralsSharingNodesWithCurves) {
  const MeshData m = read_mesh(mesh_path("sze_strip.geo"), params({{"nx", 6}, {"ny", 2}}), "ctx");
  ASSERT_EQ(m.surface_blocks.size(), 1u);
  const MeshSurfaceBlock& s = *m.find_surface_block("strip");
  EXPECT_EQ(s.elements.size(), 12u);
  for (const auto& el : s.elements) {
    EXPECT_EQ(el.size(), 4u);
    EXPECT_GT(normal_z(m, el), 0.0);  // counter-clockwise about +z, as the .geo's curve loop
  }
  EXPECT_EQ(m.points.size(), 21u);  // 7 × 3 nodes, the curve groups' nodes are the same nodes
  const MeshLineBlock* tip = m.find_line_block("tip");
  ASSERT_NE(tip, nullptr);
  EXPECT_EQ(tip->elements.size(), 2u);
  EXPECT_EQ(m.named_points.count("tip_a"), 1u);
  EXPECT_EQ(m.find_surface_block("tip"), nullptr);
}

TEST(MeshSurfaces, TrianglesAndMixedMeshes) {
  const MeshData t = read_mesh(mesh_path("sze_strip.geo"), params({{"nx", 4}, {"ny", 1}, {"quads", 0}}), "ctx");
  ASSERT_EQ(t.surface_blocks.size(), 1u);
  EXPECT_EQ(t.surface_blocks[0].elements.size(), 8u);
  for (const auto& el : t.surface_blocks[0].elements) {
    EXPECT_EQ(el.size(), 3u);
    EXPECT_GT(normal_z(t, el), 0.0);
  }
  // Two surfaces, one recombined, one not: both element types in one group.
  const std::string geo = write_temp("mixed.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {2, 0, 0};
Point(4) = {2, 1, 0}; Point(5) = {1, 1, 0}; Point(6) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 1}; Line(7) = {2, 5};
Curve Loop(1) = {1, 7, 5, 6}; Plane Surface(1) = {1};
Curve Loop(2) = {2, 3, 4, -7}; Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7} = 3;
Transfinite Surface{1}; Transfinite Surface{2};
Recombine Surface{1};
Physical Surface("plate") = {1, 2};
)");
  const MeshData m = read_mesh(geo, {}, "ctx");
  size_t tri = 0, quad = 0;
  for (const auto& el : m.surface_blocks.at(0).elements) {
    (el.size() == 3 ? tri : quad)++;
    EXPECT_GT(normal_z(m, el), 0.0);
  }
  EXPECT_EQ(quad, 4u);
  EXPECT_EQ(tri, 8u);
}

// A .msh whose second element runs clockwise: it is reversed to match the first, with a warning.
const char* kTwoQuads = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 "plate"
$EndPhysicalNames
$Entities
0 0 1 0
1 0 0 0 2 1 0 1 1 0
$EndEntities
$Nodes
1 6 1 6
2 1 0 6
1
2
3
4
5
6
0 0 0
1 0 0
2 0 0
2 1 0
1 1 0
0 1 0
$EndNodes
$Elements
1 2 1 2
2 1 3 2
1 1 2 5 6
2 2 5 4 3
$EndElements
)";

TEST(MeshSurfaces, ElementsAgainstTheirNeighboursAreReversed) {
  const MeshData m = read_mesh(write_temp("flipped.msh", kTwoQuads), {}, "ctx");
  const auto& els = m.surface_blocks.at(0).elements;
  ASSERT_EQ(els.size(), 2u);
  EXPECT_GT(normal_z(m, els[0]), 0.0);
  EXPECT_GT(normal_z(m, els[1]), 0.0);
  bool warned = false;
  for (const auto& w : m.warnings) warned = warned || w.find("1 element(s) reversed") != std::string::npos;
  EXPECT_TRUE(warned);
}

// A Möbius strip of 4 quadrilaterals (the last one joins the first with a half twist).
TEST(MeshSurfaces, NonOrientableSurfaceIsRefused) {
  std::string msh = R"($MeshFormat
4.1 0 8
$EndMeshFormat
$PhysicalNames
1
2 1 "band"
$EndPhysicalNames
$Entities
0 0 1 0
1 -2 -2 -1 2 2 1 1 1 0
$EndEntities
$Nodes
1 8 1 8
2 1 0 8
1
2
3
4
5
6
7
8
)";
  // Pairs (inner, outer) at 4 angles; the twist swaps the pair when closing the loop.
  for (int k = 0; k < 4; ++k) {
    const double c = std::cos(k * M_PI / 2), s = std::sin(k * M_PI / 2);
    msh += std::to_string(1.5 * c) + " " + std::to_string(1.5 * s) + " " + std::to_string(-0.5) + "\n";
    msh += std::to_string(1.5 * c) + " " + std::to_string(1.5 * s) + " " + std::to_string(0.5) + "\n";
  }
  msh += R"($EndNodes
$Elements
1 4 1 4
2 1 3 4
1 1 3 4 2
2 3 5 6 4
3 5 7 8 6
4 7 2 1 8
$EndElements
)";
  const std::string e = surface_error_of(write_temp("moebius.msh", msh));
  EXPECT_NE(e.find("physical group 'band' (dimension 2) cannot be oriented consistently"), std::string::npos) << e;
  EXPECT_NE(e.find("Moebius"), std::string::npos) << e;
}

TEST(MeshSurfaces, SecondOrderSurfaceElementsAreRefused) {
  const std::string geo = write_temp("tri6.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
Physical Surface("plate") = {1};
Mesh.ElementOrder = 2;
)");
  const std::string e = surface_error_of(geo);
  EXPECT_NE(e.find("physical group 'plate' (dimension 2) holds element"), std::string::npos) << e;
  EXPECT_NE(e.find("expected 3-node triangles (type 2) or 4-node quadrangles (type 3)"), std::string::npos) << e;
  EXPECT_EQ(e.rfind("ctx: mesh '", 0), 0u) << e;
}

}  // namespace
}  // namespace alphaflex
