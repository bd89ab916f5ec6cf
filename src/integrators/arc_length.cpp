#include "alphaflex/integrators/arc_length.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "alphaflex/core/error.hpp"

namespace alphaflex {

std::string CriticalPoint::kind_name() const {
  switch (kind) {
    case Kind::LimitMaximum: return "limit point (load maximum)";
    case Kind::LimitMinimum: return "limit point (load minimum)";
    case Kind::Bifurcation: break;
  }
  return "bifurcation candidate (det K_T changes sign)";
}

ArcLength::ArcLength(SaddlePointSystem& system, LinearSolver& solver, StaticOptions options)
    : lin_(system, solver), sub_(system.subdomain()), solver_(solver), opt_(options) {
  ArcLengthOptions& a = opt_.arc_length;
  if (!(a.max_load_factor > 0.0)) a.max_load_factor = std::fabs(opt_.target);
  if (!(a.max_load_factor > 0.0)) throw InputError("solver.static.arc_length.max_load_factor: expected a load factor > 0");
  if (!(a.min > 0.0 && a.min <= a.initial && a.initial <= a.max))
    throw InputError("solver.static.arc_length: expected 0 < min ≤ initial ≤ max");
}

double ArcLength::dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  return dots({{&a, &b}})[0];
}

std::vector<double> ArcLength::dots(const std::vector<std::pair<const Eigen::VectorXd*, const Eigen::VectorXd*>>& pairs) const {
  // Owned coordinates only (a ghost's entry is its owner's), summed over the ranks in one call.
  const Subdomain& sub = sub_;
  const Eigen::Index n = sub.num_owned_dofs();
  std::vector<double> v;
  v.reserve(pairs.size());
  for (const auto& [a, b] : pairs) v.push_back(weight_ * a->head(n).dot(b->head(n)));
  sub.sum(v);
  return v;
}

double ArcLength::search_slope(const ModelVector& dx, const ModelVector& r) const {
  // s = δxᵀ r over the owned coordinates and the multipliers (all owned), over the ranks.
  const Subdomain& sub = sub_;
  const Eigen::Index n = sub.num_owned_dofs();
  std::vector<double> v{dx.dofs.head(n).dot(r.dofs.head(n)) + dx.multipliers.dot(r.multipliers)};
  sub.sum(v);
  return v[0];
}

ArcLength::Linearization ArcLength::linearize(const MechanicalState& s, double load_factor) {
  AssemblyCoefficients c;
  c.stiffness = 1.0;
  c.load_factor = load_factor;
  Linearization L;
  L.xr = lin_.solve(s, c, ConstraintRows::Dynamic, &L.r);
  L.det_sign = solver_.determinant_sign();
  // The residual is affine in Λ (every load is Λ times a function of q), so ∂r/∂Λ = r(Λ + 1) − r(Λ)
  // exactly, and the second right-hand side costs a residual assembly and a solve with the same
  // factors: x_f = S⁻¹r(Λ + 1) − x_r.
  c.load_factor = load_factor + 1.0;
  const ModelVector x1 = lin_.solve_with_last_factorization(s, c, ConstraintRows::Dynamic, nullptr);
  L.xf.dofs = x1.dofs - L.xr.dofs;
  L.xf.multipliers = x1.multipliers - L.xr.multipliers;
  return L;
}

