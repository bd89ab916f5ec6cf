// The geometrically exact beam on SE(3) (elements/geometrically_exact_beam.hpp) and its sections:
//  - K, C, M are the derivatives of r on the group (central differences of r(q ∘ exp(±h e_j)));
//  - the closed-form elastic r and its AD1 tangent equal the nested-AD derivatives of the energy;
//  - the strain is objective and exact for every constant-strain state (pure bending on a circle);
//  - no shear locking: a slender cantilever's tip deflection is Timoshenko's up to the element's
//    known O(n⁻²) error (one-point-quadrature equivalent), already accurate for a few elements;
//  - the cantilever's first two bending frequencies converge to Euler–Bernoulli's;
//  - Newton with K rolls a cantilever into the exact circle under an end moment;
//  - the section factories give the tabulated section properties;
//  (cost per evaluation: docs/theory/beam.md, measured outside the tests)
// Numbers measured here are quoted in docs/theory/beam.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/beam_section.hpp"
#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "alphaflex/joints/spatial_joints.hpp"
#include "alphaflex/model/node.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;
using Vector6d = Eigen::Matrix<double, 6, 1>;

using testing::kPi;
using testing::relative_error;

// ------------------------------------------------------------------ helpers

Vector3d random_vector3(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Vector3d(u(rng), u(rng), u(rng));
}

Matrix3d random_rotation(std::mt19937& rng) { return exp_so3<double>(random_vector3(rng, 2.0)); }

/// Configuration numbers of two poses.
VectorXd configuration(const Pose<double>& a, const Pose<double>& b) {
  VectorXd q(14);
  store_pose(a.x, a.R, q.data());
  store_pose(b.x, b.R, q.data() + 7);
  return q;
}

LocalState beam_state(const VectorXd& q, const VectorXd& v = VectorXd::Zero(12), const VectorXd& qdd = VectorXd::Zero(12)) {
  return testing::local_state(q, v, qdd);
}

using testing::element_residual;
using testing::element_tangents;

/// Central differences of r (test_support.hpp): on the group for q, h = 1e-6 L0 for translations
/// and 1e-6 rad for rotations; h = 1e-6 on v and q̈ (vector spaces).
using testing::Wrt;
MatrixXd beam_central_differences(const Element& e, const LocalState& s, Wrt wrt, double length) {
  const testing::VectorFunction r_at = testing::element_residual_of(e, s, wrt);
  if (wrt == Wrt::q)
    return testing::central_differences_on_frames(r_at, s.q, [&](int j, double) { return 1e-6 * (j % 6 < 3 ? length : 1.0); });
  return testing::central_differences(r_at, testing::variable(s, wrt), testing::fixed_fd_step(1e-6));
}

/// A section whose six stiffnesses and three inertias are all of order one, so that a relative
/// matrix error measures every term (with steel's EA/EI ~ 1e5 an error in bending would hide).
BeamSection unit_section() { return BeamSection::from_properties(10.0, 6.0, 4.0, 2.0, 3.0, 1.5, 2.0, 0.3, 0.1); }

/// A beam whose nodes' frames differ from its section frames (offsets O_i ≠ I) and whose
/// reference is straight (twist_b = 0) or curved and twisted.
struct Specimen {
  Pose<double> a, b;
  Matrix3d sec_a, sec_b;
  GeometricallyExactBeam beam;
};

Specimen specimen(std::mt19937& rng, const BeamSection& section, double length, const Vector3d& turn_b,
                  const Vector3d& gravity = Vector3d::Zero(), double damping = 0.0) {
  const Matrix3d sec_a = random_rotation(rng);
  const Matrix3d sec_b = sec_a * exp_so3<double>(turn_b);
  Pose<double> a{random_vector3(rng, 1.0), random_rotation(rng)};
  Pose<double> b{a.x + length * sec_a.col(0), random_rotation(rng)};
  return Specimen{a, b, sec_a, sec_b, GeometricallyExactBeam("beam", 0, 1, section, a, b, sec_a, sec_b, gravity, damping)};
}

/// Stiffness and mass matrices of a clamped-free chain of n equal elements of a straight beam of
/// length L along `axis`, assembled by hand from the element tangents at the reference (6 unknowns
/// per node, node 0 removed). Node frames are random rotations: the offsets O_i are exercised.
struct Chain {
  MatrixXd K, M, C;
  Matrix3d sec;  // section frame (world components)
};

Chain cantilever(const BeamSection& section, double L, int n, const Vector3d& axis, unsigned seed,
                 double damping = 0.0) {
  std::mt19937 rng(seed);
  Chain c;
  EXPECT_TRUE(frame_from(axis, Vector3d(0.3, -1.0, 0.2), c.sec));
  std::vector<Pose<double>> nodes;
  for (int k = 0; k <= n; ++k) nodes.push_back(Pose<double>{(L * k / n) * c.sec.col(0), random_rotation(rng)});
  const int N = 6 * (n + 1);
  MatrixXd K = MatrixXd::Zero(N, N), M = MatrixXd::Zero(N, N), C = MatrixXd::Zero(N, N);
  for (int e = 0; e < n; ++e) {
    const GeometricallyExactBeam beam("b", e, e + 1, section, nodes[e], nodes[e + 1], c.sec, c.sec, Vector3d::Zero(),
                                      damping);
    const LocalResidual t = element_tangents(beam, beam_state(configuration(nodes[e], nodes[e + 1])));
    K.block(6 * e, 6 * e, 12, 12) += t.K;
    M.block(6 * e, 6 * e, 12, 12) += t.M;
    C.block(6 * e, 6 * e, 12, 12) += t.C;
  }
  c.K = K.bottomRightCorner(N - 6, N - 6);
  c.M = M.bottomRightCorner(N - 6, N - 6);
  c.C = C.bottomRightCorner(N - 6, N - 6);
  return c;
}

// ------------------------------------------------------------------ tangents

