// ParaView output: one ASCII VTK PolyData file (.vtp) per output frame and a .pvd collection
// that lists them with their times. Cables are polylines through points sampled on the Hermite
// interpolation of each element; bodies are a vertex at the origin plus three axis lines; each
// contact pair in contact is a vertex where its resultant acts, with the force as point data.
#pragma once

#include <string>
#include <vector>

#include "ancf/system/assembly.hpp"

namespace ancf {

/// Write `path` (.vtp) for `state`: `samples_per_element` ≥ 1 segments per cable element, body
/// axes drawn `axis_length` [m] long. Cell data "object" numbers cables 0 …, then bodies, then
/// contact pairs (Model numbering); point data "velocity" [m/s] and "contact_force" [N] (the
/// pair's resultant at its vertex, zero elsewhere: a Glyph filter draws it). Throws ModelError if
/// the file cannot be written. `ws` is scratch for the contact states (a workspace of `model`).
void write_vtp(const std::string& path, const Model& model, const SystemState& state,
               int samples_per_element, double axis_length, Workspace& ws);

/// The .pvd series file, rewritten after every added frame so that it is valid even if the run
/// stops early.
class PvdSeries {
 public:
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  /// Add a frame file (path relative to the .pvd) at time t [s] and rewrite the series.
  void add(double t, const std::string& relative_file);
  [[nodiscard]] std::size_t size() const { return frames_.size(); }

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> frames_;
};

}  // namespace ancf
