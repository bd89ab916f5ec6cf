#include "alphaflex/io/scene.hpp"

#include "scene_reader.hpp"
#include "types/sensor_feedback.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/expression.hpp"
#include "alphaflex/core/time_function.hpp"

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
      {"initial_conditions", KeyType::List, "–", "none", "placement and rigid initial velocity of mesh groups (3D)"},
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
      {"h", KeyType::Number, "s", "1e-3", "time step; at most `t_end`, and t_end/h ≤ 1e10. With `tolerance`: the first step", Range::positive(), "step size (s)"},
      {"tolerance", KeyType::Map, "–", "none (fixed steps)",
       "adaptive steps (`solver.tolerance`: `rtol`, `atol`): h is chosen by the local error estimate of q (without the content the scheme damps: filtered by the iteration matrix) and a PI controller, steps above the tolerance are rejected and retried, Newton failures halve h (docs/theory/adaptive_steps.md). Not together with `step_cuts`"},
      {"h_min", KeyType::Number, "s", "1e-10 `t_end`", "with `tolerance`: the smallest step; a step that would need less stops the run (exit 3)", Range::positive(), "step size (s)"},
      {"h_max", KeyType::Number, "s", "`t_end`", "with `tolerance`: the largest step", Range::positive(), "step size (s)"},
      {"t_end", KeyType::Number, "s", "1", "final time (the run starts at t = 0)", Range::positive(), "final time (s)"},
      {"step_cuts", KeyType::Integer, "–", "0",
       "Newton failure policy of a fixed-step dynamic run: 0 stops at the first step whose Newton iteration fails (the paper's fixed-step scheme); N > 0 retries such a step from the same state with h halved, and doubles h again (up to `h`) after 4 converged steps. N bounds the halvings in force, not the failures between two converged steps: each cut adds one, each doubling undoes one, so h never falls below `h`/2^N (a last step shortened to land on t_end: its length/2^N), however often failures and converged steps alternate; a step that fails at that h stops the run (exit 3), and the message gives that h and the cuts so far. The summary counts the cuts and the smallest h. At each change of h the auxiliary vector a is moved to the new step as with adaptive steps (docs/theory/adaptive_steps.md). Measured on the slider-crank with Newton limited to 3 iterations (tests/unit/test_step_cuts.cpp): u4's error at t_end is 1.5e-2 with 5 cuts at h = 5e-3, 6.5e-3 with fixed h and no failures: halving and doubling h this far from the asymptotic range costs accuracy; for an accuracy, give `tolerance`",
       Range::closed(0, 30)},
      {"scaling", KeyType::Flag, "–", "on", "scale the iteration matrix (dynamic rows × βh², unknown βh²Δλ; Bottasso, Dopico & Trainelli 2006)"},
      {"consistent_start", KeyType::Flag, "–", "on", "project the initial positions onto Φ = 0 (in the metric of `start_projection`) and the velocities onto Φ_q q̇ + Φ_t = 0 (correction of least kinetic energy) before the first step"},
      {"start", KeyType::Choice, "–", "`standard`",
       "starting value of the auxiliary vector a: `standard` a₀ = q̈₀ (Arnold & Brüls 2007); `corrected` a₀ = q̈₀ + (α_m − α_f) h q⃛₀ with q⃛₀ from the accelerations one step ahead (Arnold, Brüls & Cardona 2015), so a₀ matches the shifted time t₀ + (α_m − α_f)h to O(h²). On quick_return the multipliers' start-up transient measured is O(h²)·ρ∞ⁿ with either start, and the corrected start changes it by 0.2–9 % at ρ∞ = 0.5–0.95 (docs/theory/starting_values.md §1). `smooth`: q̇₀, a₀ and q̈₀ of the first step on the smooth expansion of the numerical solution, q̇₀ + s₂h²q⃛₀ + s₃h³q⁽⁴⁾₀, q̈₀ + (α_m − α_f)h q⃛₀ + r₂h²q⁽⁴⁾₀, q̈₀ + w₂h²q⁽⁴⁾₀, with q⃛₀, q⁽⁴⁾₀ from the accelerations at h and 2h ahead (three more solves): the start-up transient is O(h³) (on quick_return 10–16× smaller at h = 1e-3); what remains early is the scheme's own smooth O(h²) error, which no starting value changes and which on quick_return is still ~11× the later error while the crank accelerates from rest (docs/theory/starting_values.md §5)",
       {}, "", "", {"standard", "corrected", "smooth"}},
      {"start_projection", KeyType::Choice, "–", "`mass`",
       "metric of the consistent start's position projection onto Φ = 0: `mass` min ½Δqᵀ(M + εI)Δq, ε = 1e-12 max diag M (massless points move, bodies stay where they were placed); `minimum-norm` min ½‖Δq‖² (docs/theory/starting_values.md)",
       {}, "", "", {"mass", "minimum-norm"}},
      {"newton", KeyType::Map, "–", "all defaults", "Newton iteration (`solver.newton`)"},
      {"static", KeyType::Map, "–", "all defaults", "load stepping of a static analysis or of `initial_static` (`solver.static`)"},
      {"linear", KeyType::Map, "–", "all defaults", "the linear solver of each Newton iteration (`solver.linear`)"},
      {"initial_static", KeyType::Flag, "–", "off", "before the dynamic run, bring the initial state to static equilibrium under the loads at t = 0 (load stepping as `static`); the dynamics then starts from that pre-loaded state at rest"},
  }};
  return s;
}

