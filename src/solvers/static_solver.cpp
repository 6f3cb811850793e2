#include "ancf/solvers/static_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/solvers/singularity_estimate.hpp"

namespace ancf {
StaticSolver::StaticSolver(StaticProblem& problem, StaticSolverOptions options)
    : problem_(problem),
      options_(options),
      klu_(problem.jacobian_pattern()),
      residual_(problem.size()),
      values_(problem.jacobian_pattern().nonzeros()) {}

std::string StaticSolver::worst_residual(double load_factor) const {
  Index worst = 0;
  residual_.cwiseAbs().maxCoeff(&worst);
  return fmt::format("largest residual {:.3e} at {} (load factor {:.6g})", residual_[worst],
                     problem_.describe_row(worst), load_factor);
}

std::string StaticSolver::describe_direction(const VecX& direction) const {
  // The three largest components, and any others within 10 % of the largest.
  std::vector<Index> order(static_cast<std::size_t>(direction.size()));
  std::iota(order.begin(), order.end(), Index{0});
  const std::size_t shown = std::min<std::size_t>(3, order.size());
  std::partial_sort(
      order.begin(), order.begin() + static_cast<std::ptrdiff_t>(shown), order.end(),
      [&](Index a, Index b) { return std::abs(direction[a]) > std::abs(direction[b]); });
  const double largest = shown ? std::abs(direction[order[0]]) : 0.0;
  std::string out;
  for (std::size_t k = 0; k < shown; ++k) {
    const double w = std::abs(direction[order[k]]);
    if (k > 0 && w < 0.1 * largest) break;
    out += fmt::format("{}{} ({:.2g})", k ? ", " : "", problem_.describe_row(order[k]),
                       largest > 0.0 ? w / largest : 0.0);
  }
  return out;
}

int StaticSolver::newton(VecX& y, double s) {
  const Index n = problem_.coordinate_count();
  const SparsityPattern& pattern = problem_.jacobian_pattern();
  // StaticProblem's contract: std::domain_error means the iterate is not evaluable (e.g. a rod
  // tangent turned against its committed frame by an overshooting Newton step). A failed
  // iteration: the load increment is cut, as for a non-finite residual.
  auto evaluate = [&](int it, bool with_jacobian) {
    try {
      problem_.residual(as_span(y), s, as_span(residual_));
      if (with_jacobian && residual_.allFinite())
        problem_.jacobian(as_span(y), s, as_span(values_));
    } catch (const std::domain_error& e) {
      throw SolverError(fmt::format("static Newton: {} at iteration {}", e.what(), it));
    }
  };
  for (int it = 1; it <= options_.max_iterations; ++it) {
    evaluate(it, true);
    if (!residual_.allFinite())
      throw SolverError("static Newton: non-finite residual, " + worst_residual(s));
    try {
      klu_.factor(as_span(values_));
    } catch (const SolverError& e) {
      // At the first iteration the tangent is that of the state the increment starts from (the
      // last converged state): a zero pivot there is structural, cutting the load cannot help.
      const std::string what =
          fmt::format("static Newton: {} at iteration {}; {}", e.what(), it, worst_residual(s));
      if (it == 1)
        throw SingularStaticProblem(
            fmt::format("the tangent of the state the increment to load factor {:.6g} starts "
                        "from is singular; {}",
                        s, what));
      throw SolverError(what);
    }
    // At the start of an increment (the tangent of the last converged state) the Newton step is
    // compared with the residual in equilibrated units (singularity_estimate.hpp):
    // ‖r_s‖/‖Δy_s‖ ≥ σ_min(J_s), and a ratio below singular_tolerance means the residual acts
    // on a direction the tangent has no stiffness in. No equilibrium is near then, and a smaller
    // load increment would not change the ratio.
    const bool check = it == 1;
    Equilibration scales;
    VecX scaled_residual;
    residual_ = -residual_;
    if (check) {
      scales = equilibrate(pattern, as_span(values_), n);
      scaled_residual = scales.row_scale.cwiseProduct(residual_);
    }
    klu_.solve(as_span(residual_));  // residual_ now holds Δy
    ++iterations_;
    if (check && residual_.allFinite()) {
      const VecX scaled_step = residual_.cwiseQuotient(scales.column_scale);
      // stableNorm: loads near the overflow threshold must not turn the ratio into 0 or NaN.
      const double stiffness = scaled_residual.stableNorm() / scaled_step.stableNorm();
      if (stiffness < options_.singular_tolerance)
        throw SingularStaticProblem(fmt::format(
            "no equilibrium near the state the increment to load factor {:.6g} starts from: its "
            "tangent has no stiffness against the load (residual / Newton step {:.2e} in "
            "equilibrated units, below {:.1e}); the step would move mostly {}",
            s, stiffness, options_.singular_tolerance,
            describe_direction(scaled_step / scaled_step.stableNorm())));
    }
    if (!residual_.allFinite())
      throw SolverError(fmt::format("static Newton: non-finite increment at iteration {}", it));
    y += residual_;
    const double dq = residual_.head(n).lpNorm<Eigen::Infinity>();
    const double scale = std::max(1.0, y.head(n).lpNorm<Eigen::Infinity>());
    if (dq <= options_.increment_tolerance * scale) {
      // The tangent of the last iterate, within the tolerance of the solution.
      const SingularityEstimate at_solution =
          estimate_singularity(pattern, as_span(values_), klu_, n);
      last_singular_value_ = at_solution.smallest_singular_value();
      last_singular_direction_ = last_singular_value_ < options_.singular_tolerance
                                     ? describe_direction(at_solution.direction)
                                     : std::string();
      return it;
    }
  }
  evaluate(options_.max_iterations + 1, false);
  throw SolverError(fmt::format("static Newton did not converge in {} iterations; {}",
                                options_.max_iterations, worst_residual(s)));
}

StaticSolverStatistics StaticSolver::solve(VecX& y) {
  const auto start = std::chrono::steady_clock::now();
  StaticSolverStatistics stats;
  iterations_ = 0;
  double s = 0.0;
  double ds = 1.0 / std::max(1, options_.load_steps);
  int cuts_left = options_.max_step_cuts;
  VecX y_converged = y;
  while (s < 1.0) {
    // The last increment ends at 1 exactly: equal increments summed in floating point fall short
    // of 1 by round-off (ten of 0.1 give 1 − 1.1e-16), which would add an empty increment.
    const double s_next = s + ds >= 1.0 - 1e-12 ? 1.0 : s + ds;
    try {
      newton(y, s_next);
    } catch (const SingularStaticProblem& e) {
      y = y_converged;
      throw SingularStaticProblem(
          fmt::format("static solve stopped at load factor {:.6g}: {}", s, e.what()));
    } catch (const SolverError& e) {
      y = y_converged;
      klu_.reset_pivoting();
      if (cuts_left-- <= 0) {
        throw SolverError(
            fmt::format("static solve stopped at load factor {:.6g} after {} step cuts: {}", s,
                        options_.max_step_cuts, e.what()));
      }
      ds *= 0.5;
      ++stats.step_cuts;
      continue;
    }
    s = s_next;
    y_converged = y;
    problem_.commit(as_span(y));
    ++stats.load_steps;
  }
  stats.newton_iterations = iterations_;
  stats.full_factorizations = klu_.full_factorizations();
  stats.refactorizations = klu_.refactorizations();
  stats.smallest_singular_value = last_singular_value_;
  stats.singular_direction = last_singular_direction_;
  problem_.residual(as_span(y), 1.0, as_span(residual_));
  stats.residual_norm = residual_.lpNorm<Eigen::Infinity>();
  stats.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace ancf
