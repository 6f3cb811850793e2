// Bounds checked before a run starts (run_limits.hpp).
#include "ancf/io/run_limits.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace ancf {

double machine_memory_bytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size)
                                    : 0.0;
}

void require_memory_for_elements(double elements, double budget_bytes) {
  const double budget = budget_bytes > 0.0 ? budget_bytes : machine_memory_bytes();
  const double need = elements * kRunBytesPerCableElement;
  if (budget > 0.0 && need > budget)
    throw ModelError(
        fmt::format("{:.0f} cable elements in all would need about {:.3g} GB to run ({:.0f} kB per "
                    "element), more than the {:.3g} GB {}",
                    elements, need / 1e9, kRunBytesPerCableElement / 1e3, budget / 1e9,
                    budget_bytes > 0.0 ? "allowed" : "of this machine"));
}

double minimum_step_count(const IntegratorSettings& s, double output_interval) {
  // The output times interval, 2·interval, … < t_end plus t_end (simulation.hpp output_times).
  const double outputs = std::ceil(s.t_end / output_interval);
  // Error-controlled generalized-α: `step` is only the first step; h_max (0: none) bounds them.
  const double limit = s.kind != IntegratorKind::genalpha ? s.max_step
                       : s.ga_error_controlled            ? s.ga_controller.h_max
                                                          : s.step;
  const double by_step = limit > 0.0 ? std::ceil(s.t_end / limit) : 0.0;
  return std::max(outputs, by_step);
}

void require_bounded_steps(const IntegratorSettings& s, double output_interval, double max_steps) {
  const double steps = minimum_step_count(s, output_interval);
  if (!(steps <= max_steps)) {
    const bool ga = s.kind == IntegratorKind::genalpha;
    const double limit = !ga ? s.max_step : s.ga_error_controlled ? s.ga_controller.h_max : s.step;
    const bool by_outputs = !(limit > 0.0) || std::ceil(s.t_end / output_interval) >= steps;
    throw ModelError(fmt::format(
        "the run would take at least {:.3g} steps ({}), more than the bound of {:.3g}: change "
        "the settings, or raise the bound with --max-steps",
        steps,
        by_outputs ? fmt::format("t_end {:g} s / output interval {:g} s", s.t_end, output_interval)
                   : fmt::format("t_end {:g} s / {} {:g} s", s.t_end,
                                 ga ? "generalized-alpha step" : "IDA max_step", limit),
        max_steps));
  }
}

void require_runnable(const IntegratorSettings& s, double output_interval, double max_steps) {
  if (s.kind == IntegratorKind::genalpha && s.step > s.t_end)
    throw ModelError("--step exceeds t_end");
  const StepControllerOptions& c = s.ga_controller;
  if (c.h_max > 0.0 && c.h_max < c.h_min)
    throw ModelError("generalized-alpha h_max (--h-max) is below h_min (--h-min)");
  require_bounded_steps(s, output_interval, max_steps);
}

}  // namespace ancf