const Schema& tolerance_schema() {
  static const Schema s{"solver.tolerance", {
      {"rtol", KeyType::Number, "–", "0", "relative tolerance of the local error of q per unit step (the run's length t_end as the unit): the errors the steps leave add up to about rtol‖q‖∞ + atol at t_end", Range::non_negative(), "tolerance"},
      {"atol", KeyType::Number, "m, rad", "0", "absolute tolerance of the same (at least one of rtol, atol > 0)", Range::non_negative(), "tolerance (m, rad)"},
      {"estimate", KeyType::Choice, "–", "`filtered`", "the local error estimate: `filtered` (C·h³·q⃛ filtered by the iteration matrix k = ⌈ln(t_end/h)⌉ times, so the modes ρ∞ damps do not drive h; k + 1 extra residuals and back-substitutions per step) or `local` (C·h³·q⃛ unfiltered: cheaper per step, better where no stiff undamped content is excited, e.g. Andrews; docs/theory/adaptive_steps.md §3b)", {}, "", "", {"filtered", "local"}},
      {"hold", KeyType::Number, "–", "1 (off)", "step-size hysteresis: an accepted step whose controller asks for growth by less than this factor keeps its h, so that modified Newton keeps its factorization (Hairer & Wanner II, Sec. IV.8, RADAU5: 1.2); at least 1", Range::at_least(1.0), "factor"},
  }};
  return s;
}

const Schema& static_schema() {
  static const Schema s{"solver.static", {
      {"steps", KeyType::Integer, "–", "10", "initial number of equal load steps", Range::closed(1, 1000000)},
      {"max_cuts", KeyType::Integer, "–", "12", "halvings of one load step allowed in a row after Newton failures", Range::closed(0, 50)},
      {"method", KeyType::Choice, "–", "`load_control`",
       "`load_control` (load factor stepped from 0 to `load.factor`; stops at a limit point) or `arc_length` (path following through limit points, `solver.static.arc_length`; `analysis: static` only)",
       {}, "", "", {"load_control", "arc_length"}},
      {"arc_length", KeyType::Map, "–", "all defaults", "path following by arc length (`solver.static.arc_length`), with `method: arc_length`"},
  }};
  return s;
}

