// Scaling study (studies/README.md, "Cost per step against problem size"): does the cost of a
// time step grow linearly with the number of cable elements (one string of N elements) and with
// the number of cables (K strings of 100 elements), for generalized-α (MultibodyProblem) and IDA
// (GglProblem)? Scene: scaling_scene.hpp (same physics per element at every size).
//
// Every case runs in a forked child (child_process.hpp) so its peak memory can be read with
// wait4; the child builds the model, then integrates `repeats` times from the initial state
// (fresh problem and integrator each time) until at least --min-seconds of integration were
// timed, and reports the fastest and the median wall time of one integration (set-up, consistent
// initial values and KLU analysis excluded) with the counters of the last one (they are
// deterministic). The time per step is that of the fastest repeat (the least disturbed by other
// jobs on a shared machine); the median is in the CSV beside it.
//
// Usage: ancf-study-scaling [--out DIR] [--steps N] [--ida-t-end T] [--ida-rtol R]
//                           [--ida-max-order K] [--min-seconds S] [--max-elements N]
//                           [--integrator genalpha|ida|both] [--ida-model-scales]
//                           [--elements 10,30,...] [--cables 1,2,...]
//                           [--capture 12,24,48 [--capture-t-end T] [--capture-integrator
//                            genalpha|ida|both] [--only-capture]]   (scaling_capture.hpp)
// Writes DIR/scaling.csv, DIR/scaling_fits.csv and DIR/run.json (default DIR out/scaling).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ancf/io/run_metadata.hpp"
#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ancf/system/multibody_problem.hpp"
#include "child_process.hpp"
#include "scaling_capture.hpp"
#include "scaling_scene.hpp"

#ifndef ANCF_VERSION
#define ANCF_VERSION "unknown"
#endif
#ifndef ANCF_SOURCE_DIR
#define ANCF_SOURCE_DIR "."
#endif

namespace {

using ancf::Index;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string out = "out/scaling";
  long genalpha_steps = 200;  // h = 1e-3 s: 0.2 s ≈ 2 wave periods
  double ida_t_end = 0.05;    // [s]
  // BDF order <= 2 (A-stable): orders 3-5 are unstable on part of the imaginary axis and on an
  // undamped cable their step size is set by that, not by the error test (studies/README.md,
  // ancf-bench-ida); order <= 2 gives the same step sequence at every size (see the README).
  double ida_rtol = 1e-5;
  int ida_max_order = 2;
  double min_seconds = 0.3;  // timed integration per case, at least
  Index max_elements = 10000;
  std::vector<Index> element_counts = {10, 30, 100, 300, 1000, 3000, 10000};  // one string
  std::vector<Index> cable_counts = {1, 2, 4, 8, 16, 32};                     // of 100 elements
  bool genalpha = true, ida = true;
  // IDA's tolerance scales (GglScales): by default those of one 100-element string for every
  // case; with --ida-model-scales each model derives its own (see run_ida).
  bool ida_model_scales = false;
  ancf::GglScales ida_scales{};
  // The capture scene at these rope meshes (scaling_capture.hpp); empty: not run.
  std::vector<Index> capture_elements;
  double capture_t_end = 2.0;
  std::vector<std::string> capture_integrators = {"genalpha"};
  bool only_capture = false;
};

enum class Integrator { genalpha, ida };
const char* name(Integrator i) {
  return i == Integrator::genalpha ? "genalpha" : "ida";
}

