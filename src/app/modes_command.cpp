// `ancf modes`: natural frequencies and mode shapes of a scene linearised about its initial state
// (which must be an equilibrium) or about its static equilibrium (--static, solved as by
// `ancf static`), with the scene's constraints (modal_analysis.hpp: dense, small models).
// Writes modes.csv (one row per mode), one .pvd series per mode that animates one period of the
// mode shape in ParaView, and run.json.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include "ancf/io/run_outputs.hpp"
#include "ancf/io/vtk_writer.hpp"
#include "ancf/system/modal_analysis.hpp"
#include "commands.hpp"
#include "scene_statics.hpp"

namespace ancf::app {

namespace {

/// Largest displacement of a cable node or body origin in `shape`, or of any coordinate if those
/// do not move (a mode of slopes or axes only).
double largest_displacement(const Model& model, const VecX& shape) {
  double largest = 0.0;
  for (const CableData& c : model.cables())
    for (Index k = 0; k < c.node_count; ++k)
      largest = std::max(largest, shape.segment<3>(c.first_coordinate + 6 * k).norm());
  for (const BodyData& b : model.bodies())
    largest = std::max(largest, shape.segment<3>(b.first_coordinate).norm());
  return largest > 0.0 ? largest : shape.cwiseAbs().maxCoeff();
}

/// Mode `mode`'s series: frames k = 0 … frames−1 at q = q₀ + a sin(2πk/frames) φ (a: the largest
/// displacement equals `amplitude`), velocity a ω cos(2πk/frames) φ; the .pvd time of a frame is
/// its phase in periods, k/frames, so that ParaView plays one period per loop.
void write_mode_series(const Scene& scene, const SystemState& about, const NaturalModes& modes,
                       Index mode, double amplitude, int frames, const std::string& dir) {
  const std::string name = fmt::format("mode_{:03d}", mode + 1);
  std::filesystem::create_directories(std::filesystem::path(dir) / "modes" / name);
  const VecX& phi = modes.shapes.col(mode);
  const double largest = largest_displacement(scene.model, phi);
  const double a = largest > 0.0 ? amplitude / largest : 0.0;
  const double omega = std::isfinite(modes.omega(mode)) ? modes.omega(mode) : 0.0;
  SystemState s = about;
  Workspace ws(scene.model);
  PvdSeries pvd(dir + "/modes/" + name + ".pvd");
  for (int k = 0; k < frames; ++k) {
    const double phase = 2.0 * std::numbers::pi * k / frames;
    s.q = about.q + a * std::sin(phase) * phi;
    s.v = a * omega * std::cos(phase) * phi;
    const std::string file = fmt::format("{}/frame_{:03d}.vtp", name, k);
    write_vtp(dir + "/modes/" + file, scene.model, s, scene.output.vtk_samples_per_element,
              tenth_of_extent(scene.model), ws);
    pvd.add(static_cast<double>(k) / frames, file);
  }
}

}  // namespace

int modes_command(const ModesOptions& options) {
  Scene scene;
  const std::string text = read_text(options.scene_path);
  try {
    scene = load_scene(options.scene_path);
    const double n = static_cast<double>(scene.model.coordinate_count());
    if (n > options.max_coordinates)
      throw ModelError(fmt::format(
          "{}: {} coordinates exceed the dense eigen-analysis bound of {} (O(n^3) time, "
          "O(n^2) memory); --max-coordinates N raises it",
          options.scene_path, scene.model.coordinate_count(), options.max_coordinates));
    std::filesystem::create_directories(options.out_dir);
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  const auto start = std::chrono::steady_clock::now();
  std::string status = "completed", message;
  SceneStatics statics;
  NaturalModes modes;
  ModalAnalysisOptions modal;
  modal.component = options.component;
  JsonObject opts, counts, results;
  try {
    if (options.about_static) {
      solve_scene_statics(scene, options.statics, statics);
      add_static_json(options.statics, statics.statistics, opts, counts, results);
      modes = natural_modes(scene.model, statics.state, modal);
    } else {
      statics.state = SystemState::initial(scene.model);
      modes = natural_modes_at_initial_equilibrium(scene.model, modal);
    }
  } catch (const SolverError& e) {
    status = "failed", message = e.what();
  } catch (const std::domain_error& e) {
    // The model cannot be evaluated at the state (e.g. a rod tangent turned over against its
    // frame): reported like a solver failure, with run.json written.
    status = "failed", message = e.what();
  } catch (const std::invalid_argument& e) {
    // Not an equilibrium, or a component that is coupled to the others.
    status = "failed", message = e.what();
    if (!options.about_static && message.find("not an equilibrium") != std::string::npos)
      message += "; with loads or gravity use --static (modes about the static equilibrium)";
  } catch (const std::runtime_error& e) {
    // The eigen-solver did not converge (natural_modes).
    status = "failed", message = e.what();
  }
  const Index count =
      status == "completed"
          ? std::min<Index>(options.count, static_cast<Index>(modes.omega_squared.size()))
          : 0;
  if (status == "completed") {
    std::ofstream csv(options.out_dir + "/modes.csv");
    csv << "mode,omega_squared,omega,frequency,period\n";
    for (Index i = 0; i < count; ++i) {
      const double w = modes.omega(i);
      csv << fmt::format("{},{},{},{},{}\n", i + 1, modes.omega_squared[i], w,
                         w / (2.0 * std::numbers::pi), 2.0 * std::numbers::pi / w);
    }
    if (options.vtk) {
      const double amplitude =
          options.amplitude > 0.0 ? options.amplitude : tenth_of_extent(scene.model);
      for (Index i = 0; i < count; ++i)
        write_mode_series(scene, statics.state, modes, i, amplitude, options.frames,
                          options.out_dir);
    }
  } else {
    fmt::print(stderr, "modal analysis failed: {}\n", message);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  opts.set("about", options.about_static ? "static" : "initial")
      .set("count", static_cast<long>(options.count))
      .set("component", options.component < 0 ? "all" : std::string(1, "xyz"[options.component]))
      .set("out", options.out_dir);
  if (status == "completed")
    results.set("modes", static_cast<long>(count))
        .set("selected_coordinates", static_cast<long>(modes.selected_coordinates))
        .set("constraint_rank", static_cast<long>(modes.constraint_rank))
        .set("asymmetry", modes.asymmetry);
  JsonObject meta = run_json_header(scene, text, "modes", status, message, wall);
  meta.set("options", opts).set("counters", counts).set("results", results);
  write_run_json(options.out_dir, meta);

  if (!options.quiet && status == "completed") {
    fmt::print("{}: {} modes about the {} ({} coordinates, constraint rank {}), in {}\n",
               scene.name, count, options.about_static ? "static equilibrium" : "initial state",
               modes.selected_coordinates, modes.constraint_rank, options.out_dir);
    // ω² shown too: a rigid-body mode's ω² is round-off and may be negative, where ω is nan.
    fmt::print("  {:>4}  {:>18}  {:>16}  {:>16}\n", "mode", "omega^2 [rad2/s2]", "omega [rad/s]",
               "f [Hz]");
    for (Index i = 0; i < count; ++i)
      fmt::print("  {:>4}  {:>18.9g}  {:>16.9g}  {:>16.9g}\n", i + 1, modes.omega_squared[i],
                 modes.omega(i), modes.omega(i) / (2.0 * std::numbers::pi));
  }
  return status == "completed" ? 0 : 2;
}

}  // namespace ancf::app
