#include "alphaflex/integrators/quasi_static.hpp"

#include <cmath>
#include <sstream>

#include "alphaflex/core/error.hpp"

namespace alphaflex {
QuasiStatic::QuasiStatic(SaddlePointSystem& system, LinearSolver& solver, StaticOptions options)
    : lin_(system, solver), opt_(options) {
  if (opt_.steps < 1) throw InputError("the quasi-static analysis needs at least one load step");
}

bool QuasiStatic::equilibrium(MechanicalState& s, MechanicalState trial, double lf, std::vector<NewtonRecord>& history,
                              ModelVector& r) {
  const Subdomain& sub = lin_.system().subdomain();
  const Model& m = lin_.model();
  AssemblyCoefficients c;
  c.stiffness = 1.0;
  c.load_factor = lf;
  history.clear();
  const NewtonScales scales = NewtonScales::of(sub);
  for (int it = 1; it <= opt_.newton.max_iterations; ++it) {
    ModelVector x;
    try {
      x = lin_.solve(trial, c, ConstraintRows::Dynamic, &r);
    } catch (const SolverError&) {
      if (it == 1) throw;  // singular at a converged state: not a matter of step size
      return false;
    }
    m.retract(trial.q, -x.dofs);
    trial.lambda -= x.multipliers;
    NewtonRecord rec = newton_record(sub, r, x.dofs, x.multipliers);
    scales.measure(rec, sub, opt_.newton, trial.q, x.dofs);
    history.push_back(rec);
    if (!std::isfinite(rec.correction_q) || !std::isfinite(rec.correction_lambda)) return false;
    if (newton_converged(opt_.newton, rec, it, sub.max_abs(trial.lambda))) {
      s = trial;
      return true;
    }
  }
  return false;
}

StaticReport QuasiStatic::solve(MechanicalState& s, const std::function<void(const MechanicalState&, double)>& on_step) {
  s.v.setZero();
  s.qdd.setZero();
  StaticReport rep;
  const double target = opt_.target;
  const double first = target / opt_.steps;
  double lf = 0.0, dl = first;
  std::vector<NewtonRecord> history;
  ModelVector r;
  int cuts_here = 0;
  bool have_previous = false;
  MechanicalState previous;  // the converged state before the last one
  double previous_lf = 0.0;
  const Model& m = lin_.model();
  while (std::fabs(target - lf) > 1e-12 * std::max(1.0, std::fabs(target))) {
    if (std::fabs(dl) > std::fabs(target - lf)) dl = target - lf;
    const double next = lf + dl;
    MechanicalState trial = s;
    if (have_previous && lf != previous_lf) {
      const double ratio = (next - lf) / (lf - previous_lf);
      m.retract(trial.q, ratio * m.difference(previous.q, s.q));
      trial.lambda = s.lambda + ratio * (s.lambda - previous.lambda);
    }
    const MechanicalState before = s;
    bool ok = equilibrium(s, trial, next, history, r);
    if (!ok && have_previous) ok = equilibrium(s, before, next, history, r);  // without the predictor
    if (ok) {
      previous = before;
      previous_lf = lf;
      have_previous = true;
      lf = next;
      ++rep.load_steps;
      rep.iterations += static_cast<long>(history.size());
      rep.max_iterations = std::max(rep.max_iterations, static_cast<int>(history.size()));
      if (on_step) on_step(s, lf);
      // Grow back towards the nominal step after an easy step (≤ 4 iterations).
      if (cuts_here > 0 && history.size() <= 4) dl = std::copysign(std::min(std::fabs(first), 1.5 * std::fabs(dl)), first);
      cuts_here = std::max(0, cuts_here - 1);
      continue;
    }
    ++rep.cuts;
    ++cuts_here;
    if (cuts_here > opt_.max_cuts) {
      std::ostringstream os;
      os << "the quasi-static analysis did not converge from load factor " << lf << " to " << next << " after "
         << opt_.max_cuts << " step cuts (load step " << dl << ").\n"
         << format_newton_history(history, false) << "  " << lin_.describe_largest(r)
         << ".\n  The structure may be unstable at this load (a limit or bifurcation point), or a part is not held "
            "by joints or stiffness; try more solver.static.steps or check the supports.";
      throw SolverError(os.str());
    }
    dl /= 2.0;
  }
  return rep;
}

}  // namespace alphaflex
