// Cost of one element evaluation (a benchmark, not a test: it prints, nothing is timed against a
// bound, and ctest does not run it). Built with the tests; run it on a quiet machine:
//
//     build/tests/benchmarks/element_cost [ROUNDS]
//
// For each element — the MITC4 quadrilateral and MITC3 triangle shells (docs/theory/shell.md) and
// the two-node SE(3) beam (docs/theory/beam.md) — at a deformed, moving state: the thread CPU time
// of evaluate() for r alone and for r with K, C, M, the best of ROUNDS (default 5) rounds of 200
// calls, so that other processes on a shared machine inflate the figures as little as possible.
#include <time.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "alphaflex/core/rotation.hpp"
#include "alphaflex/elements/beam_section.hpp"
#include "alphaflex/elements/geometrically_exact_beam.hpp"
#include "alphaflex/elements/reduced_body.hpp"
#include "alphaflex/elements/shell.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/spatial_kernel.hpp"

using namespace alphaflex;

namespace {

double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// Best time (µs) per call of `evaluate(out)` at a state with `s.v.size()` unknowns.
template <class Evaluate>
double microseconds_per_call(const LocalState& s, bool tangent, int rounds, const Evaluate& evaluate) {
  constexpr int kCalls = 200;
  double best = 1e300;
  LocalResidual out;
  for (int round = 0; round < rounds; ++round) {
    const double t0 = thread_cpu_seconds();
    for (int i = 0; i < kCalls; ++i) {
      out.reset(static_cast<int>(s.v.size()), tangent);
      evaluate(out);
    }
    best = std::min(best, (thread_cpu_seconds() - t0) / kCalls * 1e6);
  }
  return best;
}

/// Best time (µs) per evaluate() call of `e` at `s`.
double microseconds_per_call(const Element& e, const LocalState& s, bool tangent, int rounds) {
  return microseconds_per_call(s, tangent, rounds, [&](LocalResidual& out) { e.evaluate(s, out, tangent); });
}

Eigen::Vector3d random3(std::mt19937& rng, double a) {
  std::uniform_real_distribution<double> u(-a, a);
  return Eigen::Vector3d(u(rng), u(rng), u(rng));
}

/// A reduced body (docs/theory/reduced_bodies.md) with m = 14 elastic coordinates — a link's far
/// interface node (6 constraint modes) and 8 fixed-interface modes — and a moving deformed state.
/// The invariants are random matrices of the right shapes and symmetries: the cost of the closed
/// form depends on the sizes only.
std::unique_ptr<ReducedBody> reduced_body(std::mt19937& rng, LocalState& s, int m = 14, bool geometric = false) {
  const int n = 6 + m;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto random = [&](int r, int c) { return Eigen::MatrixXd(Eigen::MatrixXd::NullaryExpr(r, c, [&] { return u(rng); })); };
  ReducedBodyMatrices d;
  const Eigen::MatrixXd A = random(n, n), B = random(m, m);
  d.M0 = A * A.transpose() + n * Eigen::MatrixXd::Identity(n, n);
  d.K = B * B.transpose();
  for (int i = 0; i < m; ++i) d.C.push_back(0.1 * random(3, n));
  d.M2.resize(m * m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) {  // M2[i][j] = M2[j][i]ᵀ, as for the true invariants
      const Eigen::Matrix3d b = 0.01 * random(3, 3);
      d.M2[static_cast<size_t>(i * m + j)] = i == j ? Eigen::Matrix3d(b + b.transpose()) : b;
      d.M2[static_cast<size_t>(j * m + i)] = d.M2[static_cast<size_t>(i * m + j)].transpose();
    }
  if (geometric) {  // fully symmetric T and Q of the right sizes: sums of tensor powers of random vectors
    std::vector<Eigen::VectorXd> a;
    for (int r = 0; r < 3; ++r) a.push_back(random(m, 1));
    d.T = SymmetricTensor(3, m, [&](int i, int j, int k, int) {
      double t = 0.0;
      for (const Eigen::VectorXd& v : a) t += v[i] * v[j] * v[k];
      return t;
    });
    d.Q = SymmetricTensor(4, m, [&](int i, int j, int k, int l) {
      double t = 0.0;
      for (const Eigen::VectorXd& v : a) t += v[i] * v[j] * v[k] * v[l];
      return t;
    });
  }
  std::vector<int> coords;
  for (int i = 0; i < m; ++i) coords.push_back(1 + i);
  s.q.resize(7 + m);
  store_pose(random3(rng, 1.0), exp_so3<double>(random3(rng, 1.5)), s.q.data());
  s.q.tail(m) = 1e-2 * random(m, 1);
  s.v = 3.0 * random(n, 1);
  s.qdd = 5.0 * random(n, 1);
  return std::make_unique<ReducedBody>("link", 0, coords, d, Eigen::Vector3d(0, 0, -9.81));
}

/// The nodes' reference poses moved by O(amp) and turned by O(3 amp), with random velocities and
/// accelerations: every term of the residual is active.
LocalState moving_state(const std::vector<Pose<double>>& ref, std::mt19937& rng, double amp) {
  LocalState s;
  const Eigen::Index n = static_cast<Eigen::Index>(ref.size());
  s.q.resize(7 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Pose<double>& p = ref[static_cast<size_t>(k)];
    store_pose(Eigen::Vector3d(p.x + random3(rng, amp)), Eigen::Matrix3d(p.R * exp_so3<double>(random3(rng, 3 * amp))),
               s.q.data() + 7 * k);
  }
  s.v = Eigen::VectorXd::Random(6 * n) * 3.0;
  s.qdd = Eigen::VectorXd::Random(6 * n) * 5.0;
  return s;
}

/// A warped quadrilateral or a triangle of steel, 2 cm thick, in a general position in space, its
/// nodes' frames arbitrary rotations (as if shared with beams), directors tilted from the normal.
std::unique_ptr<Element> shell(int n, std::mt19937& rng, std::vector<Pose<double>>& ref, DirectorInterpolation interp,
                               MembraneEdges edges = MembraneEdges::chord) {
  const Eigen::Matrix3d Q = exp_so3<double>(Eigen::Vector3d(0.3, -0.5, 0.8));
  const std::vector<Eigen::Vector3d> quad = {{0, 0, 0}, {1.1, -0.1, 0.05}, {1.3, 0.9, 0}, {-0.2, 1.0, 0.05}};
  const std::vector<Eigen::Vector3d> tri = {{0, 0, 0}, {1.2, 0.1, 0}, {0.3, 0.9, 0}};
  std::vector<int> nodes;
  std::vector<Eigen::Vector3d> dirs;
  for (int I = 0; I < n; ++I) {
    nodes.push_back(I);
    ref.push_back({Q * (n == 4 ? quad : tri)[static_cast<size_t>(I)], exp_so3<double>(random3(rng, 1.5))});
    dirs.push_back((Q * (Eigen::Vector3d(0, 0, 1) + random3(rng, 0.15))).normalized());
  }
  ShellOptions options;
  options.director_interpolation = interp;
  options.membrane_edges = edges;
  return std::make_unique<ReissnerMindlinShell>("shell", nodes, ShellSection::isotropic(2.1e11, 0.3, 7800, 0.02), ref,
                                                dirs, Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, -9.81), options);
}

