// run.json: what produced a set of outputs (scene and its hash, options, version, counters,
// outcome), written as a small flat JSON document without a JSON library.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace ancf {

/// 64-bit FNV-1a hash of `bytes` (identifies the exact scene text a run used; not cryptographic).
[[nodiscard]] std::uint64_t fnv1a64(std::string_view bytes);

/// An ordered JSON object of string, number and nested-object members.
class JsonObject {
 public:
  JsonObject& set(const std::string& key, const std::string& value);
  JsonObject& set(const std::string& key, const char* value) {
    return set(key, std::string(value));
  }
  JsonObject& set(const std::string& key, double value);
  JsonObject& set(const std::string& key, long value);
  JsonObject& set(const std::string& key, bool value);
  JsonObject& set(const std::string& key, const JsonObject& value);
  /// Pretty-printed text with `indent` leading spaces on nested lines.
  [[nodiscard]] std::string text(int indent = 0) const;

 private:
  std::vector<std::pair<std::string, std::string>> members_;  // key, encoded value
};

/// JSON string literal of `s` (quotes, escapes).
[[nodiscard]] std::string json_string(std::string_view s);

}  // namespace ancf
