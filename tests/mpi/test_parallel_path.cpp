// The parallel path (partition/subdomain.hpp, assembly/saddle_point_system.hpp,
// io/results_writer.hpp) on the ranks this binary runs with (ctest: 1, 2 and 3), against the same
// model on one rank (PETSC_COMM_SELF) in the same process:
//  - the subdomains partition the nodes, elements, joints and sensors (each has exactly one owner)
//    and hold every node their elements, joints and sensors need;
//  - the distributed residual and the distributed matrix (its action on a vector) equal the serial
//    ones to round-off, and the preallocation is exact although ghost rows come from other ranks;
//  - after time steps every ghost copy equals its owner's value bit for bit (the owner's solution
//    is scattered, and both apply the same updates to it);
//  - the parallel HDF5 writer puts every rank's rows where the one-rank writer puts them: the same
//    file, bit for bit (tests/scenes/compare_ranks.py compares whole runs on 1, 2 and 3 ranks).
#include <gtest/gtest.h>
#include <hdf5.h>
#include <petscmat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <random>

#include "alphaflex/app/simulation.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/integrators/generalized_alpha.hpp"
#include "alphaflex/io/results_writer.hpp"
#include "alphaflex/io/scene.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

int world_rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

int world_size() {
  int s = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

/// The scenes the checks run on: planar bodies and joints (Andrews), beams with joints between
/// coincident nodes (a small gridshell), beams and shells sharing nodes (stiffened plate).
struct Case {
  const char* scene;
  std::vector<std::string> overrides;
};
const std::vector<Case> kCases = {
    {"andrews", {}},
    {"gridshell", {"mesh.parameters.n=4"}},
    {"stiffened_plate", {}},
};

Scene read(const Case& c) { return read_scene(source_path(std::string("inputs/") + c.scene + ".yaml"), c.overrides, PETSC_COMM_WORLD); }

/// A state near the initial one, the same on every rank (same seed), in model order.
MechanicalState generic_state(const Model& m, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MechanicalState s = m.initial_state();
  s.t = 0.2;
  Eigen::VectorXd dx(m.num_dofs());
  for (Eigen::Index i = 0; i < dx.size(); ++i) dx[i] = 0.01 * u(gen);
  m.retract(s.q, dx);
  for (Eigen::Index i = 0; i < s.v.size(); ++i) {
    s.v[i] = u(gen);
    s.qdd[i] = 10.0 * u(gen);
  }
  for (Eigen::Index i = 0; i < s.lambda.size(); ++i) s.lambda[i] = u(gen);
  return s;
}

TEST(Subdomain, PartitionsTheModelAndHoldsWhatItsPartsNeed) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.scene);
    Scene sc = read(c);
    const Model& g = *sc.model;
    const Subdomain sub(g, PETSC_COMM_WORLD);
    const Model& m = sub.model();
    // Every node, element, joint and sensor has exactly one owner.
    std::vector<double> owners(g.nodes().size() + g.elements().size() + g.constraints().size() + g.sensors().size(), 0.0);
    for (int i = 0; i < sub.num_owned_nodes(); ++i) owners[static_cast<size_t>(sub.global_node(i))] += 1.0;
    size_t off = g.nodes().size();
    for (size_t e = 0; e < m.elements().size(); ++e) owners[off + static_cast<size_t>(sub.global_element(static_cast<int>(e)))] += 1.0;
    off += g.elements().size();
    for (size_t j = 0; j < m.constraints().size(); ++j) owners[off + static_cast<size_t>(sub.global_constraint(static_cast<int>(j)))] += 1.0;
    off += g.constraints().size();
    for (size_t k = 0; k < m.sensors().size(); ++k) owners[off + static_cast<size_t>(sub.global_sensor(static_cast<int>(k)))] += 1.0;
    sub.sum(owners);
    for (double o : owners) EXPECT_EQ(o, 1.0);
    // Local parts refer only to local nodes, which are copies of the global ones.
    for (const auto& e : m.elements())
      for (int n : e->nodes()) EXPECT_TRUE(n >= 0 && n < static_cast<int>(m.nodes().size()));
    for (const auto& j : m.constraints())
      for (int n : j->nodes()) EXPECT_TRUE(n >= 0 && n < static_cast<int>(m.nodes().size()));
    for (size_t i = 0; i < m.nodes().size(); ++i) EXPECT_EQ(m.nodes()[i].name, g.node(sub.global_node(static_cast<int>(i))).name);
    // Ghosts are nodes another rank owns.
    for (int i = sub.num_owned_nodes(); i < static_cast<int>(m.nodes().size()); ++i)
      EXPECT_NE(sub.dof_map().node_owner(sub.global_node(i)), sub.rank());
    // restrict then gather gives back the state.
    const MechanicalState s = generic_state(g, 3);
    const MechanicalState back = sub.gather(sub.restrict(s));
    EXPECT_EQ(back.q, s.q);
    EXPECT_EQ(back.v, s.v);
    EXPECT_EQ(back.qdd, s.qdd);
    EXPECT_EQ(back.lambda, s.lambda);
  }
}

