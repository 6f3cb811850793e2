#include "ancf/solvers/singularity_estimate.hpp"

#include <cmath>
#include <limits>
#include <utility>

namespace ancf {

Equilibration equilibrate(const SparsityPattern& pattern, std::span<const double> values,
                          Index split) {
  const Index n = pattern.size();
  const auto& start = pattern.column_start();
  const auto& rows = pattern.row_index();
  // Largest |entry| per row (R) and then per column of R J (C), inverted; round-off zeros
  // (below kZeroFraction of the block's largest) take the block's largest instead.
  auto invert = [&](VecX& m) {
    for (const auto& [first, last] : {std::pair{Index{0}, split}, std::pair{split, n}}) {
      if (first >= last) continue;
      const double block = m.segment(first, last - first).maxCoeff();
      for (Index i = first; i < last; ++i)
        m[i] = block > 0.0 ? 1.0 / (m[i] < kZeroFraction * block ? block : m[i]) : 1.0;
    }
  };
  Equilibration e{VecX::Zero(n), VecX::Zero(n)};
  VecX& r = e.row_scale;
  VecX& c = e.column_scale;
  for (Index j = 0; j < n; ++j)
    for (Index k = start[j]; k < start[j + 1]; ++k)
      r[rows[k]] = std::max(r[rows[k]], std::abs(values[k]));
  invert(r);
  for (Index j = 0; j < n; ++j)
    for (Index k = start[j]; k < start[j + 1]; ++k)
      c[j] = std::max(c[j], r[rows[k]] * std::abs(values[k]));
  invert(c);
  return e;
}

SingularityEstimate estimate_singularity(const SparsityPattern& pattern,
                                         std::span<const double> values, KluSolver& factored,
                                         Index split, int iterations) {
  const Index n = pattern.size();
  const Equilibration e = equilibrate(pattern, values, split);
  // J_s⁻¹ x = C⁻¹ J⁻¹ R⁻¹ x. Start: a fixed vector with entries of both signs and no pattern
  // that a structured null space could be orthogonal to.
  SingularityEstimate out;
  VecX x(n);
  for (Index i = 0; i < n; ++i) x[i] = std::sin(1.0 + 2.3 * static_cast<double>(i));
  x.normalize();
  for (int it = 0; it < iterations; ++it) {
    x = x.cwiseQuotient(e.row_scale);
    factored.solve(as_span(x));
    x = x.cwiseQuotient(e.column_scale);
    const double norm = x.norm();
    if (!std::isfinite(norm)) {
      out.inverse_norm = std::numeric_limits<double>::infinity();
      break;
    }
    out.inverse_norm = norm;
    if (norm > 0.0) x /= norm;
  }
  out.direction = x;
  return out;
}

}  // namespace ancf
