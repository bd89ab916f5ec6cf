// Spatial joints, rigid bodies and loads on R³×SO(3) (joints/spatial_joints.hpp,
// elements/spatial_elements.hpp): every derivative against central differences ON THE GROUP —
// configurations perturbed through the Frame3D retraction q ∘ exp(±ε e_j) = (x ± ε e_x,
// R exp(±ε e_θ^)) — the acceleration term against second differences along q ∘ exp(τ v (+ τ²a/2)),
// the joints' allowed motions and ranks in assembled configurations, the reactions' sign
// conventions in static equilibria, and the Newton–Euler residual against Euler's equations.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/core/time_function.hpp"
#include "alphaflex/elements/spatial_elements.hpp"
#include "alphaflex/joints/spatial_joints.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/node.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

constexpr double kSpatialRelTol = 1e-6;  // FD vs analytic, relative to the quantity's scale
constexpr double kFdStep = 1e-6;  // central differences of first derivatives
constexpr double kSpatialEps = DBL_EPSILON;
constexpr int kSpatialSamples = 6;
constexpr double kT = 0.37;  // time of the evaluations

// ------------------------------------------------------------------ configurations on the group
// (random samples, random poses, stored poses: test_support.hpp)
using testing::random_pose;
using testing::random_vector;
using testing::stored;
using testing::uniform;

Eigen::Matrix3d rot(const Eigen::Vector3d& w) { return exp_so3<double>(w); }
Eigen::Matrix3d rot(int axis, double angle) { return exp_so3<double>(angle * Eigen::Vector3d::Unit(axis)); }

Pose<double> pose_at(const Eigen::VectorXd& q, int k) { return pose_of(q.data() + 7 * k); }

/// q ∘ exp(d) node by node with the Frame3D retraction of the model.
Eigen::VectorXd retracted(const Eigen::VectorXd& q, const Eigen::VectorXd& d) {
  Eigen::VectorXd out(q.size());
  for (int k = 0; k < q.size() / 7; ++k)
    retract(NodeKind::Frame3D, q.data() + 7 * k, d.data() + 6 * k, out.data() + 7 * k);
  return out;
}

/// The increment d with q1 = q0 ∘ exp(d): (x1 − x0, log(R0ᵀ R1)) per node.
Eigen::VectorXd difference(const Eigen::VectorXd& q0, const Eigen::VectorXd& q1) {
  Eigen::VectorXd d(q0.size() / 7 * 6);
  for (int k = 0; k < q0.size() / 7; ++k) {
    const Pose<double> a = pose_at(q0, k), b = pose_at(q1, k);
    d.segment<3>(6 * k) = b.x - a.x;
    d.segment<3>(6 * k + 3) = log_so3<double>(Eigen::Matrix3d(a.R.transpose() * b.R));
  }
  return d;
}

Eigen::VectorXd unit(int n, int j) { return Eigen::VectorXd::Unit(n, j); }

/// Central differences on the group, column j: [f(q ∘ exp(ε e_j)) − f(q ∘ exp(−ε e_j))] / 2ε,
/// ε = kFdStep (test_support.hpp).
Eigen::MatrixXd fd_on_group(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& q) {
  return alphaflex::testing::central_differences_on_frames(f, q, alphaflex::testing::fixed_fd_step(kFdStep));
}

double discrepancy(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B, double scale) {
  return (A - B).norm() / std::max(scale, DBL_MIN);
}

const Eigen::IOFormat kSpatialFmt(6, 0, " ", "\n", "  [", "]");

void spatial_report(const std::string& what, const std::string& label, double worst) {
  std::printf("[ FD       ] worst rel. error %.1e  %s, %s\n", worst, what.c_str(), label.c_str());
}

// ------------------------------------------------------------------ joint cases
// Markers with non-trivial offsets and rotations (testing::marker).
using testing::marker;
const Eigen::Vector3d kPosA(0.3, -0.2, 0.5), kRotA(0.4, -0.7, 0.2);
const Eigen::Vector3d kPosB(-0.4, 0.25, 0.1), kRotB(-0.3, 0.5, 0.9);
const Eigen::Vector3d kGround(1.0, -0.5, 0.8), kRotGround(0.2, 0.3, -0.6);

const TimeFunctionPtr kAngle = make_sine(0.7, 0.3, 0.4, 0.2);           // rad
const TimeFunctionPtr kDisplacement = make_sine(0.35, 0.5, -0.2, 0.1);  // m

struct SpatialJointCase {
  std::string label;
  std::shared_ptr<const SpatialJoint> joint;
  int nodes = 1;
  bool angle = false, displacement = false;
};

std::shared_ptr<const SpatialJoint> make_joint(const SpatialJointKind& kind, int nodes, SpatialMarker a,
                                               SpatialMarker b, bool angle, bool displacement) {
  std::vector<int> ids = nodes == 2 ? std::vector<int>{0, 1} : std::vector<int>{0};
  return std::make_shared<SpatialJoint>("j", ids, kind, a, b, angle ? kAngle : nullptr,
                                        displacement ? kDisplacement : nullptr);
}

const SpatialJointKind& kind(const std::string& name) {
  const SpatialJointKind* k = find_spatial_joint_kind(name);
  if (!k) throw std::logic_error("no spatial joint type '" + name + "'");
  return *k;
}

std::shared_ptr<const SpatialJoint> make_joint(const std::string& type, int nodes, SpatialMarker a, SpatialMarker b,
                                               bool angle, bool displacement) {
  return make_joint(kind(type), nodes, a, b, angle, displacement);
}

/// Every joint type of the table (spatial_joint_kinds(): a new row is tested here without a line
/// more, once allowed_motion knows its motion) and every driver combination its row takes, between
/// two nodes, between a node and the ground, with the ground as marker A, and with the markers on
/// the nodes in the other order.
std::vector<SpatialJointCase> joint_cases() {
  struct Drivers {
    const SpatialJointKind* kind;
    bool angle, displacement;
  };
  std::vector<Drivers> variants;
  for (const SpatialJointKind& k : spatial_joint_kinds()) {
    variants.push_back({&k, false, false});
    if (k.angle_driver) variants.push_back({&k, true, false});
    if (k.displacement_driver) variants.push_back({&k, false, true});
    if (k.angle_driver && k.displacement_driver) variants.push_back({&k, true, true});
  }
  std::vector<SpatialJointCase> cases;
  for (const Drivers& v : variants) {
    std::string name = v.kind->name;
    if (v.angle) name += " + angle driver";
    if (v.displacement) name += " + displacement driver";
    const auto add = [&](const std::string& where, int nodes, SpatialMarker a, SpatialMarker b) {
      cases.push_back({name + ", " + where, make_joint(*v.kind, nodes, a, b, v.angle, v.displacement), nodes, v.angle,
                       v.displacement});
    };
    add("node-node", 2, marker(0, kPosA, kRotA), marker(1, kPosB, kRotB));
    add("node-ground", 1, marker(0, kPosA, kRotA), marker(-1, kGround, kRotGround));
    add("ground-node", 1, marker(-1, kGround, kRotGround), marker(0, kPosB, kRotB));
    add("node-node, A on the second node", 2, marker(1, kPosA, kRotA), marker(0, kPosB, kRotB));
  }
  return cases;
}

// ------------------------------------------------------------------ assembled configurations
/// A relative motion of marker B with respect to marker A, in A's frame: B = A ∘ (p, R).
struct Motion {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
};

/// Number of free parameters of the joint's relative motion (6 − equations).
int free_parameters(const SpatialJointCase& c) { return 6 - c.joint->size(); }

