// Event detection of the capture example (capture_events.hpp, shared/CAPTURE.md).
#include "ancf/scenes/capture_events.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "ancf/core/error.hpp"

namespace ancf {

namespace {

Index find_body(const Model& m, const std::string& name) {
  for (std::size_t k = 0; k < m.bodies().size(); ++k)
    if (m.bodies()[k].name == name) return static_cast<Index>(k);
  throw ModelError("capture observer: the model has no body '" + name + "'");
}

Index find_pair(const Model& m, const std::string& name) {
  for (Index p = 0; p < m.contact_pair_count(); ++p)
    if (m.contact_pair_name(p) == name) return p;
  throw ModelError("capture observer: the model has no contact pair '" + name + "'");
}

constexpr double kDeg = std::numbers::pi / 180.0;

// CAPTURE.md thresholds.
constexpr double kStallTorque = 0.95 * 6.0;     // 0.95 τ_max [N m]
constexpr double kStallRate = 0.5 * kDeg;       // |θ̇| [rad/s]
constexpr double kLockTiltRate = 0.2 * kDeg;    // [rad/s]
constexpr double kLockLateralSpeed = 1e-3;      // [m/s]
constexpr double kLockMinimumDuration = 0.5;    // [s]

bool stalled(const CaptureSample& s) {
  return std::abs(s.drive_torque) >= kStallTorque && std::abs(s.ring_rate) < kStallRate;
}
bool all_on_pole(const CaptureSample& s) { return s.rope_on_pole[0] && s.rope_on_pole[1] && s.rope_on_pole[2]; }
bool locked(const CaptureSample& s) {
  return all_on_pole(s) && stalled(s) && s.tilt_rate < kLockTiltRate && s.lateral_speed < kLockLateralSpeed;
}

}  // namespace

CaptureObserver::CaptureObserver(const Model& model)
    : model_(model),
      ws_(model),
      pairs_(model.contact_pair_count()),
      ring_(find_body(model, CaptureNames::ring)),
      pole_(find_body(model, CaptureNames::pole)),
      drive_(0) {
  if (model.drives().empty() || model.drives()[0].name != CaptureNames::drive)
    throw ModelError("capture observer: the model's first drive must be '" + std::string(CaptureNames::drive) + "'");
  for (int i = 0; i < 3; ++i) {
    pole_pairs_[i] = {find_pair(model, CaptureNames::pole_pair(i, "shaft")),
                      find_pair(model, CaptureNames::pole_pair(i, "knob"))};
    const Index c = model.find_constraint(CaptureNames::ring_end(i));
    if (c < 0) throw ModelError("capture observer: no constraint '" + CaptureNames::ring_end(i) + "'");
    // first_row counts system rows (coordinates first); λ is indexed from the first constraint row.
    ring_end_rows_[i] = model.constraints()[c].first_row - model.coordinate_count();
  }
  for (Index p = static_cast<Index>(model.cable_shape_contacts().size()); p < model.contact_pair_count(); ++p)
    rope_pairs_.push_back(p);
}

const CaptureSample& CaptureObserver::record(const SystemState& state) {
  CaptureSample s;
  s.t = state.t;
  const DriveState drive = drive_state(model_, state, drive_, ws_);
  s.ring_angle = drive.angle;
  s.ring_rate = drive.rate;
  s.drive_torque = drive.torque;

  // Pole axis a₃ (body z) and the axis point at z = h/2: p = r_O + σ a₃, σ = (h/2 − r_O,z)/a₃,z.
  const Index b = model_.bodies()[pole_].first_coordinate;
  const Vec3 r = state.q.segment<3>(b), r_dot = state.v.segment<3>(b);
  const Vec3 a3 = state.q.segment<3>(b + 9), a3_dot = state.v.segment<3>(b + 9);
  s.tilt = std::atan2(a3.head<2>().norm(), a3.z());
  s.tilt_rate = a3.cross(a3_dot).norm() / a3.squaredNorm();
  const double z_mid = 0.5 * kCaptureRingHeight;
  const double sigma = (z_mid - r.z()) / a3.z();
  const double sigma_dot = (-r_dot.z() - sigma * a3_dot.z()) / a3.z();
  const Vec3 p = r + sigma * a3, p_dot = r_dot + sigma_dot * a3 + sigma * a3_dot;
  s.lateral_offset = p.head<2>().norm();
  s.lateral_speed = p_dot.head<2>().norm();

  contact_states(model_, state, ws_, pairs_);
  for (int i = 0; i < 3; ++i) {
    const ContactPairState &shaft = pairs_[pole_pairs_[i][0]], &knob = pairs_[pole_pairs_[i][1]];
    // CAPTURE.md: "any point with gap < 0": the whole centreline, not only the contact samples
    // (between samples a rope can lie on the pole before any sample penetrates).
    s.rope_pole_gap[i] = std::min(shaft.min_centreline_gap, knob.min_centreline_gap);
    s.rope_on_pole[i] = s.rope_pole_gap[i] < 0.0;
    s.rope_pole_force[i] = (shaft.normal_force + knob.normal_force).norm();
    s.ring_end_tension[i] = state.lambda.segment<3>(ring_end_rows_[i]).norm();
  }
  for (const Index p_rr : rope_pairs_) s.rope_rope_force += pairs_[p_rr].normal_force.norm();
  samples_.push_back(s);
  return samples_.back();
}

CaptureEvents CaptureObserver::events() const {
  CaptureEvents e;
  if (samples_.empty()) return e;
  double first = std::numeric_limits<double>::infinity();
  for (const CaptureSample& s : samples_) {
    for (int i = 0; i < 3; ++i) {
      if (s.rope_on_pole[i] && std::isnan(e.first_contact[i])) {
        e.first_contact[i] = s.t;
        if (s.t < first) first = s.t, e.first_rope = i;
      }
      e.peak_contact_force = std::max(e.peak_contact_force, s.rope_pole_force[i]);
    }
    if (std::isnan(e.all_three) && all_on_pole(s)) e.all_three = s.t;
    if (std::isnan(e.stall) && stalled(s)) e.stall = s.t, e.ring_angle_at_stall = s.ring_angle;
  }
  // t_lock: start of the final run of locked samples, if it lasts at least 0.5 s.
  std::size_t k = samples_.size();
  while (k > 0 && locked(samples_[k - 1])) --k;
  if (k < samples_.size() && samples_.back().t - samples_[k].t >= kLockMinimumDuration) {
    e.lock = samples_[k].t;
    for (int i = 0; i < 3; ++i) e.tension_at_lock[i] = samples_[k].ring_end_tension[i];
  }
  e.final_tilt = samples_.back().tilt;
  e.final_lateral_offset = samples_.back().lateral_offset;
  return e;
}

std::string CaptureEvents::table() const {
  const auto time = [](double t) { return std::isnan(t) ? std::string("never") : fmt::format("{:.3f} s", t); };
  std::string out;
  out += fmt::format("  {:<34} {}\n", "first contact rope 1 / 2 / 3",
                     time(first_contact[0]) + " / " + time(first_contact[1]) + " / " + time(first_contact[2]));
  out += fmt::format("  {:<34} {}\n", "first rope in contact",
                     first_rope < 0 ? std::string("none") : fmt::format("rope {}", first_rope + 1));
  out += fmt::format("  {:<34} {}\n", "all three in contact", time(all_three));
  out += fmt::format("  {:<34} {}\n", "drive stall", time(stall));
  out += fmt::format("  {:<34} {}\n", "lock", time(lock));
  out += fmt::format("  {:<34} {:.4f} deg\n", "final pole tilt", final_tilt / kDeg);
  out += fmt::format("  {:<34} {:.3f} mm\n", "final lateral offset at z = h/2", 1e3 * final_lateral_offset);
  out += fmt::format("  {:<34} {:.2f} deg\n", "ring angle at stall", ring_angle_at_stall / kDeg);
  out += fmt::format("  {:<34} {:.1f} / {:.1f} / {:.1f} N\n", "rope tensions at lock (ring end)", tension_at_lock[0],
                     tension_at_lock[1], tension_at_lock[2]);
  out += fmt::format("  {:<34} {:.1f} N\n", "peak rope-pole contact force", peak_contact_force);
  return out;
}

}  // namespace ancf
