#include "alphaflex/io/scene.hpp"

#include "scene_reader.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/time_function.hpp"
#include "alphaflex/elements/applied_load_2d.hpp"
#include "alphaflex/elements/rigid_body_2d.hpp"
#include "alphaflex/elements/spring_damper_2d.hpp"
#include "alphaflex/joints/planar_joints.hpp"

namespace alphaflex {
namespace {

using namespace scene_detail;  // Reader, Section, Schema, Key, Item, SceneBuilder, ...

// ---- Sections ---------------------------------------------------------------------------------

const Schema& top_schema() {
  static const Schema s{"top", {
      {"name", KeyType::Text, "–", "the file name without directory and extension (`inputs/andrews.yaml` → `andrews`)",
       "base name of the output files NAME.csv, NAME.h5, NAME.xdmf; non-empty, no spaces, no `/` or `\\`"},
      {"description", KeyType::Text, "–", "empty", "free text for the reader; not used by the program"},
      {"parameters", KeyType::Map, "any", "none", "named values (name: number or expression) usable in every expression"},
      {"dimension", KeyType::Integer, "–", "2", "2: planar bodies (x, y, θ) and the planar sections; 3: spatial bodies, beams, shells and joints", Range::closed(2, 3)},
      {"gravity", KeyType::List, "m/s²", "zero", "gravitational acceleration; acts on every body and particle with a mass, and on beams and shells", {}, "", "[gx, gy] (2D) or [gx, gy, gz] (3D)"},
      {"load", KeyType::Map, "–", "factor 1", "`{factor: F}`: multiplies every applied load (forces, moments, torques, pressures, gravity); a static analysis steps the load from 0 to F"},
      {"mesh", KeyType::Map, "–", "none", "the gmsh mesh of the beams and shells"},
      {"beams", KeyType::List, "–", "none", "beam blocks on curve groups of the mesh"},
      {"shells", KeyType::List, "–", "none", "shell blocks on surface groups of the mesh (3D)"},
      {"solver", KeyType::Map, "–", "all defaults", "time integration and statics"},
      {"output", KeyType::Map, "–", "all defaults", "field output, checkpoints, progress"},
      {"bodies", KeyType::List, "–", "none (the scene needs bodies or beams)", "bodies"},
      {"joints", KeyType::List, "–", "none", "joints"},
      {"forces", KeyType::List, "–", "none", "force elements and loads"},
      {"sensors", KeyType::List, "–", "none", "sensors: the columns of NAME.csv"},
      {"study", KeyType::Map, "–", "none", "read by `alphaflex study` only; `alphaflex run` ignores it"},
      {"modes", KeyType::Map, "–", "none", "read by `alphaflex modes` only (`modes`, docs/modes.md); `alphaflex run` ignores it"},
  }};
  return s;
}

const Schema& load_schema() {
  static const Schema s{"load", {{"factor", KeyType::Number, "–", "1", "multiplies every applied load; a static analysis steps it from 0"}}};
  return s;
}

const Schema& solver_schema() {
  static const Schema s{"solver", {
      {"analysis", KeyType::Choice, "–", "`dynamic`", "`dynamic` (generalized-α) or `static` (quasi-static load stepping; see [statics](#statics))", {}, "", "", {"dynamic", "static"}},
      {"scheme", KeyType::Choice, "–", "`generalized-alpha`", "time integration scheme", {}, "", "", {"generalized-alpha", "hht", "newmark"}},
      {"rho_inf", KeyType::Number, "–", "0.7 (`generalized-alpha`), 0.9 (`hht`)",
       "spectral radius at infinity ρ∞; in [0, 1] for `generalized-alpha` and `newmark`, in [0.5, 1] for `hht`; for `newmark` it gives the damped Newmark γ = (3 − ρ∞)/(2(1 + ρ∞)), β = 1/(1 + ρ∞)² (first order unless ρ∞ = 1); not together with explicit parameters"},
      {"alpha_m", KeyType::Number, "–", "from ρ∞", "explicit α_m (`generalized-alpha` only; then `alpha_m`, `alpha_f`, `beta`, `gamma` are all required); α_m ≠ 1"},
      {"alpha_f", KeyType::Number, "–", "from ρ∞", "explicit α_f (as above); α_f ≠ 1"},
      {"beta", KeyType::Number, "–", "from ρ∞; 0.25 for `newmark`", "explicit β (`generalized-alpha` with all four, or `newmark` without `rho_inf`); β > 0"},
      {"gamma", KeyType::Number, "–", "from ρ∞; 0.5 for `newmark`", "explicit γ (as `beta`); γ ≥ 0"},
      {"h", KeyType::Number, "s", "1e-3", "time step; at most `t_end`, and t_end/h ≤ 1e10", Range::positive(), "step size (s)"},
      {"t_end", KeyType::Number, "s", "1", "final time (the run starts at t = 0)", Range::positive(), "final time (s)"},
      {"step_cuts", KeyType::Integer, "–", "0",
       "Newton failure policy of a dynamic run: 0 stops at the first step whose Newton iteration fails (the paper's fixed-step scheme); N > 0 retries such a step from the same state with h halved, up to N times in a row, and doubles h again (up to `h`) after 4 converged steps. The summary counts the cuts and the smallest h. Second order in time holds for constant h only: a run with cuts carries the extra error of the step changes (tests/unit/test_step_cuts.cpp: 3 % of the motion's range on the slider-crank against 1 % with fixed h)",
       Range::closed(0, 30)},
      {"scaling", KeyType::Flag, "–", "on", "scale the iteration matrix (dynamic rows × βh², unknown βh²Δλ; Bottasso, Dopico & Trainelli 2006)"},
      {"consistent_start", KeyType::Flag, "–", "on", "project the initial positions onto Φ = 0 (minimum-norm correction) and the velocities onto Φ_q q̇ + Φ_t = 0 (correction of least kinetic energy) before the first step"},
      {"newton", KeyType::Map, "–", "all defaults", "Newton iteration (`solver.newton`)"},
      {"static", KeyType::Map, "–", "all defaults", "load stepping of a static analysis or of `initial_static` (`solver.static`)"},
      {"linear", KeyType::Map, "–", "all defaults", "the linear solver of each Newton iteration (`solver.linear`)"},
      {"initial_static", KeyType::Flag, "–", "off", "before the dynamic run, bring the initial state to static equilibrium under the loads at t = 0 (load stepping as `static`); the dynamics then starts from that pre-loaded state at rest"},
  }};
  return s;
}

const Schema& static_schema() {
  static const Schema s{"solver.static", {
      {"steps", KeyType::Integer, "–", "10", "initial number of equal load steps", Range::closed(1, 1000000)},
      {"max_cuts", KeyType::Integer, "–", "12", "halvings of one load step allowed in a row after Newton failures", Range::closed(0, 50)},
  }};
  return s;
}

const Schema& newton_schema() {
  static const Schema s{"solver.newton", {
      {"max_iter", KeyType::Integer, "–", "20", "iterations per step", Range::closed(1, 1000000)},
      {"rtol", KeyType::Number, "–", "1e-9", "relative tolerance on the last correction", Range::positive(), "tolerance"},
      {"atol", KeyType::Number, "m, rad", "1e-12", "absolute tolerance on the coordinate correction", Range::non_negative(), "tolerance (m, rad)"},
      {"atol_lambda", KeyType::Number, "N, N·m", "1e-9", "absolute tolerance on the multiplier correction", Range::non_negative(), "tolerance (N)"},
      {"modified", KeyType::Flag, "–", "off", "modified Newton: keep the factorization of S_t across iterations and steps"},
      {"max_contraction", KeyType::Number, "–", "0.5",
       "with `modified`: contraction rate θ = ‖Δ_k‖∞/‖Δ_{k−1}‖∞ above which S_t is assembled and factored afresh",
       Range::open(0, 1), "contraction rate"},
  }};
  return s;
}

const Schema& linear_schema() {
  static const Schema s{"solver.linear", {
      {"low_rank", KeyType::Number, "–", "off",
       "block low-rank factorization in MUMPS (BLR: ICNTL(35) = 2) with this dropping tolerance ε (CNTL(7)): off-diagonal blocks of the fronts are kept as low-rank products accurate to ε relative to the block; fewer flops and factor entries (the run summary gives both counts). Only the Newton matrix is approximate, the residual stays exact: converged results differ from the exact factorization's by the Newton tolerance, while a loose ε costs Newton iterations (or convergence). Off (exact LU) when absent; measurements in docs/performance.md",
       Range::open(0, 1), "tolerance"},
  }};
  return s;
}

const Schema& output_schema() {
  static const Schema s{"output", {
      {"every", KeyType::Integer, "steps", "1", "write the fields to NAME.h5 every N steps. The initial state (t = 0) and the last step are always written. Sensors (NAME.csv) are written every step regardless", Range::closed(1, 1000000)},
      {"hdf5", KeyType::Flag, "–", "on", "write NAME.h5 and NAME.xdmf; with `off` only NAME.csv"},
      {"commit_interval", KeyType::Number, "s (wall time)", "1",
       "how long a part file of the results stays open before it is committed (renamed into place and listed in NAME.h5 and NAME.xdmf; docs/running.md): a run killed at any moment opens in ParaView up to its last commit. 0: every output step. The interval grows to 10 × the last commit's cost, so commits stay under ~10 % of a run; the first output step, checkpoints, the end, a failure and a stop signal always commit",
       Range::non_negative(), "wall-time interval (s; 0: every output step is committed at once)"},
      {"checkpoint_every", KeyType::Text, "steps, or s/min/h", "none",
       "write NAME.checkpoint.h5 every so many steps (an integer ≥ 1) or so much wall time (`\"600 s\"`, `\"10 min\"`, `\"2 h\"`; dynamic runs); a checkpoint is also written at the end of every run, after a Newton failure (the last converged state) and on a stop signal. `alphaflex run SCENE --restart OUTDIR/NAME.checkpoint.h5 -o OUTDIR` goes on from it (docs/running.md)",
       {}, "", "integer ≥ 1, or a wall time with its unit"},
      {"checkpoint_keep", KeyType::Integer, "–", "1", "how many checkpoints to keep (NAME.checkpoint.h5, NAME.checkpoint.1.h5, …)", Range::closed(1, 1000)},
      {"progress", KeyType::Number, "s (wall time)", "30",
       "rank 0, on stderr: when stderr is not a terminal (batch logs), a line `progress: t = … s (… %), step … of …, Newton … per step, wall … s, ETA … s` every this many seconds (0: none), `load factor = …` and load steps in a static analysis; on a terminal the same line is rewritten in place 4 times a second and cleared before the summary",
       Range::non_negative(), "wall-time interval (s; 0: no progress lines in batch logs)"},
  }};
  return s;
}

void read_solver(Reader& rd, const YAML::Node& node, RunSettings& rs, std::vector<std::string>& warnings) {
  if (!node) return;
  const Section s(rd, node, "solver", solver_schema());
  if (s.has("analysis") && s.choice("analysis") == 1) rs.analysis = Analysis::Static;
  rs.initial_static = s.flag("initial_static", rs.initial_static);
  rs.step_cuts = s.integer("step_cuts", rs.step_cuts);
  if (s.has("static")) {
    const Section st(rd, s.node("static"), "solver.static", static_schema());
    rs.statics.steps = st.integer("steps", rs.statics.steps);
    rs.statics.max_cuts = st.integer("max_cuts", rs.statics.max_cuts);
  }
  enum { GeneralizedAlpha, Hht, Newmark };
  const int scheme = s.choice("scheme", GeneralizedAlpha);
  const bool explicit_any = s.has("alpha_m") || s.has("alpha_f") || s.has("beta") || s.has("gamma");
  double rho = scheme == Hht ? 0.9 : 0.7;
  if (s.has("rho_inf")) {
    rho = s.number("rho_inf");
    const double lo = scheme == Hht ? 0.5 : 0.0;
    if (!(rho >= lo && rho <= 1.0))
      rd.fail(s.node("rho_inf"), "solver.rho_inf",
              "expected a spectral radius in [" + std::string(scheme == Hht ? "0.5" : "0") + ", 1]" +
                  (scheme == Hht ? " for HHT (α = (1 − ρ∞)/(1 + ρ∞) ∈ [0, 1/3])" : "") + ", got " + s.node("rho_inf").Scalar());
  }
  if (scheme == GeneralizedAlpha) {
    if (explicit_any) {
      if (s.has("rho_inf")) rd.fail(s.node("rho_inf"), "solver.rho_inf", "give either rho_inf or alpha_m/alpha_f/beta/gamma, not both");
      for (const char* k : {"alpha_m", "alpha_f", "beta", "gamma"})
        if (!s.has(k)) rd.fail(node, std::string("solver.") + k, "missing: explicit parameters need all of alpha_m, alpha_f, beta, gamma");
      rs.parameters = AlphaParameters::explicit_values(s.number("alpha_m"), s.number("alpha_f"), s.number("beta"), s.number("gamma"));
    } else {
      rs.parameters = AlphaParameters::from_rho_inf(rho);
    }
  } else if (scheme == Hht) {
    if (explicit_any) rd.fail(node, "solver", "scheme hht takes rho_inf only (alpha_m, alpha_f, beta, gamma follow from it)");
    rs.parameters = AlphaParameters::hht(rho);
  } else {
    if (s.has("alpha_m") || s.has("alpha_f"))
      rd.fail(node, "solver", "scheme newmark has alpha_m = alpha_f = 0: give rho_inf, or beta and gamma");
    if (s.has("rho_inf") && (s.has("beta") || s.has("gamma")))
      rd.fail(s.node("rho_inf"), "solver.rho_inf", "give either rho_inf or beta/gamma for scheme newmark, not both");
    if (s.has("rho_inf"))  // damped Newmark with spectral radius ρ∞: γ = (3 − ρ∞)/(2(1 + ρ∞)), β = 1/(1 + ρ∞)²
      rs.parameters = AlphaParameters::newmark(1.0 / ((1.0 + rho) * (1.0 + rho)), (3.0 - rho) / (2.0 * (1.0 + rho)));
    else
      rs.parameters = AlphaParameters::newmark(s.number("beta", 0.25), s.number("gamma", 0.5));
  }
  try {
    rs.parameters.validate();
  } catch (const InputError& e) {
    rd.fail(node, "solver", e.what());
  }
  warnings = rs.parameters.warnings();
  rs.h = s.number("h", rs.h);
  rs.t_end = s.number("t_end", rs.t_end);
  if (rs.h > rs.t_end) rd.fail(s.has("h") ? s.node("h") : node, "solver.h", "the step size exceeds solver.t_end");
  if (rs.t_end / rs.h > 1e10)
    rd.fail(s.has("h") ? s.node("h") : node, "solver.h", "t_end/h exceeds 1e10 steps; choose a larger step size");
  rs.integrator.scaling = s.flag("scaling", rs.integrator.scaling);
  rs.integrator.consistent_start = s.flag("consistent_start", rs.integrator.consistent_start);
  if (s.has("newton")) {
    const Section n(rd, s.node("newton"), "solver.newton", newton_schema());
    NewtonOptions& o = rs.integrator.newton;
    o.max_iterations = n.integer("max_iter", o.max_iterations);
    o.rtol = n.number("rtol", o.rtol);
    o.atol = n.number("atol", o.atol);
    o.atol_lambda = n.number("atol_lambda", o.atol_lambda);
    o.modified = n.flag("modified", o.modified);
    o.max_contraction = n.number("max_contraction", o.max_contraction);
  }
  rs.statics.newton = rs.integrator.newton;
  if (s.has("linear")) {
    const Section l(rd, s.node("linear"), "solver.linear", linear_schema());
    rs.low_rank = l.number("low_rank", rs.low_rank);
  }
}

void read_output(Reader& rd, const YAML::Node& node, RunSettings& rs) {
  const Section o(rd, node, "output", output_schema());
  rs.commit_interval = o.number("commit_interval", rs.commit_interval);
  if (o.has("checkpoint_every")) {
    // A whole number of steps, or a wall time with its unit: "600 s", "10 min", "2 h".
    const YAML::Node c = o.node("checkpoint_every");
    const char* expected = "expected a number of steps (an integer >= 1) or a wall time with its unit, e.g. \"600 s\", \"10 min\", \"2 h\"";
    std::istringstream in(c.IsScalar() ? c.Scalar() : std::string());
    double value = 0.0;
    std::string unit, rest;
    in >> value >> unit;
    if (!unit.empty()) {
      in >> rest;
      if (!(value > 0.0) || !rest.empty() || (unit != "s" && unit != "min" && unit != "h"))
        rd.fail(c, "output.checkpoint_every", expected);
      rs.checkpoint_wall = value * (unit == "s" ? 1.0 : unit == "min" ? 60.0 : 3600.0);
    } else {
      if (!c.IsScalar()) rd.fail(c, "output.checkpoint_every", expected);
      rs.checkpoint_steps = rd.integer(c, "output.checkpoint_every", 1, 1000000000);
    }
  }
  rs.checkpoint_keep = o.integer("checkpoint_keep", rs.checkpoint_keep);
  rs.progress_interval = o.number("progress", rs.progress_interval);
  rs.output_every = o.integer("every", rs.output_every);
  rs.hdf5 = o.flag("hdf5", rs.hdf5);
}

std::vector<int> node_list(int a, int b) {
  std::vector<int> v;
  if (a >= 0) v.push_back(a);
  if (b >= 0) v.push_back(b);
  return v;
}

// ---- Planar bodies ------------------------------------------------------------------------------

void read_rigid_body_2d(const Item& it) {
  const Section& k = it.keys;
  Node nd;
  nd.name = it.name;
  nd.kind = NodeKind::RigidBody2D;
  const double m = k.number("mass"), J = k.number("inertia");
  const Eigen::Vector2d p = k.vec2("position"), v = k.vec2("velocity");
  nd.q0 = Eigen::Vector3d(p.x(), p.y(), k.number("angle", 0.0));
  nd.v0 = Eigen::Vector3d(v.x(), v.y(), k.number("angular_velocity", 0.0));
  const int id = it.model.add_node(nd);
  it.model.add_element(std::make_unique<RigidBody2D>(it.name, id, m, J, it.sb.gravity.head<2>()));
}

void read_particle_2d(const Item& it) {
  const Section& k = it.keys;
  const double m = k.number("mass", 0.0);
  Node nd;
  nd.name = it.name;
  nd.kind = NodeKind::Particle2D;
  nd.q0 = k.vec2("position");
  nd.v0 = k.vec2("velocity");
  const int id = it.model.add_node(nd);
  if (m > 0.0) it.model.add_element(std::make_unique<PointMass>(it.name, id, it.model.node(id), m, it.sb.gravity.head<2>()));
}

void read_line_particle_2d(const Item& it) {
  const Section& k = it.keys;
  const double m = k.number("mass", 0.0);
  Node nd;
  nd.name = it.name;
  nd.kind = NodeKind::LineParticle2D;
  nd.line_origin = k.vec2("origin");
  const Eigen::Vector2d d = k.vec2("direction");
  if (d.norm() == 0.0) it.rd.fail(k.node("direction"), it.at("direction"), "expected a non-zero direction");
  nd.line_direction = d.normalized();
  const Eigen::Vector2d p = k.vec2("position");
  const Eigen::Vector2d rel = p - nd.line_origin;
  const double s = rel.dot(nd.line_direction);
  if ((rel - s * nd.line_direction).norm() > 1e-9 * std::max(1.0, rel.norm()))
    it.rd.fail(k.node("position"), it.at("position"), "the point is not on the line through `origin` along `direction`");
  nd.q0 = Eigen::VectorXd::Constant(1, s);
  nd.v0 = Eigen::VectorXd::Constant(1, k.number("velocity", 0.0));
  const int id = it.model.add_node(nd);
  if (m > 0.0) it.model.add_element(std::make_unique<PointMass>(it.name, id, it.model.node(id), m, it.sb.gravity.head<2>()));
}

// ---- Planar joints ------------------------------------------------------------------------------

/// body1/point1, body2/point2 or location: the keys shared by revolute, point_on_line, prismatic.
std::vector<Key> two_point_keys() {
  return {{"body1", KeyType::Text, "–", kRequired, "the first body; not `ground`"},
          {"point1", KeyType::Vec2, "m", "[0, 0]", "point of body1, body frame relative to its centre of mass"},
          {"body2", KeyType::Text, "–", "`ground`", "the second body or `ground`; different from body1"},
          {"point2", KeyType::Vec2, "m", "[0, 0]", "point of body2 in its body frame; a world point when body2 is `ground`"},
          {"location", KeyType::Vec2, "m", "–",
           "instead of `point1`/`point2`: the world point of the joint at t = 0, converted to point1 and point2 with the bodies' initial positions and angles"}};
}

std::vector<Key> with(std::vector<Key> keys, std::vector<Key> more) {
  keys.insert(keys.end(), more.begin(), more.end());
  return keys;
}

/// The two markers of a two-point joint (body2 absent: ground).
struct TwoPoints {
  int b1 = -1, b2 = -1;
  std::vector<int> nodes;
  Eigen::Vector2d s1, s2;
};

TwoPoints two_points(const Item& it, bool default_point2_coincident) {
  const Section& k = it.keys;
  TwoPoints tp;
  tp.b1 = it.sb.body(it.node, "body1", it.path, false);
  tp.b2 = k.has("body2") ? it.sb.body(it.node, "body2", it.path, true) : -1;
  if (tp.b1 == tp.b2) it.rd.fail(k.node("body2"), it.at("body2"), "a joint needs two different bodies");
  if (k.has("location")) {
    if (k.has("point1") || k.has("point2")) it.rd.fail(k.node("location"), it.at("location"), "give either location or point1/point2");
    const Eigen::Vector2d loc = k.vec2("location");
    tp.s1 = it.sb.to_local(tp.b1, loc);
    tp.s2 = it.sb.to_local(tp.b2, loc);
  } else {
    tp.s1 = k.vec2("point1");
    const Eigen::Vector2d p1 = it.sb.initial_position(tp.b1, tp.s1);
    tp.s2 = k.has("point2") || !default_point2_coincident ? k.vec2("point2")
                                                          : (tp.b2 < 0 ? p1 : it.sb.to_local(tp.b2, p1));
  }
  tp.nodes = node_list(tp.b1, tp.b2);
  return tp;
}

PlanarMarker marker1(const Item& it, const TwoPoints& tp) { return it.sb.marker(tp.b1, tp.s1, tp.nodes, it.node, it.at("point1")); }
PlanarMarker marker2(const Item& it, const TwoPoints& tp) { return it.sb.marker(tp.b2, tp.s2, tp.nodes, it.node, it.at("point2")); }

/// The initial relative angle θ1 − θ2 that a fixed or prismatic joint keeps.
double relative_angle(const Model& model, const TwoPoints& tp) {
  return model.node(tp.b1).q0[2] - (tp.b2 >= 0 ? model.node(tp.b2).q0[2] : 0.0);
}

void read_revolute_2d(const Item& it) {
  const TwoPoints tp = two_points(it, false);
  it.model.add_constraint(std::make_unique<RevoluteJoint2D>(it.name, tp.nodes, marker1(it, tp), marker2(it, tp)));
}

void read_fixed_point_2d(const Item& it) {
  const Section& k = it.keys;
  const int b1 = it.sb.body(it.node, "body", it.path, false);
  const Eigen::Vector2d s1 = k.vec2("point");
  const Eigen::Vector2d loc = k.has("location") ? k.vec2("location") : it.sb.initial_position(b1, s1);
  const auto nodes = node_list(b1, -1);
  it.model.add_constraint(std::make_unique<RevoluteJoint2D>(it.name, nodes, it.sb.marker(b1, s1, nodes, it.node, it.at("point")),
                                                            PlanarMarker::ground(loc)));
}

void read_fixed_2d(const Item& it) {
  const TwoPoints tp = two_points(it, true);
  for (int b : {tp.b1, tp.b2})
    if (b >= 0 && !it.model.node(b).has_angle())
      it.rd.fail(it.node, it.path, "a fixed joint locks the rotation: '" + it.model.node(b).name + "' must be a rigid_body or beam node");
  it.model.add_constraint(std::make_unique<FixedJoint2D>(it.name, tp.nodes, marker1(it, tp), marker2(it, tp), relative_angle(it.model, tp)));
}

Eigen::Vector2d joint_axis_2d(const Item& it) {
  const Eigen::Vector2d axis = it.keys.vec2("axis");
  if (axis.norm() == 0.0) it.rd.fail(it.keys.node("axis"), it.at("axis"), "expected a non-zero direction");
  return axis;
}

void read_point_on_line_2d(const Item& it) {
  const TwoPoints tp = two_points(it, false);
  const PlanarMarker m1 = marker1(it, tp), m2 = marker2(it, tp);
  it.model.add_constraint(std::make_unique<PointOnLineJoint2D>(it.name, tp.nodes, m1, m2, joint_axis_2d(it)));
}

void read_prismatic_2d(const Item& it) {
  const TwoPoints tp = two_points(it, false);
  const PlanarMarker m1 = marker1(it, tp), m2 = marker2(it, tp);
  const Eigen::Vector2d axis = joint_axis_2d(it);
  if (!it.model.node(tp.b1).has_angle())
    it.rd.fail(it.node["body1"], it.at("body1"), "a prismatic joint fixes the relative rotation: body1 must be a rigid_body");
  if (tp.b2 >= 0 && !it.model.node(tp.b2).has_angle())
    it.rd.fail(it.node["body2"], it.at("body2"), "a prismatic joint fixes the relative rotation: body2 must be a rigid_body or ground");
  it.model.add_constraint(std::make_unique<PrismaticJoint2D>(it.name, tp.nodes, m1, m2, axis, relative_angle(it.model, tp)));
}

// ---- Planar forces ------------------------------------------------------------------------------

void read_spring_damper_2d(const Item& it) {
  const Section& k = it.keys;
  const int b1 = it.sb.body(it.node, "body1", it.path, true);
  const int b2 = k.has("body2") ? it.sb.body(it.node, "body2", it.path, true) : -1;
  if (b1 == b2) it.rd.fail(k.node("body2"), it.at("body2"), "a spring needs two different bodies (or one body and ground)");
  const Eigen::Vector2d s1 = k.vec2("point1"), s2 = k.vec2("point2");
  const auto nodes = node_list(b1, b2);
  const PlanarMarker m1 = it.sb.marker(b1, s1, nodes, it.node, it.at("point1"));
  const PlanarMarker m2 = it.sb.marker(b2, s2, nodes, it.node, it.at("point2"));
  const double stiffness = k.number("stiffness"), damping = k.number("damping", 0.0);
  std::optional<Eigen::Vector2d> axis;
  if (k.has("direction")) {
    const Eigen::Vector2d d = k.vec2("direction");
    if (d.norm() == 0.0) it.rd.fail(k.node("direction"), it.at("direction"), "expected a non-zero direction");
    axis = d.normalized();
  }
  const Eigen::Vector2d d0 = it.sb.initial_position(b1, s1) - it.sb.initial_position(b2, s2);
  const double initial = axis ? axis->dot(d0) : d0.norm();
  double l0 = initial;
  if (k.has("rest_length")) {
    l0 = k.number("rest_length");
    if (!axis && l0 < 0.0) it.rd.fail(k.node("rest_length"), it.at("rest_length"), "expected a non-negative length (m)");
  }
  if (!axis && initial < 1e-12)
    it.rd.fail(it.node, it.path, "the two points coincide at t = 0, so a point-to-point spring has no direction; "
                                 "give `direction` for a spring along a fixed axis");
  it.model.add_element(std::make_unique<SpringDamper2D>(it.name, nodes, m1, m2, stiffness, damping, l0, axis));
}

void read_force_2d(const Item& it) {
  const int b = it.sb.body(it.node, "body", it.path, false);
  const Eigen::Vector2d s = it.keys.vec2("point");
  const YAML::Node v = it.keys.node("value");
  if (!v.IsSequence() || v.size() != 2) it.rd.fail(v, it.at("value"), "expected [fx, fy], each a number or a time function (N)");
  it.model.add_element(std::make_unique<PointForce2D>(it.name, b, it.sb.marker(b, s, {b}, it.node, it.at("point")),
                                                      it.rd.function(v[0], it.at("value[0]")), it.rd.function(v[1], it.at("value[1]"))));
}

void read_torque_2d(const Item& it) {
  const int b = it.sb.body(it.node, "body", it.path, false);
  if (!it.model.node(b).has_angle()) it.rd.fail(it.node["body"], it.at("body"), "a torque needs a rigid_body (a particle has no rotation)");
  it.model.add_element(std::make_unique<Torque2D>(it.name, b, it.keys.function("value")));
}

// ---- Planar sensors -----------------------------------------------------------------------------

int rigid_2d(const Item& it, const char* key) {
  const int b = it.sb.body(it.node, key, it.path, false);
  if (!it.model.node(b).has_angle()) it.rd.fail(it.node[key], it.at(key), "expected a rigid_body (it has no angle)");
  return b;
}

void read_body_angle_2d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::BodyAngle;
  sn.node = rigid_2d(it, "body");
}

void read_relative_angle_2d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::RelativeAngle;
  sn.node = rigid_2d(it, "body");
  sn.node2 = rigid_2d(it, "relative_to");
}

