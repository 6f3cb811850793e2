#include "toml_reader.hpp"

#include <cmath>
#include <sstream>

namespace ancf::io {

std::string type_name(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

bool from_file(const toml::source_region& r) {
  return !(r.path && *r.path == kOverrideSource);
}

void fail_at(const std::string& file, const toml::node* node, const std::string& key,
             const std::string& message) {
  int line = 0, column = 0;
  if (node && from_file(node->source())) {
    line = static_cast<int>(node->source().begin.line);
    column = static_cast<int>(node->source().begin.column);
  }
  throw SceneError(file, line, column, key, message);
}

namespace {

std::string describe(const toml::node& n) {
  std::ostringstream s;
  if (n.is_integer()) s << *n.value<int64_t>();
  if (n.is_floating_point()) s << *n.value<double>();
  if (n.is_boolean()) s << (*n.value<bool>() ? "true" : "false");
  if (n.is_number() || n.is_boolean()) return s.str();
  if (auto str = n.value<std::string>()) return "\"" + *str + "\"";
  return type_name(n);
}

const char* range_text(Range r) {
  switch (r) {
    case Range::positive:
      return "a number > 0";
    case Range::non_negative:
      return "a number >= 0";
    case Range::unit_interval:
      return "a number in [0, 1]";
    default:
      return "a finite number";
  }
}

}  // namespace

TableReader::TableReader(const std::string& file, const toml::table& table, std::string path)
    : file_(&file), table_(&table), path_(std::move(path)) {}

std::string TableReader::path_of(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

const toml::node* TableReader::get(std::string_view key) {
  const toml::node* n = table_->get(key);
  if (n) used_.insert(std::string(key));
  return n;
}

const toml::node& TableReader::required(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) fail_here("missing required key '" + std::string(key) + "'");
  return *n;
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  const toml::node* n = table_->get(key);
  fail_at(*file_, n ? n : table_, path_of(key), message);
}

void TableReader::fail_here(const std::string& message) const {
  fail_at(*file_, table_, path_, message);
}

int TableReader::line() const {
  return from_file(table_->source()) ? static_cast<int>(table_->source().begin.line) : 0;
}

void TableReader::finish() const {
  for (auto&& [k, v] : *table_) {
    if (used_.count(k.str())) continue;
    const toml::source_region& where = k.source().begin.line ? k.source() : v.source();
    const int line = from_file(where) ? static_cast<int>(where.begin.line) : 0;
    const int column = from_file(where) ? static_cast<int>(where.begin.column) : 0;
    throw SceneError(*file_, line, column, path_of(k.str()),
                     "unknown key '" + std::string(k.str()) + "'" +
                         (path_.empty() ? std::string() : " in " + path_) +
                         " (see docs/scenes.md for the keys allowed here)");
  }
}

double TableReader::to_number(const toml::node& n, const std::string& path, Range range) const {
  if (!n.is_number())
    fail_at(*file_, &n, path,
            std::string("expected ") + range_text(range) + ", got " + type_name(n));
  const double x = *n.value<double>();
  bool ok = std::isfinite(x);
  if (range == Range::positive) ok = ok && x > 0.0;
  if (range == Range::non_negative) ok = ok && x >= 0.0;
  if (range == Range::unit_interval) ok = ok && x >= 0.0 && x <= 1.0;
  if (!ok)
    fail_at(*file_, &n, path,
            std::string("expected ") + range_text(range) + ", got " + describe(n));
  return x;
}

double TableReader::number(std::string_view key, Range range) {
  return to_number(required(key), path_of(key), range);
}

double TableReader::number_or(std::string_view key, double fallback, Range range) {
  const auto x = optional_number(key, range);
  return x ? *x : fallback;
}

std::optional<double> TableReader::optional_number(std::string_view key, Range range) {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  return to_number(*n, path_of(key), range);
}

long TableReader::integer(std::string_view key, long min_value) {
  const toml::node& n = required(key);
  if (!n.is_integer())
    fail(key, "expected an integer >= " + std::to_string(min_value) + ", got " + type_name(n));
  const long x = static_cast<long>(*n.value<int64_t>());
  if (x < min_value)
    fail(key, "expected an integer >= " + std::to_string(min_value) + ", got " + std::to_string(x));
  return x;
}

long TableReader::integer_or(std::string_view key, long fallback, long min_value) {
  if (!has(key)) return fallback;
  return integer(key, min_value);
}

bool TableReader::boolean_or(std::string_view key, bool fallback) {
  const toml::node* n = get(key);
  if (!n) return fallback;
  if (!n->is_boolean()) fail(key, "expected true or false, got " + type_name(*n));
  return *n->value<bool>();
}

std::string TableReader::string(std::string_view key) {
  const toml::node& n = required(key);
  if (!n.is_string()) fail(key, "expected a string, got " + type_name(n));
  const std::string s = *n.value<std::string>();
  if (s.empty()) fail(key, "expected a non-empty string");
  return s;
}

std::string TableReader::string_or(std::string_view key, std::string fallback) {
  const auto s = optional_string(key);
  return s ? *s : fallback;
}

std::optional<std::string> TableReader::optional_string(std::string_view key) {
  if (!has(key)) return std::nullopt;
  return string(key);
}

std::string TableReader::choice(std::string_view key, const std::vector<std::string>& choices,
                                const std::string& fallback) {
  if (!fallback.empty() && !has(key)) return fallback;
  const std::string s = string(key);
  std::string list;
  for (const std::string& c : choices) {
    if (c == s) return s;
    list += (list.empty() ? "" : " | ") + ("\"" + c + "\"");
  }
  fail(key, "expected one of " + list + ", got \"" + s + "\"");
}

Vec3 TableReader::to_vec3(const toml::node& n, const std::string& path) const {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 3)
    fail_at(*file_, &n, path,
            "expected an array of 3 numbers, got " +
                (a ? "an array of " + std::to_string(a->size()) : type_name(n)));
  Vec3 v;
  for (int i = 0; i < 3; ++i)
    v[i] = to_number(*a->get(static_cast<std::size_t>(i)), path + "[" + std::to_string(i) + "]",
                     Range::any);
  return v;
}

Vec3 TableReader::vec3(std::string_view key) {
  return to_vec3(required(key), path_of(key));
}

Vec3 TableReader::vec3_or(std::string_view key, const Vec3& fallback) {
  const auto v = optional_vec3(key);
  return v ? *v : fallback;
}

std::optional<Vec3> TableReader::optional_vec3(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  return to_vec3(*n, path_of(key));
}

Vec3 TableReader::direction(std::string_view key) {
  const Vec3 v = vec3(key);
  if (!(v.norm() > 0.0)) fail(key, "expected a non-zero direction vector, got [0, 0, 0]");
  return v.normalized();
}

std::optional<Vec3> TableReader::optional_direction(std::string_view key) {
  if (!has(key)) return std::nullopt;
  return direction(key);
}

std::vector<Vec3> TableReader::vec3_list(std::string_view key, std::size_t min_count) {
  const toml::node& n = required(key);
  const toml::array* a = n.as_array();
  if (!a || a->size() < min_count)
    fail(key, "expected an array of at least " + std::to_string(min_count) +
                  " points [x, y, z], got " +
                  (a ? "an array of " + std::to_string(a->size()) : type_name(n)));
  std::vector<Vec3> out;
  for (std::size_t i = 0; i < a->size(); ++i)
    out.push_back(to_vec3(*a->get(i), path_of(key) + "[" + std::to_string(i) + "]"));
  return out;
}

std::optional<std::pair<long, long>> TableReader::optional_pair(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) return std::nullopt;
  const toml::array* a = n->as_array();
  if (!a || a->size() != 2 || !a->get(0)->is_integer() || !a->get(1)->is_integer())
    fail(key, "expected [first, count], two integers");
  return std::pair<long, long>(static_cast<long>(*a->get(0)->value<int64_t>()),
                               static_cast<long>(*a->get(1)->value<int64_t>()));
}

TableReader TableReader::table(std::string_view key) {
  const toml::node& n = required(key);
  if (!n.is_table()) fail(key, "expected a table, got " + type_name(n));
  return TableReader(*file_, *n.as_table(), path_of(key));
}

std::optional<TableReader> TableReader::optional_table(std::string_view key) {
  if (!has(key)) return std::nullopt;
  return table(key);
}

std::vector<TableReader> TableReader::tables(std::string_view key) {
  std::vector<TableReader> out;
  const toml::node* n = get(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (a && a->empty()) return out;
  if (!a || !a->is_array_of_tables())
    fail(key, "expected an array of tables ([[" + path_of(key) + "]]), got " + type_name(*n));
  for (std::size_t i = 0; i < a->size(); ++i)
    out.emplace_back(*file_, *a->get(i)->as_table(), path_of(key) + "[" + std::to_string(i) + "]");
  return out;
}

}  // namespace ancf::io
