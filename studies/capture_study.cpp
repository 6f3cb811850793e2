// The capture example (shared/CAPTURE.md) end to end: run studies/scenes/capture.toml with either
// integrator, detect the paper's events and write what the plots and the event table need.
//
// Usage: ancf-capture [--scene studies/scenes/capture.toml] [--integrator genalpha|ida]
//                     [--elements N] [--t-end T] [--omega-max DEG_PER_S] [--tilt DEG]
//                     [--friction MU] [--regularization-speed V] [--step H] [--rtol R]
//                     [--rho-inf R] [--axial-damping C] [--bending EI] [--bending-damping CB]
//                     [--mass-damping ALPHA] [--no-rope-rope] [--index2] [--free-pole]
//                     [--contact-pattern near|all] [--contact-samples K] [--set KEY=VALUE ...]
//                     [--scene-set KEY=VALUE ...] [--out DIR]
//                     [--error-control] [--error-rtol R] [--error-atol A] [--h-min H] [--h-max H]
//                     [--step-change MODE] [--refresh-on-contact] [--newton-damping N] [--fast]
// MODE: automatic|restart|rescale|rescale_with_velocity|rescale_climbs.
// --set sets any key of the scene's [integrator] table by its dotted path below it, e.g.
// --set genalpha.step=5e-4 or --set ida.max_order=2 (VALUE: a TOML number, "string" or true).
// --scene-set sets any key of the scene by its dotted path from the file's root, as in the sweep
// files and SceneError messages, e.g. --scene-set 'rod[0].grading.band_ratio=0.3' or
// --scene-set 'contact[0].law.stiffness=1.5e7'; applied last (after the flags and --set), and
// checked by the scene rules as if written in the file.
// `--contact-pattern all` reserves every candidate contact block (the first design), to compare.
// --contact-samples K: samples per element of the rope-shape (shaft, knob) pairs; mesh studies
// scale it with 1/elements to keep the contact sample spacing fixed (docs/capture.md).
// --error-control etc. set the [integrator.genalpha] keys of error-controlled stepping
// (docs/scenes.md).
// --fast: generalized-α settings that meet the issue-15 agreement with the fixed-step reference at
// a fraction of its cost (studies/README.md, "The capture example through contact"):
// error-controlled stepping, Newton rtol 1e-4, ρ∞ 0.5, the tension-only cable tangent,
// failure-ceiling rate 0.3, i.e.
// --error-control --rtol 1e-4 --rho-inf 0.5 --set cable_tangent='"tension_only"'
// --set genalpha.ceiling_rate=0.3; flags given explicitly take precedence (scripts/demo uses it).
// Overrides change the scene's TOML before it is built (element counts, and the rope–rope
// candidate ranges with them; drive ω_max; pole tilt; friction of every pair; rope damping and
// bending, mass-proportional damping α [1/s]; rope–rope pairs off; integrator; generalized-α
// error-controlled stepping and its tolerances, step-change mode, fresh matrix on contact change),
// so the mesh check and the calibration run exactly the scene file otherwise. Writes into DIR
// (default out/capture-<integrator>): samples.csv (one row per output time), snapshots.csv (node
// positions of the ropes and the pole axis at t = 0, the event times and the end), events.json
// (event table, counters, options, wall time). Prints the event table.
#include <fmt/format.h>

#include <toml++/toml.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "ancf/io/run_metadata.hpp"
#include "ancf/io/scene.hpp"
#include "ancf/io/scene_overrides.hpp"
#include "ancf/io/simulation.hpp"
#include "ancf/scenes/capture_events.hpp"
#include "capture_mesh.hpp"

