#include "stress_case.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/io/simulation.hpp"
#include "ancf/system/assembly.hpp"

namespace ancf::studies {

namespace {

// Thrown by the output hook to stop a run that has blown up; caught below.
struct BlowUp : std::runtime_error {
  CaseEnd end;
  BlowUp(CaseEnd e, const std::string& what) : std::runtime_error(what), end(e) {}
};

void set_message(CaseReport& report, const std::string& text) {
  const std::size_t n = std::min(text.size(), sizeof(report.message) - 1);
  std::memcpy(report.message, text.data(), n);
  report.message[n] = '\0';
}

long counter(const SimulationCounters& counters, const char* name) {
  for (const auto& [key, value] : counters)
    if (key == name) return value;
  return 0;
}

void copy_counters(const SimulationCounters& c, bool ida, CaseReport& report) {
  if (c.empty()) return;  // failed before the integrator existed
  report.steps = counter(c, "steps");
  report.iterations = counter(c, "Newton iterations");
  if (ida) {
    report.factorizations = counter(c, "linear solver setups");
    report.failures = counter(c, "error test failures") + counter(c, "convergence failures");
  } else {
    report.factorizations = counter(c, "factorizations");
    report.failures = counter(c, "convergence failures");
    report.halvings = counter(c, "step halvings");
  }
}

bool finite_state(const SystemState& s) {
  return s.q.allFinite() && s.v.allFinite() && s.a.allFinite() && s.lambda.allFinite();
}

}  // namespace

void run_stress_case(const std::function<StressScene()>& make_scene, const StressRun& run,
                     CaseReport& report) noexcept {
  const bool ida = run.settings.kind == IntegratorKind::ida;
  SimulationCounters counters;
  try {
    const StressScene scene = make_scene();
    Workspace ws(scene.model);
    double e0 = 0.0;
    bool first = true;
    int next_mark = 0;
    const auto start = std::chrono::steady_clock::now();
    SimulationHooks hooks;
    hooks.output = [&](const SystemState& s) {
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      while (next_mark < kWallMarks &&
             s.t >= run.settings.t_end * next_mark / (kWallMarks - 1) * (1.0 - 1e-12))
        report.wall_marks[next_mark++] = wall;
      report.t_reached = s.t;
      if (!finite_state(s))
        throw BlowUp(
            CaseEnd::nonfinite_state,
            fmt::format("non-finite state at t = {:.9g} (the integrator did not stop)", s.t));
      const double e = energies(scene.model, s, ws).total();
      if (first) e0 = e;
      first = false;
      const double rel = (e - e0) / scene.energy_scale;
      const ConstraintViolation cv = constraint_violation(scene.model, s, ws);
      report.energy_error_max = std::max(report.energy_error_max, std::abs(rel));
      report.energy_growth_max = std::max(report.energy_growth_max, rel);
      report.energy_error_final = rel;
      report.position_drift_max = std::max(report.position_drift_max, cv.position);
      report.velocity_drift_max = std::max(report.velocity_drift_max, cv.velocity);
      if (report.series_count < kSeriesLength) {
        const int k = report.series_count++;
        report.series_t[k] = s.t;
        report.series_energy[k] = rel;
        report.series_position_drift[k] = cv.position;
      }
      if (s.lambda.size() > 0)
        report.multiplier_max = std::max(report.multiplier_max, s.lambda.lpNorm<Eigen::Infinity>());
      if (!std::isfinite(rel) || rel > run.energy_growth_limit)
        throw BlowUp(CaseEnd::energy_growth,
                     fmt::format("energy grew by {:.3e} x scale by t = {:.9g} (the integrator did "
                                 "not stop)",
                                 rel, s.t));
    };
    // Generalized-α reports every accepted step: the time and the step count survive a kill.
    hooks.progress = [&](double t) {
      report.t_reached = t;
      if (!ida) ++report.steps;
    };
    simulate(scene.model, run.settings, output_times(run.output_interval, run.settings.t_end),
             hooks, counters);
    copy_counters(counters, ida, report);
    report.end = CaseEnd::success;
  } catch (const BlowUp& e) {
    copy_counters(counters, ida, report);
    report.end = e.end;
    set_message(report, e.what());
  } catch (const SolverError& e) {
    copy_counters(counters, ida, report);
    report.end = CaseEnd::solver_error;
    set_message(report, e.what());
  } catch (const std::invalid_argument& e) {
    report.end = CaseEnd::refused;
    set_message(report, e.what());
  } catch (const std::exception& e) {
    copy_counters(counters, ida, report);
    report.end = CaseEnd::other_exception;
    set_message(report, e.what());
  } catch (...) {
    report.end = CaseEnd::other_exception;
    set_message(report, "unknown exception");
  }
}

}  // namespace ancf::studies