// One case's numbers; trivially copyable (it crosses the pipe from the child).
struct CaseResult {
  long unknowns = 0, nonzeros = 0;
  long steps = 0, newton_iterations = 0, residual_evaluations = 0, matrix_evaluations = 0;
  long factorizations = 0, convergence_failures = 0, error_test_failures = 0;
  int repeats = 0;
  double median_seconds = 0.0;       // one integration, median of the repeats
  double fastest_seconds = 0.0;      // the fastest repeat: least disturbed by other jobs
  double fastest_cpu_seconds = 0.0;  // smallest CPU time of one integration over the repeats
  double setup_seconds = 0.0;        // model build (finalize)
};

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// CPU time of this process [s]. Beside the wall time because the machine is shared: waiting for
// a core while other jobs run adds wall time but no CPU time (cache sharing still adds some).
double cpu_seconds() {
  timespec ts{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Wall and CPU seconds of one timed integration.
struct Timing {
  double wall = 0.0, cpu = 0.0;
};

// One generalized-α integration over opt.genalpha_steps nominal steps; the counters of the steps
// only (initialize's index-1 solve and factorization subtracted).
Timing run_genalpha(const ancf::Model& model, const Options& opt, CaseResult& r) {
  ancf::MultibodyProblem problem(model);
  ancf::GeneralizedAlphaOptions o;  // defaults: h = 1e-3, ρ∞ = 0.8, modified Newton, rtol 1e-6
  ancf::GeneralizedAlphaStepper stepper(problem, o);
  stepper.initialize(0.0);
  const ancf::GeneralizedAlphaStatistics s0 = stepper.statistics();
  const auto start = Clock::now();
  const double cpu_start = cpu_seconds();
  stepper.advance_to(static_cast<double>(opt.genalpha_steps) * o.step_size);
  const Timing timing{seconds_since(start), cpu_seconds() - cpu_start};
  const ancf::GeneralizedAlphaStatistics& s = stepper.statistics();
  r.unknowns = problem.system_size();
  r.nonzeros = problem.iteration_pattern().nonzeros();
  r.steps = s.steps - s0.steps;
  r.newton_iterations = s.newton_iterations - s0.newton_iterations;
  r.residual_evaluations = s.residual_evaluations - s0.residual_evaluations;
  r.matrix_evaluations = s.matrix_evaluations - s0.matrix_evaluations;
  r.factorizations = s.factorizations - s0.factorizations;
  r.convergence_failures = s.convergence_failures - s0.convergence_failures;
  r.error_test_failures = s.step_halvings - s0.step_halvings;  // the stepper's only "rejection"
  return timing;
}

// One IDA integration to opt.ida_t_end (consistent initial values in the constructor, untimed).
// The absolute tolerances are rtol × scale per unknown (ggl_problem.hpp). The scales derived from
// a model depend on its overall size: the length L is the extent of the configuration and the time
// T = L / √(2E/m), so the slope-velocity scale 1/T shrinks like 1/L as a string gets longer and
// its tolerance tightens although each element's motion is unchanged. To compare like with like,
// every case gets the scales of the one-string 100-element model unless --ida-model-scales.
Timing run_ida(const ancf::Model& model, const Options& opt, CaseResult& r) {
  ancf::GglProblem problem(model, opt.ida_model_scales ? ancf::GglScales{} : opt.ida_scales);
  ancf::IdaOptions o;
  o.rtol = opt.ida_rtol;
  o.max_order = opt.ida_max_order;
  ancf::IdaIntegrator ida(problem, o);
  const auto start = Clock::now();
  const double cpu_start = cpu_seconds();
  ida.advance(opt.ida_t_end);
  const Timing timing{seconds_since(start), cpu_seconds() - cpu_start};
  const ancf::IdaStatistics s = ida.statistics();
  r.unknowns = problem.size();
  r.nonzeros = problem.jacobian_pattern().nonzeros();
  r.steps = s.steps;
  r.newton_iterations = s.nonlinear_iterations;
  r.residual_evaluations = s.residual_evaluations;
  r.matrix_evaluations = s.jacobian_evaluations;
  r.factorizations = s.linear_solver_setups;
  r.convergence_failures = s.convergence_failures;
  r.error_test_failures = s.error_test_failures;
  return timing;
}

CaseResult measure_case(Integrator integrator, Index elements, Index cables, const Options& opt) {
  CaseResult r;
  const auto build = Clock::now();
  const ancf::Model model = ancf::studies::taut_strings_model(elements, cables);
  r.setup_seconds = seconds_since(build);
  std::vector<double> walls, cpus;
  double total = 0.0;
  do {  // at least one integration, then repeats until min_seconds were timed
    const Timing t =
        integrator == Integrator::genalpha ? run_genalpha(model, opt, r) : run_ida(model, opt, r);
    walls.push_back(t.wall);
    cpus.push_back(t.cpu);
    total += t.wall;
  } while (total < opt.min_seconds && walls.size() < 51);
  std::sort(walls.begin(), walls.end());
  r.repeats = static_cast<int>(walls.size());
  r.median_seconds = walls[walls.size() / 2];
  r.fastest_seconds = walls.front();
  r.fastest_cpu_seconds = *std::min_element(cpus.begin(), cpus.end());
  return r;
}

struct Row {
  Integrator integrator;
  std::string sweep;  // "elements" or "cables"
  Index elements_per_cable, cables;
  CaseResult result;
  double rss_increment_mib;
  // Time per step of the fastest repeat: on a shared machine other jobs only ever add time.
  [[nodiscard]] double per_step() const {
    return result.fastest_seconds / static_cast<double>(result.steps);
  }
  [[nodiscard]] double cpu_per_step() const {
    return result.fastest_cpu_seconds / static_cast<double>(result.steps);
  }
  [[nodiscard]] Index total_elements() const { return elements_per_cable * cables; }
};

// Least-squares line y = intercept + slope·x.
struct Line {
  double intercept = 0.0, slope = 0.0;
};
Line fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double count = static_cast<double>(x.size());
  double mx = 0.0, my = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / count;
    my += y[i] / count;
  }
  double sxy = 0.0, sxx = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  return {my - sxy / sxx * mx, sxy / sxx};
}

