// The planar geometrically exact beam on SE(2) (elements/planar_beam.hpp):
//  - K, C, M are the derivatives of r (central differences at random deformed, moving states; K
//    also equals the automatic-differentiation Hessian of W to round-off, across the series switch
//    of g(α) = (α/2)/sin(α/2));
//  - rigid motions (any rotation, the angles being additive) give zero strain and force, and the
//    strain, residual and tangent are objective;
//  - a circular arc of nodes with tangent sections gives ε = (0, 0, 1/ρ) exactly for any element
//    length; a uniform stretch gives N = EA ε (patch test);
//  - no shear locking: a slender cantilever (L/h = 1000) matches Timoshenko up to O(n⁻²);
//  - it agrees with the spatial GeometricallyExactBeam restricted to the plane;
//  - inertia, gravity, outputs, input validation, and the cost of one evaluation.
// Numbers measured here are quoted in docs/theory/planar_beam.md.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "alphaflex/core/autodiff.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/beam_section.hpp"
#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "alphaflex/elements/planar_beam.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "test_support.hpp"

namespace alphaflex {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

using testing::kPi;
using testing::relative_error;
using testing::uniform;

// ------------------------------------------------------------------ helpers

Vector2d direction(double angle) { return Vector2d(std::cos(angle), std::sin(angle)); }

VectorXd local_q(const Vector3d& a, const Vector3d& b) {
  VectorXd q(6);
  q << a, b;
  return q;
}

LocalState planar_state(const VectorXd& q, const VectorXd& v = VectorXd::Zero(6), const VectorXd& qdd = VectorXd::Zero(6)) {
  return testing::local_state(q, v, qdd);
}

using testing::element_residual;
using testing::element_tangents;

/// Central differences of r with respect to q, q̇ or q̈ (vector spaces; test_support.hpp's step
/// rule h = 1e-6 max(1, |x_j|)).
using testing::Wrt;
MatrixXd planar_central_differences(const Element& e, const LocalState& s, Wrt wrt) {
  return testing::central_differences(testing::element_residual_of(e, s, wrt), testing::variable(s, wrt));
}

/// Stiffnesses and inertias all of order one, so that a relative matrix error measures every term
/// (with steel's EA/EI ~ 1e5 an error in bending would hide).
struct Props {
  double EA = 10.0, GA = 6.0, EI = 1.5, rhoA = 2.0, rhoI = 0.3;
};

Vector3d p_stiffness(const Props& p) { return Vector3d(p.EA, p.GA, p.EI); }

/// A beam from A = (x_a, θ_a) along `angle` with length L whose end sections turn by `turn`
/// (a reference arc; 0: straight). The node angles are random (offsets φ_i ≠ 0).
struct PlanarSpecimen {
  Vector3d a, b;
  double sec_a, sec_b;
  PlanarBeam beam;
};

PlanarSpecimen planar_specimen(std::mt19937& rng, const Props& p, double L, double turn,
                  const Vector2d& gravity = Vector2d::Zero()) {
  const double sec_a = uniform(rng, -kPi, kPi), sec_b = sec_a + turn;
  // Chord of an arc of length L turning by `turn`: length L sinc(turn/2), at turn/2 from section A.
  const double chord = std::abs(turn) < 1e-12 ? L : L * std::sin(0.5 * turn) / (0.5 * turn);
  const Vector2d xa(uniform(rng, -1, 1), uniform(rng, -1, 1));
  const Vector2d xb = xa + chord * direction(sec_a + 0.5 * turn);
  const Vector3d a(xa.x(), xa.y(), uniform(rng, -kPi, kPi)), b(xb.x(), xb.y(), uniform(rng, -kPi, kPi));
  return PlanarSpecimen{a, b, sec_a, sec_b,
                  PlanarBeam("beam", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, a, b, sec_a, sec_b, gravity)};
}

/// A node's displacement: up to 0.2 in x and y, 0.6 rad in θ.
Vector3d small_deformation(std::mt19937& rng) {
  return Vector3d(uniform(rng, -0.2, 0.2), uniform(rng, -0.2, 0.2), uniform(rng, -0.6, 0.6));
}

/// q after the rigid motion x → c + R(β) x, θ → θ + β of both nodes.
VectorXd moved(const VectorXd& q, double beta, const Vector2d& c) {
  VectorXd out(6);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(beta).toRotationMatrix();
  for (int k = 0; k < 2; ++k) {
    out.segment<2>(3 * k) = c + R * q.segment<2>(3 * k);
    out[3 * k + 2] = q[3 * k + 2] + beta;
  }
  return out;
}

/// q_ref with the nodes moved by up to 0.3 L and the angles by up to ±1.2 rad, then a rigid motion
/// by up to ±20 rad (additive angles).
VectorXd deformed_and_moved(std::mt19937& rng, const VectorXd& q_ref, double L) {
  VectorXd dq(6);
  for (int k = 0; k < 2; ++k) {
    dq.segment<2>(3 * k) = Vector2d(uniform(rng, -0.3, 0.3), uniform(rng, -0.3, 0.3)) * L;
    dq[3 * k + 2] = uniform(rng, -1.2, 1.2);
  }
  return moved(q_ref + dq, uniform(rng, -20.0, 20.0), Vector2d(uniform(rng, -2, 2), uniform(rng, -2, 2)));
}

/// W(q) and its exact gradient and Hessian by nested automatic differentiation (AD2).
void energy_derivatives(const PlanarBeam& beam, const VectorXd& q, double& W, VectorXd& grad, MatrixXd& hess) {
  using ad::AD2;
  AD2 qs[6];
  for (int i = 0; i < 6; ++i) {
    qs[i] = ad::outer_variable(q[i], 6, i, 6);
    qs[i].value().derivatives() = ad::Derivatives1::Unit(6, i);
  }
  const Eigen::Matrix<AD2, 3, 1> e = beam.strain_of<AD2>(qs);
  AD2 w = AD2(0.0);
  for (int k = 0; k < 3; ++k) w += AD2(0.5 * beam.reference_length() * beam.stiffness()[k]) * e[k] * e[k];
  W = ad::value(w);
  grad.resize(6);
  hess.resize(6, 6);
  for (int i = 0; i < 6; ++i) {
    grad[i] = ad::inner_derivative(w, i);
    for (int j = 0; j < 6; ++j) hess(i, j) = ad::mixed_derivative(w, i, j);
  }
}

/// The elastic residual alone (no inertia, no gravity: q̈ = 0, g = 0 in the specimens using it).
VectorXd elastic_residual(const PlanarBeam& beam, const VectorXd& q) { return element_residual(beam, planar_state(q)); }

// ------------------------------------------------------------------ tangents

// K = ∂r/∂q, C = ∂r/∂q̇ (zero), M = ∂r/∂q̈ against central differences of the full residual
// (elastic + inertia + gravity at load factor 0.7) at the reference and at random deformed states:
// nodes moved by up to 0.3 L, angles by up to ±1.2 rad, then a rigid rotation by up to ±20 rad
// (additive angles), random velocities and accelerations; straight and curved references. A
// mutation — the material stiffness Bᵀ C B / L0 alone, without the geometric stiffness — is
// rejected by the same check.
TEST(PlanarBeamTangents, MatchCentralDifferencesAtRandomDeformedStates) {
  std::mt19937 rng(7);
  const Props p;
  const double L = 0.8;
  std::vector<PlanarSpecimen> beams;
  beams.push_back(planar_specimen(rng, p, L, 0.0, Vector2d(0.0, -9.81)));
  beams.push_back(planar_specimen(rng, p, L, 0.9, Vector2d(1.5, -9.81)));
  beams.push_back(planar_specimen(rng, p, L, -2.5, Vector2d(0.0, -9.81)));
  double worst_K = 0.0, worst_C = 0.0, worst_M = 0.0, mutation_K = 1e300, largest_turn = 0.0;
  int checked = 0;
  for (const PlanarSpecimen& sp : beams) {
    const VectorXd q_ref = local_q(sp.a, sp.b);
    for (int sample = 0; sample < 10; ++sample) {
      LocalState s = planar_state(q_ref);
      s.load_factor = 0.7;
      if (sample > 0) {
        s.q = deformed_and_moved(rng, q_ref, L);
        s.v = VectorXd::Random(6) * 3.0;
        s.qdd = VectorXd::Random(6) * 5.0;
      }
      const double turn = s.q[5] + sp.beam.section_offset(1) - s.q[2] - sp.beam.section_offset(0);
      largest_turn = std::max(largest_turn, std::abs(turn));
      const LocalResidual t = element_tangents(sp.beam, s);
      ASSERT_LE((t.r - element_residual(sp.beam, s)).norm(), 1e-14 * t.r.norm());
      const MatrixXd Kfd = planar_central_differences(sp.beam, s, Wrt::q);
      const MatrixXd Cfd = planar_central_differences(sp.beam, s, Wrt::v);
      const MatrixXd Mfd = planar_central_differences(sp.beam, s, Wrt::qdd);
      const double eK = relative_error(Kfd, t.K), eM = relative_error(Mfd, t.M);
      const double eC = Cfd.norm() / t.K.norm();  // C = 0 exactly: compared on the scale of K
      EXPECT_LE(eK, 1e-6) << "sample " << sample << ", turn " << turn;
      EXPECT_LE(eM, 1e-6) << "sample " << sample;
      EXPECT_LE(eC, 1e-6) << "sample " << sample;
      EXPECT_EQ(t.C.norm(), 0.0);
      EXPECT_LE((t.K - t.K.transpose()).norm(), 1e-14 * t.K.norm()) << "K is a Hessian: symmetric";
      worst_K = std::max(worst_K, eK);
      worst_C = std::max(worst_C, eC);
      worst_M = std::max(worst_M, eM);
      ++checked;
      if (sample == 0) continue;
      // Mutation: K_material = Bᵀ C B / L0 with B = ∂d/∂q = L0 ∂ε/∂q (central differences).
      MatrixXd B(3, 6);
      for (int j = 0; j < 6; ++j) {
        VectorXd dq = VectorXd::Zero(6);
        dq[j] = 1e-6;
        B.col(j) = (sp.beam.strain(s.q + dq) - sp.beam.strain(s.q - dq)) / 2e-6 * sp.beam.reference_length();
      }
      const MatrixXd Kmat = B.transpose() * (sp.beam.stiffness() / sp.beam.reference_length()).asDiagonal() * B;
      mutation_K = std::min(mutation_K, relative_error(Kfd, Kmat));
    }
  }
  std::printf("planar beam tangents vs central differences (%d states, end-section turn up to %.2f rad): "
              "K %.1e, C %.1e, M %.1e; mutation K without geometric stiffness: error >= %.1e\n",
              checked, largest_turn, worst_K, worst_C, worst_M, mutation_K);
  EXPECT_GT(largest_turn, 3.0);
  EXPECT_GT(mutation_K, 1e-2);
}

// r and K are the exact gradient and Hessian of W = (L0/2) εᵀ C ε: they equal nested automatic
// differentiation (AD2) of the templated strain to round-off, on both sides of the switch of
// g(α) = (α/2)/sin(α/2) from its series to the closed form at |α| = 1, at α = 0 exactly, and at
// turns up to 5 rad; g, g', g'' are continuous across the switch to round-off.
TEST(PlanarBeamTangents, EqualAutomaticDifferentiationOfTheEnergyAcrossTheSeriesSwitch) {
  const Props p;
  const PlanarBeam beam("b", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, Vector3d(0, 0, 0), Vector3d(1, 0, 0), 0.0, 0.0,
                        Vector2d::Zero());
  double worst_r = 0.0, worst_K = 0.0, worst_fd = 0.0;
  for (double turn : {0.0, 1e-9, 0.05, 0.3, 0.9999999, 1.0, 1.0000001, -0.9999999, -1.0000001, 1.5, 3.0, 5.0}) {
    const VectorXd q = local_q(Vector3d(0.01, -0.02, 0.1), Vector3d(1.03, 0.04, 0.1 + turn));
    double W;
    VectorXd grad;
    MatrixXd hess;
    energy_derivatives(beam, q, W, grad, hess);
    const LocalResidual t = element_tangents(beam, planar_state(q));
    EXPECT_NEAR(W, beam.elastic_energy(q), 1e-15 * W);
    const double er = (t.r - grad).norm() / grad.norm(), eK = relative_error(hess, t.K);
    const double efd = relative_error(planar_central_differences(beam, planar_state(q), Wrt::q), t.K);
    EXPECT_LE(er, 1e-13) << "turn " << turn;
    EXPECT_LE(eK, 1e-13) << "turn " << turn;
    EXPECT_LE(efd, 1e-6) << "turn " << turn;
    worst_r = std::max(worst_r, er);
    worst_K = std::max(worst_K, eK);
    worst_fd = std::max(worst_fd, efd);
  }
  double jump[3] = {0, 0, 0};
  for (double sign : {1.0, -1.0}) {
    double lo[3], hi[3];
    PlanarBeam::lengthening(sign * std::nextafter(PlanarBeam::kSeriesBelow, 0.0), lo[0], lo[1], lo[2]);
    PlanarBeam::lengthening(sign * PlanarBeam::kSeriesBelow, hi[0], hi[1], hi[2]);
    for (int k = 0; k < 3; ++k) jump[k] = std::max(jump[k], std::abs(hi[k] - lo[k]) / std::abs(hi[k]));
  }
  double g0, dg0, ddg0;
  PlanarBeam::lengthening(0.0, g0, dg0, ddg0);
  EXPECT_EQ(g0, 1.0);
  EXPECT_EQ(dg0, 0.0);
  EXPECT_DOUBLE_EQ(ddg0, 1.0 / 12.0);
  std::printf("planar beam r, K vs AD2 of W (turn 0 ... 5 rad): %.1e, %.1e (central differences %.1e); "
              "relative jumps of g, g', g'' at the series switch: %.1e %.1e %.1e\n",
              worst_r, worst_K, worst_fd, jump[0], jump[1], jump[2]);
  for (int k = 0; k < 3; ++k) EXPECT_LE(jump[k], 1e-14) << "derivative " << k;
}

// ------------------------------------------------------------------ strain measure

// A rigid motion of a (straight or curved, offset) reference — translation c, rotation β up to
// ±50 rad added to both node angles — gives ε = 0 and a zero elastic residual. Objectivity of a
// deformed state: ε, W and the section forces are unchanged by a rigid motion, the residual is its
// image (r_x → R(β) r_x, r_θ → r_θ) and K → P K Pᵀ with P = diag(R(β), 1, R(β), 1).
TEST(PlanarBeamStrain, RigidMotionGivesZeroStrainAndForceAndIsObjective) {
  std::mt19937 rng(11);
  const Props p;
  double worst_rigid = 0.0, worst_obj = 0.0;
  for (double ref_turn : {0.0, 0.7, -2.0}) {
    const PlanarSpecimen sp = planar_specimen(rng, p, 1.1, ref_turn);
    const VectorXd q_ref = local_q(sp.a, sp.b);
    const double fscale = p.EA;  // force scale of a unit strain
    for (double beta : {0.0, 0.3, -1.0, kPi, 4.0, -7.5, 50.0}) {
      const VectorXd q = moved(q_ref, beta, Vector2d(uniform(rng, -3, 3), uniform(rng, -3, 3)));
      const Vector3d e = sp.beam.strain(q);
      const double er = elastic_residual(sp.beam, q).norm() / fscale;
      EXPECT_LE(e.norm(), 1e-14) << "beta " << beta << ", reference turn " << ref_turn;
      EXPECT_LE(er, 1e-14) << "beta " << beta;
      worst_rigid = std::max({worst_rigid, e.norm(), er});
    }
    for (int sample = 0; sample < 5; ++sample) {
      VectorXd dq(6);
      for (int k = 0; k < 2; ++k) dq.segment<3>(3 * k) = small_deformation(rng);
      const VectorXd q = q_ref + dq;
      const double beta = uniform(rng, -30.0, 30.0);
      const VectorXd qm = moved(q, beta, Vector2d(uniform(rng, -3, 3), uniform(rng, -3, 3)));
      const Vector3d e = sp.beam.strain(q), em = sp.beam.strain(qm);
      ASSERT_GT(e.norm(), 1e-2);
      const LocalResidual t = element_tangents(sp.beam, planar_state(q)), tm = element_tangents(sp.beam, planar_state(qm));
      MatrixXd P = MatrixXd::Identity(6, 6);
      const Eigen::Matrix2d R = Eigen::Rotation2Dd(beta).toRotationMatrix();
      P.block<2, 2>(0, 0) = R;
      P.block<2, 2>(3, 3) = R;
      const double de = (em - e).norm() / e.norm();
      const double dW = std::abs(sp.beam.elastic_energy(qm) - sp.beam.elastic_energy(q)) / sp.beam.elastic_energy(q);
      const double dr = (tm.r - P * t.r).norm() / t.r.norm();
      const double dK = relative_error(P * t.K * P.transpose(), tm.K);
      EXPECT_LE(de, 1e-13);
      EXPECT_LE(dW, 1e-13);
      EXPECT_LE(dr, 1e-13);
      EXPECT_LE(dK, 1e-13);
      worst_obj = std::max({worst_obj, de, dW, dr, dK});
    }
  }
  std::printf("planar beam rigid motions (rotations up to 50 rad): |eps|, |r|/EA <= %.1e; objectivity of "
              "eps, W, r, K: <= %.1e relative\n",
              worst_rigid, worst_obj);
}

// A straight element of length L bent onto a circle of radius ρ, nodes on the circle and sections
// tangent to it (node angles ≠ section angles: the offsets φ_i are exercised), has
// ε = (0, 0, 1/ρ) to round-off for every element length, L/ρ from 1e-9 to 5 rad, across the series
// switch; likewise a reference arc of radius ρ0 bent to radius ρ gives ε = (0, 0, 1/ρ − 1/ρ0) and
// L0 = its arc length. The section forces vanish except M = EI/ρ.
TEST(PlanarBeamStrain, CircularArcWithTangentSectionsIsExactForAnyElementLength) {
  std::mt19937 rng(13);
  const Props p;
  double worst = 0.0;
  for (double rho0 : {0.0, 2.5}) {  // 0: straight reference
    for (double L : {1e-9, 1e-3, 0.049, 0.05, 0.051, 0.4, 1.0, 2.0, 3.1, 5.0}) {
      for (double rho : {1.0, 1.6}) {
        if (rho0 > 0.0 && L / rho0 >= kPi) continue;
        const double psi = uniform(rng, -kPi, kPi);  // direction of the reference
        Vector2d ra(0.3, -0.2), rb;
        double sa = psi, sb = psi;
        if (rho0 == 0.0) rb = ra + L * direction(psi);
        else {
          sb = psi + L / rho0;
          rb = ra + 2.0 * rho0 * std::sin(0.5 * L / rho0) * direction(psi + 0.5 * L / rho0);
        }
        const double phi_a = uniform(rng, -2, 2), phi_b = uniform(rng, -2, 2);  // θ_i = α_i − φ_i
        const PlanarBeam beam("arc", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, Vector3d(ra.x(), ra.y(), sa - phi_a),
                              Vector3d(rb.x(), rb.y(), sb - phi_b), sa, sb, Vector2d::Zero());
        // Deformed: an arc of radius rho centred at c, from angle t0 (section A tangent, CCW), t0
        // with several turns added (the angles are additive). The arc turns by dt = t1 − t0 as
        // represented (t1 = t0 + L/ρ rounds by up to ε|t0|, which is not the element's error).
        const Vector2d c(uniform(rng, -1, 1), uniform(rng, -1, 1));
        const double t0 = uniform(rng, -kPi, kPi) + 2.0 * kPi * std::round(uniform(rng, -3, 3));
        const double t1 = t0 + L / rho, dt = t1 - t0;
        const Vector2d xa = c + rho * direction(t0), xb = c + rho * direction(t1);
        const double alpha_a = t0 + 0.5 * kPi, alpha_b = t1 + 0.5 * kPi;
        const VectorXd q = local_q(Vector3d(xa.x(), xa.y(), alpha_a - beam.section_offset(0)),
                                   Vector3d(xb.x(), xb.y(), alpha_b - beam.section_offset(1)));
        // Exact: ε = (ρ dt/L − 1, 0, dt/L − κ0) (= (0, 0, 1/ρ − κ0) up to the rounding of t1).
        const Vector3d expected(rho * dt / L - 1.0, 0.0, dt / L - (rho0 > 0.0 ? 1.0 / rho0 : 0.0));
        const Vector3d e = beam.strain(q);
        // Round-off: positions of size ~ρ + |c| carry ε_mach of absolute error, and the chord of
        // length ~L divides them: the axial/shear strain is exact to ~ε_mach (1 + |c| + ρ)/L.
        // Likewise the angles (up to ~25 rad) carry ε_mach|α| and Δθ/L0 an error ~ε_mach|α|/L.
        const double tol = 1e-15 * (1.0 + c.norm() + rho) / std::min(L, 1.0);
        const double tol_curv = 1e-15 * (std::abs(t0) + 10.0) / std::min(L, 1.0);
        EXPECT_NEAR(beam.reference_length(), L, tol * L);
        EXPECT_NEAR(e[0], expected[0], tol) << "L " << L << ", rho " << rho << ", rho0 " << rho0;
        EXPECT_NEAR(e[1], 0.0, tol) << "L " << L << ", rho " << rho << ", rho0 " << rho0;
        EXPECT_NEAR(e[2], expected[2], tol_curv) << "L " << L << ", rho " << rho;
        EXPECT_LE(std::abs(expected[0]) + std::abs(expected[2] - 1.0 / rho + (rho0 > 0.0 ? 1.0 / rho0 : 0.0)),
                  1e-14 / std::min(L, 1.0));
        if (L >= 1e-3)
          worst = std::max({worst, std::abs(e[0] - expected[0]), std::abs(e[1]), std::abs(e[2] - expected[2]) * rho});
        VectorXd out;
        beam.output(planar_state(q), out);
        EXPECT_NEAR(out[2], p.EI * expected[2], p.EI * tol_curv);
      }
    }
  }
  std::printf("planar beam on a circle (L/rho = 1e-3 ... 5 rad, straight and curved references): strain "
              "error <= %.1e\n",
              worst);
}

// Patch test: a straight chain of 5 unequal elements along a random direction, stretched uniformly
// by (1 + e0) with all sections along the axis, has ε = (e0, 0, 0) and N = EA e0 in every element
// (output()), and the assembled elastic residual is zero at the interior nodes and ∓N along the
// axis at the ends (the reactions of a bar under end forces N).
TEST(PlanarBeamPatch, UniformStretchGivesNEqualsEAEpsilonAndBalancedNodes) {
  std::mt19937 rng(17);
  const Props p;
  const double psi = uniform(rng, -kPi, kPi), e0 = 0.037;
  const std::vector<double> s = {0.0, 0.3, 0.45, 1.0, 1.2, 1.9};
  const int n = static_cast<int>(s.size()) - 1;
  const Vector2d origin(0.4, -1.3), u = direction(psi);
  std::vector<Vector3d> ref, def;
  for (int k = 0; k <= n; ++k) {
    const double theta = uniform(rng, -3, 3);  // node angles: offsets to the section angle psi
    const Vector2d x = origin + s[k] * u, y = origin + (1.0 + e0) * s[k] * u;
    ref.emplace_back(x.x(), x.y(), theta);
    def.emplace_back(y.x(), y.y(), theta);
  }
  VectorXd R = VectorXd::Zero(3 * (n + 1));
  for (int k = 0; k < n; ++k) {
    const PlanarBeam beam("b" + std::to_string(k), k, k + 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, ref[k], ref[k + 1],
                          psi, psi, Vector2d::Zero());
    const VectorXd q = local_q(def[k], def[k + 1]);
    VectorXd out;
    beam.output(planar_state(q), out);
    EXPECT_NEAR(out[0], p.EA * e0, 1e-13 * p.EA) << "element " << k;
    EXPECT_NEAR(out[1], 0.0, 1e-13 * p.EA);
    EXPECT_NEAR(out[2], 0.0, 1e-13 * p.EA);
    EXPECT_NEAR(out[3], e0, 1e-13);
    EXPECT_NEAR(out[4], 0.0, 1e-13);
    EXPECT_NEAR(out[5], 0.0, 1e-13);
    R.segment<6>(3 * k) += elastic_residual(beam, q);
  }
  const double N = p.EA * e0;
  VectorXd expected = VectorXd::Zero(3 * (n + 1));
  expected.segment<2>(0) = -N * u;
  expected.segment<2>(3 * n) = N * u;
  EXPECT_LE((R - expected).norm(), 1e-13 * N) << R.transpose();
  std::printf("planar beam patch test: |r - r_exact| = %.1e N for N = %.3f N\n", (R - expected).norm(), N);
}

// ------------------------------------------------------------------ convergence

// A slender cantilever (rectangle 20 × 10 mm steel, L/h = 1000: L = 10 m) under a tip force P
// across the axis, on a chain of n elements along a random direction with random node angles,
// solved linearly with K at the reference (assembled by hand, node 0 clamped). The element is
// exact for constant strain (moment and curvature are constant per element, nodal rotations are
// exact): δ_n = PL³/(3EI)(1 − 1/(4n²)) + PL/GA, an error ∝ n⁻² with no (L/h)² locking factor.
// Checked: δ_n against that formula, within 1.6 % of Timoshenko's PL³/(3EI) + PL/GA at n = 4,
// and a fitted order of 2.
TEST(PlanarBeamCantilever, HasNoShearLockingAndConvergesAsNToMinusTwo) {
  const double b = 0.02, h = 0.01, P = 1.0, E = 210e9, nu = 0.3, rho = 7850.0;
  const double A = b * h, I = b * h * h * h / 12.0, G = E / (2.0 * (1.0 + nu));
  const double k = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);  // Cowper, rectangle
  const double EA = E * A, GA = k * G * A, EI = E * I;
  const double L = 1000.0 * h;
  const double timoshenko = P * L * L * L / (3.0 * EI) + P * L / GA;
  std::mt19937 rng(19);
  const double psi = uniform(rng, -kPi, kPi);
  const Vector2d u = direction(psi), w = direction(psi + 0.5 * kPi);
  std::vector<double> ns, errors;
  for (int n : {1, 2, 4, 8, 16, 32, 64}) {
    const int N = 3 * (n + 1);
    MatrixXd K = MatrixXd::Zero(N, N);
    std::vector<Vector3d> nodes;
    for (int j = 0; j <= n; ++j) {
      const Vector2d x = (L * j / n) * u;
      nodes.emplace_back(x.x(), x.y(), uniform(rng, -kPi, kPi));
    }
    for (int e = 0; e < n; ++e) {
      const PlanarBeam beam("b", e, e + 1, EA, GA, EI, rho * A, rho * I, nodes[e], nodes[e + 1], psi, psi,
                            Vector2d(0.0, -9.81));
      K.block(3 * e, 3 * e, 6, 6) += element_tangents(beam, planar_state(local_q(nodes[e], nodes[e + 1]))).K;
    }
    const MatrixXd Kr = K.bottomRightCorner(N - 3, N - 3);
    VectorXd f = VectorXd::Zero(N - 3);
    f.segment<2>(3 * (n - 1)) = P * w;
    const VectorXd sol = Kr.ldlt().solve(f);
    ASSERT_LE((Kr * sol - f).norm(), 1e-12 * Kr.norm() * sol.norm());
    const double tip = sol.segment<2>(3 * (n - 1)).dot(w);
    const double predicted = P * L * L * L / (3.0 * EI) * (1.0 - 0.25 / (n * n)) + P * L / GA;
    const double err = std::abs(tip - timoshenko) / timoshenko;
    std::printf("planar cantilever L/h = 1000, n = %2d: tip %.10e m, Timoshenko %.10e m, relative error %.3e "
                "(1/(4n^2) = %.3e)\n",
                n, tip, timoshenko, err, 0.25 / (n * n));
    EXPECT_NEAR(tip, predicted, 1e-7 * timoshenko) << "n = " << n;
    EXPECT_LE(std::abs(sol.segment<2>(3 * (n - 1)).dot(u)), 1e-9 * timoshenko) << "no axial displacement";
    if (n == 4) EXPECT_LT(err, 0.016);
    ns.push_back(n);
    errors.push_back(err);
  }
  const double order = -testing::fitted_slope(ns, errors);
  std::printf("planar cantilever L/h = 1000 tip deflection: fitted order %.4f\n", order);
  EXPECT_NEAR(order, 2.0, 0.02);
}

