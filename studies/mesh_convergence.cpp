// Mesh convergence of the cubic Hermite ANCF cable against closed-form and high-accuracy
// references (REFERENCES §1–§4), for element counts N = 2, 4, …, max:
//
//  * cantilever_elastica: tip displacement (Δx, Δy) of the extensible elastica of §2 (Green /
//    Gerstmayr–Shabana only: it is that element's continuum limit; 12-digit reference);
//  * cantilever_mattiasson: tip (u, w, rotation) of Mattiasson's inextensible elastica, k = 3
//    (§1, 8 digits), both strain measures, EA L²/EI = --mattiasson-slenderness (the O(P/EA)
//    extensibility error is a floor under the discretisation error);
//  * catenary: mid-span sag and support tension of Irvine's elastic catenary (§3, EA = 1e3 N,
//    elastic line: Irvine's strain measure);
//  * beam, bar, string: natural frequencies of the linearisation at the equilibrium (dense
//    K φ = ω² M φ on the constraint null space, system/modal_analysis.hpp) of a clamped–free
//    Euler–Bernoulli beam (y bending, modes 1–4), a fixed–free axial bar (x, modes 1–3) and a taut
//    string stretched by λ = 1.01 (y, modes 1–3), both strain measures (§4).
//
// Expected orders (Strang & Fix, An Analysis of the Finite Element Method, 1973, §6.3 and the
// nodal superconvergence of §1.3/Douglas & Dupont): for elements complete to degree k − 1 = 3 and a
// problem of order 2m, eigenvalues converge as h^{2(k−m)} and nodal values of smooth solutions as
// h^{2(k−m)}: bending (m = 2) h⁴, axial/string problems (m = 1) h⁶. Frequencies ω = √(ω²) have
// the same relative order.
//
// Output (directory, default out/mesh_convergence): errors.csv (one row per problem, quantity,
// strain measure and N: value, reference, relative error, local order log2(e_{N/2}/e_N), Newton
// iterations), orders.csv (least-squares slope of log e against log h over the finest
// --fit-points meshes before the round-off floor, see fit_order, and the expected order), run.json.
//
// Usage: ancf-study-mesh-convergence [out dir] [--max-elements 256] [--fit-points 3]
//        [--error-floor 1e-13] [--mattiasson-slenderness 1e9]
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "ancf/core/fitted_order.hpp"
#include "ancf/io/run_metadata.hpp"
#include "ancf/scenes/cantilever_references.hpp"
#include "ancf/scenes/elastic_catenary.hpp"
#include "ancf/scenes/vibration_scenes.hpp"
#include "ancf/system/modal_analysis.hpp"

using namespace ancf;

