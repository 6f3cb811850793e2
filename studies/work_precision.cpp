// Time convergence and work–precision of the two integrators on scene files (issue: studies).
//
// For each scene: a reference run (IDA, BDF order ≤ 5, tight rtol) on the same mesh; then
//  * IDA over an rtol sweep for each BDF order limit (default 5 and 2),
//  * generalized-α (index 3, scaled, modified Newton with a tight Newton tolerance so that the
//    error is the discretization error) over a step-size sweep for each ρ∞ (default 0.6, 0.8,
//    0.9),
// every run through the same driver as `ancf run` (ancf::simulate). The error of a run is the
// largest distance between its node positions (every cable node, every body origin) and the
// reference's at the check times (ten, evenly spaced over the scene's t_end), in metres;
// scd = −log10(error / max |r_ref|) is the normwise form of the significant correct digits of
// REFERENCES §9. Wall time is that of simulate() (set-up, consistent initial values, KLU analysis,
// integration), the median of several runs for runs shorter than 0.5 s.
//
// Observed orders: generalized-α, the least-squares slope of log error against log h over the
// smallest four steps (expected 2 for every ρ∞ < 1); IDA, the slopes of log error against log
// rtol (tolerance proportionality, ideally 1) and against log(steps) (−effective order).
//
// Usage: ancf-study-work-precision [--out DIR] [--quick] [--reference-rtol R] [--rtols LIST]
//          [--steps LIST] [--rho LIST] [--ida-orders LIST] [--perturbed-start] [--min-order P]
//          [SCENE.toml ...]
// (LIST: comma-separated, or "none" to skip that integrator; default scenes:
// studies/scenes/{cable_pendulum,cable_body,cable_drop}.toml; --quick: three sweep points per
// curve, for the smoke test; --min-order P: exit status 2 if a generalized-α curve's fitted order
// is below P). Writes DIR/runs.csv (one row per run),
// DIR/orders.csv (one row per curve) and DIR/run.json; prints both tables.
#include <fmt/format.h>
#include <fmt/os.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/core/fitted_order.hpp"
#include "ancf/io/run_metadata.hpp"
#include "ancf/io/scene.hpp"
#include "ancf/io/simulation.hpp"

using namespace ancf;

namespace {

struct Options {
  std::string out = "out/work_precision";
  std::vector<std::string> scenes;
  double reference_rtol = 1e-10;
  bool quick = false;
  std::vector<int> ida_orders = {5, 2};
  std::vector<double> rho = {0.6, 0.8, 0.9};
  std::vector<double> rtols = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9};
  std::vector<double> steps = {4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5};
  bool perturbed_start = false;
  double min_order = 0.0;  ///< exit status 2 if a generalized-α curve's fitted order is below
};

/// "a,b,c" → {a, b, c}; "none" → {}.
template <class T>
std::vector<T> parse_list(const std::string& text) {
  std::vector<T> out;
  if (text == "none") return out;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    out.push_back(static_cast<T>(std::stod(text.substr(begin, end - begin))));
    begin = end + 1;
  }
  return out;
}

/// Node positions (all cable nodes, then body origins) at each check time.
using Trajectory = std::vector<std::vector<Vec3>>;

struct Run {
  Trajectory points;
  double wall_s = 0.0;
  SimulationCounters counters;
  std::string failure;  ///< empty on success
};

std::vector<Vec3> positions(const Model& model, const VecX& q) {
  std::vector<Vec3> p;
  for (Index c = 0; c < static_cast<Index>(model.cables().size()); ++c)
    for (Index k = 0; k < model.cables()[c].node_count; ++k)
      p.push_back(q.segment<3>(model.node_coordinate(c, k)));
  for (const BodyData& b : model.bodies()) p.push_back(q.segment<3>(b.first_coordinate));
  return p;
}

