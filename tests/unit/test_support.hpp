#pragma once
// Helpers shared by the tests: run a scene in-process, read reference CSVs, fit slopes, a fresh
// output directory, central differences, random samples. A helper that two test files would
// define alike lives here: the unit tests are compiled in unity batches (ALPHAFLEX_UNITY_BUILD),
// where two files' file-local helpers of one name would meet (scripts/check_unity_names.py).
#include <gtest/gtest.h>
#include <petscsys.h>
#include <stdlib.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "alphaflex/app/simulation.hpp"
#include "alphaflex/assembly/saddle_point_system.hpp"
#include "alphaflex/integrators/alpha_parameters.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/model/element.hpp"
#include "alphaflex/model/node.hpp"
#include "alphaflex/model/spatial_kernel.hpp"
#include "alphaflex/io/scene.hpp"

namespace alphaflex::testing {

inline std::string source_path(const std::string& rel) { return std::string(ALPHAFLEX_SOURCE_DIR) + "/" + rel; }

/// The InputError message of `f` (the test fails if `f` throws anything else, or nothing).
inline std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an InputError: " << e.what();
    return "";
  } catch (...) {
    ADD_FAILURE() << "not an InputError (not even a std::exception)";
    return "";
  }
  ADD_FAILURE() << "accepted: no error";
  return "";
}

/// The coefficients of a generalized-α step of size h with the Bottasso scaling, written out from
/// eq. 6 (β' = (1 − α_m)/(βh²(1 − α_f)), γ' = γ/(βh), rows × βh², multipliers ÷ βh²): what tests of
/// the assembly use, independently of GeneralizedAlpha::step_coefficients.
inline AssemblyCoefficients scaled_step_coefficients(const AlphaParameters& p, double h) {
  AssemblyCoefficients c;
  c.mass = (1 - p.alpha_m) / (h * h * p.beta * (1 - p.alpha_f));
  c.damping = p.gamma / (h * p.beta);
  c.stiffness = 1.0;
  c.row_scale = p.beta * h * h;
  c.multiplier_scale = 1.0 / (p.beta * h * h);
  return c;
}

/// An element's local state (q: configuration numbers, v and q̇̇ in the element's unknowns).
inline LocalState local_state(const Eigen::VectorXd& q, const Eigen::VectorXd& v, const Eigen::VectorXd& qdd) {
  LocalState s;
  s.q = q;
  s.v = v;
  s.qdd = qdd;
  return s;
}

/// r = M q̈ − g of an element at a local state (no tangents).
inline Eigen::VectorXd element_residual(const Element& e, const LocalState& s) {
  LocalResidual out;
  out.reset(static_cast<int>(s.v.size()), false);
  e.evaluate(s, out, false);
  return out.r;
}

/// r with its tangents K, C, M at a local state.
inline LocalResidual element_tangents(const Element& e, const LocalState& s) {
  LocalResidual out;
  out.reset(static_cast<int>(s.v.size()), true);
  e.evaluate(s, out, true);
  return out;
}

/// Where a test writes its files: never the source tree or the working directory (a test's output
/// once ended up committed). By default a fresh directory under the system's temporary directory,
/// removed with this object; if the environment variable ALPHAFLEX_TEST_OUTPUT_DIR is set, the
/// directory $ALPHAFLEX_TEST_OUTPUT_DIR/<name>, emptied first and kept, for a later test that reads
/// the files (ctest scenes.paraview_shells_unit opens those of ResultsShells in ParaView).
class TestOutputDir {
 public:
  explicit TestOutputDir(const std::string& name) {
    namespace fs = std::filesystem;
    if (const char* given = std::getenv("ALPHAFLEX_TEST_OUTPUT_DIR"); given && *given) {
      path_ = (fs::path(given) / name).string();
      fs::remove_all(path_);
      fs::create_directories(path_);
      return;
    }
    std::string pattern = (fs::temp_directory_path() / ("alphaflex_" + name + "_XXXXXX")).string();
    if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot create a directory " + pattern);
    path_ = pattern;
    owned_ = true;
  }
  ~TestOutputDir() {
    std::error_code ec;
    if (owned_) std::filesystem::remove_all(path_, ec);
  }
  TestOutputDir(const TestOutputDir&) = delete;
  TestOutputDir& operator=(const TestOutputDir&) = delete;
  const std::string& path() const { return path_; }
  std::string file(const std::string& name) const { return (std::filesystem::path(path_) / name).string(); }
  /// Writes `text` to the file `name` here; returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = file(name);
    std::ofstream(p) << text;
    return p;
  }

 private:
  std::string path_;
  bool owned_ = false;
};

