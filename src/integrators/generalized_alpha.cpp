#include "alphaflex/integrators/generalized_alpha.hpp"

#include <algorithm>
#include <mpi.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include "alphaflex/assembly/diagnostics.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/fault_injection.hpp"

namespace alphaflex {
GeneralizedAlpha::GeneralizedAlpha(SaddlePointSystem& system, LinearSolver& solver, AlphaParameters params,
                                   IntegratorOptions options)
    : lin_(system, solver),
      scales_(NewtonScales::of(system.subdomain())),
      p_(std::move(params)),
      opt_(options),
      modified_(false) {
  p_.validate();
  // Decided on the global model, which every rank holds whole (the scene is read on every rank:
  // partition/subdomain.hpp), so every rank and every restart decides alike. When the scene is cut
  // per rank (docs/architecture.md, "Past this machine"), this loop needs an MPI_LOR reduction.
  const NewtonOptions& n = opt_.newton;
  const long unknowns = system.subdomain().dof_map().global_size();
  const Element* favouring = nullptr;
  for (const auto& e : system.subdomain().global_model().elements())
    if (e->favours_modified_newton()) {
      favouring = e.get();
      break;
    }
  modified_ = n.uses_modified(unknowns, favouring != nullptr);
  std::ostringstream why;
  why << (modified_ ? "modified" : "full") << " (solver.newton.modified: ";
  if (n.method != NewtonOptions::Method::automatic)
    why << (modified_ ? "on" : "off") << ")";
  else if (unknowns >= n.modified_from)
    why << "auto, " << unknowns << " unknowns >= modified_from " << n.modified_from << ")";
  else if (favouring)
    why << "auto, " << unknowns << " unknowns < modified_from " << n.modified_from << " but `" << favouring->name()
        << "` is " << favouring->favours_modified_newton() << ")";
  else
    why << "auto, " << unknowns << " unknowns < modified_from " << n.modified_from << ")";
  newton_method_ = why.str();
}

double GeneralizedAlpha::initialize(MechanicalState& s) {
  // Every decision below is collective (norms over all ranks, the model's global joint count), so
  // that all ranks take the same branch and the same number of solves.
  const Subdomain& sub = lin_.system().subdomain();
  const Model& m = lin_.model();
  const Eigen::VectorXd q_in = s.q;
  // Redundant joints make every S_t singular whatever h is, and MUMPS may not notice when the
  // dependence is only up to round-off: check them up front (Gram–Schmidt on Φ_q, cheap), and
  // leave the full diagnosis to a failed factorization.
  const double t0 = MPI_Wtime();
  const bool redundant = !find_redundant_constraints(sub, s).empty();
  lin_.times().setup += MPI_Wtime() - t0;
  if (redundant) {
    std::ostringstream os;
    os << "the model is singular at t = 0:\n  " << diagnose_singular_system(sub, s);
    const double viol = constraint_violation(sub, s);
    if (viol > 1e-9 * std::max(1.0, sub.max_abs(s.q)))
      os << "\n  Note: the initial positions also violate the joints (by up to " << viol
         << "); a singular configuration such as links in a straight line can look redundant. Check the positions.";
    throw InputError(os.str());
  }
  lin_.initializing = true;
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{lin_.initializing};
  if (opt_.consistent_start && sub.global_model().num_multipliers() > 0) {
    // Gauss–Newton projection onto Φ(q, t0) = 0: each correction solves
    // [[W, Φ_qᵀ],[Φ_q, 0]] [Δq; μ] = [0; Φ], the minimiser of ½ΔqᵀWΔq on the linearized
    // constraints. W = M + εI (mass-weighted, the default): a coordinate moves in inverse
    // proportion to its mass, so massless points (weight ε) take the correction and the bodies
    // the user placed keep their places up to ε/m of it (docs/theory/starting_values.md); W = I:
    // the minimum-norm correction, which moves metres and radians alike.
    AssemblyCoefficients proj;
    proj.identity = 1.0;
    if (opt_.projection == StartProjection::Mass) {
      const double eps = projection_regularisation(s);
      if (eps > 0.0) {
        proj.mass = 1.0;
        proj.identity = eps;
      }
    }
    ModelVector r;
    for (int it = 0; it < 50; ++it) {
      const ModelVector x = lin_.solve(s, proj, ConstraintRows::Position, nullptr);
      m.retract(s.q, -x.dofs);
      if (sub.max_abs(x.dofs) <= 1e-14 * std::max(1.0, sub.max_abs(s.q))) break;
    }
    check_petsc(lin_.system().assemble(s, proj, ConstraintRows::Position, false), "assembly");
    check_petsc(lin_.system().to_model(lin_.system().residual(), r), "residual gather");
    const double viol = sub.max_abs(r.multipliers);
    if (viol > 1e-9 * std::max(1.0, sub.max_abs(s.q))) {
      ModelVector only_constraints{Eigen::VectorXd(), r.multipliers};
      std::ostringstream os;
      os << "the initial positions cannot be brought onto the joints (remaining violation " << viol << " after "
         << "the consistent-start projection): " << lin_.describe_largest(only_constraints).substr(2)
         << ". Check the bodies' positions and the joints' points.";
      throw InputError(os.str());
    }
    // Velocities: the correction onto Φ_q q̇ + Φ_t = 0 of least kinetic energy, ½ΔvᵀMΔv
    // (linear: one solve of [[M, Φ_qᵀ],[Φ_q, 0]], the matrix of the acceleration solve below). It is
    // the velocity an impulsive start produces (Kelvin's minimum-energy theorem), so a driver that
    // starts at speed moves the whole mechanism as it would be jerked into motion, rather than only
    // the coordinates next to the driver (which the unweighted minimum norm would change).
    AssemblyCoefficients vel;
    vel.mass = 1.0;
    const ModelVector x = lin_.solve(s, vel, ConstraintRows::Velocity, nullptr);
    s.v -= x.dofs;
  }
  consistent_accelerations(s);
  a_ = s.qdd;  // a_0 = q̈_0 (eq. 3)
  h_aux_ = 0.0;  // no shift yet: a_0 − q̈_0 = 0 whatever the first h
  factored_h_ = 0.0;  // the solves above factored other matrices
  // Corrected start: a_0 needs the first step's h, which the first step gives.
  start_pending_ = (opt_.start == StartValues::Corrected && p_.alpha_m != p_.alpha_f) || opt_.start == StartValues::Smooth;
  t_start_ = s.t;
  return sub.max_abs(m.difference(q_in, s.q));
}

void GeneralizedAlpha::consistent_accelerations(MechanicalState& s) {
  // Accelerations and multipliers from the index-1 system at t (linear in q̈, λ: one solve).
  s.qdd.setZero();
  s.lambda.setZero();
  AssemblyCoefficients acc;
  acc.mass = 1.0;
  acc.load_factor = opt_.load_factor;
  const ModelVector x = lin_.solve(s, acc, ConstraintRows::Acceleration, nullptr);
  s.qdd = -x.dofs;
  s.lambda = -x.multipliers;
}

double GeneralizedAlpha::projection_regularisation(const MechanicalState& s) {
  // The largest diagonal entry of M at q0 sets the scale of the weights (kg, kg·m²): ε = 1e-12
  // of it keeps W = M + εI positive definite where M is singular (massless points, a model of
  // springs and joints only) while a body of mass m moves by about ε/m of what a massless point
  // beside it moves (docs/theory/starting_values.md).
  AssemblyCoefficients mass;
  mass.mass = 1.0;
  SaddlePointSystem& sys = lin_.system();
  check_petsc(sys.assemble(s, mass, ConstraintRows::Position, true), "assembly");
  check_petsc(MatGetDiagonal(sys.matrix(), sys.solution()), "mass diagonal");
  ModelVector d;
  check_petsc(sys.to_model(sys.solution(), d), "mass diagonal gather");
  return 1e-12 * sys.subdomain().max_abs(d.dofs);
}

Eigen::VectorXd GeneralizedAlpha::acceleration_ahead(const MechanicalState& s, double sigma, const Eigen::VectorXd* q3) {
  MechanicalState ahead = s;
  ahead.t = s.t + sigma;
  if (q3) {
    lin_.model().retract(ahead.q, sigma * s.v + 0.5 * sigma * sigma * s.qdd + (sigma * sigma * sigma / 6.0) * *q3);
    ahead.v = s.v + sigma * s.qdd + (0.5 * sigma * sigma) * *q3;
  } else {
    lin_.model().retract(ahead.q, sigma * s.v + 0.5 * sigma * sigma * s.qdd);
    ahead.v = s.v + sigma * s.qdd;
  }
  consistent_accelerations(ahead);
  factored_h_ = 0.0;  // the solve factored another matrix
  return ahead.qdd;
}

Eigen::VectorXd GeneralizedAlpha::corrected_start(const MechanicalState& s, double h) {
  // Arnold, Brüls & Cardona (2015): a_n approximates q̈(t_n + Δ_α h), Δ_α = α_m − α_f, to O(h²);
  // a_0 = q̈_0 is O(h) off, which the multipliers carry as an O(h)·ρ∞ⁿ transient. The shifted
  // value a_0 = q̈_0 + Δ_α h q⃛_0 + O(h²) removes it. q⃛_0 is the forward difference of the
  // consistent accelerations over one step h: q̈(t_0 + h) at the Taylor state
  // q = q_0 ∘ exp(h q̇_0 + ½h² q̈_0), q̇ = q̇_0 + h q̈_0 (off the exact solution by O(h³), O(h²),
  // hence q̈ by O(h²) and q⃛_0 by O(h)), never before t_0 (drivers may start there).
  return s.qdd + (p_.alpha_m - p_.alpha_f) * (acceleration_ahead(s, h, nullptr) - s.qdd);
}

void GeneralizedAlpha::smooth_start(MechanicalState& s, double h) {
  // The numerical solution is a smooth expansion plus parasitic modes (damped like the roots of σ,
  // Arnold & Brüls 2007, eq. 37–38). Along a smooth q(t) the scheme's kinematic relations (4)–(5)
  // and eq. (3) give, with z = hD (docs/theory/starting_values.md §5):
  //   v = S(z) q̇,  a = R(z) q̈,  q̈_n = W(z) q̈,
  //   R = 1 + (½ − γ)z + (γ² − γ/2 − β + 1/12)z² + …,  S = 1 + (γ/2 − β − 1/12)z² + (2β − γ)(2γ − 1)/4 z³ + …,
  //   W = 1 + (α_f − α_m − γ + ½)z + w₂z² + ….
  // Starting values off this expansion excite the parasitic modes, and the multipliers take the
  // constraint part of the mismatch with weight O(1) in a_0 and q̈_0 and O(1/h) in q̇_0 (the next
  // positions must stay on Φ = 0). So a_0, q̈_0 to O(h³) and q̇_0 to O(h⁴) leave an O(h³) transient:
  // q⃛_0 is needed to O(h²), q⁽⁴⁾_0 to O(h).
  // First q⃛_0 to O(h) (the corrected start's forward difference), then the accelerations at the
  // Taylor states h and 2h with that q⃛ (off by O(h³) in q and q̇, so q̈ by O(h³)):
  // q̈(σ) = q̈_0 + σq⃛_0 + ½σ²q⁽⁴⁾_0 + O(h³) gives q⃛_0 to O(h²) and q⁽⁴⁾_0 to O(h). Never before t_0.
  const Eigen::VectorXd q3_first = (acceleration_ahead(s, h, nullptr) - s.qdd) / h;
  const Eigen::VectorXd d1 = acceleration_ahead(s, h, &q3_first) - s.qdd;
  const Eigen::VectorXd d2 = acceleration_ahead(s, 2.0 * h, &q3_first) - s.qdd;
  const Eigen::VectorXd q3 = (4.0 * d1 - d2) / (2.0 * h);
  const Eigen::VectorXd q4 = (d2 - 2.0 * d1) / (h * h);
  const double am = p_.alpha_m, af = p_.alpha_f, b = p_.beta, g = p_.gamma;
  const double r1 = 0.5 - g, r2 = g * g - 0.5 * g - b + 1.0 / 12.0;
  const double s2 = 0.5 * g - b - 1.0 / 12.0, s3 = 0.25 * (2.0 * b - g) * (2.0 * g - 1.0);
  const double w1 = af - am - g + 0.5,
               w2 = af * af - af * am - af * g + am * g - b + g * g - 0.5 * g + 1.0 / 12.0;
  a_ = s.qdd + (r1 * h) * q3 + (r2 * h * h) * q4;
  s.v += (s2 * h * h) * q3 + (s3 * h * h * h) * q4;
  s.qdd += (w1 * h) * q3 + (w2 * h * h) * q4;
}

AssemblyCoefficients GeneralizedAlpha::step_coefficients(double h, const Eigen::VectorXd& increment) const {
  AssemblyCoefficients c;
  c.mass = p_.beta_prime(h);  // eq. (6)
  c.damping = p_.gamma_prime(h);
  c.stiffness = 1.0;
  c.load_factor = opt_.load_factor;
  // S_t = M β' + C γ' + K T(x) (Brüls, Cardona & Arnold 2012, eq. 48)
  if (lin_.model().has_lie_group_nodes()) c.increment = &increment;
  if (opt_.scaling) {
    c.row_scale = p_.beta * h * h;
    c.multiplier_scale = 1.0 / (p_.beta * h * h);
  }
  return c;
}

StepReport GeneralizedAlpha::step(MechanicalState& s, double h) { return step(s, h, s.t + h); }

StepReport GeneralizedAlpha::step(MechanicalState& s, double h, double t_next) {
  // The corrected start: a_0 for this first step's h (again for a retried first step, which the
  // step loop restores with the h of a set to 0).
  if (start_pending_ && h_aux_ == 0.0 && s.t == t_start_) {
    if (opt_.start == StartValues::Smooth) {
      // The smooth start moves q̇_0 and q̈_0 as well: on a copy, so that a failed first step leaves
      // `s` as it was.
      MechanicalState first = s;
      smooth_start(first, h);
      StepReport rep = advance(first, h, t_next);
      s = std::move(first);
      return rep;
    }
    a_ = corrected_start(s, h);
  }
  return advance(s, h, t_next);
}

StepReport GeneralizedAlpha::advance(MechanicalState& s, double h, double t_next) {
  if (variable_ && h_aux_ > 0.0 && h != h_aux_) {
    // a_n − q̈_n ≈ (α_m − α_f) h_old q⃛(t_n) (Arnold & Brüls 2007, a_n ≈ q̈(t_n + (α_m − α_f)h)):
    // scaled by h/h_old it is the shift of the new step (docs/theory/adaptive_steps.md).
    a_ = s.qdd + (h / h_aux_) * (a_ - s.qdd);
  }
  Eigen::VectorXd a_n = estimate_ ? a_ : Eigen::VectorXd();
  StepReport rep = step_at(s, h, t_next);
  h_aux_ = h;
  if (estimate_) {
    const Subdomain& sub = lin_.system().subdomain();
    rep.local_error = std::fabs(p_.local_error_constant()) * h * h * sub.max_abs(a_ - a_n);
    rep.q_norm = sub.max_abs(s.q);
    rep.a_start = std::move(a_n);
  }
  return rep;
}

namespace {
/// Whether the adaptive step's Newton tolerance on q, step_atol + step_rtol‖q‖∞, lies above the
/// round-off floor ε S (10⁴ + 64‖q‖∞/L) of NewtonScales::measure (S = max(L, 1), the largest scale).
/// The stale iteration converges linearly and stops when θ/(1 − θ)‖Δq‖ passes the step's Newton
/// tolerance; where that tolerance is clipped at the round-off floor, q̇ and q̈ keep that error
/// times γ' ~ 1/h and β' ~ 1/h² — on the hammer's blow (h ~ 1e-7 … 1e-5 s) 0.07 % of the impulse,
/// 40× the error of tol = 1e-6 at t_end. A fresh S_t's first iteration is a full Newton step, whose
/// error is quadratically below the floor: there S_t is refactored at a change of h, as before
/// (docs/theory/adaptive_steps.md §6).
bool newton_tolerance_above_roundoff(const NewtonOptions& nt, double model_size, double q_norm) {
  if (nt.step_atol < 0.0) return true;
  const double L = model_size;
  const double floor = std::numeric_limits<double>::epsilon() * std::max(L, 1.0) * (1e4 + 64.0 * q_norm / L);
  return nt.step_atol + nt.step_rtol * q_norm > floor;
}
}  // namespace

bool GeneralizedAlpha::usable_across_h(double h) const {
  // Only the scaled S_t (Bottasso et al.) has blocks of mass and constraints independent of h
  // (docs/theory/adaptive_steps.md §6); unscaled, the constraint rows and the multipliers' column
  // weigh differently at every h.
  const NewtonOptions& nt = opt_.newton;
  if (!across_h_ || !opt_.scaling || factored_h_ <= 0.0 || nt.h_change_rate <= 0.0) return false;
  const double rho2 = (h / factored_h_) * (h / factored_h_);
  return std::fabs(1.0 - rho2) / (1.0 + rho2) <= nt.h_change_rate;
}

StepReport GeneralizedAlpha::step_at(MechanicalState& s, double h, double t_next) {
  bool used_old_matrix = false;
  if (!modified_) return try_step(s, h, t_next, false, used_old_matrix);
  try {
    return try_step(s, h, t_next, true, used_old_matrix);
  } catch (const SolverError&) {
    // A factorization from an earlier state may be too far off for this step: full Newton from the
    // same start decides whether the step itself fails (try_step leaves `s` as it was).
    if (!used_old_matrix) throw;
    factored_h_ = 0.0;
    StepReport again = try_step(s, h, t_next, false, used_old_matrix);
    return again;
  }
}

StepReport GeneralizedAlpha::try_step(MechanicalState& s, double h, double t_next, bool allow_reuse, bool& used_old_matrix) {
  const Subdomain& sub = lin_.system().subdomain();
  const Model& model = lin_.model();
  const double am = p_.alpha_m, af = p_.alpha_f, beta = p_.beta, gamma = p_.gamma;
  const double beta_p = p_.beta_prime(h);  // eq. (6)
  const double gamma_p = p_.gamma_prime(h);

  // Lie-group form (Brüls, Cardona & Arnold 2012, Algorithm 1 there): q_{n+1} = q_n ∘ exp(x) with
  // x = hΔq_n = h v_n + h²(1/2 − β) a_n + h²β a_{n+1}; every change dx of x moves q through
  // Model::advance, which on vector spaces is q += dx — Algorithm 1 of Arnold & Brüls (2007)
  // operation by operation, so planar models give the same bits through this path.
  const Eigen::VectorXd q_n = s.q;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(s.v.size());
  MechanicalState n1 = s;
  n1.t = t_next;
  auto move = [&](const Eigen::VectorXd& dx) {
    x += dx;
    model.advance(q_n, x, dx, n1.q);
  };
  // Predictor.
  move(h * s.v);
  move(h * h * (0.5 - beta) * a_);
  n1.v = s.v + h * (1.0 - gamma) * a_;
  n1.lambda.setZero();
  const Eigen::VectorXd a_pred = (af * s.qdd - am * a_) / (1.0 - am);
  move(h * h * beta * a_pred);
  n1.v += h * gamma * a_pred;
  n1.qdd.setZero();

  const AssemblyCoefficients c = step_coefficients(h, x);

  StepReport report;
  ModelVector r;
  const NewtonOptions& nt = opt_.newton;
  bool converged = false;
  // Modified Newton: whether the S_t factored now may be used — the one of this h, or (adaptive
  // steps, scaled S_t) one of another h_f whose stale iteration still contracts fast enough.
  // (‖q_n‖∞ over all ranks: h and factored_h_ are the same on every rank, so all reach the all-reduce.)
  bool fresh = !(allow_reuse && (factored_h_ == h || (usable_across_h(h) &&
                                                       newton_tolerance_above_roundoff(nt, scales_.model_size, sub.max_abs(q_n)))));
  // A step whose old S_t failed its first rate test (θ ≥ max_contraction at the second iteration)
  // costs two iterations that full Newton does not and refactors anyway. Where that repeats step
  // after step (a matrix one step old that does not contract: the flexible four-bar at ρ∞ ≤ 0.5
  // gives θ ≈ 0.99 at every step, whatever h), the next steps begin on a fresh factorization —
  // 1, 2, 4, … up to 16 of them after each failed probe, the doubling reset by a probe that passes
  // (the rule of RADAU5 and IDA: decide on the Jacobian from the rate the last steps showed;
  // Hairer & Wanner II, Sec. IV.8). Every rank takes the same branch (θ is of global norms).
  bool probing = !fresh;  // this step begins on an old factorization: its first rate test decides
  if (probing && fresh_starts_left_ > 0) {
    --fresh_starts_left_;
    ++fresh_starts_;
    fresh = true;
    probing = false;
  }
  double prev_q = 0.0, prev_l = 0.0;  // ‖Δq‖∞, ‖Δλ‖∞ of the previous iteration
  // The multipliers' own scale (docs/theory/starting_values.md §3): besides ‖λ‖∞, the change of λ
  // that goes with a change of the coordinates by rtol S_i, Δλ₁/(rtol ρ₁) from a first full iteration
  // (ρ₁ = max_i |Δq_i|/(atol + rtol S_i)): the test then asks of λ what it asks of q, whatever
  // β' ~ 1/h² amplifies, and never less than the round-off of q lets λ resolve (at 10 km from the
  // origin λ wanders by ~1e-7 N on the slider-crank, which a test on ‖λ‖∞ alone cannot pass).
  double lambda_amplification = 0.0;
  for (int it = 1; it <= nt.max_iterations && !converged; ++it) {
    const bool reuse = allow_reuse && !fresh;
    if (reuse) {
      used_old_matrix = true;
      ++reused_;
    }
    ModelVector x = reuse ? lin_.solve_with_last_factorization(n1, c, ConstraintRows::Dynamic, &r)
                          : lin_.solve(n1, c, ConstraintRows::Dynamic, &r);
    if (reuse && factored_h_ != h) {
      // S_t of h_f, the residual of h: the correction scaled by 2/(1 + ρ²), ρ = h/h_f, the scalar
      // that minimises the worst contraction over the spectrum of S_t(h_f)⁻¹S_t(h), which lies in
      // [min(1, ρ²), max(1, ρ²)] (docs/theory/adaptive_steps.md §6; IDA's 2/(1 + cjratio)).
      const double rho2 = (h / factored_h_) * (h / factored_h_);
      const double scale = 2.0 / (1.0 + rho2);
      x.dofs *= scale;
      x.multipliers *= scale;
      ++rescaled_;
    }
    if (!reuse) factored_h_ = h;  // a reused factorization keeps the h it was made for
    fresh = false;
    Eigen::VectorXd dq = -x.dofs;
    if (fault_injected("newton") && dq.size()) dq[0] = std::numeric_limits<double>::quiet_NaN();  // tests only
    const Eigen::VectorXd dl = -c.multiplier_scale * x.multipliers;
    move(dq);
    n1.v += gamma_p * dq;
    n1.qdd += beta_p * dq;
    n1.lambda += dl;

    NewtonRecord rec = newton_record(sub, r, dq, dl);
    scales_.measure(rec, sub, nt, n1.q, dq);
    report.history.push_back(rec);
    report.iterations = it;
    if (!std::isfinite(rec.correction_q) || !std::isfinite(rec.correction_lambda)) break;
    if (it == 1 && !reuse && rec.q_tolerance_ratio > 0.0 && std::isfinite(rec.q_tolerance_ratio))
      lambda_amplification = rec.correction_lambda / (nt.rtol * rec.q_tolerance_ratio);
    // Only after a full Newton iteration, whose error is the next correction, quadratically smaller
    // than this one; with an old S_t (linear rate θ) the error is θ/(1−θ)‖Δ‖ itself.
    const double lambda_scale = std::max(sub.max_abs(n1.lambda), reuse ? 0.0 : lambda_amplification);
    if (!reuse) {
      converged = newton_converged(nt, rec, it, lambda_scale);
    } else if (it > 1) {
      // Linear convergence with the old S_t: test the error estimate θ/(1−θ)‖Δ_k‖ (Hairer &
      // Wanner IV.8.13), θ the larger contraction of q and λ; θ ≥ max_contraction: refactor.
      const double theta = std::max(prev_q > 0.0 ? rec.correction_q / prev_q : 0.0,
                                    prev_l > 0.0 ? rec.correction_lambda / prev_l : 0.0);
      if (theta < 1.0) {
        NewtonRecord estimate = rec;
        estimate.correction_q *= theta / (1.0 - theta);
        estimate.correction_lambda *= theta / (1.0 - theta);
        estimate.q_tolerance_ratio *= theta / (1.0 - theta);
        estimate.q_roundoff_ratio *= theta / (1.0 - theta);
        converged = newton_converged(nt, estimate, it, lambda_scale);
      }
      if (!converged && theta >= nt.max_contraction) {
        fresh = true;
        ++refreshes_;
      }
      if (probing && it == 2) {
        if (fresh) {
          fresh_run_ = std::min(fresh_run_ == 0 ? 1 : 2 * fresh_run_, 16);
          fresh_starts_left_ = fresh_run_;
        } else {
          fresh_run_ = 0;
        }
        probing = false;
      }
    }
    // (The first iteration with an old S_t has no rate yet: one more iteration measures it.)
    prev_q = rec.correction_q;
    prev_l = rec.correction_lambda;
  }
  if (!converged) {
    std::ostringstream os;
    os.precision(4);
    os << "Newton did not converge at t = " << n1.t << " s (h = " << h << " s) after "
       << report.iterations << " iterations.\n" << format_newton_history(report.history, opt_.scaling);
    os << "  " << lin_.describe_largest(r)
       << ".\n  Try a smaller solver.h, a larger solver.newton.max_iter, or check the model near that node/joint.";
    throw SolverError(os.str());
  }
  a_ = a_pred + (1.0 - af) / (1.0 - am) * n1.qdd;
  if (estimate_) report.increment = x;
  s = n1;
  return report;
}

}  // namespace alphaflex