// Roll-up (the classic large-rotation test): a cantilever of n = 8 elements (node angles offset
// from the sections) under an end moment M bends into a circle of radius EI/M; at M = 2π EI/L it
// closes into a full circle, the tip back at the root with θ advanced by 2π. Solved by Newton's
// method with K in 16 load steps from the straight reference: the strain measure being exact for
// constant curvature, every step lands on the exact circle to round-off, and the iterations
// converge quadratically.
TEST(PlanarBeamRollUp, EndMomentBendsTheCantileverIntoAnExactCircle) {
  const int n = 8, steps = 16;
  const double L = 1.0, EA = 4.2e7, GA = 1.35e7, EI = 350.0;
  std::mt19937 rng(37);
  std::vector<Vector3d> ref;
  std::vector<PlanarBeam> beams;
  for (int j = 0; j <= n; ++j) ref.emplace_back(L * j / n, 0.0, uniform(rng, -1, 1));
  for (int e = 0; e < n; ++e)
    beams.emplace_back("b", e, e + 1, EA, GA, EI, 1.0, 1.0, ref[e], ref[e + 1], 0.0, 0.0, Vector2d::Zero());
  const int N = 3 * (n + 1);
  VectorXd q(N);
  for (int j = 0; j <= n; ++j) q.segment<3>(3 * j) = ref[j];
  double worst = 0.0;
  int iterations = 0;
  std::vector<double> last_corrections;
  for (int step = 1; step <= steps; ++step) {
    const double M = 2.0 * kPi * EI / L * step / steps;
    last_corrections.clear();
    for (int it = 0; it < 20; ++it) {
      VectorXd R = VectorXd::Zero(N);
      MatrixXd K = MatrixXd::Zero(N, N);
      for (int e = 0; e < n; ++e) {
        const LocalResidual t = element_tangents(beams[static_cast<size_t>(e)], planar_state(q.segment<6>(3 * e)));
        R.segment<6>(3 * e) += t.r;
        K.block<6, 6>(3 * e, 3 * e) += t.K;
      }
      R[N - 1] -= M;  // the applied moment on the tip's θ
      const VectorXd dq = -K.bottomRightCorner(N - 3, N - 3).partialPivLu().solve(R.tail(N - 3));
      q.tail(N - 3) += dq;
      ++iterations;
      last_corrections.push_back(dq.norm());
      if (dq.norm() < 1e-13 * L) break;
    }
    ASSERT_LT(last_corrections.back(), 1e-12) << "step " << step;
    const double rho = EI / M;
    for (int j = 0; j <= n; ++j) {
      const double s = L * j / n;
      const Vector3d exact(rho * std::sin(s / rho), rho * (1.0 - std::cos(s / rho)), ref[j][2] + s / rho);
      worst = std::max(worst, (q.segment<3>(3 * j) - exact).norm());
    }
  }
  std::printf("planar roll-up, %d elements, %d load steps: %d Newton iterations, last step corrections", n, steps,
              iterations);
  for (double c : last_corrections) std::printf(" %.1e", c);
  std::printf("; largest distance to the exact circle %.1e\n", worst);
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(q[N - 3], 0.0, 1e-12);
  EXPECT_NEAR(q[N - 2], 0.0, 1e-12);
  EXPECT_NEAR(q[N - 1], ref[n][2] + 2.0 * kPi, 1e-12);
}