/// Runs inputs/<scene>.yaml with --set style overrides, no files written.
inline RunSummary run_scene(const std::string& scene, const std::vector<std::string>& overrides) {
  Scene s = read_scene(source_path("inputs/" + scene + ".yaml"), overrides);
  RunOptions opt;
  opt.write_results = false;
  opt.verbose = false;
  opt.keep_history = true;
  return run_simulation(s, opt, PETSC_COMM_WORLD);
}

/// Index of sensor `name` in a run's sensor rows.
inline size_t column(const RunSummary& r, const std::string& name) {
  for (size_t i = 0; i < r.sensor_names.size(); ++i)
    if (r.sensor_names[i] == name) return i;
  throw std::runtime_error("no sensor " + name);
}

/// Value of sensor `name` at the final time.
inline double final_value(const RunSummary& r, const std::string& name) { return r.final_sensors[column(r, name)]; }

/// A CSV with a header row (after optional '#' comment lines): column name → values.
inline std::map<std::string, std::vector<double>> read_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  std::string line;
  while (std::getline(in, line) && !line.empty() && line[0] == '#') {
  }  // comment lines (source and method) before the header
  std::vector<std::string> names;
  std::stringstream hs(line);
  for (std::string c; std::getline(hs, c, ',');) names.push_back(c);
  std::map<std::string, std::vector<double>> cols;
  while (std::getline(in, line)) {
    std::stringstream ls(line);
    size_t k = 0;
    for (std::string c; std::getline(ls, c, ',') && k < names.size(); ++k) cols[names[k]].push_back(std::stod(c));
  }
  return cols;
}

/// Value of column `name` at time t (rows must contain t up to round-off).
inline double at_time(const std::map<std::string, std::vector<double>>& csv, const std::string& name, double t) {
  const auto& tt = csv.at("t");
  for (size_t i = 0; i < tt.size(); ++i)
    if (std::fabs(tt[i] - t) < 1e-9) return csv.at(name)[i];
  throw std::runtime_error("time not in reference");
}

