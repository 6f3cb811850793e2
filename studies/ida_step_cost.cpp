// IDA's cost per step on the benchmark cable pendulum (REFERENCES §10, issue 20): one IDA
// configuration (BDF order limit, rtol) timed several times, with the split of the wall time into
// the residual and Jacobian callbacks, KLU factorization and solves, and the rest — IDA's own
// work (predictor, error weights, norms, Newton bookkeeping, history updates) — per step.
//
// Usage: ancf-bench-ida-step [--elements N] [--order K] [--rtol R] [--runs M] [--no-reference]
//                            [--ida-vectors]  (SUNDIALS' own vector operations and error weights)
//                            [--klu-solve]    (klu_l_solve instead of the extracted factors)
//                            [--divide-pivots] (the extracted solve dividing by U's pivots)
//                            [--klu-refactor] (klu_l_refactor instead of the LU on the runs)
//                            [--steady-clock] (time shares read steady_clock, not the TSC)
//                            [--sundials-klu] (SUNLinSol_KLU instead of the project's KluSolver)
//
// Defaults: 20 elements, order ≤ 2, rtol 1e-5 (the fastest configuration of ancf-bench-ida with a
// tip error ≤ 1e-5 m). Printed: the counters, median wall time and µs per step with the split,
// the tip at 0.25, 0.5, 1.0 s (9 digits, to compare builds) and, unless --no-reference, the tip
// error against an IDA run at rtol 1e-11, order ≤ 5, on the same mesh.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ancf/core/stopwatch.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "option_value.hpp"

namespace {

using ancf::IdaOptions;
using ancf::IdaStatistics;
using ancf::Index;
using ancf::Vec3;

const std::vector<double> kOutputTimes = {0.25, 0.5, 1.0};

struct Run {
  std::vector<Vec3> tip;
  IdaStatistics stats;
};

Run simulate(const ancf::Model& model, const IdaOptions& options) {
  ancf::GglProblem problem(model);
  const Index tip = model.node_coordinate(0, -1);
  ancf::IdaIntegrator ida(problem, options);
  Run run;
  ida.run([&](double, std::span<const double> y, std::span<const double>) {
    run.tip.emplace_back(y[tip], y[tip + 1], y[tip + 2]);
  });
  run.stats = ida.statistics();
  return run;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  Index elements = 20;
  int runs = 5;
  bool reference = true;
  IdaOptions options;
  options.max_order = 2;
  options.rtol = 1e-5;
  options.output_times = kOutputTimes;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&] { return ancf::studies::option_value(argc, argv, i); };
    if (arg == "--elements")
      elements = std::stol(value());
    else if (arg == "--order")
      options.max_order = std::stoi(value());
    else if (arg == "--rtol")
      options.rtol = std::stod(value());
    else if (arg == "--runs")
      runs = std::max(1, std::stoi(value()));
    else if (arg == "--no-reference")
      reference = false;
    else if (arg == "--ida-vectors")
      options.compiled_vector_ops = false;
    else if (arg == "--klu-solve")
      options.klu_solve = ancf::KluSolve::klu;
    else if (arg == "--divide-pivots")
      options.klu_solve = ancf::KluSolve::extracted;
    else if (arg == "--steady-clock")
      ancf::TickClock::use_steady_clock(true);
    else if (arg == "--klu-refactor")
      options.klu_refactor = ancf::KluRefactor::klu;
    else if (arg == "--sundials-klu")
      options.linear_solver = ancf::IdaLinearSolver::sundials_klu;
    else {
      std::fprintf(stderr,
                   "usage: %s [--elements N] [--order K] [--rtol R] [--runs M] [--no-reference] "
                   "[--ida-vectors] [--klu-solve] [--divide-pivots] [--klu-refactor] "
                   "[--sundials-klu] [--steady-clock]\n",
                   argv[0]);
      return 2;
    }
  }
  const ancf::Model model = ancf::cable_pendulum_model(ancf::benchmark_cable_pendulum(elements));

  std::vector<double> wall, residual, jacobian, factor, solve;
  Run run;
  for (int r = 0; r < runs; ++r) {
    run = simulate(model, options);
    const IdaStatistics& s = run.stats;
    wall.push_back(s.wall_time);
    residual.push_back(s.residual_seconds);
    jacobian.push_back(s.jacobian_seconds);
    factor.push_back(s.factor_seconds);
    solve.push_back(s.solve_seconds);
  }
  const IdaStatistics& s = run.stats;
  const double steps = static_cast<double>(s.steps);
  fmt::print("benchmark cable pendulum, {} elements; IDA order <= {}, rtol {:.3g}\n", elements,
             options.max_order, options.rtol);
  fmt::print(
      "steps {}, residuals {} ({:.3f}/step), Jacobians {}, setups {}, Newton iterations {} "
      "({:.3f}/step), error-test failures {}, convergence failures {}, full factorizations {}, "
      "refactorizations {}\n",
      s.steps, s.residual_evaluations, s.residual_evaluations / steps, s.jacobian_evaluations,
      s.linear_solver_setups, s.nonlinear_iterations, s.nonlinear_iterations / steps,
      s.error_test_failures, s.convergence_failures, s.full_factorizations, s.refactorizations);
  const double w = median(wall), res = median(residual), jac = median(jacobian),
               fac = median(factor), sol = median(solve);
  const double own = w - res - jac - fac - sol;
  fmt::print(
      "wall (median of {}): {:.4f} s = {:.2f} us/step: residual {:.2f}, Jacobian {:.2f}, KLU "
      "factor {:.2f}, KLU solve {:.2f}, IDA's own work {:.2f} us/step ({:.0f} %)\n",
      runs, w, 1e6 * w / steps, 1e6 * res / steps, 1e6 * jac / steps, 1e6 * fac / steps,
      1e6 * sol / steps, 1e6 * own / steps, 100.0 * own / w);
  for (std::size_t k = 0; k < kOutputTimes.size(); ++k)
    fmt::print("tip at {:.2f} s: ({:.9f}, {:.9f}, {:.9f}) m\n", kOutputTimes[k], run.tip[k].x(),
               run.tip[k].y(), run.tip[k].z());
  if (reference) {
    IdaOptions tight;
    tight.rtol = 1e-11;
    tight.output_times = kOutputTimes;
    const Run ref = simulate(model, tight);
    double error = 0.0;
    for (std::size_t k = 0; k < kOutputTimes.size(); ++k)
      error = std::max(error, (run.tip[k] - ref.tip[k]).norm());
    fmt::print("tip error against rtol 1e-11 (order <= 5): {:.3e} m\n", error);
  }
  return 0;
}