// ------------------------------------------------------------------ the spatial beam in the plane

// An in-plane configuration of the spatial GeometricallyExactBeam (node frames and section frames
// rotations about z, GA2 = GA, EI3 = EI, ρI3 = ρI) has the planar beam's strain (ε1, ε2, ε6) and
// energy; the in-plane components (x, y, θ_z of both nodes) of its residual, K and M equal the
// planar beam's, out-of-plane strains vanish. Random deformed, moving states; the spatial
// increments δθ_z act as Rz(θ) Rz(δ) = Rz(θ + δ), so the tangents are comparable entry by entry.
TEST(PlanarBeamSpatialBeam, SameStrainEnergyResidualAndTangentsInThePlane) {
  std::mt19937 rng(23);
  const Props p;
  const BeamSection sec = BeamSection::from_properties(p.EA, p.GA, 4.0, 2.0, 3.0, p.EI, p.rhoA, 0.2, p.rhoI);
  const int in_plane[6] = {0, 1, 5, 6, 7, 11};
  auto Rz = [](double a) { return Matrix3d(Eigen::AngleAxisd(a, Vector3d::UnitZ())); };
  auto pose = [&](const Vector3d& s) { return Pose<double>{Vector3d(s[0], s[1], 0.0), Rz(s[2])}; };
  double worst = 0.0;
  for (double turn : {0.0, 0.8, -2.2}) {
    const Vector2d g(0.7, -9.81);
    const PlanarSpecimen sp = planar_specimen(rng, p, 0.9, turn, g);
    const GeometricallyExactBeam spatial("s", 0, 1, sec, pose(sp.a), pose(sp.b), Rz(sp.sec_a), Rz(sp.sec_b),
                                         Vector3d(g.x(), g.y(), 0.0));
    EXPECT_NEAR(spatial.reference_length(), sp.beam.reference_length(), 1e-14);
    for (int sample = 0; sample < 6; ++sample) {
      VectorXd dq = VectorXd::Zero(6);
      if (sample > 0)
        for (int k = 0; k < 2; ++k) dq.segment<3>(3 * k) = small_deformation(rng);
      const VectorXd q = moved(local_q(sp.a, sp.b) + dq, uniform(rng, -1.0, 1.0), Vector2d(uniform(rng, -1, 1), 0.3));
      if (std::abs(q[5] + sp.beam.section_offset(1) - q[2] - sp.beam.section_offset(0)) >= kPi - 0.1) continue;
      LocalState s = planar_state(q, VectorXd::Random(6), VectorXd::Random(6));
      s.load_factor = 0.6;
      LocalState s3;
      s3.q.resize(14);
      store_pose(pose(q.head<3>()).x, pose(q.head<3>()).R, s3.q.data());
      store_pose(pose(q.tail<3>()).x, pose(q.tail<3>()).R, s3.q.data() + 7);
      s3.v = VectorXd::Zero(12);
      s3.qdd = VectorXd::Zero(12);
      for (int i = 0; i < 6; ++i) {
        s3.v[in_plane[i]] = s.v[i];
        s3.qdd[in_plane[i]] = s.qdd[i];
      }
      s3.load_factor = 0.6;
      const Eigen::Matrix<double, 6, 1> e3 = spatial.strain(s3.q);
      const Vector3d e = sp.beam.strain(q);
      const double de = (Vector3d(e3[0], e3[1], e3[5]) - e).norm() + Vector3d(e3[2], e3[3], e3[4]).norm();
      // Relative to W, floored at 1e-6 EA L0 (the reference, W = 0).
      const double dW = std::abs(spatial.elastic_energy(s3.q) - sp.beam.elastic_energy(q)) /
                        std::max(sp.beam.elastic_energy(q), 1e-6 * p.EA * sp.beam.reference_length());
      LocalResidual t3;
      t3.reset(12, true);
      spatial.evaluate(s3, t3, true);
      const LocalResidual t = element_tangents(sp.beam, s);
      VectorXd r3(6);
      MatrixXd K3(6, 6), M3(6, 6), C3(6, 6);
      for (int i = 0; i < 6; ++i) {
        r3[i] = t3.r[in_plane[i]];
        for (int j = 0; j < 6; ++j) {
          K3(i, j) = t3.K(in_plane[i], in_plane[j]);
          M3(i, j) = t3.M(in_plane[i], in_plane[j]);
          C3(i, j) = t3.C(in_plane[i], in_plane[j]);
        }
      }
      const double dr = (r3 - t.r).norm() / t.r.norm();
      const double dK = relative_error(t.K, K3), dM = relative_error(t.M, M3);
      EXPECT_LE(de, 1e-13) << "sample " << sample << ", turn " << turn;
      EXPECT_LE(dW, 1e-12) << "sample " << sample;
      EXPECT_LE(dr, 1e-12) << "sample " << sample;
      EXPECT_LE(dK, 1e-11) << "sample " << sample;
      EXPECT_LE(dM, 1e-14) << "sample " << sample;
      EXPECT_LE(C3.norm(), 1e-12 * t.M.norm()) << "no in-plane gyroscopic damping";
      worst = std::max({worst, de, dW, dr, dK, dM});
    }
  }
  std::printf("planar beam vs spatial beam in the plane: strain, energy, r, K, M agree to %.1e\n", worst);
}