/// The relative motion the joint allows, from its free parameters p (size free_parameters), with
/// the driven angle and displacement at time t. The drivers prescribe the motion of marker A
/// relative to marker B (header: a1·(cos φ b2 − sin φ b1) = 0, (p_A − p_B)·b3 − u = 0), so B
/// relative to A is turned by −φ(t) about a3 and shifted by −u(t) along it.
Motion allowed_motion(const SpatialJointCase& c, const Eigen::VectorXd& p, double t) {
  Motion m;
  int k = 0;
  const auto next = [&]() { return p[k++]; };
  // By name: an independent statement of each joint type's motion (a new row of the table fails
  // here until its motion is written down).
  const std::string& type = c.joint->kind().name;
  if (type == "spherical") {
    m.R = rot(Eigen::Vector3d(next(), next(), next()));
  } else if (type == "universal") {
    const double alpha = next(), beta = next();
    m.R = rot(0, alpha) * rot(1, beta);  // about a1, then about the cross axis b2
  } else if (type == "revolute") {
    m.R = rot(2, c.angle ? -kAngle->value(t) : next());
  } else if (type == "cylindrical") {
    const double phi = c.angle ? -kAngle->value(t) : next();
    const double s = c.displacement ? -kDisplacement->value(t) : next();
    m.R = rot(2, phi);
    m.p = Eigen::Vector3d(0, 0, s);
  } else if (type == "prismatic") {
    m.p = Eigen::Vector3d(0, 0, c.displacement ? -kDisplacement->value(t) : next());
  } else if (type == "planar") {
    const double phi = next(), u = next(), v = next();
    m.R = rot(2, phi);
    m.p = Eigen::Vector3d(u, v, 0);
  } else if (type == "fixed") {
  } else if (type == "point_on_line") {  // any rotation, any slide along a3
    m.R = rot(Eigen::Vector3d(next(), next(), next()));
    m.p = Eigen::Vector3d(0, 0, next());
  } else if (type == "point_on_plane") {  // any rotation, any position in the plane ⊥ a3
    m.R = rot(Eigen::Vector3d(next(), next(), next()));
    m.p = Eigen::Vector3d(next(), next(), 0);
  } else {
    ADD_FAILURE() << "joint type '" << type << "': write its allowed motion in allowed_motion";
    while (k < p.size()) next();
  }
  EXPECT_EQ(k, p.size()) << c.label << ": free parameters of the allowed motion";
  return m;
}

/// Pose of a node on which marker m has the world pose P.
Pose<double> node_from_marker(const SpatialMarker& m, const Pose<double>& P) {
  const Eigen::Matrix3d R = P.R * m.rotation.transpose();
  return {P.x - R * m.position, R};
}

/// A configuration with B = A ∘ M: the node of marker A (if any) at `base`, the other node placed.
Eigen::VectorXd assembled(const SpatialJointCase& c, const Pose<double>& base, const Motion& M) {
  const SpatialMarker &a = c.joint->marker_a(), &b = c.joint->marker_b();
  std::vector<Pose<double>> nodes(c.nodes, base);
  if (a.slot >= 0 && b.slot >= 0) {
    nodes[a.slot] = base;
    const Pose<double> A = a.pose<double>(nodes.data());
    nodes[b.slot] = node_from_marker(b, {A.x + A.R * M.p, A.R * M.R});
  } else if (a.slot >= 0) {  // B on the ground: A = B ∘ M⁻¹
    const Pose<double> B = b.pose<double>(nodes.data());
    const Eigen::Matrix3d RA = B.R * M.R.transpose();
    nodes[a.slot] = node_from_marker(a, {B.x - RA * M.p, RA});
  } else {  // A on the ground
    const Pose<double> A = a.pose<double>(nodes.data());
    nodes[b.slot] = node_from_marker(b, {A.x + A.R * M.p, A.R * M.R});
  }
  return stored(nodes);
}

/// A random configuration that violates the joint somewhat: assembled, then moved by up to 0.2
/// in every coordinate of the group.
Eigen::VectorXd violated(std::mt19937& rng, const SpatialJointCase& c) {
  const Eigen::VectorXd p = random_vector(rng, free_parameters(c), -1.0, 1.0);
  const Eigen::VectorXd q = assembled(c, random_pose(rng), allowed_motion(c, p, kT));
  return retracted(q, random_vector(rng, 6 * c.nodes, -0.2, 0.2));
}

// ------------------------------------------------------------------ joint evaluations
Eigen::VectorXd spatial_phi_of(const Constraint& j, const Eigen::VectorXd& q, double t = kT) {
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  j.evaluate(q, t, phi, phi_q);
  return phi;
}

Eigen::MatrixXd spatial_phi_q_of(const Constraint& j, const Eigen::VectorXd& q, double t = kT) {
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  j.evaluate(q, t, phi, phi_q);
  return phi_q;
}

/// d²/dτ² Φ(q ∘ exp(τ v + τ² a / 2), t + τ) at τ = 0: second differences at τ = ±h, 0, with
/// Richardson extrapolation from h = 1e-2 and 5e-3 (truncation O(h⁴) ~ 1e-10, round-off
/// ~ ε/h² ~ 1e-11; a first-derivative step of 1e-6 would leave ε/h² ~ 1e-4).
Eigen::VectorXd fd_second_along(const Constraint& j, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& a, double t) {
  const auto at = [&](double tau) { return spatial_phi_of(j, retracted(q, tau * v + 0.5 * tau * tau * a), t + tau); };
  const auto second = [&](double h) { return ((at(h) - 2.0 * at(0.0) + at(-h)) / (h * h)).eval(); };
  const double h = 1e-2;
  return (4.0 * second(h / 2) - second(h)) / 3.0;
}

}  // namespace

// =================================================================== SpatialJoint: counts

TEST(SpatialJoint, EquationCountsAreThoseOfTheHeaderTablePlusOnePerDriver) {
  // 6 − the degrees of freedom each joint leaves (the motions of EachJointAllowsExactly… below).
  const std::vector<std::pair<std::string, int>> table = {
      {"spherical", 3}, {"universal", 4}, {"revolute", 5},      {"cylindrical", 4},   {"prismatic", 5},
      {"planar", 3},    {"fixed", 6},     {"point_on_line", 2}, {"point_on_plane", 1}};
  EXPECT_EQ(spatial_joint_kinds().size(), table.size()) << "a joint type without an expected count here";
  for (const auto& [type, m] : table) {
    EXPECT_EQ(kind(type).num_equations, m) << type;
    EXPECT_EQ(make_joint(type, 2, marker(0, kPosA, kRotA), marker(1, kPosB, kRotB), false, false)->size(), m);
  }
  const SpatialMarker a = marker(0, kPosA, kRotA), b = marker(-1, kGround, kRotGround);
  EXPECT_EQ(make_joint("revolute", 1, a, b, true, false)->size(), 6);
  EXPECT_EQ(make_joint("cylindrical", 1, a, b, true, false)->size(), 5);
  EXPECT_EQ(make_joint("cylindrical", 1, a, b, false, true)->size(), 5);
  EXPECT_EQ(make_joint("cylindrical", 1, a, b, true, true)->size(), 6);
  EXPECT_EQ(make_joint("prismatic", 1, a, b, false, true)->size(), 6);
  // Drivers only where the joint has that freedom.
  EXPECT_THROW(make_joint("prismatic", 1, a, b, true, false), std::invalid_argument);
  EXPECT_THROW(make_joint("revolute", 1, a, b, false, true), std::invalid_argument);
  EXPECT_THROW(make_joint("spherical", 1, a, b, true, false), std::invalid_argument);
  for (const SpatialJointCase& c : joint_cases()) {
    Eigen::VectorXd phi;
    Eigen::MatrixXd phi_q;
    c.joint->evaluate(assembled(c, Pose<double>{Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()}, Motion{}), kT,
                      phi, phi_q);
    EXPECT_EQ(phi.size(), c.joint->size()) << c.label;
    EXPECT_EQ(phi_q.rows(), c.joint->size()) << c.label;
    EXPECT_EQ(phi_q.cols(), 6 * c.nodes) << c.label;
  }
}

