#include "ancf/system/mesh_grading.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

std::vector<double> node_fractions(Index elements, double length, const MeshGrading& grading) {
  if (elements < 1)
    throw ModelError("mesh grading: element count must be >= 1, got " + std::to_string(elements));
  if (!(length > 0.0)) throw ModelError("mesh grading: the length must be > 0");
  std::vector<double> f(static_cast<std::size_t>(elements) + 1);
  const double n = static_cast<double>(elements);
  if (grading.uniform()) {
    for (Index k = 0; k <= elements; ++k) f[k] = static_cast<double>(k) / n;
    return f;
  }
  if (!(grading.end_ratio > 0.0 && grading.end_ratio <= 1.0))
    throw ModelError("mesh grading: end_ratio must be in (0, 1], got " +
                     std::to_string(grading.end_ratio));
  if (grading.graded_ends() && !(grading.end_length > 0.0))
    throw ModelError("mesh grading: end_length must be > 0 [m]");
  if (!(grading.band_ratio > 0.0 && grading.band_ratio <= 1.0))
    throw ModelError("mesh grading: band_ratio must be in (0, 1], got " +
                     std::to_string(grading.band_ratio));
  if (grading.graded_band() && !(grading.band_width > 0.0))
    throw ModelError("mesh grading: band_width must be > 0 [m]");
  if (!(grading.band_centre >= 0.0 && grading.band_centre <= 1.0))
    throw ModelError("mesh grading: band_centre must be in [0, 1], got " +
                     std::to_string(grading.band_centre));
  // In units of L: x = s/L, λ = ℓ/L, m = μ/L, x_b = band_centre;
  //   N(x) = x + cλ[a(1 − e^{−x/λ}) + b(e^{−(1−x)/λ} − e^{−1/λ})]
  //          + c_b m √π/2 [erf((x − x_b)/m) + erf(x_b/m)],
  // N'(x) = ρ(x) ≥ 1, so N is strictly increasing and Newton with a bracket converges.
  const bool ends = grading.graded_ends(), band = grading.graded_band();
  const double c = ends ? 1.0 / grading.end_ratio - 1.0 : 0.0;
  const double lambda = ends ? grading.end_length / length : 1.0;
  const double a = grading.at_start ? 1.0 : 0.0, b = grading.at_end ? 1.0 : 0.0;
  const double tail = std::exp(-1.0 / lambda);
  const double cb = band ? 1.0 / grading.band_ratio - 1.0 : 0.0;
  const double m = band ? grading.band_width / length : 1.0, xb = grading.band_centre;
  const double half_sqrt_pi = 0.5 * std::sqrt(std::numbers::pi);
  auto count = [&](double x) {
    return x +
           c * lambda *
               (a * (1.0 - std::exp(-x / lambda)) + b * (std::exp(-(1.0 - x) / lambda) - tail)) +
           cb * m * half_sqrt_pi * (std::erf((x - xb) / m) + std::erf(xb / m));
  };
  auto density = [&](double x) {
    const double z = (x - xb) / m;
    return 1.0 + c * (a * std::exp(-x / lambda) + b * std::exp(-(1.0 - x) / lambda)) +
           cb * std::exp(-z * z);
  };
  const double total = count(1.0);
  f.front() = 0.0;
  f.back() = 1.0;
  double lo = 0.0;
  for (Index k = 1; k < elements; ++k) {
    const double target = total * static_cast<double>(k) / n;
    double left = lo, right = 1.0, x = lo + (target - count(lo)) / density(lo);
    for (int it = 0; it < 200; ++it) {
      if (!(x > left && x < right)) x = 0.5 * (left + right);
      const double r = count(x) - target;
      if (r > 0.0)
        right = x;
      else
        left = x;
      const double next = x - r / density(x);
      if (std::abs(next - x) <= 4.0 * std::numeric_limits<double>::epsilon() * x ||
          right - left <= 4.0 * std::numeric_limits<double>::epsilon()) {
        x = next > left && next < right ? next : x;
        break;
      }
      x = next;
    }
    f[k] = x;
    lo = x;
  }
  // A length scale below round-off against L (λ or m underflowing, the density's exponentials
  // overflowing) leaves fractions that do not increase, or NaN: refuse them here, where the
  // cause is known, instead of as a non-increasing mesh in the geometry generators.
  for (Index k = 1; k <= elements; ++k)
    if (!(f[k] > f[k - 1]))
      throw ModelError(
          "mesh grading: end_length or band_width so far below the length that the element "
          "lengths do not resolve in double precision (node " +
          std::to_string(k) + "); expected length scales of the order of the elements");
  return f;
}

}  // namespace ancf
