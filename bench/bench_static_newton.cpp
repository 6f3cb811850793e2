// One assembled static Newton iteration of the cantilever (Green strain + Gerstmayr–Shabana
// bending, EI = 1 N m², the model the tests and the demo use) at 10, 100 and 1000 elements, split
// into its parts: residual assembly, Jacobian assembly, KLU refactor + solve, and the whole
// iteration. Every part should grow linearly with the element count; items/s is elements per
// second and s_per_element the time per element, so linear growth shows as a constant
// s_per_element across the three sizes.
#include <benchmark/benchmark.h>

#include <span>

#include "ancf/core/klu_solver.hpp"
#include "ancf/scenes/cantilever.hpp"
#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/static_model_problem.hpp"

namespace {

using ancf::Index;
using ancf::VecX;

// std::span<double> converts implicitly where the problem takes std::span<const double>.
std::span<double> as_span(VecX& v) { return {v.data(), static_cast<std::size_t>(v.size())}; }

// The model, the problem and a deformed equilibrium state y, built outside the timed loop. The
// state is the solved cantilever (tip deflection ~0.3 L) rather than the straight reference, so
// the element code sees real curvature; the cost of an iteration does not depend on how far it
// is from convergence, only on the configuration's branches (κ ≠ 0 here, as in practice).
struct NewtonSetup {
  ancf::Model model;
  ancf::StaticModelProblem problem;
  VecX y;

  explicit NewtonSetup(Index elements)
      : model(ancf::cantilever_model(spec(elements))), problem(model), y(problem.initial_guess()) {
    ancf::StaticSolverOptions options;
    options.load_steps = 2;
    ancf::StaticSolver solver(problem, options);
    solver.solve(y);
  }

  static ancf::CantileverSpec spec(Index elements) {
    ancf::CantileverSpec s;
    s.elements = elements;
    return s;
  }
};

// Common counters: elements per second (items/s) and the time per element, plus the system
// size so the table documents what was solved.
void set_counters(benchmark::State& state, const NewtonSetup& s, Index elements) {
  state.SetItemsProcessed(state.iterations() * elements);
  state.counters["elements"] = static_cast<double>(elements);
  state.counters["unknowns"] = static_cast<double>(s.problem.size());
  state.counters["s_per_element"] = benchmark::Counter(
      static_cast<double>(elements),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// (a) R(y, s): element forces scattered into the global vector, plus the constraint rows.
void BM_NewtonResidual(benchmark::State& state) {
  const Index elements = state.range(0);
  NewtonSetup s(elements);
  VecX r(s.problem.size());
  for (auto _ : state) {
    s.problem.residual(as_span(s.y), 1.0, as_span(r));
    benchmark::DoNotOptimize(r.data());
    benchmark::ClobberMemory();  // r's contents count as read
  }
  set_counters(state, s, elements);
}

// (b) ∂R/∂y: element tangents scattered into the CSC values through the precomputed slots.
void BM_NewtonJacobian(benchmark::State& state) {
  const Index elements = state.range(0);
  NewtonSetup s(elements);
  VecX values(s.model.pattern().nonzeros());
  for (auto _ : state) {
    s.problem.jacobian(as_span(s.y), 1.0, as_span(values));
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, s, elements);
  state.counters["nonzeros"] = static_cast<double>(values.size());
}

// (c) KLU numeric refactor (fixed pivot order, with the pivot-growth check KluSolver does) and
// the triangular solves. The symbolic analysis (constructor) and the first full factorization
// with pivoting happen once, outside the loop, exactly as in StaticSolver. The O(n) copy of the
// right-hand side (solve works in place) is included; it is negligible next to the solve.
void BM_NewtonFactorSolve(benchmark::State& state) {
  const Index elements = state.range(0);
  NewtonSetup s(elements);
  VecX r(s.problem.size()), values(s.model.pattern().nonzeros()), rhs(s.problem.size());
  s.problem.residual(as_span(s.y), 1.0, as_span(r));
  s.problem.jacobian(as_span(s.y), 1.0, as_span(values));
  ancf::KluSolver klu(s.model.pattern());
  klu.factor(as_span(values));
  for (auto _ : state) {
    klu.factor(as_span(values));
    rhs = -r;
    klu.solve(as_span(rhs));
    benchmark::DoNotOptimize(rhs.data());
    benchmark::ClobberMemory();
  }
  // A pivot-growth fallback would make this time full factorizations, not refactors.
  if (klu.full_factorizations() != 1) state.SkipWithError("KLU fell back to full factorization");
  set_counters(state, s, elements);
}

// (d) The whole iteration as StaticSolver::newton does it: residual, Jacobian, refactor, solve,
// update. The update goes into a trial vector from the fixed state, so every iteration does the
// same work on the same configuration.
void BM_NewtonIteration(benchmark::State& state) {
  const Index elements = state.range(0);
  NewtonSetup s(elements);
  VecX r(s.problem.size()), values(s.model.pattern().nonzeros()), y_trial(s.problem.size());
  s.problem.jacobian(as_span(s.y), 1.0, as_span(values));
  ancf::KluSolver klu(s.model.pattern());
  klu.factor(as_span(values));
  for (auto _ : state) {
    s.problem.residual(as_span(s.y), 1.0, as_span(r));
    s.problem.jacobian(as_span(s.y), 1.0, as_span(values));
    klu.factor(as_span(values));
    r = -r;
    klu.solve(as_span(r));
    y_trial = s.y + r;
    benchmark::DoNotOptimize(y_trial.data());
    benchmark::ClobberMemory();
  }
  if (klu.full_factorizations() != 1) state.SkipWithError("KLU fell back to full factorization");
  set_counters(state, s, elements);
}

}  // namespace

BENCHMARK(BM_NewtonResidual)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NewtonJacobian)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NewtonFactorSolve)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NewtonIteration)->Arg(10)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);
