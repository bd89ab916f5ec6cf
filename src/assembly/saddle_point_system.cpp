#include "alphaflex/assembly/saddle_point_system.hpp"

#include <algorithm>
#include <cmath>
#include <new>
#include <sstream>
#include <set>
#include <stdexcept>
#include <string>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/rotation.hpp"
#include "alphaflex/core/fault_injection.hpp"
#include "alphaflex/core/memory.hpp"
#include "alphaflex/core/petsc_error.hpp"

namespace alphaflex {
namespace {

/// out = global[idx] (storage reused when the size is unchanged: no allocation per element).
void gather_to(const Eigen::VectorXd& global, const std::vector<int>& idx, Eigen::VectorXd& out) {
  out.resize(static_cast<Eigen::Index>(idx.size()));
  for (size_t i = 0; i < idx.size(); ++i) out[static_cast<Eigen::Index>(i)] = global[idx[i]];
}

/// A ← A·T(x) on the columns of each Lie-group node of `nodes` (x: the step increment).
void apply_tangent_operator(const Model& m, const std::vector<int>& nodes, const Eigen::VectorXd& x,
                            Eigen::MatrixXd& A) {
  int off = 0;
  for (int n : nodes) {
    const Node& nd = m.node(n);
    if (nd.kind == NodeKind::Frame3D) {
      // T = diag(I, T_SO(3)(θ)): only the three rotation columns change (fixed-size, no allocation).
      const double* xr = x.data() + nd.first_dof + 3;
      const Eigen::Matrix3d T = tangent_so3<double>(Eigen::Vector3d(xr[0], xr[1], xr[2]));
      for (Eigen::Index r = 0; r < A.rows(); ++r) {
        const Eigen::RowVector3d a = A.block<1, 3>(r, off + 3);
        A.block<1, 3>(r, off + 3).noalias() = a * T;
      }
    } else if (is_lie_group(nd.kind)) {
      const Eigen::MatrixXd T = tangent_operator(nd.kind, x.data() + nd.first_dof);
      A.middleCols(off, nd.ndof) = A.middleCols(off, nd.ndof) * T;
    }
    off += nd.ndof;
  }
}

/// The message of a std::bad_alloc on this rank of `comm` (its size is not known).
std::string out_of_memory_here(MPI_Comm comm, const std::string& what) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  return out_of_memory_message(what, 0.0, rank);
}

}  // namespace