Run run_once(const Scene& scene, const IntegratorSettings& settings,
             const std::vector<double>& times) {
  Run r;
  SimulationHooks hooks;
  hooks.output = [&](const SystemState& s) {
    if (s.t > 0.0) r.points.push_back(positions(scene.model, s.q));
  };
  const auto start = std::chrono::steady_clock::now();
  try {
    simulate(scene.model, settings, times, hooks, r.counters);
  } catch (const std::exception& e) {
    r.failure = e.what();
  }
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

/// Median wall time over repeats for short runs (the result itself is deterministic).
Run timed_run(const Scene& scene, const IntegratorSettings& settings,
              const std::vector<double>& times) {
  Run r = run_once(scene, settings, times);
  if (!r.failure.empty() || r.wall_s > 0.5) return r;
  std::vector<double> walls = {r.wall_s};
  for (int k = 0; k < 4; ++k) walls.push_back(run_once(scene, settings, times).wall_s);
  std::nth_element(walls.begin(), walls.begin() + 2, walls.end());
  r.wall_s = walls[2];
  return r;
}

double max_distance(const Trajectory& a, const Trajectory& b) {
  if (a.size() != b.size()) return std::numeric_limits<double>::quiet_NaN();
  double e = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k)
    for (std::size_t i = 0; i < a[k].size(); ++i) e = std::max(e, (a[k][i] - b[k][i]).norm());
  return e;
}

double max_norm(const Trajectory& a) {
  double m = 0.0;
  for (const auto& frame : a)
    for (const Vec3& p : frame) m = std::max(m, p.cwiseAbs().maxCoeff());
  return m;
}

long counter(const SimulationCounters& c, const std::string& name) {
  for (const auto& [key, value] : c)
    if (key == name) return value;
  return 0;
}

/// One sweep point, as written to runs.csv.
struct Point {
  std::string scene, method;  // method: "ida" or "genalpha"
  int max_order = 0;
  double rho = 0.0, parameter = 0.0;  // rtol (IDA) or h [s] (generalized-α)
  double error = 0.0, scd = 0.0, wall_s = 0.0;
  long steps = 0, newton = 0, residuals = 0, matrices = 0, factorizations = 0, failures = 0;
  std::string failure;
};

Point measure(const Scene& scene, const IntegratorSettings& s, const std::vector<double>& times,
              const Run& reference, double scale) {
  const Run r = timed_run(scene, s, times);
  Point p;
  p.scene = scene.name;
  p.method = s.kind == IntegratorKind::ida ? "ida" : "genalpha";
  p.max_order = s.kind == IntegratorKind::ida ? s.max_order : 0;
  p.rho = s.kind == IntegratorKind::ida ? 0.0 : s.rho_infinity;
  p.parameter = s.kind == IntegratorKind::ida ? s.rtol : s.step;
  p.failure = r.failure;
  p.error = r.failure.empty() ? max_distance(r.points, reference.points)
                              : std::numeric_limits<double>::quiet_NaN();
  p.scd = -std::log10(p.error / scale);
  p.wall_s = r.wall_s;
  p.steps = counter(r.counters, "steps");
  p.newton = counter(r.counters, "Newton iterations");
  p.residuals = counter(r.counters, "residual evaluations");
  p.matrices =
      counter(r.counters, "Jacobian evaluations") + counter(r.counters, "matrix evaluations");
  p.factorizations = s.kind == IntegratorKind::ida ? counter(r.counters, "linear solver setups")
                                                   : counter(r.counters, "factorizations");
  p.failures =
      counter(r.counters, "error test failures") + counter(r.counters, "convergence failures");
  return p;
}

/// One curve's observed order (orders.csv).
struct Order {
  std::string scene, curve;
  double slope_parameter = 0.0;  // d log error / d log (h or rtol)
  double slope_steps = 0.0;      // d log error / d log steps
  int points = 0;
};

