#include "alphaflex/assembly/saddle_point_system.hpp"

#include <set>
#include <string>

#include "alphaflex/core/error.hpp"
#include "alphaflex/core/fault_injection.hpp"

namespace alphaflex {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

PetscErrorCode add_block(Mat S, const std::vector<int>& rows, const std::vector<int>& cols, const RowMajor& block) {
  PetscFunctionBeginUser;
  PetscCall(MatSetValues(S, static_cast<PetscInt>(rows.size()), rows.data(), static_cast<PetscInt>(cols.size()),
                         cols.data(), block.data(), ADD_VALUES));
  PetscFunctionReturn(0);
}

/// A ← A·T(x) on the columns of each Lie-group node of `nodes` (x: the step increment).
void apply_tangent_operator(const Model& m, const std::vector<int>& nodes, const Eigen::VectorXd& x,
                            Eigen::MatrixXd& A) {
  int off = 0;
  for (int n : nodes) {
    const Node& nd = m.node(n);
    if (is_lie_group(nd.kind)) {
      const Eigen::MatrixXd T = tangent_operator(nd.kind, x.data() + nd.first_dof);
      A.middleCols(off, nd.ndof) = A.middleCols(off, nd.ndof) * T;
    }
    off += nd.ndof;
  }
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
  PetscCallAbort(comm_, preallocate());
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

PetscErrorCode SaddlePointSystem::assemble(const MechanicalState& s, const AssemblyCoefficients& c,
                                           ConstraintRows rows, bool matrix) {
  PetscFunctionBeginUser;
  PetscCall(VecSet(r_, 0.0));
  if (matrix) PetscCall(MatZeroEntries(S_));

  // An element or joint may throw on the rank that owns it (e.g. a spring of zero length). The
  // other ranks would then wait in the assembly below: agree on failure first, then all throw.
  std::string local_error;
  bool configuration = false;  // a ConfigurationError: keeps its type on every rank
  try {
    // Tests of error handling: one rank adds nothing, which leaves rows of the matrix zero.
    if (!(matrix && fault_injected("singular"))) PetscCall(add_local_contributions(s, c, rows, matrix));
  } catch (const ConfigurationError& e) {
    local_error = e.what();
    configuration = true;
  } catch (const std::exception& e) {
    local_error = e.what();
  }
  PetscCall(raise_if_any_rank_failed(local_error, configuration));
  if (matrix) {
    PetscCall(MatAssemblyBegin(S_, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(S_, MAT_FINAL_ASSEMBLY));
  }
  PetscCall(VecAssemblyBegin(r_));
  PetscCall(VecAssemblyEnd(r_));
  PetscFunctionReturn(0);
}

PetscErrorCode SaddlePointSystem::raise_if_any_rank_failed(const std::string& local_error, bool configuration) {
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
  int kind = configuration ? 1 : 0;
  PetscCallMPI(MPI_Bcast(&kind, 1, MPI_INT, first, comm_));
  if (kind) throw ConfigurationError(msg);
  throw SolverError(msg);
}

PetscErrorCode SaddlePointSystem::add_local_contributions(const MechanicalState& s, const AssemblyCoefficients& c,
                                                          ConstraintRows rows, bool matrix) {
  PetscFunctionBeginUser;
  const bool elements_in = rows == ConstraintRows::Acceleration || rows == ConstraintRows::Dynamic;
  const double sc = c.row_scale;
  LocalState ls;
  LocalResidual lr;
  for (size_t e = 0; e < model_.elements().size(); ++e) {
    const auto& idx = elem_dofs_[e];
    const auto& g = elem_rows_[e];
    const int n = static_cast<int>(idx.size());
    // Element tangents are also needed without the element residuals when the matrix weights the
    // projection rows by the mass (mass-weighted velocity projection of the consistent start).
    const bool tangents_only = !elements_in && matrix && c.mass != 0.0;
    if (elements_in || tangents_only) {
      ls.q = gather(s.q, elem_confs_[e]);
      ls.v = gather(s.v, idx);
      ls.qdd = gather(s.qdd, idx);
      ls.t = s.t;
      ls.load_factor = c.load_factor;
      lr.reset(n, matrix);
      model_.elements()[e]->evaluate(ls, lr, matrix);
      if (matrix && c.increment) apply_tangent_operator(model_, model_.elements()[e]->nodes(), *c.increment, lr.K);
      if (elements_in) {
        const Eigen::VectorXd re = sc * lr.r;
        PetscCall(VecSetValues(r_, n, g.data(), re.data(), ADD_VALUES));
      }
    }
    if (matrix) {
      // The pattern must hold every entry from the first assembly on, even with zero values.
      const RowMajor block = elements_in     ? RowMajor(sc * (c.mass * lr.M + c.damping * lr.C + c.stiffness * lr.K))
                             : tangents_only ? RowMajor(sc * c.mass * lr.M)
                                             : RowMajor::Zero(n, n);
      PetscCall(add_block(S_, g, g, block));
    }
  }

  Eigen::VectorXd phi, extra;
  Eigen::MatrixXd phi_q, kc;
  for (size_t k = 0; k < model_.constraints().size(); ++k) {
    const Constraint& con = *model_.constraints()[k];
    const auto& idx = con_dofs_[k];
    const int n = static_cast<int>(idx.size()), m = con.size();
    const Eigen::VectorXd q = gather(s.q, con_confs_[k]);
    const Eigen::VectorXd lam = s.lambda.segment(model_.first_multiplier(static_cast<int>(k)), m);
    con.evaluate(q, s.t, phi, phi_q);

    Eigen::VectorXd rc;  // multiplier rows
    switch (rows) {
      case ConstraintRows::Position:
      case ConstraintRows::Dynamic: rc = phi; break;
      case ConstraintRows::Velocity:
        con.time_derivative(q, s.t, extra);
        rc = phi_q * gather(s.v, idx) + extra;
        break;
      case ConstraintRows::Acceleration:
        con.acceleration_term(q, gather(s.v, idx), s.t, extra);
        rc = phi_q * gather(s.qdd, idx) + extra;
        break;
    }
    PetscCall(VecSetValues(r_, m, con_mults_[k].data(), rc.data(), ADD_VALUES));
    if (elements_in) {
      const Eigen::VectorXd rq = sc * phi_q.transpose() * lam;
      PetscCall(VecSetValues(r_, n, con_rows_[k].data(), rq.data(), ADD_VALUES));
    }
    if (matrix) {
      RowMajor kblock = RowMajor::Zero(n, n);
      if (c.stiffness != 0.0 && elements_in) {
        con.geometric_stiffness(q, s.t, lam, kc);
        if (c.increment) apply_tangent_operator(model_, con.nodes(), *c.increment, kc);
        kblock = sc * c.stiffness * kc;
      }
      PetscCall(add_block(S_, con_rows_[k], con_rows_[k], kblock));
      // ∂(Φ_qᵀλ)/∂λ = Φ_qᵀ; but ∂Φ(q_n ∘ exp(x))/∂x = Φ_q T(x) in the multiplier rows.
      const RowMajor bt = sc * c.multiplier_scale * phi_q.transpose();
      PetscCall(add_block(S_, con_rows_[k], con_mults_[k], bt));
      if (c.increment && rows == ConstraintRows::Dynamic) apply_tangent_operator(model_, con.nodes(), *c.increment, phi_q);
      const RowMajor b = phi_q;
      PetscCall(add_block(S_, con_mults_[k], con_rows_[k], b));
      // Explicit zeros on the multiplier diagonal keep it in the pattern (some factorizations want it).
      for (int g : con_mults_[k]) PetscCall(MatSetValue(S_, g, g, 0.0, ADD_VALUES));
    }
  }

  if (matrix) {
    // Diagonal of every owned node unknown: c_I (projections) or an explicit zero (pattern).
    for (int i = 0; i < sub_.num_owned_dofs(); ++i) {
      const PetscInt g = sub_.dof_indices()[static_cast<size_t>(i)];
      PetscCall(MatSetValue(S_, g, g, sc * c.identity, ADD_VALUES));
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
