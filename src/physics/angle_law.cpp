#include "ancf/physics/angle_law.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

AngleLaw AngleLaw::fixed(double angle) {
  AngleLaw l;
  l.angle0_ = angle;
  return l;
}

AngleLaw AngleLaw::constant_rate(double rate, double angle0) {
  AngleLaw l;
  l.kind_ = Kind::constant_rate;
  l.rate_ = rate;
  l.angle0_ = angle0;
  return l;
}

AngleLaw AngleLaw::smooth_ramp(double max_rate, double ramp_time, double angle0) {
  if (!(ramp_time > 0.0))
    throw ModelError("smooth ramp: ramp time must be > 0 s, got " + std::to_string(ramp_time));
  AngleLaw l;
  l.kind_ = Kind::smooth_ramp;
  l.rate_ = max_rate;
  l.ramp_time_ = ramp_time;
  l.angle0_ = angle0;
  return l;
}

AngleLaw AngleLaw::callback(std::function<AngleState(double)> law) {
  if (!law) throw ModelError("angle law callback is empty");
  AngleLaw l;
  l.kind_ = Kind::callback;
  l.callback_ = std::move(law);
  return l;
}

AngleState AngleLaw::at(double t) const {
  switch (kind_) {
    case Kind::fixed:
      return {angle0_, 0.0, 0.0};
    case Kind::constant_rate:
      return {angle0_ + rate_ * t, rate_, 0.0};
    case Kind::smooth_ramp: {
      const double ta = ramp_time_, w = rate_;
      if (t >= ta) return {angle0_ + 0.5 * w * ta + w * (t - ta), w, 0.0};
      const double s = std::numbers::pi * t / ta;
      return {angle0_ + 0.5 * w * (t - ta / std::numbers::pi * std::sin(s)),
              0.5 * w * (1.0 - std::cos(s)), 0.5 * w * std::numbers::pi / ta * std::sin(s)};
    }
    case Kind::callback:
      return callback_(t);
  }
  return {};
}

}  // namespace ancf