const Schema& arc_length_schema() {
  static const Schema s{"solver.static.arc_length", {
      {"initial", KeyType::Number, "– (load factor)", "0.1", "arc length of the first step; arc lengths are in load-factor units (coordinates measured against the linear response to the loads at load factor 1: on the linear part of a path a step of arc length Δℓ raises the load factor by Δℓ)", Range::positive(), "arc length"},
      {"min", KeyType::Number, "– (load factor)", "1e-5", "smallest arc length: a step that fails at this length stops the run (exit 3)", Range::positive(), "arc length"},
      {"max", KeyType::Number, "– (load factor)", "1", "largest arc length", Range::positive(), "arc length"},
      {"target_iterations", KeyType::Integer, "–", "5", "Newton iterations per step the arc length is adapted to: Δℓ ← Δℓ·√(target/iterations)", Range::closed(1, 100)},
      {"max_load_factor", KeyType::Number, "–", "`load.factor`", "the path ends when |load factor| reaches this (the last step lands on it at fixed load)", Range::positive(), "load factor"},
      {"max_steps", KeyType::Integer, "–", "200", "the path ends after this many steps", Range::closed(1, 10000000)},
      {"line_search", KeyType::Flag, "–", "on", "scale a Newton correction that overshoots (Crisfield 1983: |δxᵀr(x + δx)| > 0.8|δxᵀr(x)|) by regula falsi, η ∈ [0.1, 1]"},
  }};
  return s;
}

