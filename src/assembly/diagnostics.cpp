#include "alphaflex/assembly/diagnostics.hpp"

#include <Eigen/QR>
#include <Eigen/SparseCore>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseQR>
#include <Eigen/OrderingMethods>
#include <set>
#include <sstream>

namespace alphaflex {
namespace {

constexpr int kDenseLimit = 2000;  // unknowns; beyond this the O(n³) check is not attempted

/// Calls f(row, column, value) for every entry of Φ_q(q, t), in model order.
template <class F>
void for_each_jacobian_entry(const Model& m, const MechanicalState& s, F&& f) {
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  for (size_t c = 0; c < m.constraints().size(); ++c) {
    const Constraint& con = *m.constraints()[c];
    const auto idx = m.dofs_of(con.nodes());
    con.evaluate(gather(s.q, m.confs_of(con.nodes())), s.t, phi, phi_q);
    const int first = m.first_multiplier(static_cast<int>(c));
    for (int k = 0; k < con.size(); ++k)
      for (size_t j = 0; j < idx.size(); ++j) f(first + k, idx[j], phi_q(k, static_cast<Eigen::Index>(j)));
  }
}

Eigen::MatrixXd dense_constraint_jacobian(const Model& m, const MechanicalState& s, std::vector<int>& row_joint,
                                          std::vector<int>& row_eq) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m.num_multipliers(), m.num_dofs());
  for_each_jacobian_entry(m, s, [&](int r, int c, double v) { A(r, c) = v; });
  for (size_t c = 0; c < m.constraints().size(); ++c)
    for (int k = 0; k < m.constraints()[c]->size(); ++k) {
      row_joint.push_back(static_cast<int>(c));
      row_eq.push_back(k);
    }
  return A;
}

/// Rank of Φ_q: true if full row rank. A screen first: the sparse LDLᵀ of Φ_q Φ_qᵀ (m × m, AMD
/// ordering, no pivoting, stable on a positive semi-definite matrix) has every pivot D_ii above
/// 1e-12 of its row's N_ii = |row i|² when the rows are independent to better than ~1e-6 in
/// their singular values; a dependence at the QR's threshold (1e-10 in σ, so 1e-20 in σ²) leaves a
/// pivot at round-off, far below the screen's. Only when the screen flags a pivot does the
/// rank-revealing sparse QR of Φ_qᵀ (COLAMD) decide — it costs ~10⁴× more on large models
/// (0.6 s against 0.3 ms for 2·10⁵ coordinates).
bool full_row_rank(const Model& m, const MechanicalState& s) {
  std::vector<Eigen::Triplet<double>> entries;
  for_each_jacobian_entry(m, s, [&](int r, int c, double v) {
    if (v != 0.0) entries.emplace_back(c, r, v);
  });
  Eigen::SparseMatrix<double> At(m.num_dofs(), m.num_multipliers());
  At.setFromTriplets(entries.begin(), entries.end());
  At.makeCompressed();
  {
    const Eigen::SparseMatrix<double> N = Eigen::SparseMatrix<double>(At.transpose()) * At;
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::AMDOrdering<int>> ldlt(N);
    if (ldlt.info() == Eigen::Success) {
      const Eigen::VectorXd D = ldlt.vectorD();
      const Eigen::VectorXd diag = N.diagonal();
      // vectorD is in the permuted order: compare each pivot with the diagonal of its own row.
      const Eigen::VectorXd pdiag = ldlt.permutationP() * diag;
      bool all_clear = true;
      for (Eigen::Index i = 0; i < D.size() && all_clear; ++i) all_clear = D[i] > 1e-12 * pdiag[i];
      if (all_clear) return true;
    }
  }
  Eigen::SparseQR<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> qr;
  double largest = 1.0;
  for (const auto& e : entries) largest = std::max(largest, std::fabs(e.value()));
  qr.setPivotThreshold(1e-10 * largest);
  qr.compute(At);
  return qr.info() == Eigen::Success && qr.rank() == m.num_multipliers();
}

}  // namespace

