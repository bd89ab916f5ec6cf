#include "alphaflex/integrators/generalized_alpha.hpp"

#include <mpi.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include "alphaflex/assembly/diagnostics.hpp"
#include "alphaflex/core/error.hpp"

namespace alphaflex {
namespace {

double inf_norm(const Eigen::VectorXd& v) { return v.size() ? v.cwiseAbs().maxCoeff() : 0.0; }

// PETSc log events, so that -log_view splits the step like the run summary does.
PetscLogEvent ev_assembly = 0, ev_factor = 0, ev_solve = 0;

void register_events() {
  static bool done = false;
  if (done) return;
  PetscClassId cid;
  PetscClassIdRegister("alphaflex", &cid);
  PetscLogEventRegister("AfAssembly", cid, &ev_assembly);
  PetscLogEventRegister("AfFactor", cid, &ev_factor);
  PetscLogEventRegister("AfSolve", cid, &ev_solve);
  done = true;
}

void check_petsc(PetscErrorCode ierr, const char* what) {
  if (ierr) throw SolverError(std::string("PETSc error ") + std::to_string(ierr) + " in " + what);
}

}  // namespace

GeneralizedAlpha::GeneralizedAlpha(SaddlePointSystem& system, LinearSolver& solver, AlphaParameters params,
                                   IntegratorOptions options)
    : sys_(system), solver_(solver), p_(std::move(params)), opt_(options) {
  p_.validate();
  register_events();
}

ModelVector GeneralizedAlpha::solve_linear(const MechanicalState& s, const AssemblyCoefficients& c,
                                           ConstraintRows rows, ModelVector* residual) {
  double t0 = MPI_Wtime();
  PetscLogEventBegin(ev_assembly, 0, 0, 0, 0);
  check_petsc(sys_.assemble(s, c, rows, true), "assembly");
  if (residual) check_petsc(sys_.to_model(sys_.residual(), *residual), "residual gather");
  PetscLogEventEnd(ev_assembly, 0, 0, 0, 0);
  double t1 = MPI_Wtime();
  times_.assembly += t1 - t0;
  PetscLogEventBegin(ev_factor, 0, 0, 0, 0);
  check_petsc(solver_.factor(sys_.matrix()), "factorization");
  PetscLogEventEnd(ev_factor, 0, 0, 0, 0);
  double t2 = MPI_Wtime();
  times_.factorization += t2 - t1;
  if (!solver_.failure().empty()) {
    // Name the cause (redundant joints, coordinates nothing acts on) instead of a MUMPS code; at
    // the start it is the model as given, i.e. bad input.
    const std::string why = diagnose_singular_system(sys_.model(), s);
    if (initializing_ && !why.empty()) throw InputError("the model is singular at t = 0:\n  " + why);
    std::ostringstream os;
    os << "the iteration matrix could not be factored at t = " << s.t << " s: " << solver_.failure();
    if (!why.empty()) os << "\n  " << why;
    throw SolverError(os.str());
  }
  PetscLogEventBegin(ev_solve, 0, 0, 0, 0);
  check_petsc(solver_.solve(sys_.residual(), sys_.solution()), "solve");
  PetscLogEventEnd(ev_solve, 0, 0, 0, 0);
  if (!solver_.failure().empty()) throw SolverError(solver_.failure());
  ModelVector x;
  check_petsc(sys_.to_model(sys_.solution(), x), "solution gather");
  times_.solve += MPI_Wtime() - t2;
  return x;
}

std::string GeneralizedAlpha::describe_largest(const ModelVector& r) const {
  const Model& m = sys_.model();
  std::ostringstream os;
  Eigen::Index i = 0, j = 0;
  if (r.dofs.size()) {
    r.dofs.cwiseAbs().maxCoeff(&i);
    for (const Node& n : m.nodes())
      if (i >= n.first_dof && i < n.first_dof + n.ndof)
        os << "largest equilibrium residual " << r.dofs[i] << " at node '" << n.name << "' ("
           << coordinate_name(n.kind, static_cast<int>(i) - n.first_dof) << ")";
  }
  if (r.multipliers.size()) {
    r.multipliers.cwiseAbs().maxCoeff(&j);
    for (size_t c = 0; c < m.constraints().size(); ++c) {
      const int first = m.first_multiplier(static_cast<int>(c));
      if (j >= first && j < first + m.constraints()[c]->size())
        os << "; largest constraint violation " << r.multipliers[j] << " in joint '" << m.constraints()[c]->name()
           << "' (" << m.constraints()[c]->type() << ", equation " << (j - first + 1) << ")";
    }
  }
  return os.str();
}

double GeneralizedAlpha::initialize(MechanicalState& s) {
  const Model& m = sys_.model();
  const Eigen::VectorXd q_in = s.q;
  // Redundant joints make every S_t singular whatever h is, and MUMPS may not notice when the
  // dependence is only up to round-off: check them up front (Gram–Schmidt on Φ_q, cheap), and
  // leave the full diagnosis to a failed factorization.
  if (!find_redundant_constraints(m, s).empty()) {
    std::ostringstream os;
    os << "the model is singular at t = 0:\n  " << diagnose_singular_system(m, s);
    const double viol = constraint_violation(m, s);
    if (viol > 1e-9 * std::max(1.0, inf_norm(s.q)))
      os << "\n  Note: the initial positions also violate the joints (by up to " << viol
         << "); a singular configuration such as links in a straight line can look redundant. Check the positions.";
    throw InputError(os.str());
  }
  initializing_ = true;
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{initializing_};
  AssemblyCoefficients proj;
  proj.identity = 1.0;
  if (opt_.consistent_start && m.num_multipliers() > 0) {
    // Gauss–Newton projection onto Φ(q, t0) = 0 with the minimum-norm correction.
    ModelVector r;
    for (int it = 0; it < 50; ++it) {
      const ModelVector x = solve_linear(s, proj, ConstraintRows::Position, nullptr);
      m.retract(s.q, -x.dofs);
      if (inf_norm(x.dofs) <= 1e-14 * std::max(1.0, inf_norm(s.q))) break;
    }
    check_petsc(sys_.assemble(s, proj, ConstraintRows::Position, false), "assembly");
    check_petsc(sys_.to_model(sys_.residual(), r), "residual gather");
    const double viol = inf_norm(r.multipliers);
    if (viol > 1e-9 * std::max(1.0, inf_norm(s.q))) {
      ModelVector only_constraints{Eigen::VectorXd(), r.multipliers};
      std::ostringstream os;
      os << "the initial positions cannot be brought onto the joints (remaining violation " << viol << " after "
         << "the consistent-start projection): " << describe_largest(only_constraints).substr(2)
         << ". Check the bodies' positions and the joints' points.";
      throw InputError(os.str());
    }
    // Velocities: minimum-norm correction onto Φ_q q̇ + Φ_t = 0 (linear: one solve).
    const ModelVector x = solve_linear(s, proj, ConstraintRows::Velocity, nullptr);
    s.v -= x.dofs;
  }
  // Accelerations and multipliers from the index-1 system at t0 (linear in q̈, λ: one solve).
  s.qdd.setZero();
  s.lambda.setZero();
  AssemblyCoefficients acc;
  acc.mass = 1.0;
  const ModelVector x = solve_linear(s, acc, ConstraintRows::Acceleration, nullptr);
  s.qdd = -x.dofs;
  s.lambda = -x.multipliers;
  a_ = s.qdd;  // a_0 = q̈_0 (eq. 3)
  return inf_norm(m.difference(q_in, s.q));
}

StepReport GeneralizedAlpha::step(MechanicalState& s, double h) {
  const Model& model = sys_.model();
  const double am = p_.alpha_m, af = p_.alpha_f, beta = p_.beta, gamma = p_.gamma;
  const double beta_p = (1.0 - am) / (h * h * beta * (1.0 - af));  // eq. (6)
  const double gamma_p = gamma / (h * beta);

  // Lie-group form (Brüls, Cardona & Arnold 2012, Algorithm 1 there): q_{n+1} = q_n ∘ exp(x) with
  // x = hΔq_n = h v_n + h²(1/2 − β) a_n + h²β a_{n+1}; every change dx of x moves q through
  // Model::advance, which on vector spaces is q += dx — Algorithm 1 of Arnold & Brüls (2007)
  // operation by operation, so planar models give the same bits through this path.
  const Eigen::VectorXd q_n = s.q;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(s.v.size());
  MechanicalState n1 = s;
  n1.t = s.t + h;
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

  AssemblyCoefficients c;
  c.mass = beta_p;
  c.damping = gamma_p;
  c.stiffness = 1.0;
  if (model.has_lie_group_nodes()) c.increment = &x;  // S_t = M β' + C γ' + K T(x) (eq. 48 there)
  if (opt_.scaling) {
    c.row_scale = beta * h * h;
    c.multiplier_scale = 1.0 / (beta * h * h);
  }

  StepReport report;
  ModelVector r;
  const NewtonOptions& nt = opt_.newton;
  bool converged = false;
  for (int it = 1; it <= nt.max_iterations && !converged; ++it) {
    const ModelVector x = solve_linear(n1, c, ConstraintRows::Dynamic, &r);
    const Eigen::VectorXd dq = -x.dofs;
    const Eigen::VectorXd dl = -c.multiplier_scale * x.multipliers;
    move(dq);
    n1.v += gamma_p * dq;
    n1.qdd += beta_p * dq;
    n1.lambda += dl;

    NewtonRecord rec;
    rec.residual_dynamic = r.dofs.norm();
    rec.residual_constraint = r.multipliers.norm();
    rec.correction_q = inf_norm(dq);
    rec.correction_lambda = inf_norm(dl);
    report.history.push_back(rec);
    report.iterations = it;
    if (!std::isfinite(rec.correction_q) || !std::isfinite(rec.correction_lambda)) break;
    // λ cannot be resolved below the round-off of q amplified by β' ~ 1/(βh²) (the index-3
    // amplification of Sec. 3.3): once Δq is at round-off level, λ is as good as it gets.
    const double q_scale = std::max(inf_norm(n1.q), 1e-300);
    const bool q_converged = rec.correction_q <= nt.atol + nt.rtol * q_scale;
    const bool q_at_roundoff = rec.correction_q <= 1e4 * std::numeric_limits<double>::epsilon() * q_scale;
    const bool lambda_converged = rec.correction_lambda <= nt.atol_lambda + nt.rtol * inf_norm(n1.lambda);
    converged = q_converged && (lambda_converged || (it > 1 && q_at_roundoff));
  }
  if (!converged) {
    std::ostringstream os;
    os.precision(4);
    os << "Newton did not converge at t = " << n1.t << " s (h = " << h << " s) after "
       << report.iterations << " iterations.\n  " << std::setw(9) << "iteration" << std::setw(13) << "|r_q|"
       << std::setw(13) << "|Phi|" << std::setw(13) << "|dq|_inf" << std::setw(15) << "|dlambda|_inf"
       << (opt_.scaling ? "   (r_q scaled by beta h^2)" : "") << "\n";
    for (size_t i = 0; i < report.history.size(); ++i) {
      const auto& h_i = report.history[i];
      os << "  " << std::setw(9) << (i + 1) << std::scientific << std::setprecision(4) << std::setw(13)
         << h_i.residual_dynamic << std::setw(13) << h_i.residual_constraint << std::setw(13) << h_i.correction_q
         << std::setw(15) << h_i.correction_lambda << "\n"
         << std::defaultfloat;
    }
    os << "  " << describe_largest(r)
       << ".\n  Try a smaller solver.h, a larger solver.newton.max_iter, or check the model near that node/joint.";
    throw SolverError(os.str());
  }
  a_ = a_pred + (1.0 - af) / (1.0 - am) * n1.qdd;
  s = n1;
  return report;
}

}  // namespace alphaflex