/// A beam of length 1 whose six stiffnesses and three inertias are of order one, its nodes' frames
/// turned away from its section frames.
std::unique_ptr<Element> beam(std::mt19937& rng, std::vector<Pose<double>>& ref) {
  const BeamSection section = BeamSection::from_properties(10.0, 6.0, 4.0, 2.0, 3.0, 1.5, 2.0, 0.3, 0.1);
  const Eigen::Matrix3d sec_a = exp_so3<double>(random3(rng, 1.0));
  const Eigen::Matrix3d sec_b = sec_a * exp_so3<double>(Eigen::Vector3d(0.1, 0.2, -0.1));
  ref = {{random3(rng, 1.0), exp_so3<double>(random3(rng, 1.5))}, {}};
  ref[1] = {ref[0].x + sec_a.col(0), exp_so3<double>(random3(rng, 1.5))};
  return std::make_unique<GeometricallyExactBeam>("beam", 0, 1, section, ref[0], ref[1], sec_a, sec_b,
                                                  Eigen::Vector3d(0, 0, -9.81));
}

}  // namespace

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  std::mt19937 rng(17);
  std::printf("thread CPU time per evaluate(), best of %d rounds of 200 calls\n", rounds);
  std::printf("%-12s %10s %16s\n", "element", "r (us)", "r, K, C, M (us)");
  for (int kind : {4, 3, 2}) {
    std::vector<Pose<double>> ref;
    const std::mt19937 start = rng;  // the geodesic shell below: the same element and state
    const std::unique_ptr<Element> e = kind == 2 ? beam(rng, ref) : shell(kind, rng, ref, DirectorInterpolation::linear);
    const LocalState s = moving_state(ref, rng, 0.2);
    std::printf("%-12s %10.2f %16.2f\n", e->type(), microseconds_per_call(*e, s, false, rounds),
                microseconds_per_call(*e, s, true, rounds));
    if (kind == 2) continue;
    // director_interpolation: geodesic (docs/theory/shell.md): the strain forms grow by the edge rows.
    std::mt19937 again = start;
    std::vector<Pose<double>> ref2;
    const std::unique_ptr<Element> g = shell(kind, again, ref2, DirectorInterpolation::geodesic);
    std::printf("%-12s %10.2f %16.2f   (geodesic directors)\n", g->type(), microseconds_per_call(*g, s, false, rounds),
                microseconds_per_call(*g, s, true, rounds));
    // membrane_edges: arc on top: the edges' arc rows as well.
    again = start;
    std::vector<Pose<double>> ref3;
    const std::unique_ptr<Element> a = shell(kind, again, ref3, DirectorInterpolation::geodesic, MembraneEdges::arc);
    std::printf("%-12s %10.2f %16.2f   (geodesic directors, arc membrane edges)\n", a->type(),
                microseconds_per_call(*a, s, false, rounds), microseconds_per_call(*a, s, true, rounds));
  }
  LocalState s;
  const std::unique_ptr<ReducedBody> body = reduced_body(rng, s);
  std::printf("%-12s %10.2f %16.2f   (m = 14; closed form)\n", body->type(), microseconds_per_call(*body, s, false, rounds),
              microseconds_per_call(*body, s, true, rounds));
  std::printf("%-12s %10s %16.2f   (m = 14; the AD reference, reduced_body_tangent_by_ad)\n", body->type(), "",
              microseconds_per_call(s, true, rounds, [&](LocalResidual& out) { reduced_body_tangent_by_ad(*body, s, out); }));
  // Geometric stiffness (cubic and quartic energy terms, O(m⁴)): m = 8 and 16, without and with,
  // interleaved.
  for (int m : {8, 16})
    for (bool geometric : {false, true}) {
      LocalState sg;
      const std::unique_ptr<ReducedBody> b = reduced_body(rng, sg, m, geometric);
      std::printf("%-12s %10.2f %16.2f   (m = %d; %s geometric stiffness)\n", b->type(), microseconds_per_call(*b, sg, false, rounds),
                  microseconds_per_call(*b, sg, true, rounds), m, geometric ? "with" : "without");
    }
  return 0;
}
