// mesh module: gmsh .geo/.msh → MeshData. Meshes from meshes/ and small files written into a
// temporary directory; every error case is checked for its message.
#include <gmsh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <string>

#include "alphaflex/core/error.hpp"
#include "alphaflex/mesh/gmsh_reader.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

namespace fs = std::filesystem;

using testing::mesh_path;

/// A directory of its own per test (tests may run in parallel processes), removed at the end.
struct TempDir : testing::TestOutputDir {
  TempDir()
      : TestOutputDir("mesh_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name()) +
                      "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name()) {}
};

using testing::input_error_of;

#define EXPECT_HAS(text, fragment) EXPECT_NE(std::string(text).find(fragment), std::string::npos) << "message: " << (text)

MeshOptions with_elements(int n) {
  MeshOptions o;
  o.elements_per_curve = n;
  return o;
}

MeshOptions with_parameters(std::map<std::string, double> p) {
  MeshOptions o;
  o.parameters = std::move(p);
  return o;
}

/// A straight beam along x from the origin: n equal elements in a chain root → tip, all nodes used.
void expect_straight_beam(const MeshData& m, const std::string& block, const std::string& root,
                          double length, int n) {
  ASSERT_EQ(m.line_blocks.size(), 1u);
  const MeshLineBlock* b = m.find_line_block(block);
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(m.find_line_block("nope"), nullptr);
  ASSERT_EQ(b->elements.size(), static_cast<size_t>(n));
  ASSERT_EQ(b->element_tags.size(), static_cast<size_t>(n));
  ASSERT_EQ(m.points.size(), static_cast<size_t>(n + 1));
  ASSERT_EQ(m.node_tags.size(), m.points.size());
  EXPECT_EQ(std::set<size_t>(m.node_tags.begin(), m.node_tags.end()).size(), m.node_tags.size());
  // Chain in element order; local ids in order of first use: 0, 1, ..., n along the beam.
  for (int e = 0; e < n; ++e) {
    EXPECT_EQ(b->elements[e][0], e);
    EXPECT_EQ(b->elements[e][1], e + 1);
    const Eigen::Vector3d d = m.points[b->elements[e][1]] - m.points[b->elements[e][0]];
    EXPECT_NEAR(d.x(), length / n, 1e-10 * length);
  }
  for (const Eigen::Vector3d& p : m.points) {
    EXPECT_EQ(p.y(), 0.0);
    EXPECT_EQ(p.z(), 0.0);
    EXPECT_GE(p.x(), 0.0);
    EXPECT_LE(p.x(), length);
  }
  ASSERT_EQ(m.named_points.count(root), 1u);
  ASSERT_EQ(m.named_points.count("tip"), 1u);
  EXPECT_EQ(m.named_points.at(root), 0);
  EXPECT_EQ(m.named_points.at("tip"), n);
  EXPECT_EQ(m.points[m.named_points.at(root)], Eigen::Vector3d::Zero());
  EXPECT_EQ(m.points[m.named_points.at("tip")], Eigen::Vector3d(length, 0, 0));
}

void expect_same_mesh(const MeshData& a, const MeshData& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i)
    EXPECT_LE((a.points[i] - b.points[i]).norm(), 1e-14 * (1 + a.points[i].norm())) << "node " << i;
  EXPECT_EQ(a.node_tags, b.node_tags);
  ASSERT_EQ(a.line_blocks.size(), b.line_blocks.size());
  for (size_t k = 0; k < a.line_blocks.size(); ++k) {
    EXPECT_EQ(a.line_blocks[k].name, b.line_blocks[k].name);
    EXPECT_EQ(a.line_blocks[k].tag, b.line_blocks[k].tag);
    EXPECT_EQ(a.line_blocks[k].elements, b.line_blocks[k].elements);
    EXPECT_EQ(a.line_blocks[k].element_tags, b.line_blocks[k].element_tags);
  }
  EXPECT_EQ(a.named_points, b.named_points);
}

const char* kStraightGeo = R"(
Point(1) = {0, 0, 0};
Point(2) = {2, 0, 0};
Line(1) = {1, 2};
Physical Curve("beam") = {1};
Physical Point("root") = {1};
Physical Point("tip") = {2};
)";

// ---- meshes/ ---------------------------------------------------------------------------------

