// Bodies and elastic displacement in the results (src/io/results_layout.hpp, issue 21): a hub node
// that no element uses and a 3 × 3-node plate of four shell quadrilaterals, written by the results
// writer; the HDF5 file is read back.
//  - The bodies grid holds the hub only (body_position), not the plate's nodes.
//  - elastic_displacement of the plate: with the plate bent by d_i = α (x_i² − 2/3) e_z and then
//    moved rigidly, x_i = t + Q (X_i + d_i), the best-fit rigid motion is (t, Q) exactly (d has zero
//    mean and Σ (X_i − c) d_iᵀ = 0 on this symmetric grid, so H = Σ (X_i − c)(X_i − c)ᵀ is
//    symmetric and its polar rotation is I before Q), and the elastic displacement is Q d_i; a
//    rigid motion alone gives 0. Values to round-off (1e-14 m on a plate of 2 m).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <string>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/shell.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/model/model.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "test_support.hpp"

using namespace alphaflex;

namespace {

std::vector<double> read_set(hid_t file, const std::string& path) {
  if (H5Lexists(file, path.c_str(), H5P_DEFAULT) <= 0) return {};
  const hid_t set = H5Dopen2(file, path.c_str(), H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  std::vector<double> v(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  if (!v.empty()) H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(set);
  return v;
}

Node frame(const std::string& name, const Eigen::Vector3d& x) {
  Node n;
  n.name = name;
  n.kind = NodeKind::Frame3D;
  n.q0.resize(7);
  store_pose(x, Eigen::Matrix3d::Identity(), n.q0.data());
  n.v0 = Eigen::VectorXd::Zero(6);
  return n;
}

}  // namespace

TEST(ResultsLayout, BodiesGridHoldsBodiesAndElasticDisplacementRemovesTheRigidMotion) {
  Model model;
  model.name = "layout";
  model.add_node(frame("hub", Eigen::Vector3d(-3, 0, 0)));
  std::vector<Eigen::Vector3d> X;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) X.emplace_back(i, j, 0);
  for (size_t k = 0; k < X.size(); ++k) model.add_node(frame("p" + std::to_string(k), X[k]));
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
  const std::vector<double> body = read_set(f, "/step_000001/body_position");
  ASSERT_EQ(body.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(body[static_cast<size_t>(k)], hub_at[k]);
  EXPECT_EQ(read_set(f, "/step_000001/body_displacement").size(), 3u);

  const std::vector<double> e_rigid = read_set(f, "/step_000000/node_elastic_displacement");
  const std::vector<double> e_bent = read_set(f, "/step_000001/node_elastic_displacement");
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
  const std::vector<double> disp = read_set(f, "/step_000001/node_displacement");
  EXPECT_GT(std::fabs(disp[3 * 5 + 2]), 1.0);
  H5Fclose(f);
}
