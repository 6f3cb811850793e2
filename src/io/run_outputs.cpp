#include "ancf/io/run_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace ancf {

namespace {

std::string prepared(const std::string& dir, bool vtk) {
  std::filesystem::create_directories(vtk ? std::filesystem::path(dir) / "frames"
                                          : std::filesystem::path(dir));
  return dir;
}

/// Axis glyphs of bodies: a tenth of the extent of the initial positions (0.1 m if degenerate).
double axis_length(const Model& model) {
  Aabb box;
  for (const CableData& c : model.cables())
    for (Index k = 0; k < c.node_count; ++k)
      box.extend(model.initial_coordinates().segment<3>(c.first_coordinate + 6 * k));
  for (const BodyData& b : model.bodies())
    box.extend(model.initial_coordinates().segment<3>(b.first_coordinate));
  const double extent = (box.upper - box.lower).norm();
  return std::isfinite(extent) && extent > 0.0 ? 0.1 * extent : 0.1;
}

}  // namespace

RunOutputs::RunOutputs(const Scene& scene, const std::string& dir)
    : scene_(scene),
      dir_(prepared(dir, scene.output.vtk)),
      ws_(scene.model),
      recorder_(scene.model, scene.output.probes),
      csv_(dir_ + "/probes.csv", recorder_.columns()),
      axis_length_(axis_length(scene.model)) {
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