// K = ∂r/∂δ (right-trivialized, node.hpp), C = ∂r/∂v, M = ∂r/∂q̈ against central differences of
// the full residual (elastic + inertia + gravity) on the group, at the straight undeformed
// reference and at random deformed, rotated and moving states with relative rotations between the
// end sections up to ~1.2 rad. Mutations — the material stiffness L0 BᵀCB alone (geometric term
// dropped), C without its −(J̄Ω̄)^ term, a lumped mass — are rejected by the same check.
TEST(BeamTangents, MatchCentralDifferencesOnTheGroup) {
  std::mt19937 rng(7);
  const double L = 0.8;
  std::vector<Specimen> beams;
  beams.push_back(specimen(rng, unit_section(), L, Vector3d::Zero(), Vector3d(0.0, 0.0, -9.81)));
  beams.push_back(specimen(rng, unit_section(), L, Vector3d(0.2, -0.3, 0.25), Vector3d(1.0, 2.0, -9.81)));
  double worst_K = 0.0, worst_C = 0.0, worst_M = 0.0, mutation_K = 1e300, mutation_C = 1e300, mutation_M = 1e300;
  double largest_turn = 0.0;
  int checked = 0;
  for (const Specimen& sp : beams) {
    const GeometricallyExactBeam& beam = sp.beam;
    const VectorXd q_ref = configuration(sp.a, sp.b);
    for (int sample = 0; sample < 6; ++sample) {
      LocalState s = beam_state(q_ref);
      if (sample > 0) {
        // Deform (up to 0.15 L and 0.6 rad per node), then move rigidly; random velocities.
        VectorXd dx(12);
        for (int k = 0; k < 2; ++k) {
          dx.segment<3>(6 * k) = random_vector3(rng, 0.15 * L);
          dx.segment<3>(6 * k + 3) = random_vector3(rng, 0.6 / std::sqrt(3.0));
        }
        s.q = testing::retracted_frames(q_ref, dx);
        const Matrix3d Q = random_rotation(rng);
        const Vector3d c = random_vector3(rng, 1.0);
        for (int k = 0; k < 2; ++k) {
          const Pose<double> p = pose_of(s.q.data() + 7 * k);
          store_pose(c + Q * p.x, Q * p.R, s.q.data() + 7 * k);
        }
        s.v = VectorXd::Random(12) * 3.0;
        s.qdd = VectorXd::Random(12) * 5.0;
      }
      const Pose<double> pa = pose_of(s.q.data()), pb = pose_of(s.q.data() + 7);
      const double turn = log_so3<double>(Matrix3d((pa.R * beam.section_offset(0)).transpose() * pb.R *
                                                   beam.section_offset(1)))
                              .norm();
      largest_turn = std::max(largest_turn, turn);
      const LocalResidual t = element_tangents(beam, s);
      ASSERT_LT((t.r - element_residual(beam, s)).norm(), 1e-12 * t.r.norm() + 1e-14);
      const MatrixXd Kfd = beam_central_differences(beam, s, Wrt::q, L);
      const MatrixXd Cfd = beam_central_differences(beam, s, Wrt::v, L);
      const MatrixXd Mfd = beam_central_differences(beam, s, Wrt::qdd, L);
      const double eK = relative_error(Kfd, t.K), eC = sample ? relative_error(Cfd, t.C) : 0.0;
      const double eM = relative_error(Mfd, t.M);
      EXPECT_LT(eK, 1e-6) << "sample " << sample << ", turn " << turn;
      if (sample) EXPECT_LT(eC, 1e-6) << "sample " << sample;
      else EXPECT_LT(t.C.norm(), 1e-14);  // at rest there is no gyroscopic damping
      EXPECT_LT(eM, 1e-6);
      worst_K = std::max(worst_K, eK);
      worst_C = std::max(worst_C, eC);
      worst_M = std::max(worst_M, eM);
      ++checked;
      if (sample == 0) continue;

      // Mutation 1: K_material = L0 Bᵀ C B with B = ∂ε/∂δ (central differences of the strain):
      // the geometric stiffness Σ_k (C ε)_k L0 ∂²ε_k is missing.
      const MatrixXd B = testing::central_differences_on_frames(
          [&](const VectorXd& x) { return VectorXd(beam.strain(x)); }, s.q, testing::fixed_fd_step(1e-6));
      const MatrixXd Kmat = beam.reference_length() * B.transpose() * beam.section().stiffness().asDiagonal() * B;
      // Mutation 2: C without −(J̄Ω̄(s))^ (the derivative of Ω̄ × J̄Ω̄ through J̄Ω̄).
      MatrixXd Cmut = t.C;
      const Matrix3d J = beam.section().rotary_inertia();
      const Vector3d W0 = beam.section_offset(0).transpose() * s.v.segment<3>(3);
      const Vector3d W1 = beam.section_offset(1).transpose() * s.v.segment<3>(9);
      for (double xi : {0.5 - 0.5 / std::sqrt(3.0), 0.5 + 0.5 / std::sqrt(3.0)}) {
        const double N[2] = {1.0 - xi, xi};
        const Vector3d JW = J * (N[0] * W0 + N[1] * W1);
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j)
            Cmut.block<3, 3>(6 * i + 3, 6 * j + 3) += 0.5 * beam.reference_length() * N[i] * N[j] * beam.section_offset(i) *
                                                       hat<double>(JW) * beam.section_offset(j).transpose();
      }
      // Mutation 3: row-sum lumped mass.
      const MatrixXd Mlump = MatrixXd(t.M.rowwise().sum().asDiagonal());
      mutation_K = std::min(mutation_K, relative_error(Kfd, Kmat));
      mutation_C = std::min(mutation_C, relative_error(Cfd, Cmut));
      mutation_M = std::min(mutation_M, relative_error(Mfd, Mlump));
    }
  }
  std::printf("beam tangents vs central differences (%d states, end-section turn up to %.2f rad): "
              "K %.1e, C %.1e, M %.1e; mutations (smallest error): K without geometric stiffness %.1e, "
              "C without -(J W)^ %.1e, lumped M %.1e\n",
              checked, largest_turn, worst_K, worst_C, worst_M, mutation_K, mutation_C, mutation_M);
  EXPECT_GT(largest_turn, 0.9);
  EXPECT_GT(std::min({mutation_K, mutation_C, mutation_M}), 1e-3);
}

// The logarithm of SO(3) switches from its series to the closed form at sin²θ = 1e-4 and from
// atan2 to the symmetric-part axis at θ = π/2; J_l⁻¹ switches at θ² = 0.25. K stays the exact
// derivative of r on both sides of each switch and at θ = 0 exactly (node and section frames the
// identity, so the relative rotation is exactly I in the reference).
TEST(BeamTangents, ExactAcrossTheSwitchesOfLogAndItsSeries) {
  const Pose<double> a{Vector3d::Zero(), Matrix3d::Identity()}, b{Vector3d::UnitX(), Matrix3d::Identity()};
  const GeometricallyExactBeam beam("b", 0, 1, unit_section(), a, b, Matrix3d::Identity(), Matrix3d::Identity(),
                                    Vector3d::Zero());
  const Vector3d axis = Vector3d(0.3, -0.5, 0.8).normalized();
  double worst = 0.0;
  for (double turn : {0.0, 1e-8, 0.00999, 0.0100001, 0.49, 0.51, 1.5707, 1.5709, 3.0}) {
    const Pose<double> bt{Vector3d(1.02, 0.05, -0.03), exp_so3<double>(Vector3d(turn * axis))};
    const LocalState s = beam_state(configuration(a, turn == 0.0 ? b : bt));
    const double e = relative_error(beam_central_differences(beam, s, Wrt::q, 1.0), element_tangents(beam, s).K);
    EXPECT_LT(e, 1e-8) << "turn " << turn;
    worst = std::max(worst, e);
  }
  std::printf("beam K across the switches of log SO(3) (turn 0 ... 3 rad): worst relative error %.1e\n", worst);
}

// A straight element spinning rigidly (Ω̄_A = Ω̄_B = Ω̄, Ω̄̇_A = Ω̄̇_B) carries half of the rigid
// rod's Euler moment L0 (J̄ Ω̄̇ + Ω̄ × J̄ Ω̄) at each end (the interpolation is exact for it).
TEST(BeamInertia, RigidlySpinningElementGivesEulersEquation) {
  std::mt19937 rng(3);
  const Specimen sp = specimen(rng, unit_section(), 0.7, Vector3d::Zero());
  const Vector3d W = random_vector3(rng, 4.0), Wd = random_vector3(rng, 9.0);
  VectorXd v = VectorXd::Zero(12), qdd = VectorXd::Zero(12);
  for (int i = 0; i < 2; ++i) {
    v.segment<3>(6 * i + 3) = sp.beam.section_offset(i) * W;  // node components of the same Ω̄
    qdd.segment<3>(6 * i + 3) = sp.beam.section_offset(i) * Wd;
  }
  const VectorXd r = element_residual(sp.beam, beam_state(configuration(sp.a, sp.b), v, qdd));
  const Matrix3d J = sp.beam.section().rotary_inertia();
  const Vector3d euler = 0.7 * (J * Wd + W.cross(J * W));
  for (int i = 0; i < 2; ++i)
    EXPECT_LT((sp.beam.section_offset(i).transpose() * r.segment<3>(6 * i + 3) - 0.5 * euler).norm(),
              1e-13 * euler.norm());
}

