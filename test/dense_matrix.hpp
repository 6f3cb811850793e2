// The dense matrix of values stored in a fixed CSC pattern (tests compare it entry by entry with
// finite differences or closed forms).
#pragma once

#include <cstddef>

#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/core/types.hpp"

namespace ancf::testing {

/// values[k] is the entry of slot k of `p` (any indexable container of p.nonzeros() doubles).
template <class Values>
MatX dense(const SparsityPattern& p, const Values& values) {
  MatX m = MatX::Zero(p.size(), p.size());
  for (Index col = 0; col < p.size(); ++col)
    for (Index k = p.column_start()[col]; k < p.column_start()[col + 1]; ++k)
      m(p.row_index()[k], col) = values[static_cast<std::size_t>(k)];
  return m;
}

}  // namespace ancf::testing