void read_point_sensor_2d(const Item& it, Sensor& sn, Sensor::Kind kind) {
  sn.kind = kind;
  sn.node = it.sb.body(it.node, "body", it.path, false);
  const Eigen::Vector2d local = it.keys.vec2("point");
  sn.local = Eigen::Vector3d(local.x(), local.y(), 0.0);
  it.sb.marker(sn.node, local, {sn.node}, it.node, it.at("point"));
  sn.component = it.keys.choice("component");
  const Eigen::Vector2d p0 = it.sb.initial_position(sn.node, local);
  sn.initial = Eigen::Vector3d(p0.x(), p0.y(), 0.0);
}

void read_joint_reaction_2d(const Item& it, Sensor& sn) {
  sn.kind = Sensor::Kind::JointReaction;
  sn.constraint = scene_detail::sensor_joint(it);
  sn.component = it.keys.choice("component");
  if (sn.component == 2) sn.component = 5;  // mz: the sixth component of a reaction
}

}  // namespace

namespace scene_detail {

int sensor_joint(const Item& it) {
  const std::string jn = it.keys.text("joint");
  const int c = it.model.find_constraint(jn);
  if (c < 0) it.rd.fail(it.node["joint"], it.at("joint"), "no joint named '" + jn + "'");
  return c;
}

Schema type_schema(const std::string& name, const std::string& type_doc, std::vector<Key> keys) {
  keys.insert(keys.begin(), {{"name", KeyType::Text, "–", kRequired, "unique in its list"},
                             {"type", KeyType::Text, "–", kRequired, type_doc}});
  return Schema{name, std::move(keys)};
}

const SceneTypes& planar_types() {
  static const SceneTypes t = [] {
    SceneTypes t{{"body type", ""}, {"joint type", ""}, {"force type", ""}, {"sensor type", ""}, "", {}};
    const Key mass_required{"mass", KeyType::Number, "kg", kRequired, "positive (zero makes the mass matrix singular)",
                            Range::positive(), "mass (kg); a zero mass makes the mass matrix singular"};
    const Key mass_optional{"mass", KeyType::Number, "kg", "0", "0 = massless point (no inertia, no weight)", Range::non_negative(), "mass (kg)"};
    const Key velocity{"velocity", KeyType::Vec2, "m/s", "[0, 0]", "velocity at t = 0"};
    t.bodies.add("rigid_body", type_schema("bodies.2d.rigid_body", "`rigid_body`: x, y, θ of the centre of mass", {
        mass_required,
        {"inertia", KeyType::Number, "kg·m²", kRequired, "moment of inertia about the centre of mass", Range::positive(),
         "moment of inertia about the centre of mass (kg m^2); zero makes the mass matrix singular"},
        {"position", KeyType::Vec2, "m", kRequired, "world position of the centre of mass at t = 0"},
        {"angle", KeyType::Number, "rad", "0", "angle of the body frame at t = 0"},
        velocity,
        {"angular_velocity", KeyType::Number, "rad/s", "0", "at t = 0, counter-clockwise positive"}}), read_rigid_body_2d);
    t.bodies.add("particle", type_schema("bodies.2d.particle", "`particle`: x, y", {
        mass_optional, {"position", KeyType::Vec2, "m", kRequired, "world position at t = 0"}, velocity}), read_particle_2d);
    t.bodies.add("line_particle", type_schema("bodies.2d.line_particle", "`line_particle`: s along a fixed line", {
        mass_optional,
        {"origin", KeyType::Vec2, "m", "[0, 0]", "a world point of the line (s = 0)"},
        {"direction", KeyType::Vec2, "–", kRequired, "direction of the line (normalized by the program); non-zero"},
        {"position", KeyType::Vec2, "m", kRequired, "world position at t = 0; on the line (to 1e-9·max(1, distance from origin))"},
        {"velocity", KeyType::Number, "m/s", "0", "speed along `direction` at t = 0 (a number, not a vector)"}}), read_line_particle_2d);

    const Key axis{"axis", KeyType::Vec2, "–", kRequired, "direction in body2's frame (world when body2 is `ground`, a particle or a line particle); non-zero"};
    t.joints.add("revolute", type_schema("joints.2d.revolute", "`revolute`: pin, 2 equations", two_point_keys()), read_revolute_2d);
    t.joints.add("fixed_point", type_schema("joints.2d.fixed_point", "`fixed_point`: a body point pinned to the world, 2 equations", {
        {"body", KeyType::Text, "–", kRequired, "a body; not `ground`"},
        {"point", KeyType::Vec2, "m", "[0, 0]", "point of the body, body frame relative to its centre of mass"},
        {"location", KeyType::Vec2, "m", "the point's world position at t = 0", "world point it is pinned to"}}), read_fixed_point_2d);
    t.joints.add("fixed", type_schema("joints.2d.fixed", "`fixed`: clamp or weld, 3 equations; point2 defaults to the point of body2 at point1", two_point_keys()), read_fixed_2d);
    t.joints.add("point_on_line", type_schema("joints.2d.point_on_line", "`point_on_line`: point 1 on the line through point 2 along `axis`, 1 equation",
                                              with(two_point_keys(), {axis})), read_point_on_line_2d);
    t.joints.add("prismatic", type_schema("joints.2d.prismatic", "`prismatic`: slider, 2 equations", with(two_point_keys(), {axis})), read_prismatic_2d);

    t.loads.add("spring_damper", type_schema("forces.2d.spring_damper", "`spring_damper`: tension T = k·(L − L0) + c·L̇", {
        {"body1", KeyType::Text, "–", kRequired, "a body or `ground`"},
        {"point1", KeyType::Vec2, "m", "[0, 0]", "point of body1 (body frame; world point for `ground`)"},
        {"body2", KeyType::Text, "–", "`ground`", "a body or `ground`; different from body1"},
        {"point2", KeyType::Vec2, "m", "[0, 0]", "point of body2 (body frame; world point for `ground`)"},
        {"stiffness", KeyType::Number, "N/m", kRequired, "k", Range::non_negative(), "stiffness (N/m)"},
        {"damping", KeyType::Number, "N·s/m", "0", "c", Range::non_negative(), "damping (N s/m)"},
        {"rest_length", KeyType::Number, "m", "the length L at t = 0", "L0; ≥ 0 for a point-to-point spring, any sign with `direction`"},
        {"direction", KeyType::Vec2, "–", "none", "a spring along this fixed world direction d (normalized), L = d·(r1 − r2); non-zero"}}),
                  read_spring_damper_2d);
    t.loads.add("force", type_schema("forces.2d.force", "`force`: a force at a body point", {
        {"body", KeyType::Text, "–", kRequired, "a body; not `ground`"},
        {"point", KeyType::Vec2, "m", "[0, 0]", "point of application, body frame relative to the centre of mass"},
        {"value", KeyType::List, "N", kRequired, "world components [fx, fy], each a number or a time function", {}, "", "[fx, fy]"}}), read_force_2d);
    t.loads.add("torque", type_schema("forces.2d.torque", "`torque`: a torque on a rigid body", {
        {"body", KeyType::Text, "–", kRequired, "a `rigid_body`"},
        {"value", KeyType::Function, "N·m", kRequired, "counter-clockwise positive"}}), read_torque_2d);

    const Key body{"body", KeyType::Text, "–", kRequired, "a body; not `ground`"};
    const Key point{"point", KeyType::Vec2, "m", "[0, 0]", "body frame relative to the centre of mass; [0, 0] for particles"};
    const Key xy{"component", KeyType::Choice, "–", kRequired, "world component", {}, "", "", {"x", "y"}};
    t.sensors.add("body_angle", type_schema("sensors.2d.body_angle", "`body_angle`: θ of a `rigid_body` (rad, not wrapped)", {
        {"body", KeyType::Text, "–", kRequired, "a `rigid_body`"}}), read_body_angle_2d);
    t.sensors.add("relative_angle", type_schema("sensors.2d.relative_angle", "`relative_angle`: θ_body − θ_relative_to (rad)", {
        {"body", KeyType::Text, "–", kRequired, "a `rigid_body`"},
        {"relative_to", KeyType::Text, "–", kRequired, "a `rigid_body`"}}), read_relative_angle_2d);
    const std::pair<const char*, Sensor::Kind> points[] = {
        {"point_position", Sensor::Kind::PointPosition}, {"point_displacement", Sensor::Kind::PointDisplacement},
        {"point_velocity", Sensor::Kind::PointVelocity}, {"point_acceleration", Sensor::Kind::PointAcceleration}};
    for (const auto& [name, kind] : points)  // one schema, four quantities (m, m, m/s, m/s²)
      t.sensors.add(name, type_schema(std::string("sensors.2d.") + name, std::string("`") + name + "` of a body point, world frame", {body, point, xy}),
                    [kind = kind](const Item& it, Sensor& sn) { read_point_sensor_2d(it, sn, kind); });
    t.sensors.add("joint_reaction", type_schema("sensors.2d.joint_reaction", "`joint_reaction`: what the joint exerts on its body1, world frame (N, N·m)", {
        {"joint", KeyType::Text, "–", kRequired, "a joint of `joints`"},
        {"component", KeyType::Choice, "–", kRequired, "force or moment component", {}, "", "", {"fx", "fy", "mz"}}}), read_joint_reaction_2d);
    return t;
  }();
  return t;
}

std::vector<const Schema*> section_schemas() {
  std::vector<const Schema*> v{&top_schema(), &load_schema(), &solver_schema(), &static_schema(), &newton_schema(), &linear_schema(), &output_schema()};
  for (const Schema* s : mesh_schemas()) v.push_back(s);
  v.push_back(&modes_schema());
  v.push_back(&campbell_schema());
  for (const auto& s : input::time_function_schemas()) v.push_back(&s);
  return v;
}

}  // namespace scene_detail

