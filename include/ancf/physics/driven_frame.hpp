// Frames whose motion is prescribed (ground, a rotating ring): not unknowns. Attachments to them
// are rheonomic constraints.
#pragma once

#include <string>

#include "ancf/core/types.hpp"
#include "ancf/physics/angle_law.hpp"

namespace ancf {

/// Position r(t), rotation A(t) and their first and second time derivatives.
struct FrameKinematics {
  Vec3 r = Vec3::Zero(), r_dot = Vec3::Zero(), r_ddot = Vec3::Zero();
  Mat3 a = Mat3::Identity(), a_dot = Mat3::Zero(), a_ddot = Mat3::Zero();
};

/// A frame with fixed origin that rotates about the global unit `axis` through the origin:
/// A(t) = R(axis, θ(t)) A₀. A fixed frame has AngleLaw::fixed().
struct DrivenFrame {
  std::string name;
  Vec3 origin = Vec3::Zero();
  Mat3 initial_rotation = Mat3::Identity();
  Vec3 axis = Vec3::UnitZ();
  AngleLaw law = AngleLaw::fixed();

  /// Ȧ = θ̇ [n]× A, Ä = (θ̈ [n]× + θ̇² [n]×²) A.
  [[nodiscard]] FrameKinematics at(double t) const;
};

}  // namespace ancf
