#include "alphaflex/integrators/linearized_system.hpp"

#include <mpi.h>

#include <iomanip>
#include <algorithm>
#include <limits>
#include <sstream>

#include "alphaflex/assembly/diagnostics.hpp"
#include "alphaflex/core/error.hpp"
#include "alphaflex/core/petsc_error.hpp"

namespace alphaflex {
namespace {

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


}  // namespace

LinearizedSystem::LinearizedSystem(SaddlePointSystem& system, LinearSolver& solver) : sys_(system), solver_(solver) {
  register_events();
}

void LinearizedSystem::assemble(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows,
                                bool matrix, ModelVector* residual) {
  const double t0 = MPI_Wtime();
  PetscLogEventBegin(ev_assembly, 0, 0, 0, 0);
  check_petsc(sys_.assemble(s, c, rows, matrix), "assembly");
  if (residual) check_petsc(sys_.to_model(sys_.residual(), *residual), "residual gather");
  PetscLogEventEnd(ev_assembly, 0, 0, 0, 0);
  times_.assembly += MPI_Wtime() - t0;
}

ModelVector LinearizedSystem::solve_factored() {
  const double t0 = MPI_Wtime();
  PetscLogEventBegin(ev_solve, 0, 0, 0, 0);
  check_petsc(solver_.solve(sys_.residual(), sys_.solution()), "solve");
  PetscLogEventEnd(ev_solve, 0, 0, 0, 0);
  if (!solver_.failure().empty()) throw SolverError(solver_.failure());
  ModelVector x;
  check_petsc(sys_.to_model(sys_.solution(), x), "solution gather");
  times_.solve += MPI_Wtime() - t0;
  return x;
}

ModelVector LinearizedSystem::solve(const MechanicalState& s, const AssemblyCoefficients& c, ConstraintRows rows,
                                    ModelVector* residual) {
  assemble(s, c, rows, true, residual);
  const double t1 = MPI_Wtime();
  PetscLogEventBegin(ev_factor, 0, 0, 0, 0);
  check_petsc(solver_.factor(sys_.matrix()), "factorization");
  PetscLogEventEnd(ev_factor, 0, 0, 0, 0);
  times_.factorization += MPI_Wtime() - t1;
  if (!solver_.failure().empty()) {
    // Name the cause (redundant joints, coordinates nothing acts on) instead of a MUMPS code; at
    // the start it is the model as given, i.e. bad input.
    // A workspace failure is not a property of the model: no diagnosis of it then.
    const std::string why = solver_.workspace_failure() ? std::string() : diagnose_singular_system(sys_.subdomain(), s);
    if (initializing && !why.empty()) throw InputError("the model is singular at t = 0:\n  " + why);
    std::ostringstream os;
    os << "the iteration matrix could not be factored at t = " << s.t << " s: " << solver_.failure();
    if (!why.empty()) os << "\n  " << why;
    throw SolverError(os.str());
  }
  return solve_factored();
}

ModelVector LinearizedSystem::solve_with_last_factorization(const MechanicalState& s, const AssemblyCoefficients& c,
                                                           ConstraintRows rows, ModelVector* residual) {
  // S is left as it was factored: PETSc sees no change of its state and does not refactor.
  assemble(s, c, rows, false, residual);
  return solve_factored();
}

ModelVector LinearizedSystem::solve_mass_action_with_last_factorization(const MechanicalState& s,
                                                                       const AssemblyCoefficients& c,
                                                                       const Eigen::VectorXd& w) {
  const double t0 = MPI_Wtime();
  PetscLogEventBegin(ev_assembly, 0, 0, 0, 0);
  check_petsc(sys_.assemble_mass_action(s, c, w), "assembly");
  PetscLogEventEnd(ev_assembly, 0, 0, 0, 0);
  times_.assembly += MPI_Wtime() - t0;
  return solve_factored();
}

std::string LinearizedSystem::describe_largest(const ModelVector& r) const {
  // Collective: the rank holding the largest entry names it (its node or joint), every rank gets
  // the text. Only owned coordinates compete (a ghost's entry is its owner's).
  const Subdomain& sub = sys_.subdomain();
  const Model& m = sys_.model();
  std::string text;
  // Whether the residual's coordinate part was given (the consistent start passes only the
  // constraint rows) is the same on every rank; a rank may own no coordinate at all.
  const bool have_dofs = sub.max_abs(Eigen::VectorXd::Constant(1, static_cast<double>(r.dofs.size()))) > 0.0;
  if (have_dofs) {
    Eigen::Index i = 0;
    const bool mine_here = r.dofs.size() > 0 && sub.num_owned_dofs() > 0;
    const double mine = mine_here ? r.dofs.head(sub.num_owned_dofs()).cwiseAbs().maxCoeff(&i) : -1.0;
    const int root = sub.rank_of_max(mine);
    std::ostringstream os;
    if (sub.rank() == root && mine >= 0.0)
      for (const Node& n : m.nodes())
        if (i >= n.first_dof && i < n.first_dof + n.ndof)
          os << "largest equilibrium residual " << r.dofs[i] << " at node '" << n.name << "' ("
             << coordinate_name(n.kind, static_cast<int>(i) - n.first_dof) << ")";
    text = sub.broadcast(os.str(), root);
  }
  Eigen::Index j = 0;
  const double mine = r.multipliers.size() ? r.multipliers.cwiseAbs().maxCoeff(&j) : -1.0;
  const int root = sub.rank_of_max(mine);
  std::ostringstream os;
  if (sub.rank() == root && mine >= 0.0)
    for (size_t c = 0; c < m.constraints().size(); ++c) {
      const int first = m.first_multiplier(static_cast<int>(c));
      if (j >= first && j < first + m.constraints()[c]->size())
        os << "; largest constraint violation " << r.multipliers[j] << " in joint '" << m.constraints()[c]->name()
           << "' (" << m.constraints()[c]->type() << ", " << m.constraints()[c]->equation_label(static_cast<int>(j - first)) << ")";
    }
  return text + sub.broadcast(os.str(), root);
}

std::string format_newton_history(const std::vector<NewtonRecord>& history, bool scaled) {
  std::ostringstream os;
  os << "  " << std::setw(9) << "iteration" << std::setw(13) << "|r_q|" << std::setw(13) << "|Phi|" << std::setw(13)
     << "|dq|_inf" << std::setw(15) << "|dlambda|_inf" << (scaled ? "   (r_q scaled by beta h^2)" : "") << "\n";
  for (size_t i = 0; i < history.size(); ++i) {
    const auto& h_i = history[i];
    os << "  " << std::setw(9) << (i + 1) << std::scientific << std::setprecision(4) << std::setw(13)
       << h_i.residual_dynamic << std::setw(13) << h_i.residual_constraint << std::setw(13) << h_i.correction_q
       << std::setw(15) << h_i.correction_lambda << "\n"
       << std::defaultfloat;
  }
  return os.str();
}

NewtonRecord newton_record(const Subdomain& sub, const ModelVector& r, const Eigen::VectorXd& dq,
                           const Eigen::VectorXd& dl) {
  NewtonRecord rec;
  rec.residual_dynamic = sub.dof_norm(r.dofs);
  rec.residual_constraint = sub.multiplier_norm(r.multipliers);
  rec.correction_q = sub.max_abs(dq);
  rec.correction_lambda = sub.max_abs(dl);
  return rec;
}

NewtonScales NewtonScales::of(const Subdomain& sub) {
  // L from the whole model's nodes at t = 0 (the same on every rank, no communication): the
  // diagonal of their bounding box, which a shift of the scene leaves as it is.
  NewtonScales sc;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Node& n : sub.global_model().nodes()) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    if (n.kind == NodeKind::LineParticle2D) p.head<2>() = n.line_origin + n.q0[0] * n.line_direction;
    else if (n.kind == NodeKind::Frame3D) p = n.q0.head<3>();
    else p.head<2>() = n.q0.head<2>();
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = sub.global_model().nodes().empty() ? 0.0 : (hi - lo).norm();
  sc.model_size = diagonal > 0.0 ? diagonal : 1.0;  // one node, or all at one point: 1 m
  const Model& m = sub.model();
  sc.scale = Eigen::VectorXd::Constant(m.num_dofs(), sc.model_size);
  sc.position.assign(static_cast<size_t>(m.num_dofs()), -1);
  for (const Node& n : m.nodes())
    for (int k = 0; k < n.ndof; ++k) {
      const bool angle = (n.kind == NodeKind::RigidBody2D && k == 2) || (n.kind == NodeKind::Frame3D && k >= 3);
      if (angle) sc.scale[n.first_dof + k] = 1.0;  // rad
      else sc.position[static_cast<size_t>(n.first_dof + k)] = n.first_conf + k;
    }
  return sc;
}