using namespace ancf;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Options {
  std::string scene = "studies/scenes/capture.toml", integrator = "genalpha", out;
  long elements = 0;         // 0: as in the scene
  long contact_samples = 0;  // rope-shape samples per element; 0: as in the scene
  double t_end = 0.0, omega_max_deg = 0.0, tilt_deg = -1.0, friction = -1.0, step = 0.0, rtol = 0.0;
  double regularization_speed = 0.0, rho_infinity = -1.0, axial_damping = -1.0,
         bending_stiffness = -1.0;
  double bending_damping = -1.0, mass_damping = -1.0;
  bool free_pole = false, rope_rope = true, index2 = false;
  bool error_control = false, refresh_on_contact = false, fast = false;
  double error_rtol = 0.0, error_atol = 0.0, h_min = 0.0, h_max = -1.0;
  std::string step_change;
  long newton_damping = -1;
  std::string contact_pattern;                                // "" (scene's), "near" or "all"
  std::vector<std::pair<std::string, std::string>> settings;  // --set KEY=VALUE under [integrator]
  std::vector<SceneOverride> scene_settings;                  // --scene-set KEY=VALUE from the root
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
    else if (a == "--integrator")
      o.integrator = value();
    else if (a == "--elements")
      o.elements = std::stol(value());
    else if (a == "--t-end")
      o.t_end = std::stod(value());
    else if (a == "--omega-max")
      o.omega_max_deg = std::stod(value());
    else if (a == "--tilt")
      o.tilt_deg = std::stod(value());
    else if (a == "--friction")
      o.friction = std::stod(value());
    else if (a == "--step")
      o.step = std::stod(value());
    else if (a == "--rtol")
      o.rtol = std::stod(value());
    else if (a == "--regularization-speed")
      o.regularization_speed = std::stod(value());
    else if (a == "--rho-inf")
      o.rho_infinity = std::stod(value());
    else if (a == "--axial-damping")
      o.axial_damping = std::stod(value());
    else if (a == "--bending")
      o.bending_stiffness = std::stod(value());
    else if (a == "--bending-damping")
      o.bending_damping = std::stod(value());
    else if (a == "--mass-damping")
      o.mass_damping = std::stod(value());
    else if (a == "--free-pole")
      o.free_pole = true;
    else if (a == "--index2")
      o.index2 = true;
    else if (a == "--no-rope-rope")
      o.rope_rope = false;
    else if (a == "--error-control")
      o.error_control = true;
    else if (a == "--error-rtol")
      o.error_rtol = std::stod(value());
    else if (a == "--error-atol")
      o.error_atol = std::stod(value());
    else if (a == "--h-min")
      o.h_min = std::stod(value());
    else if (a == "--h-max")
      o.h_max = std::stod(value());
    else if (a == "--step-change")
      o.step_change = value();
    else if (a == "--refresh-on-contact")
      o.refresh_on_contact = true;
    else if (a == "--newton-damping")
      o.newton_damping = std::stol(value());
    else if (a == "--out")
      o.out = value();
    else if (a == "--fast")
      o.fast = true;
    else if (a == "--contact-pattern")
      o.contact_pattern = value();
    else if (a == "--contact-samples")
      o.contact_samples = std::stol(value());
    else if (a == "--set") {
      const std::string kv = value();
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0)
        throw std::invalid_argument("--set needs KEY=VALUE, got " + kv);
      o.settings.emplace_back(kv.substr(0, eq), kv.substr(eq + 1));
    } else if (a == "--scene-set")
      o.scene_settings.push_back(parse_scene_override(value()));
    else
      throw std::invalid_argument("unknown option " + a);
  }
  if (o.integrator != "genalpha" && o.integrator != "ida")
    throw std::invalid_argument("--integrator must be genalpha or ida");
  if (o.out.empty()) o.out = "out/capture-" + o.integrator;
  if (o.fast) {
    if (o.integrator != "genalpha")
      throw std::invalid_argument("--fast sets generalized-α options; not with --integrator ida");
    o.error_control = true;
    if (o.rtol == 0.0) o.rtol = 1e-4;
    if (o.rho_infinity < 0.0) o.rho_infinity = 0.5;
    // Before the user's --set entries, which are applied after these and so take precedence.
    o.settings.insert(o.settings.begin(),
                      {{"cable_tangent", "\"tension_only\""}, {"genalpha.ceiling_rate", "0.3"}});
  }
  return o;
}

toml::table* find_named(toml::table& root, const char* array, const std::string& name) {
  if (toml::array* a = root[array].as_array())
    for (toml::node& n : *a)
      if (toml::table* t = n.as_table(); t && (*t)["name"].value<std::string>() == name) return t;
  throw std::invalid_argument(std::string("the scene has no [[") + array + "]] named '" + name +
                              "'");
}

