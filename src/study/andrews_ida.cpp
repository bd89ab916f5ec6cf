#include "alphaflex/study/andrews_ida.hpp"

#include <ida/ida.h>
#include <ida/ida_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "alphaflex/core/autodiff.hpp"  // Eigen/Dense, then Eigen's AutoDiff module

#include <sstream>

#include "alphaflex/study/cpu_time.hpp"
#include "andrews_relative.hpp"

namespace alphaflex::study {
namespace {

using namespace andrews;

// Unknowns y = (q, v, λ, μ): 7 + 7 + 6 + 6.
constexpr int kQ = 0, kV = 7, kL = 14, kMu = 20, kN = 26;
constexpr double kAlgebraicAtol = 1e3;  // N for λ (the forces are ~1e2 N), and the same for μ

// F(t, y, y') of the GGL form (header): q' − v + Gᵀμ, M v' − f + Gᵀλ, g, G v.
int residual(realtype /*t*/, N_Vector yy, N_Vector yp, N_Vector rr, void* /*user*/) {
  const double* y = N_VGetArrayPointer(yy);
  const double* dy = N_VGetArrayPointer(yp);
  double* r = N_VGetArrayPointer(rr);
  const Eigen::Map<const Vec7> q(y + kQ), v(y + kV), qp(dy + kQ), vp(dy + kV);
  const Eigen::Map<const Vec6> lambda(y + kL), mu(y + kMu);
  Mat7 M;
  Vec7 f;
  Vec6 g, c;
  Mat67 G;
  mass_force<double>(q, v, M, f);
  constraints<double>(q, v, g, G, c);
  Eigen::Map<Vec7>(r + kQ) = qp - v + G.transpose() * mu;
  Eigen::Map<Vec7>(r + kV) = M * vp - f + G.transpose() * lambda;
  Eigen::Map<Vec6>(r + kL) = g;
  Eigen::Map<Vec6>(r + kMu) = G * v;
  return 0;
}

// The exact iteration matrix J = ∂F/∂y + c_j ∂F/∂y' (IDA's difference quotients fail to converge
// at rtol ≤ 1e-6: the index-2 corrector is ill-conditioned at small steps). F is linear in q', v',
// λ and μ; the derivatives in q and v come from forward AD over those 14 variables.
using AD = Eigen::AutoDiffScalar<Eigen::Matrix<double, 14, 1>>;

int jacobian(realtype /*t*/, realtype cj, N_Vector yy, N_Vector yp, N_Vector /*rr*/, SUNMatrix J, void* /*user*/,
             N_Vector, N_Vector, N_Vector) {
  const double* y = N_VGetArrayPointer(yy);
  const double* dy = N_VGetArrayPointer(yp);
  V7<AD> q, v;
  for (int k = 0; k < 7; ++k) {
    q[k] = AD(y[kQ + k], 14, k);
    v[k] = AD(y[kV + k], 14, 7 + k);
  }
  Eigen::Matrix<AD, 7, 7> M;
  V7<AD> f;
  V6<AD> g, c;
  Eigen::Matrix<AD, 6, 7> G;
  mass_force<AD>(q, v, M, f);
  constraints<AD>(q, v, g, G, c);
  const Eigen::Map<const Vec7> vp(dy + kV);
  const Eigen::Map<const Vec6> lambda(y + kL), mu(y + kMu);
  Eigen::Matrix<double, kN, kN> A = Eigen::Matrix<double, kN, kN>::Zero();
  for (int i = 0; i < 7; ++i) {
    AD rq(0.0), rv(0.0);
    for (int j = 0; j < 6; ++j) rq += G(j, i) * mu[j];  // (Gᵀμ)_i
    for (int j = 0; j < 7; ++j) rv += M(i, j) * vp[j];
    rv -= f[i];
    for (int j = 0; j < 6; ++j) rv += G(j, i) * lambda[j];
    A.block<1, 14>(kQ + i, 0) = rq.derivatives().transpose();
    A(kQ + i, kV + i) -= 1.0;
    A(kQ + i, kQ + i) += cj;
    A.block<1, 14>(kV + i, 0) = rv.derivatives().transpose();
    for (int j = 0; j < 7; ++j) A(kV + i, kV + j) += cj * M(i, j).value();
  }
  for (int i = 0; i < 6; ++i) {
    AD gv(0.0);
    for (int j = 0; j < 7; ++j) {
      gv += G(i, j) * v[j];
      A(kQ + j, kMu + i) = G(i, j).value();  // ∂(Gᵀμ)/∂μ
      A(kV + j, kL + i) = G(i, j).value();   // ∂(Gᵀλ)/∂λ
    }
    A.block<1, 14>(kL + i, 0) = g[i].derivatives().transpose();
    A.block<1, 14>(kMu + i, 0) = gv.derivatives().transpose();
  }
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) SM_ELEMENT_D(J, i, j) = A(i, j);
  return 0;
}

void record_error(int /*code*/, const char* module, const char* function, char* msg, void* user) {
  auto* text = static_cast<std::string*>(user);
  *text = std::string(module) + " " + function + ": " + msg;
}

}  // namespace

