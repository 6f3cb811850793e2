// RAII wrapper around SuiteSparse KLU (64-bit interface) for a fixed sparsity pattern.
#pragma once

#include <memory>
#include <span>

#include "ancf/core/sparsity_pattern.hpp"

namespace ancf {

/// Sparse LU for a square matrix. The symbolic analysis (block triangular form + fill-reducing
/// ordering) runs in the constructor and again in analyze(), after the owner of `pattern` has
/// changed it (the contact pattern of DESIGN §5 follows the near pairs). factor()
/// performs a full numeric factorization with pivoting the first time and a cheaper refactor
/// (same pivot order) afterwards; refactor_threshold guards against pivot growth: if KLU's
/// reciprocal pivot growth estimate drops below it, a full factorization with fresh pivoting is
/// done. That estimate costs a pass over A and U (~20 % of a refactorization of a small banded
/// matrix); RefactorCheck::diagonal replaces it by the O(n) diagonal estimate of rcond(), which
/// catches a stale pivot order that has become (nearly) singular but not a moderate growth.
///
/// Ownership: keeps a reference to `pattern`, which must outlive the solver; after the pattern
/// object is changed, call analyze() before the next factor().
/// Guard of a refactorization (same pivot order) against a poor pivot order.
enum class RefactorCheck {
  pivot_growth,  ///< KLU's reciprocal pivot growth > 1e-10 (klu_rgrowth: O(nnz(A) + nnz(U)))
  diagonal,      ///< min|u_ii|/max|u_ii| > 1e-13 (klu_rcond: O(n))
};

/// How solve() runs after a factorization.
enum class KluSolve {
  klu,         ///< klu_l_solve on KLU's packed factors (3e3daf4 … issue 20)
  extracted,   ///< the factors copied out once per factorization into sorted column runs
               ///< (src/core/run_lu_factors.hpp): the same substitutions, vectorized updates
               ///< (bit-identical to klu_l_solve)
  reciprocal,  ///< extracted, with U's pivots applied as reciprocals stored per factorization:
               ///< a multiplication instead of a division on the back substitution's critical
               ///< path (one rounding more per pivot; not bit-identical to klu_l_solve)
};

/// How a refactorization (same pivot order) is computed.
enum class KluRefactor {
  klu,   ///< klu_l_refactor, then the factors extracted for KluSolve::extracted (… issue 15c/20c)
  runs,  ///< left-looking LU on the extracted factors' column runs with the last full
         ///< factorization's pivots and row scaling (src/core/run_lu_factors.hpp); needs
         ///< KluSolve::extracted or reciprocal, else klu is used
};

class KluSolver {
 public:
  explicit KluSolver(const SparsityPattern& pattern);
  ~KluSolver();
  KluSolver(const KluSolver&) = delete;
  KluSolver& operator=(const KluSolver&) = delete;

  /// Numeric factorization of the matrix with the given values (one per pattern non-zero).
  /// Throws SolverError if the matrix is singular; the message gives the column KLU stopped at.
  void factor(std::span<const double> values);
  /// Symbolic analysis of the pattern's current arrays (its size and non-zeros may have changed);
  /// drops the numeric factorization, so the next factor() pivots afresh. Throws SolverError.
  void analyze();
  /// Force the next factor() to pivot afresh (use when values changed by orders of magnitude).
  void reset_pivoting() { pivots_valid_ = false; }
  /// How a refactorization is checked before it is accepted (default pivot_growth).
  void set_refactor_check(RefactorCheck check) { check_ = check; }
  /// How solve() works (default reciprocal); takes effect at the next factor().
  void set_solve(KluSolve method) { solve_method_ = method; }
  /// How a refactorization is computed (default runs); takes effect at the next factor().
  void set_refactor(KluRefactor method) { refactor_method_ = method; }
  /// Solve A x = b in place. Precondition: factor() succeeded.
  void solve(std::span<double> rhs);

  /// Reciprocal condition number estimate (cheap, from the diagonal of U: min|u_jj|/max|u_jj|).
  [[nodiscard]] double rcond();

  [[nodiscard]] int full_factorizations() const { return full_factorizations_; }
  [[nodiscard]] int refactorizations() const { return refactorizations_; }
  /// Column at which the last failed factorization found the matrix singular, or −1.
  [[nodiscard]] Index singular_column() const { return singular_column_; }
  /// Symbolic analyses (the constructor's and every analyze()).
  [[nodiscard]] int symbolic_analyses() const { return symbolic_analyses_; }
  /// Wall time spent in analysis + numeric factorization, and in solves [s] (cumulative).
  [[nodiscard]] double factor_seconds() const { return factor_seconds_; }
  [[nodiscard]] double solve_seconds() const { return solve_seconds_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  const SparsityPattern& pattern_;
  bool pivots_valid_ = false;
  RefactorCheck check_ = RefactorCheck::pivot_growth;
  KluSolve solve_method_ = KluSolve::reciprocal;
  KluRefactor refactor_method_ = KluRefactor::runs;
  double runs_rcond_ = -1.0;  // diagonal rcond of the last KluRefactor::runs factors, −1: KLU's
  bool extracted_valid_ = false;  // the extracted factors are those of the last factor()
  void extract(bool refactorized);
  int full_factorizations_ = 0;
  int refactorizations_ = 0;
  int symbolic_analyses_ = 0;
  Index singular_column_ = -1;
  double factor_seconds_ = 0.0;
  double solve_seconds_ = 0.0;
};

}  // namespace ancf
