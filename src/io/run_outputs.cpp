#include "ancf/io/run_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#ifndef ANCF_VERSION
#define ANCF_VERSION "unknown"
#endif

namespace ancf {

namespace {

std::string prepared(const std::string& dir, bool vtk) {
  std::filesystem::create_directories(vtk ? std::filesystem::path(dir) / "frames"
                                          : std::filesystem::path(dir));
  return dir;
}

}  // namespace

double tenth_of_extent(const Model& model) {
  Aabb box;
  for (const CableData& c : model.cables())
    for (Index k = 0; k < c.node_count; ++k)
      box.extend(model.initial_coordinates().segment<3>(c.first_coordinate + 6 * k));
  for (const BodyData& b : model.bodies())
    box.extend(model.initial_coordinates().segment<3>(b.first_coordinate));
  const double extent = (box.upper - box.lower).norm();
  return std::isfinite(extent) && extent > 0.0 ? 0.1 * extent : 0.1;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

JsonObject run_json_header(const Scene& scene, const std::string& scene_text,
                           const std::string& command, const std::string& status,
                           const std::string& message, double wall_seconds) {
  JsonObject meta;
  meta.set("ancf_version", ANCF_VERSION)
      .set("command", command)
      .set("scene", scene.path)
      .set("scene_name", scene.name)
      .set("scene_fnv1a64", fmt::format("{:016x}", fnv1a64(scene_text)))
      .set("status", status)
      .set("message", message)
      .set("wall_time_s", wall_seconds);
  return meta;
}

void write_run_json(const std::string& dir, const JsonObject& json) {
  std::ofstream out(dir + "/run.json");
  out << json.text() << '\n';
  if (!out) throw ModelError("cannot write " + dir + "/run.json");
}

RunOutputs::RunOutputs(const Scene& scene, const std::string& dir)
    : scene_(scene),
      dir_(prepared(dir, scene.output.vtk)),
      ws_(scene.model),
      recorder_(scene.model, scene.output.probes),
      csv_(dir_ + "/probes.csv", recorder_.columns()),
      axis_length_(tenth_of_extent(scene.model)) {
  if (scene.output.vtk) pvd_.emplace(dir_ + "/" + scene.name + ".pvd");
}

void RunOutputs::record(const SystemState& state) {
  csv_.write(recorder_.evaluate(state, ws_));
  const double e = energies(scene_.model, state, ws_).total();
  if (csv_.rows() == 1) initial_energy_ = e;
  final_energy_ = e;
  max_energy_change_ = std::max(max_energy_change_, std::abs(e - initial_energy_));
  const ConstraintViolation v = constraint_violation(scene_.model, state, ws_);
  max_position_violation_ = std::max(max_position_violation_, v.position);
  max_velocity_violation_ = std::max(max_velocity_violation_, v.velocity);
  last_time_ = state.t;
  if (pvd_) {
    const std::string file = fmt::format("frames/frame_{:06d}.vtp", pvd_->size());
    write_vtp(dir_ + "/" + file, scene_.model, state, scene_.output.vtk_samples_per_element,
              axis_length_, ws_);
    pvd_->add(state.t, file);
  }
}

}  // namespace ancf