SaddlePointSystem::SaddlePointSystem(const Subdomain& subdomain)
    : sub_(subdomain), model_(subdomain.model()), comm_(subdomain.comm()) {
  const auto& pet = sub_.dof_indices();
  for (const auto& e : model_.elements()) {
    elem_dofs_.push_back(model_.dofs_of(e->nodes()));
    elem_confs_.push_back(model_.confs_of(e->nodes()));
    std::vector<int> rows;
    for (int d : elem_dofs_.back()) rows.push_back(pet[static_cast<size_t>(d)]);
    elem_rows_.push_back(rows);
  }
  for (size_t c = 0; c < model_.constraints().size(); ++c) {
    const auto& con = model_.constraints()[c];
    con_dofs_.push_back(model_.dofs_of(con->nodes()));
    con_confs_.push_back(model_.confs_of(con->nodes()));
    std::vector<int> rows, mults;
    for (int d : con_dofs_.back()) rows.push_back(pet[static_cast<size_t>(d)]);
    const int first = model_.first_multiplier(static_cast<int>(c));
    for (int k = 0; k < con->size(); ++k) mults.push_back(sub_.multiplier_indices()[static_cast<size_t>(first + k)]);
    con_rows_.push_back(rows);
    con_mults_.push_back(mults);
  }
  // Memory exhaustion (issue 24, defect 3). PETSc's hash table of the pattern (MATPREALLOCATOR)
  // cannot report a failed allocation in an optimized build (khash's resize returns −1 and
  // PetscHashAssert is compiled out): it drops the entry and tries to grow again at the next one,
  // which under an address-space limit never ends. So the room is checked first, on every rank
  // together; a PETSc allocation that fails later is reported without PETSc's trace, and the ranks
  // agree on the outcome before anything else collective.
  std::ostringstream what;
  what << "preallocating the iteration matrix (" << sub_.dof_map().global_size() << " unknowns, "
       << sub_.dof_map().local_size() << " on this rank)";
  require_address_space(comm_, preallocation_bytes(), what.str());
  std::string error;
  FailureKind kind = FailureKind::Solver;
  try {
    const QuietPetscErrors quiet;
    quiet.check(preallocate(), what.str().c_str());
  } catch (const MemoryError& e) {
    error = e.what();
    kind = FailureKind::Memory;
  } catch (const std::bad_alloc&) {
    error = out_of_memory_here(comm_, what.str());
    kind = FailureKind::Memory;
  } catch (const std::exception& e) {
    error = e.what();
  }
  check_petsc(raise_if_any_rank_failed(error, kind), "the agreement on the preallocation");
  // The matrix's CSR arrays (a value and a column index per entry allocated, MatGetInfo), the row
  // and column indices MUMPS receives (two 32-bit integers per entry: PETSc's triples, whose values
  // are the matrix's own) and the assembly's entry maps (one PetscInt per block entry).
  MatInfo info;
  check_petsc(MatGetInfo(S_, MAT_LOCAL, &info), "MatGetInfo");
  double bytes = info.nz_allocated * (sizeof(PetscScalar) + sizeof(PetscInt) + 8.0);
  for (const auto* list : {&elem_pos_, &con_qq_pos_, &con_ql_pos_, &con_lq_pos_, &con_ll_pos_})
    for (const auto& v : *list) bytes += static_cast<double>(v.size()) * sizeof(PetscInt);
  matrix_mb_ = bytes / 1048576.0;
}

double SaddlePointSystem::preallocation_bytes() const {
  // Every block entry counted once per block (an upper bound of the distinct entries: blocks of
  // neighbouring elements share their node's diagonal blocks).
  double entries = static_cast<double>(sub_.num_owned_dofs());
  for (const auto& rows : elem_rows_) entries += static_cast<double>(rows.size() * rows.size());
  for (size_t c = 0; c < con_rows_.size(); ++c)
    entries += static_cast<double>(con_rows_[c].size() * (con_rows_[c].size() + 2 * con_mults_[c].size()) + con_mults_[c].size());
  // khash (PETSc's PetscHSetIJ): buckets a power of 2 at most 77 % full, a key of two PetscInt,
  // old and new tables both alive while it grows; then the AIJ matrix (a value and a column index
  // per entry) and the entry maps (one PetscInt per block entry).
  const double buckets = std::exp2(std::ceil(std::log2(std::max(entries / 0.77, 16.0))));
  const double hash = 1.5 * buckets * (2.0 * sizeof(PetscInt) + 0.25);
  return hash + entries * (sizeof(PetscScalar) + 2.0 * sizeof(PetscInt));
}

SaddlePointSystem::~SaddlePointSystem() {
  VecScatterDestroy(&to_local_);
  VecDestroy(&local_);
  VecDestroy(&x_);
  VecDestroy(&r_);
  MatDestroy(&S_);
}