bool ArcLength::step(const MechanicalState& sn, double lfn, const Linearization& tangent, double dl, bool fixed_load,
                     MechanicalState& s, double& dlf, std::vector<NewtonRecord>& history, ModelVector& r,
                     int& line_searches) {
  const Subdomain& sub = sub_;
  const Model& m = lin_.model();
  history.clear();
  // Predictor: along the tangent (q, λ)' = −x_f at the converged state.
  MechanicalState trial = sn;
  m.retract(trial.q, -dlf * tangent.xf.dofs);
  trial.lambda = sn.lambda - dlf * tangent.xf.multipliers;
  double inc = dlf;  // ΔΛ of this step so far
  // The last correction, for the line search: the state before it, δx, δΛ and s(0) = δxᵀr(before).
  MechanicalState before;
  ModelVector dx;
  double d_load = 0.0, s0 = 0.0;
  const NewtonScales scales = NewtonScales::of(sub);  // per-coordinate scales of the stopping rule
  for (int it = 1; it <= opt_.newton.max_iterations; ++it) {
    Linearization L;
    try {
      L = linearize(trial, lfn + inc);
      if (opt_.arc_length.line_search && it > 1) {
        const double s1 = search_slope(dx, L.r);
        if (std::fabs(s1) > 0.8 * std::fabs(s0)) {
          // Regula falsi for s(η) = 0 between η = 0 and 1 (Crisfield 1983), kept in [0.1, 1]:
          // only shortens a correction that overshoots.
          double eta = (s0 - s1) != 0.0 ? s0 / (s0 - s1) : 0.5;
          if (!(eta > 0.0 && eta < 1.0)) eta = 0.5;
          eta = std::clamp(eta, 0.1, 1.0);
          trial = before;
          m.retract(trial.q, eta * dx.dofs);
          trial.lambda += eta * dx.multipliers;
          inc += (eta - 1.0) * d_load;
          L = linearize(trial, lfn + inc);
          ++line_searches;
        }
      }
    } catch (const SolverError&) {
      return false;  // singular along the way: a shorter arc length may pass
    }
    r = L.r;
    const Eigen::VectorXd du_now = m.difference(sn.q, trial.q);  // Δu, on the group
    const Eigen::VectorXd a = du_now - L.xr.dofs;
    const Eigen::VectorXd& xf = L.xf.dofs;
    double dL = 0.0;
    if (!fixed_load) {
      // ‖a − δΛ x_f‖²_w = Δℓ²: δΛ² (x_f·x_f) − 2δΛ (a·x_f) + a·a − Δℓ² = 0.
      const std::vector<double> d = dots({{&xf, &xf}, {&a, &xf}, {&a, &a}, {&a, &du_now}, {&xf, &du_now}});
      const double A = d[0], B = -2.0 * d[1], C = d[2] - dl * dl;
      const double disc = B * B - 4.0 * A * C;
      if (!(A > 0.0) || !(disc >= 0.0)) return false;  // no real root: a shorter arc length
      const double sq = std::sqrt(disc);
      // Numerically stable roots; the one whose increment a − δΛ x_f turns least from Δu.
      const double qq = -0.5 * (B + std::copysign(sq, B));
      const double r1 = qq / A, r2 = qq != 0.0 ? C / qq : r1;
      const double c1 = d[3] - r1 * d[4], c2 = d[3] - r2 * d[4];
      dL = c1 >= c2 ? r1 : r2;
    }
    dx.dofs = -L.xr.dofs - dL * xf;
    dx.multipliers = -L.xr.multipliers - dL * L.xf.multipliers;
    d_load = dL;
    s0 = search_slope(dx, L.r);
    before = trial;
    m.retract(trial.q, dx.dofs);
    trial.lambda += dx.multipliers;
    inc += dL;
    NewtonRecord rec = newton_record(sub, L.r, dx.dofs, dx.multipliers);
    scales.measure(rec, sub, opt_.newton, trial.q, dx.dofs);
    history.push_back(rec);
    if (!std::isfinite(rec.correction_q) || !std::isfinite(rec.correction_lambda) || !std::isfinite(inc)) return false;
    const bool load_converged =
        std::fabs(dL) <= opt_.newton.rtol * std::max(std::fabs(lfn + inc), std::fabs(inc)) + opt_.newton.atol;
    if (load_converged && newton_converged(opt_.newton, rec, it, sub.max_abs(trial.lambda))) {
      s = trial;
      dlf = inc;
      return true;
    }
  }
  return false;
}

namespace {

/// Vertex of the parabola through (s_i, λ_i), i = 0..2 (s increasing); λ_1 if it is flat or the
/// vertex falls outside [s_0, s_2].
double parabola_vertex(const double s[3], const double l[3]) {
  const double d01 = (l[1] - l[0]) / (s[1] - s[0]), d12 = (l[2] - l[1]) / (s[2] - s[1]);
  const double c2 = (d12 - d01) / (s[2] - s[0]);  // λ = l1 + c1 (σ − s1) + c2 (σ − s1)²
  if (!(std::fabs(c2) > 0.0)) return l[1];
  const double c1 = d01 + c2 * (s[1] - s[0]);
  const double sv = s[1] - c1 / (2.0 * c2);
  if (!(sv >= s[0] && sv <= s[2])) return l[1];
  return l[1] + c1 * (sv - s[1]) + c2 * (sv - s[1]) * (sv - s[1]);
}

}  // namespace

