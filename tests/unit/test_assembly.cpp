// The assembled iteration matrix is the exact derivative of the assembled residual along the
// Newton update of Algorithm 1 (q += Δq, q̇ += γ'Δq, q̈ += β'Δq, λ += μ Δλ̃), with Bottasso scaling
// on, checked column by column by central differences; the preallocation is exact (no mallocs).
#include <gtest/gtest.h>
#include <petscmat.h>

#include <cfloat>
#include <cstdio>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/elements/spatial_elements.hpp"
#include "alphaflex/partition/subdomain.hpp"
#include "test_support.hpp"

namespace alphaflex::testing {
namespace {

Eigen::VectorXd dense_residual(SaddlePointSystem& sys, const MechanicalState& s, const AssemblyCoefficients& c) {
  EXPECT_EQ(sys.assemble(s, c, ConstraintRows::Dynamic, false), 0);
  ModelVector r;
  EXPECT_EQ(sys.to_model(sys.residual(), r), 0);
  Eigen::VectorXd out(r.dofs.size() + r.multipliers.size());
  out << r.dofs, r.multipliers;
  return out;
}

class AssembledTangent : public ::testing::TestWithParam<const char*> {};

TEST_P(AssembledTangent, IterationMatrixIsDerivativeOfResidualAlongNewtonUpdate) {
  Scene sc = read_scene(source_path(std::string("inputs/") + GetParam() + ".yaml"));
  const Model& m = *sc.model;
  Subdomain sub(m, PETSC_COMM_WORLD);
  SaddlePointSystem sys(sub);

  // A generic state near the initial one (random velocities, accelerations and multipliers).
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MechanicalState s = m.initial_state();
  s.t = 0.3;
  for (Eigen::Index i = 0; i < s.q.size(); ++i) {
    s.q[i] += 0.01 * u(gen);
    s.v[i] = u(gen);
    s.qdd[i] = 10.0 * u(gen);
  }
  for (Eigen::Index i = 0; i < s.lambda.size(); ++i) s.lambda[i] = 5.0 * u(gen);

  const AlphaParameters p = AlphaParameters::from_rho_inf(0.7);
  // A large step, so that the stiffness terms (×βh² after scaling) weigh as much as the mass terms.
  const double h = 0.05;
  const AssemblyCoefficients c = scaled_step_coefficients(p, h);

  ASSERT_EQ(sys.assemble(s, c, ConstraintRows::Dynamic, true), 0);
  MatInfo info;
  ASSERT_EQ(MatGetInfo(sys.matrix(), MAT_GLOBAL_SUM, &info), 0);
  EXPECT_EQ(info.mallocs, 0.0) << "preallocation was not exact";
  EXPECT_EQ(info.nz_allocated, info.nz_used) << "preallocated entries left unused";

  const int nd = m.num_dofs(), nm = m.num_multipliers(), n = nd + nm;
  Eigen::MatrixXd S(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const PetscInt gi = i < nd ? sub.dof_map().dof(i) : sub.dof_map().multiplier(i - nd);
      const PetscInt gj = j < nd ? sub.dof_map().dof(j) : sub.dof_map().multiplier(j - nd);
      PetscScalar v = 0.0;
      ASSERT_EQ(MatGetValues(sys.matrix(), 1, &gi, 1, &gj, &v), 0);
      S(i, j) = v;
    }

  // Central differences (h = 1e-7) along the Newton update: δq = d, δq̇ = damping d, δq̈ = mass d,
  // δλ = multiplier_scale d.
  const Eigen::MatrixXd fd = central_differences(
      [&](const Eigen::VectorXd& d) {
        MechanicalState t = s;
        t.q += d.head(nd);
        t.v += c.damping * d.head(nd);
        t.qdd += c.mass * d.head(nd);
        t.lambda += c.multiplier_scale * d.tail(nm);
        return dense_residual(sys, t, c);
      },
      Eigen::VectorXd::Zero(n), fixed_fd_step(1e-7));
  const double err = (S - fd).cwiseAbs().maxCoeff() / S.cwiseAbs().maxCoeff();
  RecordProperty("relative_error", std::to_string(err));
  EXPECT_LT(err, 1e-6) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(PaperScenes, AssembledTangent, ::testing::Values("slider_crank", "andrews"));

// ---------------------------------------------------------------- mass action (adaptive steps §3b)
// The filtered error estimate applies W = S_t⁻¹ β'M (docs/theory/adaptive_steps.md, eq. F) through
// SaddlePointSystem::assemble_mass_action, which asks each element for M(q) w (Element::mass_action)
// instead of the difference of two residuals. Checked: (1) per element, M w = (∂r/∂q̈) w with the
// element's own tangent M (itself checked against central differences in each element's tests);
// (2) assembled, r = s_r c_m M w equals r(q̈ + c_m w) − r(q̈), the difference the filter took before,
// to its round-off; multiplier rows zero.

/// A state away from the initial one: q moved on its group (Model::retract), random q̇, q̈, λ.
MechanicalState generic_state(const Model& m, std::mt19937& gen) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  MechanicalState s = m.initial_state();
  s.t = 0.3;
  Eigen::VectorXd dx(m.num_dofs());
  for (Eigen::Index i = 0; i < dx.size(); ++i) dx[i] = 0.05 * u(gen);
  m.retract(s.q, dx);
  for (Eigen::Index i = 0; i < s.v.size(); ++i) {
    s.v[i] = u(gen);
    s.qdd[i] = 10.0 * u(gen);
  }
  for (Eigen::Index i = 0; i < s.lambda.size(); ++i) s.lambda[i] = 5.0 * u(gen);
  return s;
}

/// Every element of `m`: M w from mass_action against the tangent's M w. Returns the types that
/// offer mass_action (and were checked) and, in `fallback`, those that do not.
std::set<std::string> check_element_mass_actions(const Model& m, const MechanicalState& s, std::mt19937& gen,
                                                 std::set<std::string>& fallback) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::set<std::string> checked;
  for (const auto& e : m.elements()) {
    std::vector<int> confs, dofs;
    for (int n : e->nodes()) {
      const Node& nd = m.node(n);
      for (int k = 0; k < nd.nconf; ++k) confs.push_back(nd.first_conf + k);
      for (int k = 0; k < nd.ndof; ++k) dofs.push_back(nd.first_dof + k);
    }
    LocalState ls;
    ls.t = s.t;
    ls.q.resize(static_cast<Eigen::Index>(confs.size()));
    ls.v.resize(static_cast<Eigen::Index>(dofs.size()));
    ls.qdd.resize(ls.v.size());
    for (size_t i = 0; i < confs.size(); ++i) ls.q[static_cast<Eigen::Index>(i)] = s.q[confs[i]];
    for (size_t i = 0; i < dofs.size(); ++i) {
      ls.v[static_cast<Eigen::Index>(i)] = s.v[dofs[i]];
      ls.qdd[static_cast<Eigen::Index>(i)] = s.qdd[dofs[i]];
    }
    Eigen::VectorXd w(ls.v.size()), Mw;
    for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = u(gen);
    if (!e->mass_action(ls, w, Mw)) {
      fallback.insert(e->type());
      continue;
    }
    const LocalResidual t = element_tangents(*e, ls);
    const Eigen::VectorXd expected = t.M * w;
    EXPECT_EQ(Mw.size(), expected.size()) << e->type() << " " << e->name();
    if (Mw.size() != expected.size()) continue;
    const double scale = std::max(t.M.cwiseAbs().maxCoeff() * w.cwiseAbs().maxCoeff(), 1e-300);
    EXPECT_LE((Mw - expected).cwiseAbs().maxCoeff(), 1e-13 * scale) << e->type() << " " << e->name();
    checked.insert(e->type());
  }
  return checked;
}

class MassAction : public ::testing::TestWithParam<const char*> {};

TEST_P(MassAction, IsTheTangentMassTimesWAndTheResidualsDifferenceAlongQdd) {
  // "scene" or "scene|override".
  const std::string param = GetParam(), name = param.substr(0, param.find('|'));
  std::vector<std::string> overrides;
  if (param.find('|') != std::string::npos) overrides.push_back(param.substr(param.find('|') + 1));
  Scene sc = read_scene(source_path("inputs/" + name + ".yaml"), overrides);
  const Model& m = *sc.model;
  Subdomain sub(m, PETSC_COMM_WORLD);
  SaddlePointSystem sys(sub);
  std::mt19937 gen(11);
  const MechanicalState s = generic_state(m, gen);

  std::set<std::string> fallback;
  const std::set<std::string> checked = check_element_mass_actions(m, s, gen, fallback);
  std::string types;
  for (const auto& t : checked) types += t + " ";
  for (const auto& t : fallback) types += "(" + t + ": difference of residuals) ";
  RecordProperty("element_types", types);
  std::printf("%s: %s\n", param.c_str(), types.c_str());

  // The coefficients of a step (h = 1e-3, ρ∞ = 0.7) and a random w.
  const AlphaParameters p = AlphaParameters::from_rho_inf(0.7);
  const double h = 1e-3;
  const AssemblyCoefficients c = scaled_step_coefficients(p, h);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd w(s.qdd.size());
  for (Eigen::Index i = 0; i < w.size(); ++i) w[i] = 10.0 * u(gen);

  ASSERT_EQ(sys.assemble_mass_action(s, c, w), 0);
  ModelVector r;
  ASSERT_EQ(sys.to_model(sys.residual(), r), 0);
  const int nd = m.num_dofs();
  Eigen::VectorXd action(r.dofs.size() + r.multipliers.size());
  action << r.dofs, r.multipliers;

  MechanicalState shifted = s;
  shifted.qdd += c.mass * w;
  const Eigen::VectorXd r1 = dense_residual(sys, shifted, c), r0 = dense_residual(sys, s, c);
  const Eigen::VectorXd difference = r1 - r0;
  // Round-off of the difference: ε times the residuals it subtracts.
  const double floor = 64.0 * DBL_EPSILON * std::max(r1.cwiseAbs().maxCoeff(), r0.cwiseAbs().maxCoeff());
  const double err = (action - difference).cwiseAbs().maxCoeff();
  RecordProperty("error_over_roundoff", std::to_string(err / floor));
  EXPECT_LE(err, floor) << "largest |M w| " << action.head(nd).cwiseAbs().maxCoeff();
  EXPECT_GT(action.head(nd).cwiseAbs().maxCoeff(), 1e3 * floor) << "a vacuous comparison";
  if (m.num_multipliers() > 0) EXPECT_EQ(action.tail(m.num_multipliers()).cwiseAbs().maxCoeff(), 0.0) << "multiplier rows";
}

// Scenes that hold between them every element type with an inertia of its own (rigid bodies 2D
// and 3D, particles, planar and spatial beams, shells) and the force elements (springs, bushings,
// loads, pressure, joint forces, stops), and one that takes the difference of residuals (a
// motor whose law reads sensors).
INSTANTIATE_TEST_SUITE_P(Scenes, MassAction,
                         ::testing::Values("andrews", "slider_crank", "slider_crank_flexible", "cart_pendulum",
                                           "heavy_top", "beam_hammer_damped", "plate_pressure", "stiffened_plate",
                                           "energy_balance", "robot_arm", "pan_tilt_head",
                                           "slider_crank_flexible_3d", "tumbling_plate|mesh.parameters.quads=0"));

TEST(RigidBodyMassAction, AboutAPointOffItsCentreIsTheTangentMassTimesW) {
  // RigidBody3D with an offset (a body welded into a reduced body) is built by no scene of its own.
  Model m;
  Node n;
  n.name = "P";
  n.kind = NodeKind::Frame3D;
  n.ndof = Node::dofs_of(n.kind);
  n.nconf = 7;
  n.q0 = (Eigen::VectorXd(7) << 0.1, -0.2, 0.3, 1.0, 0.0, 0.0, 0.0).finished();  // (x, q_w, q_x, q_y, q_z)
  n.v0 = Eigen::VectorXd::Zero(6);
  const int node = m.add_node(n);
  Eigen::Matrix3d J;
  J << 0.3, 0.01, -0.02, 0.01, 0.5, 0.03, -0.02, 0.03, 0.7;
  m.add_element(std::make_unique<RigidBody3D>("payload", node, 2.5, J, Eigen::Vector3d(0, 0, -9.81),
                                              Eigen::Vector3d(0.05, -0.1, 0.2)));
  std::mt19937 gen(5);
  const MechanicalState s = generic_state(m, gen);
  std::set<std::string> fallback;
  EXPECT_EQ(check_element_mass_actions(m, s, gen, fallback).count("rigid_body"), 1u);
  EXPECT_TRUE(fallback.empty());
}

}  // namespace
}  // namespace alphaflex::testing
