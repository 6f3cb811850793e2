#include "run_lu_factors.hpp"

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
  for (auto* v : {&scale_, &diagonal_, &unit_diagonal_, &work_}) fit(*v, n);
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
  l_.fill(lx_, unit_diagonal_);
  u_.fill(ux_, diagonal_);
  f_.fill(fx_, unit_diagonal_);  // F has no diagonal entries
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
      c[j] /= diagonal_[j];
      if (c[j] != 0.0) column(u_, j, c[j]);
    }
    for (Index j = k1; j < k2; ++j)
      if (c[j] != 0.0) column(f_, j, c[j]);
  }
  for (Index k = 0; k < n_; ++k) b[perm_col_[k]] = c[k];
}

}  // namespace ancf::detail
