#include "klu_linear_solver.hpp"

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>
#include <exception>

#include "ancf/core/error.hpp"

namespace ancf::detail {
namespace {

KluLinearSolver& content(SUNLinearSolver s) {
  return *static_cast<KluLinearSolver*>(s->content);
}

SUNLinearSolver_Type get_type(SUNLinearSolver) {
  return SUNLINEARSOLVER_DIRECT;
}
SUNLinearSolver_ID get_id(SUNLinearSolver) {
  return SUNLINEARSOLVER_CUSTOM;
}

// Factorization of A (values in the pattern's CSC order). A singular matrix is an unrecoverable
// failure, as with SUNLinSol_KLU: IDA then stops with IDA_LSETUP_FAIL and the report names the
// singular column (a smaller step would not make a structurally singular system regular).
int setup(SUNLinearSolver s, SUNMatrix a) noexcept {
  KluLinearSolver& c = content(s);
  try {
    if (c.analysed_revision != c.pattern_revision) {
      c.klu.analyze();
      c.analysed_revision = c.pattern_revision;
    }
    c.klu.factor({SUNSparseMatrix_Data(a), static_cast<std::size_t>(c.pattern.nonzeros())});
    ++c.setups;
    c.last_flag = SUNLS_SUCCESS;
  } catch (...) {
    c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  return c.last_flag;
}

int solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, realtype) noexcept {
  KluLinearSolver& c = content(s);
  try {
    const sunindextype n = N_VGetLength(b);
    double* xs = N_VGetArrayPointer(x);
    const double* bs = N_VGetArrayPointer(b);
    if (xs != bs) std::copy(bs, bs + n, xs);
    c.klu.solve({xs, static_cast<std::size_t>(n)});
    c.last_flag = SUNLS_SUCCESS;
  } catch (const SolverError&) {
    c.last_flag = SUNLS_PACKAGE_FAIL_REC;
  } catch (...) {
    c.last_flag = SUNLS_PACKAGE_FAIL_UNREC;
  }
  return c.last_flag;
}

sunindextype last_flag(SUNLinearSolver s) {
  return content(s).last_flag;
}

int free_solver(SUNLinearSolver s) {
  SUNLinSolFreeEmpty(s);  // the content is owned by the integrator
  return SUNLS_SUCCESS;
}

}  // namespace

SUNLinearSolver make_klu_linear_solver(KluLinearSolver& c, SUNContext context) {
  SUNLinearSolver s = SUNLinSolNewEmpty(context);
  if (!s) throw SolverError("SUNDIALS: SUNLinSolNewEmpty returned NULL");
  s->content = &c;
  s->ops->gettype = get_type;
  s->ops->getid = get_id;
  s->ops->setup = setup;
  s->ops->solve = solve;
  s->ops->lastflag = last_flag;
  s->ops->free = free_solver;
  return s;
}

}  // namespace ancf::detail
