// Observed order of convergence: the least-squares slope of log(error) against log(h). Shared by
// the convergence tests and the study executables (time, mesh and scaling studies).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

namespace ancf {

/// Precondition: h.size() == error.size() ≥ 2, all entries > 0, not all h equal.
inline double fitted_order(const std::vector<double>& h, const std::vector<double>& error) {
  const auto n = static_cast<double>(h.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    const double x = std::log(h[i]), y = std::log(error[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace ancf
