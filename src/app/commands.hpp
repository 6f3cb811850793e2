// Subcommands of the `ancf` executable. Each returns the process exit status and prints its own
// errors (scene errors on stderr, exit 1).
#pragma once

#include <string>
#include <vector>

#include "ancf/io/run_limits.hpp"
#include "scene_statics.hpp"

namespace ancf::app {

/// `ancf check SCENE`: parse, validate and finalize; prints "OK" or the located error. Also
/// refuses a scene whose own [integrator]/[output] settings imply more than `max_steps` steps.
int check_command(const std::string& scene_path, double max_steps = kDefaultMaxSteps);
/// `ancf info SCENE`: unknowns, constraints, multipliers, pattern nonzeros, contact pairs.
int info_command(const std::string& scene_path);

/// Command-line overrides of the scene's [integrator] and [output] for `ancf run`.
struct RunOptions {
  std::string scene_path;
  std::string integrator;       ///< "" (scene's), "ida" or "genalpha"
  double rtol = 0.0;            ///< 0: scene's
  double step = 0.0;            ///< 0: scene's (genalpha step; IDA max step)
  double t_end = 0.0;           ///< 0: scene's
  std::string contact_pattern;  ///< "" (scene's), "near" or "all"
  /// Generalized-α error-controlled stepping and its controller (0: scene's), docs/scenes.md.
  bool error_control = false;
  double error_rtol = 0.0, error_atol = 0.0, h_min = 0.0, h_max = -1.0;
  std::string out_dir = "out";
  bool progress = false;  ///< force the progress bar even when stderr is not a terminal
  bool quiet = false;     ///< no summary table
  double max_steps = kDefaultMaxSteps;  ///< refuse runs that imply more steps (run_limits.hpp)
  /// Scene value overrides KEY=VALUE (scene_overrides.hpp), applied before the scene is built.
  std::vector<std::string> set;
  /// Also detect the capture example's events (capture_events.hpp) and write them to run.json
  /// and to the results file.
  bool capture_events = false;
  /// "" or a file to write a flat TOML summary to (status, message, wall time, counters,
  /// events): what `ancf sweep` reads back from each case.
  std::string results_file;
};
/// `ancf run SCENE …`: integrate and write probes.csv, VTK frames, run.json into out_dir.
int run_command(const RunOptions& options);

/// `ancf sweep SWEEP.toml …` (docs/sweeps.md): many runs of one scene with varied values.
struct SweepOptions {
  std::string sweep_path;
  long workers = 0;      ///< worker processes (0: from the cores)
  std::string ancf;      ///< the ancf executable to run each case with ("": this one)
  bool mpi = false;      ///< force MPI mode (otherwise detected from the launcher's variables)
  std::string out_dir;   ///< "" : the sweep file's [sweep] out
  bool restart = false;  ///< discard finished cases instead of resuming
};
int sweep_command(const SweepOptions& options, const char* argv0);

/// `ancf static SCENE …`: the static equilibrium under the scene's loads and gravity; writes
/// probes.csv (one row), one VTK frame with its .pvd series and run.json into out_dir.
struct StaticOptions {
  std::string scene_path;
  StaticSettings settings;
  std::string out_dir = "out";
  bool quiet = false;
};
int static_command(const StaticOptions& options);

/// `ancf modes SCENE …`: natural frequencies (modes.csv) and mode-shape series
/// (modes/mode_NNN.pvd) about the initial state or, with about_static, the static equilibrium.
struct ModesOptions {
  std::string scene_path;
  long count = 10;            ///< lowest modes reported
  bool about_static = false;  ///< linearise about the static equilibrium (else the initial state)
  StaticSettings statics;     ///< its solve
  int component = -1;      ///< −1: all; 0, 1, 2: x, y or z components only (ModalAnalysisOptions)
  double amplitude = 0.0;  ///< [m] largest displacement in the animations; 0: extent/10
  int frames = 24;         ///< frames per period in each mode's series
  bool vtk = true;         ///< write the mode-shape series
  double max_coordinates = 3000;  ///< refuse larger models (dense O(n³) eigen-analysis)
  std::string out_dir = "out";
  bool quiet = false;
};
int modes_command(const ModesOptions& options);

}  // namespace ancf::app
