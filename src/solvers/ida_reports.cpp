// What an IDA run reports: the failure message built from IdaFailureReport, and the counters as
// a table (ida_integrator.hpp). Independent of the integrator's SUNDIALS state.
#include <fmt/format.h>

#include <string>
#include <utility>

#include "ancf/solvers/ida_integrator.hpp"

namespace ancf {

IdaFailure::IdaFailure(IdaFailureReport r)
    : SolverError(fmt::format(
          "IDA failed at t = {:.10g} s with step {:.3g} s: {} ({}){}{}", r.t, r.step, r.flag_name,
          r.ida_message,
          r.component >= 0
              ? fmt::format("; worst {}: {} ({:.3g})", r.measure, r.component_name, r.value)
              : std::string(),
          r.callback_message.empty() ? std::string()
                                     : "; last callback error: " + r.callback_message)),
      report_(std::move(r)) {}

std::string IdaStatistics::table() const {
  std::string s;
  auto row = [&](const char* name, auto value) {
    s += fmt::format("  {:<28} {:>12}\n", name, value);
  };
  row("steps", steps);
  row("residual evaluations", residual_evaluations);
  row("Jacobian evaluations", jacobian_evaluations);
  row("linear solver setups", linear_solver_setups);
  row("Newton iterations", nonlinear_iterations);
  row("error test failures", error_test_failures);
  row("convergence failures", convergence_failures);
  row("root function evaluations", root_evaluations);
  row("KLU re-pivotings", klu_repivots);
  row("re-initializations", reinitializations);
  row("pattern changes", pattern_changes);
  row("symbolic analyses", symbolic_analyses);
  row("full factorizations", full_factorizations);
  row("refactorizations", refactorizations);
  row("last order", last_order);
  row("last step [s]", fmt::format("{:.3e}", last_step));
  row("wall time [s]", fmt::format("{:.4f}", wall_time));
  return s;
}

}  // namespace ancf
