// Everything `ancf run` and `ancf static` write per output frame (probes.csv row, .vtp frame, .pvd
// series), the run-wide measures of the summary (energy drift, largest constraint violation), and
// the run.json header that `run`, `static` and `modes` share.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "ancf/io/probe_recorder.hpp"
#include "ancf/io/run_metadata.hpp"
#include "ancf/io/scene.hpp"
#include "ancf/io/vtk_writer.hpp"

namespace ancf {

/// The bytes of `path` ("" if it cannot be read: load_scene reports that).
[[nodiscard]] std::string read_text(const std::string& path);

/// A tenth of the extent of the model's initial positions (cable nodes, body origins) [m], 0.1 m
/// if degenerate: the body-axis glyph length and the mode-shape amplitude.
[[nodiscard]] double tenth_of_extent(const Model& model);

/// The members every run.json starts with: ancf_version, command ("run", "static", "modes"),
/// scene (path as given), scene_name, scene_fnv1a64 (hash of `scene_text`), status, message,
/// wall_time_s. The command adds its options, counters and results.
[[nodiscard]] JsonObject run_json_header(const Scene& scene, const std::string& scene_text,
                                         const std::string& command, const std::string& status,
                                         const std::string& message, double wall_seconds);
/// Write `json` to dir/run.json. Throws ModelError if it cannot be written.
void write_run_json(const std::string& dir, const JsonObject& json);

class RunOutputs {
 public:
  /// Creates `dir` (and dir/frames with VTK on). Ownership: keeps a reference to `scene`.
  RunOutputs(const Scene& scene, const std::string& dir);
  /// Record one output frame at `state`.
  void record(const SystemState& state);

  [[nodiscard]] long frames() const { return csv_.rows(); }
  [[nodiscard]] double last_time() const { return last_time_; }
  [[nodiscard]] double initial_energy() const { return initial_energy_; }
  [[nodiscard]] double final_energy() const { return final_energy_; }
  /// max over frames of |E(t) − E(0)| [J] (a drift only for conservative scenes).
  [[nodiscard]] double max_energy_change() const { return max_energy_change_; }
  /// max over frames of max|Φ| [m or -] and max|Φ_q v + Φ_t|.
  [[nodiscard]] double max_position_violation() const { return max_position_violation_; }
  [[nodiscard]] double max_velocity_violation() const { return max_velocity_violation_; }
  [[nodiscard]] const ProbeRecorder& probes() const { return recorder_; }

 private:
  const Scene& scene_;
  std::string dir_;
  Workspace ws_;
  ProbeRecorder recorder_;
  CsvWriter csv_;
  std::optional<PvdSeries> pvd_;
  double axis_length_ = 0.1;
  double last_time_ = 0.0, initial_energy_ = 0.0, final_energy_ = 0.0, max_energy_change_ = 0.0;
  double max_position_violation_ = 0.0, max_velocity_violation_ = 0.0;
};

}  // namespace ancf