TEST(SpatialJoint, EquationNamesAreThoseOfTheTableThenTheDrivers) {
  EXPECT_EQ(kind("revolute").equation_names, (std::vector<std::string>{"x", "y", "z", "a3·b1", "a3·b2"}));
  EXPECT_EQ(kind("prismatic").equation_names,
            (std::vector<std::string>{"a1·d", "a2·d", "a3·b1", "a3·b2", "a1·b2"}));
  EXPECT_EQ(find_spatial_joint_kind("hinge"), nullptr);
  const SpatialMarker a = marker(0, kPosA, kRotA), b = marker(-1, kGround, kRotGround);
  const auto cyl = make_joint("cylindrical", 1, a, b, true, true);
  EXPECT_EQ(cyl->equation_name(3), "a3·b2");
  EXPECT_EQ(cyl->equation_name(4), "angle");
  EXPECT_EQ(cyl->equation_name(5), "displacement");
  EXPECT_EQ(cyl->equation_label(4), "equation 5 (angle)");
  EXPECT_EQ(make_joint("prismatic", 1, a, b, false, true)->equation_name(5), "displacement");
  EXPECT_EQ(spatial_joint_kind_names(),
            "spherical, universal, revolute, cylindrical, prismatic, planar, fixed, point_on_line, point_on_plane");
  using V = MarkerVector;
  EXPECT_EQ((dot(V::a1, V::b2) + dot(V::a2, V::b1)).name, "a1·b2 + a2·b1");
  EXPECT_EQ((dot(V::a1, V::d) + -1.0 * dot(V::b3, V::d)).name, "a1·d − b3·d");
  EXPECT_EQ((2.0 * (dot(V::a1, V::d) + dot(V::e_z, V::d))).name, "2 (a1·d + z)");
  // A malformed row is refused.
  EXPECT_THROW(SpatialJointKind::make("bad", "", {dot(V::e_x, V::e_y)}, 0, 0), std::logic_error);
  EXPECT_THROW(SpatialJointKind::make("bad", "", {dot(V::a1, V::d), dot(V::a1, V::d)}, 0, 0), std::logic_error);
}

// Rows of the table are single products; a row with sums and coefficients (a made-up kind, not in
// the table) has Φ equal to the formula evaluated directly on the markers, and Φ_q and the
// closed-form K_Φ equal to finite differences and to nested AD.
TEST(SpatialJoint, EquationsWithSumsAndCoefficientsHaveExactDerivatives) {
  using V = MarkerVector;
  const SpatialJointKind skew = SpatialJointKind::make(
      "skew", "test only",
      {dot(V::a1, V::d) + 2.0 * dot(V::a2, V::d), dot(V::a3, V::b1) + -0.5 * dot(V::a1, V::b2) + dot(V::e_z, V::d)},
      SpatialJointKind::axis, SpatialJointKind::angle | SpatialJointKind::displacement);
  std::mt19937 rng(402);
  for (int nodes = 1; nodes <= 2; ++nodes)
    for (int drivers = 0; drivers < 2; ++drivers) {
      SCOPED_TRACE(std::to_string(nodes) + " node(s), drivers " + std::to_string(drivers));
      const SpatialMarker a = marker(0, kPosA, kRotA), b = nodes == 2 ? marker(1, kPosB, kRotB)
                                                                         : marker(-1, kGround, kRotGround);
      const auto joint = make_joint(skew, nodes, a, b, drivers, drivers);
      ASSERT_EQ(joint->size(), 2 + 2 * drivers);
      for (int i = 0; i < kSpatialSamples; ++i) {
        std::vector<Pose<double>> poses;
        for (int n = 0; n < nodes; ++n) poses.push_back(random_pose(rng));
        const Eigen::VectorXd q = stored(poses);
        const Pose<double> A = a.pose<double>(poses.data()), B = b.pose<double>(poses.data());
        const Eigen::Vector3d d = B.x - A.x;
        Eigen::VectorXd expected(joint->size());
        expected.head<2>() << A.R.col(0).dot(d) + 2.0 * A.R.col(1).dot(d),
            A.R.col(2).dot(B.R.col(0)) - 0.5 * A.R.col(0).dot(B.R.col(1)) + d.z();
        if (drivers) {
          const double phi = kAngle->value(kT);
          expected[2] = A.R.col(0).dot(std::cos(phi) * B.R.col(1) - std::sin(phi) * B.R.col(0));
          expected[3] = -B.R.col(2).dot(d) - kDisplacement->value(kT);
        }
        EXPECT_LE((spatial_phi_of(*joint, q) - expected).cwiseAbs().maxCoeff(), 1e-14) << spatial_phi_of(*joint, q).transpose();
        const Eigen::MatrixXd phi_q = spatial_phi_q_of(*joint, q);
        const Eigen::MatrixXd fd = fd_on_group([&](const Eigen::VectorXd& x) { return spatial_phi_of(*joint, x); }, q);
        EXPECT_LE(discrepancy(phi_q, fd, phi_q.norm()), kSpatialRelTol);
        const Eigen::VectorXd lambda = random_vector(rng, joint->size(), -2.0, 2.0);
        Eigen::MatrixXd closed, by_ad;
        joint->geometric_stiffness(q, kT, lambda, closed);
        joint->geometric_stiffness_by_ad(q, kT, lambda, by_ad);
        EXPECT_LE((closed - by_ad).cwiseAbs().maxCoeff(), 1e-13 * std::max(1.0, by_ad.cwiseAbs().maxCoeff()));
        const Eigen::MatrixXd kfd =
            fd_on_group([&](const Eigen::VectorXd& x) { return (spatial_phi_q_of(*joint, x).transpose() * lambda).eval(); }, q);
        EXPECT_LE(discrepancy(closed, kfd, closed.norm()), kSpatialRelTol);
      }
    }
}

// =================================================================== SpatialJoint: allowed motions

TEST(SpatialJoint, AssembledConfigurationsSatisfyTheJointAndTheJacobianHasFullRank) {
  // Over the whole family of allowed configurations (random pose of the first node, random free
  // relative motion, driven angle/displacement at t): Φ = 0, rank Φ_q = number of equations, and
  // the tangent directions of the family (central differences on the group, h = 1e-5, so exact
  // to ~h² = 1e-10) span the null space of Φ_q: the joint allows exactly these motions.
  std::mt19937 rng(100);
  double worst_phi = 0.0, worst_null = 0.0, worst_cond = 0.0;
  for (const SpatialJointCase& c : joint_cases()) {
    SCOPED_TRACE(c.label);
    const int m = c.joint->size(), n = 6 * c.nodes, nfree = free_parameters(c);
    const int nbase = c.nodes == 2 ? 6 : 0;  // the two-node families also move the first node rigidly
    for (int sample = 0; sample < 4; ++sample) {
      const Pose<double> base = random_pose(rng);
      const Eigen::VectorXd p0 = random_vector(rng, nfree, -1.2, 1.2);
      const auto family = [&](const Eigen::VectorXd& mu) {
        Pose<double> b = base;
        if (nbase) b = {base.x + mu.head<3>(), base.R * rot(Eigen::Vector3d(mu.segment<3>(3)))};
        return assembled(c, b, allowed_motion(c, mu.tail(nfree), kT));
      };
      Eigen::VectorXd mu0 = Eigen::VectorXd::Zero(nbase + nfree);
      mu0.tail(nfree) = p0;
      const Eigen::VectorXd q = family(mu0);
      Eigen::VectorXd phi;
      Eigen::MatrixXd phi_q;
      c.joint->evaluate(q, kT, phi, phi_q);
      worst_phi = std::max(worst_phi, phi.cwiseAbs().maxCoeff());
      EXPECT_LE(phi.cwiseAbs().maxCoeff(), 1e-14) << "Φ = " << phi.transpose();

      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(phi_q);
      const Eigen::VectorXd sv = svd.singularValues();
      ASSERT_EQ(sv.size(), m);
      const double cond = sv[m - 1] / sv[0];
      worst_cond = std::max(worst_cond, 1.0 / cond);
      EXPECT_GT(cond, 1e-3) << "Φ_q is rank deficient: singular values " << sv.transpose();

      // Tangents of the family at mu0: (n − m) independent directions in the null space of Φ_q.
      const int dim = nbase + nfree;
      ASSERT_EQ(dim, n - m);
      if (dim == 0) continue;
      Eigen::MatrixXd N(n, dim);
      const double h = 1e-5;
      for (int k = 0; k < dim; ++k)
        N.col(k) =
            (difference(q, family(mu0 + h * unit(dim, k))) - difference(q, family(mu0 - h * unit(dim, k)))) / (2.0 * h);
      const double null = (phi_q * N).norm() / (phi_q.norm() * N.norm());
      worst_null = std::max(worst_null, null);
      EXPECT_LE(null, 1e-8) << "allowed motions not in the null space of Φ_q:\n" << (phi_q * N).format(kSpatialFmt);
      const Eigen::JacobiSVD<Eigen::MatrixXd> nsvd(N);
      EXPECT_GT(nsvd.singularValues()[dim - 1] / nsvd.singularValues()[0], 1e-3)
          << "the allowed motions are not independent: " << nsvd.singularValues().transpose();
    }
  }
  std::printf("[ worst    ] |Φ| at assembly %.1e, |Φ_q N|/(|Φ_q||N|) %.1e, cond(Φ_q) %.1f\n", worst_phi, worst_null,
              worst_cond);
}

