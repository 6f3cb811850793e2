// `ancf run`: integrate a scene with IDA (GGL index 2) or generalized-α and write its outputs.
// A solver failure keeps everything written so far, is printed with the integrator's own report
// (time, step, worst component) and recorded in run.json; the exit status is then 2.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <toml++/toml.h>
#include <numbers>

#include "ancf/io/run_outputs.hpp"
#include "ancf/io/run_record.hpp"
#include "ancf/io/scene_overrides.hpp"
#include "ancf/io/simulation.hpp"
#include "ancf/scenes/capture_events.hpp"
#include "commands.hpp"
#include "progress_bar.hpp"

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

constexpr double kDeg = std::numbers::pi / 180.0;

/// The capture events as flat name → value (angles in degrees, NaN: did not happen).
std::vector<std::pair<std::string, double>> event_values(const CaptureEvents& ev) {
  std::vector<std::pair<std::string, double>> v;
  for (int i = 0; i < 3; ++i)
    v.emplace_back(fmt::format("first_contact_rope_{}", i + 1), ev.first_contact[i]);
  v.emplace_back("first_rope", static_cast<double>(ev.first_rope + 1));
  v.emplace_back("all_three", ev.all_three);
  v.emplace_back("stall", ev.stall);
  v.emplace_back("lock", ev.lock);
  v.emplace_back("final_tilt_deg", ev.final_tilt / kDeg);
  v.emplace_back("final_lateral_offset_m", ev.final_lateral_offset);
  v.emplace_back("ring_angle_at_stall_deg", ev.ring_angle_at_stall / kDeg);
  for (int i = 0; i < 3; ++i)
    v.emplace_back(fmt::format("tension_at_lock_{}", i + 1), ev.tension_at_lock[i]);
  v.emplace_back("peak_contact_force", ev.peak_contact_force);
  return v;
}

/// The flat summary `ancf sweep` reads back: written last, so its presence means the run ended.
void write_results(const std::string& file, const std::string& status, const std::string& message,
                   double wall, double t_reached, const Counters& counters,
                   const std::vector<std::pair<std::string, double>>& events) {
  toml::table root, counts, evs;
  root.insert("status", status);
  root.insert("message", message);
  root.insert("wall_seconds", wall);
  root.insert("t_reached", t_reached);
  for (const auto& [name, value] : counters) counts.insert(name, static_cast<int64_t>(value));
  for (const auto& [name, value] : events) evs.insert(name, value);
  root.insert("counters", std::move(counts));
  root.insert("events", std::move(evs));
  if (const auto dir = std::filesystem::path(file).parent_path(); !dir.empty())
    std::filesystem::create_directories(dir);
  const std::string tmp = file + ".tmp";
  std::ofstream(tmp) << root << '\n';
  std::rename(tmp.c_str(), file.c_str());  // atomic: a reader sees all of it or nothing
}

}  // namespace

int run_command(const RunOptions& options) {
  Scene scene;
  const std::string text = read_text(options.scene_path);
  try {
    std::vector<SceneOverride> overrides;
    for (const std::string& a : options.set) overrides.push_back(parse_scene_override(a));
    scene = load_scene(options.scene_path, overrides);
    apply_overrides(options, scene.integrator);
    require_runnable(scene.integrator, scene.output.interval, options.max_steps);
  } catch (const ModelError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    if (!options.results_file.empty())
      write_results(options.results_file, "error", e.what(), 0.0, 0.0, {}, {});
    return 1;
  }
  const IntegratorSettings& s = scene.integrator;
  const bool ida = s.kind == IntegratorKind::ida;
  const auto start = std::chrono::steady_clock::now();
  std::string status = "completed", message;
  Counters counters;
  SimulationTimings timings;
  std::optional<RunOutputs> out;
  std::optional<CaptureObserver> capture;
  try {
    if (options.capture_events) capture.emplace(scene.model);
    out.emplace(scene, options.out_dir);
    ProgressBar bar(s.t_end, options.progress || isatty(fileno(stderr)));
    try {
      SimulationHooks hooks;
      hooks.output = [&](const SystemState& state) {
        out->record(state);
        if (capture) capture->record(state);
      };
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

  RunRecord record{.scene_path = options.scene_path,
                   .scene_text = text,
                   .out_dir = options.out_dir,
                   .status = status,
                   .message = message,
                   .wall_seconds = wall,
                   .counters = counters,
                   .timings = timings};
  JsonObject meta = run_json(scene, record, out ? &*out : nullptr);
  std::vector<std::pair<std::string, double>> events;
  if (capture) {
    events = event_values(capture->events());
    JsonObject e;
    for (const auto& [name, value] : events) e.set(name, value);
    meta.set("capture_events", e);
  }
  if (out) write_run_json(options.out_dir, meta);
  if (!options.results_file.empty())
    write_results(options.results_file, status, message, wall, out ? out->last_time() : 0.0,
                  counters, events);

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