/// Least-squares slope of log(err) against log(h).
inline double fitted_slope(const std::vector<double>& h, const std::vector<double>& err) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(h.size());
  for (size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Least-squares slopes, one per sensor in `names`, of the final-time errors of runs of `scene` at
/// the step sizes `hs` against column `names[k]` of the reference CSV at time t (`extra`: more
/// --set overrides for every run).
inline std::vector<double> error_slopes(const std::string& scene, const std::string& reference_csv,
                                        const std::vector<std::string>& names, const std::vector<double>& hs, double t,
                                        const std::vector<std::string>& extra = {}) {
  const auto ref = read_csv(source_path(reference_csv));
  std::vector<std::vector<double>> err(names.size());
  for (double h : hs) {
    std::vector<std::string> overrides = extra;
    overrides.push_back("solver.h=" + std::to_string(h));
    const RunSummary r = run_scene(scene, overrides);
    for (size_t k = 0; k < names.size(); ++k)
      err[k].push_back(std::fabs(r.final_sensors[column(r, names[k])] - at_time(ref, names[k], t)));
  }
  std::vector<double> slopes;
  for (const auto& e : err) slopes.push_back(fitted_slope(hs, e));
  return slopes;
}

/// Differences between two final states of spatial scenes (7 numbers per frame): the largest
/// position difference (m) and relative rotation angle (rad) over the frames, on the group, and
/// the largest velocity and multiplier differences.
struct StateDifference {
  double position = 0, rotation = 0, velocity = 0, multiplier = 0;
};

inline StateDifference spatial_difference(const MechanicalState& a, const MechanicalState& b) {
  StateDifference d;
  for (Eigen::Index n = 0; n < a.q.size() / 7; ++n) {
    const Pose<double> pa = pose_of(a.q.data() + 7 * n), pb = pose_of(b.q.data() + 7 * n);
    d.position = std::max(d.position, (pa.x - pb.x).norm());
    d.rotation = std::max(d.rotation, log_so3<double>(Eigen::Matrix3d(pa.R.transpose() * pb.R)).norm());
  }
  d.velocity = (a.v - b.v).cwiseAbs().maxCoeff();
  d.multiplier = a.lambda.size() ? (a.lambda - b.lambda).cwiseAbs().maxCoeff() : 0.0;
  return d;
}

/// Order of convergence in time on the group from runs at decreasing step sizes hs: the differences
/// of successive runs' final states (a Cauchy sequence, so the slope of the error itself), fitted
/// against h for positions, rotations, velocities and multipliers; `label` prefixes the printout.
struct GroupOrders {
  double position = 0, rotation = 0, velocity = 0, multiplier = 0;
};

inline GroupOrders successive_difference_orders(const std::vector<double>& hs, const std::vector<RunSummary>& runs,
                                                const std::string& label) {
  std::vector<double> ex, er, ev, el;
  for (size_t k = 0; k + 1 < runs.size(); ++k) {
    const StateDifference d = spatial_difference(runs[k].final_state, runs[k + 1].final_state);
    ex.push_back(d.position);
    er.push_back(d.rotation);
    ev.push_back(d.velocity);
    el.push_back(d.multiplier);
    std::printf("%sh %.2e: |dx| %.3e m, |dR| %.3e rad, |dv| %.3e, |dlambda| %.3e\n", label.c_str(), hs[k], d.position,
                d.rotation, d.velocity, d.multiplier);
  }
  const std::vector<double> h_fit(hs.begin(), hs.end() - 1);
  const GroupOrders o{fitted_slope(h_fit, ex), fitted_slope(h_fit, er), fitted_slope(h_fit, ev), fitted_slope(h_fit, el)};
  std::printf("%sslopes: position %.2f, rotation %.2f, velocity %.2f, multiplier %.2f\n", label.c_str(), o.position,
              o.rotation, o.velocity, o.multiplier);
  return o;
}

// ---- Random samples and small vectors ---------------------------------------------------------------

inline constexpr double kPi = 3.14159265358979323846;

/// A sample of the uniform distribution on [a, b).
inline double uniform(std::mt19937& rng, double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); }

/// n samples of the uniform distribution on [a, b).
inline Eigen::VectorXd random_vector(std::mt19937& rng, int n, double a, double b) {
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) x[i] = uniform(rng, a, b);
  return x;
}

/// The vector of the numbers x.
inline Eigen::VectorXd vec(std::initializer_list<double> x) {
  Eigen::VectorXd v(static_cast<int>(x.size()));
  int i = 0;
  for (double xi : x) v[i++] = xi;
  return v;
}

/// A pose at a uniform position in [−1, 1)³, rotated by a uniform angle in [0, max_angle) about a
/// uniform direction.
inline Pose<double> random_pose(std::mt19937& rng, double max_angle = 3.0) {
  const Eigen::Vector3d w = random_vector(rng, 3, -1.0, 1.0);
  return {random_vector(rng, 3, -1.0, 1.0), exp_so3<double>(Eigen::Vector3d(uniform(rng, 0.0, max_angle) * w.normalized()))};
}

/// A marker of frame `slot` at p in the frame, rotated from it by exp(ŵ).
inline SpatialMarker marker(int slot, const Eigen::Vector3d& p, const Eigen::Vector3d& w = Eigen::Vector3d::Zero()) {
  SpatialMarker m;
  m.slot = slot;
  m.position = p;
  m.rotation = exp_so3<double>(w);
  return m;
}

/// The 7 stored numbers (position, unit quaternion) of each pose, one pose after the other.
inline Eigen::VectorXd stored(const std::vector<Pose<double>>& poses) {
  Eigen::VectorXd q(7 * poses.size());
  for (size_t k = 0; k < poses.size(); ++k) store_pose(poses[k].x, poses[k].R, q.data() + 7 * k);
  return q;
}

/// |approx − exact| / |exact| (Frobenius norms).
inline double relative_error(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& approx) {
  return (approx - exact).norm() / exact.norm();
}

