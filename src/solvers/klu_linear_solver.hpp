// Internal to the solvers layer: the project's KluSolver as a SUNDIALS linear solver, so that IDA
// factorizes its Jacobian the way generalized-α does (refactorization in the first pivot order,
// guarded by KLU's pivot-growth estimate) and the analysis follows a changing pattern.
//
// Why not SUNDIALS' own SUNLinSol_KLU: after every refactorization it estimates the condition
// number (klu_condest) and, above 1/ε^(2/3) ≈ 3e10, discards the factorization and factorizes
// again with fresh pivoting. The GGL Jacobian of a stiff rope scene (c_j ~ 1e4 1/s, EA/l ~ 3e7 N,
// identity blocks) is always that ill-conditioned in this sense, so every setup cost a
// refactorization, a condition estimate and a full factorization (capture scene: klu_l_kernel 31 %
// and klu_l_refactor 14 % of the run). Pivot growth, not the condition number, tells whether an
// old pivot order is still stable (Davis, KLU user guide: klu_rgrowth).
#pragma once

#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>

#include "ancf/core/klu_solver.hpp"

namespace ancf::detail {

/// Content of the SUNLinearSolver made by make_klu_linear_solver. The pattern is the problem's
/// Jacobian pattern (updated in place by DaeProblem::update_jacobian_pattern); bump
/// pattern_revision after a change, and the next setup re-runs the symbolic analysis.
struct KluLinearSolver {
  explicit KluLinearSolver(const SparsityPattern& p) : pattern(p), klu(p) {}
  const SparsityPattern& pattern;
  KluSolver klu;
  long pattern_revision = 0, analysed_revision = 0;
  long setups = 0;
  int last_flag = 0;
};

/// A SUNLinearSolver (type DIRECT) whose content is `content` (not owned; must outlive it). Free
/// it with SUNLinSolFree.
SUNLinearSolver make_klu_linear_solver(KluLinearSolver& content, SUNContext context);

}  // namespace ancf::detail
