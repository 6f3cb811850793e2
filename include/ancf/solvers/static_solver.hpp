// Newton's method with load stepping for StaticProblem (sparse direct solves with KLU).
#pragma once

#include <string>

#include "ancf/core/error.hpp"
#include "ancf/core/klu_solver.hpp"
#include "ancf/core/static_problem.hpp"

namespace ancf {

struct StaticSolverOptions {
  int load_steps = 1;       ///< equal load increments from s = 0 to s = 1
  int max_iterations = 30;  ///< Newton iterations per load step
  int max_step_cuts = 10;   ///< times a failed load increment may be halved
  /// Converged when ‖Δq‖∞ ≤ increment_tolerance·max(1, ‖q‖∞) (q in model units) and the
  /// residual is finite. Newton converges quadratically, so the default leaves q at round-off.
  double increment_tolerance = 1e-11;
  /// The tangent is numerically singular when the smallest singular value estimate of the
  /// equilibrated Jacobian (singularity_estimate.hpp) is below this. An exactly singular tangent
  /// (a mechanism, a slack cable, a curved cable's zero modes) computes to 1e-17 … 1e-15 in the
  /// tests; regular problems of the test suite stay above 3e-10.
  double singular_tolerance = 1e-13;
  /// A singular tangent with a residual that has more than this fraction on its null direction
  /// (|wᵀr|/‖r‖, equilibrated) is inconsistent: no equilibrium near the current state, the load
  /// drives a zero-stiffness motion. Consistent singular systems give round-off (≲ 1e-12).
  double inconsistency_tolerance = 1e-6;
};

struct StaticSolverStatistics {
  int load_steps = 0;         ///< load increments taken (after cuts)
  int step_cuts = 0;          ///< failed increments that were halved
  int newton_iterations = 0;  ///< total linear solves
  int full_factorizations = 0;
  int refactorizations = 0;
  double wall_seconds = 0.0;
  /// Smallest singular value estimate of the equilibrated tangent at the solution.
  double smallest_singular_value = 0.0;
  /// Non-empty when that tangent is singular (the equilibrium is not isolated: zero-stiffness
  /// motions the loads do not drive): the unknowns the near-null direction moves most.
  std::string singular_direction;
  /// ∞-norm of R(y, 1) at the solution (coordinate rows [N], constraint rows [m or -]).
  double residual_norm = 0.0;
};

/// Owns the KLU analysis of problem.jacobian_pattern(), done once in the constructor.
/// Ownership: keeps a reference to `problem`, which must outlive the solver.
class StaticSolver {
 public:
  explicit StaticSolver(StaticProblem& problem, StaticSolverOptions options = {});

  /// Solve R(y, 1) = 0 starting from y (in/out), stepping the load factor 0 → 1.
  /// Throws SolverError with the load factor, iteration and the worst residual row (named by
  /// the problem) if a load step cannot be completed; y then holds the last converged state.
  /// A singular tangent at the start of an increment whose residual acts on its null direction
  /// (no equilibrium nearby: cutting the load would not help) is reported at once, naming the
  /// unknowns of that direction, instead of cutting.
  StaticSolverStatistics solve(VecX& y);

  /// Newton at a fixed load factor. Returns the iteration count; throws SolverError on failure
  /// (y is left at the last iterate).
  int newton(VecX& y, double load_factor);

 private:
  [[nodiscard]] std::string worst_residual(double load_factor) const;
  /// The unknowns the unit vector `direction` (equilibrated) moves most, named by the problem.
  [[nodiscard]] std::string describe_direction(const VecX& direction) const;
  StaticProblem& problem_;
  StaticSolverOptions options_;
  KluSolver klu_;
  VecX residual_, values_;
  int iterations_ = 0;
  double last_singular_value_ = 0.0;  // of the last factorization checked
  std::string last_singular_direction_;
};

/// Thrown when the solve cannot succeed for a structural reason (singular tangent with the load on
/// its null direction; a zero pivot at a converged state): cutting the load does not help.
class SingularStaticProblem : public SolverError {
 public:
  using SolverError::SolverError;
};

}  // namespace ancf
