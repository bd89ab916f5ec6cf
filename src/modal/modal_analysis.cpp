#include "alphaflex/modal/modal_analysis.hpp"

#include <slepceps.h>
#include <slepcpep.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <sstream>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/integrators/linearized_system.hpp"

namespace alphaflex {

const char* to_string(ModeKind kind) {
  switch (kind) {
    case ModeKind::Elastic: return "elastic";
    case ModeKind::RigidBody: return "rigid-body";
    case ModeKind::Overdamped: return "overdamped";
    case ModeKind::Unstable: return "unstable";
  }
  return "?";
}

namespace {

constexpr double kTwoPi = 6.283185307179586;
/// |ω²| below this fraction of max K_ii / max M_ii is a zero frequency: the round-off of a
/// rigid-body eigenvalue is ~ε·‖K‖/‖M‖ times the conditioning of the pencil, while the lowest
/// bending mode of a slender beam on 16 elements is ≥ 10⁻⁸ of the same scale.
constexpr double kZeroRelative = 1e-10;

/// The matrices of the linearization, owned here (copies of the assembly's matrix).
struct Pencil {
  Mat K = nullptr, C = nullptr, M = nullptr;  ///< [K Φ_qᵀ; Φ_q 0], [C 0; 0 0], [M 0; 0 0]
  ~Pencil() {
    MatDestroy(&K);
    MatDestroy(&C);
    MatDestroy(&M);
  }
};

/// S at coefficients c (dynamic rows: [c_M M + c_C C + c_K (K + K_Φ), Φ_qᵀ; Φ_q, 0]) copied.
void assemble_copy(SaddlePointSystem& system, const MechanicalState& s, double load_factor, double mass, double damping,
                   double stiffness, Mat* out) {
  AssemblyCoefficients c;
  c.mass = mass;
  c.damping = damping;
  c.stiffness = stiffness;
  c.load_factor = load_factor;
  check_petsc(system.assemble(s, c, ConstraintRows::Dynamic, true), "modal assembly");
  check_petsc(MatDuplicate(system.matrix(), MAT_COPY_VALUES, out), "modal matrix copy");
}

/// K, C, M of the pencil. C and M come as S(c) − S(0): the Φ_q blocks cancel exactly (the same
/// numbers), the dynamic block is C or M exactly (x − 0 = x), with no round-off of K mixed in.
void build_pencil(SaddlePointSystem& system, const MechanicalState& s, double load_factor, Pencil& p) {
  Mat zero = nullptr;
  assemble_copy(system, s, load_factor, 0.0, 0.0, 0.0, &zero);
  assemble_copy(system, s, load_factor, 0.0, 0.0, 1.0, &p.K);
  assemble_copy(system, s, load_factor, 1.0, 0.0, 0.0, &p.M);
  assemble_copy(system, s, load_factor, 0.0, 1.0, 0.0, &p.C);
  check_petsc(MatAXPY(p.M, -1.0, zero, SAME_NONZERO_PATTERN), "M = S(M) - S(0)");
  check_petsc(MatAXPY(p.C, -1.0, zero, SAME_NONZERO_PATTERN), "C = S(C) - S(0)");
  MatDestroy(&zero);
}

double global_max(double v, MPI_Comm comm);

/// The velocity kinematics of the perturbation, δv = δ̇ + G δ and δv̇ = δ̈ + G_a δ̇ + H δ, per node
/// (docs/theory/modes.md), substituted into M δv̇ + C δv + K δ:
///   M δ̈ + (C + M G_a) δ̇ + (K + C G + M H) δ.
/// Rotations of a frame node (body frame, R = R̄ exp(δθ^), body angular velocity Ω̄):
/// Ω = exp(−δθ^) Ω̄ + T(δθ) δθ̇ = Ω̄ + Ω̄ × δθ + δθ̇ + O(δ²), so G = G_a = Ω̄^, H = (dΩ̄/dt)^.
/// Translations (world frame) are additive: G = G_a = H = 0 in the inertial frame. In a frame
/// turning at the constant spin ω_f (world), x = x̄ + R_f(t) η with Ṙ_f = ω_f^ R_f and R_f = I at the
/// state: δẋ = η̇ + ω_f^ η and δẍ = η̈ + 2 ω_f^ η̇ + ω_f^ ω_f^ η, so G = ω_f^, G_a = 2 ω_f^ (Coriolis)
/// and H = ω_f^ ω_f^ = −|ω_f|² P_⊥ (centrifugal softening); the body-frame rotations are already
/// co-rotating. M G_a is the gyroscopic (Coriolis) matrix that the Newton matrix of the integrator
/// (the tangent at fixed v) leaves out. Returns false (nothing added) when nothing turns.
bool add_group_kinematics(const Subdomain& sub, const MechanicalState& s, const Eigen::Vector3d& frame_spin,
                          Pencil& p) {
  const Model& m = sub.model();
  struct Block {
    int row;
    Eigen::Matrix3d g, ga, h;
  };
  std::vector<Block> blocks;
  const Eigen::Matrix3d wf = hat<double>(frame_spin);
  const bool rotating = frame_spin.squaredNorm() > 0.0;
  double largest = frame_spin.norm();
  std::string not_frame;
  for (int nd = 0; nd < sub.num_owned_nodes(); ++nd) {
    const Node& n = m.node(nd);
    if (n.kind != NodeKind::Frame3D) {
      if (rotating && not_frame.empty()) not_frame = n.name;
      continue;
    }
    const int row = sub.dof_indices()[static_cast<size_t>(n.first_dof)];
    const Eigen::Vector3d w = s.v.segment<3>(n.first_dof + 3), wdot = s.qdd.segment<3>(n.first_dof + 3);
    if (rotating) blocks.push_back({row, wf, 2.0 * wf, wf * wf});
    blocks.push_back({row + 3, hat<double>(w), hat<double>(w), hat<double>(wdot)});
    largest = std::max({largest, w.norm(), wdot.norm()});
  }
  const std::string bad = sub.first_error(not_frame.empty() ? "" : "node '" + not_frame + "'");
  if (!bad.empty())
    throw InputError("modes.rotating_frame: " + bad +
                     " is not a 3D frame node; the rotating-frame linearization is for 3D models (beams, shells, "
                     "rigid bodies)");
  if (global_max(largest, sub.comm()) == 0.0) return false;
  PetscInt rows = 0, cols = 0;
  check_petsc(MatGetLocalSize(p.K, &rows, &cols), "local size");
  auto block_matrix = [&](Eigen::Matrix3d Block::*which, Mat* out) {
    check_petsc(MatCreateAIJ(sub.comm(), rows, cols, PETSC_DETERMINE, PETSC_DETERMINE, 3, nullptr, 0, nullptr, out),
                "MatCreateAIJ");
    for (const Block& b : blocks) {
      const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> a = b.*which;
      const PetscInt idx[3] = {b.row, b.row + 1, b.row + 2};
      check_petsc(MatSetValues(*out, 3, idx, 3, idx, a.data(), INSERT_VALUES), "MatSetValues");
    }
    check_petsc(MatAssemblyBegin(*out, MAT_FINAL_ASSEMBLY), "assembly");
    check_petsc(MatAssemblyEnd(*out, MAT_FINAL_ASSEMBLY), "assembly");
  };
  Mat G = nullptr, Ga = nullptr, H = nullptr, MGa = nullptr, CG = nullptr, MH = nullptr;
  block_matrix(&Block::g, &G);
  block_matrix(&Block::ga, &Ga);
  block_matrix(&Block::h, &H);
  check_petsc(MatMatMult(p.M, Ga, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &MGa), "M G_a");
  check_petsc(MatMatMult(p.C, G, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &CG), "C G");
  check_petsc(MatMatMult(p.M, H, MAT_INITIAL_MATRIX, PETSC_DEFAULT, &MH), "M H");
  check_petsc(MatAXPY(p.K, 1.0, CG, DIFFERENT_NONZERO_PATTERN), "K + C G");
  check_petsc(MatAXPY(p.K, 1.0, MH, DIFFERENT_NONZERO_PATTERN), "K + M H");
  check_petsc(MatAXPY(p.C, 1.0, MGa, DIFFERENT_NONZERO_PATTERN), "C + M G_a");
  for (Mat* x : {&G, &Ga, &H, &MGa, &CG, &MH}) MatDestroy(x);
  return true;
}

double global_max(double v, MPI_Comm comm) {
  double g = 0.0;
  MPI_Allreduce(&v, &g, 1, MPI_DOUBLE, MPI_MAX, comm);
  return g;
}

/// Number of leading coordinates of a node that are translations (m); the others are rotations.
int translations(const Node& n) {
  switch (n.kind) {
    case NodeKind::Frame3D: return 3;
    case NodeKind::RigidBody2D: return 2;
    default: return n.ndof;
  }
}

/// Local node of each local coordinate and its index in the node.
struct DofOwner {
  std::vector<int> node, index;
};
DofOwner dof_owners(const Model& m) {
  DofOwner o;
  o.node.resize(static_cast<size_t>(m.num_dofs()));
  o.index.resize(o.node.size());
  for (int n = 0; n < static_cast<int>(m.nodes().size()); ++n)
    for (int k = 0; k < m.node(n).ndof; ++k) {
      o.node[static_cast<size_t>(m.node(n).first_dof + k)] = n;
      o.index[static_cast<size_t>(m.node(n).first_dof + k)] = k;
    }
  return o;
}

/// Diagonals of K and M on the owned coordinates; refuses coordinates whose rows of K, M and Φ_qᵀ
/// are all zero (massless, no stiffness, no joint: the pencil is singular at every shift).
double check_and_scale(SaddlePointSystem& system, const Pencil& p) {
  const Subdomain& sub = system.subdomain();
  const Model& m = system.model();
  Vec vk = nullptr, vm = nullptr, dk = nullptr, dm = nullptr;
  check_petsc(MatCreateVecs(p.K, &vk, nullptr), "vectors");
  check_petsc(VecDuplicate(vk, &vm), "vectors");
  check_petsc(VecDuplicate(vk, &dk), "vectors");
  check_petsc(VecDuplicate(vk, &dm), "vectors");
  check_petsc(MatGetRowMaxAbs(p.K, vk, nullptr), "row max");
  check_petsc(MatGetRowMaxAbs(p.M, vm, nullptr), "row max");
  check_petsc(MatGetDiagonal(p.K, dk), "diagonal");
  check_petsc(MatGetDiagonal(p.M, dm), "diagonal");
  ModelVector rk, rm, ek, em;
  check_petsc(system.to_model(vk, rk), "gather");
  check_petsc(system.to_model(vm, rm), "gather");
  check_petsc(system.to_model(dk, ek), "gather");
  check_petsc(system.to_model(dm, em), "gather");
  VecDestroy(&vk);
  VecDestroy(&vm);
  VecDestroy(&dk);
  VecDestroy(&dm);
  const DofOwner owner = dof_owners(m);
  std::string bad;
  int nbad = 0;
  double kmax = 0.0, mmax = 0.0;
  for (int i = 0; i < sub.num_owned_dofs(); ++i) {
    if (rk.dofs[i] == 0.0 && rm.dofs[i] == 0.0) {
      if (nbad++ < 5) {
        const Node& n = m.node(owner.node[static_cast<size_t>(i)]);
        bad += std::string(bad.empty() ? "" : ", ") + n.name + "." + coordinate_name(n.kind, owner.index[static_cast<size_t>(i)]);
      }
    }
    kmax = std::max(kmax, std::fabs(ek.dofs[i]));
    mmax = std::max(mmax, em.dofs[i]);
  }
  // The ranks agree on the error before anyone throws (a collective call follows otherwise).
  int total = 0;
  MPI_Allreduce(&nbad, &total, 1, MPI_INT, MPI_SUM, sub.comm());
  if (total > 0) {
    // Rank order: the first rank with a bad coordinate names them.
    int rank = 0, first = 0;
    MPI_Comm_rank(sub.comm(), &rank);
    int mine = nbad > 0 ? rank : 1 << 30;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, sub.comm());
    const std::string names = [&] {
      unsigned long long len = bad.size();
      MPI_Bcast(&len, 1, MPI_UNSIGNED_LONG_LONG, first, sub.comm());
      std::string out = bad;
      out.resize(static_cast<size_t>(len));
      MPI_Bcast(out.data(), static_cast<int>(len), MPI_CHAR, first, sub.comm());
      return out;
    }();
    throw InputError("modes: " + std::to_string(total) + " coordinate(s) have neither mass nor stiffness nor a joint (" +
                     names + (total > 5 ? ", ..." : "") +
                     "): their frequency is undefined. Give them a mass or inertia, a spring, or a joint");
  }
  // max K_ii / max M_ii, not max (K_ii / M_ii): a tiny rotary inertia (slender beams) makes the
  // latter the top of the spectrum by many decades, and "zero" would swallow the lowest modes.
  kmax = global_max(kmax, sub.comm());
  mmax = global_max(mmax, sub.comm());
  return mmax > 0.0 ? kmax / mmax : 0.0;
}

/// Part of each element of the global model (its name up to '['), and the joints by name.
struct Parts {
  std::vector<std::string> names;
  std::vector<int> of_element, of_constraint;  // global element / constraint → part
};
Parts model_parts(const Model& global) {
  Parts p;
  std::map<std::string, int> index;
  auto part = [&](const std::string& full) {
    const std::string n = full.substr(0, full.find('['));
    auto it = index.find(n);
    if (it != index.end()) return it->second;
    p.names.push_back(n);
    return index[n] = static_cast<int>(p.names.size()) - 1;
  };
  for (const auto& e : global.elements()) p.of_element.push_back(part(e->name()));
  for (const auto& c : global.constraints()) p.of_constraint.push_back(part(c->name()));
  return p;
}

/// Kinetic (x̄ᵀMx) and potential (x̄ᵀ(K + K_Φ)x, symmetric part) energy of every mode's (complex)
/// shape per part: each element and joint owned by this rank evaluated once for all modes, then a
/// sum over ranks. Fills the modal mass, the shares and the dominant part of each mode.
void energy_shares(const Subdomain& sub, const Parts& parts, const MechanicalState& s, double load_factor,
                   std::vector<Mode>& modes) {
  const Model& m = sub.model();
  const size_t np = parts.names.size(), nm = modes.size();
  std::vector<double> local(2 * np * nm, 0.0);  // [mode][part][kinetic, potential]
  auto quad = [](const Eigen::MatrixXd& A, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    return a.dot(A * a) + b.dot(A * b);
  };
  auto add = [&](const std::vector<int>& dofs, size_t part, const Eigen::MatrixXd* M, const Eigen::MatrixXd& K) {
    for (size_t k = 0; k < nm; ++k) {
      const Eigen::VectorXd ar = gather(modes[k].shape_re, dofs), ai = gather(modes[k].shape_im, dofs);
      if (M) local[2 * (k * np + part)] += quad(*M, ar, ai);
      local[2 * (k * np + part) + 1] += quad(K, ar, ai);
    }
  };
  LocalState ls;
  LocalResidual lr;
  for (size_t e = 0; e < m.elements().size(); ++e) {
    const Element& el = *m.elements()[e];
    const std::vector<int> dofs = m.dofs_of(el.nodes()), confs = m.confs_of(el.nodes());
    ls.q = gather(s.q, confs);
    ls.v = gather(s.v, dofs);
    ls.qdd = gather(s.qdd, dofs);
    ls.t = s.t;
    ls.load_factor = load_factor;
    lr.reset(static_cast<int>(dofs.size()), true);
    el.evaluate(ls, lr, true);
    add(dofs, static_cast<size_t>(parts.of_element[static_cast<size_t>(sub.global_element(static_cast<int>(e)))]), &lr.M,
        lr.K);
  }
  Eigen::MatrixXd kphi;
  for (size_t c = 0; c < m.constraints().size(); ++c) {
    const Constraint& con = *m.constraints()[c];
    const std::vector<int> dofs = m.dofs_of(con.nodes()), confs = m.confs_of(con.nodes());
    const Eigen::VectorXd lam = s.lambda.segment(m.first_multiplier(static_cast<int>(c)), con.size());
    kphi.setZero(static_cast<Eigen::Index>(dofs.size()), static_cast<Eigen::Index>(dofs.size()));
    con.geometric_stiffness(gather(s.q, confs), s.t, lam, kphi);
    add(dofs, static_cast<size_t>(parts.of_constraint[static_cast<size_t>(sub.global_constraint(static_cast<int>(c)))]),
        nullptr, kphi);
  }
  std::vector<double> all(local.size(), 0.0);
  MPI_Allreduce(local.data(), all.data(), static_cast<int>(all.size()), MPI_DOUBLE, MPI_SUM, sub.comm());
  for (size_t k = 0; k < nm; ++k) {
    Mode& md = modes[k];
    double tk = 0.0, tp = 0.0;
    for (size_t p = 0; p < np; ++p) {
      tk += all[2 * (k * np + p)];
      tp += all[2 * (k * np + p) + 1];
    }
    md.modal_mass = tk;
    md.kinetic_share.assign(np, 0.0);
    md.strain_share.assign(np, 0.0);
    for (size_t p = 0; p < np; ++p) {
      if (tk != 0.0) md.kinetic_share[p] = all[2 * (k * np + p)] / tk;
      if (tp != 0.0) md.strain_share[p] = all[2 * (k * np + p) + 1] / tp;
      if (md.dominant_part < 0 || md.kinetic_share[p] > md.kinetic_share[static_cast<size_t>(md.dominant_part)])
        md.dominant_part = static_cast<int>(p);
    }
  }
}

/// Scales the shape so that its largest translation is 1 (real, phase removed); a shape with no
/// translation above 10⁻⁸ × (largest rotation × model size) is scaled by its largest rotation.
double normalize(const Subdomain& sub, const DofOwner& owner, double model_size, Eigen::VectorXd& xr,
                 Eigen::VectorXd& xi) {
  const Model& m = sub.model();
  // Largest |x_j| among translations and among rotations, with its complex value.
  double best[2][3] = {{0, 0, 0}, {0, 0, 0}};
  for (int i = 0; i < sub.num_owned_dofs(); ++i) {
    const Node& n = m.node(owner.node[static_cast<size_t>(i)]);
    const int kind = owner.index[static_cast<size_t>(i)] < translations(n) ? 0 : 1;
    const double a = std::hypot(xr[i], xi[i]);
    if (a > best[kind][0]) best[kind][0] = a, best[kind][1] = xr[i], best[kind][2] = xi[i];
  }
  int size = 1;
  MPI_Comm_size(sub.comm(), &size);
  std::vector<double> all(static_cast<size_t>(6 * size));
  MPI_Allgather(&best[0][0], 6, MPI_DOUBLE, all.data(), 6, MPI_DOUBLE, sub.comm());
  double g[2][3] = {{0, 0, 0}, {0, 0, 0}};
  for (int r = 0; r < size; ++r)
    for (int k = 0; k < 2; ++k)
      if (all[static_cast<size_t>(6 * r + 3 * k)] > g[k][0])
        for (int j = 0; j < 3; ++j) g[k][j] = all[static_cast<size_t>(6 * r + 3 * k + j)];
  const int k = g[0][0] > 1e-8 * g[1][0] * std::max(model_size, 1e-300) || g[1][0] == 0.0 ? 0 : 1;
  if (g[k][0] == 0.0) return 0.0;
  // x ← x / z with z the largest entry: that entry becomes 1, the phase of the whole shape follows.
  const std::complex<double> z(g[k][1], g[k][2]);
  for (Eigen::Index i = 0; i < xr.size(); ++i) {
    const std::complex<double> v = std::complex<double>(xr[i], xi[i]) / z;
    xr[i] = v.real();
    xi[i] = v.imag();
  }
  return g[1][0] / std::hypot(g[k][1], g[k][2]);  // the largest rotation after scaling
}

/// Largest distance between two nodes' positions (bounding-box diagonal, m), over all ranks.
double model_size(const Subdomain& sub, const MechanicalState& s) {
  const Model& m = sub.model();
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (const Node& n : m.nodes()) {
    const int dims = n.kind == NodeKind::Frame3D ? 3 : n.kind == NodeKind::LineParticle2D ? 0 : 2;
    for (int d = 0; d < dims; ++d) {
      lo[d] = std::min(lo[d], s.q[n.first_conf + d]);
      hi[d] = std::max(hi[d], s.q[n.first_conf + d]);
    }
  }
  double glo[3], ghi[3];
  MPI_Allreduce(lo, glo, 3, MPI_DOUBLE, MPI_MIN, sub.comm());
  MPI_Allreduce(hi, ghi, 3, MPI_DOUBLE, MPI_MAX, sub.comm());
  double d2 = 0.0;
  for (int d = 0; d < 3; ++d)
    if (ghi[d] >= glo[d]) d2 += (ghi[d] - glo[d]) * (ghi[d] - glo[d]);
  return std::sqrt(d2);
}

/// Forward or backward whirl: the sense of the orbit x(t) = Re(x e^{iωt}) of the nodes' translations,
/// n = x_im × x_r per node (world frame), against the spin Ω (world frame) of the spinning frames;
/// when no node translates (a rotor on a joint at its centre), the orbit of the rotations (body
/// frame, turned to the world).
std::string whirl_of(const Subdomain& sub, const MechanicalState& s, const Eigen::VectorXd& xr, const Eigen::VectorXd& xi) {
  const Model& m = sub.model();
  double sum[4] = {0.0, 0.0, 0.0, 0.0};  // translations: Σ n·Ω, Σ |n||Ω|; rotations: the same
  for (int nd = 0; nd < sub.num_owned_nodes(); ++nd) {
    const Node& n = m.node(nd);
    if (n.kind != NodeKind::Frame3D) continue;
    const Eigen::Vector4d qv = s.q.segment<4>(n.first_conf + 3);
    const Eigen::Matrix3d R = Eigen::Quaterniond(qv[0], qv[1], qv[2], qv[3]).normalized().toRotationMatrix();
    const Eigen::Vector3d omega = R * s.v.segment<3>(n.first_dof + 3);
    const Eigen::Vector3d orbit = xi.segment<3>(n.first_dof).cross(xr.segment<3>(n.first_dof));
    const Eigen::Vector3d turn = R * xi.segment<3>(n.first_dof + 3).cross(xr.segment<3>(n.first_dof + 3));
    sum[0] += orbit.dot(omega);
    sum[1] += orbit.norm() * omega.norm();
    sum[2] += turn.dot(omega);
    sum[3] += turn.norm() * omega.norm();
  }
  double g[4];
  MPI_Allreduce(sum, g, 4, MPI_DOUBLE, MPI_SUM, sub.comm());
  const int k = g[1] > 1e-12 * g[3] ? 0 : 2;
  if (!(g[k + 1] > 0.0) || std::fabs(g[k]) < 1e-6 * g[k + 1]) return "";
  return g[k] > 0.0 ? "forward" : "backward";
}

struct RawPair {
  double re, im;
  Eigen::VectorXd xr, xi;
};

}  // namespace