// Gravity is ∫ N_i ρA g ds = ρA L0 g/2 on each node's translation, scaled by the load factor.
TEST(BeamGravity, HalfTheWeightOnEachNodeTimesTheLoadFactor) {
  std::mt19937 rng(5);
  const Vector3d g(0.5, -1.0, -9.81);
  const Specimen sp = specimen(rng, unit_section(), 1.3, Vector3d(0.1, 0.2, -0.1), g);
  LocalState s = beam_state(configuration(sp.a, sp.b));
  s.load_factor = 0.25;
  const VectorXd r = element_residual(sp.beam, s);
  const Vector3d expected = -0.25 * 0.5 * 2.0 * sp.beam.reference_length() * g;
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT((r.segment<3>(6 * i) - expected).norm(), 1e-13 * expected.norm());
    EXPECT_LT(r.segment<3>(6 * i + 3).norm(), 1e-13);
  }
}

// ------------------------------------------------------------------ closed-form elastic forces

/// Relative Frobenius difference, or the absolute one where the reference vanishes.
double relative_difference(const MatrixXd& fast, const MatrixXd& reference) {
  const double n = reference.norm();
  return n > 0.0 ? (fast - reference).norm() / n : (fast - reference).norm();
}

// The closed-form residual r = Bᵀ C ε (T_SE(3)⁻ᵀ of core/se3.hpp) and its AD1 Jacobian K, which
// evaluate() uses, equal the nested-AD derivatives of W (kernel_jacobian and kernel_second of the
// energy, the former implementation) to round-off: at relative rotations between the end sections
// of exactly 0 (undeformed, and stretched and sheared without rotation), 1e-8, small, around the
// series switches (θ² = 0.25, 1), around the switch of log SO(3) at π/2 and up to 3 rad, and at
// random deformed, rigidly moved states of straight and curved, twisted references whose node
// frames differ from the section frames.
TEST(BeamElasticForces, ClosedFormEqualsNestedADOfTheEnergy) {
  double worst_r = 0.0, worst_K = 0.0, worst_r_zero = 0.0;
  int checked = 0;
  auto compare = [&](const GeometricallyExactBeam& beam, const VectorXd& q, const std::string& what) {
    VectorXd r, r_ref;
    MatrixXd K, K_ref;
    beam.elastic_forces(q, r, &K);
    beam.elastic_forces_from_energy(q, r_ref, &K_ref);
    VectorXd r_only;
    beam.elastic_forces(q, r_only);
    EXPECT_LT((r_only - r).norm(), 1e-14 * (r.norm() + K.norm())) << what;  // double and AD1 paths
    // evaluate() adds exactly these (no inertia or gravity here, at rest).
    const LocalResidual t = element_tangents(beam, beam_state(q));
    EXPECT_EQ((t.K - K).norm(), 0.0) << what;
    const double eK = relative_difference(K, K_ref);
    EXPECT_LT(eK, 1e-10) << what;
    worst_K = std::max(worst_K, eK);
    if (r_ref.norm() > 0.0) {
      const double er = relative_difference(r, r_ref);
      EXPECT_LT(er, 1e-10) << what;
      worst_r = std::max(worst_r, er);
    } else {  // undeformed: both vanish
      EXPECT_LT(r.norm(), 1e-14 * K.norm()) << what;
      worst_r_zero = std::max(worst_r_zero, r.norm() / K.norm());
    }
    ++checked;
  };
  // Identity node and section frames: the relative rotation is exactly the turn given to node B.
  const Pose<double> a{Vector3d::Zero(), Matrix3d::Identity()}, b{Vector3d::UnitX(), Matrix3d::Identity()};
  const Matrix3d I = Matrix3d::Identity();
  const GeometricallyExactBeam straight("b", 0, 1, unit_section(), a, b, I, I, Vector3d::Zero());
  compare(straight, configuration(a, b), "undeformed, turn 0");
  compare(straight, configuration(a, Pose<double>{Vector3d(1.02, 0.05, -0.03), I}), "stretched and sheared, turn 0");
  const Vector3d axis = Vector3d(0.3, -0.5, 0.8).normalized();
  for (double turn : {1e-8, 1e-4, 0.1, 0.4999, 0.5001, 0.9999, 1.0001, 1.5707, 1.5708, 1.5709, 2.0, 3.0}) {
    const Pose<double> bt{Vector3d(1.02, 0.05, -0.03), exp_so3<double>(Vector3d(turn * axis))};
    compare(straight, configuration(a, bt), "turn " + std::to_string(turn));
  }
  // Random specimens and states (as BeamTangents.MatchCentralDifferencesOnTheGroup).
  std::mt19937 rng(23);
  for (int kind = 0; kind < 4; ++kind) {
    const Vector3d turn_b = kind == 0 ? Vector3d::Zero() : random_vector3(rng, 0.4);
    const Specimen sp = specimen(rng, unit_section(), 0.5 + 0.4 * kind, turn_b);
    const VectorXd q_ref = configuration(sp.a, sp.b);
    compare(sp.beam, q_ref, "reference of specimen " + std::to_string(kind));
    for (int sample = 0; sample < 10; ++sample) {
      VectorXd dx(12);
      for (int k = 0; k < 2; ++k) {
        dx.segment<3>(6 * k) = random_vector3(rng, 0.2 * sp.beam.reference_length());
        dx.segment<3>(6 * k + 3) = random_vector3(rng, 0.3 * (1 + sample % 3));
      }
      VectorXd q = testing::retracted_frames(q_ref, dx);
      const Matrix3d Q = random_rotation(rng);
      const Vector3d c = random_vector3(rng, 2.0);
      for (int k = 0; k < 2; ++k) {
        const Pose<double> p = pose_of(q.data() + 7 * k);
        store_pose(c + Q * p.x, Q * p.R, q.data() + 7 * k);
      }
      compare(sp.beam, q, "specimen " + std::to_string(kind) + ", sample " + std::to_string(sample));
    }
  }
  std::printf("beam closed-form r, K vs nested AD of W (%d states, turns 0 ... 3 rad): max relative difference "
              "r %.1e, K %.1e; undeformed |r|/|K| %.1e\n",
              checked, worst_r, worst_K, worst_r_zero);
}

/// Thread CPU time per call of f in µs (best of 5 rounds of n calls); a measurement, not a test.
template <class F>
double microseconds_per_call(F f, int n) {
  auto now = [] {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  };
  double best = 1e300;
  for (int round = 0; round < 5; ++round) {
    const double t0 = now();
    for (int i = 0; i < n; ++i) f();
    best = std::min(best, (now() - t0) / n * 1e6);
  }
  return best;
}

// Cost per evaluation is measured in docs/theory/beam.md (a benchmark, not a timed test).

