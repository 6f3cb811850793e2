// KLU's factors copied out of its numeric object into column runs, for a faster solve (private
// to the core layer; KluSolve::extracted of klu_solver.hpp).
//
// KLU factors P (R⁻¹A) Q = L U + F (R = diag(Rs) the row scaling, L, U block diagonal on the
// block-triangular blocks, F the entries above the diagonal blocks; KLU user guide, klu_extract).
// A x = b is then solved block by block from the last: c = P R⁻¹ b (klu_l_extract gives Rs in the
// permuted order, verified in test_core); for block k = last … 0:
// solve L_k U_k y_k = c_k, then c_j −= F_jk y_k for the earlier blocks; x = Q y. The solve here
// is that of klu_solve with one difference in storage: the row indices of each column of L, U
// and F are sorted and stored as runs of consecutive rows, so that the update of column j is one
// contiguous axpy per run (vectorized), not an indexed scatter per entry. For the banded
// matrices of cables most columns are a single run. With reciprocal pivots (KluSolve::reciprocal)
// the division by u_jj becomes a multiplication by 1/u_jj, computed once per factorization.
//
// refactor() (KluRefactor::runs of klu_solver.hpp) recomputes these factors
// for new values of A with the pivot order, row scaling and structure of the last full load:
// left-looking column LU (Gilbert & Peierls 1988, the algorithm of KLU's own kernel, Davis &
// Palamadai Natarajan 2010 §3) on the known patterns of L and U, so without KLU's packed storage,
// its per-refactor row scaling, the pivot-growth pass over A and U and the extraction afterwards.
#pragma once

#include <klu.h>

#include <span>
#include <vector>

#include "ancf/core/types.hpp"

namespace ancf::detail {

class RunLuFactors {
 public:
  /// Copy the factors of `numeric` (klu_l_extract) and sort them into runs. same_structure: the
  /// factors come from a refactorization (klu_l_refactor keeps the pattern of L, U and F), so only
  /// the values are moved, through the map of the last full load. Allocates only when the factors
  /// have more entries than at any earlier load. Returns false if KLU fails.
  bool load(klu_l_numeric* numeric, klu_l_symbolic* symbolic, klu_l_common* common,
            bool same_structure);
  /// U's pivots applied as stored reciprocals (KluSolve::reciprocal) or by division as
  /// klu_solve does (KluSolve::extracted, bit-identical to klu_l_solve).
  void set_reciprocal_pivots(bool on) { reciprocal_pivots_ = on; }
  /// Solve A x = b in place (b overwritten with x); precondition: load() succeeded.
  void solve(std::span<double> b);

  /// Pivot quality of a refactorization: KLU's reciprocal pivot growth (min over the columns of
  /// max|Ã_ij| / max|u_ij| in the diagonal blocks, Ã = P R⁻¹ A Q) and min|u_jj| / max|u_jj|.
  struct PivotQuality {
    double growth = 0.0, diagonal = 0.0;
  };
  /// Refactorize for new values `ax` of the matrix whose pattern (CSC arrays ap, ai of the
  /// matrix of the last full load) is unchanged, with that load's pivot order and row scaling.
  /// Precondition: load() succeeded. The map from A's entries into the factors is built at the
  /// first call after a full load (allocating); later calls allocate nothing. A zero or
  /// non-finite pivot, or a matrix that is not that of the last load, gives growth = diagonal = 0
  /// (the factors are then unusable).
  PivotQuality refactor(const Index* ap, const Index* ai, std::span<const double> ax);

 private:
  // One triangular (or off-diagonal) factor, column by column: the runs of column j are
  // col_runs[j] … col_runs[j+1]−1; run r covers rows first[r] … first[r]+length[r]−1 with the
  // values value[offset[r]] …; diagonal entries are not stored (held in `diagonal` for U, 1 for L).
  // destination[a]: where extracted entry a goes (value index, or −1 − j for the diagonal of
  // column j).
  struct Runs {
    std::vector<Index> col_runs, first, length, offset, destination, order;
    std::vector<double> value;
    Index entries = -1;  // extracted entries of the last build
    void build(Index n, const std::vector<Index>& p, const std::vector<Index>& i);
    void fill(const std::vector<double>& x, std::vector<double>& diagonal);
  };
  // refactor(): A's entries in the diagonal blocks by permuted column (inside_start[j] …
  // inside_start[j+1]−1: source index in ax, permuted row, factor 1/Rs), and those above the
  // blocks (source, index into f_.value, factor); row_of: the inverse row permutation.
  struct Scatter {
    std::vector<Index> row_of, inside_start, inside_source, inside_row, outside_source,
        outside_value;
    std::vector<double> inside_factor, outside_factor;
    Index outside_entries = 0;
    bool valid = false;
  };
  bool map_matrix(const Index* ap, const Index* ai);
  Scatter scatter_;
  Index n_ = 0, blocks_ = 0;
  std::vector<Index> lp_, li_, up_, ui_, fp_, fi_, perm_row_, perm_col_, block_start_;
  std::vector<double> lx_, ux_, fx_, scale_, diagonal_, inverse_diagonal_, unit_diagonal_, work_;
  Runs l_, u_, f_;
  bool reciprocal_pivots_ = true;
};

}  // namespace ancf::detail
