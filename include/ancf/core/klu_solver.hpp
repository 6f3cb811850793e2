// RAII wrapper around SuiteSparse KLU (64-bit interface) for a fixed sparsity pattern.
#pragma once

#include <memory>
#include <span>

#include "ancf/core/sparsity_pattern.hpp"

namespace ancf {

/// Sparse LU for a square matrix whose pattern is fixed at construction. The symbolic analysis
/// (block triangular form + fill-reducing ordering) runs once, in the constructor. factor()
/// performs a full numeric factorization with pivoting the first time and a cheaper refactor
/// (same pivot order) afterwards; refactor_threshold guards against pivot growth: if KLU's
/// reciprocal pivot growth estimate drops below it, a full factorization with fresh pivoting is done.
///
/// Ownership: keeps a reference to `pattern`, which must outlive the solver.
class KluSolver {
 public:
  explicit KluSolver(const SparsityPattern& pattern);
  ~KluSolver();
  KluSolver(const KluSolver&) = delete;
  KluSolver& operator=(const KluSolver&) = delete;

  /// Numeric factorization of the matrix with the given values (one per pattern non-zero).
  /// Throws SolverError if the matrix is singular; the message gives the column KLU stopped at.
  void factor(std::span<const double> values);
  /// Force the next factor() to pivot afresh (use when values changed by orders of magnitude).
  void reset_pivoting() { pivots_valid_ = false; }
  /// Solve A x = b in place. Precondition: factor() succeeded.
  void solve(std::span<double> rhs);

  /// Reciprocal condition number estimate (cheap, from the diagonal of U).
  [[nodiscard]] double rcond();

  [[nodiscard]] int full_factorizations() const { return full_factorizations_; }
  [[nodiscard]] int refactorizations() const { return refactorizations_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  const SparsityPattern& pattern_;
  bool pivots_valid_ = false;
  int full_factorizations_ = 0;
  int refactorizations_ = 0;
};

}  // namespace ancf