// internal_force (what the reduction's nonlinear_stiffness differentiates) is evaluate()'s residual
// at rest — zero velocities and accelerations, no load — to the last bit, with and without material
// damping, at deformed states of straight and curved references: skipping the inertia terms
// (zero there) changes no number. Gravity on, so that a load factor would show.
TEST(BeamElasticForces, InternalForceIsTheResidualAtRestBitForBit) {
  std::mt19937 rng(11);
  for (const double eta : {0.0, 0.02})
    for (const Vector3d& turn : {Vector3d(0, 0, 0), Vector3d(0.3, -0.2, 0.4)}) {
      const Specimen sp = specimen(rng, unit_section(), 1.3, turn, Vector3d(0, 0, -9.81), eta);
      for (int trial = 0; trial < 3; ++trial) {
        Pose<double> a = sp.a, b = sp.b;
        a.x += random_vector3(rng, 0.1);
        a.R = a.R * exp_so3<double>(random_vector3(rng, 0.5));
        b.x += random_vector3(rng, 0.1);
        b.R = b.R * exp_so3<double>(random_vector3(rng, 0.5));
        const VectorXd q = configuration(a, b);
        VectorXd r;
        ASSERT_TRUE(sp.beam.internal_force(q, r));
        LocalState s = beam_state(q);
        s.load_factor = 0.0;
        const VectorXd at_rest = element_residual(sp.beam, s);
        ASSERT_EQ(r.size(), 12);
        EXPECT_EQ((r - at_rest).cwiseAbs().maxCoeff(), 0.0) << "eta " << eta << ", trial " << trial;
        EXPECT_GT(r.norm(), 0.0);
      }
    }
}

TEST(BeamStrain, IsObjective) {
  std::mt19937 rng(11);
  const Specimen sp = specimen(rng, unit_section(), 1.1, Vector3d(0.3, 0.1, -0.2));
  for (int sample = 0; sample < 5; ++sample) {
    VectorXd dx(12);
    for (int k = 0; k < 2; ++k) {
      dx.segment<3>(6 * k) = random_vector3(rng, 0.2);
      dx.segment<3>(6 * k + 3) = random_vector3(rng, 0.5);
    }
    const VectorXd q = testing::retracted_frames(configuration(sp.a, sp.b), dx);
    const Matrix3d Q = random_rotation(rng);
    const Vector3d c = random_vector3(rng, 3.0);
    VectorXd qm(14);
    for (int k = 0; k < 2; ++k) {
      const Pose<double> p = pose_of(q.data() + 7 * k);
      store_pose(c + Q * p.x, Q * p.R, qm.data() + 7 * k);
    }
    const GeometricallyExactBeam& b = sp.beam;
    ASSERT_GT(b.strain(q).norm(), 1e-2);
    EXPECT_LT((b.strain(qm) - b.strain(q)).norm(), 1e-13);
    EXPECT_NEAR(b.elastic_energy(qm), b.elastic_energy(q), 1e-13 * b.elastic_energy(q));
    VectorXd f, fm;
    b.output(beam_state(q), f);
    b.output(beam_state(qm), fm);
    EXPECT_LT((fm - f).norm(), 1e-12 * f.norm());
    const LocalResidual t = element_tangents(b, beam_state(q)), tm = element_tangents(b, beam_state(qm));
    MatrixXd P = MatrixXd::Identity(12, 12);
    P.block<3, 3>(0, 0) = Q;
    P.block<3, 3>(6, 6) = Q;
    EXPECT_LT((tm.r - P * t.r).norm(), 1e-12 * t.r.norm());
    EXPECT_LT((tm.K - P * t.K * P.transpose()).norm(), 1e-12 * t.K.norm());
  }
}

// Exactness for constant strain: the beam through H_A and H_B = H_A exp(L0 ξ) (a helix, or a
// circle) has ε = ξ − ε0 for any element length. Pure bending: a straight reference of length
// L0 = ρφ bent onto a circle of radius ρ (nodes at angle 0 and φ, frames tangent, axis 3 normal to
// the plane) gives ε = (0, 0, 0, 0, 0, 1/ρ) — curvature about axis 3, no axial or shear strain.
TEST(BeamStrain, PureBendingAndEveryConstantStrainStateAreExact) {
  std::mt19937 rng(13);
  const double rho = 2.5;
  for (double phi : {1e-3, 0.1, 0.5, 1.0, 2.0, 3.0}) {
    const double L0 = rho * phi;
    const Matrix3d Q = random_rotation(rng);  // the circle's plane, anywhere in space
    const Vector3d c = random_vector3(rng, 1.0);
    const Matrix3d node_a = random_rotation(rng), node_b = random_rotation(rng);  // node frames ≠ sections
    const Pose<double> a0{c, node_a}, b0{c + L0 * Q.col(0), node_b};
    const GeometricallyExactBeam beam("arc", 0, 1, unit_section(), a0, b0, Q, Q, Vector3d::Zero());
    EXPECT_NEAR(beam.reference_length(), L0, 1e-14);  // round-off of positions ~1 m away from 0
    // Deformed: section frames Q Rz(0) and Q Rz(φ), positions on the circle (centre at ρ e2).
    const Matrix3d Rphi = Q * Eigen::AngleAxisd(phi, Vector3d::UnitZ()).toRotationMatrix();
    const Vector3d xb = c + Q * Vector3d(rho * std::sin(phi), rho * (1.0 - std::cos(phi)), 0.0);
    const Pose<double> a{c, Q * beam.section_offset(0).transpose()};
    const Pose<double> b{xb, Rphi * beam.section_offset(1).transpose()};
    Vector6d expected;
    expected << 0, 0, 0, 0, 0, 1.0 / rho;
    const Vector6d e = beam.strain(configuration(a, b));
    EXPECT_LT((e - expected).norm(), 1e-12 / rho) << "phi = " << phi << ": eps = " << e.transpose();
  }
  // Any constant strain ξ on a curved, twisted reference: H_B = H_A exp(L0 ξ_total).
  for (int sample = 0; sample < 5; ++sample) {
    const Specimen sp = specimen(rng, unit_section(), 0.5 + sample, random_vector3(rng, 0.3));
    const GeometricallyExactBeam& beam = sp.beam;
    Vector6d xi;
    xi << random_vector3(rng, 0.1), random_vector3(rng, 0.4) / beam.reference_length();
    const Vector6d total = beam.reference_strain() + xi;
    const double L0 = beam.reference_length();
    const Vector3d kappa = L0 * total.tail<3>();
    const Matrix3d RsA = random_rotation(rng);
    const Vector3d xA = random_vector3(rng, 1.0);
    const Matrix3d RsB = RsA * exp_so3<double>(kappa);
    const Vector3d xB = xA + RsA * (tangent_so3<double>(kappa).transpose() * (L0 * total.head<3>()));
    const Pose<double> a{xA, RsA * beam.section_offset(0).transpose()};
    const Pose<double> b{xB, RsB * beam.section_offset(1).transpose()};
    EXPECT_LT((beam.strain(configuration(a, b)) - xi).norm(), 1e-12);
  }
}

// ------------------------------------------------------------------ linear cantilever