// ------------------------------------------------------------------ inertia, gravity, output, input

// r = M q̈ − f_g with M = ρA L0/6 [[2, 1], [1, 2]] on x and y, ρI L0/6 [[2, 1], [1, 2]] on θ and
// f_g = ρA L0/2 g λ on each node (λ the load factor), at the stress-free reference; M is exact and
// constant, C = 0 and the kinetic energy of a rigid translation and of a uniform spin are exact.
TEST(PlanarBeamInertia, ConsistentMassAndHalfTheWeightOnEachNodeTimesTheLoadFactor) {
  std::mt19937 rng(29);
  const Props p;
  const Vector2d g(0.5, -9.81);
  const PlanarSpecimen sp = planar_specimen(rng, p, 1.3, 0.4, g);
  const double L0 = sp.beam.reference_length();
  LocalState s = planar_state(local_q(sp.a, sp.b), VectorXd::Random(6), VectorXd::Random(6));
  s.load_factor = 0.25;
  const LocalResidual t = element_tangents(sp.beam, s);
  MatrixXd M = MatrixXd::Zero(6, 6);
  const double mt = p.rhoA * L0 / 6.0, mr = p.rhoI * L0 / 6.0;
  for (int i = 0; i < 3; ++i) {
    const double m = i < 2 ? mt : mr;
    M(i, i) = M(i + 3, i + 3) = 2.0 * m;
    M(i, i + 3) = M(i + 3, i) = m;
  }
  VectorXd fg = VectorXd::Zero(6);
  fg.segment<2>(0) = fg.segment<2>(3) = 0.25 * 0.5 * p.rhoA * L0 * g;
  EXPECT_LE((t.M - M).norm(), 1e-15 * M.norm());
  EXPECT_EQ(t.C.norm(), 0.0);
  EXPECT_LE((t.r - (M * s.qdd - fg)).norm(), 1e-14 * t.r.norm());
  // Rigid translation with velocity u: T = ½ ρA L0 |u|²; uniform spin ω of the sections: ½ ρI L0 ω².
  VectorXd v(6);
  v << 0.3, -0.8, 0.0, 0.3, -0.8, 0.0;
  EXPECT_NEAR(0.5 * v.dot(t.M * v), 0.5 * p.rhoA * L0 * 0.73, 1e-14);
  v << 0.0, 0.0, 1.7, 0.0, 0.0, 1.7;
  EXPECT_NEAR(0.5 * v.dot(t.M * v), 0.5 * p.rhoI * L0 * 1.7 * 1.7, 1e-14);
}

