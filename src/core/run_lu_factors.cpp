#include "run_lu_factors.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace ancf::detail {
namespace {

static_assert(sizeof(SuiteSparse_long) == sizeof(Index), "KLU long interface must match Index");

SuiteSparse_long* klu_ptr(std::vector<Index>& v) {
  return reinterpret_cast<SuiteSparse_long*>(v.data());
}

// Sizes without shrinking (no allocation once the largest factor has been seen).
template <class T>
void fit(std::vector<T>& v, std::size_t size) {
  if (v.size() < size) v.resize(size);
}

// y[0 … len) −= v[0 … len) · s: the update of one run (contiguous, vectorizable).
inline void subtract_scaled(double* __restrict y, const double* __restrict v, Index len, double s) {
  for (Index k = 0; k < len; ++k) y[k] -= v[k] * s;
}

}  // namespace

void RunLuFactors::Runs::build(Index n, const std::vector<Index>& p, const std::vector<Index>& i) {
  col_runs.clear();
  first.clear();
  length.clear();
  offset.clear();
  entries = p[n];
  fit(destination, static_cast<std::size_t>(entries));
  fit(order, static_cast<std::size_t>(entries));
  Index values = 0;
  for (Index j = 0; j < n; ++j) {
    col_runs.push_back(static_cast<Index>(first.size()));
    const Index begin = p[j], end = p[j + 1];
    // The column's entries by row: insertion sort of their positions (columns are short).
    for (Index a = begin; a < end; ++a) {
      Index b = a;
      for (; b > begin && i[order[b - 1]] > i[a]; --b) order[b] = order[b - 1];
      order[b] = a;
    }
    for (Index a = begin; a < end; ++a) {
      const Index row = i[order[a]];
      if (row == j) {  // diagonal: U's pivot, L's unit entry
        destination[order[a]] = -1 - j;
        continue;
      }
      if (static_cast<Index>(first.size()) > col_runs.back() &&
          first.back() + length.back() == row) {
        ++length.back();
      } else {
        first.push_back(row);
        length.push_back(1);
        offset.push_back(values);
      }
      destination[order[a]] = values++;
    }
  }
  col_runs.push_back(static_cast<Index>(first.size()));
  fit(value, static_cast<std::size_t>(values));
}

void RunLuFactors::Runs::fill(const std::vector<double>& x, std::vector<double>& diagonal) {
  for (Index a = 0; a < entries; ++a) {
    const Index d = destination[a];
    if (d >= 0)
      value[d] = x[a];
    else
      diagonal[-1 - d] = x[a];
  }
}

bool RunLuFactors::load(klu_l_numeric* numeric, klu_l_symbolic* symbolic, klu_l_common* common,
                        bool same_structure) {
  n_ = symbolic->n;
  blocks_ = symbolic->nblocks;
  const auto n = static_cast<std::size_t>(n_);
  const auto lnz = static_cast<std::size_t>(numeric->lnz);
  const auto unz = static_cast<std::size_t>(numeric->unz);
  const auto fnz = static_cast<std::size_t>(numeric->nzoff) + 1;  // KLU writes ≥ 1 entry
  for (auto* v : {&lp_, &up_, &fp_, &block_start_}) fit(*v, n + 1);
  for (auto* v : {&perm_row_, &perm_col_}) fit(*v, n);
  fit(li_, lnz);
  fit(lx_, lnz);
  fit(ui_, unz);
  fit(ux_, unz);
  fit(fi_, fnz);
  fit(fx_, fnz);
  for (auto* v : {&scale_, &diagonal_, &inverse_diagonal_, &unit_diagonal_, &work_}) fit(*v, n);
  if (klu_l_extract(numeric, symbolic, klu_ptr(lp_), klu_ptr(li_), lx_.data(), klu_ptr(up_),
                    klu_ptr(ui_), ux_.data(), klu_ptr(fp_), klu_ptr(fi_), fx_.data(),
                    klu_ptr(perm_row_), klu_ptr(perm_col_), scale_.data(), klu_ptr(block_start_),
                    common) != 1)
    return false;
  // A refactorization keeps the structure; the entry counts guard against a mismatch.
  const bool same =
      same_structure && l_.entries == lp_[n_] && u_.entries == up_[n_] && f_.entries == fp_[n_];
  if (!same) {
    l_.build(n_, lp_, li_);
    u_.build(n_, up_, ui_);
    f_.build(n_, fp_, fi_);
  }
  scatter_.valid = false;  // the pivot order or the scaling may have changed
  l_.fill(lx_, unit_diagonal_);
  u_.fill(ux_, diagonal_);
  f_.fill(fx_, unit_diagonal_);  // F has no diagonal entries
  for (Index j = 0; j < n_; ++j) inverse_diagonal_[j] = 1.0 / diagonal_[j];
  return true;
}

void RunLuFactors::solve(std::span<double> b) {
  double* c = work_.data();
  // klu_l_extract returns the scale factors in the permuted order: Rs[k] is that of row P[k].
  for (Index k = 0; k < n_; ++k) c[k] = b[perm_row_[k]] / scale_[k];
  auto column = [&](const Runs& r, Index j, double s) {
    for (Index q = r.col_runs[j]; q < r.col_runs[j + 1]; ++q)
      subtract_scaled(c + r.first[q], r.value.data() + r.offset[q], r.length[q], s);
  };
  for (Index blk = blocks_ - 1; blk >= 0; --blk) {
    const Index k1 = block_start_[blk], k2 = block_start_[blk + 1];
    for (Index j = k1; j < k2; ++j)
      if (c[j] != 0.0) column(l_, j, c[j]);
    for (Index j = k2 - 1; j >= k1; --j) {
      // The reciprocal: a multiplication (4 cycles) instead of a division (13–20) on the
      // critical path of the back substitution; one rounding more per pivot.
      if (reciprocal_pivots_)
        c[j] *= inverse_diagonal_[j];
      else
        c[j] /= diagonal_[j];
      if (c[j] != 0.0) column(u_, j, c[j]);
    }
    for (Index j = k1; j < k2; ++j)
      if (c[j] != 0.0) column(f_, j, c[j]);
  }
  for (Index k = 0; k < n_; ++k) b[perm_col_[k]] = c[k];
}