TEST(SpatialJoint, EachJointAllowsExactlyTheElementaryMotionsOfItsName) {
  // From an assembled configuration, move marker B relative to marker A by 0.4 along / about each
  // axis of A: Φ stays 0 exactly for the motions the joint's name allows, and not otherwise.
  //   spherical: rotations; universal: rotations about a1 and a2 (= b2); revolute: rotation about a3;
  //   cylindrical: rotation about and translation along a3; prismatic: translation along a3;
  //   planar: translations along a1, a2 and rotation about a3; fixed: none; point_on_line: rotations
  //   and translation along a3; point_on_plane: rotations and translations along a1, a2.
  // A driver removes its motion (rotation about a3, translation along a3).
  const auto allowed = [](const SpatialJointCase& c, bool rotation, int axis) {
    const std::string& type = c.joint->kind().name;
    if (type == "spherical") return bool(rotation);
    if (type == "universal") return rotation && axis < 2;
    if (type == "revolute") return rotation && axis == 2 && !c.angle;
    if (type == "cylindrical") return axis == 2 && (rotation ? !c.angle : !c.displacement);
    if (type == "prismatic") return !rotation && axis == 2 && !c.displacement;
    if (type == "planar") return rotation ? axis == 2 : axis < 2;
    if (type == "fixed") return false;
    if (type == "point_on_line") return rotation || axis == 2;
    if (type == "point_on_plane") return rotation || axis < 2;
    ADD_FAILURE() << "joint type '" << type << "': write its elementary motions here";
    return false;
  };
  std::mt19937 rng(200);
  for (const SpatialJointCase& c : joint_cases()) {
    SCOPED_TRACE(c.label);
    const Pose<double> base = random_pose(rng);
    const Motion m0 = allowed_motion(c, Eigen::VectorXd::Zero(free_parameters(c)), kT);
    for (int rotation = 0; rotation < 2; ++rotation)
      for (int axis = 0; axis < 3; ++axis) {
        Motion m = m0;
        if (rotation)
          m.R = rot(axis, 0.4) * m0.R;
        else
          m.p += 0.4 * Eigen::Vector3d::Unit(axis);
        const Eigen::VectorXd phi = spatial_phi_of(*c.joint, assembled(c, base, m));
        const std::string what =
            std::string(rotation ? "rotation about a" : "translation along a") + std::to_string(axis + 1) + ": Φ = ";
        if (allowed(c, rotation, axis))
          EXPECT_LE(phi.cwiseAbs().maxCoeff(), 1e-14) << what << phi.transpose();
        else
          EXPECT_GT(phi.cwiseAbs().maxCoeff(), 0.05) << what << phi.transpose();
      }
  }
}

// =================================================================== SpatialJoint: derivatives

TEST(SpatialJoint, ConstraintJacobianMatchesFiniteDifferencesOnTheGroup) {
  std::mt19937 rng(300);
  for (const SpatialJointCase& c : joint_cases()) {
    double worst = 0.0;
    for (int i = 0; i < kSpatialSamples; ++i) {
      SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
      const Eigen::VectorXd q = violated(rng, c);
      const Eigen::MatrixXd phi_q = spatial_phi_q_of(*c.joint, q);
      const Eigen::MatrixXd fd = fd_on_group([&](const Eigen::VectorXd& x) { return spatial_phi_of(*c.joint, x); }, q);
      const double d = discrepancy(phi_q, fd, phi_q.norm());
      worst = std::max(worst, d);
      EXPECT_LE(d, kSpatialRelTol) << "Φ_q:\n" << phi_q.format(kSpatialFmt) << "\nFD:\n" << fd.format(kSpatialFmt);
    }
    spatial_report("Φ_q", c.label, worst);
  }
}

TEST(SpatialJoint, GeometricStiffnessMatchesFiniteDifferencesOfPhiQTransposeLambda) {
  // K_Φ e_j ≈ [Φ_q(q ∘ exp(ε e_j))ᵀλ − Φ_q(q ∘ exp(−ε e_j))ᵀλ] / 2ε: the outer perturbation first.
  std::mt19937 rng(400);
  for (const SpatialJointCase& c : joint_cases()) {
    double worst = 0.0;
    for (int i = 0; i < kSpatialSamples; ++i) {
      SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
      const Eigen::VectorXd q = violated(rng, c);
      const Eigen::VectorXd lambda = random_vector(rng, c.joint->size(), -2.0, 2.0);
      Eigen::MatrixXd k;
      c.joint->geometric_stiffness(q, kT, lambda, k);
      ASSERT_EQ(k.rows(), 6 * c.nodes);
      ASSERT_EQ(k.cols(), 6 * c.nodes);
      const Eigen::MatrixXd fd =
          fd_on_group([&](const Eigen::VectorXd& x) { return (spatial_phi_q_of(*c.joint, x).transpose() * lambda).eval(); }, q);
      const double d = discrepancy(k, fd, k.norm());
      worst = std::max(worst, d);
      EXPECT_LE(d, kSpatialRelTol) << "K_Φ:\n"
                            << k.format(kSpatialFmt) << "\nFD:\n"
                            << fd.format(kSpatialFmt) << "\nλ = " << lambda.transpose();
    }
    spatial_report("∂(Φ_qᵀλ)/∂δ", c.label, worst);
  }
}

// The closed form of K_Φ (dot products of marker axes, points and d: spatial_joints.cpp) against
// nested forward AD of the joint equations (model/spatial_kernel.hpp), which computes the same mixed
// derivatives by another route: equal to round-off for every joint type, driver and ground case.
TEST(SpatialJoint, ClosedFormGeometricStiffnessEqualsNestedAutomaticDifferentiation) {
  std::mt19937 rng(401);
  for (const SpatialJointCase& c : joint_cases()) {
    for (int i = 0; i < kSpatialSamples; ++i) {
      SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
      const Eigen::VectorXd q = violated(rng, c);
      const Eigen::VectorXd lambda = random_vector(rng, c.joint->size(), -2.0, 2.0);
      Eigen::MatrixXd closed, by_ad;
      c.joint->geometric_stiffness(q, kT, lambda, closed);
      c.joint->geometric_stiffness_by_ad(q, kT, lambda, by_ad);
      ASSERT_EQ(closed.rows(), by_ad.rows());
      ASSERT_EQ(closed.cols(), by_ad.cols());
      EXPECT_LE((closed - by_ad).cwiseAbs().maxCoeff(), 1e-13 * std::max(1.0, by_ad.cwiseAbs().maxCoeff()))
          << "closed form:\n" << closed.format(kSpatialFmt) << "\nAD:\n" << by_ad.format(kSpatialFmt);
    }
  }
}