ArcLengthReport ArcLength::solve(MechanicalState& s, const std::function<void(const MechanicalState&, double)>& on_step,
                                 const std::function<void(const CriticalPoint&)>& critical) {
  const ArcLengthOptions& a = opt_.arc_length;
  const Model& m = lin_.model();
  s.v.setZero();
  s.qdd.setZero();
  solver_.compute_determinant(true);
  ArcLengthReport rep;
  double lf = 0.0;
  weight_ = 1.0;
  Linearization L = linearize(s, lf);
  {
    // u₀ = the linear response to the loads at Λ = 1: the scale of the coordinates in Δℓ.
    const Eigen::VectorXd t = -L.xf.dofs;
    const double u0 = std::sqrt(dot(t, t));
    if (!(u0 > 0.0) || !std::isfinite(u0))
      throw InputError("solver.static.method: arc_length needs loads that move the structure at load factor 1 (the "
                       "linear response to the loads is " + std::to_string(u0) + ")");
    weight_ = 1.0 / (u0 * u0);
  }
  double dl = a.initial;
  Eigen::VectorXd prev_du;
  double prev_dlf = 0.0, arc = 0.0;
  int det_prev = L.det_sign;
  bool pending = false;  // a sign change of det S waiting for the next step (see below)
  CriticalPoint pending_point;
  // The last three converged points (arc length along the path, Λ) for the limit-point estimate.
  std::vector<double> path_s{0.0}, path_l{0.0};
  std::vector<NewtonRecord> history;
  ModelVector r;
  MechanicalState next;
  rep.min_arc = a.max;
  while (true) {
    if (rep.load_steps >= a.max_steps) {
      rep.stop = "max_steps";
      break;
    }
    const Eigen::VectorXd t = -L.xf.dofs;
    const double norm_t = std::sqrt(dot(t, t));
    // The direction of the predictor: that of the last increment (Feng, Perić & Owen 1995).
    double sign = 1.0;
    if (prev_du.size() > 0) {
      const double d = dot(prev_du, t);
      sign = d > 0.0 ? 1.0 : (d < 0.0 ? -1.0 : (prev_dlf >= 0.0 ? 1.0 : -1.0));
    }
    double dlf = sign * dl / norm_t;
    bool landing = false;
    if (std::fabs(lf + dlf) >= a.max_load_factor) {
      // The last step lands on ±max_load_factor at fixed load (load control for this step only).
      dlf = std::copysign(a.max_load_factor, lf + dlf) - lf;
      landing = true;
    }
    if (!step(s, lf, L, dl, landing, next, dlf, history, r, rep.line_searches)) {
      ++rep.cuts;
      dl *= 0.5;
      if (dl < a.min) {
        std::ostringstream os;
        os << "the arc-length path did not converge from load factor " << lf << " after " << rep.load_steps
           << " steps: the arc length fell below solver.static.arc_length.min = " << a.min << ".\n"
           << format_newton_history(history, false) << "  " << lin_.describe_largest(r)
           << ".\n  Try a smaller solver.static.arc_length.initial/max or more solver.newton.max_iter.";
        throw SolverError(os.str());
      }
      continue;
    }
    const Eigen::VectorXd du = m.difference(s.q, next.q);
    const double ds = std::sqrt(dot(du, du));
    s = next;
    lf += dlf;
    arc += ds;
    ++rep.load_steps;
    const int its = static_cast<int>(history.size());
    rep.iterations += its;
    rep.max_iterations = std::max(rep.max_iterations, its);
    rep.min_arc = std::min(rep.min_arc, ds);
    rep.max_arc = std::max(rep.max_arc, ds);
    rep.load_factor = lf;
    if (on_step) on_step(s, lf);
    L = linearize(s, lf);  // the next predictor's tangent and det S here
    path_s.push_back(arc);
    path_l.push_back(lf);
    if (path_s.size() > 3) {
      path_s.erase(path_s.begin());
      path_l.erase(path_l.begin());
    }
    // A limit point lies inside a step: det S at the step's end may have changed sign while ΔΛ
    // changes sign only at the next step. A sign change of det S is therefore a bifurcation
    // candidate only if ΔΛ keeps its sign over that step and the next one.
    const bool det_changed = L.det_sign != 0 && det_prev != 0 && L.det_sign != det_prev;
    if (prev_dlf != 0.0 && dlf * prev_dlf < 0.0) {
      CriticalPoint cp;
      cp.kind = prev_dlf > 0.0 ? CriticalPoint::Kind::LimitMaximum : CriticalPoint::Kind::LimitMinimum;
      cp.step = rep.load_steps - 1;
      cp.load_factor = path_s.size() == 3 ? parabola_vertex(path_s.data(), path_l.data()) : path_l[path_l.size() - 2];
      cp.lower = std::min(path_l.front(), path_l.back());
      cp.upper = std::max(path_l.front(), path_l.back());
      rep.critical_points.push_back(cp);
      if (critical) critical(cp);
      pending = false;
    } else if (pending) {
      rep.critical_points.push_back(pending_point);
      if (critical) critical(pending_point);
      pending = false;
    }
    if (det_changed) {
      pending_point = CriticalPoint{};
      pending_point.kind = CriticalPoint::Kind::Bifurcation;
      pending_point.step = rep.load_steps;
      pending_point.lower = std::min(lf - dlf, lf);
      pending_point.upper = std::max(lf - dlf, lf);
      pending_point.load_factor = 0.5 * (pending_point.lower + pending_point.upper);
      // Within a step where ΔΛ changed sign it is the limit point's own sign change.
      pending = !(prev_dlf != 0.0 && dlf * prev_dlf < 0.0);
    }
    if (L.det_sign != 0) det_prev = L.det_sign;
    prev_du = du;
    prev_dlf = dlf;
    if (landing) {
      rep.stop = "max_load_factor";
      break;
    }
    // Arc length for the next step from this step's iterations (Crisfield 1981, Ramm 1981).
    dl = std::clamp(dl * std::sqrt(static_cast<double>(a.target_iterations) / std::max(1, its)), a.min, a.max);
  }
  if (pending) {  // the path ended right after it: no later step can make it a limit point
    rep.critical_points.push_back(pending_point);
    if (critical) critical(pending_point);
  }
  return rep;
}

}  // namespace alphaflex
