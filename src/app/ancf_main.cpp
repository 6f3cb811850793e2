// The `ancf` command: check, info and run a scene file (docs/scenes.md).
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

  CLI11_PARSE(app, argc, argv);
  if (*sweep) return ancf::app::sweep_command(sweep_options, argv[0]);
  if (*check) return ancf::app::check_command(scene, check_max_steps);
  if (*info) return ancf::app::info_command(scene);
  return ancf::app::run_command(run_options);
}