/// meshes/NAME of the source tree.
inline std::string mesh_path(const std::string& name) { return std::string(ALPHAFLEX_SOURCE_DIR) + "/meshes/" + name; }

// ---- Central differences: the one finite-difference helper of the tests ---------------------------
// Finite differences only check (docs/architecture.md): every tangent of the code is exact and is
// compared here with central differences, whose error is O(h²) truncation plus O(ε|f|/h) round-off;
// at h ≈ 1e-6 of the variable's scale both are ~1e-10..1e-12 of |f|, well below the tests'
// tolerances. Each test states the step it uses.

using VectorFunction = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;
/// The step h_j of column j, given the variable's value x_j (0 on the group: the increment's origin).
using FdStep = std::function<double(int j, double x_j)>;

/// The default step rule: h_j = 1e-6 max(1, |x_j|), relative for large values, absolute near zero.
inline double default_fd_step(int, double x_j) { return 1e-6 * std::max(1.0, std::abs(x_j)); }

/// The same step h for every column.
inline FdStep fixed_fd_step(double h) {
  return [h](int, double) { return h; };
}

/// ∂f/∂x on a vector space: column j = [f(x + h_j e_j) − f(x − h_j e_j)] / (2 h_j).
inline Eigen::MatrixXd central_differences(const VectorFunction& f, const Eigen::VectorXd& x,
                                           const FdStep& step = default_fd_step) {
  Eigen::MatrixXd J;
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double h = step(static_cast<int>(j), x[j]);
    Eigen::VectorXd xp = x, xm = x;
    xp[j] += h;
    xm[j] -= h;
    const Eigen::VectorXd col = (f(xp) - f(xm)) / (2.0 * h);
    if (j == 0) J.resize(col.size(), x.size());
    J.col(j) = col;
  }
  return J;
}

/// q ∘ exp(d) frame by frame: q stores 7 numbers per R³×SO(3) frame (position, unit quaternion),
/// d has 6 per frame (δx in the world frame, δθ in the body frame; model/node.hpp's retraction).
inline Eigen::VectorXd retracted_frames(const Eigen::VectorXd& q, const Eigen::VectorXd& d) {
  Eigen::VectorXd out(q.size());
  for (Eigen::Index k = 0; k < q.size() / 7; ++k)
    retract(NodeKind::Frame3D, q.data() + 7 * k, d.data() + 6 * k, out.data() + 7 * k);
  return out;
}

/// The derivative of f along the right-trivialized increments of frames (R³×SO(3)), 6 columns per
/// frame: column j = [f(q ∘ exp(h_j e_j)) − f(q ∘ exp(−h_j e_j))] / (2 h_j), h_j = step(j, 0).
inline Eigen::MatrixXd central_differences_on_frames(const VectorFunction& f, const Eigen::VectorXd& q,
                                                     const FdStep& step) {
  const Eigen::Index n = q.size() / 7 * 6;
  Eigen::MatrixXd J;
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = step(static_cast<int>(j), 0.0);
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(n, j) * h;
    const Eigen::VectorXd col = (f(retracted_frames(q, e)) - f(retracted_frames(q, -e))) / (2.0 * h);
    if (j == 0) J.resize(col.size(), n);
    J.col(j) = col;
  }
  return J;
}

/// Which of an element's state vectors a derivative is taken with respect to: K = ∂r/∂q (on the
/// group for frames), C = ∂r/∂q̇, M = ∂r/∂q̈.
enum class Wrt { q, v, qdd };

inline const Eigen::VectorXd& variable(const LocalState& s, Wrt w) { return w == Wrt::q ? s.q : w == Wrt::v ? s.v : s.qdd; }

/// x ↦ r(s with x in place of its q, q̇ or q̈): the function whose central differences are K, C, M.
inline VectorFunction element_residual_of(const Element& e, const LocalState& s, Wrt w) {
  return [&e, s, w](const Eigen::VectorXd& x) {
    LocalState p = s;
    (w == Wrt::q ? p.q : w == Wrt::v ? p.v : p.qdd) = x;
    LocalResidual out;
    out.reset(static_cast<int>(p.v.size()), false);
    e.evaluate(p, out, false);
    return out.r;
  };
}

}  // namespace alphaflex::testing
