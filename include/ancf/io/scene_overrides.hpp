// Overrides of scene values, KEY=VALUE, applied to the parsed scene file before anything is read
// from it: the scene rules (types, ranges, unknown keys, names) then check an overridden value
// exactly like one written in the file. Used by the Python module and by ancf-capture --set.
#pragma once

#include <string>
#include <vector>

#include "ancf/io/scene.hpp"

namespace ancf {

/// `key` is the dotted path of the value from the file's root, array entries counted from 0 as
/// in SceneError key paths: "integrator.genalpha.step", "cable[0].section.EA",
/// "output.probe[1].node". `value` is TOML value text: 5e-4, "ida" (with the quotes), true,
/// [0.0, 0.0, -9.81], { EA = 1e6 }. Tables missing along the path are created (so a key the
/// file leaves at its default can be set); an array entry beyond the array's end, or a path
/// through a value that is not a table, is a SceneError naming the override.
struct SceneOverride {
  std::string key;
  std::string value;
};

/// "KEY=VALUE" → SceneOverride; throws SceneError (file "override") without '=' or key.
[[nodiscard]] SceneOverride parse_scene_override(const std::string& assignment);

/// load_scene_from_string with `overrides` applied in order to the parsed text. Values set by
/// an override have no line in the file: their errors carry line 0 and the key path.
[[nodiscard]] Scene load_scene_from_string(const std::string& text, const std::string& path,
                                           const std::vector<SceneOverride>& overrides,
                                           const SceneLimits& limits = {});
/// The same from a file (the checks of load_scene apply to `path`).
[[nodiscard]] Scene load_scene(const std::string& path, const std::vector<SceneOverride>& overrides,
                               const SceneLimits& limits = {});

/// The text of the scene file `path`, with load_scene's checks (exists, a regular file).
[[nodiscard]] std::string read_scene_text(const std::string& path);

/// The scene text with `overrides` applied, as TOML (toml++'s formatting; comments dropped), for
/// recording exactly what ran. Throws SceneError like load_scene_from_string.
[[nodiscard]] std::string apply_scene_overrides(const std::string& text, const std::string& path,
                                                const std::vector<SceneOverride>& overrides);

}  // namespace ancf