// The closed form of Φ_q (first derivatives of marker axes, points and d: spatial_joints.cpp)
// against forward AD of the joint equations over the 12 increments (model/spatial_kernel.hpp), and
// Φ itself: equal to round-off for every joint type, driver and ground case, and for a made-up row
// with sums and coefficients.
TEST(SpatialJoint, ClosedFormJacobianEqualsForwardAutomaticDifferentiation) {
  std::mt19937 rng(403);
  using V = MarkerVector;
  const SpatialJointKind skew = SpatialJointKind::make(
      "skew", "test only",
      {dot(V::a1, V::d) + 2.0 * dot(V::a2, V::d), dot(V::a3, V::b1) + -0.5 * dot(V::a1, V::b2) + dot(V::e_z, V::d)},
      SpatialJointKind::axis, SpatialJointKind::angle | SpatialJointKind::displacement);
  std::vector<std::pair<std::string, std::shared_ptr<const SpatialJoint>>> joints;
  for (const SpatialJointCase& c : joint_cases()) joints.emplace_back(c.label, c.joint);
  for (int nodes = 1; nodes <= 2; ++nodes) {
    const SpatialMarker a = marker(0, kPosA, kRotA), b = nodes == 2 ? marker(1, kPosB, kRotB) : marker(-1, kGround, kRotGround);
    joints.emplace_back("skew, " + std::to_string(nodes) + " node(s)", make_joint(skew, nodes, a, b, true, true));
  }
  double worst = 0.0;
  for (const auto& [label, joint] : joints) {
    const int nodes = static_cast<int>(joint->nodes().size());
    for (int i = 0; i < kSpatialSamples; ++i) {
      SCOPED_TRACE(label + ", random configuration #" + std::to_string(i));
      std::vector<Pose<double>> poses;
      for (int n = 0; n < nodes; ++n) poses.push_back(random_pose(rng));
      const Eigen::VectorXd q = stored(poses);
      Eigen::VectorXd phi, phi_ad;
      Eigen::MatrixXd closed, by_ad;
      joint->evaluate(q, kT, phi, closed);
      joint->evaluate_by_ad(q, kT, phi_ad, by_ad);
      ASSERT_EQ(closed.rows(), by_ad.rows());
      ASSERT_EQ(closed.cols(), by_ad.cols());
      // The same kernel in doubles and as the AD value part: a few ulps apart at most.
      EXPECT_LE((phi - phi_ad).cwiseAbs().maxCoeff(), 1e-15 * (1.0 + phi_ad.cwiseAbs().maxCoeff()));
      const double d = (closed - by_ad).cwiseAbs().maxCoeff() / std::max(1.0, by_ad.cwiseAbs().maxCoeff());
      EXPECT_LE(d, 1e-14) << "closed form:\n" << closed.format(kSpatialFmt) << "\nAD:\n" << by_ad.format(kSpatialFmt);
      worst = std::max(worst, d);
    }
  }
  std::printf("spatial joints: closed-form Φ_q against forward AD, worst difference %.1e (relative to the largest entry)\n",
              worst);
}

TEST(SpatialJoint, TimeDerivativeMatchesFiniteDifferencesInTimeAndVanishesWithoutDrivers) {
  std::mt19937 rng(500);
  for (const SpatialJointCase& c : joint_cases()) {
    double worst = 0.0;
    for (int i = 0; i < kSpatialSamples; ++i) {
      SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
      const Eigen::VectorXd q = violated(rng, c);
      const double t = uniform(rng, 0.0, 3.0);
      Eigen::VectorXd phi_t;
      c.joint->time_derivative(q, t, phi_t);
      ASSERT_EQ(phi_t.size(), c.joint->size());
      const Eigen::VectorXd fd = (spatial_phi_of(*c.joint, q, t + kFdStep) - spatial_phi_of(*c.joint, q, t - kFdStep)) / (2 * kFdStep);
      if (!c.angle && !c.displacement) {
        EXPECT_EQ(phi_t, Eigen::VectorXd::Zero(c.joint->size()));
        EXPECT_EQ(fd, Eigen::VectorXd::Zero(c.joint->size()));
        continue;
      }
      // Only the driver rows depend on time.
      EXPECT_EQ(phi_t.head(c.joint->kind().num_equations), Eigen::VectorXd::Zero(c.joint->kind().num_equations));
      const double d = discrepancy(phi_t, fd, phi_t.norm());
      worst = std::max(worst, d);
      EXPECT_LE(d, kSpatialRelTol) << "Φ_t = " << phi_t.transpose() << "\nFD:   " << fd.transpose();
    }
    if (c.angle || c.displacement) spatial_report("Φ_t", c.label, worst);
  }
}

TEST(SpatialJoint, DriversPrescribeTheMotionOfNode1RelativeToNode2) {
  // The header's convention, in the user's terms: a crank (node 1) on a revolute or cylindrical
  // joint to the ground, driven at φ(t), is turned by +φ(t) about the axis (right-hand rule) from
  // where it was assembled; a slider (node 1) driven at u(t) is moved by +u(t) along the axis.
  // Joint frame: a3 along the world direction n, markers coincident when the node is at identity.
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const Eigen::Vector3d p(0.4, 0.1, -0.2);  // joint point; the node's origin is elsewhere
  Eigen::Matrix3d frame;
  ASSERT_TRUE(frame_from(n, Eigen::Vector3d(1.0, 0.2, 0.0), frame));
  frame = (Eigen::Matrix3d() << frame.col(1), frame.col(2), frame.col(0)).finished();  // a3 = n
  const Eigen::Vector3d x0(1.1, -0.6, 0.3);
  const SpatialMarker a = marker(0, p - x0, Eigen::Vector3d::Zero()), b = marker(-1, p, Eigen::Vector3d::Zero());
  SpatialMarker a_framed = a, b_framed = b;
  a_framed.rotation = frame;
  b_framed.rotation = frame;
  for (double t : {0.0, 0.37, 1.3}) {
    const double phi = kAngle->value(t), u = kDisplacement->value(t);
    // Node turned by φ about n through p, then moved by u along n.
    const Eigen::Matrix3d R = Eigen::AngleAxisd(phi, n).toRotationMatrix();
    const Eigen::Vector3d x = p + R * (x0 - p) + u * n;
    const Eigen::VectorXd q = stored({{x, R}}),
                          q_wrong = stored({{p + R.transpose() * (x0 - p) - u * n, R.transpose()}});
    const SpatialJoint cyl("c", {0}, kind("cylindrical"), a_framed, b_framed, kAngle, kDisplacement);
    EXPECT_LE(spatial_phi_of(cyl, q, t).cwiseAbs().maxCoeff(), 1e-14) << "t = " << t << ": " << spatial_phi_of(cyl, q, t).transpose();
    EXPECT_GT(spatial_phi_of(cyl, q_wrong, t).tail<2>().cwiseAbs().minCoeff(), 1e-3) << "t = " << t;
    // Rates: at a configuration satisfying the drivers, Φ_t = (−φ', −u').
    Eigen::VectorXd phi_t;
    cyl.time_derivative(q, t, phi_t);
    EXPECT_NEAR(phi_t[4], -kAngle->derivative(t), 4 * kSpatialEps * std::abs(kAngle->derivative(t)));
    EXPECT_NEAR(phi_t[5], -kDisplacement->derivative(t), 4 * kSpatialEps * std::abs(kDisplacement->derivative(t)));
  }
}

TEST(SpatialJoint, AccelerationTermIsTheSecondDerivativeOfPhiAlongTheGroupMotion) {
  // c = d²/dτ² Φ(q ∘ exp(τ v), t + τ) (Φ_q v̇ = 0 on this path), and along q ∘ exp(τ v + τ² a/2):
  // Φ̈ = Φ_q a + c, which fixes the group convention q(t + τ) = q ∘ exp(τ v + τ² v̇ / 2 + O(τ³)).
  std::mt19937 rng(600);
  for (const SpatialJointCase& c : joint_cases()) {
    double worst1 = 0.0, worst2 = 0.0;
    for (int i = 0; i < kSpatialSamples; ++i) {
      SCOPED_TRACE(c.label + ", random state #" + std::to_string(i));
      const Eigen::VectorXd q = violated(rng, c);
      const int n = 6 * c.nodes;
      const Eigen::VectorXd v = random_vector(rng, n, -1.5, 1.5), a = random_vector(rng, n, -2.0, 2.0);
      Eigen::VectorXd acc;
      c.joint->acceleration_term(q, v, kT, acc);
      ASSERT_EQ(acc.size(), c.joint->size());
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
      const Eigen::VectorXd fd1 = fd_second_along(*c.joint, q, v, zero, kT);
      const double d1 = discrepancy(acc, fd1, acc.norm());
      worst1 = std::max(worst1, d1);
      EXPECT_LE(d1, kSpatialRelTol) << "c = " << acc.transpose() << "\nd²Φ/dτ² (FD) = " << fd1.transpose();
      const Eigen::VectorXd expected = spatial_phi_q_of(*c.joint, q) * a + acc;
      const Eigen::VectorXd fd2 = fd_second_along(*c.joint, q, v, a, kT);
      const double d2 = discrepancy(expected, fd2, expected.norm());
      worst2 = std::max(worst2, d2);
      EXPECT_LE(d2, kSpatialRelTol) << "Φ_q a + c = " << expected.transpose() << "\nd²Φ/dτ² (FD) = " << fd2.transpose();
    }
    spatial_report("c vs d²Φ(q∘exp(τv), t+τ)/dτ²", c.label, worst1);
    spatial_report("Φ_q a + c vs d²Φ(q∘exp(τv+τ²a/2), t+τ)/dτ²", c.label, worst2);
  }
}

