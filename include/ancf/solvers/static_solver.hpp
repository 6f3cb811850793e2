// Newton's method with load stepping for StaticProblem (sparse direct solves with KLU).
#pragma once

#include <string>

#include "ancf/core/klu_solver.hpp"
#include "ancf/core/static_problem.hpp"

namespace ancf {

struct StaticSolverOptions {
  int load_steps = 1;          ///< equal load increments from s = 0 to s = 1
  int max_iterations = 30;     ///< Newton iterations per load step
  int max_step_cuts = 10;      ///< times a failed load increment may be halved
  /// Converged when ‖Δq‖∞ ≤ increment_tolerance·max(1, ‖q‖∞) (q in model units) and the
  /// residual is finite. Newton converges quadratically, so the default leaves q at round-off.
  double increment_tolerance = 1e-11;
};

struct StaticSolverStatistics {
  int load_steps = 0;         ///< load increments taken (after cuts)
  int step_cuts = 0;          ///< failed increments that were halved
  int newton_iterations = 0;  ///< total linear solves
  int full_factorizations = 0;
  int refactorizations = 0;
  double wall_seconds = 0.0;
};

/// Owns the KLU analysis of problem.jacobian_pattern(), done once in the constructor.
/// Ownership: keeps a reference to `problem`, which must outlive the solver.
class StaticSolver {
 public:
  explicit StaticSolver(StaticProblem& problem, StaticSolverOptions options = {});

  /// Solve R(y, 1) = 0 starting from y (in/out), stepping the load factor 0 → 1.
  /// Throws SolverError with the load factor, iteration and the worst residual row (named by
  /// the problem) if a load step cannot be completed; y then holds the last converged state.
  StaticSolverStatistics solve(VecX& y);

  /// Newton at a fixed load factor. Returns the iteration count; throws SolverError on failure
  /// (y is left at the last iterate).
  int newton(VecX& y, double load_factor);

 private:
  [[nodiscard]] std::string worst_residual(double load_factor) const;
  StaticProblem& problem_;
  StaticSolverOptions options_;
  KluSolver klu_;
  VecX residual_, values_;
  int iterations_ = 0;
};

}  // namespace ancf