// Shared with the superelement's fixed-interface modes (superelement.cpp).
void set_mumps_shift_invert(ST st) {
  KSP ksp;
  PC pc;
  check_petsc(STSetType(st, STSINVERT), "STSetType");
  check_petsc(STGetKSP(st, &ksp), "STGetKSP");
  check_petsc(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  check_petsc(KSPGetPC(ksp, &pc), "KSPGetPC");
  check_petsc(PCSetType(pc, PCLU), "PCSetType");
  check_petsc(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
}

namespace {

/// The calls EPS and PEP share under their own names.
template <class Solver>
struct SlepcCalls {
  PetscErrorCode (*get_st)(Solver, ST*);
  PetscErrorCode (*from_options)(Solver);
  PetscErrorCode (*solve)(Solver);
  PetscErrorCode (*converged)(Solver, PetscInt*);
  PetscErrorCode (*iterations)(Solver, PetscInt*);
  PetscErrorCode (*pair)(Solver, PetscInt, PetscScalar*, PetscScalar*, Vec, Vec);
  PetscErrorCode (*destroy)(Solver*);
};
const SlepcCalls<EPS> kEpsCalls{EPSGetST, EPSSetFromOptions, EPSSolve, EPSGetConverged, EPSGetIterationNumber,
                                EPSGetEigenpair, EPSDestroy};
const SlepcCalls<PEP> kPepCalls{PEPGetST, PEPSetFromOptions, PEPSolve, PEPGetConverged, PEPGetIterationNumber,
                                PEPGetEigenpair, PEPDestroy};

/// Shift-and-invert with MUMPS, the command line's options over it, the solve, and the converged
/// eigenpairs with Im ≥ 0 (a conjugate is the same mode) on this rank's coordinates. Destroys
/// `solver`, also when it throws.
template <class Solver>
std::vector<RawPair> solve_and_collect(Solver solver, const SlepcCalls<Solver>& f, SaddlePointSystem& system,
                                       Mat layout, int& iterations, const char* failure) {
  Vec xr = nullptr, xi = nullptr;
  std::vector<RawPair> pairs;
  try {
    ST st;
    check_petsc(f.get_st(solver, &st), "get ST");
    set_mumps_shift_invert(st);
    check_petsc(f.from_options(solver), "SetFromOptions");
    const PetscErrorCode ierr = f.solve(solver);
    if (ierr)
      throw SolverError(std::string("modes: ") + failure + " (PETSc error " + std::to_string(ierr) +
                        ", in the shift-and-invert factorization or the iteration)");
    PetscInt nconv = 0, its = 0;
    check_petsc(f.converged(solver, &nconv), "converged");
    check_petsc(f.iterations(solver, &its), "iterations");
    iterations = static_cast<int>(its);
    check_petsc(MatCreateVecs(layout, &xr, nullptr), "vectors");
    check_petsc(VecDuplicate(xr, &xi), "vectors");
    ModelVector mr, mi;
    for (PetscInt i = 0; i < nconv; ++i) {
      PetscScalar kr, ki;
      check_petsc(f.pair(solver, i, &kr, &ki, xr, xi), "eigenpair");
      if (ki < 0.0) continue;
      check_petsc(system.to_model(xr, mr), "gather");
      check_petsc(system.to_model(xi, mi), "gather");
      pairs.push_back({kr, ki, mr.dofs, mi.dofs});
    }
  } catch (...) {
    VecDestroy(&xr);
    VecDestroy(&xi);
    f.destroy(&solver);
    throw;
  }
  VecDestroy(&xr);
  VecDestroy(&xi);
  check_petsc(f.destroy(&solver), "destroy");
  return pairs;
}

std::string converged_list(const std::vector<RawPair>& pairs, bool damped) {
  std::ostringstream os;
  os.precision(6);
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double f = damped ? std::fabs(pairs[i].im) / kTwoPi : std::sqrt(std::fabs(pairs[i].re)) / kTwoPi;
    os << (i ? ", " : "") << f << " Hz";
  }
  return pairs.empty() ? std::string("none") : os.str();
}

[[noreturn]] void not_converged(int want, const std::vector<RawPair>& got, bool damped, int its) {
  std::ostringstream os;
  os << "modes: the eigensolver did not converge: " << got.size() << " of " << want << " modes after " << its
     << " iterations (converged: " << converged_list(got, damped) << "). Ask again with more iterations or a "
     << "larger subspace, e.g. " << (damped ? "-pep_max_it 1000 -pep_ncv " : "-eps_max_it 1000 -eps_ncv ")
     << 3 * want + 10 << ", or fewer modes (modes.count)";
  throw SolverError(os.str());
}

}  // namespace

ModalResult compute_modes(SaddlePointSystem& system, const MechanicalState& state, double load_factor,
                          const ModalOptions& options) {
  const Subdomain& sub = system.subdomain();
  const MPI_Comm comm = sub.comm();
  const Model& global = sub.global_model();
  ModalResult res;
  const int free_dofs = global.num_dofs() - global.num_multipliers();
  if (free_dofs < 1)
    throw InputError("modes: the model has no degree of freedom (" + std::to_string(global.num_dofs()) +
                     " coordinates, " + std::to_string(global.num_multipliers()) + " joint equations)");
  if (options.count < 0) throw InputError("modes.count: expected at least 1 mode");
  if (options.count > free_dofs) {
    std::ostringstream os;
    os << "modes.count = " << options.count << ": the model has only " << free_dofs << " degrees of freedom ("
       << global.num_dofs() << " coordinates - " << global.num_multipliers() << " joint equations); ask for at most "
       << free_dofs;
    throw InputError(os.str());
  }
  const int count = options.count > 0 ? options.count : std::min(10, free_dofs);
  res.requested = count;

  Pencil p;
  build_pencil(system, state, load_factor, p);
  res.spectral_scale = check_and_scale(system, p);
  add_group_kinematics(sub, state, options.frame_spin, p);
  PetscReal nk = 0.0, nm = 0.0, nc = 0.0;
  check_petsc(MatNorm(p.K, NORM_INFINITY, &nk), "norm");
  check_petsc(MatNorm(p.M, NORM_INFINITY, &nm), "norm");
  check_petsc(MatNorm(p.C, NORM_INFINITY, &nc), "norm");
  // Damped when C is more than round-off against √(‖K‖‖M‖), the scale of ωM and of K/ω.
  const double cscale = nk > 0.0 ? std::sqrt(nk * nm) : nm;
  res.damped = nc > 1e-12 * cscale;
  // The scale of "zero": K/M, or (C/M)² when damping or spin dominate (a spinning rotor on a
  // joint has no stiffness at all); 1 rad²/s² when nothing is stiff or damped (every mode is then
  // a rigid-body mode, ω² at round-off).
  if (res.damped && nm > 0.0) res.spectral_scale = std::max(res.spectral_scale, (nc / nm) * (nc / nm));
  if (!(res.spectral_scale > 0.0)) res.spectral_scale = 1.0;
  const double scale = res.spectral_scale;
  if (res.damped && options.shift > 0.0)
    throw InputError("modes.shift: the damped/gyroscopic problem (C != 0) is searched from the lowest natural "
                     "frequency up (a real PETSc build has no complex shift); leave modes.shift out");
  // The shift: at the requested frequency, else just below zero — K alone is singular when rigid-
  // body modes exist, K + |σ|M is not.
  const double sigma = options.shift > 0.0 ? std::pow(kTwoPi * options.shift, 2) : -1e-6 * scale;

  std::vector<RawPair> pairs;
  int its = 0;
  if (!res.damped) {
    EPS eps;
    check_petsc(EPSCreate(comm, &eps), "EPSCreate");
    check_petsc(EPSSetOperators(eps, p.K, p.M), "EPSSetOperators");
    // Non-Hermitian: K + K_Φ is unsymmetric away from equilibrium (follower loads, the Lie-group
    // linearization in motion), and the pencil is indefinite in any case (the multiplier block).
    check_petsc(EPSSetProblemType(eps, EPS_GNHEP), "EPSSetProblemType");
    check_petsc(EPSSetDimensions(eps, count, PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
    check_petsc(EPSSetTarget(eps, sigma), "EPSSetTarget");
    check_petsc(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
    check_petsc(EPSSetTolerances(eps, 1e-12, 500), "EPSSetTolerances");
    pairs = solve_and_collect(eps, kEpsCalls, system, p.K, its,
                              "the eigensolver failed; with modes.shift, move it away from an eigenfrequency");
  } else {
    PEP pep;
    check_petsc(PEPCreate(comm, &pep), "PEPCreate");
    Mat ops[3] = {p.K, p.C, p.M};
    check_petsc(PEPSetOperators(pep, 3, ops), "PEPSetOperators");
    check_petsc(PEPSetProblemType(pep, PEP_GENERAL), "PEPSetProblemType");
    // Each oscillating mode is a conjugate pair, and a free coordinate without damping a double
    // zero (a Jordan block: two eigenvalues, one mode): room for both.
    check_petsc(PEPSetDimensions(pep, 2 * count + 2, PETSC_DEFAULT, PETSC_DEFAULT), "PEPSetDimensions");
    check_petsc(PEPSetTarget(pep, -std::sqrt(1e-6 * scale)), "PEPSetTarget");
    check_petsc(PEPSetWhichEigenpairs(pep, PEP_TARGET_MAGNITUDE), "PEPSetWhichEigenpairs");
    check_petsc(PEPSetTolerances(pep, 1e-12, 500), "PEPSetTolerances");
    pairs = solve_and_collect(pep, kPepCalls, system, p.K, its, "the quadratic eigensolver failed");
  }
  res.iterations = its;
  res.target = res.damped ? -std::sqrt(1e-6 * scale) : sigma;
  const double zero = kZeroRelative * res.spectral_scale;
  if (res.damped) {
    // A rigid-body coordinate without damping has s = 0 twice with one eigenvector (a Jordan block,
    // returned as two eigenvalues ~√ε apart with nearly the same vector): one mode. Zero
    // eigenvalues whose shapes are in the span of those kept already are dropped.
    const Eigen::Index owned = sub.num_owned_dofs();
    std::vector<Eigen::VectorXd> basis;  // orthonormal (owned entries)
    auto adds_direction = [&](const Eigen::VectorXd& x) {
      auto dot = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
        double l = a.head(owned).dot(b.head(owned)), g = 0.0;
        MPI_Allreduce(&l, &g, 1, MPI_DOUBLE, MPI_SUM, comm);
        return g;
      };
      Eigen::VectorXd v = x;
      const double n0 = std::sqrt(dot(v, v));
      if (n0 == 0.0) return false;
      for (const auto& b : basis) v -= dot(b, v) * b;
      const double n1 = std::sqrt(dot(v, v));
      if (n1 <= 1e-4 * n0) return false;
      basis.push_back(v / n1);
      return true;
    };
    std::vector<RawPair> kept;
    for (RawPair& rp : pairs) {
      if (std::hypot(rp.re, rp.im) <= std::sqrt(zero)) {
        const bool re_new = adds_direction(rp.xr), im_new = adds_direction(rp.xi);
        if (!re_new && !im_new) continue;
      }
      kept.push_back(std::move(rp));
    }
    pairs = std::move(kept);
  }
  if (static_cast<int>(pairs.size()) < count) not_converged(count, pairs, res.damped, res.iterations);
  // Nearest the target first (SLEPc's order); keep `count`, then sort by frequency.
  pairs.resize(static_cast<size_t>(count));
  res.converged = static_cast<int>(pairs.size());

  const Parts parts = model_parts(global);
  res.parts = parts.names;
  const DofOwner owner = dof_owners(system.model());
  const double size = model_size(sub, state);
  res.model_size = size;
  for (RawPair& rp : pairs) {
    Mode md;
    md.re = rp.re;
    md.im = res.damped ? rp.im : 0.0;
    if (!res.damped) {
      // ω² of a real pencil: a complex pair here is round-off of a (nearly) double eigenvalue.
      if (rp.re > zero) md.kind = ModeKind::Elastic;
      else if (rp.re >= -zero) md.kind = ModeKind::RigidBody;
      else md.kind = ModeKind::Unstable;
      md.frequency = md.kind == ModeKind::Elastic ? std::sqrt(rp.re) / kTwoPi : 0.0;
      md.natural_frequency = md.frequency;
      rp.xi.setZero(rp.xr.size());
    } else {
      const double mag = std::hypot(rp.re, rp.im);
      if (mag <= std::sqrt(zero)) md.kind = ModeKind::RigidBody;
      else if (rp.re > std::sqrt(zero)) md.kind = ModeKind::Unstable;
      else if (rp.im <= 1e-10 * mag) md.kind = ModeKind::Overdamped;
      else md.kind = ModeKind::Elastic;
      md.frequency = md.kind == ModeKind::RigidBody ? 0.0 : rp.im / kTwoPi;
      md.natural_frequency = md.kind == ModeKind::RigidBody ? 0.0 : mag / kTwoPi;
      md.damping_ratio = md.kind == ModeKind::RigidBody ? 0.0 : -rp.re / mag;
    }
    md.largest_rotation = normalize(sub, owner, size, rp.xr, rp.xi);
    if (res.damped && md.kind == ModeKind::Elastic) md.whirl = whirl_of(sub, state, rp.xr, rp.xi);
    md.shape_re = std::move(rp.xr);
    md.shape_im = std::move(rp.xi);
    res.modes.push_back(std::move(md));
  }
  energy_shares(sub, parts, state, load_factor, res.modes);
  std::stable_sort(res.modes.begin(), res.modes.end(), [](const Mode& a, const Mode& b) {
    return a.natural_frequency < b.natural_frequency;
  });
  for (const Mode& md : res.modes)
    if (md.kind == ModeKind::RigidBody) ++res.rigid_body_modes;
  if (options.below > 0.0) {
    const size_t before = res.modes.size();
    res.modes.erase(std::remove_if(res.modes.begin(), res.modes.end(),
                                   [&](const Mode& md) { return md.natural_frequency > options.below; }),
                    res.modes.end());
    if (res.modes.size() == before)
      res.warnings.push_back("all " + std::to_string(before) + " modes found are below modes.below = " +
                             std::to_string(options.below) + " Hz: there may be more (raise modes.count)");
  }
  return res;
}

namespace {

/// v and v̇ of every frame node of the local model moving rigidly with the rotation `spin` about the
/// axis through `point`: v = (Ω × (x − p), Rᵀ Ω), v̇ = (Ω × (Ω × (x − p)), 0).
void set_rigid_rotation(const Model& m, const Eigen::Vector3d& spin, const Eigen::Vector3d& point, MechanicalState& s) {
  for (const Node& n : m.nodes()) {
    if (n.kind != NodeKind::Frame3D) continue;
    const Eigen::Vector3d r = s.q.segment<3>(n.first_conf) - point;
    const Eigen::Vector4d qv = s.q.segment<4>(n.first_conf + 3);
    const Eigen::Matrix3d R = Eigen::Quaterniond(qv[0], qv[1], qv[2], qv[3]).normalized().toRotationMatrix();
    s.v.segment<3>(n.first_dof) = spin.cross(r);
    s.v.segment<3>(n.first_dof + 3) = R.transpose() * spin;
    s.qdd.segment<3>(n.first_dof) = spin.cross(spin.cross(r));
    s.qdd.segment<3>(n.first_dof + 3).setZero();
  }
}

}  // namespace

MechanicalState steady_rotation(SaddlePointSystem& system, const MechanicalState& state, double load_factor,
                                const Eigen::Vector3d& spin, const Eigen::Vector3d& point) {
  const Subdomain& sub = system.subdomain();
  const Model& m = system.model();
  MechanicalState s = state;
  const double size = std::max(model_size(sub, s), 1e-300);
  constexpr int kMaxIterations = 30;
  double step = 0.0;
  for (int it = 0; it < kMaxIterations; ++it) {
    set_rigid_rotation(m, spin, point, s);
    // The residual at the rigidly turning state, and its Jacobian with v(q), v̇(q): K + C G + M H
    // with the rotating-frame G, H of add_group_kinematics (δv = G δ, δv̇ = H δ at fixed η̇ = 0).
    Pencil p;
    build_pencil(system, s, load_factor, p);
    add_group_kinematics(sub, s, spin, p);
    Vec rhs = nullptr, x = nullptr;
    KSP ksp = nullptr;
    PC pc = nullptr;
    check_petsc(VecDuplicate(system.residual(), &rhs), "vectors");
    check_petsc(VecCopy(system.residual(), rhs), "copy");
    check_petsc(VecScale(rhs, -1.0), "scale");
    check_petsc(VecDuplicate(rhs, &x), "vectors");
    check_petsc(KSPCreate(sub.comm(), &ksp), "KSPCreate");
    check_petsc(KSPSetOperators(ksp, p.K, p.K), "KSPSetOperators");
    check_petsc(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
    check_petsc(KSPGetPC(ksp, &pc), "KSPGetPC");
    check_petsc(PCSetType(pc, PCLU), "PCSetType");
    check_petsc(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
    const PetscErrorCode ierr = KSPSolve(ksp, rhs, x);
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    if (!ierr) KSPGetConvergedReason(ksp, &reason);
    ModelVector dx;
    if (!ierr && reason >= 0) check_petsc(system.to_model(x, dx), "gather");
    KSPDestroy(&ksp);
    VecDestroy(&rhs);
    VecDestroy(&x);
    if (ierr || reason < 0)
      throw SolverError("modes: steady rotation at |Ω| = " + std::to_string(spin.norm()) +
                        " rad/s: the rotating-frame stiffness is singular (a buckled or unrestrained state: is the "
                        "speed above a divergence speed, or does a joint leave the structure free?)");
    m.retract(s.q, dx.dofs);
    s.lambda += dx.multipliers;
    step = sub.max_abs(dx.dofs);
    if (step <= 1e-12 * size) {
      set_rigid_rotation(m, spin, point, s);
      return s;
    }
  }
  std::ostringstream os;
  os << "modes: the steady rotation at |Ω| = " << spin.norm() << " rad/s did not converge in " << kMaxIterations
     << " Newton iterations (last correction " << step << " against a model size " << size << " m)";
  throw SolverError(os.str());
}

MechanicalState displaced_state(const Model& model, const MechanicalState& state, const Mode& mode, double amplitude,
                                double phase) {
  MechanicalState out = state;
  const Eigen::VectorXd dx = amplitude * (mode.shape_re * std::cos(phase) - mode.shape_im * std::sin(phase));
  model.retract(out.q, dx);
  return out;
}

}  // namespace alphaflex
