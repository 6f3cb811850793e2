#include "ancf/core/gauss_legendre.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace ancf {
namespace {

// Rules are computed once by Newton iteration on the Legendre polynomial P_n (Golub-free
// classical approach, Abramowitz & Stegun 25.4.29) to full double precision and mapped to [0, 1].
struct UnitRule {
  std::vector<double> x;
  std::vector<double> w;
};

UnitRule make_rule(int n) {
  UnitRule r;
  r.x.resize(n);
  r.w.resize(n);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-17) break;
    }
    // Recompute the derivative at the converged root for the weight.
    double p0 = 1.0, p1 = z;
    for (int k = 2; k <= n; ++k) {
      const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
      p0 = p1;
      p1 = p2;
    }
    dp = n * (z * p1 - p0) / (z * z - 1.0);
    // Map from [-1, 1] to [0, 1]: ξ = (1 + z)/2, weight halves.
    r.x[n - 1 - i] = 0.5 * (1.0 + z);
    r.w[n - 1 - i] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
  return r;
}

const std::vector<UnitRule>& all_rules() {
  static const std::vector<UnitRule> rules = [] {
    std::vector<UnitRule> v;
    for (int n = 1; n <= 8; ++n) v.push_back(make_rule(n));
    return v;
  }();
  return rules;
}

}  // namespace

GaussRule gauss_legendre_unit(int n) {
  if (n < 1 || n > 8) {
    throw std::invalid_argument("gauss_legendre_unit: n = " + std::to_string(n) +
                                " is outside the supported range 1..8");
  }
  const UnitRule& r = all_rules()[n - 1];
  return GaussRule{r.x, r.w};
}

}  // namespace ancf