TEST(PlanarBeamOutput, NamesAndValuesAreSectionForcesThenStrains) {
  const Props p;
  const PlanarBeam beam("b", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, Vector3d(0, 0, 0.2), Vector3d(2, 0, -0.1), 0.0,
                        0.0, Vector2d::Zero());
  EXPECT_STREQ(beam.type(), "beam");
  EXPECT_EQ(beam.nodes(), (std::vector<int>{0, 1}));
  const std::vector<std::string> names = {"N", "V", "M", "axial_strain", "shear_strain", "curvature"};
  EXPECT_EQ(beam.output_names(), names);
  const VectorXd q = local_q(Vector3d(0.1, 0.05, 0.3), Vector3d(2.2, 0.3, 0.1));
  VectorXd out;
  beam.output(planar_state(q), out);
  ASSERT_EQ(out.size(), 6);
  const Vector3d e = beam.strain(q);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(out[3 + k], e[k]);
    EXPECT_EQ(out[k], beam.stiffness()[k] * e[k]);
  }
  // Hand values: sections at θ_A + φ_A = 0.1, θ_B + φ_B = 0.2 (φ_A = −0.2, φ_B = 0.1), mean 0.15,
  // turn 0.1, chord (2.1, 0.25): d1 = g (cos 0.15 · 2.1 + sin 0.15 · 0.25), L0 = 2.
  const double g = 0.05 / std::sin(0.05);
  EXPECT_NEAR(e[0], g * (std::cos(0.15) * 2.1 + std::sin(0.15) * 0.25) / 2.0 - 1.0, 1e-15);
  EXPECT_NEAR(e[1], g * (std::cos(0.15) * 0.25 - std::sin(0.15) * 2.1) / 2.0, 1e-15);
  EXPECT_NEAR(e[2], 0.05, 1e-15);
}

