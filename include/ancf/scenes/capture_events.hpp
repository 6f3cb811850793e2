// Event detection of the capture example (shared/CAPTURE.md, "Outputs that mirror the paper"),
// fed with the state at every output time. The resolution of every event time is the output
// interval of the caller. The scene itself is studies/scenes/capture.toml; the observer finds its
// parts by the names below.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "ancf/system/assembly.hpp"
#include "ancf/system/contact_output.hpp"

namespace ancf {

/// Names the capture scene file uses for what the events are measured on.
struct CaptureNames {
  static constexpr const char* ring = "ring";
  static constexpr const char* pole = "pole";
  static constexpr const char* drive = "ring drive";
  static constexpr std::array<const char*, 3> ropes = {"rope 1", "rope 2", "rope 3"};
  /// Constraint holding rope i's end on the rotating ring: its multipliers are the end force.
  static std::string ring_end(int rope) { return std::string(ropes[rope]) + " at ring"; }
  /// Contact pair of rope i with "shaft" or "knob".
  static std::string pole_pair(int rope, const char* part) { return std::string(ropes[rope]) + "-" + part; }
};

/// CAPTURE.md: the rotating ring's height h [m] (the lateral offset is measured at z = h/2).
inline constexpr double kCaptureRingHeight = 0.15;

/// One output sample of the capture run.
struct CaptureSample {
  double t = 0.0;
  double ring_angle = 0.0, ring_rate = 0.0, drive_torque = 0.0;  ///< [rad], [rad/s], [N m]
  double tilt = 0.0;            ///< angle between pole axis and +z [rad]
  double tilt_rate = 0.0;       ///< |a₃ × ȧ₃|/|a₃|² : rate of turn of the pole axis [rad/s]
  double lateral_offset = 0.0;  ///< distance of the pole axis from the ring axis at z = h/2 [m]
  double lateral_speed = 0.0;   ///< speed of that axis point across the ring axis [m/s]
  std::array<bool, 3> rope_on_pole{};         ///< some point of the rope has gap < 0 to shaft or knob
  std::array<double, 3> rope_pole_force{};    ///< |normal force resultant| rope–pole [N]
  /// Smallest gap of the rope's centreline (every point, not only the contact samples) to shaft
  /// or knob [m] (< 0: contact).
  std::array<double, 3> rope_pole_gap{};
  std::array<double, 3> ring_end_tension{};   ///< |rope end force| at the rotating ring [N]
  double rope_rope_force = 0.0;               ///< sum of |normal resultants| of rope–rope pairs [N]
};

/// The paper-style event table (NaN: the event did not happen).
struct CaptureEvents {
  static constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  std::array<double, 3> first_contact{nan, nan, nan};
  int first_rope = -1;  ///< 0-based index of the rope that touched first (−1: none)
  double all_three = nan, stall = nan, lock = nan;
  double final_tilt = nan, final_lateral_offset = nan;
  double ring_angle_at_stall = nan;
  std::array<double, 3> tension_at_lock{nan, nan, nan};
  double peak_contact_force = 0.0;  ///< max over time and ropes of the rope–pole normal resultant [N]
  /// Plain-text table (angles in degrees).
  [[nodiscard]] std::string table() const;
};

/// Evaluates samples from states of the capture model and finds the events.
class CaptureObserver {
 public:
  explicit CaptureObserver(const Model& model);
  /// Record the state at time state.t (states must come in increasing t); λ must be the
  /// multipliers at that state (ring-end tensions).
  const CaptureSample& record(const SystemState& state);
  [[nodiscard]] const std::vector<CaptureSample>& samples() const { return samples_; }
  /// The event table from the samples recorded so far (t_lock needs the run to its end).
  [[nodiscard]] CaptureEvents events() const;

 private:
  const Model& model_;
  Workspace ws_;
  std::vector<ContactPairState> pairs_;
  Index ring_, pole_, drive_;
  std::array<std::array<Index, 2>, 3> pole_pairs_{};
  std::vector<Index> rope_pairs_;
  std::array<Index, 3> ring_end_rows_{};
  std::vector<CaptureSample> samples_;
};

}  // namespace ancf
