#include "ancf/solvers/static_solver.hpp"

#include <fmt/format.h>
#include <chrono>
#include <cmath>

#include "ancf/core/error.hpp"

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

int StaticSolver::newton(VecX& y, double s) {
  const Index n = problem_.coordinate_count();
  for (int it = 1; it <= options_.max_iterations; ++it) {
    problem_.residual(as_span(y), s, as_span(residual_));
    if (!residual_.allFinite())
      throw SolverError("static Newton: non-finite residual, " + worst_residual(s));
    problem_.jacobian(as_span(y), s, as_span(values_));
    try {
      klu_.factor(as_span(values_));
    } catch (const SolverError& e) {
      throw SolverError(
          fmt::format("static Newton: {} at iteration {}; {}", e.what(), it, worst_residual(s)));
    }
    residual_ = -residual_;
    klu_.solve(as_span(residual_));  // residual_ now holds Δy
    ++iterations_;
    if (!residual_.allFinite())
      throw SolverError(fmt::format("static Newton: non-finite increment at iteration {}", it));
    y += residual_;
    const double dq = residual_.head(n).lpNorm<Eigen::Infinity>();
    const double scale = std::max(1.0, y.head(n).lpNorm<Eigen::Infinity>());
    if (dq <= options_.increment_tolerance * scale) return it;
  }
  problem_.residual(as_span(y), s, as_span(residual_));
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
    const double s_next = std::min(1.0, s + ds);
    try {
      newton(y, s_next);
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
    ++stats.load_steps;
  }
  stats.newton_iterations = iterations_;
  stats.full_factorizations = klu_.full_factorizations();
  stats.refactorizations = klu_.refactorizations();
  stats.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace ancf
