// Is a factored sparse matrix numerically singular, and along which unknowns? Used by the static
// solver to refuse loads that act on zero-stiffness motions (mechanisms, slack cables, the
// out-of-plane motion of a planar arc) instead of "converging" to an arbitrary point of a
// zero-stiffness family (issue 17 item 5), and to say when an equilibrium is not isolated.
#pragma once

#include <span>

#include "ancf/core/klu_solver.hpp"
#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/core/types.hpp"

namespace ancf {

/// A row (column) whose largest entry is below kZeroFraction of the largest entry of its block is
/// a round-off zero, not a stiffness (e.g. the out-of-plane rows of a stress-free planar arc,
/// whose scalar curvature has no first-order out-of-plane term: 2e-19 of the block's largest
/// entry): it is scaled like the block's largest row, so that it stays a zero instead of being
/// blown up to 1. Rows of real stiffness differ from the largest by factors of the element length
/// (slopes against positions), far above this.
inline constexpr double kZeroFraction = 1e-10;

/// J_s = R J C: R scales every row of J and then C every column of R J to a largest |entry| of 1
/// (one pass of row/column equilibration), which removes the unit mismatch between stiffness rows
/// [N/m], constraint rows and multiplier columns. Entries ≤ 1, so ‖J_s‖₂ ≥ 1 and
/// σ_min(J_s) ≤ 1/cond(J_s). Blocks for the round-off test: unknowns [0, split) and [split, n)
/// (coordinates and multipliers, whose units differ).
struct Equilibration {
  VecX row_scale, column_scale;  ///< the diagonals of R and C
};
[[nodiscard]] Equilibration equilibrate(const SparsityPattern& pattern,
                                        std::span<const double> values, Index split);

/// Smallest singular value estimate of J_s.
struct SingularityEstimate {
  /// ‖J_s⁻¹x‖/‖x‖ after `iterations` steps of power iteration on J_s⁻¹: a lower bound of
  /// ‖J_s⁻¹‖₂ = 1/σ_min(J_s) that is sharp after one step when J_s is singular to round-off
  /// (the null component grows by ~1/ε at once).
  double inverse_norm = 0.0;
  /// Unit vector x (equilibrated unknowns C⁻¹y) of the last iterate: a near-null direction.
  VecX direction;
  [[nodiscard]] double smallest_singular_value() const { return 1.0 / inverse_norm; }
};

/// `values` are the entries of `pattern` that `factored` holds the LU factors of.
/// Deterministic (fixed start vector). Cost: `iterations` solves plus two passes over the values.
[[nodiscard]] SingularityEstimate estimate_singularity(const SparsityPattern& pattern,
                                                       std::span<const double> values,
                                                       KluSolver& factored, Index split,
                                                       int iterations = 3);

}  // namespace ancf
