// One case of the stability stress study: integrate a StressScene with one integrator setting and
// record how the run ends (success with its error measures and counters, or how it failed).
// The report is trivially copyable so that it can live in the shared memory of a forked child
// (time_limited_run.hpp) and be read after the child was killed.
#pragma once

#include <functional>

#include "ancf/io/scene.hpp"
#include "stress_scenes.hpp"

namespace ancf::studies {

/// How the integration itself ended (the time limit and crashes are seen by the parent).
enum class CaseEnd : int {
  running = 0,      ///< not ended yet (a killed child leaves this)
  success,          ///< reached t_end
  refused,          ///< the integrator refused the options (std::invalid_argument), by design
  solver_error,     ///< SolverError: the integrator stopped and said why
  nonfinite_state,  ///< NaN or Inf in q, v, q'' or λ at an output time (detected by the study)
  energy_growth,    ///< (E − E₀)/scale exceeded the growth limit (detected by the study)
  other_exception,  ///< any other exception
};

inline constexpr int kWallMarks = 11;       ///< wall time at t = 0, t_end/10, …, t_end
inline constexpr int kSeriesLength = 1001;  ///< outputs kept as a time series (the first ones)

struct CaseReport {
  CaseEnd end = CaseEnd::running;
  double t_reached = 0.0;           ///< [s] last accepted time reported by the integrator
  double energy_error_max = 0.0;    ///< max |E − E₀|/scale over the outputs
  double energy_growth_max = 0.0;   ///< max (E − E₀)/scale (> 0: energy gained)
  double energy_error_final = 0.0;  ///< (E − E₀)/scale at the last output
  double position_drift_max = 0.0;  ///< max |Φ| over the outputs
  double velocity_drift_max = 0.0;  ///< max |Φ_q v + Φ_t| over the outputs
  double multiplier_max = 0.0;  ///< max ‖λ‖∞ over the outputs (the snap's force jump) [N]
  // Counters (integrator's own; steps also while running for generalized-α).
  long steps = 0, iterations = 0, factorizations = 0, failures = 0, halvings = 0;
  double wall_marks[kWallMarks] = {};  ///< integration wall time at the ten tenths of t_end [s]
  // Time series of the first kSeriesLength outputs: t, (E − E₀)/scale, |Φ|max.
  int series_count = 0;
  double series_t[kSeriesLength] = {}, series_energy[kSeriesLength] = {},
         series_position_drift[kSeriesLength] = {};
  char message[640] = {};  ///< the exception's text for the failed ends
};

struct StressRun {
  IntegratorSettings settings;    ///< integrator, options and t_end
  double output_interval = 0.01;  ///< [s] energy and drift are sampled at these times
  /// Relative energy gain that counts as a blow-up: none of the scenes has an energy source, so a
  /// dissipative or conservative scheme can only gain round-off and discretization error.
  double energy_growth_limit = 0.5;
};

/// Builds the scene (inside the caller's process: meant to run in the forked child) and
/// integrates it; never throws, everything ends up in `report`.
void run_stress_case(const std::function<StressScene()>& make_scene, const StressRun& run,
                     CaseReport& report) noexcept;

}  // namespace ancf::studies