// The scene text with the command-line overrides applied (see the file comment).
std::string apply_overrides(const Options& o) {
  toml::table root = toml::parse_file(o.scene);
  if (o.elements > 0) studies::set_capture_rope_elements(root, o.elements);
  const bool rods = !root["cable"].as_array();  // the ropes are [[rod]]s: they always bend
  if (o.axial_damping >= 0.0 || o.bending_stiffness >= 0.0 || o.bending_damping >= 0.0 ||
      o.mass_damping >= 0.0)
    for (toml::node& c : *root[rods ? "rod" : "cable"].as_array()) {
      toml::table& section = *c.as_table()->at("section").as_table();
      if (o.axial_damping >= 0.0) section.insert_or_assign("axial_damping", o.axial_damping);
      if (o.bending_stiffness > 0.0) {
        if (!rods) section.insert_or_assign("bending", true);  // a rod has no 'bending' switch
        section.erase("EI2");
        section.erase("EI3");
        section.insert_or_assign("EI", o.bending_stiffness);
      }
      if (o.bending_damping >= 0.0) section.insert_or_assign("bending_damping", o.bending_damping);
      if (o.mass_damping >= 0.0) section.insert_or_assign("mass_damping", o.mass_damping);
    }
  toml::array* contacts = root["contact"].as_array();
  if (!contacts)
    throw std::invalid_argument("the scene has no [[contact]] entries (not a capture scene)");
  if (!o.rope_rope)
    for (std::size_t k = contacts->size(); k-- > 0;)
      if ((*contacts)[k].as_table()->contains("other_cable"))
        contacts->erase(contacts->begin() + static_cast<long>(k));
  for (toml::node& c : *contacts) {
    toml::table& law = *c.as_table()->at("law").as_table();
    if (o.friction >= 0.0) law.insert_or_assign("friction", o.friction);
    if (o.contact_samples > 0 && c.as_table()->contains("shape"))
      c.as_table()->insert_or_assign("samples_per_element",
                                     static_cast<int64_t>(o.contact_samples));
    if (o.regularization_speed > 0.0)
      law.insert_or_assign("regularization_speed", o.regularization_speed);
  }
  if (o.omega_max_deg > 0.0)
    find_named(root, "drive", "ring drive")
        ->at("reference")
        .as_table()
        ->insert_or_assign("max_rate", o.omega_max_deg * kDeg);
  if (o.tilt_deg >= 0.0)
    find_named(root, "body", "pole")
        ->at("rotation")
        .as_table()
        ->insert_or_assign("angle", o.tilt_deg * kDeg);
  if (o.free_pole) {
    toml::array& joints = *root["joint"].as_array();
    for (auto it = joints.begin(); it != joints.end(); ++it)
      if ((*it->as_table())["name"].value<std::string>() == "pole root") {
        joints.erase(it);
        break;
      }
  }
  toml::table& integrator = *root["integrator"].as_table();
  integrator.insert_or_assign("method", o.integrator);
  if (o.t_end > 0.0) integrator.insert_or_assign("t_end", o.t_end);
  if (o.rtol > 0.0) integrator.insert_or_assign("rtol", o.rtol);
  if (!integrator.contains("genalpha")) integrator.insert_or_assign("genalpha", toml::table{});
  toml::table& genalpha = *integrator.at("genalpha").as_table();
  if (o.index2) genalpha.insert_or_assign("formulation", "stabilized_index2");
  if (o.rho_infinity >= 0.0) genalpha.insert_or_assign("rho_infinity", o.rho_infinity);
  if (o.error_control) genalpha.insert_or_assign("stepping", "error_controlled");
  if (o.error_rtol > 0.0) genalpha.insert_or_assign("error_rtol", o.error_rtol);
  if (o.error_atol > 0.0) genalpha.insert_or_assign("error_atol", o.error_atol);
  if (o.h_min > 0.0) genalpha.insert_or_assign("h_min", o.h_min);
  if (o.h_max >= 0.0) genalpha.insert_or_assign("h_max", o.h_max);
  if (!o.step_change.empty()) genalpha.insert_or_assign("step_change", o.step_change);
  if (o.refresh_on_contact) genalpha.insert_or_assign("refresh_on_contact_change", true);
  if (o.newton_damping >= 0)
    genalpha.insert_or_assign("newton_damping", static_cast<int64_t>(o.newton_damping));
  if (o.step > 0.0) {
    const char* group = o.integrator == "ida" ? "ida" : "genalpha";
    if (!integrator.contains(group)) integrator.insert_or_assign(group, toml::table{});
    integrator.at(group).as_table()->insert_or_assign(o.integrator == "ida" ? "max_step" : "step",
                                                      o.step);
  }
  if (!o.contact_pattern.empty()) integrator.insert_or_assign("contact_pattern", o.contact_pattern);
  std::ostringstream text;
  text << root;
  return text.str();
}

