// Sweep files → cases (sweep_design.hpp). Random designs use their own generator (splitmix64,
// Steele, Lea & Flood, OOPSLA 2014) rather than <random>'s distributions, whose output is not
// specified across standard libraries: a seed gives the same cases on every machine.
#include "ancf/io/sweep_design.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numeric>

#include "scene_parts.hpp"
#include "toml_reader.hpp"

namespace ancf {

namespace {

struct SplitMix64 {
  std::uint64_t state;
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform integer in [0, n) (n small: the modulo bias is < n/2⁶⁴).
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

/// Shortest round-trip text of x that TOML reads as a float ("1" would be an integer).
std::string float_text(double x) {
  std::string s = fmt::format("{}", x);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string substitute(const std::string& pattern, const std::string& v) {
  std::string out;
  for (std::size_t k = 0; k < pattern.size(); ++k) {
    if (pattern.compare(k, 2, "{}") == 0) {
      out += v;
      ++k;
    } else {
      out += pattern[k];
    }
  }
  return out;
}

std::vector<std::string> string_list(io::TableReader& t, std::string_view key, bool required) {
  std::vector<std::string> out;
  const toml::node* n = t.get(key);
  if (!n) {
    if (required) t.fail(key, "expected an array of strings");
    return out;
  }
  const toml::array* a = n->as_array();
  if (!a) t.fail(key, "expected an array of strings, got " + io::type_name(*n));
  for (const toml::node& e : *a) {
    if (!e.is_string()) t.fail(key, "expected strings in the array, got " + io::type_name(e));
    out.push_back(*e.value<std::string>());
  }
  return out;
}

SweepParameter read_parameter(io::TableReader& t, const std::string& design) {
  SweepParameter p;
  p.name = t.string("name");
  p.keys = string_list(t, "keys", true);
  if (p.keys.empty()) t.fail("keys", "expected at least one scene key path");
  p.value = t.string_or("value", "{}");
  if (p.value.find("{}") == std::string::npos) t.fail("value", "expected a template with {}");
  p.scale = t.number_or("scale", 1.0);
  if (design == "grid" || design == "list") {
    const toml::node* n = t.get("values");
    const toml::array* a = n ? n->as_array() : nullptr;
    if (!a || a->empty())
      t.fail("values", "expected a non-empty array of numbers or of TOML texts");
    for (const toml::node& e : *a) {
      if (e.is_number())
        p.numbers.push_back(*e.value<double>());
      else if (e.is_string())
        p.texts.push_back(*e.value<std::string>());
      else
        t.fail("values", "expected numbers or strings, got " + io::type_name(e));
    }
    if (!p.numbers.empty() && !p.texts.empty())
      t.fail("values", "expected all numbers or all strings, not both");
  } else {
    p.min = t.number("min");
    p.max = t.number("max");
    if (!(p.max > p.min)) t.fail("max", "expected max > min");
  }
  t.finish();
  return p;
}

std::size_t value_count(const SweepParameter& p) {
  return p.numbers.empty() ? p.texts.size() : p.numbers.size();
}

/// Adds parameter p's value number k (grid/list) or number x (random/lhs) to the case.
void add_value(SweepCase& c, const SweepParameter& p, std::size_t k, double x, bool listed) {
  std::string shown, text;
  if (listed && !p.texts.empty()) {
    shown = text = p.texts[k];
  } else {
    const double v = listed ? p.numbers[k] : x;
    shown = fmt::format("{}", v);
    text = float_text(v * p.scale);
  }
  c.shown.push_back(shown);
  for (const std::string& key : p.keys) c.overrides.push_back({key, substitute(p.value, text)});
}

}  // namespace

SweepSpec load_sweep(const std::string& path) {
  SweepSpec spec;
  spec.file = path;
  const toml::table root = io::parse_scene_text(io::read_scene_file(path), path);
  io::TableReader top(path, root, "");
  io::TableReader s = top.table("sweep");
  spec.scene = s.string("scene");
  if (std::filesystem::path(spec.scene).is_relative())
    spec.scene =
        (std::filesystem::path(path).parent_path() / spec.scene).lexically_normal().string();
  spec.out = s.string_or("out", "sweep");
  spec.design = s.choice("design", {"grid", "list", "random", "lhs"}, "grid");
  const bool sampled = spec.design == "random" || spec.design == "lhs";
  if (sampled) spec.samples = s.integer("samples", 1);
  spec.seed = s.integer_or("seed", 1, 0);
  spec.time_limit = s.number_or("time_limit", 0.0, io::Range::non_negative);
  spec.run_args = string_list(s, "run_args", false);
  spec.results = string_list(s, "results", false);
  spec.fixed = string_list(s, "set", false);
  s.finish();
  for (io::TableReader& p : top.tables("parameter"))
    spec.parameters.push_back(read_parameter(p, spec.design));
  top.finish();
  if (spec.parameters.empty()) top.fail_here("expected at least one [[parameter]]");

  std::vector<SceneOverride> fixed;
  for (const std::string& a : spec.fixed) fixed.push_back(parse_scene_override(a));
  const std::size_t n_par = spec.parameters.size();
  auto new_case = [&] {
    SweepCase c;
    c.index = static_cast<long>(spec.cases.size());
    c.overrides = fixed;
    return c;
  };
  if (spec.design == "grid") {
    // Last parameter fastest, like nested loops in the order the parameters are written.
    std::vector<std::size_t> k(n_par, 0);
    for (;;) {
      SweepCase c = new_case();
      for (std::size_t i = 0; i < n_par; ++i) add_value(c, spec.parameters[i], k[i], 0.0, true);
      spec.cases.push_back(std::move(c));
      std::size_t i = n_par;
      while (i > 0 && ++k[i - 1] == value_count(spec.parameters[i - 1])) k[--i] = 0;
      if (i == 0) break;
    }
  } else if (spec.design == "list") {
    const std::size_t n = value_count(spec.parameters.front());
    for (const SweepParameter& p : spec.parameters)
      if (value_count(p) != n)
        top.fail("parameter",
                 fmt::format("design \"list\": parameter '{}' has {} values, '{}' has {}", p.name,
                             value_count(p), spec.parameters.front().name, n));
    for (std::size_t k = 0; k < n; ++k) {
      SweepCase c = new_case();
      for (const SweepParameter& p : spec.parameters) add_value(c, p, k, 0.0, true);
      spec.cases.push_back(std::move(c));
    }
  } else {
    SplitMix64 rng{static_cast<std::uint64_t>(spec.seed)};
    const auto n = static_cast<std::size_t>(spec.samples);
    // Latin hypercube (McKay, Beckman & Conover 1979): each parameter's range cut into n equal
    // strata, one sample per stratum, strata paired across parameters by random permutations.
    std::vector<std::vector<std::size_t>> strata(n_par, std::vector<std::size_t>(n));
    for (auto& perm : strata) {
      std::iota(perm.begin(), perm.end(), std::size_t{0});
      for (std::size_t i = n; i > 1; --i) std::swap(perm[i - 1], perm[rng.below(i)]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      SweepCase c = new_case();
      for (std::size_t i = 0; i < n_par; ++i) {
        const SweepParameter& p = spec.parameters[i];
        const double u =
            spec.design == "lhs"
                ? (static_cast<double>(strata[i][k]) + rng.uniform()) / static_cast<double>(n)
                : rng.uniform();
        add_value(c, p, 0, p.min + u * (p.max - p.min), false);
      }
      spec.cases.push_back(std::move(c));
    }
  }
  return spec;
}

}  // namespace ancf
