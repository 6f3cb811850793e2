#include "ancf/io/run_metadata.hpp"

#include <fmt/format.h>

#include <cmath>

namespace ancf {

std::uint64_t fnv1a64(std::string_view bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned>(c));
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

JsonObject& JsonObject::set(const std::string& key, const std::string& value) {
  members_.emplace_back(key, json_string(value));
  return *this;
}
JsonObject& JsonObject::set(const std::string& key, double value) {
  // JSON has no inf/nan: write null for them. Finite values at full precision (the shortest
  // decimal that reads back to the same double).
  members_.emplace_back(key, std::isfinite(value) ? fmt::format("{}", value) : "null");
  return *this;
}
JsonObject& JsonObject::set(const std::string& key, long value) {
  members_.emplace_back(key, std::to_string(value));
  return *this;
}
JsonObject& JsonObject::set(const std::string& key, bool value) {
  members_.emplace_back(key, value ? "true" : "false");
  return *this;
}
JsonObject& JsonObject::set(const std::string& key, const JsonObject& value) {
  members_.emplace_back(key, value.text(0));
  return *this;
}

std::string JsonObject::text(int indent) const {
  const std::string pad(static_cast<std::size_t>(indent) + 2, ' ');
  std::string s = "{\n";
  for (std::size_t i = 0; i < members_.size(); ++i) {
    // Nested objects were rendered at indent 0: shift their inner lines to this depth.
    std::string value;
    for (char c : members_[i].second) value += c == '\n' ? "\n" + pad : std::string(1, c);
    s += pad + json_string(members_[i].first) + ": " + value +
         (i + 1 < members_.size() ? ",\n" : "\n");
  }
  return s + std::string(static_cast<std::size_t>(indent), ' ') + "}";
}

}  // namespace ancf