TEST(DistributedAssembly, ResidualAndMatrixEqualTheSerialOnesAndThePreallocationIsExact) {
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.scene);
    Scene sc = read(c);
    const Model& g = *sc.model;
    const Subdomain sub(g, PETSC_COMM_WORLD), serial(g, PETSC_COMM_SELF);
    SaddlePointSystem dist(sub), one(serial);
    const MechanicalState s = generic_state(g, 11);
    const AlphaParameters p = AlphaParameters::from_rho_inf(0.7);
    const double h = 0.02;
    const AssemblyCoefficients co = scaled_step_coefficients(p, h);
    // A Lie-group increment too (T(x) on the position columns), the same in both numberings.
    const MechanicalState xs = generic_state(g, 5);
    const Eigen::VectorXd x = 0.1 * xs.v;
    const Eigen::VectorXd x_local = sub.restrict(xs).v * 0.1;
    AssemblyCoefficients cd = co, cs = co;
    if (g.has_lie_group_nodes()) {
      cs.increment = &x;
      cd.increment = &x_local;
    }
    ASSERT_EQ(dist.assemble(sub.restrict(s), cd, ConstraintRows::Dynamic, true), 0);
    ASSERT_EQ(one.assemble(s, cs, ConstraintRows::Dynamic, true), 0);

    MatInfo di, si;
    ASSERT_EQ(MatGetInfo(dist.matrix(), MAT_GLOBAL_SUM, &di), 0);
    ASSERT_EQ(MatGetInfo(one.matrix(), MAT_GLOBAL_SUM, &si), 0);
    EXPECT_EQ(di.mallocs, 0.0) << "preallocation was not exact";
    EXPECT_EQ(di.nz_allocated, di.nz_used) << "preallocated entries left unused";
    EXPECT_EQ(di.nz_used, si.nz_used) << "the distributed pattern differs from the serial one";

    // Residuals: the owned entries of each rank against the serial vector at their model places.
    ModelVector rd, rs;
    ASSERT_EQ(dist.to_model(dist.residual(), rd), 0);
    ASSERT_EQ(one.to_model(one.residual(), rs), 0);
    const Eigen::VectorXd rd_all = sub.gather_dofs(rd.dofs), ld_all = sub.gather_multipliers(rd.multipliers);
    const double scale = std::max(rs.dofs.cwiseAbs().maxCoeff(), 1e-300), lscale = rs.multipliers.size() ? std::max(rs.multipliers.cwiseAbs().maxCoeff(), 1e-300) : 1.0;
    EXPECT_LE((rd_all - rs.dofs).cwiseAbs().maxCoeff(), 1e-13 * scale);
    if (rs.multipliers.size()) EXPECT_LE((ld_all - rs.multipliers).cwiseAbs().maxCoeff(), 1e-13 * lscale);
    // Ghost entries of the residual are the assembled (owner's) values too.
    for (int i = 0; i < static_cast<int>(sub.model().nodes().size()); ++i) {
      const Node& ln = sub.model().node(i);
      const Node& gn = g.node(sub.global_node(i));
      for (int k = 0; k < ln.ndof; ++k) EXPECT_NEAR(rd.dofs[ln.first_dof + k], rs.dofs[gn.first_dof + k], 1e-13 * scale);
    }

    // The matrices' action on the same vector y (model order on one rank, PETSc order in parallel).
    std::mt19937 gen(19);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Eigen::VectorXd y(g.num_dofs() + g.num_multipliers());
    for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = u(gen);
    Vec yd, zd, ys, zs;
    ASSERT_EQ(MatCreateVecs(dist.matrix(), &yd, &zd), 0);
    ASSERT_EQ(MatCreateVecs(one.matrix(), &ys, &zs), 0);
    // Owned node coordinates and multipliers of this rank, by their PETSc index.
    int li = 0;
    for (int n = 0; n < sub.num_owned_nodes(); ++n) {
      const Node& gn = g.node(sub.global_node(n));
      for (int k = 0; k < gn.ndof; ++k, ++li)
        ASSERT_EQ(VecSetValue(yd, sub.dof_indices()[static_cast<size_t>(li)], y[gn.first_dof + k], INSERT_VALUES), 0);
    }
    for (size_t jc = 0; jc < sub.model().constraints().size(); ++jc) {
      const int gj = sub.global_constraint(static_cast<int>(jc));
      const int first_l = sub.model().first_multiplier(static_cast<int>(jc)), first_g = g.first_multiplier(gj);
      for (int k = 0; k < g.constraints()[static_cast<size_t>(gj)]->size(); ++k)
        ASSERT_EQ(VecSetValue(yd, sub.multiplier_indices()[static_cast<size_t>(first_l + k)], y[g.num_dofs() + first_g + k],
                              INSERT_VALUES), 0);
    }
    ASSERT_EQ(VecAssemblyBegin(yd), 0);
    ASSERT_EQ(VecAssemblyEnd(yd), 0);
    PetscScalar* a = nullptr;
    ASSERT_EQ(VecGetArray(ys, &a), 0);
    for (Eigen::Index i = 0; i < y.size(); ++i) a[i] = y[i];
    ASSERT_EQ(VecRestoreArray(ys, &a), 0);
    ASSERT_EQ(MatMult(dist.matrix(), yd, zd), 0);
    ASSERT_EQ(MatMult(one.matrix(), ys, zs), 0);
    ModelVector zdm, zsm;
    ASSERT_EQ(dist.to_model(zd, zdm), 0);
    ASSERT_EQ(one.to_model(zs, zsm), 0);
    const Eigen::VectorXd zd_all = sub.gather_dofs(zdm.dofs), zl_all = sub.gather_multipliers(zdm.multipliers);
    const double zscale = zsm.dofs.cwiseAbs().maxCoeff();
    EXPECT_LE((zd_all - zsm.dofs).cwiseAbs().maxCoeff(), 1e-12 * zscale);
    if (zsm.multipliers.size())
      EXPECT_LE((zl_all - zsm.multipliers).cwiseAbs().maxCoeff(), 1e-12 * zsm.multipliers.cwiseAbs().maxCoeff());
    VecDestroy(&yd);
    VecDestroy(&zd);
    VecDestroy(&ys);
    VecDestroy(&zs);
  }
}

