// A sweep file (docs/sweeps.md): a base scene, the values to vary by their scene key paths, and
// the design that combines them into cases (grid, list, seeded random, Latin hypercube). Each
// case is a list of scene overrides (scene_overrides.hpp), so a case's values are checked by the
// scene rules exactly like values written in the scene file.
#pragma once

#include <string>
#include <vector>

#include "ancf/io/scene_overrides.hpp"

namespace ancf {

/// One varied quantity. Its value v (a number, or TOML text for a list of strings) is written to
/// every key of `keys` as `value` with "{}" replaced by v·scale (numbers) or v (text): e.g. the
/// pole's lateral offset as keys = ["body[1].position", "joint[1].point"],
/// value = "[{}, 0.0, -0.0753]".
struct SweepParameter {
  std::string name;                ///< CSV column
  std::vector<std::string> keys;   ///< scene key paths (scene_overrides.hpp)
  std::string value = "{}";        ///< TOML text template
  double scale = 1.0;              ///< factor from the column's unit to the scene's (numbers)
  std::vector<double> numbers;     ///< grid / list values (numbers)
  std::vector<std::string> texts;  ///< grid / list values given as TOML text strings
  double min = 0.0, max = 0.0;     ///< random / lhs range
};

struct SweepCase {
  long index = 0;                        ///< 0-based case number (the case folder is case-NNNN)
  std::vector<std::string> shown;        ///< the parameter values as they appear in the table
  std::vector<SceneOverride> overrides;  ///< what the case changes in the base scene
};

struct SweepSpec {
  std::string file;           ///< the sweep file
  std::string scene;          ///< base scene path (relative paths are relative to the sweep file)
  std::string out = "sweep";  ///< sweep folder (relative to the working directory)
  std::string design = "grid";
  long samples = 0;                   ///< random / lhs: number of cases
  long seed = 1;                      ///< random / lhs
  double time_limit = 0.0;            ///< per case wall time limit [s] (0: none)
  std::vector<std::string> run_args;  ///< extra `ancf run` arguments of every case
  /// Result columns: keys of the case's results file, "events.lock", "counters.steps", …
  std::vector<std::string> results;
  std::vector<SweepParameter> parameters;
  std::vector<std::string> fixed;  ///< KEY=VALUE overrides applied to every case
  std::vector<SweepCase> cases;
};

/// Read and check a sweep file and expand its design into cases. Throws SceneError naming the
/// file, line and key (unknown keys, wrong types, list parameters of unequal length, a
/// parameter without values). A value the base scene rejects is not an error here: that case
/// fails alone when it runs (status "error" in the table).
[[nodiscard]] SweepSpec load_sweep(const std::string& path);

}  // namespace ancf