// Growth exponent p of y ~ x^p: the least-squares slope of log y against log x.
double log_log_slope(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<double> lx(x.size()), ly(y.size());
  std::transform(x.begin(), x.end(), lx.begin(), [](double v) { return std::log(v); });
  std::transform(y.begin(), y.end(), ly.begin(), [](double v) { return std::log(v); });
  return fit_line(lx, ly).slope;
}

// Commit of the source tree the study was built from, if git can tell.
std::string source_commit() {
  std::string commit;
  if (FILE* p = ::popen("git -C " ANCF_SOURCE_DIR " rev-parse --short HEAD 2>/dev/null", "r")) {
    char buffer[64] = {};
    if (std::fgets(buffer, sizeof(buffer), p)) commit = buffer;
    ::pclose(p);
  }
  while (!commit.empty() && (commit.back() == '\n' || commit.back() == '\r')) commit.pop_back();
  return commit.empty() ? "unknown" : commit;
}

// "10,30,100" → {10, 30, 100}; an empty string gives an empty list (that sweep is skipped).
std::vector<Index> parse_list(const std::string& text) {
  std::vector<Index> values;
  std::size_t begin = 0;
  while (begin < text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    values.push_back(std::stol(text.substr(begin, end - begin)));
    begin = end + 1;
  }
  return values;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--out")
      o.out = value();
    else if (arg == "--steps")
      o.genalpha_steps = std::stol(value());
    else if (arg == "--ida-t-end")
      o.ida_t_end = std::stod(value());
    else if (arg == "--ida-rtol")
      o.ida_rtol = std::stod(value());
    else if (arg == "--ida-max-order")
      o.ida_max_order = std::stoi(value());
    else if (arg == "--min-seconds")
      o.min_seconds = std::stod(value());
    else if (arg == "--max-elements")
      o.max_elements = std::stol(value());
    else if (arg == "--elements")
      o.element_counts = parse_list(value());
    else if (arg == "--cables")
      o.cable_counts = parse_list(value());
    else if (arg == "--ida-model-scales")
      o.ida_model_scales = true;
    else if (arg == "--capture")
      o.capture_elements = parse_list(value());
    else if (arg == "--capture-t-end")
      o.capture_t_end = std::stod(value());
    else if (arg == "--capture-integrator") {
      const std::string v = value();
      o.capture_integrators = v == "both" ? std::vector<std::string>{"genalpha", "ida"}
                                          : std::vector<std::string>{v};
    } else if (arg == "--only-capture")
      o.only_capture = true;
    else if (arg == "--integrator") {
      const std::string v = value();
      o.genalpha = v == "genalpha" || v == "both";
      o.ida = v == "ida" || v == "both";
      if (!o.genalpha && !o.ida) throw std::invalid_argument("--integrator genalpha|ida|both");
    } else
      throw std::invalid_argument(
          "unknown option " + arg +
          "; usage: ancf-study-scaling [--out DIR] [--steps N] "
          "[--ida-t-end T] [--ida-rtol R] [--ida-max-order K] "
          "[--min-seconds S] [--max-elements N] [--integrator genalpha|ida|both] "
          "[--ida-model-scales] [--elements LIST] [--cables LIST] [--capture LIST] "
          "[--capture-t-end T] [--capture-integrator genalpha|ida|both] [--only-capture]");
  }
  return o;
}

}  // namespace