TEST(PlanarBeamInput, RejectsInvalidPropertiesNodesAndGeometryWithAClearMessage) {
  const Vector3d a(0, 0, 0), b(1, 0, 0);
  const Vector2d g(0, -9.81);
  auto expect_message = [](auto make, const std::string& fragment) {
    try {
      make();
      ADD_FAILURE() << "no exception, expected one mentioning '" << fragment << "'";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("'bad'"), std::string::npos) << "names the element: " << e.what();
    }
  };
  expect_message([&] { PlanarBeam("bad", 0, 1, 0.0, 1, 1, 1, 1, a, b, 0, 0, g); }, "EA must be positive");
  expect_message([&] { PlanarBeam("bad", 0, 1, 1, -1, 1, 1, 1, a, b, 0, 0, g); }, "GA must be positive");
  expect_message([&] { PlanarBeam("bad", 0, 1, 1, 1, NAN, 1, 1, a, b, 0, 0, g); }, "EI must be positive");
  expect_message([&] { PlanarBeam("bad", 0, 1, 1, 1, 1, 0, 1, a, b, 0, 0, g); }, "rhoA must be positive");
  expect_message([&] { PlanarBeam("bad", 0, 1, 1, 1, 1, 1, INFINITY, a, b, 0, 0, g); }, "rhoI must be positive");
  expect_message([&] { PlanarBeam("bad", 3, 3, 1, 1, 1, 1, 1, a, b, 0, 0, g); }, "two different nodes");
  expect_message([&] { PlanarBeam("bad", 0, 1, 1, 1, 1, 1, 1, a, a, 0, 0, g); }, "zero reference length");
  expect_message([&] { PlanarBeam("bad", 0, 1, 1, 1, 1, 1, 1, a, b, 0, 3.2, g); }, "less than pi");
  expect_message([&] { PlanarBeam("bad", 0, 1, 1, 1, 1, 1, 1, a, Vector3d(1, NAN, 0), 0, 0, g); }, "finite");
}

