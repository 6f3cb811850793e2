// The abstract equilibrium problem the static solver sees: no elements, only vectors and a
// fixed sparse pattern (DESIGN §7: solvers never see physics).
#pragma once

#include <span>
#include <string>

#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/core/types.hpp"

namespace ancf {

/// Find y = [q; λ] with R(y, s) = 0 for a load factor s ∈ [0, 1]: R is the equilibrium residual
/// F(q) − s·Q(q) + Φ_qᵀλ stacked on the constraints Φ(q). Implementations own their data.
class StaticProblem {
 public:
  virtual ~StaticProblem() = default;

  /// Number of unknowns (coordinates plus multipliers).
  [[nodiscard]] virtual Index size() const = 0;
  /// Fixed pattern of ∂R/∂y (frozen, never changes).
  [[nodiscard]] virtual const SparsityPattern& jacobian_pattern() const = 0;
  /// Index range [0, n_coordinates) are coordinates; the rest are multipliers.
  [[nodiscard]] virtual Index coordinate_count() const = 0;

  /// R(y, s) into `residual` (size()). May throw std::domain_error: y is not evaluable (the
  /// solver takes it as a failed Newton iteration and cuts the load increment, as for a
  /// non-finite residual); anything else is fatal.
  virtual void residual(std::span<const double> y, double load_factor,
                        std::span<double> residual) = 0;
  /// ∂R/∂y values (one per pattern non-zero) into `values`. May throw as residual().
  virtual void jacobian(std::span<const double> y, double load_factor,
                        std::span<double> values) = 0;
  /// Called with each accepted (converged) state of a load step, before the next load step: an
  /// implementation with history (e.g. rod reference triads) commits it here. Trial iterates are
  /// never passed, so a rejected increment needs no rollback. Default: nothing.
  virtual void commit(std::span<const double> /*y*/) {}
  /// Human-readable name of unknown / residual row i ("cable 'rope' node 3 r_x.y", ...).
  [[nodiscard]] virtual std::string describe_row(Index i) const = 0;
};

}  // namespace ancf
