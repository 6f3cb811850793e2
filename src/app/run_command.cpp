// `ancf run`: integrate a scene with IDA (GGL index 2) or generalized-α and write its outputs.
// A solver failure keeps everything written so far, is printed with the integrator's own report
// (time, step, worst component) and recorded in run.json; the exit status is then 2.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>

#include "ancf/io/run_metadata.hpp"
#include "ancf/io/simulation.hpp"
#include "commands.hpp"
#include "progress_bar.hpp"
#include "run_outputs.hpp"

namespace ancf::app {

namespace {

using Counters = SimulationCounters;

void apply_overrides(const RunOptions& o, IntegratorSettings& s) {
  if (o.integrator == "ida") s.kind = IntegratorKind::ida;
  if (o.integrator == "genalpha") s.kind = IntegratorKind::genalpha;
  if (o.rtol > 0.0) s.rtol = o.rtol;
  if (o.t_end > 0.0) s.t_end = o.t_end;
  if (o.step > 0.0) (s.kind == IntegratorKind::ida ? s.max_step : s.step) = o.step;
  if (o.contact_pattern == "near") s.contact_pattern = ContactPatternPolicy::near;
  if (o.contact_pattern == "all") s.contact_pattern = ContactPatternPolicy::all;
  if (o.error_control) s.ga_error_controlled = true;
  if (o.error_rtol > 0.0) s.ga_controller.rtol = o.error_rtol;
  if (o.error_atol > 0.0) s.ga_controller.atol = o.error_atol;
  if (o.h_min > 0.0) s.ga_controller.h_min = o.h_min;
  if (o.h_max >= 0.0) s.ga_controller.h_max = o.h_max;
}

}  // namespace

int run_command(const RunOptions& options) {
  Scene scene;
  const std::string text = read_text(options.scene_path);
  try {
    scene = load_scene(options.scene_path);
    apply_overrides(options, scene.integrator);
    if (scene.integrator.kind == IntegratorKind::genalpha &&
        scene.integrator.step > scene.integrator.t_end)
      throw ModelError("--step exceeds t_end");
    const StepControllerOptions& c = scene.integrator.ga_controller;
    if (c.h_max > 0.0 && c.h_max < c.h_min)
      throw ModelError("generalized-alpha h_max (--h-max) is below h_min (--h-min)");
    require_bounded_steps(scene.integrator, scene.output.interval, options.max_steps);
  } catch (const ModelError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  const IntegratorSettings& s = scene.integrator;
  const bool ida = s.kind == IntegratorKind::ida;
  const auto start = std::chrono::steady_clock::now();
  std::string status = "completed", message;
  Counters counters;
  SimulationTimings timings;
  std::optional<RunOutputs> out;
  try {
    out.emplace(scene, options.out_dir);
    ProgressBar bar(s.t_end, options.progress || isatty(fileno(stderr)));
    try {
      SimulationHooks hooks;
      hooks.output = [&](const SystemState& state) { out->record(state); };
      hooks.progress = [&](double t) { bar.update(t); };
      simulate(scene.model, s, output_times(scene.output.interval, s.t_end), hooks, counters,
               timings);
    } catch (...) {
      bar.finish();
      throw;
    }
    bar.finish();
  } catch (const std::exception& e) {
    status = "failed";
    message = e.what();
    fmt::print(stderr, "\nrun failed: {}\n", message);
    if (out)
      fmt::print(stderr, "outputs up to t = {:.6g} s are kept in {}\n", out->last_time(),
                 options.out_dir);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  JsonObject opts, counts, results, times;
  opts.set("integrator", ida ? "ida" : "genalpha").set("rtol", s.rtol).set("t_end", s.t_end);
  opts.set("contact_pattern", s.contact_pattern == ContactPatternPolicy::all ? "all" : "near");
  if (ida)
    opts.set("max_step", s.max_step).set("max_order", static_cast<long>(s.max_order));
  else
    opts.set("step", s.step)
        .set("rho_infinity", s.rho_infinity)
        .set("formulation", s.stabilized_index2 ? "stabilized_index2" : "index3")
        .set("stepping", s.ga_error_controlled ? "error_controlled" : "fixed");
  if (!ida && s.ga_error_controlled)
    opts.set("error_rtol", s.ga_controller.rtol)
        .set("error_atol", s.ga_controller.atol)
        .set("h_min", s.ga_controller.h_min)
        .set("h_max", s.ga_controller.h_max);
  opts.set("output_interval", scene.output.interval).set("out", options.out_dir);
  for (const auto& [name, value] : counters) counts.set(name, value);
  for (const auto& [name, value] : timings) times.set(name, value);
  if (out)
    results.set("frames", out->frames())
        .set("t_reached", out->last_time())
        .set("initial_energy", out->initial_energy())
        .set("final_energy", out->final_energy())
        .set("max_energy_change", out->max_energy_change())
        .set("max_position_violation", out->max_position_violation())
        .set("max_velocity_violation", out->max_velocity_violation());
  JsonObject meta = run_json_header(scene, text, "run", status, message, wall);
  meta.set("options", opts).set("counters", counts).set("time_s", times).set("results", results);
  if (out) write_run_json(options.out_dir, meta);

  if (!options.quiet && out) {
    fmt::print("\n{} ({}) {}: t = {:.6g} / {:.6g} s, {} frames in {}\n", scene.name,
               ida ? "IDA" : "generalized-alpha", status, out->last_time(), s.t_end, out->frames(),
               options.out_dir);
    for (const auto& [name, value] : counters) fmt::print("  {:<28} {:>12}\n", name, value);
    fmt::print("  {:<28} {:>12.4f}\n", "wall time [s]", wall);
    // Shares of the integrator's wall time (the first timing).
    if (!timings.empty() && timings.front().second > 0.0)
      for (std::size_t k = 1; k < timings.size(); ++k)
        fmt::print("    {:<44} {:>6.1f} %\n", timings[k].first,
                   100.0 * timings[k].second / timings.front().second);
    fmt::print("  {:<28} {:>12.4e}\n", "energy E(0) [J]", out->initial_energy());
    fmt::print("  {:<28} {:>12.4e}\n", "max |E - E(0)| [J]", out->max_energy_change());
    fmt::print("  {:<28} {:>12.4e}\n", "max |Phi|", out->max_position_violation());
    fmt::print("  {:<28} {:>12.4e}\n", "max |Phi_q v + Phi_t|", out->max_velocity_violation());
  }
  return status == "completed" ? 0 : 2;
}

}  // namespace ancf::app