// Shear locking: a cantilever of L/h = 1000 (steel, 20 × 10 mm, L = 10 m) with a tip load P along
// section axis 3, K at the reference assembled for n elements. The element has the same linear
// kinematics as the one-point-quadrature Timoshenko element (γ uses the mean rotation of the
// ends): nodal rotations are exact and the deflection integrates them by the trapezoidal rule, so
//   δ_n = PL³/(3EI2) (1 − 1/(4n²)) + PL/GA3,
// an error ∝ n⁻² with no (L/h)² locking factor (a locking element would be stiff by ~1e6 here).
// Checked: δ_n matches that formula for L/h = 1000 and for a stocky L/h = 10 (where the shear
// term is 0.8 % of δ), is within 1.6 % of Timoshenko's PL³/(3EI2) + PL/GA3 at n = 4 for L/h = 1000,
// and the fitted order is 2.
TEST(BeamCantilever, HasNoShearLockingAndConvergesAsNToMinusTwo) {
  const double b = 0.02, h = 0.01, P = 1.0;
  const BeamSection sec = BeamSection::from_material(210e9, 0.3, 7850.0, SectionShape::rectangle(b, h));
  for (double slenderness : {1000.0, 10.0}) {
    const double L = slenderness * h;
    const double timoshenko = P * L * L * L / (3.0 * sec.EI2()) + P * L / sec.GA3();
    std::vector<double> ns, errors;
    for (int n : {1, 2, 4, 8, 16, 32}) {
      const Chain c = cantilever(sec, L, n, Vector3d(1.0, 2.0, 2.0), 17u + static_cast<unsigned>(n));
      VectorXd f = VectorXd::Zero(c.K.rows());
      f.segment<3>(6 * (n - 1)) = P * c.sec.col(2);
      const VectorXd u = c.K.ldlt().solve(f);
      ASSERT_LT((c.K * u - f).norm(), 1e-13 * c.K.norm() * u.norm());  // backward stable solve
      const double tip = u.segment<3>(6 * (n - 1)).dot(c.sec.col(2));
      const double predicted = P * L * L * L / (3.0 * sec.EI2()) * (1.0 - 0.25 / (n * n)) + P * L / sec.GA3();
      const double err = std::fabs(tip - timoshenko) / timoshenko;
      std::printf("cantilever L/h = %4.0f, n = %2d: tip %.10e m, Timoshenko %.10e m, relative error %.3e "
                  "(1/(4n^2) = %.3e)\n",
                  slenderness, n, tip, timoshenko, err, 0.25 / (n * n));
      EXPECT_NEAR(tip, predicted, 1e-7 * timoshenko) << "L/h = " << slenderness << ", n = " << n;
      // Sideways displacement vanishes (the load is along a principal axis).
      EXPECT_LT(std::fabs(u.segment<3>(6 * (n - 1)).dot(c.sec.col(1))), 1e-8 * timoshenko);
      if (n == 4 && slenderness == 1000.0) EXPECT_LT(err, 0.016);
      if (n >= 2) {
        ns.push_back(n);
        errors.push_back(err);
      }
    }
    const double order = -testing::fitted_slope(ns, errors);
    std::printf("cantilever L/h = %4.0f tip deflection: fitted order %.3f\n", slenderness, order);
    if (slenderness == 1000.0) EXPECT_NEAR(order, 2.0, 0.05);
  }
}

// Roll-up (the classic large-rotation test; the scene-level version is BeamRollup in test_beam_benchmarks.cpp): a cantilever under an end moment M about section axis
// 3 bends into a circle of radius EI3/M; at M = 2π EI3/L it closes into a full circle, tip back at
// the root with its frame back to the root's. Solved by Newton's method with K (and the dead
// moment's own tangent −(RᵀM)^) in 16 load steps on 4 elements (90° each) (the last iterations converge
// quadratically: corrections 3e-6, 1e-10, 1e-15): the strain measure being exact for constant
// curvature, every step lands on the exact circle to round-off, whatever n.
TEST(BeamLargeRotation, EndMomentRollsTheCantileverIntoAnExactCircle) {
  const int n = 4;
  const double L = 1.0;
  const BeamSection sec = BeamSection::from_material(210e9, 0.3, 7850.0, SectionShape::rectangle(0.02, 0.01));
  const Matrix3d I = Matrix3d::Identity();
  std::vector<Pose<double>> ref;
  for (int k = 0; k <= n; ++k) ref.push_back(Pose<double>{Vector3d(L * k / n, 0.0, 0.0), I});
  std::vector<GeometricallyExactBeam> beams;
  for (int e = 0; e < n; ++e) beams.emplace_back("b", e, e + 1, sec, ref[e], ref[e + 1], I, I, Vector3d::Zero());
  VectorXd q(7 * (n + 1));
  for (int k = 0; k <= n; ++k) store_pose(ref[k].x, ref[k].R, q.data() + 7 * k);
  const int N = 6 * n;  // node 0 clamped
  int iterations = 0;
  double worst_position = 0.0;
  const int steps = 16;
  for (int step = 1; step <= steps; ++step) {
    const double lambda = static_cast<double>(step) / steps;
    const Vector3d M(0.0, 0.0, lambda * 2.0 * kPi * sec.EI3() / L);
    for (int it = 0;; ++it) {
      ASSERT_LT(it, 20) << "Newton did not converge at load step " << step;
      VectorXd r = VectorXd::Zero(6 * (n + 1));
      MatrixXd K = MatrixXd::Zero(6 * (n + 1), 6 * (n + 1));
      for (int e = 0; e < n; ++e) {
        const LocalResidual t = element_tangents(beams[e], beam_state(q.segment<14>(7 * e)));
        r.segment<12>(6 * e) += t.r;
        K.block<12, 12>(6 * e, 6 * e) += t.K;
      }
      const Matrix3d Rt = pose_of(q.data() + 7 * n).R;
      r.segment<3>(6 * n + 3) -= Rt.transpose() * M;  // dead moment, body components
      K.block<3, 3>(6 * n + 3, 6 * n + 3) -= hat<double>(Vector3d(Rt.transpose() * M));
      const VectorXd dx = -K.bottomRightCorner(N, N).partialPivLu().solve(r.tail(N));
      for (int k = 1; k <= n; ++k) retract(NodeKind::Frame3D, q.data() + 7 * k, dx.data() + 6 * (k - 1), q.data() + 7 * k);
      ++iterations;
      if (dx.cwiseAbs().maxCoeff() < 1e-13) break;
    }
    const double rho = L / (2.0 * kPi * lambda);
    for (int k = 1; k <= n; ++k) {
      const double phi = (L * k / n) / rho;
      const Vector3d exact = (lambda == 1.0 && k == n) ? Vector3d::Zero()
                                                       : Vector3d(rho * std::sin(phi), rho * (1.0 - std::cos(phi)), 0.0);
      worst_position = std::max(worst_position, (pose_of(q.data() + 7 * k).x - exact).norm());
    }
    for (int e = 0; e < n; ++e) {
      Vector6d expected;
      expected << 0, 0, 0, 0, 0, 1.0 / rho;
      EXPECT_LT((beams[e].strain(q.segment<14>(7 * e)) - expected).norm(), 1e-9 / rho);
    }
  }
  const Pose<double> tip = pose_of(q.data() + 7 * n);
  std::printf("roll-up, %d elements, %d load steps: %d Newton iterations, worst nodal position error %.1e m, "
              "tip at %.1e m from the root, tip frame turned by %.1e rad\n",
              n, steps, iterations, worst_position, tip.x.norm(), log_so3<double>(tip.R).norm());
  EXPECT_LT(worst_position, 1e-10);
  EXPECT_LT(log_so3<double>(tip.R).norm(), 1e-10);
}