TEST(MeshCantilever, ElementsPerCurve) {
  for (int n : {1, 4, 16}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const MeshData m = read_mesh(mesh_path("cantilever.geo"), with_elements(n), "test");
    expect_straight_beam(m, "beam", "root", 1.0, n);
    EXPECT_EQ(m.file, mesh_path("cantilever.geo"));
  }
}

TEST(MeshCantilever, DefineConstantParameters) {
  for (int n : {1, 4, 16}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const MeshData m = read_mesh(mesh_path("cantilever.geo"), with_parameters({{"n", n}, {"L", 2.5}}), "test");
    expect_straight_beam(m, "beam", "root", 2.5, n);
    EXPECT_EQ(m.parameters, (std::map<std::string, double>{{"L", 2.5}, {"n", n}}));
  }
}

TEST(MeshCantilever, DefaultsAndNoLeakBetweenReads) {
  // gmsh keeps its ONELAB database across finalize/initialize: a value set for one read must
  // not reach the next one.
  read_mesh(mesh_path("cantilever.geo"), with_parameters({{"n", 4}}), "test");
  const MeshData m = read_mesh(mesh_path("cantilever.geo"), {}, "test");
  expect_straight_beam(m, "beam", "root", 1.0, 16);
  EXPECT_EQ(m.parameters, (std::map<std::string, double>{{"L", 1}, {"n", 16}}));
  EXPECT_TRUE(m.warnings.empty());
}

TEST(MeshCantilever, ElementsPerCurveOverridesParameter) {
  MeshOptions o = with_parameters({{"n", 3}});
  o.elements_per_curve = 5;
  expect_straight_beam(read_mesh(mesh_path("cantilever.geo"), o, "test"), "beam", "root", 1.0, 5);
}

TEST(MeshCantilever, DeterministicAndWorkingDirectoryKept) {
  const fs::path cwd = fs::current_path();
  const MeshData a = read_mesh(mesh_path("bend45.geo"), {}, "test");
  const MeshData b = read_mesh(mesh_path("bend45.geo"), {}, "test");
  EXPECT_EQ(fs::current_path(), cwd);
  ASSERT_EQ(a.points.size(), b.points.size());
  for (size_t i = 0; i < a.points.size(); ++i) EXPECT_EQ(a.points[i], b.points[i]);
  expect_same_mesh(a, b);
}

TEST(MeshSpinupBeam, DefaultsTenElementsOfOneMetre) {
  const MeshData m = read_mesh(mesh_path("spinup_beam.geo"), {}, "test");
  expect_straight_beam(m, "beam", "hub", 10.0, 10);
  EXPECT_EQ(m.parameters, (std::map<std::string, double>{{"L", 10}, {"n", 10}}));
}

TEST(MeshBend45, NodesOnTheArcAndEqualChords) {
  const double R = 100, s = std::sin(M_PI / 4), c = std::cos(M_PI / 4);
  for (int n : {8, 16}) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const MeshData m = read_mesh(mesh_path("bend45.geo"), with_parameters({{"n", n}}), "test");
    const MeshLineBlock* b = m.find_line_block("bend");
    ASSERT_NE(b, nullptr);
    ASSERT_EQ(b->elements.size(), static_cast<size_t>(n));
    ASSERT_EQ(m.points.size(), static_cast<size_t>(n + 1));
    const Eigen::Vector3d centre(0, R, 0);
    for (const Eigen::Vector3d& p : m.points) {
      EXPECT_NEAR((p - centre).norm(), R, 1e-9 * R);
      EXPECT_EQ(p.z(), 0.0);
    }
    const double chord = 2 * R * std::sin(M_PI / 4 / n / 2);
    for (const auto& e : b->elements) EXPECT_NEAR((m.points[e[1]] - m.points[e[0]]).norm(), chord, 1e-9 * R);
    EXPECT_EQ(m.points[m.named_points.at("root")], Eigen::Vector3d::Zero());
    EXPECT_LE((m.points[m.named_points.at("tip")] - Eigen::Vector3d(R * s, R * (1 - c), 0)).norm(), 1e-12 * R);
    EXPECT_EQ(m.named_points.at("root"), 0);
    EXPECT_EQ(m.named_points.at("tip"), n);
  }
}

// ---- .msh ------------------------------------------------------------------------------------

