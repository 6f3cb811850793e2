// Fixed compressed-sparse-column pattern, built once from the model's connectivity.
#pragma once

#include <span>
#include <vector>

#include "ancf/core/types.hpp"

namespace ancf {

/// Collects (row, col) couples, then freezes them into a CSC pattern with sorted, unique row
/// indices per column. After freeze() the pattern never changes; assembly writes values through
/// precomputed slots (positions in the value array) obtained with slot().
class SparsityPattern {
 public:
  SparsityPattern() = default;
  explicit SparsityPattern(Index n) : n_(n) {}

  /// Square dimension n (rows = cols).
  [[nodiscard]] Index size() const { return n_; }

  /// Declare that entry (row, col) may be non-zero. Precondition: not frozen; 0 ≤ row, col < n.
  void add(Index row, Index col);
  /// Declare a dense block rows × cols.
  void add_block(std::span<const Index> rows, std::span<const Index> cols);

  /// Build the CSC arrays; idempotent.
  void freeze();
  [[nodiscard]] bool frozen() const { return frozen_; }

  /// Position of (row, col) in the value array. Throws std::out_of_range if absent.
  [[nodiscard]] Index slot(Index row, Index col) const;
  /// Position of (row, col) in the value array, or −1 if the entry is not in the pattern.
  [[nodiscard]] Index find(Index row, Index col) const;

  [[nodiscard]] Index nonzeros() const { return static_cast<Index>(row_index_.size()); }
  [[nodiscard]] const std::vector<Index>& column_start() const { return column_start_; }
  [[nodiscard]] const std::vector<Index>& row_index() const { return row_index_; }

 private:
  Index n_ = 0;
  bool frozen_ = false;
  std::vector<std::pair<Index, Index>> couples_;  // (col, row) before freeze
  std::vector<Index> column_start_;               // size n + 1
  std::vector<Index> row_index_;                  // size nnz
};

}  // namespace ancf
