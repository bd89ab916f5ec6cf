// Shells in the results (io/results_writer.hpp): a small mixed mesh of ReissnerMindlinShell
// quadrilaterals and triangles, built here in C++ next to a node that no shell uses, written at two
// states; the HDF5 datasets are read back with the HDF5 C API and compared with the model: the
// Mixed connectivity (XDMF type code, then the model's node ids), the node positions and
// displacements of the deformed state, and every shell_<field> equal to the element's own output.
// The XDMF index must have a "shells" grid with a Mixed topology and every field as cell data.
// The files go to a fresh temporary directory, or to $ALPHAFLEX_TEST_OUTPUT_DIR/results_shells
// when that is set (test_support.hpp): ctest scenes.paraview_shells_unit sets it and opens the
// files with ParaView (tests/scenes/paraview_shells.py). ResultsCapabilities: elements of types
// the writer does not know are drawn and measured from what they say of themselves.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/shell.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "alphaflex/study/strain_energy.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

/// A dataset of the file as doubles (any shape, row-major); empty if it does not exist.
std::vector<double> read_doubles(hid_t file, const std::string& path) {
  if (H5Lexists(file, path.c_str(), H5P_DEFAULT) <= 0) return {};
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<double> v(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  if (!v.empty()) H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(set);
  return v;
}

std::vector<int> read_ints(hid_t file, const std::string& path) {
  if (H5Lexists(file, path.c_str(), H5P_DEFAULT) <= 0) return {};
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<int> v(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  if (!v.empty()) H5Dread(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(set);
  return v;
}

/// Number of dimensions and extents of a dataset.
std::vector<hsize_t> shape(hid_t file, const std::string& path) {
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<hsize_t> dims(static_cast<size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(set);
  return dims;
}

Node frame_node(const std::string& name, const Eigen::Vector3d& x) {
  Node n;
  n.name = name;
  n.kind = NodeKind::Frame3D;
  n.q0.resize(7);
  store_pose(x, Eigen::Matrix3d::Identity(), n.q0.data());
  n.v0 = Eigen::VectorXd::Zero(6);
  return n;
}

}  // namespace

TEST(ResultsShells, MixedShellMeshIsWrittenWithConnectivityGeometryAndResultants) {
  // Node 0 belongs to no shell (a body, say), so the shell connectivity must use model node ids.
  // Shell nodes 1..8: two quadrilaterals [1 2 5 4], [2 3 6 5] and two triangles [3 7 6], [6 7 8].
  Model model;
  model.name = "shells";
  model.add_node(frame_node("hub", Eigen::Vector3d(-1, 0, 0)));
  const std::vector<Eigen::Vector3d> X = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0},
                                          {1, 1, 0}, {2, 1, 0}, {3, 0.5, 0}, {3, 1.5, 0}};
  for (size_t i = 0; i < X.size(); ++i) model.add_node(frame_node("p" + std::to_string(i + 1), X[i]));
  const std::vector<std::vector<int>> cells = {{1, 2, 5, 4}, {2, 3, 6, 5}, {3, 7, 6}, {6, 7, 8}};
  const ShellSection section = ShellSection::isotropic(2.1e11, 0.3, 7800, 0.01);
  for (size_t c = 0; c < cells.size(); ++c) {
    std::vector<Pose<double>> ref;
    std::vector<Eigen::Vector3d> dirs;
    for (int n : cells[c]) {
      ref.push_back({X[static_cast<size_t>(n - 1)], Eigen::Matrix3d::Identity()});
      dirs.emplace_back(0, 0, 1);
    }
    model.add_element(std::make_unique<ReissnerMindlinShell>("s" + std::to_string(c), cells[c], section, ref, dirs,
                                                             Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero()));
  }
  // A displacement sensor on the corner (3, 1.5, 0): tests/scenes/paraview_shells.py compares the
  // motion of that point in ParaView with the CSV (ctest scenes.paraview_shells_unit).
  Sensor tip;
  tip.name = "tip_w";
  tip.kind = Sensor::Kind::PointDisplacement;
  tip.node = 8;
  tip.component = 2;
  tip.initial = X[7];
  model.add_sensor(tip);
  ASSERT_STREQ(model.elements()[0]->type(), "shell_quad4");
  ASSERT_STREQ(model.elements()[2]->type(), "shell_tri3");

  // The deformed state: the plate bent about the y axis, w = 0.05 x², stretched by 1% in x, the
  // node frames turned by the slope; every node moves.
  MechanicalState s0 = model.initial_state();
  MechanicalState s1 = s0;
  s1.t = 0.5;
  for (size_t i = 0; i < model.nodes().size(); ++i) {
    const Node& n = model.nodes()[i];
    const Eigen::Vector3d x0 = n.q0.head<3>();
    const Eigen::Vector3d x(1.01 * x0.x(), x0.y() + 0.002 * x0.x(), 0.05 * x0.x() * x0.x());
    const Eigen::Matrix3d R = exp_so3<double>(Eigen::Vector3d(0, -std::atan(0.1 * x0.x()), 0.01 * x0.y()));
    store_pose(x, R, s1.q.data() + n.first_conf);
    s1.v.segment(n.first_dof, 6) << 0.1 * x0.x(), 0, 0.2, 0, 0.3, 0;
  }

  const alphaflex::testing::TestOutputDir out("results_shells");
  const std::string& outdir = out.path();
  std::string h5, xdmf;
  {
    Subdomain sub(model, MPI_COMM_SELF);
    ResultsWriter w(sub, outdir, "shells", true);
    for (const MechanicalState* s : {&s0, &s1}) {
      w.write_sensors(s->t, {model.sensors()[0].evaluate(model, *s)});
      w.write_fields(*s);
    }
    w.finish();
    h5 = w.h5_path();
    xdmf = w.xdmf_path();
  }

  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0) << h5;
  // Mixed topology: (4 = triangle | 5 = quadrilateral, then the node ids), cells in model order.
  const std::vector<int> conn = read_ints(f, "/topology/shell_connectivity");
  const std::vector<int> want = {5, 1, 2, 5, 4, 5, 2, 3, 6, 5, 4, 3, 7, 6, 4, 6, 7, 8};
  EXPECT_EQ(conn, want);
  EXPECT_EQ(H5Lexists(f, "/topology/beam_connectivity", H5P_DEFAULT), 0) << "shells are not beams";

  const size_t nn = model.nodes().size(), ns = cells.size();
  const auto names = model.elements()[0]->output_names();
  ASSERT_EQ(names.size(), 10u);
  for (int which = 0; which < 2; ++which) {
    const MechanicalState& s = which == 0 ? s0 : s1;
    const std::string step = which == 0 ? "/step_000000/" : "/step_000001/";
    SCOPED_TRACE(step);
    const std::vector<double> pos = read_doubles(f, step + "node_position");
    const std::vector<double> disp = read_doubles(f, step + "node_displacement");
    ASSERT_EQ(pos.size(), 3 * nn);
    ASSERT_EQ(disp.size(), 3 * nn);
    EXPECT_EQ(disp[3 * 8 + 2], model.sensors()[0].evaluate(model, s));
    for (size_t i = 0; i < nn; ++i)
      for (int k = 0; k < 3; ++k) {
        const Node& n = model.nodes()[i];
        EXPECT_EQ(pos[3 * i + k], s.q[n.first_conf + k]);
        EXPECT_NEAR(disp[3 * i + k], s.q[n.first_conf + k] - n.q0[k], 1e-15);
      }
    // Every field: one value per shell element, equal to the element's own output at that state.
    std::vector<Eigen::VectorXd> expected(ns);
    for (size_t e = 0; e < ns; ++e) {
      const Element& el = *model.elements()[e];
      LocalState ls;
      const auto idx = model.dofs_of(el.nodes());
      ls.q = gather(s.q, model.confs_of(el.nodes()));
      ls.v = gather(s.v, idx);
      ls.qdd = gather(s.qdd, idx);
      ls.t = s.t;
      el.output(ls, expected[e]);
      ASSERT_EQ(expected[e].size(), static_cast<Eigen::Index>(names.size()));
    }
    for (size_t k = 0; k < names.size(); ++k) {
      const std::string set = step + "shell_" + names[k];
      const std::vector<double> v = read_doubles(f, set);
      ASSERT_EQ(v.size(), ns) << set;
      EXPECT_EQ(shape(f, set), std::vector<hsize_t>{ns}) << set;
      for (size_t e = 0; e < ns; ++e)
        EXPECT_EQ(v[e], expected[e][static_cast<Eigen::Index>(k)]) << set << " element " << e;
    }
    double largest = 0.0;
    for (size_t k = 0; k < names.size(); ++k)
      for (size_t e = 0; e < ns; ++e) largest = std::max(largest, std::fabs(expected[e][static_cast<Eigen::Index>(k)]));
    if (s.t == 0.0) {
      EXPECT_LT(largest, 1e-6) << "the reference state is stress free";
    } else {
      EXPECT_GT(largest, 1e3) << "the bent and stretched plate carries resultants";
    }
  }
  H5Fclose(f);

  // The XDMF index: a temporal collection "shells" of Mixed grids, the node positions of each step
  // as geometry, every field as cell data and the displacement as node data.
  std::ifstream in(xdmf);
  ASSERT_TRUE(in.good()) << xdmf;
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string x = buf.str();
  EXPECT_NE(x.find("<Grid Name=\"shells\" GridType=\"Collection\" CollectionType=\"Temporal\">"), std::string::npos);
  EXPECT_NE(x.find("<Topology TopologyType=\"Mixed\" NumberOfElements=\"4\">"), std::string::npos);
  // Each step refers to the part file that holds it (io/results_writer.hpp): the first output step
  // is committed at once (part 0), the second at finish() (part 1), each with its own topology.
  EXPECT_NE(x.find("Dimensions=\"18\" NumberType=\"Int\" Precision=\"4\" Format=\"HDF\">"
                   "shells.h5.parts/part_000000.h5:/topology/shell_connectivity"),
            std::string::npos);
  EXPECT_NE(x.find("shells.h5.parts/part_000001.h5:/topology/shell_connectivity"), std::string::npos);
  EXPECT_NE(x.find("shells.h5.parts/part_000001.h5:/step_000001/shell_von_mises_top"), std::string::npos);
  for (const auto& name : names)
    EXPECT_NE(x.find("<Attribute Name=\"" + name + "\" AttributeType=\"Scalar\" Center=\"Cell\">"), std::string::npos)
        << name;
  EXPECT_EQ(x.find("<Grid Name=\"beams\""), std::string::npos);
}