// =================================================================== SpatialJoint: reactions

TEST(SpatialJoint, ReactionIsTheGeneralizedForceOnNode1ReadAtMarkerA) {
  // For any λ: −Φ_{q,node 1}ᵀλ = [F; R₁ᵀ(M + (p_A − x₁) × F)] (virtual work on node 1 of a force F
  // at p_A and a moment M, world components), location = p_A, frame = rotation of marker A.
  std::mt19937 rng(700);
  for (const SpatialJointCase& c : joint_cases()) {
    SCOPED_TRACE(c.label);
    for (int i = 0; i < kSpatialSamples; ++i) {
      const Eigen::VectorXd q = violated(rng, c);
      const Eigen::VectorXd lambda = random_vector(rng, c.joint->size(), -2.0, 2.0);
      const JointReaction r = c.joint->reaction(q, kT, lambda);
      std::vector<Pose<double>> nodes;
      for (int k = 0; k < c.nodes; ++k) nodes.push_back(pose_at(q, k));
      const Pose<double> A = c.joint->marker_a().pose<double>(nodes.data());
      EXPECT_LE((r.location - A.x).norm(), 4 * kSpatialEps * (1 + A.x.norm()));
      EXPECT_LE((r.frame - A.R).norm(), 4 * kSpatialEps);
      const Eigen::VectorXd g = -spatial_phi_q_of(*c.joint, q).leftCols(6).transpose() * lambda;
      Eigen::VectorXd from_reaction(6);
      from_reaction << r.force, nodes[0].R.transpose() * (r.moment + (r.location - nodes[0].x).cross(r.force));
      EXPECT_LE((g - from_reaction).norm(), 1e-14 * std::max(1.0, g.norm()))
          << "−Φ_q1ᵀλ = " << g.transpose() << "\nfrom the reaction: " << from_reaction.transpose();
    }
  }
}

TEST(SpatialJoint, SphericalJointHoldingAHangingBodyPushesUpWithItsWeight) {
  // A body hangs at rest from a spherical joint to the ground at p, its centre of mass below p.
  // The joint's force on the body (node 1) is +m g up, its moment about the joint point is zero,
  // and with Φ = p_ground − p_A the multiplier is that force: λ = (0, 0, m g).
  const double mass = 3.2, g = 9.81;
  const Eigen::Matrix3d R = rot(Eigen::Vector3d(0.7, -0.4, 1.1));
  const Eigen::Vector3d p(0.4, -0.3, 2.0);
  const Eigen::Vector3d s_body = R.transpose() * Eigen::Vector3d(0.0, 0.0, 0.8);  // joint 0.8 above the CM
  const SpatialJoint joint("pivot", {0}, kind("spherical"), marker(0, s_body, kRotA),
                           marker(-1, p, kRotGround));
  const Eigen::VectorXd q = stored({{p - R * s_body, R}});
  EXPECT_LE(spatial_phi_of(joint, q).norm(), 4 * kSpatialEps);
  const RigidBody3D body("body", 0, mass, Eigen::Vector3d(0.2, 0.3, 0.4).asDiagonal(), Eigen::Vector3d(0, 0, -g));
  LocalState s;
  s.q = q;
  s.v = Eigen::VectorXd::Zero(6);
  s.qdd = Eigen::VectorXd::Zero(6);
  s.t = kT;
  LocalResidual out;
  out.reset(6, false);
  body.evaluate(s, out, false);
  // Equilibrium r + Φ_qᵀλ = 0, solved for λ (6 equations, 3 unknowns; consistent only if the
  // weight passes through the pivot).
  const Eigen::MatrixXd phi_q = spatial_phi_q_of(joint, q);
  const Eigen::VectorXd lambda = phi_q.transpose().colPivHouseholderQr().solve(-out.r);
  EXPECT_LE((out.r + phi_q.transpose() * lambda).norm(), 1e-13 * mass * g) << "not in equilibrium";
  EXPECT_LE((lambda - Eigen::Vector3d(0, 0, mass * g)).norm(), 1e-14 * mass * g) << "λ = " << lambda.transpose();
  const JointReaction r = joint.reaction(q, kT, lambda);
  EXPECT_LE((r.force - Eigen::Vector3d(0, 0, mass * g)).norm(), 1e-14 * mass * g) << "F = " << r.force.transpose();
  EXPECT_LE(r.moment.norm(), 1e-14 * mass * g) << "M = " << r.moment.transpose();
  EXPECT_LE((r.location - p).norm(), 4 * kSpatialEps * p.norm());
  EXPECT_LE((r.frame - R * rot(kRotA)).norm(), 4 * kSpatialEps);
}

