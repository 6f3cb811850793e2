// The `ancf` command: check, info and run a scene file (docs/scenes.md).
#include <CLI/CLI.hpp>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ancf: ANCF cable and rigid-body multibody dynamics"};
  app.require_subcommand(1);
  std::string scene;

  CLI::App* check = app.add_subcommand("check", "parse and validate a scene (exit 1 on error)");
  check->add_option("SCENE", scene, "scene file (TOML)")->required();
  CLI::App* info =
      app.add_subcommand("info", "print unknowns, constraints, nonzeros, contact pairs");
  info->add_option("SCENE", scene, "scene file (TOML)")->required();

  CLI11_PARSE(app, argc, argv);
  if (*check) return ancf::app::check_command(scene);
  if (*info) return ancf::app::info_command(scene);
  return 1;
}