std::vector<RedundantEquation> find_redundant_constraints(const Model& m, const MechanicalState& s, double tol) {
  std::vector<RedundantEquation> out;
  if (m.num_multipliers() == 0) return out;
  if (full_row_rank(m, s)) return out;  // the common case, decided by a sparse QR in milliseconds
  // Naming the redundant equations uses dense Φ_q: up to ~20 million entries (160 MB).
  if (static_cast<double>(m.num_multipliers()) * m.num_dofs() > 2e7) {
    out.push_back(RedundantEquation{-1, -1, {}});
    return out;
  }
  std::vector<int> row_joint, row_eq;
  const Eigen::MatrixXd A = dense_constraint_jacobian(m, s, row_joint, row_eq);
  // Greedy in scene order (modified Gram–Schmidt, twice for stability): an equation is redundant if
  // it lies, to tol, in the span of the independent equations before it. Only for the redundant
  // ones a least-squares fit names the joints it depends on.
  std::vector<int> kept;
  std::vector<Eigen::VectorXd> basis;
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    const Eigen::VectorXd a = A.row(r).transpose();
    const double norm = a.norm();
    Eigen::VectorXd w = a;
    for (int pass = 0; pass < 2; ++pass)
      for (const auto& b : basis) w -= b.dot(w) * b;
    if (norm > 0.0 && w.norm() > tol * norm) {
      kept.push_back(static_cast<int>(r));
      basis.push_back(w / w.norm());
      continue;
    }
    RedundantEquation e{row_joint[static_cast<size_t>(r)], row_eq[static_cast<size_t>(r)], {}};
    if (!kept.empty() && norm > 0.0) {
      Eigen::MatrixXd B(A.cols(), static_cast<Eigen::Index>(kept.size()));
      for (size_t k = 0; k < kept.size(); ++k) B.col(static_cast<Eigen::Index>(k)) = A.row(kept[k]).transpose();
      const Eigen::VectorXd coef = B.colPivHouseholderQr().solve(a);
      std::set<int> deps;
      for (Eigen::Index k = 0; k < coef.size(); ++k)
        if (std::fabs(coef[k]) > 1e-8) deps.insert(row_joint[static_cast<size_t>(kept[static_cast<size_t>(k)])]);
      e.depends_on.assign(deps.begin(), deps.end());
    }
    out.push_back(e);
  }
  return out;
}

double constraint_violation(const Model& m, const MechanicalState& s) {
  double viol = 0.0;
  Eigen::VectorXd phi;
  Eigen::MatrixXd phi_q;
  for (const auto& c : m.constraints()) {
    c->evaluate(gather(s.q, m.confs_of(c->nodes())), s.t, phi, phi_q);
    if (phi.size()) viol = std::max(viol, phi.cwiseAbs().maxCoeff());
  }
  return viol;
}

