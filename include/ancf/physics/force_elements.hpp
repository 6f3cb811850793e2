// Force elements acting on points and bodies: spring-dampers, point forces, body torques and the
// torque-limited PD drive of a revolute joint. Points and directions are AffineVector expressions
// (dot_constraint.hpp), so an element can attach to cable nodes, body points, ground or driven
// frames alike.
//
// Sign convention: every element returns its contribution Q to the generalised EXTERNAL force of
// M q'' + F + Φ_qᵀλ = Q, with ∂Q/∂q and ∂Q/∂v, all restricted to the element's 3-blocks.
#pragma once

#include <array>
#include <functional>
#include <span>

#include "ancf/physics/angle_law.hpp"
#include "ancf/physics/dot_constraint.hpp"

namespace ancf {

/// The distinct 3-blocks (global first-coordinate indices) an element touches, in a fixed order
/// that evaluation results follow. At most 8 blocks.
struct BlockList {
  static constexpr int kMaxBlocks = 8;
  std::array<Index, kMaxBlocks> blocks{};
  int count = 0;
  /// Add `block` if not present; returns its position. Throws std::length_error beyond 8 blocks.
  int insert(Index block);
  /// Position of `block`, or −1.
  [[nodiscard]] int find(Index block) const;
};

using LocalVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 24, 1>;
using LocalMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 24, 24>;

/// Q (3·count), ∂Q/∂q and ∂Q/∂v (3·count square) over the element's BlockList.
struct ForceResult {
  LocalVector force;
  LocalMatrix d_force_dq;
  LocalMatrix d_force_dv;
  void resize(int blocks);  // sets sizes and zeroes; no heap allocation (fixed capacity)
};

/// Linear spring-damper between points p1 and p2: tension f = k(ℓ − ℓ₀) + c ℓ̇ along n = (p2 − p1)/ℓ;
/// p1 is pulled by +f n, p2 by −f n. Precondition at evaluation: ℓ > 0.
struct SpringDamper {
  AffineVector p1, p2;
  double stiffness = 0.0;    ///< k [N/m]
  double damping = 0.0;      ///< c [N s/m]
  double rest_length = 0.0;  ///< ℓ₀ [m]
};

/// Force F(t) [N] at a point: constant `force` unless `time_function` is set.
struct PointForce {
  AffineVector point;
  Vec3 force = Vec3::Zero();
  std::function<Vec3(double)> time_function;
};

/// Torque τ(t) [N m] (global frame) on a rigid body with first coordinate `body`:
/// Q_{a_k} = ½ τ × a_k, whose virtual work is τ·δθ for orthonormal a_k.
struct BodyTorque {
  Index body = 0;
  Vec3 torque = Vec3::Zero();
  std::function<Vec3(double)> time_function;
};

/// Torque-limited PD drive about a revolute joint axis. The joint angle is
/// θ = atan2(d·e₂, d·e₁) with d a direction fixed in the driven body (⊥ axis) and (e₁, e₂) a
/// right-handed pair ⊥ axis fixed in the base body or ground. Torque on the driven body about the
/// axis (the base receives the reaction through ∂θ/∂q):
///   τ = τ_max tanh(u/τ_max),  u = K_p wrap(θ_ref(t) − θ) + K_d (ω_ref(t) − θ̇),
/// wrap(·) ∈ (−π, π]: the tracking error must stay below π. Q = τ ∂θ/∂q.
struct RevoluteDrive {
  AffineVector d, e1, e2;
  AngleLaw reference;
  double kp = 0.0;          ///< K_p [N m/rad]
  double kd = 0.0;          ///< K_d [N m s/rad]
  double torque_max = 0.0;  ///< τ_max [N m] > 0
};

/// Drive outputs for post-processing.
struct DriveState {
  double angle = 0.0, rate = 0.0, torque = 0.0;
};

[[nodiscard]] BlockList blocks_of(const SpringDamper& e);
[[nodiscard]] BlockList blocks_of(const PointForce& e);
[[nodiscard]] BlockList blocks_of(const BodyTorque& e);
[[nodiscard]] BlockList blocks_of(const RevoluteDrive& e);

/// Each evaluate() fills `out` over blocks_of(e) (same order). q, v are global vectors.
void evaluate(const SpringDamper& e, std::span<const double> q, std::span<const double> v,
              std::span<const FrameKinematics> frames, ForceResult& out);
void evaluate(const PointForce& e, double t, ForceResult& out);
void evaluate(const BodyTorque& e, std::span<const double> q, double t, ForceResult& out);
DriveState evaluate(const RevoluteDrive& e, std::span<const double> q, std::span<const double> v,
                    double t, ForceResult& out);

/// ½ k (ℓ − ℓ₀)² [J].
[[nodiscard]] double potential_energy(const SpringDamper& e, std::span<const double> q,
                                      std::span<const FrameKinematics> frames);

}  // namespace ancf
