// Prescribed angle histories θ(t) with analytic θ̇ and θ̈: used by driven frames and as the
// reference of drives.
#pragma once

#include <functional>

namespace ancf {

/// θ [rad], θ̇ [rad/s], θ̈ [rad/s²] at one time.
struct AngleState {
  double angle = 0.0;
  double rate = 0.0;
  double acceleration = 0.0;
};

/// One of: fixed (θ ≡ θ₀), constant rate (θ = θ₀ + ω t), smooth ramp to a rate
/// (ω(t) = ω_max (1 − cos(πt/t_a))/2 for t < t_a, then ω_max; θ = θ₀ + ∫ω), or a user callback
/// that must return consistent θ, θ̇, θ̈.
class AngleLaw {
 public:
  static AngleLaw fixed(double angle = 0.0);
  static AngleLaw constant_rate(double rate, double angle0 = 0.0);
  /// Precondition: ramp_time > 0.
  static AngleLaw smooth_ramp(double max_rate, double ramp_time, double angle0 = 0.0);
  static AngleLaw callback(std::function<AngleState(double)> law);

  [[nodiscard]] AngleState at(double t) const;
  [[nodiscard]] bool is_fixed() const { return kind_ == Kind::fixed; }

 private:
  enum class Kind { fixed, constant_rate, smooth_ramp, callback };
  Kind kind_ = Kind::fixed;
  double angle0_ = 0.0, rate_ = 0.0, ramp_time_ = 0.0;
  std::function<AngleState(double)> callback_;
};

}  // namespace ancf