Order fit(const std::vector<Point>& curve, const std::string& scene, const std::string& name,
          std::size_t last) {
  // The asymptotic range: the `last` finest successful points.
  std::vector<const Point*> ok;
  for (const Point& p : curve)
    if (p.failure.empty() && std::isfinite(p.error) && p.error > 0.0) ok.push_back(&p);
  std::sort(ok.begin(), ok.end(),
            [](const Point* a, const Point* b) { return a->parameter > b->parameter; });
  if (ok.size() > last) ok.erase(ok.begin(), ok.end() - static_cast<std::ptrdiff_t>(last));
  Order o{scene, name, std::numeric_limits<double>::quiet_NaN(),
          std::numeric_limits<double>::quiet_NaN(), static_cast<int>(ok.size())};
  if (ok.size() < 2) return o;
  std::vector<double> x, steps, e;
  for (const Point* p : ok)
    x.push_back(p->parameter), steps.push_back(static_cast<double>(p->steps)),
        e.push_back(p->error);
  o.slope_parameter = fitted_order(x, e);
  o.slope_steps = fitted_order(steps, e);
  return o;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--out")
      o.out = value();
    else if (a == "--quick")
      o.quick = true;
    else if (a == "--reference-rtol")
      o.reference_rtol = std::stod(value());
    else if (a == "--rtols")
      o.rtols = parse_list<double>(value());
    else if (a == "--steps")
      o.steps = parse_list<double>(value());
    else if (a == "--rho")
      o.rho = parse_list<double>(value());
    else if (a == "--ida-orders")
      o.ida_orders = parse_list<int>(value());
    else if (a == "--perturbed-start")
      o.perturbed_start = true;
    else if (a == "--min-order")
      o.min_order = std::stod(value());
    else if (a.starts_with("--"))
      throw std::invalid_argument("unknown option " + a);
    else
      o.scenes.push_back(a);
  }
  if (o.scenes.empty())
    o.scenes = {"studies/scenes/cable_pendulum.toml", "studies/scenes/cable_body.toml",
                "studies/scenes/cable_drop.toml"};
  return o;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  std::filesystem::create_directories(opt.out);
  std::vector<double> rtols = opt.rtols, steps = opt.steps;
  if (opt.quick) rtols = {1e-4, 1e-5, 1e-6}, steps = {2e-3, 1e-3, 5e-4};

  std::vector<Point> points;
  std::vector<Order> orders;
  JsonObject meta;
  meta.set("study", "work_precision")
      .set("reference_rtol", opt.reference_rtol)
      .set("quick", opt.quick);
  for (const std::string& path : opt.scenes) {
    const Scene scene = load_scene(path);
    const double t_end = scene.integrator.t_end;
    const std::vector<double> times = output_times(t_end / 10.0, t_end);

    IntegratorSettings ref = scene.integrator;
    ref.kind = IntegratorKind::ida;
    ref.rtol = opt.reference_rtol;
    ref.max_order = 5;
    ref.max_step = 0.0;
    const Run reference = run_once(scene, ref, times);
    if (!reference.failure.empty())
      throw SolverError("reference run of " + path + " failed: " + reference.failure);
    const double scale = max_norm(reference.points);
    fmt::print("{}: reference IDA rtol {:.0e} in {:.2f} s, {} steps; max |r| = {:.3g} m\n",
               scene.name, opt.reference_rtol, reference.wall_s,
               counter(reference.counters, "steps"), scale);
    JsonObject sm;
    sm.set("path", path)
        .set("reference_wall_s", reference.wall_s)
        .set("reference_steps", counter(reference.counters, "steps"))
        .set("position_scale_m", scale);
    meta.set(scene.name, sm);

    // One curve: measure each setting, print a line per point, fit the order, keep the points.
    auto sweep = [&](const std::string& label, const std::vector<IntegratorSettings>& settings) {
      std::vector<Point> curve;
      for (const IntegratorSettings& s : settings) {
        curve.push_back(measure(scene, s, times, reference, scale));
        const Point& p = curve.back();
        fmt::print("  {} {} {:.3e}: error {:.3e} m, scd {:.2f}, {:.4f} s, {} steps{}\n", label,
                   s.kind == IntegratorKind::ida ? "rtol" : "h", p.parameter, p.error, p.scd,
                   p.wall_s, p.steps, p.failure.empty() ? "" : " FAILED: " + p.failure);
      }
      orders.push_back(fit(curve, scene.name, label, 4));
      points.insert(points.end(), curve.begin(), curve.end());
    };
    for (const int order : opt.ida_orders) {
      std::vector<IntegratorSettings> settings;
      for (const double rtol : rtols) {
        if (order <= 2 && rtol < 1e-7)
          continue;  // BDF2 at rtol 1e-8 needs h ~ 1e-6 s: minutes per run
        IntegratorSettings s = scene.integrator;
        s.kind = IntegratorKind::ida;
        s.rtol = rtol;
        s.max_order = order;
        s.max_step = 0.0;
        settings.push_back(s);
      }
      sweep(fmt::format("ida order<={}", order), settings);
    }
    for (const double rho : opt.rho) {
      std::vector<IntegratorSettings> settings;
      for (const double h : steps) {
        IntegratorSettings s = scene.integrator;
        s.kind = IntegratorKind::genalpha;
        s.step = h;
        s.rho_infinity = rho;
        s.stabilized_index2 = false;
        s.perturbed_start = opt.perturbed_start;
        s.rtol = 1e-8;  // Newton: its error in q is ≈ rtol |v| h / 2 per step, far below h²
        s.ga_atol_position = 1e-10, s.ga_atol_velocity = 1e-8, s.ga_atol_multiplier = 1e-8;
        settings.push_back(s);
      }
      sweep(fmt::format("genalpha rho={:.1f}", rho), settings);
    }
  }

  auto runs = fmt::output_file(opt.out + "/runs.csv");
  runs.print(
      "scene,method,max_order,rho_inf,parameter,error_m,scd,wall_s,steps,newton_iterations,"
      "residual_evaluations,matrix_evaluations,factorizations,failures,status\n");
  for (const Point& p : points)
    runs.print("{},{},{},{},{:.6e},{:.6e},{:.4f},{:.6e},{},{},{},{},{},{},\"{}\"\n", p.scene,
               p.method, p.max_order, p.rho, p.parameter, p.error, p.scd, p.wall_s, p.steps,
               p.newton, p.residuals, p.matrices, p.factorizations, p.failures,
               p.failure.empty() ? "ok" : p.failure);
  auto ord = fmt::output_file(opt.out + "/orders.csv");
  ord.print("scene,curve,points,slope_vs_parameter,slope_vs_steps\n");
  fmt::print(
      "\n| scene | curve | fitted points | d log err / d log (h or rtol) | d log err / d log steps "
      "|\n"
      "|---|---|---|---|---|\n");
  for (const Order& o : orders) {
    ord.print("{},{},{},{:.4f},{:.4f}\n", o.scene, o.curve, o.points, o.slope_parameter,
              o.slope_steps);
    fmt::print("| {} | {} | {} | {:.2f} | {:.2f} |\n", o.scene, o.curve, o.points,
               o.slope_parameter, o.slope_steps);
  }
  std::ofstream(opt.out + "/run.json") << meta.text() << "\n";
  fmt::print("wrote {}/runs.csv, orders.csv, run.json\n", opt.out);
  int status = 0;
  for (const Order& o : orders)
    if (o.curve.starts_with("genalpha") && !(o.slope_parameter >= opt.min_order)) {
      fmt::print(stderr, "{} {}: fitted order {:.2f} < --min-order {:.2f}\n", o.scene, o.curve,
                 o.slope_parameter, opt.min_order);
      status = 2;
    }
  return status;
} catch (const std::exception& e) {
  fmt::print(stderr, "ancf-study-work-precision: {}\n", e.what());
  return 1;
}
