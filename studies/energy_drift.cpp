// Energy drift of the two integrators over many periods of two undamped, unforced-in-time scenes
// (DESIGN §8 "conservation"; REFERENCES §5, §10):
//
//  * pendulum: the benchmark cable pendulum of REFERENCES §10 (10 elements), pinned at the origin,
//    released straight along +x at rest under gravity; 20 s ≈ 10 swings. Energy scale for the
//    relative error: ρA L g · L/2 (the potential energy released by the swing).
//  * spinning: the same cable (10 elements, no gravity) pinned at its midpoint (node 5, a
//    spherical pivot) and started as a rigid rotation ω = 2π rad/s about +z; 20 s = 20 turns. The
//    centrifugal load excites axial vibration. Energy scale: the initial kinetic energy. The
//    angular momentum about the pivot is conserved too and is written beside the energy.
//  * rigid: the rod pendulum of REFERENCES §5 (natural coordinates, revolute joint, θ₀ = 1 rad);
//    20 s ≈ 9.5 periods. Its constraints (orthonormality, hinge axis) are non-linear, so the
//    position and velocity constraint drift are not trivially zero as for the cables' linear
//    pins. Energy scale m g L/2.
//
// Runs: generalized-α index 3 with ρ∞ ∈ {0.9, 0.6} and the stabilized index-2 variant with ρ∞ = 1,
// each at h ∈ {2e-3, 1e-3, 5e-4} s (modified Newton, rtol 1e-8); IDA on the GGL form at
// rtol ∈ {1e-4, 1e-6, 1e-8}. Every run writes <out>/<scene>_<run>.csv sampled every 0.01 s:
//   t, energy [J], relative energy error (E − E₀)/E_scale, max |Φ| (position constraint drift),
//   max |Φ_q v + Φ_t| (velocity constraint drift), relative angular-momentum error,
// <out>/run.json (options, per-run steps, wall time and energy figures) and <out>/summary.csv one
// line per run: max |relative energy error|, drift rate (least-squares
// slope of the relative error against t, 1/s), max |Φ|, max |Φ_q v + Φ_t|, max relative
// angular-momentum error (spinning only; nan / 0 elsewhere), steps, wall time.
//
// Usage: ancf-study-energy-drift [output directory = out/energy_drift] [duration = 20] [--no-ida]
// (--no-ida skips the IDA runs, which take almost all of the ≈ 20 min).
#include <fmt/format.h>
#include <fmt/os.h>
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "ancf/io/run_metadata.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ancf/system/model_builder.hpp"
#include "ancf/system/multibody_problem.hpp"

using namespace ancf;

namespace {

constexpr double kSampleInterval = 0.01;  // [s]

struct Scene {
  std::string name;
  Model model;
  double energy_scale = 1.0;        // [J]
  bool conserves_momentum = false;  // angular momentum about the origin (pivot) is conserved
};

Scene pendulum_scene() {
  const CablePendulumSpec spec = benchmark_cable_pendulum(10);
  Scene s{"pendulum", cable_pendulum_model(spec), 0.0};
  s.energy_scale =
      spec.mass_per_length * spec.length * std::abs(spec.gravity.z()) * 0.5 * spec.length;
  return s;
}

Scene spinning_scene() {
  const CablePendulumSpec spec = benchmark_cable_pendulum(10);
  CableSection section;
  section.axial_stiffness = spec.axial_stiffness;
  section.bending_stiffness = spec.bending_stiffness;
  section.mass_per_length = spec.mass_per_length;
  ModelBuilder b;
  const CableGeometry g = straight_cable(Vec3(-0.5, 0.0, 0.0), Vec3(0.5, 0.0, 0.0), 10);
  const Index c = b.add_cable("rotor", g, section);
  // Rigid rotation ω ẑ: ṙ = ω × r, ṙ_x = ω × r_x.
  const Vec3 omega(0.0, 0.0, 2.0 * std::numbers::pi);
  std::vector<NodeCoordinates> v(g.nodes.size());
  for (std::size_t k = 0; k < g.nodes.size(); ++k)
    v[k] << omega.cross(g.nodes[k].head<3>()), omega.cross(g.nodes[k].tail<3>());
  b.set_initial_configuration(c, g, &v);
  b.pin("pivot", {c, 5}, Vec3::Zero());
  Scene s{"spinning", b.finalize(), 0.0, true};
  s.energy_scale = kinetic_energy(s.model, s.model.initial_velocities());
  return s;
}

Scene rigid_scene() {
  const RigidPendulumSpec spec;
  return {"rigid", rigid_pendulum_model(spec), spec.mass * spec.gravity * 0.5 * spec.length, false};
}

// One row of a trace.
struct Sample {
  double t, energy, phi, phi_v, momentum;
};

struct Trace {
  std::string run;
  std::vector<Sample> samples;
  long steps = 0;
  double wall = 0.0;
};

// Measures a state of `model` (energy, constraint drift, angular momentum about the origin).
class Meter {
 public:
  explicit Meter(const Model& model)
      : model_(model), ws_(model), state_(SystemState::initial(model)) {}
  Sample measure(double t, const VecX& q, const VecX& v) {
    state_.t = t;
    state_.q = q;
    state_.v = v;
    const ConstraintViolation cv = constraint_violation(model_, state_, ws_);
    return {t, energies(model_, state_, ws_).total(), cv.position, cv.velocity,
            momentum(model_, q, v).angular.norm()};
  }

