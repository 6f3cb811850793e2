// Gauss–Legendre quadrature on [0, 1].
#pragma once

#include <array>
#include <span>

namespace ancf {

/// Abscissae ξ_g ∈ (0, 1) and weights w_g (Σ w_g = 1) of the n-point Gauss–Legendre rule on
/// [0, 1]; exact for polynomials of degree 2n − 1. Supported n: 1 … 8 (throws otherwise).
struct GaussRule {
  std::span<const double> points;
  std::span<const double> weights;
  [[nodiscard]] int size() const { return static_cast<int>(points.size()); }
};

[[nodiscard]] GaussRule gauss_legendre_unit(int n);

}  // namespace ancf