TEST(MeshMsh, CommittedMshMatchesItsGeo) {
  // meshes/cantilever_n4.msh: gmsh -1 -setnumber n 4 -format msh41 cantilever.geo
  const MeshData msh = read_mesh(mesh_path("cantilever_n4.msh"), {}, "test");
  const MeshData geo = read_mesh(mesh_path("cantilever.geo"), with_parameters({{"n", 4}}), "test");
  expect_same_mesh(msh, geo);
  expect_straight_beam(msh, "beam", "root", 1.0, 4);
  EXPECT_TRUE(msh.parameters.empty());
  // gmsh numbers the end points 1, 2 and the interior nodes 3, 4, 5; local ids follow the beam.
  EXPECT_EQ(msh.node_tags, (std::vector<std::size_t>{1, 3, 4, 5, 2}));
  EXPECT_EQ(msh.line_blocks[0].element_tags, (std::vector<std::size_t>{3, 4, 5, 6}));
}

/// Meshes `geo` with gmsh itself (order `order`) and writes it as `msh` in MSH `version`.
void write_msh_with_gmsh(const std::string& geo, const std::string& msh, double version, int order) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::onelab::clear();
  gmsh::open(geo);
  gmsh::option::setNumber("Mesh.ElementOrder", order);
  gmsh::model::mesh::generate(1);
  gmsh::option::setNumber("Mesh.MshFileVersion", version);
  gmsh::write(msh);
  gmsh::finalize();
}

TEST(MeshMsh, WrittenByGmshReadsBackIdentically) {
  const TempDir dir;
  for (int order : {1, 2}) {
    for (double version : {4.1, 2.2}) {
      SCOPED_TRACE("order " + std::to_string(order) + ", MSH " + std::to_string(version));
      const std::string geo = dir.write("beam.geo", std::string(kStraightGeo) + "Transfinite Curve{1} = 6;\nMesh.ElementOrder = " +
                                                        std::to_string(order) + ";\n");
      const std::string msh = dir.file("beam.msh");
      write_msh_with_gmsh(geo, msh, version, order);
      const MeshData from_msh = read_mesh(msh, {}, "test");
      const MeshData from_geo = read_mesh(geo, {}, "test");
      expect_same_mesh(from_msh, from_geo);
      EXPECT_EQ(from_msh.line_blocks.at(0).elements.size(), static_cast<size_t>(5 * order));
    }
  }
}

TEST(MeshMsh, Msh2WithCurveInTwoGroupsIsRefused) {
  // MSH 2 stores an element once per physical group; gmsh reads both copies into each group.
  const TempDir dir;
  const std::string geo = dir.write("two.geo", std::string(kStraightGeo) + "Physical Curve(\"all\") = {1};\n");
  const std::string msh = dir.file("two.msh");
  write_msh_with_gmsh(geo, msh, 2.2, 1);
  const std::string e = input_error_of([&] { read_mesh(msh, {}, "scene.yaml:3: mesh.file"); });
  EXPECT_HAS(e, "scene.yaml:3: mesh.file: mesh '" + msh + "'");
  EXPECT_HAS(e, "join the same gmsh nodes");
  EXPECT_HAS(e, "MSH 4");
  // The same mesh in MSH 4 holds each element once: two blocks over the same segments.
  write_msh_with_gmsh(geo, msh, 4.1, 1);
  const MeshData m = read_mesh(msh, {}, "test");
  ASSERT_EQ(m.line_blocks.size(), 2u);
  EXPECT_EQ(m.line_blocks[0].elements, m.line_blocks[1].elements);
  EXPECT_FALSE(m.line_blocks[0].elements.empty());
}

// ---- second order ----------------------------------------------------------------------------

TEST(MeshSecondOrder, ThreeNodeLinesSplitAtTheMidNode) {
  const TempDir dir;
  const std::string geo = dir.write("o2.geo", std::string(kStraightGeo) + "Mesh.ElementOrder = 2;\n");
  const MeshData m = read_mesh(geo, with_elements(4), "test");
  // 4 three-node lines → 8 segments over 9 nodes (every node used), the chain root → tip.
  expect_straight_beam(m, "beam", "root", 2.0, 8);
  const MeshLineBlock& b = m.line_blocks[0];
  for (size_t e = 0; e < 8; e += 2) EXPECT_EQ(b.element_tags[e], b.element_tags[e + 1]);
  EXPECT_EQ(std::set<size_t>(b.element_tags.begin(), b.element_tags.end()).size(), 4u);

  // On the arc, the mid nodes lie on the circle too.
  const std::string arc = dir.write("arc.geo", "Include \"" + mesh_path("bend45.geo") + "\";\nMesh.ElementOrder = 2;\n");
  const MeshData a = read_mesh(arc, with_parameters({{"n", 3}}), "test");
  ASSERT_EQ(a.line_blocks.at(0).elements.size(), 6u);
  ASSERT_EQ(a.points.size(), 7u);
  for (const Eigen::Vector3d& p : a.points) EXPECT_NEAR((p - Eigen::Vector3d(0, 100, 0)).norm(), 100, 1e-9);
}

