// The capture scene in the scaling study (ancf-study-scaling --capture 12,24,48): the cost per
// step of the paper's example at 12/24/48 elements per rope, from t = 0 to --capture-t-end (the
// slack phase up to ~4 s, contact after), with the scene's own integrator settings. Each case
// runs in a forked child (child_process.hpp) like the other cases.
#pragma once

#include <fmt/format.h>

#include <toml++/toml.h>
#include <chrono>
#include <sstream>
#include <string>
#include <vector>

#include "ancf/io/scene.hpp"
#include "ancf/io/simulation.hpp"
#include "capture_mesh.hpp"
#include "child_process.hpp"

namespace ancf::studies {

/// One capture case; trivially copyable (it crosses the pipe from the child).
struct CaptureScalingResult {
  long unknowns = 0, steps = 0, newton_iterations = 0, factorizations = 0, pattern_changes = 0;
  long largest_nonzeros = 0;
  double wall_seconds = 0.0;  ///< integration only (outputs at the scene's interval included)
  double factor_seconds = 0.0, element_seconds = 0.0, contact_seconds = 0.0;
};

inline long counter_of(const SimulationCounters& c, const char* name) {
  for (const auto& [key, value] : c)
    if (key == name) return value;
  return 0;
}
inline double timing_of(const SimulationTimings& t, const char* name) {
  for (const auto& [key, value] : t)
    if (key == name) return value;
  return 0.0;
}

/// The capture scene at `elements` per rope integrated with `integrator` ("genalpha"/"ida") to
/// t_end, in this process.
inline CaptureScalingResult measure_capture(const std::string& scene_path, long elements,
                                            const std::string& integrator, double t_end) {
  toml::table root = toml::parse_file(scene_path);
  set_capture_rope_elements(root, elements);
  toml::table& settings = *root["integrator"].as_table();
  settings.insert_or_assign("method", integrator);
  settings.insert_or_assign("t_end", t_end);
  if (integrator == "ida") {
    if (!settings.contains("ida")) settings.insert_or_assign("ida", toml::table{});
    settings.at("ida").as_table()->insert_or_assign("slope_scale", "position_equivalent");
  }
  std::ostringstream text;
  text << root;
  const Scene scene = load_scene_from_string(text.str(), scene_path);
  SimulationCounters counters;
  SimulationTimings timings;
  simulate(scene.model, scene.integrator, output_times(scene.output.interval, t_end), {}, counters,
           timings);
  CaptureScalingResult r;
  r.unknowns = static_cast<long>(scene.model.system_size());
  r.steps = counter_of(counters, "steps");
  r.newton_iterations = counter_of(counters, "Newton iterations");
  r.factorizations =
      counter_of(counters, integrator == "ida" ? "linear solver setups" : "factorizations");
  r.pattern_changes = counter_of(counters, "pattern changes");
  r.largest_nonzeros = counter_of(counters, "pattern non-zeros (largest)");
  r.wall_seconds = timing_of(timings, "wall");
  r.factor_seconds = timing_of(timings, "factorization");
  r.element_seconds = timing_of(timings, "element kernels");
  r.contact_seconds = timing_of(timings, "contact");
  return r;
}

/// Runs every (integrator, elements) case in a child; prints a table and writes capture.csv.
/// Returns false if a case failed.
inline bool capture_scaling(const std::string& scene_path, const std::vector<long>& elements,
                            const std::vector<std::string>& integrators, double t_end,
                            const std::string& out_dir) {
  std::ofstream csv(out_dir + "/capture.csv");
  csv << "integrator,elements_per_rope,unknowns,t_end,steps,newton_iterations,factorizations,"
         "pattern_changes,largest_nonzeros,wall_seconds,seconds_per_step,factor_share,"
         "element_share,contact_share\n";
  fmt::print(
      "\ncapture scene to t = {} s (scene settings; IDA with position-equivalent slope "
      "scales)\n{:>8} {:>6} {:>8} {:>7} {:>7} {:>7} {:>8} {:>9} {:>10} {:>7}\n",
      t_end, "method", "N/rope", "unknowns", "steps", "newton", "fact", "patterns", "nnz max",
      "ms/step", "wall s");
  bool ok = true;
  for (const std::string& integrator : integrators)
    for (const long n : elements) {
      const auto outcome = run_in_child<CaptureScalingResult>(
          [&] { return measure_capture(scene_path, n, integrator, t_end); });
      if (!outcome.ok) {
        fmt::print(stderr, "capture {} {} elements: {}\n", integrator, n, outcome.error);
        ok = false;
        continue;
      }
      const CaptureScalingResult& r = outcome.result;
      const double per_step = r.wall_seconds / static_cast<double>(std::max(r.steps, 1L));
      fmt::print("{:>8} {:6} {:8} {:7} {:7} {:7} {:8} {:9} {:10.4f} {:7.2f}\n", integrator, n,
                 r.unknowns, r.steps, r.newton_iterations, r.factorizations, r.pattern_changes,
                 r.largest_nonzeros, 1e3 * per_step, r.wall_seconds);
      csv << fmt::format("{},{},{},{},{},{},{},{},{},{:.6e},{:.6e},{:.4f},{:.4f},{:.4f}\n",
                         integrator, n, r.unknowns, t_end, r.steps, r.newton_iterations,
                         r.factorizations, r.pattern_changes, r.largest_nonzeros, r.wall_seconds,
                         per_step, r.factor_seconds / r.wall_seconds,
                         r.element_seconds / r.wall_seconds, r.contact_seconds / r.wall_seconds);
    }
  return ok;
}

}  // namespace ancf::studies