// Rope node positions and the pole axis (root and tip) at one time.
struct Snapshot {
  std::string label;
  double t = 0.0;
  std::vector<Vec3> points;  // ropes' nodes in order, then pole root and tip
};

Snapshot snapshot_of(const Model& model, const SystemState& s, const std::string& label) {
  Snapshot snap{label, s.t, {}};
  for (const CableData& c : model.cables())
    for (Index k = 0; k < c.node_count; ++k)
      snap.points.push_back(s.q.segment<3>(c.first_coordinate + 6 * k));
  for (const BodyData& b : model.bodies())
    if (b.name == "pole") {
      const Index i = b.first_coordinate;
      snap.points.push_back(s.q.segment<3>(i));
      snap.points.push_back(s.q.segment<3>(i) + 0.273 * s.q.segment<3>(i + 9));
    }
  return snap;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  Scene scene;
  try {
    o = parse(argc, argv);
    // --set KEY=VALUE below [integrator]: the io layer's scene overrides (scene_overrides.hpp).
    std::vector<SceneOverride> settings;
    for (const auto& [key, text] : o.settings) settings.push_back({"integrator." + key, text});
    settings.insert(settings.end(), o.scene_settings.begin(), o.scene_settings.end());
    scene = load_scene_from_string(apply_overrides(o), o.scene, settings);
  } catch (const std::exception& e) {
    fmt::print(stderr, "ancf-capture: {}\n", e.what());
    return 1;
  }
  std::filesystem::create_directories(o.out);
  std::ofstream csv(o.out + "/samples.csv");
  csv << "t,ring_angle_deg,ring_rate_deg_s,drive_torque,tilt_deg,tilt_rate_deg_s,lateral_offset_mm,"
         "lateral_speed_mm_s,on_pole_1,on_pole_2,on_pole_3,pole_force_1,pole_force_2,pole_force_3,"
         "ring_tension_1,ring_tension_2,ring_tension_3,rope_rope_force,pole_gap_mm_1,pole_gap_mm_2,"
         "pole_gap_mm_3\n";

  CaptureObserver observer(scene.model);
  std::vector<Snapshot> frames;  // every output frame (kept for the event-time snapshots)
  SimulationHooks hooks;
  hooks.output = [&](const SystemState& state) {
    const CaptureSample& s = observer.record(state);
    csv << fmt::format(
        "{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{},{},{:.6g},{:.6g},{:.6g},"
        "{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}\n",
        s.t, s.ring_angle / kDeg, s.ring_rate / kDeg, s.drive_torque, s.tilt / kDeg,
        s.tilt_rate / kDeg, 1e3 * s.lateral_offset, 1e3 * s.lateral_speed, int(s.rope_on_pole[0]),
        int(s.rope_on_pole[1]), int(s.rope_on_pole[2]), s.rope_pole_force[0], s.rope_pole_force[1],
        s.rope_pole_force[2], s.ring_end_tension[0], s.ring_end_tension[1], s.ring_end_tension[2],
        s.rope_rope_force, 1e3 * s.rope_pole_gap[0], 1e3 * s.rope_pole_gap[1],
        1e3 * s.rope_pole_gap[2]);
    csv.flush();
    frames.push_back(snapshot_of(scene.model, state, ""));
  };
  long last_report = 0;
  hooks.progress = [&](double t) {
    if (static_cast<long>(t) > last_report)
      fmt::print(stderr, "  t = {:.0f} s\n", t), last_report = static_cast<long>(t);
  };

  SimulationCounters counters;
  SimulationTimings timings;
  std::string status = "completed", message;
  const auto start = std::chrono::steady_clock::now();
  try {
    simulate(scene.model, scene.integrator,
             output_times(scene.output.interval, scene.integrator.t_end), hooks, counters, timings);
  } catch (const std::exception& e) {
    status = "failed";
    message = e.what();
    fmt::print(stderr, "run failed: {}\noutputs up to the failure are kept in {}\n", message,
               o.out);
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const CaptureEvents ev = observer.events();

  // Snapshots at t = 0, each event that happened, and the end (nearest output frame).
  std::ofstream snaps(o.out + "/snapshots.csv");
  snaps << "label,t,point,x,y,z\n";
  auto write_snapshot = [&](const std::string& label, double t) {
    if (std::isnan(t) || frames.empty()) return;
    const Snapshot* best = &frames.front();
    for (const Snapshot& f : frames)
      if (std::abs(f.t - t) < std::abs(best->t - t)) best = &f;
    for (std::size_t k = 0; k < best->points.size(); ++k)
      snaps << fmt::format("{},{:.6f},{},{:.9g},{:.9g},{:.9g}\n", label, best->t, k,
                           best->points[k].x(), best->points[k].y(), best->points[k].z());
  };
  write_snapshot("start", 0.0);
  for (int i = 0; i < 3; ++i)
    write_snapshot(fmt::format("first contact rope {}", i + 1), ev.first_contact[i]);
  write_snapshot("all three", ev.all_three);
  write_snapshot("stall", ev.stall);
  write_snapshot("lock", ev.lock);
  if (!frames.empty()) write_snapshot("end", frames.back().t);

  JsonObject events, opts, counts, meta, times;
  for (const auto& [name, value] : timings) times.set(name, value);
  for (int i = 0; i < 3; ++i)
    events.set(fmt::format("first_contact_rope_{}", i + 1), ev.first_contact[i]);
  events.set("first_rope", static_cast<long>(ev.first_rope + 1))
      .set("all_three", ev.all_three)
      .set("stall", ev.stall)
      .set("lock", ev.lock)
      .set("final_tilt_deg", ev.final_tilt / kDeg)
      .set("final_lateral_offset_m", ev.final_lateral_offset)
      .set("ring_angle_at_stall_deg", ev.ring_angle_at_stall / kDeg)
      .set("tension_at_lock_1", ev.tension_at_lock[0])
      .set("tension_at_lock_2", ev.tension_at_lock[1])
      .set("tension_at_lock_3", ev.tension_at_lock[2])
      .set("peak_contact_force", ev.peak_contact_force);
  const IntegratorSettings& s = scene.integrator;
  opts.set("integrator", o.integrator)
      .set("elements_per_rope", static_cast<long>(scene.model.cables()[0].elements.size()))
      .set("t_end", s.t_end)
      .set("rtol", s.rtol)
      .set("step", o.integrator == "ida" ? s.max_step : s.step)
      .set("fast", o.fast)
      .set("rho_infinity", s.rho_infinity)
      .set("cable_tangent",
           s.cable_tangent == CableTangent::tension_only ? "tension_only" : "exact")
      .set("rod_frame_turn", s.rod_frame_turn)
      .set("ida_slope_scale", ida_scale_name(s.ida_slope_position_scale))
      .set("ida_twist_scale", ida_scale_name(s.ida_twist_position_scale))
      .set("genalpha_ceiling_rate", s.ga_controller.easy_rate)
      .set("genalpha_stepping", s.ga_error_controlled ? "error_controlled" : "fixed")
      .set("genalpha_error_rtol", s.ga_controller.rtol)
      .set("genalpha_error_atol", s.ga_controller.atol)
      .set("genalpha_h_max", s.ga_controller.h_max)
      .set("free_pole", o.free_pole)
      .set("output_interval", scene.output.interval)
      .set("rope_EI", scene.model.cables()[0].section.bending_stiffness)
      .set("rope_axial_damping", scene.model.cables()[0].section.axial_damping)
      .set("rope_bending_damping", scene.model.cables()[0].section.bending_damping)
      .set("rope_mass_damping", scene.model.cables()[0].section.mass_damping);
  JsonObject scene_set;  // --scene-set entries in order, key → TOML value text
  for (const SceneOverride& v : o.scene_settings) scene_set.set(v.key, v.value);
  opts.set("scene_set", scene_set);
  for (const auto& [name, value] : counters) counts.set(name, value);
  meta.set("scene", o.scene)
      .set("status", status)
      .set("message", message)
      .set("wall_time_s", wall)
      .set("options", opts)
      .set("counters", counts)
      .set("time_s", times)
      .set("events", events);
  std::ofstream(o.out + "/events.json") << meta.text() << '\n';

  fmt::print("capture ({}, {} elements per rope{}): {} in {:.1f} s wall\n", o.integrator,
             scene.model.cables()[0].elements.size(), o.free_pole ? ", free pole" : "", status,
             wall);
  fmt::print("{}", ev.table());
  for (const auto& [name, value] : counters) fmt::print("  {:<34} {}\n", name, value);
  if (!timings.empty() && timings.front().second > 0.0)
    for (std::size_t k = 1; k < timings.size(); ++k)
      fmt::print("    {:<46} {:>6.1f} %\n", timings[k].first,
                 100.0 * timings[k].second / timings.front().second);
  return status == "completed" ? 0 : 2;
}
