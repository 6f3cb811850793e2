// Numerical stability stress study (studies/README.md, "ancf-study-stability"): drive both
// integrators into the regimes where they are most likely to fail and record how each run ends.
//
// Groups of cases (scenes in stress_scenes.hpp):
//  * stiffness: Gerstmayr–Shabana pendulum (REFERENCES §7) over f, i.e. EA L²/EI = 4π·1e6/f²;
//  * wire: a steel wire pendulum (E = 2.1e11 Pa, d = 1 mm, L = 0.1 m) down to 1 mm elements;
//  * snap: a mass on a slack cable that falls and jerks the cable taut;
//  * long: 10⁶ generalized-α steps of a 4-element pendulum (energy and constraint drift bounded,
//    wall time per tenth of the run constant);
//  * rho: generalized-α ρ∞ = 0, 0.2, …, 1 in both formulations (index 3 refuses ρ∞ = 1); IDA's
//    counterpart of the dissipation knob, the BDF order limit 1 … 5;
//  * large_h: generalized-α steps up to 0.1 s, IDA rtol up to 0.3.
// Every case runs in a forked child under a wall-time limit (time_limited_run.hpp) and ends as
// success, refused (by design), clean stop (a SolverError), time limit, or blow-up (non-finite
// state, energy gain above half the energy scale, crash, or an exception that is not a
// SolverError).
//
// Usage: ancf-study-stability [output directory = out/stability_stress] [--time-limit s = 20]
//        [--long-time-limit s = 120] [--long-output-interval s = 1] [--energy-growth-limit x = 0.5]
//        [--group name]...
//        (default: all groups)
// Writes <out>/cases.csv (one row per case), <out>/long_run_wall.csv (wall time per tenth of the
// long runs), <out>/long_run_series.csv (their energy error and |Φ| every 1 s) and <out>/run.json
// (options, outcome counts). Exit status 0, or 3 if any case blew up.
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "ancf/io/run_metadata.hpp"
#include "stress_case.hpp"
#include "time_limited_run.hpp"

using namespace ancf;
using namespace ancf::studies;