// ---- Element capabilities (model/element.hpp): the results and the strain energy ask elements
// what they draw and store, so an element type the writer has never seen is written correctly.

namespace {

/// What a test element of a structure the writer does not know says of itself: its structure,
/// its cell, its fields, their values and its energy. It has no forces: only its capabilities are
/// under test.
struct ToyKind {
  const char* structure;
  OutputCell cell;
  std::vector<CellField> fields;
  std::function<Eigen::VectorXd(const LocalState&)> values;
  std::function<double(const Eigen::VectorXd&)> energy;
};

class ToyElement final : public Element {
 public:
  ToyElement(std::string name, std::vector<int> nodes, const ToyKind& kind)
      : Element(std::move(name), std::move(nodes)), kind_(&kind) {}
  const char* type() const override { return kind_->structure; }
  void evaluate(const LocalState&, LocalResidual&, bool) const override {}
  const char* structure() const override { return kind_->structure; }
  OutputCell output_cell() const override { return kind_->cell; }
  std::vector<CellField> cell_fields() const override { return kind_->fields; }
  void output(const LocalState& s, Eigen::VectorXd& v) const override { v = kind_->values(s); }
  double elastic_energy(const Eigen::VectorXd& q) const override { return kind_->energy(q); }
  std::unique_ptr<Element> clone() const override { return std::make_unique<ToyElement>(*this); }

