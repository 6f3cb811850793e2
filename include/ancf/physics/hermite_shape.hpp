// Cubic Hermite shape functions of the gradient-deficient ANCF cable element (S1; DESIGN §2).
//
// r(ξ) = Σ_k S_k(ξ) e_k with e = [r_i, r_i,x, r_j, r_j,x], ξ = x/l ∈ [0, 1]:
//   S1 = 1 − 3ξ² + 2ξ³,  S2 = l(ξ − 2ξ² + ξ³),  S3 = 3ξ² − 2ξ³,  S4 = l(ξ³ − ξ²).
// Every 12×12 element matrix is (4×4 scalar) ⊗ I₃; these functions return the scalar parts.
#pragma once

#include "ancf/core/types.hpp"

namespace ancf::hermite {

/// Shape function values S(ξ) for element length l [m].
[[nodiscard]] inline Vec4 values(double xi, double l) {
  const double x2 = xi * xi, x3 = x2 * xi;
  return {1.0 - 3.0 * x2 + 2.0 * x3, l * (xi - 2.0 * x2 + x3), 3.0 * x2 - 2.0 * x3, l * (x3 - x2)};
}

/// First derivative dS/dx = (1/l) dS/dξ [1/m for position slots, 1 for slope slots].
[[nodiscard]] inline Vec4 first_derivative(double xi, double l) {
  const double x2 = xi * xi;
  return {(-6.0 * xi + 6.0 * x2) / l, 1.0 - 4.0 * xi + 3.0 * x2, (6.0 * xi - 6.0 * x2) / l,
          3.0 * x2 - 2.0 * xi};
}

/// Second derivative d²S/dx² = (1/l²) d²S/dξ².
[[nodiscard]] inline Vec4 second_derivative(double xi, double l) {
  return {(-6.0 + 12.0 * xi) / (l * l), (-4.0 + 6.0 * xi) / l, (6.0 - 12.0 * xi) / (l * l),
          (6.0 * xi - 2.0) / l};
}

/// Consistent mass matrix, scalar part: ρA ∫₀ˡ S Sᵀ dx in closed form (exact).
/// The 12×12 element mass matrix is this ⊗ I₃. rho_a: mass per unit length [kg/m].
[[nodiscard]] inline Mat4 mass_matrix(double rho_a, double l) {
  Mat4 m;
  const double l2 = l * l;
  m << 156.0, 22.0 * l, 54.0, -13.0 * l,  //
      22.0 * l, 4.0 * l2, 13.0 * l, -3.0 * l2,  //
      54.0, 13.0 * l, 156.0, -22.0 * l,  //
      -13.0 * l, -3.0 * l2, -22.0 * l, 4.0 * l2;
  return (rho_a * l / 420.0) * m;
}

/// ∫₀ˡ S dx (exact): the consistent nodal weights of a uniform distributed load.
[[nodiscard]] inline Vec4 load_weights(double l) { return {0.5 * l, l * l / 12.0, 0.5 * l, -l * l / 12.0}; }

}  // namespace ancf::hermite