// Modal frequencies: K φ = ω² M φ of the clamped cantilever (K and M at the reference) against
// Euler–Bernoulli, ω_k = (β_k L)² sqrt(EI2/(ρA L⁴)), β_1 L = 1.875104068711961,
// β_2 L = 4.694091132974175, for bending along axis 3, with L/h = 1000 so that shear and rotary
// inertia change ω by less than 1e-5. Solved as M φ = (1/ω²) K φ (Cholesky of K): the lowest modes
// are then the best conditioned, whereas a Cholesky of M would mix in round-off of the very high
// rotational frequencies (ρI is 1e-7 of ρA L²).
TEST(BeamCantilever, FrequenciesConvergeToEulerBernoulli) {
  const double b = 0.02, h = 0.01, L = 1000.0 * h;
  const BeamSection sec = BeamSection::from_material(210e9, 0.3, 7850.0, SectionShape::rectangle(b, h));
  const double beta[2] = {1.875104068711961, 4.694091132974175};
  std::vector<double> ns, e1, e2;
  for (int n : {4, 8, 16, 32}) {
    const Chain c = cantilever(sec, L, n, Vector3d(-1.0, 0.5, 2.0), 29u + static_cast<unsigned>(n));
    const MatrixXd K = 0.5 * (c.K + c.K.transpose());
    Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(c.M, K);
    ASSERT_EQ(es.info(), Eigen::Success);
    // Modes bending along axis 3, lowest frequency first (μ = 1/ω² descending).
    std::vector<double> omega;
    for (Eigen::Index k = es.eigenvalues().size() - 1; k >= 0 && omega.size() < 2; --k) {
      const VectorXd phi = es.eigenvectors().col(k);
      double along3 = 0.0, rest = 0.0;
      for (int node = 0; node < n; ++node) {
        const Vector3d u = phi.segment<3>(6 * node);
        along3 += std::pow(u.dot(c.sec.col(2)), 2);
        rest += std::pow(u.dot(c.sec.col(1)), 2) + std::pow(u.dot(c.sec.col(0)), 2);
      }
      if (along3 > 0.999 * (along3 + rest)) omega.push_back(1.0 / std::sqrt(es.eigenvalues()[k]));
    }
    ASSERT_EQ(omega.size(), 2u);
    double err[2];
    for (int k = 0; k < 2; ++k) {
      const double exact = beta[k] * beta[k] * std::sqrt(sec.EI2() / (sec.rhoA() * std::pow(L, 4)));
      err[k] = (omega[k] - exact) / exact;
    }
    std::printf("cantilever modes n = %2d: omega1 %.8f rad/s (error %+.3e), omega2 %.8f rad/s (error %+.3e)\n", n,
                omega[0], err[0], omega[1], err[1]);
    ns.push_back(n);
    e1.push_back(std::fabs(err[0]));
    e2.push_back(std::fabs(err[1]));
  }
  const double p1 = -testing::fitted_slope(ns, e1), p2 = -testing::fitted_slope(ns, e2);
  std::printf("cantilever frequencies: fitted orders %.3f (mode 1), %.3f (mode 2)\n", p1, p2);
  EXPECT_LT(e1.back(), 2e-4);  // measured 1.2e-4 and 2.4e-3 at n = 32 (≈ 0.12/n² and 2.5/n²)
  EXPECT_LT(e2.back(), 3e-3);
  EXPECT_NEAR(p1, 2.0, 0.1);
  EXPECT_NEAR(p2, 2.0, 0.15);
}

// ------------------------------------------------------------------ sections

// Hand values: rectangle 40 × 20 mm (A = 8e-4 m², I2 = bh³/12, I3 = hb³/12, J = 0.2287 b h³ from
// Saint-Venant's table for b/h = 2, Timoshenko & Goodier §109: k1 = 0.229; square: 0.1406),
// circle d = 30 mm (πd⁴/64, πd⁴/32), tube 50 × 5 mm (π(Ro⁴ − Ri⁴)/4), Cowper's coefficients at
// ν = 0.3 (rectangle 0.8497, circle 0.8864, tube (m = 0.8) 0.5411), and G = E/(2(1 + ν)).
TEST(BeamSection, FactoriesMatchHandValues) {
  const double E = 200e9, nu = 0.3, rho = 7800.0, G = E / (2.0 * (1.0 + nu));
  {
    const SectionGeometry g = section_geometry(SectionShape::rectangle(0.04, 0.02));
    EXPECT_NEAR(g.area, 8e-4, 1e-18);
    EXPECT_NEAR(g.I2, 0.04 * 8e-6 / 12.0, 1e-22);
    EXPECT_NEAR(g.I3, 0.02 * 6.4e-5 / 12.0, 1e-22);
    EXPECT_NEAR(g.torsion / (0.04 * 8e-6), 0.228682, 2e-6);  // k1(b/h = 2), Timoshenko & Goodier: 0.229
    EXPECT_NEAR(section_geometry(SectionShape::rectangle(0.02, 0.04)).torsion, g.torsion, 1e-20);  // b < h
    EXPECT_NEAR(section_geometry(SectionShape::rectangle(0.03, 0.03)).torsion / std::pow(0.03, 4), 0.140577, 2e-6);
    EXPECT_NEAR(section_geometry(SectionShape::rectangle(1.0, 0.01)).torsion / (1.0 * 1e-6), 1.0 / 3.0 - 0.0021, 1e-5);
    const double k = 10.0 * 1.3 / (12.0 + 3.3);
    EXPECT_NEAR(k, 0.8497, 1e-4);
    const BeamSection s = BeamSection::from_material(E, nu, rho, SectionShape::rectangle(0.04, 0.02));
    EXPECT_DOUBLE_EQ(s.EA(), E * 8e-4);
    EXPECT_DOUBLE_EQ(s.GA2(), k * G * 8e-4);
    EXPECT_DOUBLE_EQ(s.GA3(), k * G * 8e-4);
    EXPECT_DOUBLE_EQ(s.GJ(), G * g.torsion);
    EXPECT_DOUBLE_EQ(s.EI2(), E * g.I2);
    EXPECT_DOUBLE_EQ(s.EI3(), E * g.I3);
    EXPECT_DOUBLE_EQ(s.rhoA(), rho * 8e-4);
    EXPECT_DOUBLE_EQ(s.rhoI2(), rho * g.I2);
    EXPECT_DOUBLE_EQ(s.rhoI3(), rho * g.I3);
    EXPECT_DOUBLE_EQ(s.rhoI_polar(), rho * (g.I2 + g.I3));
  }
  {
    const double d = 0.03;
    const SectionGeometry g = section_geometry(SectionShape::circle(d));
    EXPECT_NEAR(g.area, 7.0685834705770345e-4, 1e-18);
    EXPECT_NEAR(g.I2, 3.9760782021995817e-8, 1e-22);
    EXPECT_EQ(g.I2, g.I3);
    EXPECT_NEAR(g.torsion, 7.952156404399163e-8, 1e-22);
    EXPECT_NEAR(cowper_shear_coefficient(SectionShape::circle(d), nu), 6.0 * 1.3 / 8.8, 1e-15);
    EXPECT_NEAR(cowper_shear_coefficient(SectionShape::circle(d), nu), 0.886364, 1e-6);
  }
  {
    const SectionShape t = SectionShape::tube(0.05, 0.005);  // Ro = 25 mm, Ri = 20 mm, m = 0.8
    const SectionGeometry g = section_geometry(t);
    EXPECT_NEAR(g.area, kPi * (625e-6 - 400e-6), 1e-18);
    EXPECT_NEAR(g.I2, kPi * (3.90625e-7 - 1.6e-7) / 4.0, 1e-22);
    EXPECT_NEAR(g.torsion, 2.0 * g.I2, 1e-22);
    const double m2 = 0.64, p = (1 + m2) * (1 + m2);
    EXPECT_NEAR(cowper_shear_coefficient(t, nu), 6.0 * 1.3 * p / (8.8 * p + 23.6 * m2), 1e-15);
    EXPECT_NEAR(cowper_shear_coefficient(t, nu), 0.5411, 1e-4);
    // Thin-walled limit 2(1 + ν)/(4 + 3ν) and solid limit (the circle).
    EXPECT_NEAR(cowper_shear_coefficient(SectionShape::tube(1.0, 1e-6), nu), 2.6 / 4.9, 1e-5);
    EXPECT_NEAR(cowper_shear_coefficient(SectionShape::tube(0.03, 0.015), nu),
                cowper_shear_coefficient(SectionShape::circle(0.03), nu), 1e-15);
    EXPECT_NEAR(section_geometry(SectionShape::tube(0.03, 0.015)).I2, section_geometry(SectionShape::circle(0.03)).I2,
                1e-22);
  }
  {
    const BeamSection s = BeamSection::from_properties(1, 2, 3, 4, 5, 6, 7, 8, 9);
    EXPECT_EQ(s.stiffness(), (Vector6d() << 1, 2, 3, 4, 5, 6).finished());
    EXPECT_EQ(s.rotary_inertia(), Vector3d(17, 8, 9).asDiagonal().toDenseMatrix());
    EXPECT_EQ(BeamSection::from_properties(1, 2, 3, 4, 5, 6, 7, 8, 9, 20.0).rhoI_polar(), 20.0);
  }
}