 private:
  const ToyKind* kind_;
};

}  // namespace

TEST(ResultsCapabilities, UnknownElementTypesAreDrawnAndMeasuredFromTheirCapabilities) {
  Model model;
  model.name = "toys";
  const std::vector<Eigen::Vector3d> X = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 0, 0}};
  for (size_t i = 0; i < X.size(); ++i) model.add_node(frame_node("n" + std::to_string(i), X[i]));
  // "membrane": triangles drawn with their corners in the order (0, 2, 1), a field of 3
  // components (the mean of the nodes' positions) and a scalar (t); energy: the sum of the x.
  const ToyKind membrane{"membrane", {CellShape::triangle, {0, 2, 1}}, {{"centre", 3}, {"t", 1}},
                         [](const LocalState& s) {
                           Eigen::VectorXd v(4);
                           v.head<3>() = (s.q.segment<3>(0) + s.q.segment<3>(7) + s.q.segment<3>(14)) / 3.0;
                           v[3] = s.t;
                           return v;
                         },
                         [](const Eigen::VectorXd& q) { return q[0] + q[7] + q[14]; }};
  // "cable": lines drawn from the second node to the first, tension x_0 − x_1, energy ½ (x_1 − x_0)².
  const ToyKind cable{"cable", {CellShape::line, {1, 0}}, {{"tension"}},
                      [](const LocalState& s) { return Eigen::VectorXd::Constant(1, s.q[0] - s.q[7]); },
                      [](const Eigen::VectorXd& q) { return 0.5 * (q[7] - q[0]) * (q[7] - q[0]); }};
  model.add_element(std::make_unique<ToyElement>("m[0]", std::vector<int>{0, 1, 2}, membrane));
  model.add_element(std::make_unique<ToyElement>("m[1]", std::vector<int>{1, 3, 2}, membrane));
  model.add_element(std::make_unique<ToyElement>("c[0]", std::vector<int>{1, 4}, cable));
  MechanicalState s = model.initial_state();
  s.t = 0.25;
  for (size_t i = 0; i < X.size(); ++i) s.q[model.nodes()[i].first_conf] += 0.1 * static_cast<double>(i);

  const alphaflex::testing::TestOutputDir out("results_toys");
  const std::filesystem::path dir = out.path();
  std::string h5, xdmf;
  {
    Subdomain sub(model, MPI_COMM_SELF);
    ResultsWriter w(sub, dir.string(), "toys", true);
    w.write_sensors(s.t, {});
    w.write_fields(s);
    w.finish();
    h5 = w.h5_path();
    xdmf = w.xdmf_path();
  }
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0) << h5;
  // Faces: a Mixed topology (4 = triangle, then the corners in the element's cell order);
  // lines only: a Polyline of two node ids per cell.
  EXPECT_EQ(read_ints(f, "/topology/membrane_connectivity"), (std::vector<int>{4, 0, 2, 1, 4, 1, 2, 3}));
  EXPECT_EQ(read_ints(f, "/topology/cable_connectivity"), (std::vector<int>{4, 1}));
  // A field of 3 components is one dataset of 3 columns; each value is the element's own.
  EXPECT_EQ(shape(f, "/step_000000/membrane_centre"), (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(shape(f, "/step_000000/membrane_t"), (std::vector<hsize_t>{2}));
  std::vector<double> want;
  Eigen::VectorXd v;
  for (int e = 0; e < 2; ++e) {
    const Element& el = *model.elements()[static_cast<size_t>(e)];
    el.output(model.local_state(el, s), v);
    for (int k = 0; k < 3; ++k) want.push_back(v[k]);
  }
  EXPECT_EQ(read_doubles(f, "/step_000000/membrane_centre"), want);
  EXPECT_EQ(read_doubles(f, "/step_000000/membrane_t"), (std::vector<double>{0.25, 0.25}));
  EXPECT_EQ(read_doubles(f, "/step_000000/cable_tension"), (std::vector<double>{s.q[7] - s.q[28]}));
  H5Fclose(f);
  EXPECT_EQ(model.elements()[0]->output_names(), (std::vector<std::string>{"centre[0]", "centre[1]", "centre[2]", "t"}));

  std::ifstream in(xdmf);
  std::stringstream buf;
  buf << in.rdbuf();
  const std::string x = buf.str();
  // Grids of lines come first, then faces; a grid is named after its structure.
  const size_t cables = x.find("<Grid Name=\"cables\""), membranes = x.find("<Grid Name=\"membranes\"");
  ASSERT_NE(cables, std::string::npos);
  ASSERT_NE(membranes, std::string::npos);
  EXPECT_LT(cables, membranes);
  EXPECT_NE(x.find("<Topology TopologyType=\"Polyline\" NumberOfElements=\"1\" NodesPerElement=\"2\">"), std::string::npos);
  EXPECT_NE(x.find("<Topology TopologyType=\"Mixed\" NumberOfElements=\"2\">"), std::string::npos);
  EXPECT_NE(x.find("<Attribute Name=\"centre\" AttributeType=\"Vector\" Center=\"Cell\">\n      <DataItem Dimensions=\"2 3\""),
            std::string::npos);

  // The strain energy of each block of a structure: the sum of its elements' elastic energies.
  const auto parts = study::flexible_parts(model);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].name, "m");
  EXPECT_EQ(parts[0].kind, "membrane");
  EXPECT_EQ(parts[1].name, "c");
  EXPECT_EQ(parts[1].kind, "cable");
  const std::vector<double> W = study::strain_energies(model, parts, s);
  const double x0 = s.q[0], x1 = s.q[7], x2 = s.q[14], x3 = s.q[21], x4 = s.q[28];
  EXPECT_EQ(W[0], (x0 + x1 + x2) + (x1 + x3 + x2));
  EXPECT_EQ(W[1], 0.5 * (x4 - x1) * (x4 - x1));
}