namespace {

struct StressCase {
  std::string group, scene, parameter_name;
  double parameter = 0.0;
  std::string integrator;  // label: "GA-i3", "GA-i2", "IDA-o5", …
  std::function<StressScene()> make_scene;
  StressRun run;
};

IntegratorSettings genalpha(double h, double rho, bool index2, double t_end) {
  IntegratorSettings s;
  s.kind = IntegratorKind::genalpha;
  s.step = h;
  s.rho_infinity = rho;
  s.stabilized_index2 = index2;
  s.t_end = t_end;
  return s;
}

IntegratorSettings ida(double rtol, int max_order, double t_end) {
  IntegratorSettings s;
  s.kind = IntegratorKind::ida;
  s.rtol = rtol;
  s.max_order = max_order;
  s.t_end = t_end;
  return s;
}

std::string ga_label(bool index2) {
  return index2 ? "GA-i2" : "GA-i3";
}

// The four integrator settings every scene of the first groups runs with: generalized-α at step
// h in both formulations (ρ∞ = 0.8), IDA at rtol 1e-4 with BDF order ≤ 5 (the default) and ≤ 2
// (A-stable, see the ida-rtol study). rtol 1e-4, not tighter: on these undamped stiff cables
// IDA's steps are pinned by stability (order 5) or accuracy (order 2) near 1e-6 s, and tighter
// tolerances only run into the time limit.
void add_all_integrators(std::vector<StressCase>& cases, StressCase base, double h, double t_end,
                         double output_interval) {
  base.run.output_interval = output_interval;
  for (const bool index2 : {false, true}) {
    base.integrator = ga_label(index2);
    base.run.settings = genalpha(h, 0.8, index2, t_end);
    cases.push_back(base);
  }
  for (const int order : {5, 2}) {
    base.integrator = fmt::format("IDA-o{}", order);
    base.run.settings = ida(1e-4, order, t_end);
    cases.push_back(base);
  }
}

std::vector<StressCase> build_cases(double long_output_interval) {
  std::vector<StressCase> cases;
  for (const double f : {1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0}) {
    StressCase c{"stiffness", "gerstmayr-shabana-16",
                 "f",         f,
                 "",          [f] { return gerstmayr_shabana_scene(f, 16); },
                 {}};
    add_all_integrators(cases, c, 1e-3, 1.0, 0.01);
  }
  for (const Index elements : {10, 25, 50, 100}) {
    StressCase c{"wire",
                 "steel-wire-0.1m",
                 "element_length_mm",
                 100.0 / elements,
                 "",
                 [elements] { return steel_wire_scene(elements); },
                 {}};
    add_all_integrators(cases, c, 1e-4, 0.1, 1e-3);
  }
  for (const double mass : {0.1, 1.0, 10.0}) {
    StressCase c{"snap",
                 "slack-snap-20",
                 "tip_mass_kg",
                 mass,
                 "",
                 [mass] { return slack_snap_scene(mass, 20); },
                 {}};
    add_all_integrators(cases, c, 1e-3, 1.0, 1e-3);
  }
  for (const bool index2 : {false, true}) {
    // 10⁶ steps of h = 1e-3 s: 1000 s ≈ 600 swings of the 1 m pendulum.
    StressCase c{"long", "benchmark-pendulum-4", "steps",
                 1e6,    ga_label(index2),       [] { return benchmark_pendulum_scene(4); },
                 {}};
    c.run.settings = genalpha(1e-3, index2 ? 1.0 : 0.8, index2, 1000.0);
    c.run.output_interval = long_output_interval;
    cases.push_back(c);
  }
  for (const bool index2 : {false, true})
    for (int k = 0; k <= 5; ++k) {
      const double rho = 0.2 * k;
      StressCase c{"rho", "gerstmayr-shabana-16", "rho_inf",
                   rho,   ga_label(index2),       [] { return gerstmayr_shabana_scene(5.0, 16); },
                   {}};
      c.run.settings = genalpha(1e-3, rho, index2, 2.0);
      cases.push_back(c);
    }
  for (int order = 1; order <= 5; ++order) {
    StressCase c{"rho",       "gerstmayr-shabana-16",
                 "max_order", static_cast<double>(order),
                 "IDA",       [] { return gerstmayr_shabana_scene(5.0, 16); },
                 {}};
    c.run.settings = ida(1e-6, order, 2.0);
    cases.push_back(c);
  }
  for (const bool index2 : {false, true})
    for (const double h : {1e-3, 5e-3, 1e-2, 2e-2, 5e-2, 1e-1}) {
      StressCase c{"large_h", "benchmark-pendulum-10", "h",
                   h,         ga_label(index2),        [] { return benchmark_pendulum_scene(10); },
                   {}};
      c.run.settings = genalpha(h, 0.8, index2, 2.0);
      c.run.output_interval = 0.1;  // a multiple of every h: outputs do not shorten steps
      cases.push_back(c);
    }
  for (const int order : {5, 2})
    for (const double rtol : {1e-3, 1e-2, 3e-2, 1e-1, 3e-1}) {
      StressCase c{
          "large_h", "benchmark-pendulum-10",       "rtol",
          rtol,      fmt::format("IDA-o{}", order), [] { return benchmark_pendulum_scene(10); },
          {}};
      c.run.settings = ida(rtol, order, 2.0);
      c.run.output_interval = 0.1;
      cases.push_back(c);
    }
  return cases;
}

// Outcome class and a short verdict of one case.
std::string classify(const TimeLimitedResult<CaseReport>& r) {
  switch (r.end) {
    case ChildEnd::time_limit:
      return "time limit";
    case ChildEnd::signalled:
      return fmt::format("blow-up: crash (signal {})", r.signal);
    case ChildEnd::exception_escaped:
      return "blow-up: exception escaped";
    case ChildEnd::returned:
      break;
  }
  switch (r.report.end) {
    case CaseEnd::success:
      return "success";
    case CaseEnd::refused:
      return "refused";
    case CaseEnd::solver_error:
      return "clean stop";
    case CaseEnd::nonfinite_state:
      return "blow-up: NaN/Inf";
    case CaseEnd::energy_growth:
      return "blow-up: energy growth";
    case CaseEnd::other_exception:
      return "blow-up: exception";
    case CaseEnd::running:
      break;
  }
  return "blow-up: ended without a report";
}

std::string csv_quoted(const std::string& s) {
  std::string out = "\"";
  for (const char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

}  // namespace

int main(int argc, char** argv) {
  std::filesystem::path out_dir = "out/stability_stress";
  double time_limit = 20.0;
  double long_time_limit = 120.0;  // the 10⁶-step runs
  double growth_limit = StressRun{}.energy_growth_limit;
  double long_output_interval = 1.0;  // [s] outputs of the 10⁶-step runs
  std::vector<std::string> groups;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--time-limit" && i + 1 < argc)
      time_limit = std::atof(argv[++i]);
    else if (a == "--long-time-limit" && i + 1 < argc)
      long_time_limit = std::atof(argv[++i]);
    else if (a == "--long-output-interval" && i + 1 < argc)
      long_output_interval = std::atof(argv[++i]);
    else if (a == "--energy-growth-limit" && i + 1 < argc)
      growth_limit = std::atof(argv[++i]);
    else if (a == "--group" && i + 1 < argc)
      groups.push_back(argv[++i]);
    else if (!a.empty() && a[0] != '-')
      out_dir = a;
    else {
      fmt::print(stderr,
                 "usage: {} [out dir] [--time-limit s] [--long-time-limit s] "
                 "[--energy-growth-limit x] [--group name]...\n",
                 argv[0]);
      return 2;
    }
  }
  std::filesystem::create_directories(out_dir);
  std::vector<StressCase> cases = build_cases(long_output_interval);
  if (!groups.empty())
    std::erase_if(cases, [&](const StressCase& c) {
      return std::find(groups.begin(), groups.end(), c.group) == groups.end();
    });

  auto csv = fmt::output_file((out_dir / "cases.csv").string());
  csv.print(
      "group,scene,parameter_name,parameter,integrator,step_or_rtol,outcome,t_reached,t_end,"
      "energy_error_max,energy_growth_max,energy_error_final,position_drift_max,"
      "velocity_drift_max,multiplier_max,steps,iterations,factorizations,failures,halvings,wall_s,"
      "message\n");
  auto wall_csv = fmt::output_file((out_dir / "long_run_wall.csv").string());
  wall_csv.print("integrator,tenth,t_end_of_tenth,wall_s\n");
  auto series_csv = fmt::output_file((out_dir / "long_run_series.csv").string());
  series_csv.print("integrator,t,energy_error,position_drift\n");
  std::map<std::string, long> outcome_counts;
  fmt::print("{:<9} {:<22} {:>14} {:<7} {:>9} {:<24} {:>9} {:>9} {:>9} {:>8} {:>7} {:>7}\n",
             "group", "scene", "parameter", "integr.", "h/rtol", "outcome", "t", "|dE|max",
             "|Phi|max", "steps", "facts", "wall s");
  for (StressCase& c : cases) {
    c.run.energy_growth_limit = growth_limit;
    const auto result = run_with_time_limit<CaseReport>(
        [&](CaseReport& report) { run_stress_case(c.make_scene, c.run, report); },
        c.group == "long" ? long_time_limit : time_limit);
    const CaseReport& r = result.report;
    const std::string outcome = classify(result);
    ++outcome_counts[outcome];
    const IntegratorSettings& s = c.run.settings;
    const double knob = s.kind == IntegratorKind::ida ? s.rtol : s.step;
    fmt::print(
        "{:<9} {:<22} {:>14} {:<7} {:>9.2g} {:<24} {:>9.4g} {:>9.2e} {:>9.2e} {:>8} {:>7} "
        "{:>7.2f}\n",
        c.group, c.scene, fmt::format("{}={:g}", c.parameter_name, c.parameter), c.integrator, knob,
        outcome, r.t_reached, r.energy_error_max, r.position_drift_max, r.steps, r.factorizations,
        result.wall_seconds);
    if (r.message[0] != '\0') fmt::print("          -> {}\n", r.message);
    std::fflush(stdout);
    csv.print(
        "{},{},{},{:g},{},{:g},{},{:.9g},{:g},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{},{},{}"
        ",{},"
        "{:.3f},{}\n",
        c.group, c.scene, c.parameter_name, c.parameter, c.integrator, knob, outcome, r.t_reached,
        s.t_end, r.energy_error_max, r.energy_growth_max, r.energy_error_final,
        r.position_drift_max, r.velocity_drift_max, r.multiplier_max, r.steps, r.iterations,
        r.factorizations, r.failures, r.halvings, result.wall_seconds, csv_quoted(r.message));
    if (c.group == "long")
      for (int k = 1; k < kWallMarks; ++k)
        if (r.wall_marks[k] > 0.0)
          wall_csv.print("{},{},{:g},{:.4f}\n", c.integrator, k, s.t_end * k / (kWallMarks - 1),
                         r.wall_marks[k] - r.wall_marks[k - 1]);
    if (c.group == "long")
      for (int k = 0; k < r.series_count; ++k)
        series_csv.print("{},{:g},{:.6e},{:.6e}\n", c.integrator, r.series_t[k], r.series_energy[k],
                         r.series_position_drift[k]);
  }
  csv.close();
  wall_csv.close();
  series_csv.close();

  JsonObject options, counts;
  options.set("time_limit_s", time_limit);
  options.set("cases", static_cast<long>(cases.size()));
  options.set("long_run_time_limit_s", long_time_limit);
  options.set("energy_growth_limit", growth_limit);
  options.set("long_run_output_interval_s", long_output_interval);
  for (const auto& [name, n] : outcome_counts) counts.set(name, n);
  JsonObject run;
  run.set("study", "ancf-study-stability");
  run.set("options", options);
  run.set("outcomes", counts);
  auto json = fmt::output_file((out_dir / "run.json").string());
  json.print("{}\n", run.text());
  fmt::print("\noutcomes:");
  for (const auto& [name, n] : outcome_counts) fmt::print("  {}: {}", name, n);
  fmt::print("\nwrote {}/cases.csv, long_run_wall.csv, run.json\n", out_dir.string());
  // Exit status 3 if any case blew up, so that a smoke run in the test suite fails on a blow-up.
  for (const auto& [name, n] : outcome_counts)
    if (name.starts_with("blow-up") && n > 0) return 3;
  return 0;
}
