// Why IDA takes so many steps on the capture scene (issue: "IDA through contact"): integrate the
// scene with IDA in short windows and record, at the end of each, the step size, the order and the
// differential unknown with the largest weighted local error estimate (the one that limits the
// step), classified by kind: rope node position r / slope r' / rod twist (q or v), pole, ring. The
// scene's [integrator.ida] slope_scale and twist_scale apply. Prints steps per
// second of model time and the share of windows each kind limited; writes windows.csv.
//
// Usage: ancf-study-ida-capture [--scene studies/scenes/capture.toml] [--t-end T] [--window W]
//                               [--rtol R] [--max-order K] [--axial-damping C]
//                               [--slope-position-scale] [--tension-only-tangent]
//                               [--max-newton N] [--friction MU]
//                               [--regularization-speed V] [--onset-depth D] [--out DIR]
#include <fmt/format.h>

#include <toml++/toml.h>
#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "ancf/io/scene.hpp"
#include "ancf/io/simulation.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"

using namespace ancf;

namespace {

struct Options {
  std::string scene = "studies/scenes/capture.toml", out = "out/ida-capture-diagnosis";
  double t_end = 3.0, window = 1e-3, rtol = 0.0, axial_damping = -1.0;
  double friction = -1.0, regularization_speed = 0.0, onset_depth = 0.0;  // contact law overrides
  int max_order = 0;
  bool slope_position_scale = false;
  bool tension_only_tangent = false;
  int max_newton = 0;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--scene")
      o.scene = value();
    else if (a == "--t-end")
      o.t_end = std::stod(value());
    else if (a == "--window")
      o.window = std::stod(value());
    else if (a == "--rtol")
      o.rtol = std::stod(value());
    else if (a == "--max-order")
      o.max_order = std::stoi(value());
    else if (a == "--axial-damping")
      o.axial_damping = std::stod(value());
    else if (a == "--friction")
      o.friction = std::stod(value());
    else if (a == "--regularization-speed")
      o.regularization_speed = std::stod(value());
    else if (a == "--onset-depth")
      o.onset_depth = std::stod(value());
    else if (a == "--out")
      o.out = value();
    else if (a == "--slope-position-scale")
      o.slope_position_scale = true;
    else if (a == "--tension-only-tangent")
      o.tension_only_tangent = true;
    else if (a == "--max-newton")
      o.max_newton = std::stoi(value());
    else
      throw std::invalid_argument("unknown option " + a);
  }
  return o;
}

// "rope r'", "rope r' rate", "rope twist", "pole", …: the kind of differential unknown i of the GGL
// problem.
std::string kind_of(const Model& model, Index i) {
  const Index n = model.coordinate_count();
  const bool velocity = i >= n;
  const Index c = velocity ? i - n : i;
  for (const CableData& cable : model.cables()) {
    const Index local = c - cable.first_coordinate;
    if (local >= 0 && local < 6 * cable.node_count)
      return std::string(local % 6 < 3 ? "rope r" : "rope r'") + (velocity ? " rate" : "");
    if (cable.is_twist_coordinate(c)) return std::string("rope twist") + (velocity ? " rate" : "");
  }
  for (const BodyData& b : model.bodies())
    if (c >= b.first_coordinate && c < b.first_coordinate + 12)
      return b.name + (velocity ? " rate" : "");
  return "other";
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  Scene scene;
  try {
    o = parse(argc, argv);
    toml::table root = toml::parse_file(o.scene);
    if (o.axial_damping >= 0.0)
      for (const char* kind : {"cable", "rod"})  // the ropes are cables or Kirchhoff rods
        if (toml::array* ropes = root[kind].as_array())
          for (toml::node& c : *ropes)
            c.as_table()->at("section").as_table()->insert_or_assign("axial_damping",
                                                                     o.axial_damping);
    if (toml::array* contacts = root["contact"].as_array())  // a scene may have none
      for (toml::node& c : *contacts) {
        toml::table& law = *c.as_table()->at("law").as_table();
        if (o.friction >= 0.0) law.insert_or_assign("friction", o.friction);
        if (o.regularization_speed > 0.0)
          law.insert_or_assign("regularization_speed", o.regularization_speed);
        if (o.onset_depth > 0.0) law.insert_or_assign("onset_depth", o.onset_depth);
      }
    std::ostringstream text;
    text << root;
    scene = load_scene_from_string(text.str(), o.scene);
  } catch (const std::exception& e) {
    fmt::print(stderr, "ancf-study-ida-capture: {}\n", e.what());
    return 1;
  }
  const IntegratorSettings& s = scene.integrator;
  GglScales scales = ida_scales(s);  // the scene's, as `ancf run` takes them
  if (o.slope_position_scale) scales.slope = SlopeScale::position_equivalent;
  GglProblem problem(scene.model, scales, ContactPatternOptions{.policy = s.contact_pattern});
  problem.set_cable_tangent(o.tension_only_tangent ? CableTangent::tension_only : s.cable_tangent);
  problem.set_rod_frame_turn(s.rod_frame_turn);
  IdaOptions io;
  io.rtol = o.rtol > 0.0 ? o.rtol : s.rtol;
  io.max_order = o.max_order > 0 ? o.max_order : s.max_order;
  io.max_step = s.max_step;
  io.atol_position = s.ida_atol_position;
  io.atol_velocity = s.ida_atol_velocity;
  io.atol_multiplier = s.ida_atol_multiplier;
  io.stop_time = o.t_end;
  if (o.max_newton > 0) io.max_nonlinear_iterations = o.max_newton;
  IdaIntegrator ida(problem, io);

  std::filesystem::create_directories(o.out);
  std::ofstream csv(o.out + "/windows.csv");
  csv << "t,steps,step_size,order,error_test_failures,convergence_failures,worst_kind,worst_"
         "unknown,"
         "weighted_local_error\n";
  std::map<std::string, long> limited;  // windows per limiting kind
  long windows = 0, steps_before = 0;
  std::string status = "completed";
  const auto start = std::chrono::steady_clock::now();
  try {
    for (double t = o.window; t <= o.t_end * (1.0 + 1e-12); t += o.window) {
      ida.advance(t);
      const IdaStatistics st = ida.statistics();
      double weighted = 0.0;
      const Index worst = ida.worst_local_error(weighted);
      const std::string kind = worst >= 0 ? kind_of(scene.model, worst) : "-";
      ++limited[kind];
      ++windows;
      csv << fmt::format("{:.6f},{},{:.4e},{},{},{},{},\"{}\",{:.3e}\n", ida.time(), st.steps,
                         st.last_step, st.last_order, st.error_test_failures,
                         st.convergence_failures, kind,
                         worst >= 0 ? problem.describe_row(worst) : "-", weighted);
      if (std::abs(t - std::round(t)) < 0.5 * o.window) {
        fmt::print("t = {:5.2f} s: {:8} steps in the last second, last step {:.2e} s, order {}\n",
                   t, st.steps - steps_before, st.last_step, st.last_order);
        steps_before = st.steps;
      }
    }
  } catch (const std::exception& e) {
    status = e.what();
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("{}; {:.1f} s wall\n{}", status, wall, ida.statistics().table());
  fmt::print("unknown with the largest weighted local error at the end of each {:.0e} s window:\n",
             o.window);
  for (const auto& [kind, count] : limited)
    fmt::print("  {:<16} {:6.1f} %\n", kind,
               100.0 * static_cast<double>(count) / static_cast<double>(std::max(windows, 1L)));
  return status == "completed" ? 0 : 2;
}
