// Constraints that are linear in one cable node's coordinates: Φ = G x − c, x = [r, r_x].
// They cover boundary conditions against ground: pin (position) and clamp (slope direction).
#pragma once

#include "ancf/core/types.hpp"

namespace ancf {

/// Φ(x) = G x − c with `rows` (≤ 3) rows; G is constant, so Φ_q = G, Φ_t = 0, (Φ_q v)_q = 0 and
/// the geometric stiffness ∂(Φ_qᵀλ)/∂q = 0.
struct LinearNodeConstraint {
  int rows = 0;
  Eigen::Matrix<double, 3, 6> g = Eigen::Matrix<double, 3, 6>::Zero();
  Vec3 c = Vec3::Zero();

  [[nodiscard]] double residual(int row, const Eigen::Matrix<double, 6, 1>& x) const {
    return g.row(row).dot(x) - c[row];
  }
};

/// Node position fixed at `target` [m]: r − target = 0 (3 rows).
[[nodiscard]] LinearNodeConstraint pin_to_ground(const Vec3& target);

/// Node slope kept parallel to `direction` (any length > 0): t₁·r_x = 0, t₂·r_x = 0 with (t₁, t₂)
/// an orthonormal basis of the plane ⊥ direction (2 rows). With a pin this is a clamp; the slope's
/// length stays free, so axial stretch at the support is not restrained.
[[nodiscard]] LinearNodeConstraint slope_direction_to_ground(const Vec3& direction);

}  // namespace ancf
