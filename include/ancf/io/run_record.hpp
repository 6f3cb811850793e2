// run.json of a run (`ancf run`, the Python module's Simulation.write_record): the scene and the
// hash of its exact text, the integrator options, counters, time shares, outcome and results.
#pragma once

#include <string>

#include "ancf/io/run_metadata.hpp"
#include "ancf/io/run_outputs.hpp"
#include "ancf/io/scene.hpp"
#include "ancf/io/simulation.hpp"

namespace ancf {

/// The project version ("0.1.0"), compiled into the io layer.
[[nodiscard]] const char* ancf_version();

/// How a run went, beyond what the Scene says.
struct RunRecord {
  std::string scene_path;            ///< as given to the loader
  std::string scene_text;            ///< the exact text that ran (its FNV-1a hash is recorded)
  std::string out_dir;               ///< where the outputs went
  std::string status = "completed";  ///< "completed" or "failed"
  std::string message;               ///< the failure's message ("" when completed)
  double wall_seconds = 0.0;
  SimulationCounters counters;
  SimulationTimings timings;
};

/// The run.json document: ancf_version, scene, scene_name, scene_fnv1a64, status, message,
/// wall_time_s, options (the integrator settings that apply to scene.integrator.kind), counters,
/// time_s and, when `outputs` is given, results (frames, t reached, energies, largest constraint
/// violations).
[[nodiscard]] JsonObject run_json(const Scene& scene, const RunRecord& record,
                                  const RunOutputs* outputs);

}  // namespace ancf