PetscErrorCode SaddlePointSystem::preallocate() {
  PetscFunctionBeginUser;
  const DofMap& map = sub_.dof_map();
  const PetscInt n = map.global_size(), nlocal = map.local_size();
  // The exact pattern, off-rank rows included (a ghost node's rows get entries from this rank's
  // elements and belong to its owner): insert every block once into a MATPREALLOCATOR, which
  // communicates the off-rank rows at assembly and then preallocates S exactly.
  Mat pre;
  PetscCall(MatCreate(comm_, &pre));
  PetscCall(MatSetType(pre, MATPREALLOCATOR));
  PetscCall(MatSetSizes(pre, nlocal, nlocal, n, n));
  PetscCall(MatSetUp(pre));
  std::vector<PetscScalar> zeros;
  auto block = [&](const std::vector<int>& rows, const std::vector<int>& cols) -> PetscErrorCode {
    PetscFunctionBeginUser;
    zeros.assign(rows.size() * cols.size(), 0.0);
    PetscCall(MatSetValues(pre, static_cast<PetscInt>(rows.size()), rows.data(), static_cast<PetscInt>(cols.size()),
                           cols.data(), zeros.data(), INSERT_VALUES));
    PetscFunctionReturn(0);
  };
  for (const auto& rows : elem_rows_) PetscCall(block(rows, rows));
  for (size_t c = 0; c < con_rows_.size(); ++c) {
    PetscCall(block(con_rows_[c], con_rows_[c]));
    PetscCall(block(con_rows_[c], con_mults_[c]));
    PetscCall(block(con_mults_[c], con_rows_[c]));
    for (int g : con_mults_[c]) PetscCall(block({g}, {g}));
  }
  // The diagonal of every owned node coordinate (c_I of the projections, or an explicit zero).
  for (int i = 0; i < sub_.num_owned_dofs(); ++i) {
    const int g = sub_.dof_indices()[static_cast<size_t>(i)];
    PetscCall(block({g}, {g}));
  }
  PetscCall(MatAssemblyBegin(pre, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(pre, MAT_FINAL_ASSEMBLY));

  PetscCall(MatCreate(comm_, &S_));
  PetscCall(MatSetSizes(S_, nlocal, nlocal, n, n));
  // MATAIJ on purpose (sequential or MPI by communicator): MUMPS takes it directly, and its
  // preallocation is the one MATPREALLOCATOR fills. The type is not left to the options database.
  PetscCall(MatSetType(S_, MATAIJ));
  PetscCall(MatPreallocatorPreallocate(pre, PETSC_TRUE, S_));
  PetscCall(MatDestroy(&pre));
  PetscCall(MatSetOption(S_, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatCreateVecs(S_, &x_, &r_));
  PetscCall(build_entry_maps());

  // Owned and ghost unknowns of this rank, in local order: one scatter brings a solution back.
  std::vector<PetscInt> from(sub_.dof_indices().begin(), sub_.dof_indices().end());
  from.insert(from.end(), sub_.multiplier_indices().begin(), sub_.multiplier_indices().end());
  IS is;
  PetscCall(ISCreateGeneral(PETSC_COMM_SELF, static_cast<PetscInt>(from.size()), from.data(), PETSC_COPY_VALUES, &is));
  PetscCall(VecCreateSeq(PETSC_COMM_SELF, static_cast<PetscInt>(from.size()), &local_));
  PetscCall(VecScatterCreate(x_, is, local_, nullptr, &to_local_));
  PetscCall(ISDestroy(&is));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::build_entry_maps() {
  PetscFunctionBeginUser;
  // MatPreallocatorPreallocate(fill = true) left S assembled with its final pattern (zeros).
  PetscBool assembled = PETSC_FALSE;
  PetscCall(MatAssembled(S_, &assembled));
  if (!assembled) {
    PetscCall(MatAssemblyBegin(S_, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(S_, MAT_FINAL_ASSEMBLY));
  }
  PetscBool seq = PETSC_FALSE;
  PetscCall(PetscObjectBaseTypeCompare(reinterpret_cast<PetscObject>(S_), MATSEQAIJ, &seq));
  const PetscInt* garray = nullptr;
  if (seq) {
    diag_ = S_;
    offdiag_ = nullptr;
  } else {
    PetscCall(MatMPIAIJGetSeqAIJ(S_, &diag_, &offdiag_, &garray));
  }
  PetscInt rstart = 0, rend = 0, cstart = 0, cend = 0, n_garray = 0;
  PetscCall(MatGetOwnershipRange(S_, &rstart, &rend));
  PetscCall(MatGetOwnershipRangeColumn(S_, &cstart, &cend));
  const PetscInt *dia = nullptr, *dja = nullptr, *oia = nullptr, *oja = nullptr;
  PetscInt nrows = 0;
  PetscBool done = PETSC_FALSE;
  PetscCall(MatGetRowIJ(diag_, 0, PETSC_FALSE, PETSC_FALSE, &nrows, &dia, &dja, &done));
  PetscCheck(done, comm_, PETSC_ERR_PLIB, "no CSR structure of the diagonal part");
  if (offdiag_) {
    PetscCall(MatGetRowIJ(offdiag_, 0, PETSC_FALSE, PETSC_FALSE, &nrows, &oia, &oja, &done));
    PetscCheck(done, comm_, PETSC_ERR_PLIB, "no CSR structure of the off-diagonal part");
    PetscCall(MatGetSize(offdiag_, nullptr, &n_garray));
  }
  // Columns are sorted within each CSR row, and the off-diagonal part numbers its columns in the
  // increasing order of their global indices (garray): two binary searches per entry, once.
  auto find = [](const PetscInt* begin, const PetscInt* end, PetscInt col) -> const PetscInt* {
    const PetscInt* f = std::lower_bound(begin, end, col);
    return (f != end && *f == col) ? f : nullptr;
  };
  auto position = [&](PetscInt row, PetscInt col) -> PetscInt {
    if (row < rstart || row >= rend) return -1;
    const PetscInt r = row - rstart;
    const PetscInt* f = nullptr;
    if (col >= cstart && col < cend) {
      f = find(dja + dia[r], dja + dia[r + 1], col - cstart);
      if (f) return static_cast<PetscInt>(f - dja);
    } else if (offdiag_) {
      const PetscInt* g = find(garray, garray + n_garray, col);
      if (g) f = find(oja + oia[r], oja + oia[r + 1], static_cast<PetscInt>(g - garray));
      if (f) return -2 - static_cast<PetscInt>(f - oja);
    }
    throw std::logic_error("SaddlePointSystem: entry (" + std::to_string(row) + ", " + std::to_string(col) +
                           ") is not in the preallocated pattern");
  };
  auto block = [&](const std::vector<int>& rows, const std::vector<int>& cols) {
    std::vector<PetscInt> pos;
    pos.reserve(rows.size() * cols.size());
    for (int r : rows)
      for (int c : cols) pos.push_back(position(r, c));
    return pos;
  };
  for (const auto& rows : elem_rows_) elem_pos_.push_back(block(rows, rows));
  for (size_t c = 0; c < con_rows_.size(); ++c) {
    con_qq_pos_.push_back(block(con_rows_[c], con_rows_[c]));
    con_ql_pos_.push_back(block(con_rows_[c], con_mults_[c]));
    con_lq_pos_.push_back(block(con_mults_[c], con_rows_[c]));
    std::vector<PetscInt> diag;
    for (int g : con_mults_[c]) diag.push_back(position(g, g));
    con_ll_pos_.push_back(diag);
  }
  for (int i = 0; i < sub_.num_owned_dofs(); ++i) {
    const int g = sub_.dof_indices()[static_cast<size_t>(i)];
    dof_diag_pos_.push_back(position(g, g));
  }
  PetscCall(MatRestoreRowIJ(diag_, 0, PETSC_FALSE, PETSC_FALSE, &nrows, &dia, &dja, &done));
  if (offdiag_) PetscCall(MatRestoreRowIJ(offdiag_, 0, PETSC_FALSE, PETSC_FALSE, &nrows, &oia, &oja, &done));
  PetscFunctionReturn(0);
}

template <class Value>
PetscErrorCode SaddlePointSystem::add_mapped(const std::vector<PetscInt>& pos, const std::vector<int>& rows,
                                             const std::vector<int>& cols, const Value& value) {
  PetscFunctionBeginUser;
  const size_t m = cols.size();
  for (size_t i = 0; i < rows.size(); ++i) {
    const PetscInt* p = pos.data() + i * m;
    const Eigen::Index ii = static_cast<Eigen::Index>(i);
    if (m > 0 && p[0] == -1) {  // a ghost node's row: to its owner through the stash
      row_buffer_.resize(m);
      for (size_t j = 0; j < m; ++j) row_buffer_[j] = value(ii, static_cast<Eigen::Index>(j));
      PetscCall(MatSetValues(S_, 1, &rows[i], static_cast<PetscInt>(m), cols.data(), row_buffer_.data(), ADD_VALUES));
      continue;
    }
    for (size_t j = 0; j < m; ++j) {
      const double v = value(ii, static_cast<Eigen::Index>(j));
      if (p[j] >= 0) d_a_[p[j]] += v;
      else o_a_[-2 - p[j]] += v;
    }
  }
  PetscFunctionReturn(0);
}

template <class Add>
PetscErrorCode SaddlePointSystem::assemble_guarded(bool matrix, const Add& add) {
  PetscFunctionBeginUser;
  PetscCall(VecSet(r_, 0.0));
  if (matrix) PetscCall(MatZeroEntries(S_));

  // An element or joint may throw on the rank that owns it (e.g. a spring of zero length). The
  // other ranks would then wait in the assembly below: agree on failure first, then all throw.
  std::string local_error;
  FailureKind kind = FailureKind::Solver;  // a ConfigurationError or MemoryError keeps its type on every rank
  try {
    if (matrix) {
      PetscCall(MatSeqAIJGetArray(diag_, &d_a_));
      if (offdiag_) PetscCall(MatSeqAIJGetArray(offdiag_, &o_a_));
    }
    PetscCall(add());
  } catch (const ConfigurationError& e) {
    local_error = e.what();
    kind = FailureKind::Configuration;
  } catch (const std::bad_alloc&) {
    local_error = out_of_memory_here(comm_, "assembling the iteration matrix and residual");
    kind = FailureKind::Memory;
  } catch (const std::exception& e) {
    local_error = e.what();
  }
  if (d_a_) PetscCall(MatSeqAIJRestoreArray(diag_, &d_a_));
  if (o_a_) PetscCall(MatSeqAIJRestoreArray(offdiag_, &o_a_));
  d_a_ = o_a_ = nullptr;
  PetscCall(raise_if_any_rank_failed(local_error, kind));
  // The rows other ranks' elements fill arrive here (PETSc's stash): an allocation PETSc cannot
  // make is a MemoryError, without its trace.
  const QuietPetscErrors quiet;
  if (matrix) {
    quiet.check(MatAssemblyBegin(S_, MAT_FINAL_ASSEMBLY), "assembling the iteration matrix (rows from other ranks)");
    quiet.check(MatAssemblyEnd(S_, MAT_FINAL_ASSEMBLY), "assembling the iteration matrix (rows from other ranks)");
  }
  quiet.check(VecAssemblyBegin(r_), "assembling the residual (rows from other ranks)");
  quiet.check(VecAssemblyEnd(r_), "assembling the residual (rows from other ranks)");
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::assemble(const MechanicalState& s, const AssemblyCoefficients& c,
                                           ConstraintRows rows, bool matrix) {
  PetscFunctionBeginUser;
  PetscCall(assemble_guarded(matrix, [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    // Tests of error handling: one rank adds nothing, which leaves rows of the matrix zero.
    if (!(matrix && fault_injected("singular"))) PetscCall(add_local_contributions(s, c, rows, matrix));
    PetscFunctionReturn(0);
  }));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::assemble_mass_action(const MechanicalState& s, const AssemblyCoefficients& c,
                                                       const Eigen::VectorXd& w) {
  PetscFunctionBeginUser;
  PetscCall(assemble_guarded(false, [&]() { return add_mass_action(s, c, w); }));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::add_mass_action(const MechanicalState& s, const AssemblyCoefficients& c,
                                                  const Eigen::VectorXd& w) {
  PetscFunctionBeginUser;
  const double scale = c.row_scale * c.mass;
  LocalState& ls = ls_;
  LocalResidual& lr = lr_;
  for (size_t e = 0; e < model_.elements().size(); ++e) {
    const auto& idx = elem_dofs_[e];
    const int n = static_cast<int>(idx.size());
    const Element& el = *model_.elements()[e];
    gather_to(s.q, elem_confs_[e], ls.q);
    gather_to(s.v, idx, ls.v);
    gather_to(s.qdd, idx, ls.qdd);
    gather_to(w, idx, w_e_);
    ls.t = s.t;
    ls.load_factor = c.load_factor;
    if (el.mass_action(ls, w_e_, mw_e_)) {
      mw_e_ *= scale;
    } else {
      // r(q̈ + c_m w) − r(q̈): the filter's own difference (both residuals as in a step, so that the
      // shift c_m w is of the size of q̈ and the difference keeps its digits).
      lr.reset(n, false);
      el.evaluate(ls, lr, false);
      r_shift_ = lr.r;
      ls.qdd += c.mass * w_e_;
      lr.reset(n, false);
      el.evaluate(ls, lr, false);
      mw_e_ = c.row_scale * (lr.r - r_shift_);
    }
    PetscCall(VecSetValues(r_, n, elem_rows_[e].data(), mw_e_.data(), ADD_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::raise_if_any_rank_failed(const std::string& local_error, FailureKind kind) {
  PetscFunctionBeginUser;
  int rank = 0, size = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  int mine = local_error.empty() ? size : rank, first = size;
  PetscCallMPI(MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm_));
  if (first == size) PetscFunctionReturn(0);
  int len = static_cast<int>(local_error.size());
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, first, comm_));
  std::string msg = local_error;
  msg.resize(static_cast<size_t>(len));
  PetscCallMPI(MPI_Bcast(msg.data(), len, MPI_CHAR, first, comm_));
  int k = static_cast<int>(kind);
  PetscCallMPI(MPI_Bcast(&k, 1, MPI_INT, first, comm_));
  if (k == static_cast<int>(FailureKind::Configuration)) throw ConfigurationError(msg);
  if (k == static_cast<int>(FailureKind::Memory)) throw MemoryError(msg);
  throw SolverError(msg);
}

PetscErrorCode SaddlePointSystem::add_local_contributions(const MechanicalState& s, const AssemblyCoefficients& c,
                                                          ConstraintRows rows, bool matrix) {
  PetscFunctionBeginUser;
  const bool elements_in = rows == ConstraintRows::Acceleration || rows == ConstraintRows::Dynamic;
  const double sc = c.row_scale;
  LocalState& ls = ls_;
  LocalResidual& lr = lr_;
  for (size_t e = 0; e < model_.elements().size(); ++e) {
    const auto& idx = elem_dofs_[e];
    const auto& g = elem_rows_[e];
    const int n = static_cast<int>(idx.size());
    // Element tangents are also needed without the element residuals when the matrix weights the
    // projection rows by the mass (mass-weighted velocity projection of the consistent start).
    const bool tangents_only = !elements_in && matrix && c.mass != 0.0;
    if (!elements_in && !tangents_only) continue;  // nothing of this element in r or S
    gather_to(s.q, elem_confs_[e], ls.q);
    gather_to(s.v, idx, ls.v);
    gather_to(s.qdd, idx, ls.qdd);
    ls.t = s.t;
    ls.load_factor = c.load_factor;
    lr.reset(n, matrix);
    model_.elements()[e]->evaluate(ls, lr, matrix);
    if (matrix && c.increment) apply_tangent_operator(model_, model_.elements()[e]->nodes(), *c.increment, lr.K);
    if (elements_in) {
      lr.r *= sc;
      PetscCall(VecSetValues(r_, n, g.data(), lr.r.data(), ADD_VALUES));
    }
    if (matrix) {
      const double cm = sc * c.mass, cc = elements_in ? sc * c.damping : 0.0, ck = elements_in ? sc * c.stiffness : 0.0;
      const Eigen::MatrixXd &M = lr.M, &C = lr.C, &K = lr.K;
      PetscCall(add_mapped(elem_pos_[e], g, g,
                           [&](Eigen::Index i, Eigen::Index j) { return cm * M(i, j) + cc * C(i, j) + ck * K(i, j); }));
    }
  }

  for (size_t k = 0; k < model_.constraints().size(); ++k) {
    const Constraint& con = *model_.constraints()[k];
    const auto& idx = con_dofs_[k];
    const int n = static_cast<int>(idx.size()), m = con.size();
    gather_to(s.q, con_confs_[k], q_con_);
    lam_con_ = s.lambda.segment(model_.first_multiplier(static_cast<int>(k)), m);
    con.evaluate(q_con_, s.t, phi_, phi_q_);

    switch (rows) {  // multiplier rows
      case ConstraintRows::Position:
      case ConstraintRows::Dynamic: rc_ = phi_; break;
      case ConstraintRows::Velocity:
        con.time_derivative(q_con_, s.t, extra_);
        gather_to(s.v, idx, v_con_);
        rc_.noalias() = phi_q_ * v_con_;
        rc_ += extra_;
        break;
      case ConstraintRows::Acceleration:
        gather_to(s.v, idx, v_con_);
        con.acceleration_term(q_con_, v_con_, s.t, extra_);
        gather_to(s.qdd, idx, v_con_);
        rc_.noalias() = phi_q_ * v_con_;
        rc_ += extra_;
        break;
    }
    PetscCall(VecSetValues(r_, m, con_mults_[k].data(), rc_.data(), ADD_VALUES));
    if (elements_in) {
      rq_.noalias() = sc * phi_q_.transpose() * lam_con_;
      PetscCall(VecSetValues(r_, n, con_rows_[k].data(), rq_.data(), ADD_VALUES));
    }
    if (matrix) {
      // The pattern holds every entry already (preallocation); zero blocks are simply not added.
      if (c.stiffness != 0.0 && elements_in) {
        con.geometric_stiffness(q_con_, s.t, lam_con_, kc_);
        if (c.increment) apply_tangent_operator(model_, con.nodes(), *c.increment, kc_);
        const double ck = sc * c.stiffness;
        PetscCall(add_mapped(con_qq_pos_[k], con_rows_[k], con_rows_[k],
                             [&](Eigen::Index i, Eigen::Index j) { return ck * kc_(i, j); }));
      }
      // ∂(Φ_qᵀλ)/∂λ = Φ_qᵀ; but ∂Φ(q_n ∘ exp(x))/∂x = Φ_q T(x) in the multiplier rows.
      const double cl = sc * c.multiplier_scale;
      PetscCall(add_mapped(con_ql_pos_[k], con_rows_[k], con_mults_[k],
                           [&](Eigen::Index i, Eigen::Index j) { return cl * phi_q_(j, i); }));
      if (c.increment && rows == ConstraintRows::Dynamic) apply_tangent_operator(model_, con.nodes(), *c.increment, phi_q_);
      PetscCall(add_mapped(con_lq_pos_[k], con_mults_[k], con_rows_[k],
                           [&](Eigen::Index i, Eigen::Index j) { return phi_q_(i, j); }));
    }
  }

  if (matrix && c.identity != 0.0) {
    // Diagonal of every owned node unknown: c_I of the projections (in the pattern in any case).
    const double v = sc * c.identity;
    for (PetscInt p : dof_diag_pos_) {
      if (p >= 0) d_a_[p] += v;
      else o_a_[-2 - p] += v;  // (never: a diagonal entry is in the diagonal part)
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::to_model(Vec v, ModelVector& out) {
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(to_local_, v, local_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_local_, v, local_, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* a = nullptr;
  PetscCall(VecGetArrayRead(local_, &a));
  const Eigen::Index nd = model_.num_dofs(), nm = model_.num_multipliers();
  out.dofs = Eigen::Map<const Eigen::VectorXd>(a, nd);
  out.multipliers = Eigen::Map<const Eigen::VectorXd>(a + nd, nm);
  PetscCall(VecRestoreArrayRead(local_, &a));
  PetscFunctionReturn(0);
}

}  // namespace alphaflex
