#include "ancf/core/sparsity_pattern.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace ancf {

void SparsityPattern::add(Index row, Index col) {
  if (frozen_) throw std::logic_error("SparsityPattern::add after freeze()");
  if (row < 0 || col < 0 || row >= n_ || col >= n_) {
    throw std::out_of_range("SparsityPattern::add: entry (" + std::to_string(row) + ", " +
                            std::to_string(col) + ") outside a " + std::to_string(n_) +
                            "-square pattern");
  }
  couples_.emplace_back(col, row);
}

void SparsityPattern::add_block(std::span<const Index> rows, std::span<const Index> cols) {
  for (Index c : cols)
    for (Index r : rows) add(r, c);
}

void SparsityPattern::freeze() {
  if (frozen_) return;
  std::sort(couples_.begin(), couples_.end());
  couples_.erase(std::unique(couples_.begin(), couples_.end()), couples_.end());
  column_start_.assign(n_ + 1, 0);
  row_index_.resize(couples_.size());
  for (std::size_t k = 0; k < couples_.size(); ++k) {
    ++column_start_[couples_[k].first + 1];
    row_index_[k] = couples_[k].second;
  }
  for (Index c = 0; c < n_; ++c) column_start_[c + 1] += column_start_[c];
  couples_.clear();
  couples_.shrink_to_fit();
  frozen_ = true;
}

Index SparsityPattern::find(Index row, Index col) const {
  if (!frozen_) throw std::logic_error("SparsityPattern::find before freeze()");
  if (col < 0 || col >= n_) throw std::out_of_range("SparsityPattern::find: column out of range");
  const auto first = row_index_.begin() + column_start_[col];
  const auto last = row_index_.begin() + column_start_[col + 1];
  const auto it = std::lower_bound(first, last, row);
  return it == last || *it != row ? -1 : static_cast<Index>(it - row_index_.begin());
}

Index SparsityPattern::slot(Index row, Index col) const {
  const Index s = find(row, col);
  if (s < 0) {
    throw std::out_of_range("SparsityPattern::slot: entry (" + std::to_string(row) + ", " +
                            std::to_string(col) + ") is not in the pattern");
  }
  return s;
}

}  // namespace ancf