TEST(Ghosts, AfterTimeStepsEveryGhostCopyEqualsItsOwnerBitForBit) {
  for (const Case& c : {kCases[0], kCases[1]}) {
    SCOPED_TRACE(c.scene);
    Scene sc = read(c);
    const Subdomain sub(*sc.model, PETSC_COMM_WORLD);
    SaddlePointSystem sys(sub);
    LinearSolver solver(PETSC_COMM_WORLD);
    GeneralizedAlpha ga(sys, solver, sc.settings.parameters, sc.settings.integrator);
    MechanicalState s = sub.model().initial_state();
    ga.initialize(s);
    for (int n = 0; n < 5; ++n) ga.step(s, sc.settings.h);
    const MechanicalState g = sub.gather(s);
    const Eigen::VectorXd a = sub.gather_dofs(ga.auxiliary());
    const Model& m = sub.model();
    int compared = 0;
    for (int i = sub.num_owned_nodes(); i < static_cast<int>(m.nodes().size()); ++i) {
      const Node& ln = m.node(i);
      const Node& gn = sc.model->node(sub.global_node(i));
      for (int k = 0; k < ln.nconf; ++k) EXPECT_EQ(s.q[ln.first_conf + k], g.q[gn.first_conf + k]);
      for (int k = 0; k < ln.ndof; ++k) {
        EXPECT_EQ(s.v[ln.first_dof + k], g.v[gn.first_dof + k]);
        EXPECT_EQ(s.qdd[ln.first_dof + k], g.qdd[gn.first_dof + k]);
        EXPECT_EQ(ga.auxiliary()[ln.first_dof + k], a[gn.first_dof + k]);
      }
      ++compared;
    }
    std::vector<double> t{static_cast<double>(compared)};
    sub.sum(t);
    if (world_size() > 1) EXPECT_GT(t[0], 0.0) << "no ghost node on any rank: the test checked nothing";
  }
}

/// Every dataset of an HDF5 file (path → values as doubles, shape), read serially.
struct Dataset {
  std::vector<double> values;
  std::vector<hsize_t> dims;
  bool integer = false;
};