namespace {

/// Reads the list `section` (bodies, joints, forces, sensors): each item's name and type, its keys
/// checked against the type's schema, then the type's constructor.
template <class Build, class Open, class Done>
void read_items(Reader& rd, SceneBuilder& sb, const YAML::Node& list, const char* section, const char* what,
                const input::Registry<Build>& types, const std::string& note, Open open, Done done) {
  if (!list) return;
  if (!list.IsSequence()) rd.fail(list, section, std::string("expected a list of ") + what);
  for (size_t i = 0; i < list.size(); ++i) {
    const YAML::Node node = list[i];
    std::string path;
    const std::string name = open(node, i, path);
    const auto& type = types.find(rd, node, path, note);
    const Section keys(rd, node, path, type.schema);
    done(type.build, Item{rd, sb, sb.model_, node, name, path, keys});
  }
}

void read_bodies(Reader& rd, SceneBuilder& sb, const YAML::Node& list, const scene_detail::SceneTypes& types, bool spatial) {
  Model& model = sb.model_;
  read_items(rd, sb, list, "bodies", "bodies", types.bodies, types.body_note,
             [&](const YAML::Node& b, size_t i, std::string& path) {
               const std::string name = rd.item_name(b, "bodies", i, "expected a map with name, type, ...", path);
               if (name == "ground") rd.fail(b["name"], path + ".name", "'ground' is reserved for the fixed frame");
               if (model.find_node(name) >= 0)
                 rd.fail(b["name"], path + ".name", std::string(spatial ? "a body or mesh point" : "a body") + " named '" + name + "' exists already");
               return name;
             },
             [](const scene_detail::ItemBuild& build, const Item& it) { build(it); });
}

void read_joints(Reader& rd, SceneBuilder& sb, const YAML::Node& list, const scene_detail::SceneTypes& types) {
  Model& model = sb.model_;
  read_items(rd, sb, list, "joints", "joints", types.joints, "",
             [&](const YAML::Node& j, size_t i, std::string& path) {
               const std::string name = rd.item_name(j, "joints", i, "expected a map with name, type, ...", path);
               if (model.find_constraint(name) >= 0) rd.fail(j["name"], path + ".name", "a joint named '" + name + "' exists already");
               return name;
             },
             [](const scene_detail::ItemBuild& build, const Item& it) { build(it); });
}

void read_forces(Reader& rd, SceneBuilder& sb, const YAML::Node& list, const scene_detail::SceneTypes& types, bool spatial) {
  std::set<std::string> names;
  read_items(rd, sb, list, "forces", spatial ? "loads" : "force elements", types.loads, "",
             [&](const YAML::Node& f, size_t i, std::string& path) {
               const std::string name = rd.item_name(f, "forces", i, "expected a map with name, type, ...", path);
               if (!names.insert(name).second) rd.fail(f["name"], path + ".name", "a force named '" + name + "' exists already");
               return name;
             },
             [](const scene_detail::ItemBuild& build, const Item& it) { build(it); });
}

void read_sensors(Reader& rd, SceneBuilder& sb, const YAML::Node& list, const scene_detail::SceneTypes& types) {
  std::set<std::string> names;
  Model& model = sb.model_;
  read_items(rd, sb, list, "sensors", "sensors", types.sensors, "",
             [&](const YAML::Node& s, size_t i, std::string& path) { return rd.sensor_name(s, i, names, path); },
             [&](const scene_detail::SensorBuild& build, const Item& it) {
               Sensor sn;
               sn.name = it.name;
               build(it, sn);
               model.add_sensor(sn);
             });
}

Scene build(const YAML::Node& root, const std::string& label, const MeshLoader& mesh_loader,
            const std::vector<std::pair<YAML::Node, std::string>>& overrides) {
  Reader rd(label, mesh_loader);
  for (const auto& [node, text] : overrides) rd.add_override(node, text);
  Scene scene;
  scene.file = label;
  if (!root.IsMap()) rd.fail(root, "(top level)", "expected a map of sections (solver, bodies, joints, ...)");
  const Section top(rd, root, "", top_schema());
  // `study:` is read by `alphaflex study` (study/study_spec.hpp), `modes:` by `alphaflex modes`
  // (io/scene_modes.hpp); a run ignores them.
  rd.read_parameters(root["parameters"]);
  scene.name = top.text("name", std::filesystem::path(label).stem().string());
  if (scene.name.empty() || scene.name.find_first_of("/\\ ") != std::string::npos)
    rd.fail(root["name"], "name", "expected a plain file name (no spaces or slashes)");
  scene.description = top.text("description");
  read_solver(rd, root["solver"], scene.settings, scene.warnings);
  read_output(rd, root["output"], scene.settings);
  RunSettings& rs = scene.settings;
  rs.dimension = top.integer("dimension", rs.dimension);
  rs.load_factor = Section(rd, root["load"], "load", load_schema()).number("factor", rs.load_factor);
  rs.statics.target = rs.load_factor;
  rs.integrator.load_factor = rs.load_factor;
  scene.model = std::make_unique<Model>();
  scene.model->name = scene.name;
  SceneBuilder sb(rd, *scene.model);
  if (rs.dimension == 2) {
    const Eigen::Vector2d gravity = rd.vec2(root, "gravity", "", Eigen::Vector2d::Zero());
    sb.gravity = Eigen::Vector3d(gravity.x(), gravity.y(), 0.0);
    scene_detail::read_planar_mesh_and_beams(rd, root, *scene.model, gravity);
  } else {
    sb.gravity = rd.vec3(root, "gravity", "", Eigen::Vector3d::Zero());
    scene_detail::read_mesh_and_beams(rd, sb, root, *scene.model, sb.gravity);
  }
  const scene_detail::SceneTypes& types = rs.dimension == 2 ? scene_detail::planar_types() : scene_detail::spatial_types();
  read_bodies(rd, sb, root["bodies"], types, rs.dimension == 3);
  if (scene.model->nodes().empty())
    rd.fail(root, "bodies", rs.dimension == 2 ? "the scene has no bodies and no beams" : "the scene has no bodies, beams or shells");
  read_joints(rd, sb, root["joints"], types);
  read_forces(rd, sb, root["forces"], types, rs.dimension == 3);
  read_sensors(rd, sb, root["sensors"], types);
  return scene;
}

Scene load(const std::function<YAML::Node()>& parse, const std::string& label,
           const std::vector<std::string>& overrides, const MeshLoader& mesh_loader = read_mesh) {
  YAML::Node root;
  try {
    root = parse();
  } catch (const YAML::Exception& e) {
    throw InputError(label + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  std::vector<std::pair<YAML::Node, std::string>> applied;
  for (const auto& o : overrides) applied.emplace_back(input::apply_override(root, o, "--set", label), o);
  try {
    return build(root, label, mesh_loader, applied);
  } catch (const YAML::Exception& e) {
    throw InputError(label + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
}

}  // namespace

namespace {

/// rank 0's scene file as text, or its reason for failing, on every rank.
std::string scene_text(const std::string& path, int rank, MPI_Comm comm, std::string& error) {
  std::string text;
  if (rank == 0) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) error = path + ": cannot open the scene file (no such file)";
    else if (!std::filesystem::is_regular_file(path, ec)) error = path + ": cannot open the scene file (not a file)";
    else {
      std::ifstream in(path, std::ios::binary);
      if (!in) error = path + ": cannot open the scene file";
      else text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  error = broadcast_text(error, comm);
  text = broadcast_text(text, comm);
  return text;
}

}  // namespace

std::vector<const input::Schema*> input::scene_schemas() {
  std::vector<const Schema*> v = scene_detail::section_schemas();
  for (const scene_detail::SceneTypes* t : {&scene_detail::planar_types(), &scene_detail::spatial_types()}) {
    for (const auto& type : t->bodies.types()) v.push_back(&type.schema);
    for (const auto& type : t->joints.types()) v.push_back(&type.schema);
    for (const auto& type : t->loads.types()) v.push_back(&type.schema);
    for (const auto& type : t->sensors.types()) v.push_back(&type.schema);
    v.insert(v.end(), t->parts.begin(), t->parts.end());
  }
  return v;
}

std::string broadcast_text(const std::string& text, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  if (size == 1) return text;
  unsigned long long len = text.size();
  MPI_Bcast(&len, 1, MPI_UNSIGNED_LONG_LONG, 0, comm);
  std::string out = text;
  out.resize(static_cast<size_t>(len));
  MPI_Bcast(out.data(), static_cast<int>(len), MPI_CHAR, 0, comm);
  return out;
}

Scene read_scene(const std::string& path, const std::vector<std::string>& overrides, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": cannot open the scene file (no such file)");
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": cannot open the scene file (not a file)");
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot open the scene file");
    return load([&] { return YAML::LoadFile(path); }, path, overrides);
  }
  // Rank 0 reads the file and the mesh; every rank parses the same text, so every rank reaches the
  // mesh (or fails with the same message) at the same point, and gmsh runs once per run.
  std::string error;
  const std::string text = scene_text(path, rank, comm, error);
  if (!error.empty()) throw InputError(error);
  const scene_detail::MeshLoader from_rank0 = [rank, comm](const std::string& file, const MeshOptions& options,
                                             const std::string& context) {
    std::string err;
    std::vector<char> bytes;
    if (rank == 0) {
      try {
        bytes = pack(read_mesh(file, options, context));
      } catch (const std::exception& e) {
        err = e.what();
      }
    }
    err = broadcast_text(err, comm);
    if (!err.empty()) throw InputError(err);
    const std::string b = broadcast_text(std::string(bytes.begin(), bytes.end()), comm);
    return rank == 0 ? unpack(bytes) : unpack(std::vector<char>(b.begin(), b.end()));
  };
  return load([&] { return YAML::Load(text); }, path, overrides, from_rank0);
}

Scene read_scene_text(const std::string& yaml, const std::string& label, const std::vector<std::string>& overrides) {
  return load([&] { return YAML::Load(yaml); }, label, overrides);
}

}  // namespace alphaflex