PeerResult andrews_ida(double rtol, double atol, double t_end) {
  PeerResult res;
  res.method = "IDA (GGL index 2)";
  res.rtol = rtol;
  res.atol = atol;
  const double cpu0 = process_cpu_seconds();

  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0) {
    res.failure = "SUNContext_Create failed";
    return res;
  }
  N_Vector y = N_VNew_Serial(kN, ctx), yp = N_VNew_Serial(kN, ctx), id = N_VNew_Serial(kN, ctx),
           atolv = N_VNew_Serial(kN, ctx);
  SUNMatrix A = SUNDenseMatrix(kN, kN, ctx);
  SUNLinearSolver LS = SUNLinSol_Dense(y, A, ctx);
  void* mem = IDACreate(ctx);
  std::string message;

  // Consistent start (andrews.md §1.4): at rest, q'' and λ from the index-1 system, μ = 0.
  const Vec7 q0 = initial_angles(), v0 = Vec7::Zero();
  Vec7 qdd0;
  Vec6 lambda0;
  accelerations(q0, v0, qdd0, lambda0);
  N_VConst(0.0, y);
  N_VConst(0.0, yp);
  double* y0 = N_VGetArrayPointer(y);
  double* yp0 = N_VGetArrayPointer(yp);
  Eigen::Map<Vec7>(y0 + kQ) = q0;
  Eigen::Map<Vec6>(y0 + kL) = lambda0;
  Eigen::Map<Vec7>(yp0 + kV) = qdd0;
  double* idv = N_VGetArrayPointer(id);
  for (int i = 0; i < kN; ++i) idv[i] = i < kL ? 1.0 : 0.0;  // q, v differential; λ, μ algebraic

  int flag = 0;
  auto check = [&](int f, const char* what) {
    if (f < 0 && flag >= 0) {
      flag = f;
      std::ostringstream os;
      os << what << " returned " << f << (message.empty() ? "" : " (" + message + ")");
      res.failure = os.str();
    }
  };
  check(IDASetErrHandlerFn(mem, record_error, &message), "IDASetErrHandlerFn");
  check(IDAInit(mem, residual, 0.0, y, yp), "IDAInit");
  // Absolute tolerances: atol for q and v; kAlgebraicAtol for λ and μ, which takes them out of the
  // corrector's convergence test as suppressalg takes them out of the error test. The index-2
  // corrector cannot resolve the multipliers at small steps (its matrix has a condition ~ 1/h²):
  // with atol for all components IDA stalls at t = 0 for rtol = atol ≤ 1e-6 (measured).
  for (int i = 0; i < kN; ++i) N_VGetArrayPointer(atolv)[i] = i < kL ? atol : kAlgebraicAtol;
  check(IDASVtolerances(mem, rtol, atolv), "IDASVtolerances");
  check(IDASetId(mem, id), "IDASetId");
  check(IDASetSuppressAlg(mem, SUNTRUE), "IDASetSuppressAlg");
  check(IDASetLinearSolver(mem, LS, A), "IDASetLinearSolver");
  check(IDASetJacFn(mem, jacobian), "IDASetJacFn");
  check(IDASetMaxNumSteps(mem, 1000000), "IDASetMaxNumSteps");
  double t = 0.0;
  if (flag >= 0) check(IDASolve(mem, t_end, &t, y, yp, IDA_NORMAL), "IDASolve");
  res.ok = flag >= 0;

  long v = 0;
  if (IDAGetNumSteps(mem, &v) == 0) res.steps = v;
  if (IDAGetNumResEvals(mem, &v) == 0) res.residual_evals = v;
  if (IDAGetNumJacEvals(mem, &v) == 0) res.jacobian_evals = v;
  if (IDAGetNumNonlinSolvIters(mem, &v) == 0) res.nonlinear_iterations = v;
  if (IDAGetNumErrTestFails(mem, &v) == 0) res.error_test_failures = v;
  const double* yt = N_VGetArrayPointer(y);
  for (const char* n : {"beta", "Theta", "gamma", "Phi", "delta", "Omega", "epsilon"}) res.names.emplace_back(n);
  for (int i = 1; i <= 6; ++i) res.names.push_back("lambda" + std::to_string(i));
  for (int i = 0; i < 7; ++i) res.values.push_back(yt[kQ + i]);
  for (int i = 0; i < 6; ++i) res.values.push_back(yt[kL + i]);

  IDAFree(&mem);
  SUNLinSolFree(LS);
  SUNMatDestroy(A);
  N_VDestroy(atolv);
  N_VDestroy(id);
  N_VDestroy(yp);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  res.cpu = process_cpu_seconds() - cpu0;
  return res;
}

}  // namespace alphaflex::study