const Schema& newton_schema() {
  static const Schema s{"solver.newton", {
      {"max_iter", KeyType::Integer, "–", "20", "iterations per step", Range::closed(1, 1000000)},
      {"rtol", KeyType::Number, "–", "1e-9", "relative tolerance on the last correction", Range::positive(), "tolerance"},
      {"atol", KeyType::Number, "m, rad", "1e-12", "absolute tolerance on the coordinate correction", Range::non_negative(), "tolerance (m, rad)"},
      {"atol_lambda", KeyType::Number, "N, N·m", "1e-9", "absolute tolerance on the multiplier correction", Range::non_negative(), "tolerance (N)"},
      {"modified", KeyType::Choice, "–", "`auto`",
       "modified Newton: keep the factorization of S_t across iterations and steps (`on`), full Newton (`off`), or `auto`: modified Newton from `modified_from` unknowns (all ranks together) or for a model with a reduced body or a joint motor whose law reads sensors, full Newton otherwise; the summary's `Newton method` line says which and why (measured: docs/performance.md, \"Modified Newton by default\"). Dynamic steps only: static load steps use full Newton",
       {}, "", "", {"auto", "on", "off"}},
      {"modified_from", KeyType::Integer, "unknowns", "30",
       "with `modified: auto`: the number of unknowns (coordinates and multipliers of the whole model) from which modified Newton is used (below it too for a model with a reduced body or a joint motor that reads sensors)",
       Range::closed(1, 1000000000)},
      {"max_contraction", KeyType::Number, "–", "0.5",
       "with `modified`: contraction rate θ = ‖Δ_k‖∞/‖Δ_{k−1}‖∞ above which S_t is assembled and factored afresh",
       Range::open(0, 1), "contraction rate"},
      {"h_change_rate", KeyType::Number, "–", "0.1",
       "with `modified` and `solver.tolerance`: an adaptive step keeps the factorization of S_t made for an earlier step size h_f while |1 − ρ²|/(1 + ρ²) ≤ this rate (ρ = h/h_f; 0.1: ρ from 0.905 to 1.105; IDA's band is 0.25, ρ from 0.77 to 1.29), its Newton corrections scaled by 2/(1 + ρ²) (docs/theory/adaptive_steps.md §6); 0: refactor at every change of h",
       Range::closed(0, 0.9), "contraction rate"},
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
      {"every", KeyType::Integer, "steps", "1", "write the fields to NAME.h5 every N steps. The initial state (t = 0) and the last step are always written. Sensors (NAME.csv): every step, or see `sensors_dt`", Range::closed(1, 1000000)},
      {"dt", KeyType::Number, "s", "none", "write the fields at t = k·dt (and at t_end). Fixed steps: dt must be a multiple of `solver.h` (it sets `every`); adaptive steps (`solver.tolerance`) are shortened to land on these times. Not together with `every`", Range::positive(), "output interval (s)"},
      {"hdf5", KeyType::Flag, "–", "on", "write NAME.h5 and NAME.xdmf; with `off` only NAME.csv"},
      {"superelement_cache", KeyType::Flag, "–", "on",
       "keep the superelements of the reduced blocks (`beams`/`shells` with `reduction`) in OUTDIR/NAME.superelements.h5, under a key of everything they depend on (the block's elements, nodes and frames, sections and materials, the reduction keys): a later run with the same key reads them instead of reducing (the same results to the last bit; the summary says which blocks were read). A mismatch or an unreadable file is computed again (with a warning naming the file) and the file rewritten; `off`: every run reduces (docs/results.md)"},
      {"sensors", KeyType::Flag, "–", "on",
       "write NAME.csv; with `off` no sensor rows are written (nor evaluated, except at the end for the summary) — for benchmarks and sweeps that need only the summary or the fields"},
      {"sensors_dt", KeyType::Number, "s", "none (every step)",
       "a row of NAME.csv at the first step at or after each multiple of this time (exactly at it when it is a multiple of `solver.h`, or of an `output.dt` that adaptive steps land on), the initial state and the last step; every step when absent (dynamic runs: a static analysis writes every load step)",
       Range::positive(), "sensor output interval (s)"},
      {"commit_interval", KeyType::Number, "s (wall time)", "1",
       "how long a part file of the results stays open before it is committed (renamed into place and listed in NAME.h5 and NAME.xdmf; docs/running.md): a run killed at any moment opens in ParaView up to its last commit. 0: every output step. The interval grows to 10 × the last commit's cost, so commits stay under ~10 % of a run; the first output step, checkpoints, the end, a failure and a stop signal always commit",
       Range::non_negative(), "wall-time interval (s; 0: every output step is committed at once)"},
      {"checkpoint_every", KeyType::Interval, "steps, or s/min/h", "none",
       "write NAME.checkpoint.h5 every so many steps (an integer ≥ 1) or so much wall time (`\"600 s\"`, `\"10 min\"`, `\"2 h\"`; dynamic runs); a checkpoint is also written at the end of every run (unless `checkpoint_at_end: off`), after a Newton failure (the last converged state) and on a stop signal. `alphaflex run SCENE --restart OUTDIR/NAME.checkpoint.h5 -o OUTDIR` goes on from it (docs/running.md)",
       Range::closed(1, 1000000000), "", "integer ≥ 1, or a wall time with its unit"},
      {"checkpoint_keep", KeyType::Integer, "–", "1", "how many checkpoints to keep (NAME.checkpoint.h5, NAME.checkpoint.1.h5, …)", Range::closed(1, 1000)},
      {"checkpoint_at_end", KeyType::Flag, "–", "on",
       "write NAME.checkpoint.h5 when a dynamic run ends (to go on with `--restart` and a larger `solver.t_end`); `off` saves its cost in benchmarks and sweeps. Checkpoints after a Newton failure, on a stop signal and by `checkpoint_every` are written either way"},
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
    if (st.has("method") && st.choice("method") == 1) {
      rs.statics.method = StaticOptions::Method::ArcLength;
      if (!(s.has("analysis") && s.choice("analysis") == 1))
        rd.fail(st.node("method"), "solver.static.method", "arc_length needs solver.analysis: static (initial_static steps the load)");
    }
    if (st.has("arc_length")) {
      if (rs.statics.method != StaticOptions::Method::ArcLength)
        rd.fail(st.node("arc_length"), "solver.static.arc_length", "only with solver.static.method: arc_length");
      const Section al(rd, st.node("arc_length"), "solver.static.arc_length", arc_length_schema());
      ArcLengthOptions& a = rs.statics.arc_length;
      a.initial = al.number("initial", a.initial);
      a.min = al.number("min", a.min);
      a.max = al.number("max", a.max);
      a.target_iterations = al.integer("target_iterations", a.target_iterations);
      a.max_load_factor = al.number("max_load_factor", 0.0);  // 0: load.factor (read later)
      a.max_steps = al.integer("max_steps", a.max_steps);
      a.line_search = al.flag("line_search", a.line_search);
      if (!(a.min <= a.initial && a.initial <= a.max))
        rd.fail(st.node("arc_length"), "solver.static.arc_length", "expected min ≤ initial ≤ max");
    }
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
  if (s.has("tolerance")) {
    const Section t(rd, s.node("tolerance"), "solver.tolerance", tolerance_schema());
    rs.tolerance_rtol = t.number("rtol", 0.0);
    rs.tolerance_atol = t.number("atol", 0.0);
    rs.filtered_error_estimate = t.choice("estimate", 0) == 0;
    rs.tolerance_hold = t.number("hold", 1.0);
    if (!(rs.tolerance_rtol > 0.0 || rs.tolerance_atol > 0.0))
      rd.fail(s.node("tolerance"), "solver.tolerance", "expected rtol > 0 or atol > 0 (a tolerance of zero asks for h = 0)");
    if (rs.step_cuts > 0)
      rd.fail(s.node("step_cuts"), "solver.step_cuts", "not together with solver.tolerance (adaptive steps retry Newton failures themselves)");
  }
  for (const char* key : {"h_min", "h_max"})
    if (s.has(key) && !s.has("tolerance"))
      rd.fail(s.node(key), std::string("solver.") + key, "only with solver.tolerance (adaptive steps)");
  rs.h_min = s.number("h_min", 1e-10 * rs.t_end);
  rs.h_max = s.number("h_max", rs.t_end);
  if (rs.h_min > rs.h_max) rd.fail(s.node("h_min"), "solver.h_min", "exceeds solver.h_max");
  rs.integrator.scaling = s.flag("scaling", rs.integrator.scaling);
  rs.integrator.consistent_start = s.flag("consistent_start", rs.integrator.consistent_start);
  rs.integrator.start = std::array<StartValues, 3>{StartValues::Standard, StartValues::Corrected,
                                                   StartValues::Smooth}[s.choice("start", 0)];
  rs.integrator.projection = s.choice("start_projection", 0) == 1 ? StartProjection::MinimumNorm : StartProjection::Mass;
  if (s.has("newton")) {
    const Section n(rd, s.node("newton"), "solver.newton", newton_schema());
    NewtonOptions& o = rs.integrator.newton;
    o.max_iterations = n.integer("max_iter", o.max_iterations);
    o.rtol = n.number("rtol", o.rtol);
    o.atol = n.number("atol", o.atol);
    o.atol_lambda = n.number("atol_lambda", o.atol_lambda);
    static constexpr NewtonOptions::Method methods[] = {NewtonOptions::Method::automatic, NewtonOptions::Method::modified,
                                                        NewtonOptions::Method::full};
    if (n.has("modified")) o.method = methods[n.choice("modified", 0)];
    o.modified_from = n.integer("modified_from", static_cast<int>(o.modified_from));
    o.max_contraction = n.number("max_contraction", o.max_contraction);
    o.h_change_rate = n.number("h_change_rate", o.h_change_rate);
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
    const Section::Interval every = o.interval("checkpoint_every");
    rs.checkpoint_steps = every.steps;
    rs.checkpoint_wall = every.seconds;
  }
  rs.checkpoint_keep = o.integer("checkpoint_keep", rs.checkpoint_keep);
  rs.checkpoint_at_end = o.flag("checkpoint_at_end", rs.checkpoint_at_end);
  rs.sensors = o.flag("sensors", rs.sensors);
  if (o.has("sensors_dt")) {
    if (!rs.sensors) rd.fail(o.node("sensors_dt"), "output.sensors_dt", "output.sensors is off: give one of the two");
    rs.sensors_dt = o.number("sensors_dt");
  }
  rs.progress_interval = o.number("progress", rs.progress_interval);
  rs.output_every = o.integer("every", rs.output_every);
  if (o.has("dt")) {
    if (o.has("every")) rd.fail(o.node("dt"), "output.dt", "give either output.dt or output.every, not both");
    rs.output_dt = o.number("dt");
  }
  rs.hdf5 = o.flag("hdf5", rs.hdf5);
  rs.superelement_cache = o.flag("superelement_cache", rs.superelement_cache);
}

}  // namespace

namespace scene_detail {

std::vector<const Schema*> section_schemas() {
  std::vector<const Schema*> v{&top_schema(), &load_schema(), &solver_schema(), &tolerance_schema(), &static_schema(), &arc_length_schema(), &newton_schema(), &linear_schema(), &output_schema()};
  v.push_back(&mesh_schema());
  v.push_back(&modes_schema());
  v.push_back(&campbell_schema());
  v.push_back(&initial_conditions_schema());
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
            const std::vector<std::pair<YAML::Node, std::string>>& overrides, const std::string& outdir, MPI_Comm comm) {
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
  // The name of the results' files (NAME.h5, NAME.xdmf, NAME.csv): a safe set, so that every file
  // system and ParaView's XDMF reader take them (a non-ASCII name broke the reader; issue 24).
  const bool safe = std::all_of(scene.name.begin(), scene.name.end(),
                                [](char c) {
                                  const auto u = static_cast<unsigned char>(c);
                                  return (u < 0x80 && std::isalnum(u)) || c == '_' || c == '-' || c == '.' || c == '+';
                                });
  if (scene.name.empty() || scene.name.size() > 100 || !safe || scene.name[0] == '.' || scene.name[0] == '-')
    rd.fail(root["name"], "name",
            "expected a plain file name of 1 to 100 characters from A-Z a-z 0-9 _ - . + (not starting with . or -), got '" +
                scene.name.substr(0, 100) + (scene.name.size() > 100 ? "...'" : "'"));
  scene.description = top.text("description");
  read_solver(rd, root["solver"], scene.settings, scene.warnings);
  read_output(rd, root["output"], scene.settings);
  RunSettings& rs = scene.settings;
  if (rs.output_dt > 0.0 && !(rs.tolerance_rtol > 0.0 || rs.tolerance_atol > 0.0)) {
    // Fixed steps: the output times must be steps.
    const double ratio = rs.output_dt / rs.h;
    if (std::fabs(ratio - std::round(ratio)) > 1e-9 * std::max(1.0, ratio) || ratio < 0.5)
      rd.fail(root["output"]["dt"], "output.dt", "expected a multiple of solver.h = " + std::to_string(rs.h) + " s with fixed steps (or give solver.tolerance for adaptive steps, which land on the output times)");
    rs.output_every = static_cast<int>(std::lround(ratio));
    rs.output_dt = 0.0;
  }
  rs.dimension = top.integer("dimension", rs.dimension);
  rs.load_factor = Section(rd, root["load"], "load", load_schema()).number("factor", rs.load_factor);
  rs.statics.target = rs.load_factor;
  rs.integrator.load_factor = rs.load_factor;
  scene.model = std::make_unique<Model>();
  scene.model->name = scene.name;
  SceneBuilder sb(rd, *scene.model);
  // The reduced blocks' superelements beside the results (io/superelement_cache.hpp).
  SuperelementCache superelements(
      outdir.empty() || !rs.superelement_cache ? std::string() : (std::filesystem::path(outdir) / (scene.name + ".superelements.h5")).string(),
      comm);
  sb.superelements = &superelements;
  scene_detail::begin_sensor_feedback(sb);
  if (rs.dimension == 2) {
    const Eigen::Vector2d gravity = rd.vec2(root, "gravity", "", Eigen::Vector2d::Zero());
    sb.gravity = Eigen::Vector3d(gravity.x(), gravity.y(), 0.0);
  } else {
    sb.gravity = rd.vec3(root, "gravity", "", Eigen::Vector3d::Zero());
  }
  const scene_detail::SceneTypes& types = rs.dimension == 2 ? scene_detail::planar_types() : scene_detail::spatial_types();
  sb.root = root;
  scene_detail::read_mesh_and_blocks(rd, sb, root, types, rs.dimension);
  sb.blocks = {};  // the mesh itself is no longer needed: its groups are sb.mesh_groups
  read_bodies(rd, sb, root["bodies"], types, rs.dimension == 3);
  if (scene.model->nodes().empty())
    rd.fail(root, "bodies", rs.dimension == 2 ? "the scene has no bodies and no beams" : "the scene has no bodies, beams or shells");
  read_joints(rd, sb, root["joints"], types);
  read_forces(rd, sb, root["forces"], types, rs.dimension == 3);
  read_sensors(rd, sb, root["sensors"], types);
  scene_detail::resolve_sensor_feedback(sb);  // loads and sensors that read sensors (types/sensor_feedback.hpp)
  rs.breakpoints = rd.breakpoints();
  std::sort(rs.breakpoints.begin(), rs.breakpoints.end());
  rs.breakpoints.erase(std::unique(rs.breakpoints.begin(), rs.breakpoints.end()), rs.breakpoints.end());
  superelements.finish();
  scene.superelements = superelements.notes();
  scene.superelement_warnings = superelements.warnings();
  return scene;
}

/// A scene file's text as one YAML document, with the three things yaml-cpp would get wrong
/// refused by name (issue 24): nesting of [ ] or { } deeper than 1000 (yaml-cpp gives up with "bad
/// file", or runs out of stack), a second document after '---' (yaml-cpp's Load ignores it), and
/// YAML merge keys `<<:` (yaml-cpp reads `<<` as an ordinary key, so the merged keys went missing).
YAML::Node parse_scene_text(const std::string& text, const std::string& label) {
  // Nesting, and a document marker '---' after content (a line of its own, or followed by a space):
  // found in the text (yaml-cpp's LoadAll loops for ever on some broken files).
  int depth = 0, line = 1;
  bool comment = false, content = false, line_start = true;
  for (size_t k = 0; k < text.size(); ++k) {
    const char c = text[k];
    if (line_start && text.compare(k, 3, "---") == 0 && (k + 3 == text.size() || std::isspace(static_cast<unsigned char>(text[k + 3]))) &&
        content)
      throw InputError(label + ":" + std::to_string(line) +
                       ": a second YAML document (after '---'): a scene is one document; remove the '---' or give the rest its own file");
    line_start = false;
    if (c == '\n') {
      ++line;
      comment = false;
      line_start = true;
    } else if (c == '#') {
      comment = true;
    } else if (!comment && c != ' ' && c != '\t' && c != '\r') {
      content = true;
      if ((c == '[' || c == '{') && ++depth > 1000)
        throw InputError(label + ":" + std::to_string(line) + ": not valid YAML: lists or maps nested deeper than 1000 levels");
      if (c == ']' || c == '}') --depth;
    }
  }
  const YAML::Node root = YAML::Load(text);
  // Merge keys, anywhere (an explicit stack: no recursion on a deep tree).
  // Aliases can make a small file a huge tree (an alias of a list of aliases ...): the walk stops at
  // 10^7 values, far beyond any scene.
  std::vector<YAML::Node> todo{root};
  for (long visited = 0; !todo.empty(); ++visited) {
    if (visited > 10000000)
      throw InputError(label + ": not a scene: its aliases (*name) expand to more than 10^7 values");
    const YAML::Node n = todo.back();
    todo.pop_back();
    if (n.IsSequence())
      for (const auto& item : n) todo.push_back(item);
    if (!n.IsMap()) continue;
    for (const auto& kv : n) {
      if (kv.first.IsScalar() && kv.first.Scalar() == "<<")
        throw InputError(label + ":" + std::to_string(kv.first.Mark().line + 1) +
                         ": '<<': YAML merge keys are not supported; write the keys out (an alias *name of a whole value works)");
      todo.push_back(kv.second);
    }
  }
  return root;
}

Scene load(const std::function<YAML::Node()>& parse, const std::string& label,
           const std::vector<std::string>& overrides, const MeshLoader& mesh_loader = read_mesh, const std::string& outdir = "",
           MPI_Comm comm = MPI_COMM_SELF) {
  YAML::Node root;
  try {
    root = parse();
  } catch (const YAML::Exception& e) {
    throw InputError(label + ":" + std::to_string(e.mark.line + 1) + ": not valid YAML: " + e.msg);
  }
  std::vector<std::pair<YAML::Node, std::string>> applied;
  for (const auto& o : overrides) applied.emplace_back(input::apply_override(root, o, "--set", label), o);
  try {
    return build(root, label, mesh_loader, applied, outdir, comm);
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
    for (const auto& type : t->blocks.types()) v.push_back(&type.schema);
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

Scene read_scene(const std::string& path, const std::vector<std::string>& overrides, MPI_Comm comm, const std::string& outdir) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(path + ": cannot open the scene file (no such file)");
    if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path + ": cannot open the scene file (not a file)");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw InputError(path + ": cannot open the scene file");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return load([&] { return parse_scene_text(text, path); }, path, overrides, read_mesh, outdir, comm);
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
  return load([&] { return parse_scene_text(text, path); }, path, overrides, from_rank0, outdir, comm);
}

Scene read_scene_text(const std::string& yaml, const std::string& label, const std::vector<std::string>& overrides) {
  return load([&] { return parse_scene_text(yaml, label); }, label, overrides);
}

}  // namespace alphaflex
