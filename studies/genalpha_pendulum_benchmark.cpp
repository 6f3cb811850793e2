// Speed of the generalized-α stepper on the benchmark cable pendulum of REFERENCES §10: 20 Green +
// Gerstmayr–Shabana elements, pinned at the origin, released straight along +x at rest, gravity
// −9.81 ẑ, t ∈ [0, 1] s, h = 1e-3 s. Established codes need 13–18 µs per element per step for it
// on this kind of machine (REFERENCES §10).
//
// Reports, for the fast setting (modified Newton, factorization reused across steps):
//  * wall time per element per step, median over several runs, and the deterministic counters
//    (Newton iterations, residuals, matrix assemblies and factorizations per step);
//  * tip positions at 0.25, 0.5 and 1.0 s and their distance to (a) a reference with h = 1e-5
//    (tight Newton tolerance), i.e. the discretization error at this h, and (b) the same h with
//    full Newton at a tight tolerance, i.e. the part of the error due to the Newton setting. (b) ≪
//    (a) shows the speed is not bought with accuracy: the accuracy is that of the step size.
//
// Usage: ancf-bench-genalpha [--elements N] [--step H] [--rho R] [--runs K] [--rtol TOL]
//                            [--reuse-rate R] [--extrapolate] [--no-reference] [--profile]
//                            [--pivot-growth]   (KLU refactorization check of 3e3daf4)
//                            [--pointwise-force] (force-only cable kernel of 3e3daf4)
//                            [--pointwise-stiffness] (cable stiffness kernel of 3e3daf4)
//                            [--klu-solve]       (klu_l_solve instead of the extracted factors)
//                            [--divide-pivots]   (the extracted solve dividing by U's pivots)
//                            [--steady-clock]    (time shares read steady_clock, not the TSC)
//                            [--rescale-at-halvings] (fixed stepping rescales a at a change of h
//                                                instead of restarting; not the default)
//                            [--restart-climbs]  (restart also at a climb back: 3e3daf4's
//                            fixed-step policy)
//                            [--no-recovery-backoff] (climb back after recovery_steps always)
//                            [--klu-refactor]    (klu_l_refactor instead of the LU on the runs)
#include <fmt/format.h>
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "ancf/core/klu_solver.hpp"
#include "ancf/core/stopwatch.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/system/multibody_problem.hpp"
#include "option_value.hpp"