// ---- element size ----------------------------------------------------------------------------

TEST(MeshElementSize, BoundsTheElementLength) {
  const TempDir dir;
  const std::string geo = dir.write("free.geo", kStraightGeo);  // no Transfinite: sizes apply
  MeshOptions o;
  o.element_size = 0.3;
  const MeshData m = read_mesh(geo, o, "test");
  const MeshLineBlock& b = m.line_blocks.at(0);
  EXPECT_GE(b.elements.size(), 7u);  // length 2
  for (const auto& e : b.elements) EXPECT_LE((m.points[e[1]] - m.points[e[0]]).norm(), 0.3 * (1 + 1e-9));
  EXPECT_EQ(m.points[m.named_points.at("tip")], Eigen::Vector3d(2, 0, 0));
}

TEST(MeshElementSize, NotHonouredByATransfiniteGeoIsAnError) {
  MeshOptions o;
  o.element_size = 0.01;
  const std::string e = input_error_of([&] { read_mesh(mesh_path("cantilever.geo"), o, "ctx"); });
  EXPECT_HAS(e, "element_size = 0.01 m was not honoured");
  EXPECT_HAS(e, "Transfinite");
}

// ---- names -----------------------------------------------------------------------------------

TEST(MeshNames, UnnamedGroupsGetDefaultNames) {
  const TempDir dir;
  const std::string geo = dir.write("unnamed.geo", R"(
Point(1) = {0, 0, 0};
Point(2) = {1, 0, 0};
Point(3) = {1, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Physical Curve(5) = {1};
Physical Curve("second") = {2};
Physical Point(7) = {3};
)");
  const MeshData m = read_mesh(geo, with_elements(2), "test");
  ASSERT_EQ(m.line_blocks.size(), 2u);
  EXPECT_EQ(m.line_blocks[0].name, "line_5");  // by physical tag
  EXPECT_EQ(m.line_blocks[0].tag, 5);
  EXPECT_EQ(m.line_blocks[1].name, "second");  // gmsh gives it the next free tag, 6
  EXPECT_EQ(m.line_blocks[1].tag, 6);
  EXPECT_NE(m.find_line_block("line_5"), nullptr);
  ASSERT_EQ(m.named_points.count("point_7"), 1u);
  EXPECT_EQ(m.points[m.named_points.at("point_7")], Eigen::Vector3d(1, 1, 0));
  EXPECT_EQ(m.points.size(), 5u);  // compact: 3 + 3 nodes sharing (1, 0, 0)
}

TEST(MeshNames, OnlyNodesOfTheGroupsAreKept) {
  const TempDir dir;
  // Curve 2 is in no physical group: its nodes are left out, the numbering stays compact.
  const std::string geo = dir.write("spare.geo", std::string(kStraightGeo) + "Point(3) = {2, 1, 0};\nLine(2) = {2, 3};\n");
  const MeshData m = read_mesh(geo, with_elements(4), "test");
  expect_straight_beam(m, "beam", "root", 2.0, 4);
  for (const Eigen::Vector3d& p : m.points) EXPECT_EQ(p.y(), 0.0);
}

TEST(MeshNames, NamedPointNotOnALineIsKept) {
  const TempDir dir;
  const std::string geo = dir.write("extra.geo", std::string(kStraightGeo) + "Point(3) = {0, 5, 0};\nPhysical Point(\"off\") = {3};\n");
  const MeshData m = read_mesh(geo, with_elements(2), "test");
  ASSERT_EQ(m.points.size(), 4u);
  EXPECT_EQ(m.named_points.at("off"), 3);  // after the line nodes
  EXPECT_EQ(m.points[3], Eigen::Vector3d(0, 5, 0));
}

// ---- errors ----------------------------------------------------------------------------------

TEST(MeshErrors, MissingFileAndWrongExtension) {
  const TempDir dir;
  std::string e = input_error_of([&] { read_mesh(dir.file("nope.geo"), {}, "scene.yaml:12: mesh.file"); });
  EXPECT_HAS(e, "scene.yaml:12: mesh.file: mesh '" + dir.file("nope.geo") + "': file not found");
  e = input_error_of([&] { read_mesh(dir.write("beam.stl", "solid x\n"), {}, "ctx"); });
  EXPECT_HAS(e, "ctx: mesh '");
  EXPECT_HAS(e, "expected a gmsh file ending in .geo");
  e = input_error_of([&] { read_mesh(dir.file(""), {}, "ctx"); });
  EXPECT_HAS(e, "expected a gmsh file ending in .geo");
}

TEST(MeshErrors, MalformedGeoThenGmshStillUsable) {
  const TempDir dir;
  const std::string bad = dir.write("bad.geo", "Point(1) = {0, 0, 0;\nLine(1) = {1, 2};\n");
  std::string e = input_error_of([&] { read_mesh(bad, {}, "ctx"); });
  EXPECT_HAS(e, "ctx: mesh '" + bad + "': gmsh failed while reading the .geo (expected a valid gmsh geometry script)");
  EXPECT_HAS(e, "line 1: syntax error");
  const std::string unknown = dir.write("unknown.geo", "Point(1) = {0, 0, 0};\nPoint(2) = {x, 0, 0};\n");
  e = input_error_of([&] { read_mesh(unknown, {}, "ctx"); });
  EXPECT_HAS(e, "line 2: Unknown variable 'x'");
  // A failed read leaves gmsh usable (its session is finalized and started again).
  expect_straight_beam(read_mesh(mesh_path("cantilever.geo"), with_elements(2), "test"), "beam", "root", 1.0, 2);
}

TEST(MeshErrors, CorruptMsh) {
  const TempDir dir;
  std::string good;
  {
    std::ifstream in(mesh_path("cantilever_n4.msh"));
    good.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string truncated = dir.write("truncated.msh", good.substr(0, good.find("$Nodes") + 20));
  std::string e = input_error_of([&] { read_mesh(truncated, {}, "ctx"); });
  EXPECT_HAS(e, "ctx: mesh '" + truncated + "': not a valid MSH file (checked before gmsh reads it): line 17: ");
  EXPECT_HAS(e, "the file is cut short, or the count is wrong");
  // Without its header gmsh would run the file as a .geo script: refused before.
  e = input_error_of([&] { read_mesh(dir.write("text.msh", "hello world\n"), {}, "ctx"); });
  EXPECT_HAS(e, "not a gmsh MSH file: expected it to start with $MeshFormat, found 'hello'");
  e = input_error_of([&] { read_mesh(dir.write("empty.msh", ""), {}, "ctx"); });
  EXPECT_HAS(e, "(the file is empty)");
  std::string garbled = good;
  garbled.replace(garbled.find("$Elements") + 10, 7, "x y z w");
  e = input_error_of([&] { read_mesh(dir.write("garbled.msh", garbled), {}, "ctx"); });
  EXPECT_HAS(e, "line 33: expected the number of element blocks (an integer), found 'x'");
}

// A .msh is checked before gmsh reads it: gmsh 4.8.4 crashed (SIGSEGV in getMeshVertexByTag) on
// an element naming a node that does not exist (tests/fuzz). Each damage gets its line and what is wrong.
TEST(MeshErrors, MshCheckedBeforeGmsh) {
  const TempDir dir;
  std::string good;
  {
    std::ifstream in(mesh_path("cantilever_n4.msh"));
    good.assign(std::istreambuf_iterator<char>(in), {});
  }
  auto damaged = [&](const std::string& from, const std::string& to) {
    std::string t = good;
    const size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return dir.write("damaged.msh", t.replace(at, from.size(), to));
  };
  auto expect = [&](const std::string& msh, const std::string& what) {
    const std::string e = input_error_of([&] { read_mesh(msh, {}, "ctx"); });
    EXPECT_HAS(e, "ctx: mesh '" + msh + "': not a valid MSH file (checked before gmsh reads it): line ");
    EXPECT_HAS(e, what);
  };
  expect(damaged("\n3 1 3 \n", "\n3 1 9 \n"), "element 3 uses node 9, which is not in $Nodes");
  expect(damaged("\n3\n4\n5\n", "\n3\n40\n5\n"), "node tag 40 is outside [1, 5] (the header's minNodeTag and maxNodeTag)");
  expect(damaged("$Nodes\n3 5 1 5", "$Nodes\n3 5000000 1 5"), "the number of nodes 5000000 is more than the rest of the file can hold");
  expect(damaged("4.1 0 8", "4.1 1 8"), "a binary MSH file: alphaflex reads ASCII MSH only");
  expect(damaged("4.1 0 8", "3.0 0 8"), "MSH version '3.0': expected 4.1 or 2.2");
  expect(damaged("0.4999999999986921 0 0", "nan 0 0"), "a node coordinate is 'nan': expected a finite number");
  expect(damaged("1 1 1 4\n", "1 7 1 4\n"), "an element block of entity 7 (dimension 1), which is not in $Entities");
  expect(damaged("$EndNodes", "$EndNodez"), "expected $EndNodes, found '$EndNodez'");
  // The undamaged file still reads.
  EXPECT_EQ(read_mesh(dir.write("good.msh", good), {}, "ctx").line_blocks.size(), 1u);
}

TEST(MeshErrors, NoPhysicalGroups) {
  const TempDir dir;
  const std::string geo = dir.write("plain.geo", "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\nLine(1) = {1, 2};\n");
  std::string e = input_error_of([&] { read_mesh(geo, {}, "ctx"); });
  EXPECT_HAS(e, "no physical groups of dimension 0, 1 or 2");
  EXPECT_HAS(e, "Physical Curve(\"name\")");
  EXPECT_HAS(e, "Physical Surface(\"name\")");
}

TEST(MeshErrors, Parameters) {
  std::string e = input_error_of([&] { read_mesh(mesh_path("cantilever.geo"), with_parameters({{"N", 4}, {"length", 2}}), "ctx"); });
  EXPECT_HAS(e, "unknown parameters 'N', 'length': the .geo defines 'L', 'n'");
  EXPECT_HAS(e, "DefineConstant[ n = {16, Name \"n\"} ]");

  const TempDir dir;
  // Without a Name a DefineConstant is not a ONELAB parameter: it cannot be set from outside.
  const std::string plain = dir.write("plain.geo", std::string("DefineConstant[ m = 3 ];\n") + kStraightGeo);
  e = input_error_of([&] { read_mesh(plain, with_parameters({{"m", 4}}), "ctx"); });
  EXPECT_HAS(e, "unknown parameter 'm': the .geo defines no parameters");
  // The ONELAB name is the Name string, not the variable.
  const std::string path = dir.write("path.geo", std::string("DefineConstant[ n = {3, Name \"Mesh/n\"} ];\n") + kStraightGeo);
  e = input_error_of([&] { read_mesh(path, with_parameters({{"n", 4}}), "ctx"); });
  EXPECT_HAS(e, "unknown parameter 'n': the .geo defines 'Mesh/n'");
  EXPECT_EQ(read_mesh(path, with_parameters({{"Mesh/n", 4}}), "ctx").parameters.at("Mesh/n"), 4.0);
  // A ReadOnly constant keeps its own value.
  const std::string fixed = dir.write("fixed.geo", std::string("DefineConstant[ n = {3, Name \"n\", ReadOnly 1} ];\n") + kStraightGeo);
  e = input_error_of([&] { read_mesh(fixed, with_parameters({{"n", 4}}), "ctx"); });
  EXPECT_HAS(e, "parameter 'n' = 4 was not taken: the .geo keeps 3");
  e = input_error_of([&] { read_mesh(mesh_path("cantilever.geo"), with_parameters({{"n", NAN}}), "ctx"); });
  EXPECT_HAS(e, "parameter 'n' = nan: expected a finite number");
}

TEST(MeshErrors, OptionsThatDoNotFit) {
  MeshOptions o;
  o.elements_per_curve = 4;
  o.parameters["n"] = 4;
  std::string e = input_error_of([&] { read_mesh(mesh_path("cantilever_n4.msh"), o, "ctx"); });
  EXPECT_HAS(e, "elements_per_curve, parameters: only for a .geo; a .msh is read as is, never re-meshed");
  o = {};
  o.element_size = 0.1;
  e = input_error_of([&] { read_mesh(mesh_path("cantilever_n4.msh"), o, "ctx"); });
  EXPECT_HAS(e, "element_size: only for a .geo");
  o.elements_per_curve = 3;
  e = input_error_of([&] { read_mesh(mesh_path("cantilever.geo"), o, "ctx"); });
  EXPECT_HAS(e, "elements_per_curve and element_size exclude each other");
  e = input_error_of([&] { read_mesh(mesh_path("cantilever.geo"), with_elements(-1), "ctx"); });
  EXPECT_HAS(e, "elements_per_curve = -1: expected a number > 0");
  o = {};
  o.element_size = -0.5;
  e = input_error_of([&] { read_mesh(mesh_path("cantilever.geo"), o, "ctx"); });
  EXPECT_HAS(e, "element_size = -0.5: expected a length > 0");
}

TEST(Mesh, PointGroupOfSeveralNodesIsAGroupNotANamedPoint) {
  // Physical Point("ends") = {1, 2}: both ends of the beam, as a group (supports, hinges), while
  // "root" and "tip" (one point each) stay named points.
  const TempDir dir;
  const std::string geo = dir.write("ends.geo", std::string(kStraightGeo) + "Physical Point(\"ends\") = {1, 2};\n");
  const MeshData m = read_mesh(geo, {}, "ctx");
  EXPECT_EQ(m.named_points.count("ends"), 0u);
  ASSERT_EQ(m.point_groups.count("ends"), 1u);
  const std::vector<int>& ids = m.point_groups.at("ends");
  ASSERT_EQ(ids.size(), 2u);
  std::vector<double> xs{m.points[static_cast<size_t>(ids[0])].x(), m.points[static_cast<size_t>(ids[1])].x()};
  std::sort(xs.begin(), xs.end());
  EXPECT_EQ(xs[0], 0.0);
  EXPECT_EQ(xs[1], 2.0);
  EXPECT_EQ(ids[0] == m.named_points.at("root") || ids[1] == m.named_points.at("root"), true);
  // The same data survive the byte form in which rank 0 sends a mesh to the others.
  const MeshData back = unpack(pack(m));
  EXPECT_EQ(back.point_groups, m.point_groups);
  EXPECT_EQ(back.named_points, m.named_points);
  ASSERT_EQ(back.points.size(), m.points.size());
  for (size_t i = 0; i < m.points.size(); ++i) EXPECT_EQ(back.points[i], m.points[i]);
  ASSERT_EQ(back.line_blocks.size(), m.line_blocks.size());
  EXPECT_EQ(back.line_blocks[0].elements, m.line_blocks[0].elements);
  EXPECT_EQ(back.line_blocks[0].name, m.line_blocks[0].name);
  EXPECT_EQ(back.node_tags, m.node_tags);
}

TEST(MeshErrors, DuplicateNames) {
  const TempDir dir;
  // Across dimensions in a .geo.
  const std::string geo = dir.write("dup.geo", std::string(kStraightGeo) + "Physical Curve(\"tip\") = {1};\n");
  std::string e = input_error_of([&] { read_mesh(geo, {}, "ctx"); });
  EXPECT_HAS(e, "two physical groups are named 'tip'");
  // Within a dimension: a .msh may name two groups alike; a default name may collide too.
  std::string msh;
  {
    std::ifstream in(mesh_path("cantilever_n4.msh"));
    msh.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::string same = msh;
  same.replace(same.find("0 3 \"tip\""), 9, "0 3 \"root\"");
  e = input_error_of([&] { read_mesh(dir.write("same.msh", same), {}, "ctx"); });
  EXPECT_HAS(e, "two physical groups are named 'root'");
  std::string collide = msh;
  collide.replace(collide.find("0 3 \"tip\""), 9, "0 3 \"line_1\"");
  collide.replace(collide.find("1 1 \"beam\""), 10, "");
  collide.replace(collide.find("$PhysicalNames\n3"), 16, "$PhysicalNames\n2");
  e = input_error_of([&] { read_mesh(dir.write("collide.msh", collide), {}, "ctx"); });
  EXPECT_HAS(e, "two physical groups are named 'line_1'");
}

TEST(MeshErrors, UnsupportedElementType) {
  const TempDir dir;
  const std::string geo = dir.write("o3.geo", std::string(kStraightGeo) + "Mesh.ElementOrder = 3;\n");
  const std::string e = input_error_of([&] { read_mesh(geo, with_elements(2), "ctx"); });
  EXPECT_HAS(e, "physical group 'beam' (dimension 1) holds element 3 of type 'Line 4' (gmsh type 26)");
  EXPECT_HAS(e, "expected 2-node lines (type 1) or 3-node lines (type 8");
}

}  // namespace
}  // namespace alphaflex

#undef EXPECT_HAS  // a unity batch's next file must not see it