/// The message of the std::invalid_argument thrown by f, or "" if none.
template <class F>
std::string message_of(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(BeamSection, RejectsInvalidInputWithAClearMessage) {
  const auto rect = SectionShape::rectangle(0.02, 0.01);
  EXPECT_NE(message_of([&] { BeamSection::from_material(-1.0, 0.3, 7800, rect); }).find("Young's modulus"),
            std::string::npos);
  EXPECT_NE(message_of([&] { BeamSection::from_material(1e9, 0.5, 7800, rect); }).find("Poisson"), std::string::npos);
  EXPECT_NE(message_of([&] { BeamSection::from_material(1e9, -1.0, 7800, rect); }).find("Poisson"), std::string::npos);
  EXPECT_NE(message_of([&] { BeamSection::from_material(1e9, 0.3, 0.0, rect); }).find("density"), std::string::npos);
  EXPECT_NE(message_of([&] { SectionShape::rectangle(0.0, 0.01); }).find("width"), std::string::npos);
  EXPECT_NE(message_of([&] { SectionShape::circle(std::nan("")); }).find("diameter"), std::string::npos);
  EXPECT_NE(message_of([&] { SectionShape::tube(0.02, 0.011); }).find("exceeds the outer radius"), std::string::npos);
  EXPECT_NE(message_of([&] { BeamSection::from_properties(1, 2, 3, 4, 5, 0, 7, 8, 9); }).find("EI3"),
            std::string::npos);
  EXPECT_NE(message_of([&] { BeamSection::from_properties(1, 2, 3, 4, 5, 6, 7, 8, 9, -1.0); }).find("rhoI_polar"),
            std::string::npos);
  // The element: same node twice, a non-rotation, zero length, a half-turn between the ends.
  const BeamSection s = unit_section();
  const Pose<double> a{Vector3d::Zero(), Matrix3d::Identity()}, b{Vector3d::UnitX(), Matrix3d::Identity()};
  const Matrix3d I = Matrix3d::Identity();
  EXPECT_NE(message_of([&] { GeometricallyExactBeam("e", 1, 1, s, a, b, I, I, Vector3d::Zero()); }).find("two different"),
            std::string::npos);
  EXPECT_NE(message_of([&] { GeometricallyExactBeam("e", 0, 1, s, a, b, 2.0 * I, I, Vector3d::Zero()); })
                .find("not a rotation"),
            std::string::npos);
  EXPECT_NE(message_of([&] { GeometricallyExactBeam("e", 0, 1, s, a, a, I, I, Vector3d::Zero()); }).find("zero"),
            std::string::npos);
  const Matrix3d half = Eigen::AngleAxisd(kPi, Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NE(message_of([&] { GeometricallyExactBeam("e", 0, 1, s, a, b, I, half, Vector3d::Zero()); }).find("pi"),
            std::string::npos);
}

TEST(BeamOutput, NamesAndValuesAreSectionForcesThenStrains) {
  std::mt19937 rng(19);
  const Specimen sp = specimen(rng, unit_section(), 1.0, Vector3d::Zero());
  const std::vector<std::string> names{"N",   "V2",           "V3",             "T",
                                       "M2",  "M3",           "axial_strain",   "shear_strain_2",
                                       "shear_strain_3", "twist", "curvature_2", "curvature_3"};
  EXPECT_EQ(sp.beam.output_names(), names);
  EXPECT_STREQ(sp.beam.type(), "beam");
  VectorXd dx = VectorXd::Zero(12);
  dx << 0.01, -0.02, 0.03, 0.1, -0.05, 0.2, 0.02, 0.01, -0.01, -0.1, 0.3, 0.05;
  const VectorXd q = testing::retracted_frames(configuration(sp.a, sp.b), dx);
  VectorXd out;
  sp.beam.output(beam_state(q), out);
  ASSERT_EQ(out.size(), 12);
  const Vector6d e = sp.beam.strain(q);
  EXPECT_LT((out.tail<6>() - e).norm(), 1e-15);
  EXPECT_LT((out.head<6>() - unit_section().stiffness().cwiseProduct(e)).norm(), 1e-14);
}


// ------------------------------------------------------------------ material damping

// Kelvin–Voigt damping f = C (ε + η ε̇) (geometrically_exact_beam.hpp, Material damping):
// K = ∂r/∂δ at fixed v, C = ∂r/∂v, M = ∂r/∂q̈ against central differences on the group at the
// reference and at random deformed, rotated and moving states (η = 0.2 s with velocities up to
// 3: the viscous section forces are of the order of the elastic ones); B_ε = ∂ε/∂δ against central
// differences of the strain; no force along a rigid motion; the dissipated power vᵀ(r(v) − r(0))
// equals L0 η ε̇ᵀ C ε̇ ≥ 0. Mutations — the undamped element's K and C (the damping's q-derivative
// and C_t dropped) — are rejected by the same check.
TEST(BeamDamping, TangentsMatchCentralDifferencesOnTheGroup) {
  std::mt19937 rng(11);
  const double L = 0.8, eta = 0.2;
  double worst_K = 0.0, worst_C = 0.0, worst_B = 0.0, mutation_K = 1e300, mutation_C = 1e300;
  for (const Vector3d& turn : {Vector3d(0.0, 0.0, 0.0), Vector3d(0.2, -0.3, 0.25)}) {
    std::mt19937 twin_rng = rng;  // the same specimen without damping
    const Specimen sp = specimen(rng, unit_section(), L, turn, Vector3d(0.0, 0.0, -9.81), eta);
    const Specimen elastic = specimen(twin_rng, unit_section(), L, turn, Vector3d(0.0, 0.0, -9.81));
    const VectorXd q_ref = configuration(sp.a, sp.b);
    for (int sample = 0; sample < 5; ++sample) {
      LocalState s = beam_state(q_ref);
      VectorXd dx(12);
      for (int k = 0; k < 2; ++k) {
        dx.segment<3>(6 * k) = random_vector3(rng, 0.15 * L);
        dx.segment<3>(6 * k + 3) = random_vector3(rng, 0.6 / std::sqrt(3.0));
      }
      if (sample > 0) s.q = testing::retracted_frames(q_ref, dx);
      s.v = VectorXd::Random(12) * 3.0;
      s.qdd = VectorXd::Random(12) * 5.0;
      const LocalResidual t = element_tangents(sp.beam, s);
      ASSERT_LT((t.r - element_residual(sp.beam, s)).norm(), 1e-12 * t.r.norm());
      const MatrixXd Kfd = beam_central_differences(sp.beam, s, Wrt::q, L);
      const MatrixXd Cfd = beam_central_differences(sp.beam, s, Wrt::v, L);
      const MatrixXd Mfd = beam_central_differences(sp.beam, s, Wrt::qdd, L);
      const double eK = relative_error(Kfd, t.K), eC = relative_error(Cfd, t.C);
      EXPECT_LT(eK, 1e-6) << "sample " << sample;
      EXPECT_LT(eC, 1e-6) << "sample " << sample;
      EXPECT_LT(relative_error(Mfd, t.M), 1e-6);
      const MatrixXd Bfd = testing::central_differences_on_frames(
          [&](const VectorXd& x) { return VectorXd(sp.beam.strain(x)); }, s.q, testing::fixed_fd_step(1e-6));
      const Eigen::Matrix<double, 6, 12> B = sp.beam.strain_rate_operator(s.q);
      const double eB = relative_error(Bfd, B);
      EXPECT_LT(eB, 1e-7);
      // Dissipated power: vᵀ(r_damped − r_elastic) at the same state (the undamped twin removes the
      // elastic, inertial and gyroscopic parts) is L0 η ε̇ᵀ C ε̇.
      LocalState moving = s;
      moving.qdd.setZero();
      moving.load_factor = 0.0;
      const Vector6d rate = B * s.v;
      const double power = s.v.dot(element_residual(sp.beam, moving) - element_residual(elastic.beam, moving));
      const double expected = sp.beam.reference_length() * eta * rate.dot(unit_section().stiffness().cwiseProduct(rate));
      EXPECT_GT(expected, 0.0);
      EXPECT_NEAR(power, expected, 1e-10 * expected);
      const LocalResidual te = element_tangents(elastic.beam, s);
      worst_K = std::max(worst_K, eK);
      worst_C = std::max(worst_C, eC);
      worst_B = std::max(worst_B, eB);
      mutation_K = std::min(mutation_K, relative_error(Kfd, te.K));
      mutation_C = std::min(mutation_C, relative_error(Cfd, te.C));
      // A rigid motion (translation u, world angular velocity w): ẋ_i = u + w × x_i, Ω_i = R_iᵀ w.
      const Vector3d u = random_vector3(rng, 2.0), w = random_vector3(rng, 2.0);
      LocalState rigid = moving;
      for (int k = 0; k < 2; ++k) {
        const Pose<double> pk = pose_of(s.q.data() + 7 * k);
        rigid.v.segment<3>(6 * k) = u + w.cross(pk.x);
        rigid.v.segment<3>(6 * k + 3) = pk.R.transpose() * w;
      }
      EXPECT_LT((sp.beam.strain_rate_operator(s.q) * rigid.v).norm(), 1e-12 * rigid.v.norm());
      const VectorXd rd = element_residual(sp.beam, rigid), re = element_residual(elastic.beam, rigid);
      EXPECT_LT((rd - re).norm(), 1e-12 * std::max(1.0, re.norm()));
    }
  }
  std::printf("damped beam tangents vs central differences: K %.1e, C %.1e, B_eps %.1e; mutations (undamped K, C): "
              "%.1e, %.1e\n", worst_K, worst_C, worst_B, mutation_K, mutation_C);
  EXPECT_GT(std::min(mutation_K, mutation_C), 1e-3);
}

// At rest on the straight reference C_t = η L0 B_εᵀ C B_ε = η K (the geometric stiffness vanishes
// with the section forces): stiffness-proportional (Rayleigh) damping, whose modes are the
// undamped ones, each with the damping ratio ζ = φᵀCφ / (2 ω φᵀMφ) = η ω / 2 (the modal equation
// q̈ + η ω² q̇ + ω² q = 0; Clough & Penzien, Dynamics of Structures, 2nd ed., §12-5). The first
// bending mode of a cantilever, ω1 = 1.8751² √(EI/(ρA L⁴)) (Euler–Bernoulli), then has
// ζ1 = η ω1/2: checked with η chosen for ζ1 = 0.02 against that analytic value to 1e-3 relative
// (the n = 16 mesh's frequency error, 0.12/n² = 4.7e-4, measured in
// BeamCantilever.FrequenciesConvergeToEulerBernoulli), and to 1e-10 against η ω/2 of the mesh's own ω.
TEST(BeamDamping, FirstBendingModeHasTheDampingRatioEtaOmegaOverTwo) {
  const double b = 0.02, h = 0.01, L = 1000.0 * h, n = 16;
  const BeamSection elastic = BeamSection::from_material(210e9, 0.3, 7850.0, SectionShape::rectangle(b, h));
  const double omega_eb = std::pow(1.875104068711961, 2) * std::sqrt(elastic.EI2() / (elastic.rhoA() * std::pow(L, 4)));
  const double zeta_target = 0.02, eta = 2.0 * zeta_target / omega_eb;
  const Chain c = cantilever(elastic, L, static_cast<int>(n), Vector3d(-1.0, 0.5, 2.0), 45u, eta);
  EXPECT_LT((c.C - eta * c.K).norm(), 1e-12 * eta * c.K.norm());
  const MatrixXd K = 0.5 * (c.K + c.K.transpose());
  Eigen::GeneralizedSelfAdjointEigenSolver<MatrixXd> es(c.M, K);
  ASSERT_EQ(es.info(), Eigen::Success);
  // The lowest mode bending along axis 3 (EI2 < EI3: the lowest of all), μ = 1/ω² largest.
  const Eigen::Index k = es.eigenvalues().size() - 1;
  const VectorXd phi = es.eigenvectors().col(k);
  double along3 = 0.0, all = 0.0;
  for (int node = 0; node < n; ++node) {
    along3 += std::pow(phi.segment<3>(6 * node).dot(c.sec.col(2)), 2);
    all += phi.segment<3>(6 * node).squaredNorm();
  }
  ASSERT_GT(along3, 0.999 * all);
  const double omega = 1.0 / std::sqrt(es.eigenvalues()[k]);
  const double zeta = phi.dot(c.C * phi) / (2.0 * omega * phi.dot(c.M * phi));
  std::printf("damped cantilever: omega1 %.8f rad/s (Euler-Bernoulli %.8f), eta %.6e s, zeta1 %.8f (eta omega/2 = %.8f, "
              "analytic %.8f)\n", omega, omega_eb, eta, zeta, 0.5 * eta * omega, zeta_target);
  EXPECT_NEAR(zeta, 0.5 * eta * omega, 1e-8 * zeta);  // round-off of the 96-unknown eigenvectors
  EXPECT_NEAR(zeta, zeta_target, 1e-3 * zeta_target);
}

TEST(BeamDamping, ZeroIsTheElasticElementAndANegativeEtaIsRefused) {
  std::mt19937 rng(3);
  std::mt19937 twin = rng;
  const Specimen a = specimen(rng, unit_section(), 0.8, Vector3d(0.1, 0.2, -0.1));
  const Specimen z = specimen(twin, unit_section(), 0.8, Vector3d(0.1, 0.2, -0.1), Vector3d::Zero(), 0.0);
  LocalState s = beam_state(configuration(a.a, a.b), VectorXd::Random(12), VectorXd::Random(12));
  const LocalResidual ta = element_tangents(a.beam, s), tz = element_tangents(z.beam, s);
  EXPECT_EQ(ta.r, tz.r);
  EXPECT_EQ(ta.K, tz.K);
  EXPECT_EQ(ta.C, tz.C);
  const std::string m = message_of([&] {
    (void)GeometricallyExactBeam("b", 0, 1, unit_section(), a.a, a.b, a.sec_a, a.sec_b, Vector3d::Zero(), -0.1);
  });
  EXPECT_NE(m.find("material damping eta must be zero or positive"), std::string::npos) << m;
}

}  // namespace
}  // namespace alphaflex