TEST(SpatialJoint, FixedJointReactionBalancesTheLoadOnNode1AboutTheJointPoint) {
  // A cantilevered node at rest under a dead force F at a body point and a dead moment M: the clamp
  // (fixed joint to the ground, or to a second node) acts on node 1 with −F and, about its point
  // p_A, with −(M + (p_F − p_A) × F); its frame is marker A's.
  const Eigen::Vector3d F(3.0, -1.5, 2.2), M(-0.7, 1.1, 0.4), s_F(0.9, 0.2, -0.3);
  const Pose<double> node{Eigen::Vector3d(0.2, 0.5, -0.1), rot(Eigen::Vector3d(-0.5, 0.8, 0.3))};
  const SpatialLoad load("load", 0, s_F, {make_constant(F.x()), make_constant(F.y()), make_constant(F.z())},
                         {make_constant(M.x()), make_constant(M.y()), make_constant(M.z())}, false);
  const Eigen::Vector3d p_A = node.x + node.R * kPosA, p_F = node.x + node.R * s_F;
  const Eigen::Matrix3d frame_A = node.R * rot(kRotA);
  const Eigen::Vector3d force = -F, moment = -(M + (p_F - p_A).cross(F));
  std::mt19937 rng(800);
  for (int nodes : {1, 2}) {
    SCOPED_TRACE(nodes == 1 ? "clamped to the ground" : "clamped to a second node");
    std::vector<Pose<double>> poses = {node};
    SpatialMarker b;
    if (nodes == 1) {
      b = marker(-1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
      b.position = p_A;
      b.rotation = frame_A;
    } else {
      b = marker(1, kPosB, kRotB);
      poses.push_back(node_from_marker(b, {p_A, frame_A}));
    }
    const SpatialJoint joint("clamp", nodes == 1 ? std::vector<int>{0} : std::vector<int>{0, 1},
                             kind("fixed"), marker(0, kPosA, kRotA), b);
    const Eigen::VectorXd q = stored(poses);
    EXPECT_LE(spatial_phi_of(joint, q).norm(), 1e-14);
    LocalState s;
    s.q = q.head(7);
    s.v = Eigen::VectorXd::Zero(6);
    s.qdd = Eigen::VectorXd::Zero(6);
    s.t = kT;
    LocalResidual out;
    out.reset(6, false);
    load.evaluate(s, out, false);
    // Equilibrium of node 1: r + Φ_{q,node 1}ᵀλ = 0 (6 × 6).
    const Eigen::MatrixXd J1 = spatial_phi_q_of(joint, q).leftCols(6);
    const Eigen::VectorXd lambda = J1.transpose().partialPivLu().solve(-out.r);
    const JointReaction r = joint.reaction(q, kT, lambda);
    const double scale = F.norm() + M.norm();
    EXPECT_LE((r.force - force).norm(), 1e-13 * scale)
        << "F = " << r.force.transpose() << ", expected " << force.transpose();
    EXPECT_LE((r.moment - moment).norm(), 1e-13 * scale)
        << "M = " << r.moment.transpose() << ", expected " << moment.transpose();
    EXPECT_LE((r.location - p_A).norm(), 4 * kSpatialEps * (1 + p_A.norm()));
    EXPECT_LE((r.frame - frame_A).norm(), 4 * kSpatialEps);
  }
}

// =================================================================== RigidBody3D

namespace {

LocalState spatial_state(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& qdd, double t,
                         double load_factor = 1.0) {
  LocalState s;
  s.q = q;
  s.v = v;
  s.qdd = qdd;
  s.t = t;
  s.load_factor = load_factor;
  return s;
}

LocalResidual evaluate(const Element& e, const LocalState& s, bool tangent) {
  LocalResidual out;
  out.reset(static_cast<int>(s.v.size()), tangent);
  e.evaluate(s, out, tangent);
  return out;
}

const Eigen::Vector3d kSpatialGravity(0.0, 0.0, -9.81);

/// An inertia tensor with principal moments 0.3, 0.5, 0.9 and axes Q (body frame).
Eigen::Matrix3d general_inertia(const Eigen::Matrix3d& Q) {
  return Q * Eigen::Vector3d(0.3, 0.5, 0.9).asDiagonal() * Q.transpose();
}

}  // namespace

TEST(RigidBody3D, ResidualIsNewtonEulerInHandComputedForm) {
  // Principal axes: r = [m(ẍ − λ_f g); J1 Ω̇1 − (J2 − J3) Ω2 Ω3; J2 Ω̇2 − (J3 − J1) Ω3 Ω1;
  // J3 Ω̇3 − (J1 − J2) Ω1 Ω2]; with a general inertia Q J Qᵀ the moment rows are Q times those at QᵀΩ.
  std::mt19937 rng(900);
  const double mass = 2.5, J1 = 0.3, J2 = 0.5, J3 = 0.9;
  const RigidBody3D principal("b", 0, mass, Eigen::Vector3d(J1, J2, J3).asDiagonal(), kSpatialGravity);
  const Eigen::Matrix3d Q = rot(Eigen::Vector3d(0.3, -1.1, 0.6));
  const RigidBody3D general("b", 0, mass, general_inertia(Q), kSpatialGravity);
  for (int i = 0; i < kSpatialSamples; ++i) {
    const Pose<double> p = random_pose(rng);
    const Eigen::VectorXd q = stored({p});
    const Eigen::VectorXd v = random_vector(rng, 6, -3.0, 3.0), a = random_vector(rng, 6, -4.0, 4.0);
    const double lf = uniform(rng, 0.0, 1.0);
    const Eigen::Vector3d W = v.tail<3>(), Wd = a.tail<3>();
    Eigen::VectorXd expected(6);
    expected << mass * (a[0] - lf * kSpatialGravity[0]), mass * (a[1] - lf * kSpatialGravity[1]), mass * (a[2] - lf * kSpatialGravity[2]),
        J1 * Wd[0] - (J2 - J3) * W[1] * W[2], J2 * Wd[1] - (J3 - J1) * W[2] * W[0],
        J3 * Wd[2] - (J1 - J2) * W[0] * W[1];
    // Round-off scale: the magnitudes of the terms summed in each row.
    const double force_scale = mass * (a.head<3>().norm() + 9.81);
    const double moment_scale = J3 * (Wd.norm() + W.squaredNorm());
    const Eigen::VectorXd r = evaluate(principal, spatial_state(q, v, a, kT, lf), false).r;
    EXPECT_LE((r.head<3>() - expected.head<3>()).norm(), 4 * kSpatialEps * force_scale)
        << "r = " << r.transpose() << "\nexpected " << expected.transpose();
    EXPECT_LE((r.tail<3>() - expected.tail<3>()).norm(), 8 * kSpatialEps * moment_scale)
        << "r = " << r.transpose() << "\nexpected " << expected.transpose();
    // The same body with its principal axes turned by Q in the body frame.
    Eigen::VectorXd vg = v, ag = a;
    vg.tail<3>() = Q * W;
    ag.tail<3>() = Q * Wd;
    const Eigen::VectorXd rg = evaluate(general, spatial_state(q, vg, ag, kT, lf), false).r;
    EXPECT_LE((rg.head<3>() - expected.head<3>()).norm(), 4 * kSpatialEps * force_scale);
    EXPECT_LE((rg.tail<3>() - Q * expected.tail<3>()).norm(), 32 * kSpatialEps * moment_scale)
        << "Q r_θ(principal) = " << (Q * expected.tail<3>()).transpose()
        << "\nr_θ(general) = " << rg.tail<3>().transpose();
    // Independent of the configuration (K = 0): the same residual at another pose.
    const Eigen::VectorXd r2 = evaluate(principal, spatial_state(stored({random_pose(rng)}), v, a, kT, lf), false).r;
    EXPECT_EQ(r, r2);
  }
}

TEST(RigidBody3D, TangentsAreZeroKConstantMAndCMatchingFiniteDifferencesInOmega) {
  std::mt19937 rng(1000);
  const double mass = 2.5;
  const Eigen::Matrix3d J = general_inertia(rot(Eigen::Vector3d(0.3, -1.1, 0.6)));
  const RigidBody3D body("b", 0, mass, J, kSpatialGravity);
  double worst = 0.0;
  for (int i = 0; i < kSpatialSamples; ++i) {
    const LocalState s = spatial_state(stored({random_pose(rng)}), random_vector(rng, 6, -3.0, 3.0),
                                       random_vector(rng, 6, -4.0, 4.0), kT);
    const LocalResidual t = evaluate(body, s, true);
    EXPECT_EQ(t.r, evaluate(body, s, false).r);
    EXPECT_EQ(t.K, Eigen::MatrixXd::Zero(6, 6));
    Eigen::MatrixXd M = Eigen::MatrixXd::Zero(6, 6);
    M.topLeftCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
    M.bottomRightCorner<3, 3>() = J;
    EXPECT_EQ(t.M, M);
    // K = 0: the residual does not change along the group at all.
    const Eigen::MatrixXd K_fd = fd_on_group(
        [&](const Eigen::VectorXd& x) {
          LocalState p = s;
          p.q = x;
          return evaluate(body, p, false).r;
        },
        s.q);
    EXPECT_EQ(K_fd, Eigen::MatrixXd::Zero(6, 6));
    // C = ∂r/∂(ẋ, Ω) by central differences; C = [0 0; 0 Ω̂J − (JΩ)^].
    const Eigen::MatrixXd C_fd = alphaflex::testing::central_differences(
        [&](const Eigen::VectorXd& x) {
          LocalState p = s;
          p.v = x;
          return evaluate(body, p, false).r;
        },
        s.v, alphaflex::testing::fixed_fd_step(kFdStep));
    const double d = discrepancy(t.C, C_fd, t.C.norm());
    worst = std::max(worst, d);
    EXPECT_LE(d, kSpatialRelTol) << "C:\n" << t.C.format(kSpatialFmt) << "\nFD:\n" << C_fd.format(kSpatialFmt);
    EXPECT_EQ(t.C.leftCols(3), Eigen::MatrixXd::Zero(6, 3));
    EXPECT_EQ(t.C.topRows(3), Eigen::MatrixXd::Zero(3, 6));
    // M by differences in q̈ (r is linear in q̈: exact up to round-off).
    Eigen::MatrixXd M_fd(6, 6);
    for (int j = 0; j < 6; ++j) {
      LocalState p = s, m = s;
      p.qdd[j] += 1.0;
      m.qdd[j] -= 1.0;
      M_fd.col(j) = (evaluate(body, p, false).r - evaluate(body, m, false).r) / 2.0;
    }
    EXPECT_LE((M_fd - M).norm(), 1e-14 * M.norm());
  }
  spatial_report("C = ∂r/∂Ω", "rigid body 3D", worst);
}

TEST(RigidBody3D, TorqueFreeMotionConservesEnergyAndAngularMomentum) {
  // With Ω̇ from r_θ = 0 (no load): Ė = Ωᵀ J Ω̇ = 0 and d|JΩ|²/dt = 2 (JΩ)ᵀ J Ω̇ = 0, i.e. the
  // gyroscopic term Ω × JΩ does no work and only turns the body-frame angular momentum.
  std::mt19937 rng(1100);
  const Eigen::Matrix3d J = general_inertia(rot(Eigen::Vector3d(0.3, -1.1, 0.6)));
  const RigidBody3D body("b", 0, 1.7, J, Eigen::Vector3d::Zero());
  for (int i = 0; i < kSpatialSamples; ++i) {
    const Eigen::VectorXd v = random_vector(rng, 6, -3.0, 3.0);
    const LocalResidual t =
        evaluate(body, spatial_state(stored({random_pose(rng)}), v, Eigen::VectorXd::Zero(6), kT), true);
    const Eigen::Vector3d Wd = -t.M.bottomRightCorner<3, 3>().ldlt().solve(t.r.tail<3>());
    const Eigen::Vector3d W = v.tail<3>(), H = J * W;
    EXPECT_LE(std::abs(W.dot(J * Wd)), 1e-14 * W.norm() * (J * Wd).norm()) << "energy rate";
    EXPECT_LE(std::abs(H.dot(J * Wd)), 1e-14 * H.norm() * (J * Wd).norm()) << "rate of |JΩ|²";
    // And the residual with that Ω̇ vanishes.
    EXPECT_LE(
        evaluate(body, spatial_state(stored({random_pose(rng)}), v, (Eigen::VectorXd(6) << 0, 0, 0, Wd).finished(), kT),
                 false)
            .r.norm(),
        1e-14 * H.norm() * W.norm());
  }
}

// =================================================================== SpatialLoad

namespace {

std::array<TimeFunctionPtr, 3> components(const Eigen::Vector3d& c) {
  return {make_constant(c.x()), make_constant(c.y()), make_constant(c.z())};
}
std::array<TimeFunctionPtr, 3> none() { return {nullptr, nullptr, nullptr}; }

struct LoadCase {
  std::string label;
  std::shared_ptr<const SpatialLoad> load;
  Eigen::Vector3d F, M, s;  // values at any t (constant components) or at kT
  bool follower;
};

const Eigen::Vector3d kF(2.0, -3.0, 1.5), kM(0.6, 0.9, -1.2), kPoint(0.5, -0.8, 0.3);

std::vector<LoadCase> load_cases() {
  std::vector<LoadCase> c;
  const Eigen::Vector3d O = Eigen::Vector3d::Zero();
  c.push_back({"dead force at an offset point",
               std::make_shared<SpatialLoad>("l", 0, kPoint, components(kF), none(), false), kF, O, kPoint, false});
  c.push_back(
      {"dead moment", std::make_shared<SpatialLoad>("l", 0, O, none(), components(kM), false), O, kM, O, false});
  c.push_back({"follower force at an offset point",
               std::make_shared<SpatialLoad>("l", 0, kPoint, components(kF), none(), true), kF, O, kPoint, true});
  c.push_back(
      {"follower moment", std::make_shared<SpatialLoad>("l", 0, O, none(), components(kM), true), O, kM, O, true});
  c.push_back({"dead force and moment",
               std::make_shared<SpatialLoad>("l", 0, kPoint, components(kF), components(kM), false), kF, kM, kPoint,
               false});
  c.push_back({"follower force and moment",
               std::make_shared<SpatialLoad>("l", 0, kPoint, components(kF), components(kM), true), kF, kM, kPoint,
               true});
  // Time-dependent components: the values at kT.
  const std::array<TimeFunctionPtr, 3> f = {make_sine(1.0, 0.5, 0.1, 2.0), nullptr, make_sine(-2.0, 0.2, 0.3, 0.0)};
  const Eigen::Vector3d Ft(f[0]->value(kT), 0.0, f[2]->value(kT));
  c.push_back({"dead time-dependent force", std::make_shared<SpatialLoad>("l", 0, kPoint, f, none(), false), Ft, O,
               kPoint, false});
  return c;
}

/// The generalized force of the load, by hand: δW = F_w·(δx + R(δθ × s)) + M_w·(R δθ).
Eigen::VectorXd expected_residual(const LoadCase& c, const Eigen::Matrix3d& R, double factor) {
  const Eigen::Vector3d Fw = c.follower ? (R * c.F).eval() : c.F, Mw = c.follower ? (R * c.M).eval() : c.M;
  Eigen::VectorXd r(6);
  r << -factor * Fw, -factor * (c.s.cross(R.transpose() * Fw) + R.transpose() * Mw);
  return r;
}

}  // namespace

TEST(SpatialLoad, ResidualIsMinusTheGeneralizedForceScaledByTheLoadFactor) {
  std::mt19937 rng(1200);
  for (const LoadCase& c : load_cases()) {
    SCOPED_TRACE(c.label);
    for (int i = 0; i < kSpatialSamples; ++i) {
      const Pose<double> p = random_pose(rng);
      const Eigen::VectorXd v = random_vector(rng, 6, -1, 1), a = random_vector(rng, 6, -1, 1);
      const double scale = c.F.norm() * (1 + c.s.norm()) + c.M.norm();
      for (double lf : {1.0, 0.37, 0.0}) {
        const LocalResidual t = evaluate(*c.load, spatial_state(stored({p}), v, a, kT, lf), true);
        const Eigen::VectorXd expected = expected_residual(c, pose_at(stored({p}), 0).R, lf);
        EXPECT_LE((t.r - expected).norm(), 1e-14 * scale)
            << "λ_f = " << lf << "\nr = " << t.r.transpose() << "\nexpected " << expected.transpose();
        EXPECT_EQ(t.C, Eigen::MatrixXd::Zero(6, 6));
        EXPECT_EQ(t.M, Eigen::MatrixXd::Zero(6, 6));
        // The load factor scales r and K.
        const LocalResidual one = evaluate(*c.load, spatial_state(stored({p}), v, a, kT, 1.0), true);
        EXPECT_LE((t.r - lf * one.r).norm(), 4 * kSpatialEps * one.r.norm()) << "λ_f = " << lf;
        EXPECT_LE((t.K - lf * one.K).norm(), 4 * kSpatialEps * one.K.norm()) << "λ_f = " << lf;
        if (lf == 0.0) {
          EXPECT_EQ(t.r, Eigen::VectorXd::Zero(6));
        }
      }
    }
  }
}

TEST(SpatialLoad, StiffnessMatchesFiniteDifferencesOnTheGroup) {
  // K = ∂r/∂δ: non-zero for a dead force at an offset point (−s × RᵀF) and a dead moment (−RᵀM),
  // and for a follower force (−R F); zero for a follower moment.
  std::mt19937 rng(1300);
  for (const LoadCase& c : load_cases()) {
    double worst = 0.0;
    for (int i = 0; i < kSpatialSamples; ++i) {
      SCOPED_TRACE(c.label + ", random configuration #" + std::to_string(i));
      const LocalState s = spatial_state(stored({random_pose(rng)}), random_vector(rng, 6, -1, 1),
                                         random_vector(rng, 6, -1, 1), kT, 0.8);
      const LocalResidual t = evaluate(*c.load, s, true);
      const Eigen::MatrixXd fd = fd_on_group(
          [&](const Eigen::VectorXd& x) {
            LocalState p = s;
            p.q = x;
            return evaluate(*c.load, p, false).r;
          },
          s.q);
      const double scale = c.F.norm() * (1 + c.s.norm()) + c.M.norm();
      if (c.follower && c.F.norm() == 0.0) {
        EXPECT_EQ(t.K, Eigen::MatrixXd::Zero(6, 6));
        EXPECT_LE(fd.norm(), kSpatialRelTol * scale);
        worst = std::max(worst, fd.norm() / scale);
        continue;
      }
      ASSERT_GT(t.K.norm(), 0.1 * scale);
      const double d = discrepancy(t.K, fd, t.K.norm());
      worst = std::max(worst, d);
      EXPECT_LE(d, kSpatialRelTol) << "K:\n" << t.K.format(kSpatialFmt) << "\nFD:\n" << fd.format(kSpatialFmt);
    }
    spatial_report("K = ∂r/∂δ", c.label, worst);
  }
}

}  // namespace alphaflex
