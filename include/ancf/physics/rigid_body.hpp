// Rigid body in natural (fully Cartesian) coordinates q_b = [r_O, a₁, a₂, a₃] (DESIGN §2).
//
// A body point with body-frame coordinates p̄ is r_P = r_O + Σ_k p̄_k a_k = (c(p̄)ᵀ ⊗ I₃) q_b with
// c(p̄) = [1, p̄₁, p̄₂, p̄₃]: linear in q_b. The mass matrix is therefore constant,
//   M = (∫ρ c cᵀ dV) ⊗ I₃ = [m, m c̄ᵀ; m c̄, J̄] ⊗ I₃,  J̄ = ∫ρ p̄ p̄ᵀ dV = m c̄ c̄ᵀ + ½ tr(I_c) 1 − I_c,
// with I_c the inertia tensor about the centre of mass in the body frame. No gyroscopic terms.
#pragma once

#include <string>

#include "ancf/core/types.hpp"

namespace ancf {

using BodyCoordinates = Eigen::Matrix<double, 12, 1>;

/// Mass properties in the body frame: mass m [kg], centre of mass c̄ [m] relative to the body
/// origin O, inertia tensor about the centre of mass I_c [kg m²] (symmetric positive definite,
/// satisfying the triangle inequalities).
struct RigidBodyInertia {
  double mass = 0.0;
  Vec3 centre_of_mass = Vec3::Zero();
  Mat3 inertia = Mat3::Zero();

  /// Throws ModelError naming `body` if m ≤ 0, I_c is not symmetric positive definite or its
  /// principal moments violate the triangle inequality (J̄ would not be positive semi-definite).
  void validate(const std::string& body) const;
};

/// Scalar 4×4 part of the natural-coordinate mass matrix (full matrix = this ⊗ I₃).
[[nodiscard]] Mat4 natural_mass_matrix(const RigidBodyInertia& inertia);

/// c(p̄) = [1, p̄₁, p̄₂, p̄₃]: weights of the blocks r_O, a₁, a₂, a₃ in the position of point p̄.
[[nodiscard]] inline Vec4 point_weights(const Vec3& p) { return {1.0, p.x(), p.y(), p.z()}; }
/// Weights of a body-fixed direction d̄ = Σ d̄_k a_k: [0, d̄₁, d̄₂, d̄₃].
[[nodiscard]] inline Vec4 direction_weights(const Vec3& d) { return {0.0, d.x(), d.y(), d.z()}; }

/// Coordinates of a body with origin at `position` and rotation matrix `rotation` (columns a_k).
[[nodiscard]] BodyCoordinates body_coordinates(const Vec3& position, const Mat3& rotation);
/// Velocities for origin velocity v_O and angular velocity ω (both in the global frame):
/// ṙ_O = v_O, ȧ_k = ω × a_k.
[[nodiscard]] BodyCoordinates body_velocities(const Mat3& rotation, const Vec3& origin_velocity,
                                              const Vec3& angular_velocity);
/// Angular velocity ω = ½ Σ_k a_k × ȧ_k (exact for orthonormal a_k and ȧ_k = ω × a_k).
[[nodiscard]] Vec3 angular_velocity(const BodyCoordinates& q, const BodyCoordinates& v);
/// Rotation matrix [a₁ a₂ a₃] of body coordinates.
[[nodiscard]] Mat3 rotation_of(const BodyCoordinates& q);

}  // namespace ancf