namespace {

/// The motions that neither the joints nor the elements' matrix hold: the null space of [A; Φ_q],
/// A = M (`stiffness` false: the accelerations of the consistent start are undefined) or K (true:
/// a static equilibrium is undefined). Per motion, the coordinates it moves (" body 'b' (x), …").
/// Dense, O(n³): for at most kDenseLimit coordinates (none found above).
std::vector<std::string> unheld_motions(const Model& m, const MechanicalState& s, bool stiffness) {
  if (m.num_dofs() > kDenseLimit) return {};
  std::vector<int> rj, re;
  const Eigen::MatrixXd A = dense_constraint_jacobian(m, s, rj, re);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(m.num_dofs(), m.num_dofs());
  LocalState ls;
  LocalResidual lr;
  for (const auto& e : m.elements()) {
    const auto idx = m.dofs_of(e->nodes());
    ls.q = gather(s.q, m.confs_of(e->nodes()));
    ls.v = gather(s.v, idx);
    ls.qdd = gather(s.qdd, idx);
    ls.t = s.t;
    lr.reset(static_cast<int>(idx.size()), true);
    e->evaluate(ls, lr, true);
    const Eigen::MatrixXd& B = stiffness ? lr.K : lr.M;
    for (size_t i = 0; i < idx.size(); ++i)
      for (size_t j = 0; j < idx.size(); ++j) M(idx[i], idx[j]) += B(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
  }
  Eigen::MatrixXd stacked(M.rows() + A.rows(), m.num_dofs());
  stacked << M, A;
  Eigen::FullPivLU<Eigen::MatrixXd> lu(stacked);
  lu.setThreshold(1e-12);
  const Eigen::MatrixXd kernel = lu.dimensionOfKernel() > 0 ? Eigen::MatrixXd(lu.kernel()) : Eigen::MatrixXd();
  std::vector<std::string> out;
  for (Eigen::Index k = 0; k < kernel.cols(); ++k) {
    std::ostringstream os;
    const Eigen::VectorXd v = kernel.col(k) / kernel.col(k).cwiseAbs().maxCoeff();
    bool first = true;
    for (const Node& n : m.nodes())
      for (int d = 0; d < n.ndof; ++d)
        if (std::fabs(v[n.first_dof + d]) > 1e-8) {
          os << (first ? " " : ", ") << "body '" << n.name << "' (" << coordinate_name(n.kind, d) << ")";
          first = false;
        }
    out.push_back(os.str());
  }
  return out;
}

}  // namespace

std::string diagnose_singular_system(const Model& m, const MechanicalState& s) {
  std::ostringstream os;
  const auto red = find_redundant_constraints(m, s);
  for (const auto& e : red) {
    if (e.constraint < 0) {
      os << "redundant constraints: the joints' Jacobian is rank deficient (the model is too large to name "
            "the joints involved)\n";
      continue;
    }
    const Constraint& c = *m.constraints()[static_cast<size_t>(e.constraint)];
    os << "redundant constraint: joint '" << c.name() << "' (" << c.type() << ") " << c.equation_label(e.equation)
       << " is a combination of equations of";
    if (e.depends_on.empty()) os << " nothing (it is void at this configuration)";
    for (size_t k = 0; k < e.depends_on.size(); ++k)
      os << (k ? ", " : " ") << "'" << m.constraints()[static_cast<size_t>(e.depends_on[k])]->name() << "'";
    os << "; remove it or use a joint that imposes fewer equations.\n";
  }
  // Directions neither inertia nor joints determine: null space of [M; Φ_q]. The consistent start
  // solves [[M, Φ_qᵀ],[Φ_q, 0]] for q̈0 and λ0, which is singular there even if springs act (a
  // massless point on springs alone would need a static solve). O(n³): small models only.
  if (m.num_dofs() > kDenseLimit) {
    // Without a finding there is nothing to report: a note alone would read as a diagnosis.
    if (os.str().empty()) return "";
    os << "(the search for coordinates that nothing acts on is skipped above " << kDenseLimit << " coordinates)";
    return os.str();
  }
  for (const std::string& names : unheld_motions(m, s, false))
    os << "massless motion no joint determines:" << names
       << " has no mass and no joint fixes it, so its acceleration is undefined (springs alone do not"
          " make it determined); give it a mass or attach it by joints.\n";
  // One finding per line, indented under the message that carries them.
  std::string r = os.str();
  if (!r.empty() && r.back() == '\n') r.pop_back();
  for (size_t p = r.find('\n'); p != std::string::npos; p = r.find('\n', p + 3)) r.replace(p, 1, "\n  ");
  return r;
}

std::vector<RedundantEquation> find_redundant_constraints(const Subdomain& sub, const MechanicalState& local,
                                                          double tol) {
  if (sub.size() == 1) return find_redundant_constraints(sub.model(), local, tol);
  return find_redundant_constraints(sub.global_model(), sub.gather(local), tol);
}

double constraint_violation(const Subdomain& sub, const MechanicalState& local) {
  return sub.max_abs(Eigen::VectorXd::Constant(1, constraint_violation(sub.model(), local)));
}

std::string diagnose_singular_system(const Subdomain& sub, const MechanicalState& local) {
  if (sub.size() == 1) return diagnose_singular_system(sub.model(), local);
  return diagnose_singular_system(sub.global_model(), sub.gather(local));
}

std::string find_unheld_motion(const Subdomain& sub, const MechanicalState& local) {
  const MechanicalState s = sub.size() == 1 ? local : sub.gather(local);
  const Model& m = sub.size() == 1 ? sub.model() : sub.global_model();
  std::ostringstream os;
  for (const std::string& names : unheld_motions(m, s, true)) os << "\n  nothing holds" << names;
  return os.str();
}

}  // namespace alphaflex