bool RunLuFactors::map_matrix(const Index* ap, const Index* ai) {
  Scatter& m = scatter_;
  const auto n = static_cast<std::size_t>(n_);
  const auto nnz = static_cast<std::size_t>(ap[n_]);
  fit(m.row_of, n);
  for (Index k = 0; k < n_; ++k) m.row_of[perm_row_[k]] = k;
  fit(m.inside_start, n + 1);
  for (auto* v : {&m.inside_source, &m.inside_row, &m.outside_source, &m.outside_value})
    fit(*v, nnz);
  for (auto* v : {&m.inside_factor, &m.outside_factor}) fit(*v, nnz);
  Index inside = 0, outside = 0;
  for (Index blk = 0; blk < blocks_; ++blk) {
    const Index k1 = block_start_[blk];
    for (Index j = k1; j < block_start_[blk + 1]; ++j) {
      m.inside_start[j] = inside;
      const Index c = perm_col_[j];
      for (Index a = ap[c]; a < ap[c + 1]; ++a) {
        const Index k = m.row_of[ai[a]];
        const double factor = 1.0 / scale_[k];  // scale_ is in the permuted order
        if (k >= k1) {  // in the diagonal block (the form is block upper triangular)
          m.inside_source[inside] = a;
          m.inside_row[inside] = k;
          m.inside_factor[inside++] = factor;
          continue;
        }
        // Above the blocks: F's entry (k, j), found in its runs.
        Index index = -1;
        for (Index q = f_.col_runs[j]; q < f_.col_runs[j + 1]; ++q)
          if (k >= f_.first[q] && k < f_.first[q] + f_.length[q])
            index = f_.offset[q] + k - f_.first[q];
        if (index < 0) return false;  // not KLU's structure: refactor through KLU instead
        m.outside_source[outside] = a;
        m.outside_value[outside] = index;
        m.outside_factor[outside++] = factor;
      }
    }
  }
  m.inside_start[n_] = inside;
  m.outside_entries = outside;
  m.valid = true;
  return true;
}

RunLuFactors::PivotQuality RunLuFactors::refactor(const Index* ap, const Index* ai,
                                                  std::span<const double> ax) {
  if (!scatter_.valid && !map_matrix(ap, ai)) return {0.0, 0.0};
  const Scatter& m = scatter_;
  double* x = work_.data();
  const double* a = ax.data();
  PivotQuality quality{1.0, 1.0};
  double smallest_pivot = INFINITY, largest_pivot = 0.0;
  // x is zero before each column: every entry a column writes (A's entries lie in the pattern
  // of L + U) is set back to zero where it is read for the last time, below.
  std::fill_n(x, n_, 0.0);
  for (Index j = 0; j < n_; ++j) {
    // Column j of Ã (block part) into x.
    double largest_a = 0.0;
    for (Index e = m.inside_start[j]; e < m.inside_start[j + 1]; ++e) {
      const double v = a[m.inside_source[e]] * m.inside_factor[e];
      x[m.inside_row[e]] = v;
      largest_a = std::max(largest_a, std::abs(v));
    }
    // U(:, j) by forward substitution with the columns of L, rows ascending (a topological order:
    // column k of L only touches rows > k, so x_k is final when it is reached).
    double largest_u = 0.0;
    for (Index q = u_.col_runs[j]; q < u_.col_runs[j + 1]; ++q) {
      double* u = u_.value.data() + u_.offset[q];
      for (Index t = 0; t < u_.length[q]; ++t) {
        const Index k = u_.first[q] + t;
        const double ukj = x[k];
        u[t] = ukj;
        x[k] = 0.0;  // later columns of L only touch rows below k
        largest_u = std::max(largest_u, std::abs(ukj));
        if (ukj == 0.0) continue;
        for (Index r = l_.col_runs[k]; r < l_.col_runs[k + 1]; ++r)
          subtract_scaled(x + l_.first[r], l_.value.data() + l_.offset[r], l_.length[r], ukj);
      }
    }
    const double pivot = x[j];
    x[j] = 0.0;
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot)) return {0.0, 0.0};
    diagonal_[j] = pivot;
    largest_u = std::max(largest_u, std::abs(pivot));
    smallest_pivot = std::min(smallest_pivot, std::abs(pivot));
    largest_pivot = std::max(largest_pivot, std::abs(pivot));
    if (largest_a > 0.0) quality.growth = std::min(quality.growth, largest_a / largest_u);
    // L(:, j) = x / u_jj on its pattern.
    const double inverse = 1.0 / pivot;
    inverse_diagonal_[j] = inverse;
    for (Index q = l_.col_runs[j]; q < l_.col_runs[j + 1]; ++q) {
      double* l = l_.value.data() + l_.offset[q];
      double* xs = x + l_.first[q];
      for (Index t = 0; t < l_.length[q]; ++t) {
        l[t] = xs[t] * inverse;
        xs[t] = 0.0;
      }
    }
  }
  for (Index e = 0; e < m.outside_entries; ++e)
    f_.value[m.outside_value[e]] = a[m.outside_source[e]] * m.outside_factor[e];
  quality.diagonal = smallest_pivot / largest_pivot;
  return quality;
}

}  // namespace ancf::detail
