// One driver for both integrators on a Model: IDA on the GGL index-2 DAE (GglProblem) or
// generalized-α on the index-3 / stabilized index-2 form (MultibodyProblem), reporting the full
// state at given output times. Used by `ancf run` and by the study executables, so that every
// run of a scene goes through the same code.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "ancf/io/scene.hpp"
#include "ancf/system/assembly.hpp"

namespace ancf {

/// Deterministic counters of a run (name, value), in the integrator's own terms.
using SimulationCounters = std::vector<std::pair<std::string, long>>;
/// Where the wall time of a run went (name, seconds): element kernels, contact, the rest of the
/// assembly, factorization, solves, the integrator's own work. Timings are not deterministic.
using SimulationTimings = std::vector<std::pair<std::string, double>>;

struct SimulationHooks {
  /// Called at t = 0 (consistent initial values) and at every output time with t, q, v, a = q''
  /// and λ. The state is only valid during the call.
  std::function<void(const SystemState&)> output;
  /// Called after every accepted step of generalized-α / every output of IDA with the time.
  std::function<void(double)> progress;
};

/// Output times interval, 2·interval, … below t_end, and t_end itself. Preconditions: > 0.
[[nodiscard]] std::vector<double> output_times(double interval, double t_end);

/// Integrate `model` from t = 0 to settings.t_end. `counters` is filled also when a solver
/// failure is thrown (the integrator's own exception, which names the time, the step size and the
/// worst component), so that a caller can report how far it got. `times` must be increasing and
/// end at settings.t_end.
void simulate(const Model& model, const IntegratorSettings& settings, const std::vector<double>& times,
              const SimulationHooks& hooks, SimulationCounters& counters);
/// The same, also filling `timings` (also when a solver failure is thrown).
void simulate(const Model& model, const IntegratorSettings& settings, const std::vector<double>& times,
              const SimulationHooks& hooks, SimulationCounters& counters,
              SimulationTimings& timings);

}  // namespace ancf