void NewtonScales::measure(NewtonRecord& rec, const Subdomain& sub, const NewtonOptions& nt, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& dq) const {
  // Round-off floor of unknown i: ε S_i (10⁴ + 64 X/L), X the largest position coordinate |x|.
  // The first term is the round-off of the linear solve and of the residual relative to the
  // model's size (the former margin of 10⁴ ulps: at h = 1e-4 on the slider-crank Δλ stalled at
  // 5e-9 N with Δq at that level); it does not see the origin. The second is the resolution of the
  // positions themselves, which does: the residual is formed from differences of numbers of size
  // X, each known to an ulp εX, so lengths are resolved to ~εX and angles (differences over lengths
  // ~L) to ~εX/L. Measured on the slider-crank shifted by 10 km (X = 1e4 m, L = 0.9 m): once
  // converged, Δq wanders at 2e-12–1e-11 (m and rad) from one iteration to the next; 64 ulps
  // (1.6e-10) stay above that and below the corrections of a converging iteration (1e-8 at its
  // second iteration). At the origin (X ≈ L) the floor is ε S_i (10⁴ + 64), as before.
  const double eps = std::numeric_limits<double>::epsilon();
  double x_local = 0.0;
  for (Eigen::Index i = 0; i < dq.size(); ++i)
    if (const int c = position[static_cast<size_t>(i)]; c >= 0) x_local = std::max(x_local, std::fabs(q[c]));
  const double resolution = 1e4 + 64.0 * sub.max_abs(Eigen::VectorXd::Constant(1, x_local)) / model_size;
  double tol_ratio = 0.0, floor_ratio = 0.0;
  const double q_norm = nt.step_atol >= 0.0 ? sub.max_abs(q) : 0.0;
  for (Eigen::Index i = 0; i < dq.size(); ++i) {
    const double floor = eps * scale[i] * resolution;
    double tol = nt.atol + nt.rtol * scale[i];
    // Adaptive steps: a fraction of the local error tolerance (rtol‖q‖∞ + atol, the estimator's own
    // scale), never below round-off.
    if (nt.step_atol >= 0.0) tol = std::min(tol, std::max(nt.step_atol + nt.step_rtol * q_norm, floor));
    tol_ratio = std::max(tol_ratio, std::fabs(dq[i]) / tol);
    floor_ratio = std::max(floor_ratio, std::fabs(dq[i]) / floor);
  }
  // A NaN correction must not compare as converged: max() would drop it.
  if (!dq.allFinite()) tol_ratio = floor_ratio = std::numeric_limits<double>::infinity();
  rec.q_tolerance_ratio = sub.max_abs(Eigen::VectorXd::Constant(1, tol_ratio));
  rec.q_roundoff_ratio = sub.max_abs(Eigen::VectorXd::Constant(1, floor_ratio));
}

bool newton_converged(const NewtonOptions& nt, const NewtonRecord& rec, int iteration, double lambda_scale) {
  // λ cannot be resolved below the round-off of q amplified by β' ~ 1/(βh²) (the index-3
  // amplification of Arnold & Brüls Sec. 3.3): once Δq is at round-off level, λ is as good as it gets.
  const bool q_converged = rec.q_tolerance_ratio <= 1.0;
  const bool q_at_roundoff = rec.q_roundoff_ratio <= 1.0;
  const bool lambda_converged = rec.correction_lambda <= nt.atol_lambda + nt.rtol * lambda_scale;
  return q_converged && (lambda_converged || (iteration > 1 && q_at_roundoff));
}

}  // namespace alphaflex
