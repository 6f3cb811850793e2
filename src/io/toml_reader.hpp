// Typed, located access to the tables of a parsed scene file. Every accessor marks its key as
// used; finish() then reports any key nobody asked for, so unknown keys are caught at every table
// level. Every failure is a SceneError carrying file, line, key path and what was expected.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "ancf/core/types.hpp"
#include "ancf/io/scene_error.hpp"

namespace ancf::io {

/// Admissible range of a number (always also finite).
enum class Range { any, positive, non_negative, unit_interval };

/// Source name of values set by a scene override (scene_overrides.cpp): they have no line in
/// the file, so errors about them carry line 0 and their key path.
inline constexpr std::string_view kOverrideSource = "<scene override>";
/// False for a region parsed from an override.
[[nodiscard]] bool from_file(const toml::source_region& region);

/// "a string", "an integer", … for messages.
[[nodiscard]] std::string type_name(const toml::node& node);

/// SceneError at `node`'s source position (or line 0 without one).
[[noreturn]] void fail_at(const std::string& file, const toml::node* node, const std::string& key,
                          const std::string& message);

class TableReader {
 public:
  TableReader(const std::string& file, const toml::table& table, std::string path);

  [[nodiscard]] bool has(std::string_view key) const { return table_->contains(key); }
  [[nodiscard]] const std::string& path() const { return path_; }
  [[nodiscard]] const std::string& file() const { return *file_; }
  /// "path.key" (or "key" at the root).
  [[nodiscard]] std::string path_of(std::string_view key) const;
  /// Marks `key` used and returns its node, or nullptr if absent.
  const toml::node* get(std::string_view key);

  double number(std::string_view key, Range range = Range::any);
  double number_or(std::string_view key, double fallback, Range range = Range::any);
  std::optional<double> optional_number(std::string_view key, Range range = Range::any);
  long integer(std::string_view key, long min_value);
  long integer_or(std::string_view key, long fallback, long min_value);
  bool boolean_or(std::string_view key, bool fallback);
  std::string string(std::string_view key);
  std::string string_or(std::string_view key, std::string fallback);
  std::optional<std::string> optional_string(std::string_view key);
  /// A string that must be one of `choices`; `fallback` empty: required.
  std::string choice(std::string_view key, const std::vector<std::string>& choices,
                     const std::string& fallback = {});
  Vec3 vec3(std::string_view key);
  Vec3 vec3_or(std::string_view key, const Vec3& fallback);
  std::optional<Vec3> optional_vec3(std::string_view key);
  /// A non-zero 3-vector, returned normalized (directions and axes).
  Vec3 direction(std::string_view key);
  std::optional<Vec3> optional_direction(std::string_view key);
  /// Array of at least `min_count` 3-vectors.
  std::vector<Vec3> vec3_list(std::string_view key, std::size_t min_count);
  /// [first, count] integer pair.
  std::optional<std::pair<long, long>> optional_pair(std::string_view key);

  TableReader table(std::string_view key);
  std::optional<TableReader> optional_table(std::string_view key);
  /// An array of tables ([[key]]), possibly absent (empty result).
  std::vector<TableReader> tables(std::string_view key);

  /// SceneError at the value of `key` (at this table if the key is absent).
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  /// SceneError at this table, key path = this table's path.
  [[noreturn]] void fail_here(const std::string& message) const;
  /// Line of this table's header (or first key), for later messages about what it built.
  [[nodiscard]] int line() const;
  /// SceneError for every key of this table that no accessor asked for (the first one).
  void finish() const;

 private:
  const toml::node& required(std::string_view key);
  double to_number(const toml::node& n, const std::string& path, Range range) const;
  Vec3 to_vec3(const toml::node& n, const std::string& path) const;

  const std::string* file_;
  const toml::table* table_;
  std::string path_;
  std::set<std::string, std::less<>> used_;
};

}  // namespace ancf::io