// Cost is measured in benchmarks, not in tests (docs/theory/planar_beam.md has the numbers).


// ------------------------------------------------------------------ material damping

// Kelvin–Voigt damping f = C (ε + η ε̇) (planar_beam.hpp): K = ∂r/∂q at fixed q̇, C = ∂r/∂q̇ against
// central differences at random deformed, rotated and moving states of straight and curved
// references (η = 0.3 s, velocities up to 3: viscous and elastic section forces of one order); no
// force along a rigid motion (ε̇ = 0); dissipated power q̇ᵀ(r(q̇) − r(0)) = L0 η ε̇ᵀ C ε̇ ≥ 0 with
// ε̇ the derivative of the strain along q̇ (central differences); η = 0 is the elastic element bit
// for bit. Mutations — the undamped element's K and C — are rejected by the same check.
TEST(PlanarBeamDamping, TangentsMatchCentralDifferencesAndTheDissipationIsEtaEpsDotCEpsDot) {
  std::mt19937 rng(17);
  const Props p;
  const double L = 0.8, eta = 0.3;
  double worst_K = 0.0, worst_C = 0.0, mutation_K = 1e300, mutation_C = 1e300;
  for (double turn : {0.0, 0.9, -2.5}) {
    const PlanarSpecimen sp = planar_specimen(rng, p, L, turn);
    const PlanarBeam damped("damped", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, sp.a, sp.b, sp.sec_a, sp.sec_b,
                            Vector2d(0.0, -9.81), eta);
    const PlanarBeam elastic("elastic", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, sp.a, sp.b, sp.sec_a, sp.sec_b,
                             Vector2d(0.0, -9.81), 0.0);
    const PlanarBeam plain("plain", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, sp.a, sp.b, sp.sec_a, sp.sec_b,
                           Vector2d(0.0, -9.81));
    const VectorXd q_ref = local_q(sp.a, sp.b);
    for (int sample = 0; sample < 6; ++sample) {
      LocalState s = planar_state(q_ref);
      if (sample > 0) {
        s.q = deformed_and_moved(rng, q_ref, L);
      }
      s.v = VectorXd::Random(6) * 3.0;
      s.qdd = VectorXd::Random(6) * 5.0;
      const LocalResidual t = element_tangents(damped, s);
      ASSERT_LE((t.r - element_residual(damped, s)).norm(), 1e-14 * t.r.norm());
      const MatrixXd Kfd = planar_central_differences(damped, s, Wrt::q), Cfd = planar_central_differences(damped, s, Wrt::v);
      const double eK = relative_error(Kfd, t.K), eC = relative_error(Cfd, t.C);
      EXPECT_LE(eK, 1e-6) << "sample " << sample;
      EXPECT_LE(eC, 1e-6) << "sample " << sample;
      EXPECT_LE(relative_error(planar_central_differences(damped, s, Wrt::qdd), t.M), 1e-6);
      const LocalResidual te = element_tangents(elastic, s), tp = element_tangents(plain, s);
      EXPECT_EQ(te.r, tp.r);  // η = 0 is the elastic element, bit for bit
      EXPECT_EQ(te.K, tp.K);
      worst_K = std::max(worst_K, eK);
      worst_C = std::max(worst_C, eC);
      mutation_K = std::min(mutation_K, relative_error(Kfd, te.K));
      mutation_C = std::min(mutation_C, relative_error(Cfd, te.C));
      // Dissipated power against ε̇ by central differences of ε along q̇.
      LocalState moving = s;
      moving.qdd.setZero();
      moving.load_factor = 0.0;
      LocalState still = moving;
      still.v.setZero();
      const double step = 1e-6;
      const Vector3d rate = (damped.strain(s.q + step * s.v) - damped.strain(s.q - step * s.v)) / (2.0 * step);
      const double power = s.v.dot(element_residual(damped, moving) - element_residual(damped, still));
      const double expected = damped.reference_length() * eta * rate.dot(p_stiffness(p).cwiseProduct(rate));
      EXPECT_NEAR(power, expected, 1e-7 * expected);
      // A rigid motion: ẋ_i = u + ω e3 × x_i, θ̇_i = ω.
      const Vector2d u(uniform(rng, -2, 2), uniform(rng, -2, 2));
      const double w = uniform(rng, -2, 2);
      LocalState rigid = moving;
      for (int k = 0; k < 2; ++k) {
        rigid.v.segment<2>(3 * k) = u + w * Vector2d(-s.q[3 * k + 1], s.q[3 * k]);
        rigid.v[3 * k + 2] = w;
      }
      const VectorXd rd = element_residual(damped, rigid), re = element_residual(elastic, rigid);
      EXPECT_LE((rd - re).norm(), 1e-12 * std::max(1.0, re.norm()));
    }
  }
  std::printf("damped planar beam tangents vs central differences: K %.1e, C %.1e; mutations (undamped K, C): %.1e, %.1e\n",
              worst_K, worst_C, mutation_K, mutation_C);
  EXPECT_GT(std::min(mutation_K, mutation_C), 1e-3);
  try {
    PlanarBeam bad("bad", 0, 1, p.EA, p.GA, p.EI, p.rhoA, p.rhoI, Vector3d(0, 0, 0), Vector3d(1, 0, 0), 0.0, 0.0,
                   Vector2d::Zero(), -1.0);
    ADD_FAILURE() << "a negative eta was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("planar beam 'bad': the material damping eta"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace alphaflex