namespace {

using ancf::GeneralizedAlphaOptions;
using ancf::GeneralizedAlphaStatistics;
using ancf::GeneralizedAlphaStepper;
using ancf::Index;
using ancf::Vec3;

constexpr std::array<double, 3> kOutputTimes = {0.25, 0.5, 1.0};

struct Run {
  std::array<Vec3, 3> tip;
  GeneralizedAlphaStatistics stats;
  double seconds = 0.0;  // wall time of advance_to over [0, 1] (initialize excluded)
};

// Old kernels selectable for side-by-side timing (same results up to round-off).
struct Kernels {
  ancf::CableKernel force = ancf::CableKernel::invariant;
  ancf::CableKernel stiffness = ancf::CableKernel::invariant;
};

Run simulate(const ancf::Model& model, const GeneralizedAlphaOptions& options,
             const Kernels& kernels = {}) {
  ancf::MultibodyProblem problem(model);
  problem.set_cable_force_kernel(kernels.force);
  problem.set_cable_stiffness_kernel(kernels.stiffness);
  GeneralizedAlphaStepper stepper(problem, options);
  stepper.initialize(0.0);
  const Index tip = model.node_coordinate(0, -1);
  Run run;
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < kOutputTimes.size(); ++k) {
    stepper.advance_to(kOutputTimes[k]);
    run.tip[k] = stepper.positions().segment<3>(tip);
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.stats = stepper.statistics();
  return run;
}

// Cost of the building blocks of one Newton iteration at the initial state (median of 2000 calls):
// where the time per step goes.
void profile_kernels(const ancf::Model& model, const GeneralizedAlphaOptions& options,
                     const Kernels& kernels) {
  ancf::MultibodyProblem problem(model);
  problem.set_cable_force_kernel(kernels.force);
  problem.set_cable_stiffness_kernel(kernels.stiffness);
  GeneralizedAlphaStepper stepper(problem, options);
  stepper.initialize(0.0);
  const auto q = ancf::as_span(stepper.positions()), v = ancf::as_span(stepper.velocities());
  const auto a = ancf::as_span(stepper.accelerations()), l = ancf::as_span(stepper.multipliers());
  ancf::VecX r(problem.system_size()), values(problem.iteration_pattern().nonzeros());
  ancf::KluSolver klu(problem.iteration_pattern());
  klu.set_solve(options.klu_solve);
  klu.set_refactor(options.klu_refactor);
  const auto weights = stepper.iteration_weights(options.step_size, true);
  problem.iteration_matrix(0.0, q, v, a, l, weights, ancf::as_span(values));
  klu.factor(ancf::as_span(values));
  auto time = [](auto&& f) {
    std::vector<double> t;
    for (int k = 0; k < 2000; ++k) {
      const auto start = std::chrono::steady_clock::now();
      f();
      t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2] * 1e6;
  };
  const double t_res = time([&] { problem.residual(0.0, q, v, a, l, ancf::as_span(r)); });
  const double t_mat =
      time([&] { problem.iteration_matrix(0.0, q, v, a, l, weights, ancf::as_span(values)); });
  const double t_fac = time([&] { klu.factor(ancf::as_span(values)); });
  const double t_sol = time([&] { klu.solve(ancf::as_span(r)); });
  fmt::print(
      "kernel costs (median, us): residual {:.2f}, iteration matrix {:.2f}, KLU refactor {:.2f}, "
      "KLU solve {:.2f}\n",
      t_res, t_mat, t_fac, t_sol);
}

double max_tip_distance(const Run& a, const Run& b) {
  double d = 0.0;
  for (std::size_t k = 0; k < kOutputTimes.size(); ++k)
    d = std::max(d, (a.tip[k] - b.tip[k]).norm());
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  Index elements = 20;
  double step = 1e-3, rho = 0.8, rtol = 1e-6, reuse_rate = GeneralizedAlphaOptions{}.max_reuse_rate;
  bool extrapolate = false;
  int runs = 9;
  bool reference = true, profile = false, pivot_growth = false, klu_solve = false,
       divide_pivots = false, rescale_at_halvings = false, restart_climbs = false,
       recovery_backoff = true, klu_refactor = false;
  Kernels kernels;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&] { return ancf::studies::option_value(argc, argv, i); };
    if (arg == "--elements")
      elements = std::stol(value());
    else if (arg == "--step")
      step = std::stod(value());
    else if (arg == "--rho")
      rho = std::stod(value());
    else if (arg == "--runs")
      runs = std::stoi(value());
    else if (arg == "--rtol")
      rtol = std::stod(value());
    else if (arg == "--reuse-rate")
      reuse_rate = std::stod(value());
    else if (arg == "--extrapolate")
      extrapolate = true;
    else if (arg == "--no-reference")
      reference = false;
    else if (arg == "--profile")
      profile = true;
    else if (arg == "--pivot-growth")
      pivot_growth = true;
    else if (arg == "--klu-solve")
      klu_solve = true;
    else if (arg == "--divide-pivots")
      divide_pivots = true;
    else if (arg == "--no-recovery-backoff")
      recovery_backoff = false;
    else if (arg == "--rescale-at-halvings")
      rescale_at_halvings = true;
    else if (arg == "--restart-climbs")
      restart_climbs = true;
    else if (arg == "--steady-clock")
      ancf::TickClock::use_steady_clock(true);
    else if (arg == "--klu-refactor")
      klu_refactor = true;
    else if (arg == "--pointwise-force")
      kernels.force = ancf::CableKernel::pointwise;
    else if (arg == "--pointwise-stiffness")
      kernels.stiffness = ancf::CableKernel::pointwise;
    else {
      std::fprintf(
          stderr,
          "usage: %s [--elements N] [--step H] [--rho R] [--runs K] [--rtol TOL] "
          "[--reuse-rate R] [--extrapolate] [--no-reference] [--profile] [--pivot-growth] "
          "[--pointwise-force] [--pointwise-stiffness] [--klu-solve] [--divide-pivots] "
          "[--steady-clock] [--rescale-at-halvings] [--restart-climbs] [--no-recovery-backoff] "
          "[--klu-refactor]\n",
          argv[0]);
      return 2;
    }
  }

  const ancf::Model model = ancf::cable_pendulum_model(ancf::benchmark_cable_pendulum(elements));
  GeneralizedAlphaOptions fast;
  fast.step_size = step;
  fast.rho_infinity = rho;
  fast.newton = ancf::NewtonStrategy::modified;
  fast.rtol = rtol;
  fast.max_reuse_rate = reuse_rate;
  fast.predictor = extrapolate ? ancf::GeneralizedAlphaPredictor::extrapolated
                               : ancf::GeneralizedAlphaPredictor::constant;
  fast.atol_position = 1e-2 * rtol;
  fast.atol_velocity = rtol;
  fast.atol_multiplier = rtol;
  if (pivot_growth) fast.refactor_check = ancf::RefactorCheck::pivot_growth;
  if (divide_pivots) fast.klu_solve = ancf::KluSolve::extracted;
  if (rescale_at_halvings) fast.step_change = ancf::GeneralizedAlphaStepChange::rescale;
  if (restart_climbs) fast.step_change = ancf::GeneralizedAlphaStepChange::restart;
  fast.recovery_backoff = recovery_backoff;
  if (klu_solve) fast.klu_solve = ancf::KluSolve::klu;
  if (klu_refactor) fast.klu_refactor = ancf::KluRefactor::klu;

  std::vector<double> seconds;
  Run last;
  for (int r = 0; r < runs; ++r) {
    last = simulate(model, fast, kernels);
    seconds.push_back(last.seconds);
  }
  std::sort(seconds.begin(), seconds.end());
  const double median = seconds[seconds.size() / 2];
  const auto steps = static_cast<double>(last.stats.steps);
  const double per_element_step = median / (steps * static_cast<double>(elements)) * 1e6;

  fmt::print(
      "generalized-α benchmark: cable pendulum (REFERENCES §10), {} elements, {} unknowns, "
      "h = {:g} s, rho_inf = {:g}, modified Newton, rtol = {:g}\n",
      elements, model.system_size(), step, rho, rtol);
  fmt::print("wall time over [0, 1] s: median {:.4f} s of {} runs (min {:.4f}, max {:.4f})\n",
             median, runs, seconds.front(), seconds.back());
  fmt::print("  => {:.3f} us per element per step  ({:.2f} us per step)\n", per_element_step,
             median / steps * 1e6);
  const auto& s = last.stats;
  fmt::print(
      "counters: {} steps, {:.3f} Newton iterations/step, {:.3f} residuals/step, "
      "{:.4f} matrix assemblies/step, {:.4f} factorizations/step ({} with fresh pivoting), "
      "{} convergence failures, {} halvings\n",
      s.steps, s.newton_iterations / steps, s.residual_evaluations / steps,
      s.matrix_evaluations / steps, s.factorizations / steps, s.full_factorizations,
      s.convergence_failures, s.step_halvings);
  for (std::size_t k = 0; k < kOutputTimes.size(); ++k)
    fmt::print("tip at t = {:.2f} s: ({:+.9f}, {:+.9f}, {:+.9f}) m\n", kOutputTimes[k],
               last.tip[k].x(), last.tip[k].y(), last.tip[k].z());

  if (profile) profile_kernels(model, fast, kernels);
  if (reference) {
    GeneralizedAlphaOptions tight = fast;
    tight.newton = ancf::NewtonStrategy::full;
    tight.rtol = 1e-12;
    tight.atol_position = 1e-14;
    tight.atol_velocity = 1e-12;
    tight.atol_multiplier = 1e-12;
    const Run same_h_tight = simulate(model, tight);
    tight.step_size = 1e-5;
    const Run fine = simulate(model, tight);
    for (std::size_t k = 0; k < kOutputTimes.size(); ++k)
      fmt::print(
          "reference (h = 1e-5) tip at t = {:.2f} s: ({:+.9f}, {:+.9f}, {:+.9f}) m; |error| of "
          "the fast run {:.3e} m\n",
          kOutputTimes[k], fine.tip[k].x(), fine.tip[k].y(), fine.tip[k].z(),
          (last.tip[k] - fine.tip[k]).norm());
    fmt::print(
        "max tip error vs h = 1e-5 reference: fast {:.3e} m, full Newton tight tolerance at the "
        "same h {:.3e} m\n",
        max_tip_distance(last, fine), max_tip_distance(same_h_tight, fine));
    fmt::print(
        "max tip difference fast vs full-Newton-tight at the same h (Newton part of the error): "
        "{:.3e} m\n",
        max_tip_distance(last, same_h_tight));
  }
  return 0;
}
