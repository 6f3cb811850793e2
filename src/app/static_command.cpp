// `ancf static`: the static equilibrium of a scene under its loads and gravity, with the outputs
// of `ancf run` for one frame (probes.csv row, a VTK frame in a .pvd series, run.json). A solver
// failure (an increment that cannot be completed, a singular problem) is printed with the
// solver's report (load factor, iteration, worst row or singular direction), recorded in run.json
// with the last converged state written as the frame; the exit status is then 2.
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <optional>

#include "commands.hpp"
#include "ancf/io/run_outputs.hpp"
#include "scene_statics.hpp"

namespace ancf::app {

int static_command(const StaticOptions& options) {
  Scene scene;
  const std::string text = read_text(options.scene_path);
  try {
    scene = load_scene(options.scene_path);
  } catch (const ModelError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  const auto start = std::chrono::steady_clock::now();
  std::string status = "completed", message;
  SceneStatics statics;
  std::optional<RunOutputs> out;
  try {
    out.emplace(scene, options.out_dir);
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  try {
    solve_scene_statics(scene, options.settings, statics);
  } catch (const SolverError& e) {
    status = "failed";
    message = e.what();
    fmt::print(stderr, "static solve failed: {}\nthe last converged state is written to {}\n",
               message, options.out_dir);
  }
  out->record(statics.state);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  const StaticSolverStatistics& st = statics.statistics;
  JsonObject opts, counts, results;
  add_static_json(options.settings, st, opts, counts, results);
  opts.set("out", options.out_dir);
  results.set("frames", out->frames())
      .set("energy", out->final_energy())
      .set("max_position_violation", out->max_position_violation());
  JsonObject meta = run_json_header(scene, text, "static", status, message, wall);
  meta.set("options", opts).set("counters", counts).set("results", results);
  write_run_json(options.out_dir, meta);

  if (!options.quiet) {
    fmt::print("{} static equilibrium {}: written to {}\n", scene.name, status, options.out_dir);
    fmt::print("  {:<34} {:>12}\n", "load steps (after cuts)", st.load_steps);
    fmt::print("  {:<34} {:>12}\n", "step cuts", st.step_cuts);
    fmt::print("  {:<34} {:>12}\n", "Newton iterations", st.newton_iterations);
    fmt::print("  {:<34} {:>12.4e}\n", "residual |R|_inf [N, m]", st.residual_norm);
    fmt::print("  {:<34} {:>12.4e}\n", "max |Phi|", out->max_position_violation());
    fmt::print("  {:<34} {:>12.4e}\n", "smallest singular value (scaled)",
               st.smallest_singular_value);
    fmt::print("  {:<34} {:>12.4e}\n", "potential energy [J]", out->final_energy());
    fmt::print("  {:<34} {:>12.4f}\n", "wall time [s]", wall);
    if (!st.singular_direction.empty())
      fmt::print(
          "  warning: the tangent is singular at the solution (the equilibrium is not isolated);"
          " zero-stiffness direction moves {}\n",
          st.singular_direction);
  }
  return status == "completed" ? 0 : 2;
}

}  // namespace ancf::app
