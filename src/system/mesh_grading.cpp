#include "ancf/system/mesh_grading.hpp"

#include <cmath>
#include <limits>
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
  if (!(grading.end_length > 0.0)) throw ModelError("mesh grading: end_length must be > 0 [m]");
  // In units of L: x = s/L, λ = ℓ/L; N(x) = x + cλ[a(1 − e^{−x/λ}) + b(e^{−(1−x)/λ} − e^{−1/λ})],
  // N'(x) = ρ(x) ≥ 1, so N is strictly increasing and Newton with a bracket converges.
  const double c = 1.0 / grading.end_ratio - 1.0, lambda = grading.end_length / length;
  const double a = grading.at_start ? 1.0 : 0.0, b = grading.at_end ? 1.0 : 0.0;
  const double tail = std::exp(-1.0 / lambda);
  auto count = [&](double x) {
    return x + c * lambda *
                   (a * (1.0 - std::exp(-x / lambda)) + b * (std::exp(-(1.0 - x) / lambda) - tail));
  };
  auto density = [&](double x) {
    return 1.0 + c * (a * std::exp(-x / lambda) + b * std::exp(-(1.0 - x) / lambda));
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
  return f;
}

}  // namespace ancf