herr_t collect(hid_t loc, const char* name, const H5O_info_t* info, void* out) {
  if (info->type != H5O_TYPE_DATASET) return 0;
  auto& all = *static_cast<std::map<std::string, Dataset>*>(out);
  const hid_t set = H5Dopen2(loc, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(set);
  Dataset d;
  d.dims.resize(static_cast<size_t>(H5Sget_simple_extent_ndims(space)));
  H5Sget_simple_extent_dims(space, d.dims.data(), nullptr);
  d.values.resize(static_cast<size_t>(H5Sget_simple_extent_npoints(space)));
  const hid_t type = H5Dget_type(set);
  d.integer = H5Tget_class(type) == H5T_INTEGER;
  if (!d.values.empty()) H5Dread(set, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.values.data());
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(set);
  all[name] = d;
  return 0;
}

std::map<std::string, Dataset> read_all(const std::string& path) {
  std::map<std::string, Dataset> all;
  const hid_t f = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_GE(f, 0) << path;
  if (f < 0) return all;
  H5Ovisit2(f, H5_INDEX_NAME, H5_ITER_INC, collect, &all, H5O_INFO_BASIC);
  H5Fclose(f);
  return all;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(ParallelHdf5, EveryRankWritesItsRowsWhereTheOneRankFileHasThem) {
  // The same two states written by the parallel writer (each rank its rows, collective MPI-IO)
  // and by a one-rank writer on rank 0: every dataset, the integers and the doubles, must be equal
  // bit for bit (each value is computed from the same local data on both sides), and so must the
  // XDMF index. Row placement errors would show as O(1) differences.
  // A fresh directory made by rank 0 (test_support.hpp), its name sent to the others; removed
  // after the last barrier below.
  std::optional<TestOutputDir> dir;
  if (world_rank() == 0) dir.emplace("hdf5_np" + std::to_string(world_size()));
  int len = dir ? static_cast<int>(dir->path().size()) : 0;
  MPI_Bcast(&len, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  std::string base(static_cast<size_t>(len), '\0');
  if (dir) base = dir->path();
  MPI_Bcast(base.data(), len, MPI_CHAR, 0, PETSC_COMM_WORLD);
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.scene);
    Scene sc = read(c);
    const Model& g = *sc.model;
    const Subdomain sub(g, PETSC_COMM_WORLD);
    const MechanicalState s0 = generic_state(g, 23), s1 = generic_state(g, 29);
    {
      ResultsWriter w(sub, base + "/parallel", sc.name, true);
      for (const MechanicalState* s : {&s0, &s1}) w.write_fields(sub.restrict(*s));
      w.finish();
    }
    if (world_rank() == 0) {
      const Subdomain one(g, PETSC_COMM_SELF);
      {
        ResultsWriter w(one, base + "/serial", sc.name, true);
        for (const MechanicalState* s : {&s0, &s1}) w.write_fields(*s);
        w.finish();
      }
      // The data are in the part files (NAME.h5 links to them); each writer made one part here.
      const std::string part = "/" + sc.name + ".h5.parts/part_000000.h5";
      const auto par = read_all(base + "/parallel" + part), ser = read_all(base + "/serial" + part);
      ASSERT_FALSE(ser.empty());
      EXPECT_EQ(par.size(), ser.size());
      for (const auto& [name, d] : ser) {
        SCOPED_TRACE(name);
        ASSERT_EQ(par.count(name), 1u);
        EXPECT_EQ(par.at(name).dims, d.dims);
        if (name.find("elastic_displacement") == std::string::npos) {
          EXPECT_EQ(par.at(name).values, d.values);
        } else {
          // The one field that is not local: each block's best-fit rigid motion (Kabsch/Horn) sums
          // over all the block's nodes, by an all-reduce whose order of addition depends on the
          // partition. Equal to round-off of the sums: 1e-12 of the field's largest value.
          const std::vector<double>& a = par.at(name).values;
          ASSERT_EQ(a.size(), d.values.size());
          double scale = 0.0;
          for (double x : d.values) scale = std::max(scale, std::fabs(x));
          for (size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], d.values[i], 1e-12 * scale) << "row value " << i;
        }
      }
      EXPECT_EQ(file_text(base + "/parallel/" + sc.name + ".xdmf"), file_text(base + "/serial/" + sc.name + ".xdmf"));
    }
    MPI_Barrier(PETSC_COMM_WORLD);
  }
}

}  // namespace
}  // namespace alphaflex::testing