int main(int argc, char** argv) try {
  Options opt = parse(argc, argv);
  {
    const ancf::Model reference = ancf::studies::taut_strings_model(100, 1);
    opt.ida_scales = ancf::GglProblem(reference).scales();
  }
  std::filesystem::create_directories(opt.out);
  const auto study_start = Clock::now();

  const long baseline_kib =
      ancf::studies::run_in_child<int>([] { return 0; }).max_rss_kib;  // fork + exit only
  struct Plan {
    std::string sweep;
    Index elements, cables;
  };
  if (!opt.capture_elements.empty()) {
    const std::vector<long> counts(opt.capture_elements.begin(), opt.capture_elements.end());
    if (!ancf::studies::capture_scaling(std::string(ANCF_SOURCE_DIR) + "/studies/scenes/capture.toml",
                                        counts, opt.capture_integrators, opt.capture_t_end,
                                        opt.out))
      return 2;
    if (opt.only_capture) return 0;
  }
  std::vector<Plan> plan;
  for (const Index n : opt.element_counts)
    if (n <= opt.max_elements) plan.push_back({"elements", n, 1});
  for (const Index k : opt.cable_counts)
    if (100 * k <= opt.max_elements) plan.push_back({"cables", 100, k});

  std::vector<Row> rows;
  fmt::print(
      "{:>8} {:>8} {:>6} {:>6} {:>8} {:>9} {:>5} {:>6} {:>5} {:>5} {:>10} {:>9} {:>9} {:>6}\n",
      "method", "sweep", "N/cab", "cables", "unknowns", "nonzeros", "steps", "newton", "jac",
      "fact", "wall/step", "us/el/st", "cpu us/el", "MiB");
  for (const Integrator integrator : {Integrator::genalpha, Integrator::ida}) {
    if (!(integrator == Integrator::genalpha ? opt.genalpha : opt.ida)) continue;
    for (const Plan& p : plan) {
      const auto outcome = ancf::studies::run_in_child<CaseResult>(
          [&] { return measure_case(integrator, p.elements, p.cables, opt); });
      if (!outcome.ok) {
        fmt::print(stderr, "{} {} x {}: {}\n", name(integrator), p.elements, p.cables,
                   outcome.error);
        return 2;
      }
      const Row row{
          integrator,     p.sweep,
          p.elements,     p.cables,
          outcome.result, static_cast<double>(outcome.max_rss_kib - baseline_kib) / 1024.0};
      const CaseResult& r = row.result;
      const double elements = static_cast<double>(row.total_elements());
      fmt::print(
          "{:>8} {:>8} {:6} {:6} {:8} {:9} {:5} {:6} {:5} {:5} {:10.3e} {:9.3f} {:9.3f} {:6.1f}\n",
          name(integrator), p.sweep, p.elements, p.cables, r.unknowns, r.nonzeros, r.steps,
          r.newton_iterations, r.matrix_evaluations, r.factorizations, row.per_step(),
          1e6 * row.per_step() / elements, 1e6 * row.cpu_per_step() / elements,
          row.rss_increment_mib);
      std::fflush(stdout);
      rows.push_back(row);
    }
  }

  std::ofstream csv(opt.out + "/scaling.csv");
  csv << "integrator,sweep,elements_per_cable,cables,elements,unknowns,nonzeros,steps,"
         "newton_iterations,residual_evaluations,matrix_evaluations,factorizations,"
         "convergence_failures,rejected_steps,repeats,median_seconds_per_run,"
         "fastest_seconds_per_run,fastest_cpu_seconds_per_run,seconds_per_step,"
         "cpu_seconds_per_step,us_per_element_step,cpu_us_per_element_step,setup_seconds,"
         "peak_rss_increment_mib\n";
  for (const Row& row : rows) {
    const CaseResult& r = row.result;
    const double elements = static_cast<double>(row.total_elements());
    csv << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},", name(row.integrator),
                       row.sweep, row.elements_per_cable, row.cables, row.total_elements(),
                       r.unknowns, r.nonzeros, r.steps, r.newton_iterations, r.residual_evaluations,
                       r.matrix_evaluations, r.factorizations, r.convergence_failures,
                       r.error_test_failures, r.repeats);
    csv << fmt::format("{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{:.6f},{:.6f},{:.6e},{:.3f}\n",
                       r.median_seconds, r.fastest_seconds, r.fastest_cpu_seconds, row.per_step(),
                       row.cpu_per_step(), 1e6 * row.per_step() / elements,
                       1e6 * row.cpu_per_step() / elements, r.setup_seconds, row.rss_increment_mib);
  }

  // Growth exponents over each sweep (x = elements of the one string, or cables): of the wall and
  // the CPU time per step over all sizes and over the sizes with >= 100 elements in all (below
  // that a fixed cost per step, independent of N, is a visible share), and the peak memory as a
  // line a + b·N_total (the increment of a small case is mostly the fixed part a, so a log slope
  // would mislead).
  std::ofstream fits(opt.out + "/scaling_fits.csv");
  fits << "integrator,sweep,sizes,wall_exponent_all,wall_exponent_from_100,cpu_exponent_all,"
          "cpu_exponent_from_100,memory_fixed_mib,memory_kib_per_element\n";
  ancf::JsonObject exponents;
  fmt::print(
      "\ngrowth of the time per step, t ~ x^p (least squares of log t vs log x; linear: p = 1),"
      "\nand peak memory increment = a + b N_elements (least squares)\n");
  for (const Integrator integrator : {Integrator::genalpha, Integrator::ida}) {
    for (const std::string sweep : {"elements", "cables"}) {
      std::vector<double> x, wall, cpu, x_big, wall_big, cpu_big, n, memory;
      for (const Row& row : rows) {
        if (row.integrator != integrator || row.sweep != sweep) continue;
        const double xi =
            static_cast<double>(sweep == "elements" ? row.elements_per_cable : row.cables);
        x.push_back(xi);
        wall.push_back(row.per_step());
        cpu.push_back(row.cpu_per_step());
        if (row.total_elements() >= 100) {
          x_big.push_back(xi);
          wall_big.push_back(row.per_step());
          cpu_big.push_back(row.cpu_per_step());
        }
        n.push_back(static_cast<double>(row.total_elements()));
        memory.push_back(row.rss_increment_mib);
      }
      if (x.size() < 2) continue;
      const bool big = x_big.size() >= 2;
      const double wall_all = log_log_slope(x, wall), cpu_all = log_log_slope(x, cpu);
      const double wall_100 = big ? log_log_slope(x_big, wall_big) : NAN;
      const double cpu_100 = big ? log_log_slope(x_big, cpu_big) : NAN;
      const Line mem = fit_line(n, memory);
      fmt::print(
          "  {:8} over {:8} ({} sizes): wall p = {:.3f}, from 100 elements {:.3f}; CPU p = {:.3f}, "
          "from 100 elements {:.3f}; memory {:.2f} MiB + {:.2f} KiB/element\n",
          name(integrator), sweep, x.size(), wall_all, wall_100, cpu_all, cpu_100, mem.intercept,
          1024.0 * mem.slope);
      fits << fmt::format("{},{},{},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f},{:.4f}\n", name(integrator),
                          sweep, x.size(), wall_all, wall_100, cpu_all, cpu_100, mem.intercept,
                          1024.0 * mem.slope);
      const std::string key = fmt::format("{}_{}", name(integrator), sweep);
      exponents.set(key + "_wall_exponent_all", wall_all)
          .set(key + "_wall_exponent_from_100", wall_100)
          .set(key + "_cpu_exponent_all", cpu_all)
          .set(key + "_cpu_exponent_from_100", cpu_100)
          .set(key + "_memory_kib_per_element", 1024.0 * mem.slope);
    }
  }

  ancf::JsonObject options, meta;
  options.set("genalpha_steps", opt.genalpha_steps)
      .set("genalpha_step_size_s", ancf::GeneralizedAlphaOptions{}.step_size)
      .set("genalpha_rho_infinity", ancf::GeneralizedAlphaOptions{}.rho_infinity)
      .set("genalpha_rtol", ancf::GeneralizedAlphaOptions{}.rtol)
      .set("ida_t_end_s", opt.ida_t_end)
      .set("ida_rtol", opt.ida_rtol)
      .set("ida_max_order", static_cast<long>(opt.ida_max_order))
      .set("ida_scales", opt.ida_model_scales ? "each model's own" : "the 1 x 100-element model's")
      .set("ida_scale_length_m", opt.ida_scales.length)
      .set("ida_scale_energy_J", opt.ida_scales.energy)
      .set("ida_scale_time_s", opt.ida_scales.time)
      .set("min_seconds", opt.min_seconds)
      .set("max_elements", static_cast<long>(opt.max_elements))
      .set("element_length_m", ancf::studies::taut_string_element_length())
      .set("prestrain", ancf::studies::kPrestrain)
      .set("wave_elements", static_cast<long>(ancf::studies::kWaveElements));
  meta.set("study", "scaling")
      .set("ancf_version", ANCF_VERSION)
      .set("commit", source_commit())
      .set("options", options)
      .set("baseline_child_rss_kib", baseline_kib)
      .set("cases", static_cast<long>(rows.size()))
      .set("growth_exponents", exponents)
      .set("wall_time_s", seconds_since(study_start));
  std::ofstream(opt.out + "/run.json") << meta.text() << '\n';
  fmt::print("\nwrote {}/scaling.csv, scaling_fits.csv, run.json ({:.0f} s)\n", opt.out,
             seconds_since(study_start));
  return 0;
} catch (const std::exception& e) {
  std::fprintf(stderr, "ancf-study-scaling: %s\n", e.what());
  return 2;
}