namespace {

struct Options {
  std::string out = "out/mesh_convergence";
  Index max_elements = 256;
  int fit_points = 3;
  double error_floor = 1e-13;
  double mattiasson_slenderness = 1e9;  // EA L² / EI
};

struct Sample {
  std::string problem, quantity, strain;
  Index elements = 0;
  double value = 0.0, reference = 0.0;
  int newton_iterations = 0;
  double reference_rounding = 0.0;  ///< relative rounding of the reference's published digits
  [[nodiscard]] double error() const { return std::abs(value / reference - 1.0); }
};

// One convergence series: problem × quantity × strain measure.
struct SeriesKey {
  std::string problem, quantity, strain;
  auto operator<=>(const SeriesKey&) const = default;
};

const char* strain_name(StrainMeasure s) {
  return s == StrainMeasure::green_lagrange ? "green" : "elastic_line";
}

constexpr StrainMeasure kStrains[] = {StrainMeasure::green_lagrange, StrainMeasure::elastic_line};

// Expected order from Strang & Fix (see the header comment): h⁴ for the bending problems, h⁶ for
// the second-order (axial, string) ones.
int expected_order(const std::string& problem) {
  return problem == "catenary" || problem == "bar" || problem == "string" ? 6 : 4;
}

long g_newton_iterations = 0;  // over all static solves (each solve once)

void add_cantilever(std::vector<Sample>& out, Index n, const Options& o) {
  const CantileverTip e = solve_cantilever(extensible_elastica_cantilever(n), 4);
  g_newton_iterations += e.stats.newton_iterations;
  // The references are given to 12 (elastica) and 8 (Mattiasson) decimal places.
  const double rounding12 = 0.5e-12, rounding8 = 0.5e-8;
  out.push_back({"cantilever_elastica", "tip_dx", "green", n, e.displacement.x(), kElasticaTipDx,
                 e.stats.newton_iterations, rounding12 / std::abs(kElasticaTipDx)});
  out.push_back({"cantilever_elastica", "tip_dy", "green", n, e.displacement.y(), kElasticaTipDy,
                 e.stats.newton_iterations, rounding12 / std::abs(kElasticaTipDy)});
  const MattiassonTip& ref = kMattiassonTable[2];  // k = 3
  for (const StrainMeasure strain : kStrains) {
    CantileverSpec spec = mattiasson_cantilever(ref, n, o.mattiasson_slenderness);
    spec.strain = strain;
    const CantileverTip t = solve_cantilever(spec, 10);
    const int it = t.stats.newton_iterations;
    g_newton_iterations += it;
    out.push_back({"cantilever_mattiasson", "tip_u", strain_name(strain), n, -t.displacement.x(),
                   ref.u, it, rounding8 / ref.u});
    out.push_back({"cantilever_mattiasson", "tip_w", strain_name(strain), n, -t.displacement.y(),
                   ref.w, it, rounding8 / ref.w});
    out.push_back({"cantilever_mattiasson", "tip_rotation", strain_name(strain), n, t.rotation,
                   ref.rotation, it, rounding8 / ref.rotation});
  }
}

void add_catenary(std::vector<Sample>& out, Index n) {
  const ElasticCatenarySpec spec;
  const CatenaryValues ref = irvine_catenary(spec);
  const CatenarySolution s = solve_elastic_catenary(spec, n);
  const int it = s.stats.newton_iterations;
  g_newton_iterations += it;
  out.push_back({"catenary", "sag", "elastic_line", n, s.sag, ref.sag, it});
  out.push_back(
      {"catenary", "support_tension", "elastic_line", n, s.tension_left, ref.support_tension, it});
}

template <class Exact>
void add_modes(std::vector<Sample>& out, const char* problem, const Model& model, int component,
               int modes, StrainMeasure strain, Index n, Exact exact) {
  const NaturalModes m = natural_modes_at_initial_equilibrium(model, {.component = component});
  for (int k = 1; k <= modes && k <= m.omega_squared.size(); ++k)
    out.push_back(
        {problem, fmt::format("omega_{}", k), strain_name(strain), n, m.omega(k - 1), exact(k), 0});
}

void add_frequencies(std::vector<Sample>& out, Index n) {
  constexpr double kStretch = 1.01;
  for (const StrainMeasure strain : kStrains) {
    UniformCableSpec beam{.length = 1.0,
                          .axial_stiffness = 1e4,
                          .bending_stiffness = 1.0,
                          .mass_per_length = 1.0,
                          .elements = n,
                          .strain = strain};
    add_modes(out, "beam", clamped_free_beam_model(beam), 1, 4, strain, n,
              [&](int k) { return clamped_free_beam_frequency(beam, k); });
    UniformCableSpec bar{.length = 1.0,
                         .axial_stiffness = 1e4,
                         .bending_stiffness = 0.0,
                         .mass_per_length = 0.1,
                         .elements = n,
                         .strain = strain};
    add_modes(out, "bar", fixed_free_bar_model(bar), 0, 3, strain, n,
              [&](int k) { return fixed_free_bar_frequency(bar, k); });
    add_modes(out, "string", taut_string_model(bar, kStretch), 1, 3, strain, n,
              [&](int k) { return taut_string_frequency(bar, kStretch, k); });
  }
}

struct Fit {
  double order = std::nan("");
  Index first = 0, last = 0;  // element counts of the fitted range
  int points = 0;
};

// Least-squares slope of log e against log h = log(L/N) over the asymptotic range: the finest
// `fit_points` meshes before the round-off floor whose error is above `error_floor` and ten times
// the rounding of the reference's digits. The floor starts at the first refinement whose local
// order log2(e_{N/2}/e_N) is below 1 (the error stalls), or, at round-off level (e < 1e-9; every
// floor seen here is below that), more than 1 below the previous refinement's: that mesh and
// every finer one are left out.
Fit fit_order(const std::vector<const Sample*>& series, const Options& o) {
  std::size_t end = series.size();  // one past the last usable mesh
  double previous_local = std::nan("");
  for (std::size_t i = 1; i < series.size(); ++i) {
    const double local = std::log2(series[i - 1]->error() / series[i]->error());
    if (local < 1.0 || (series[i]->error() < 1e-9 && local < previous_local - 1.0)) {
      end = i;
      break;
    }
    previous_local = local;
  }
  std::vector<const Sample*> used;
  for (std::size_t i = end; i-- > 0 && static_cast<int>(used.size()) < o.fit_points;)
    if (series[i]->error() > std::max(o.error_floor, 10.0 * series[i]->reference_rounding))
      used.push_back(series[i]);
  Fit f;
  f.points = static_cast<int>(used.size());
  if (f.points < 3) return f;
  std::vector<double> h, e;
  for (const Sample* s : used)
    h.push_back(1.0 / static_cast<double>(s->elements)), e.push_back(s->error());
  f.order = fitted_order(h, e);
  f.first = used.back()->elements;
  f.last = used.front()->elements;
  return f;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--max-elements")
      o.max_elements = std::stol(value());
    else if (a == "--fit-points")
      o.fit_points = std::stoi(value());
    else if (a == "--error-floor")
      o.error_floor = std::stod(value());
    else if (a == "--mattiasson-slenderness")
      o.mattiasson_slenderness = std::stod(value());
    else if (!a.starts_with("--"))
      o.out = a;
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (o.max_elements < 2 || o.fit_points < 3)
    throw std::invalid_argument("need max >= 2, fit >= 3");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  try {
    o = parse(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr,
               "{}\nusage: {} [out dir] [--max-elements N] [--fit-points K] [--error-floor E] "
               "[--mattiasson-slenderness S]\n",
               e.what(), argv[0]);
    return 1;
  }
  std::filesystem::create_directories(o.out);
  const auto start = std::chrono::steady_clock::now();
  std::vector<Sample> samples;
  std::map<std::string, double> seconds;  // wall time per problem family
  for (Index n = 2; n <= o.max_elements; n *= 2) {
    auto timed = [&](const char* family, auto&& add) {
      const auto t0 = std::chrono::steady_clock::now();
      add();
      seconds[family] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };
    timed("cantilever", [&] { add_cantilever(samples, n, o); });
    timed("catenary", [&] { add_catenary(samples, n); });
    timed("frequencies", [&] { add_frequencies(samples, n); });
    fmt::print("N = {:3d} done ({:.1f} s)\n", n,
               std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }

  std::map<SeriesKey, std::vector<const Sample*>> series;
  for (const Sample& s : samples) series[{s.problem, s.quantity, s.strain}].push_back(&s);

  auto errors = fmt::output_file(o.out + "/errors.csv");
  errors.print(
      "problem,quantity,strain,elements,h_over_L,value,reference,rel_error,local_order,"
      "newton_iterations\n");
  for (const auto& [key, list] : series)
    for (std::size_t i = 0; i < list.size(); ++i) {
      const Sample& s = *list[i];
      const double local = i > 0 ? std::log2(list[i - 1]->error() / s.error()) : std::nan("");
      errors.print("{},{},{},{},{:.6e},{:.15e},{:.15e},{:.6e},{:.3f},{}\n", s.problem, s.quantity,
                   s.strain, s.elements, 1.0 / static_cast<double>(s.elements), s.value,
                   s.reference, s.error(), local, s.newton_iterations);
    }
  errors.close();

  auto orders = fmt::output_file(o.out + "/orders.csv");
  orders.print(
      "problem,quantity,strain,fitted_order,expected_order,fit_first_elements,"
      "fit_last_elements,fit_points,finest_rel_error\n");
  fmt::print("\n{:22s} {:16s} {:12s} {:>8s} {:>8s} {:>11s} {:>12s}\n", "problem", "quantity",
             "strain", "order", "expected", "fit range", "finest error");
  for (const auto& [key, list] : series) {
    const Fit f = fit_order(list, o);
    orders.print("{},{},{},{:.3f},{},{},{},{},{:.3e}\n", key.problem, key.quantity, key.strain,
                 f.order, expected_order(key.problem), f.first, f.last, f.points,
                 list.back()->error());
    fmt::print("{:22s} {:16s} {:12s} {:8.2f} {:8d} {:>5d}-{:<5d} {:12.2e}\n", key.problem,
               key.quantity, key.strain, f.order, expected_order(key.problem), f.first, f.last,
               list.back()->error());
  }
  orders.close();

  JsonObject options, counters, timing, meta;
  options.set("max_elements", static_cast<long>(o.max_elements))
      .set("fit_points", static_cast<long>(o.fit_points))
      .set("error_floor", o.error_floor)
      .set("mattiasson_slenderness", o.mattiasson_slenderness)
      .set("mattiasson_k", kMattiassonTable[2].k);
  counters.set("samples", static_cast<long>(samples.size()))
      .set("series", static_cast<long>(series.size()))
      .set("static_newton_iterations", g_newton_iterations);
  for (const auto& [family, s] : seconds) timing.set(family + "_s", s);
  meta.set("study", "mesh_convergence")
      .set("options", options)
      .set("counters", counters)
      .set("wall_time", timing);
  std::ofstream(o.out + "/run.json") << meta.text() << '\n';
  fmt::print("\nwrote {}/errors.csv, orders.csv, run.json\n", o.out);
  return 0;
}