 private:
  const Model& model_;
  Workspace ws_;
  SystemState state_;
};

Trace run_generalized_alpha(const Scene& scene, double duration, double h, double rho,
                            bool index2) {
  MultibodyProblem problem(scene.model);
  GeneralizedAlphaOptions o;
  o.step_size = h;
  o.rho_infinity = rho;
  o.formulation =
      index2 ? GeneralizedAlphaFormulation::stabilized_index2 : GeneralizedAlphaFormulation::index3;
  o.start = GeneralizedAlphaStart::perturbed;
  o.rtol = 1e-8;
  o.atol_position = 1e-10;
  o.atol_velocity = 1e-8;
  o.atol_multiplier = 1e-8;
  GeneralizedAlphaStepper stepper(problem, o);
  Meter meter(scene.model);
  Trace trace{fmt::format("genalpha_{}_rho{:.1f}_h{:.0e}", index2 ? "index2" : "index3", rho, h),
              {},
              0,
              0.0};
  stepper.initialize(0.0);
  trace.samples.push_back(meter.measure(0.0, stepper.positions(), stepper.velocities()));
  const long samples = std::lround(duration / kSampleInterval);
  double wall = 0.0;
  for (long k = 1; k <= samples; ++k) {
    const auto start = std::chrono::steady_clock::now();
    stepper.advance_to(static_cast<double>(k) * kSampleInterval);
    wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    trace.samples.push_back(
        meter.measure(stepper.time(), stepper.positions(), stepper.velocities()));
  }
  trace.steps = stepper.statistics().steps;
  trace.wall = wall;
  return trace;
}

Trace run_ida(const Scene& scene, double duration, double rtol) {
  GglProblem ggl(scene.model);
  IdaOptions o;
  o.rtol = rtol;
  const long samples = std::lround(duration / kSampleInterval);
  for (long k = 1; k <= samples; ++k)
    o.output_times.push_back(static_cast<double>(k) * kSampleInterval);
  Meter meter(scene.model);
  SystemState state = SystemState::initial(scene.model);
  Trace trace{fmt::format("ida_rtol{:.0e}", rtol), {}, 0, 0.0};
  const auto start = std::chrono::steady_clock::now();
  IdaIntegrator ida(ggl, o);
  auto record = [&](double t, std::span<const double> y, std::span<const double> yp) {
    ggl.unpack(t, y, yp, state);
    trace.samples.push_back(meter.measure(t, state.q, state.v));
  };
  record(ida.time(), ida.y(), ida.yp());
  ida.run(record);
  trace.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  trace.steps = ida.statistics().steps;
  return trace;
}

struct Summary {
  double max_error = 0.0, drift_rate = 0.0, max_phi = 0.0, max_phi_v = 0.0,
         max_momentum_error = 0.0;
};

Summary summarize(const Trace& trace, double energy_scale, bool momentum) {
  Summary s;
  const Sample& first = trace.samples.front();
  // Least-squares slope of e(t) = (E − E₀)/E_scale against t.
  double st = 0, se = 0, stt = 0, ste = 0;
  for (const Sample& x : trace.samples) {
    const double e = (x.energy - first.energy) / energy_scale;
    s.max_error = std::max(s.max_error, std::abs(e));
    s.max_phi = std::max(s.max_phi, x.phi);
    s.max_phi_v = std::max(s.max_phi_v, x.phi_v);
    if (momentum)
      s.max_momentum_error =
          std::max(s.max_momentum_error, std::abs(x.momentum - first.momentum) / first.momentum);
    st += x.t, se += e, stt += x.t * x.t, ste += x.t * e;
  }
  const auto n = static_cast<double>(trace.samples.size());
  s.drift_rate = (n * ste - st * se) / (n * stt - st * st);
  return s;
}

void write_trace(const std::filesystem::path& dir, const Scene& scene, const Trace& trace) {
  auto out = fmt::output_file((dir / (scene.name + "_" + trace.run + ".csv")).string());
  out.print("t,energy,rel_energy_error,max_abs_phi,max_abs_phi_v,rel_angular_momentum_error\n");
  const Sample& first = trace.samples.front();
  for (const Sample& x : trace.samples)
    out.print("{:.6f},{:.12e},{:.6e},{:.6e},{:.6e},{}\n", x.t, x.energy,
              (x.energy - first.energy) / scene.energy_scale, x.phi, x.phi_v,
              scene.conserves_momentum
                  ? fmt::format("{:.6e}", (x.momentum - first.momentum) / first.momentum)
                  : std::string("nan"));
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> positional;
  bool with_ida = true;
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--no-ida")
      with_ida = false;
    else
      positional.emplace_back(argv[i]);
  }
  const std::filesystem::path dir = positional.size() > 0 ? positional[0] : "out/energy_drift";
  const double duration = positional.size() > 1 ? std::atof(positional[1].c_str()) : 20.0;
  if (!(duration > 0.0)) {
    fmt::print(stderr, "usage: {} [output directory] [duration > 0] [--no-ida]\n", argv[0]);
    return 2;
  }
  std::filesystem::create_directories(dir);
  auto summary = fmt::output_file((dir / "summary.csv").string());
  summary.print(
      "scene,run,max_abs_rel_energy_error,drift_rate_per_s,max_abs_phi,max_abs_phi_v,"
      "max_rel_angular_momentum_error,steps,wall_s\n");
  fmt::print("{:9} {:32} {:>11} {:>11} {:>10} {:>10} {:>10} {:>7} {:>7}\n", "scene", "run",
             "max|dE|/E", "drift [1/s]", "max|Phi|", "max|Phi_v|", "max|dL|/L", "steps", "wall[s]");
  JsonObject meta, results;
  meta.set("study", "ancf-study-energy-drift")
      .set("duration_s", duration)
      .set("with_ida", with_ida);
  meta.set("sample_interval_s", kSampleInterval);
  for (Scene scene : {pendulum_scene(), spinning_scene(), rigid_scene()}) {
    std::vector<std::function<Trace()>> runs;
    for (const double h : {2e-3, 1e-3, 5e-4}) {
      for (const double rho : {0.9, 0.6})
        runs.emplace_back(
            [&, h, rho] { return run_generalized_alpha(scene, duration, h, rho, false); });
      runs.emplace_back([&, h] { return run_generalized_alpha(scene, duration, h, 1.0, true); });
    }
    if (with_ida)
      for (const double rtol : {1e-4, 1e-6, 1e-8})
        runs.emplace_back([&, rtol] { return run_ida(scene, duration, rtol); });
    for (const auto& run : runs) {
      Trace trace;
      try {
        trace = run();
      } catch (const std::exception& e) {
        fmt::print("{:9} failed: {}\n", scene.name, e.what());
        continue;
      }
      write_trace(dir, scene, trace);
      const Summary s = summarize(trace, scene.energy_scale, scene.conserves_momentum);
      summary.print("{},{},{:.6e},{:.6e},{:.6e},{:.6e},{:.6e},{},{:.4f}\n", scene.name, trace.run,
                    s.max_error, s.drift_rate, s.max_phi, s.max_phi_v, s.max_momentum_error,
                    trace.steps, trace.wall);
      fmt::print("{:9} {:32} {:11.3e} {:11.3e} {:10.2e} {:10.2e} {:10.2e} {:7} {:7.3f}\n",
                 scene.name, trace.run, s.max_error, s.drift_rate, s.max_phi, s.max_phi_v,
                 s.max_momentum_error, trace.steps, trace.wall);
      JsonObject r;
      r.set("max_abs_rel_energy_error", s.max_error).set("drift_rate_per_s", s.drift_rate);
      r.set("steps", static_cast<long>(trace.steps)).set("wall_s", trace.wall);
      results.set(scene.name + "/" + trace.run, r);
    }
  }
  meta.set("runs", results);
  auto json = fmt::output_file((dir / "run.json").string());
  json.print("{}\n", meta.text());
  fmt::print("CSV and run.json written to {}\n", dir.string());
  return 0;
}
