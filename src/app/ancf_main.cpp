// The `ancf` command: check, info, run, static and modes of a scene file (docs/scenes.md,
// docs/statics_and_modes.md).
#include <CLI/CLI.hpp>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ancf: ANCF cable and rigid-body multibody dynamics"};
  app.require_subcommand(1);
  std::string scene;

  double check_max_steps = ancf::kDefaultMaxSteps;
  CLI::App* check = app.add_subcommand("check", "parse and validate a scene (exit 1 on error)");
  check->add_option("SCENE", scene, "scene file (TOML)")->required();
  check
      ->add_option("--max-steps", check_max_steps,
                   "refuse settings that imply more steps (default 1e7)")
      ->check(CLI::PositiveNumber);
  CLI::App* info =
      app.add_subcommand("info", "print unknowns, constraints, nonzeros, contact pairs");
  info->add_option("SCENE", scene, "scene file (TOML)")->required();

  ancf::app::RunOptions run_options;
  CLI::App* run = app.add_subcommand("run", "integrate a scene and write its outputs");
  run->add_option("SCENE", run_options.scene_path, "scene file (TOML)")->required();
  run->add_option("--integrator", run_options.integrator, "override [integrator] method")
      ->check(CLI::IsMember({"ida", "genalpha"}));
  run->add_option("--rtol", run_options.rtol, "relative tolerance")->check(CLI::PositiveNumber);
  run->add_option("--contact-pattern", run_options.contact_pattern,
                  "contact coupling blocks: near (default) or all candidates (the first design)")
      ->check(CLI::IsMember({"near", "all"}));
  run->add_option("--step", run_options.step, "generalized-alpha step / IDA max step [s]")
      ->check(CLI::PositiveNumber);
  run->add_option("--t-end", run_options.t_end, "end time [s]")->check(CLI::PositiveNumber);
  run->add_flag("--error-control", run_options.error_control,
                "generalized-alpha: error-controlled variable step (step = first step)");
  run->add_option("--error-rtol", run_options.error_rtol,
                  "generalized-alpha local error relative tolerance")
      ->check(CLI::PositiveNumber);
  run->add_option("--error-atol", run_options.error_atol,
                  "generalized-alpha local error absolute tolerance [m]")
      ->check(CLI::PositiveNumber);
  run->add_option("--h-min", run_options.h_min, "generalized-alpha smallest step [s]")
      ->check(CLI::PositiveNumber);
  run->add_option("--h-max", run_options.h_max, "generalized-alpha largest step [s] (0: none)")
      ->check(CLI::NonNegativeNumber);
  run->add_option("--out", run_options.out_dir, "output directory (created; default: out)");
  run->add_flag("--progress", run_options.progress,
                "progress bar even if stderr is not a terminal");
  run->add_flag("--quiet", run_options.quiet, "no summary table");
  run->add_option("--max-steps", run_options.max_steps,
                  "refuse runs that imply more steps (default 1e7)")
      ->check(CLI::PositiveNumber);

  run->add_option("--set", run_options.set,
                  "scene value KEY=VALUE by its key path, e.g. body[1].rotation.angle=0.1 "
                  "(repeatable; docs/scenes.md)");
  run->add_flag("--capture-events", run_options.capture_events,
                "detect the capture example's events (shared/CAPTURE.md) into run.json");
  run->add_option("--results", run_options.results_file,
                  "also write a flat TOML summary (status, counters, events) to this file");

  ancf::app::SweepOptions sweep_options;
  CLI::App* sweep =
      app.add_subcommand("sweep", "run a scene over a design of varied values (docs/sweeps.md)");
  sweep->add_option("SWEEP", sweep_options.sweep_path, "sweep file (TOML)")->required();
  sweep->add_option("-j,--workers", sweep_options.workers, "worker processes (default: the cores)")
      ->check(CLI::PositiveNumber);
  sweep->add_option("--out", sweep_options.out_dir,
                    "sweep folder (default: the file's [sweep] out)");
  sweep->add_option("--ancf", sweep_options.ancf,
                    "ancf executable for the cases (default: this one)");
  sweep->add_flag("--mpi", sweep_options.mpi,
                  "distribute over MPI ranks (automatic under mpirun/srun when built with MPI)");
  sweep->add_flag("--restart", sweep_options.restart,
                  "discard the results of an earlier run of this sweep instead of resuming it");


  auto add_static_options = [](CLI::App* command, ancf::app::StaticSettings& settings) {
    command
        ->add_option("--load-steps", settings.load_steps,
                     "equal load increments from 0 to the full load (default 10)")
        ->check(CLI::PositiveNumber);
    command
        ->add_option("--max-iterations", settings.max_iterations,
                     "Newton iterations per load increment (default 30)")
        ->check(CLI::PositiveNumber);
    command
        ->add_option("--tolerance", settings.increment_tolerance,
                     "Newton increment tolerance relative to max(1, |q|_inf) (default 1e-11)")
        ->check(CLI::PositiveNumber);
  };
  ancf::app::StaticOptions static_options;
  CLI::App* statics =
      app.add_subcommand("static", "solve the static equilibrium and write its outputs");
  statics->add_option("SCENE", static_options.scene_path, "scene file (TOML)")->required();
  add_static_options(statics, static_options.settings);
  statics->add_option("--out", static_options.out_dir, "output directory (created; default: out)");
  statics->add_flag("--quiet", static_options.quiet, "no summary table");

  ancf::app::ModesOptions modes_options;
  std::string component = "all";
  CLI::App* modes =
      app.add_subcommand("modes", "natural frequencies and mode shapes (small models)");
  modes->add_option("SCENE", modes_options.scene_path, "scene file (TOML)")->required();
  modes->add_option("--count", modes_options.count, "lowest modes reported (default 10)")
      ->check(CLI::PositiveNumber);
  modes->add_flag("--static", modes_options.about_static,
                  "about the static equilibrium under the scene's loads (default: initial state)");
  add_static_options(modes, modes_options.statics);
  modes
      ->add_option("--component", component,
                   "only the x, y or z components of every coordinate block (default all)")
      ->check(CLI::IsMember({"all", "x", "y", "z"}));
  modes
      ->add_option("--amplitude", modes_options.amplitude,
                   "largest displacement in the mode animations [m] (default: extent/10)")
      ->check(CLI::PositiveNumber);
  modes->add_option("--frames", modes_options.frames, "frames per period (default 24)")
      ->check(CLI::Range(2, 10000));
  modes->add_flag("!--no-vtk", modes_options.vtk, "no mode-shape series");
  modes
      ->add_option("--max-coordinates", modes_options.max_coordinates,
                   "refuse larger models (default 3000; dense eigen-analysis)")
      ->check(CLI::PositiveNumber);
  modes->add_option("--out", modes_options.out_dir, "output directory (created; default: out)");
  modes->add_flag("--quiet", modes_options.quiet, "no frequency table");

  CLI11_PARSE(app, argc, argv);
  if (*sweep) return ancf::app::sweep_command(sweep_options, argv[0]);
  if (*statics) return ancf::app::static_command(static_options);
  if (*modes) {
    modes_options.component = component == "all" ? -1 : component[0] - 'x';
    return ancf::app::modes_command(modes_options);
  }
  if (*check) return ancf::app::check_command(scene, check_max_steps);
  if (*info) return ancf::app::info_command(scene);
  return ancf::app::run_command(run_options);
}