// ResultsLayout: bodies and elastic displacement in the results (src/io/results_layout.hpp): a hub node
// that no element uses and a 3 × 3-node plate of four shell quadrilaterals, written by the results
// writer; the HDF5 file is read back.
//  - The bodies grid holds the hub only (body_position), not the plate's nodes.
//  - elastic_displacement of the plate: with the plate bent by d_i = α (x_i² − 2/3) e_z and then
//    moved rigidly, x_i = t + Q (X_i + d_i), the best-fit rigid motion is (t, Q) exactly (d has zero
//    mean and Σ (X_i − c) d_iᵀ = 0 on this symmetric grid, so H = Σ (X_i − c)(X_i − c)ᵀ is
//    symmetric and its polar rotation is I before Q), and the elastic displacement is Q d_i; a
//    rigid motion alone gives 0. Values to round-off (1e-14 m on a plate of 2 m).
TEST(ResultsLayout, BodiesGridHoldsBodiesAndElasticDisplacementRemovesTheRigidMotion) {
  Model model;
  model.name = "layout";
  model.add_node(frame_node("hub", Eigen::Vector3d(-3, 0, 0)));
  std::vector<Eigen::Vector3d> X;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) X.emplace_back(i, j, 0);
  for (size_t k = 0; k < X.size(); ++k) model.add_node(frame_node("p" + std::to_string(k), X[k]));
  const ShellSection section = ShellSection::isotropic(2.1e11, 0.3, 7800, 0.01);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const int a = 1 + 3 * j + i;  // model node of the cell's first corner
      const std::vector<int> cell = {a, a + 1, a + 4, a + 3};
      std::vector<Pose<double>> ref;
      std::vector<Eigen::Vector3d> dirs;
      for (int n : cell) {
        ref.push_back({X[static_cast<size_t>(n - 1)], Eigen::Matrix3d::Identity()});
        dirs.emplace_back(0, 0, 1);
      }
      model.add_element(std::make_unique<ReissnerMindlinShell>("plate[" + std::to_string(2 * j + i) + "]", cell, section,
                                                               ref, dirs, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d::Zero()));
    }

  const Eigen::Matrix3d Q = exp_so3<double>(Eigen::Vector3d(0.3, -0.7, 1.1));
  const Eigen::Vector3d t(0.4, -2.0, 5.0), hub_at(-2.5, 1.0, 0.5);
  const double alpha = 0.05;
  auto bend = [&](const Eigen::Vector3d& x) { return Eigen::Vector3d(0, 0, alpha * (x.x() * x.x() - 2.0 / 3.0)); };
  MechanicalState rigid = model.initial_state(), bent = rigid;
  rigid.t = 1.0;
  bent.t = 2.0;
  for (size_t k = 0; k < model.nodes().size(); ++k) {
    const Node& n = model.nodes()[k];
    const Eigen::Vector3d x0 = n.q0.head<3>();
    if (k == 0) {  // the hub goes its own way: it belongs to no block
      store_pose(hub_at, Q, rigid.q.data() + n.first_conf);
      store_pose(hub_at, Q, bent.q.data() + n.first_conf);
      continue;
    }
    store_pose(t + Q * x0, Q, rigid.q.data() + n.first_conf);
    store_pose(t + Q * (x0 + bend(x0)), Q, bent.q.data() + n.first_conf);
  }

  const alphaflex::testing::TestOutputDir out("results_layout");
  std::string h5;
  {
    Subdomain sub(model, MPI_COMM_SELF);
    ResultsWriter w(sub, out.path(), "layout", true);
    for (const MechanicalState* s : {&rigid, &bent}) {
      w.write_sensors(s->t, {});
      w.write_fields(*s);
    }
    w.finish();
    h5 = w.h5_path();
  }
  const hid_t f = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0) << h5;
  // The bodies: the hub alone, at its place.
  const std::vector<double> body = read_doubles(f, "/step_000001/body_position");
  ASSERT_EQ(body.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(body[static_cast<size_t>(k)], hub_at[k]);
  EXPECT_EQ(read_doubles(f, "/step_000001/body_displacement").size(), 3u);

  const std::vector<double> e_rigid = read_doubles(f, "/step_000000/node_elastic_displacement");
  const std::vector<double> e_bent = read_doubles(f, "/step_000001/node_elastic_displacement");
  ASSERT_EQ(e_rigid.size(), 3 * model.nodes().size());
  ASSERT_EQ(e_bent.size(), 3 * model.nodes().size());
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(e_rigid[static_cast<size_t>(k)], 0.0) << "the hub is in no block";
    EXPECT_EQ(e_bent[static_cast<size_t>(k)], 0.0);
  }
  double largest = 0.0;
  for (size_t n = 1; n < model.nodes().size(); ++n) {
    const Eigen::Vector3d want = Q * bend(X[n - 1]);
    largest = std::max(largest, want.norm());
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(e_rigid[3 * n + static_cast<size_t>(k)], 0.0, 1e-14) << "node " << n;
      EXPECT_NEAR(e_bent[3 * n + static_cast<size_t>(k)], want[k], 1e-14) << "node " << n;
    }
  }
  EXPECT_GT(largest, 0.03);  // the bending is there to be found (α/3 at the middle row)
  // The displacement itself carries the rigid motion: metres, not centimetres.
  const std::vector<double> disp = read_doubles(f, "/step_000001/node_displacement");
  EXPECT_GT(std::fabs(disp[3 * 5 + 2]), 1.0);
  H5Fclose(f);
}

}  // namespace alphaflex
