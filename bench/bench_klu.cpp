// KLU on the generalized-α iteration matrix of the benchmark cable pendulum (REFERENCES §10,
// benchmark_cable_pendulum(N), pinned at the origin): numeric refactorization with the first pivot
// order (what the stepper does when it refreshes its matrix), a full numeric factorization with
// fresh partial pivoting (its first factorization and the fallback on pivot growth), and one
// solve, at N = 20, 100, 1000 and 10000 elements. The symbolic analysis (BTF + AMD) runs once in
// the KluSolver constructor, outside the timed loops, as in the stepper.
//
// The matrix is the scaled one the stepper factorizes, [(1 − α_m)/(1 − α_f) M + γh C + βh² K,
// Φ_qᵀ; Φ_q, 0] (generalized_alpha.hpp), assembled at the consistent start (the straight cable at
// rest, q'' and λ from the index-1 solve) for h = 1e-3 s, ρ∞ = 0.8. Linear growth in N shows as a
// constant s_per_element.
#include <benchmark/benchmark.h>

#include <algorithm>

#include "ancf/core/klu_solver.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/system/multibody_problem.hpp"

namespace {

using ancf::Index;
using ancf::VecX;

// Model, problem, matrix values and a right-hand side, built outside the timed loop; the solver
// has done its symbolic analysis and one factorization.
struct KluSetup {
  ancf::Model model;
  ancf::MultibodyProblem problem;
  VecX values, rhs;
  ancf::KluSolver klu;

  explicit KluSetup(Index elements)
      : model(ancf::cable_pendulum_model(ancf::benchmark_cable_pendulum(elements))),
        problem(model),
        values(model.pattern().nonzeros()),
        rhs(problem.system_size()),
        klu(problem.iteration_pattern()) {
    ancf::GeneralizedAlphaOptions options;  // h = 1e-3 s, ρ∞ = 0.8, scaled
    ancf::GeneralizedAlphaStepper stepper(problem, options);
    stepper.initialize(0.0);
    problem.iteration_matrix(
        0.0, ancf::as_span(stepper.positions()), ancf::as_span(stepper.velocities()),
        ancf::as_span(stepper.accelerations()), ancf::as_span(stepper.multipliers()),
        stepper.iteration_weights(options.step_size, true), ancf::as_span(values));
    // A fixed non-zero right-hand side: the cost of the triangular solves does not depend on it.
    for (Index i = 0; i < rhs.size(); ++i) rhs[i] = 1.0 + 1e-3 * static_cast<double>(i % 7);
    klu.factor(ancf::as_span(values));
  }
};

void set_counters(benchmark::State& state, const KluSetup& s, Index elements) {
  state.SetItemsProcessed(state.iterations() * elements);
  state.counters["elements"] = static_cast<double>(elements);
  state.counters["unknowns"] = static_cast<double>(s.problem.system_size());
  state.counters["nonzeros"] = static_cast<double>(s.values.size());
  state.counters["s_per_element"] = benchmark::Counter(
      static_cast<double>(elements),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Refactorization with the pivot order of the first factorization (klu_refactor + the check
// KluSolver does after it): Arg 1 = RefactorCheck::pivot_growth (klu_rgrowth, the default of
// KluSolver), Arg 0 = RefactorCheck::diagonal (the O(n) rcond estimate, generalized-α's default).
void BM_KluRefactor(benchmark::State& state) {
  const Index elements = state.range(0);
  KluSetup s(elements);
  s.klu.set_refactor_check(state.range(1) != 0 ? ancf::RefactorCheck::pivot_growth
                                               : ancf::RefactorCheck::diagonal);
  const int full_before = s.klu.full_factorizations();
  for (auto _ : state) {
    s.klu.factor(ancf::as_span(s.values));
    benchmark::ClobberMemory();
  }
  // Every timed call must have been a refactorization, not a fallback to fresh pivoting.
  if (s.klu.full_factorizations() != full_before)
    state.SkipWithError("pivot growth forced full factorizations inside the timed loop");
  set_counters(state, s, elements);
}

// Full numeric factorization with fresh partial pivoting (symbolic analysis reused).
void BM_KluFactorPivoting(benchmark::State& state) {
  const Index elements = state.range(0);
  KluSetup s(elements);
  for (auto _ : state) {
    s.klu.reset_pivoting();
    s.klu.factor(ancf::as_span(s.values));
    benchmark::ClobberMemory();
  }
  set_counters(state, s, elements);
}

// One solve A x = b in place. The right-hand side is restored from a copy each iteration (an
// O(n) copy, a few per cent of the solve) so that repeated solves do not drift into overflow or
// denormals.
// Arg 1: 2 = KluSolve::reciprocal (the default: the factors copied into sorted column runs, U's
// pivots as reciprocals), 1 = KluSolve::extracted (the same, dividing), 0 = KluSolve::klu
// (klu_l_solve).
void BM_KluSolve(benchmark::State& state) {
  const Index elements = state.range(0);
  KluSetup s(elements);
  const ancf::KluSolve methods[] = {ancf::KluSolve::klu, ancf::KluSolve::extracted,
                                    ancf::KluSolve::reciprocal};
  s.klu.set_solve(methods[state.range(1)]);
  s.klu.factor(ancf::as_span(s.values));  // a refactorization: the solve method takes effect
  VecX x(s.rhs.size());
  for (auto _ : state) {
    std::copy(s.rhs.begin(), s.rhs.end(), x.begin());
    s.klu.solve(ancf::as_span(x));
    benchmark::DoNotOptimize(x.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, s, elements);
}

}  // namespace

BENCHMARK(BM_KluRefactor)
    ->ArgsProduct({{20, 100, 1000, 10000}, {1, 0}})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KluFactorPivoting)
    ->Arg(20)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(10000)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_KluSolve)
    ->ArgsProduct({{20, 100, 1000, 10000}, {2, 1, 0}})
    ->Unit(benchmark::kMicrosecond);
