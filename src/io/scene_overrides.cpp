// KEY=VALUE overrides of scene values on the parsed TOML (scene_overrides.hpp); the loader then
// reads the changed table like any other, so there is one set of scene rules.
#include "ancf/io/scene_overrides.hpp"

#include <charconv>
#include <sstream>

#include "scene_parts.hpp"

namespace ancf {

namespace {

/// One step of a key path: a table key, optionally indexed ("cable[2]" → "cable", 2).
struct PathPart {
  std::string key;
  long index = -1;  // −1: not indexed
};

[[noreturn]] void fail(const std::string& path, const SceneOverride& o, const std::string& what) {
  throw SceneError(path, 0, 0, o.key, "override " + o.key + "=" + o.value + ": " + what);
}

std::vector<PathPart> split(const std::string& path, const SceneOverride& o) {
  std::vector<PathPart> parts;
  std::size_t begin = 0;
  for (;;) {
    const std::size_t dot = o.key.find('.', begin);
    std::string item = o.key.substr(begin, dot == std::string::npos ? dot : dot - begin);
    PathPart part;
    if (const auto open = item.find('['); open != std::string::npos) {
      const auto close = item.find(']', open);
      const char* first = item.data() + open + 1;
      const char* last = item.data() + (close == std::string::npos ? item.size() : close);
      const auto [end, error] = std::from_chars(first, last, part.index);
      if (close != item.size() - 1 || error != std::errc() || end != last || part.index < 0)
        fail(path, o, "expected KEY[INDEX] with INDEX ≥ 0 in '" + item + "'");
      item.resize(open);
    }
    if (item.empty()) fail(path, o, "empty key in the path");
    part.key = std::move(item);
    parts.push_back(std::move(part));
    if (dot == std::string::npos) return parts;
    begin = dot + 1;
  }
}

/// The override's value, parsed as the value of key "v" of a one-line table.
toml::table parse_value(const std::string& path, const SceneOverride& o) {
  try {
    const std::string text = "v = " + o.value;
    toml::table parsed = toml::parse(text, io::kOverrideSource);
    if (parsed.size() != 1 || !parsed.contains("v")) fail(path, o, "expected one TOML value");
    return parsed;
  } catch (const toml::parse_error& e) {
    fail(path, o,
         "the value is not TOML (" + std::string(e.description()) +
             "); strings need quotes, e.g. \"ida\"");
  }
}

void apply(toml::table& root, const std::string& path, const SceneOverride& o) {
  const std::vector<PathPart> parts = split(path, o);
  toml::table* table = &root;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const PathPart& part = parts[k];
    const bool last = k + 1 == parts.size();
    if (part.index < 0) {
      if (last) {
        parse_value(path, o).get("v")->visit(
            [&](auto&& value) { table->insert_or_assign(part.key, std::move(value)); });
        return;
      }
      if (!table->contains(part.key)) table->insert_or_assign(part.key, toml::table{});
      table = table->get(part.key)->as_table();
      if (!table) fail(path, o, "'" + part.key + "' is not a table");
      continue;
    }
    toml::array* array = table->get(part.key) ? table->get(part.key)->as_array() : nullptr;
    if (!array) fail(path, o, "'" + part.key + "' is not an array in the scene");
    if (part.index >= static_cast<long>(array->size()))
      fail(path, o,
           "'" + part.key + "' has " + std::to_string(array->size()) + " entries (0 … " +
               std::to_string(static_cast<long>(array->size()) - 1) + ")");
    const auto at = array->begin() + part.index;
    if (last) {
      parse_value(path, o).get("v")->visit(
          [&](auto&& value) { array->replace(at, std::move(value)); });
      return;
    }
    table = at->as_table();
    if (!table)
      fail(path, o, "'" + part.key + "[" + std::to_string(part.index) + "]' is not a table");
  }
}

toml::table overridden(const std::string& text, const std::string& path,
                       const std::vector<SceneOverride>& overrides) {
  toml::table root = io::parse_scene_text(text, path);
  for (const SceneOverride& o : overrides) apply(root, path, o);
  return root;
}

}  // namespace

SceneOverride parse_scene_override(const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("override", 0, 0, "", "expected KEY=VALUE, got '" + assignment + "'");
  return {assignment.substr(0, eq), assignment.substr(eq + 1)};
}

Scene load_scene_from_string(const std::string& text, const std::string& path,
                             const std::vector<SceneOverride>& overrides,
                             const SceneLimits& limits) {
  return io::build_scene(overridden(text, path, overrides), path, limits);
}

Scene load_scene(const std::string& path, const std::vector<SceneOverride>& overrides,
                 const SceneLimits& limits) {
  return load_scene_from_string(io::read_scene_file(path), path, overrides, limits);
}

std::string read_scene_text(const std::string& path) {
  return io::read_scene_file(path);
}

std::string apply_scene_overrides(const std::string& text, const std::string& path,
                                  const std::vector<SceneOverride>& overrides) {
  std::ostringstream s;
  s << overridden(text, path, overrides);
  return s.str();
}

}  // namespace ancf
