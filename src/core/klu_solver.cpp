#include "ancf/core/klu_solver.hpp"

#include <klu.h>

#include <string>

#include "ancf/core/error.hpp"
#include "ancf/core/stopwatch.hpp"
#include "run_lu_factors.hpp"

namespace ancf {

static_assert(sizeof(SuiteSparse_long) == sizeof(Index), "KLU long interface must match Index");

struct KluSolver::Impl {
  klu_l_common common{};
  klu_l_symbolic* symbolic = nullptr;
  klu_l_numeric* numeric = nullptr;
  detail::RunLuFactors factors;  // KluSolve::extracted and reciprocal
  ~Impl() {
    if (numeric) klu_l_free_numeric(&numeric, &common);
    if (symbolic) klu_l_free_symbolic(&symbolic, &common);
  }
};

namespace {
// KLU's C interface takes non-const pointers but does not modify the pattern arrays.
SuiteSparse_long* mutable_ptr(const std::vector<Index>& v) {
  return const_cast<SuiteSparse_long*>(reinterpret_cast<const SuiteSparse_long*>(v.data()));
}
}  // namespace

KluSolver::KluSolver(const SparsityPattern& pattern)
    : impl_(std::make_unique<Impl>()), pattern_(pattern) {
  klu_l_defaults(&impl_->common);
  analyze();
}

void KluSolver::analyze() {
  if (!pattern_.frozen()) throw std::logic_error("KluSolver: pattern must be frozen");
  Stopwatch watch(factor_seconds_);
  Impl& k = *impl_;
  if (k.numeric) klu_l_free_numeric(&k.numeric, &k.common);
  if (k.symbolic) klu_l_free_symbolic(&k.symbolic, &k.common);
  pivots_valid_ = false;
  extracted_valid_ = false;
  k.symbolic = klu_l_analyze(pattern_.size(), mutable_ptr(pattern_.column_start()),
                             mutable_ptr(pattern_.row_index()), &k.common);
  if (!k.symbolic) {
    throw SolverError("KLU symbolic analysis failed (status " + std::to_string(k.common.status) +
                      ") for a matrix of size " + std::to_string(pattern_.size()));
  }
  ++symbolic_analyses_;
}

KluSolver::~KluSolver() = default;

void KluSolver::factor(std::span<const double> values) {
  if (static_cast<Index>(values.size()) != pattern_.nonzeros()) {
    throw std::invalid_argument("KluSolver::factor: value count does not match the pattern");
  }
  Stopwatch watch(factor_seconds_);
  auto* ap = mutable_ptr(pattern_.column_start());
  auto* ai = mutable_ptr(pattern_.row_index());
  auto* ax = const_cast<double*>(values.data());
  Impl& k = *impl_;
  const bool factors_loaded = extracted_valid_;  // k.factors hold the last factorization
  extracted_valid_ = false;
  runs_rcond_ = -1.0;
  if (pivots_valid_ && k.numeric && refactor_method_ == KluRefactor::runs &&
      solve_method_ != KluSolve::klu && factors_loaded) {
    const auto quality =
        k.factors.refactor(pattern_.column_start().data(), pattern_.row_index().data(), values);
    // The same guards as below, computed in the same pass.
    const bool good =
        check_ == RefactorCheck::pivot_growth ? quality.growth > 1e-10 : quality.diagonal > 1e-13;
    if (good) {
      ++refactorizations_;
      extracted_valid_ = true;
      runs_rcond_ = quality.diagonal;
      return;
    }
  } else if (pivots_valid_ && k.numeric) {
    const bool ok = klu_l_refactor(ap, ai, ax, k.symbolic, k.numeric, &k.common) == 1;
    // Refactor keeps the old pivot order, which can be poor once values have changed a lot;
    // fall back to a fresh factorization then (RefactorCheck says how that is detected).
    const bool good =
        ok && (check_ == RefactorCheck::pivot_growth
                   ? klu_l_rgrowth(ap, ai, ax, k.symbolic, k.numeric, &k.common) == 1 &&
                         k.common.rgrowth > 1e-10
                   : klu_l_rcond(k.symbolic, k.numeric, &k.common) == 1 && k.common.rcond > 1e-13);
    if (good && k.common.status == KLU_OK) {
      ++refactorizations_;
      extract(true);
      return;
    }
  }
  if (k.numeric) klu_l_free_numeric(&k.numeric, &k.common);
  k.numeric = klu_l_factor(ap, ai, ax, k.symbolic, &k.common);
  if (!k.numeric || k.common.status != KLU_OK) {
    pivots_valid_ = false;
    singular_column_ = k.common.status == KLU_SINGULAR ? k.common.singular_col : -1;
    const std::string where =
        k.common.status == KLU_SINGULAR
            ? " (numerically singular at column " + std::to_string(k.common.singular_col) + ")"
            : "";
    throw SolverError("KLU factorization failed, status " + std::to_string(k.common.status) +
                      where);
  }
  pivots_valid_ = true;
  singular_column_ = -1;
  ++full_factorizations_;
  extract(false);
}

void KluSolver::extract(bool refactorized) {
  if (solve_method_ == KluSolve::klu) return;
  Impl& k = *impl_;
  k.factors.set_reciprocal_pivots(solve_method_ == KluSolve::reciprocal);
  if (!k.factors.load(k.numeric, k.symbolic, &k.common, refactorized))
    throw SolverError("KLU factor extraction failed, status " + std::to_string(k.common.status));
  extracted_valid_ = true;
}

void KluSolver::solve(std::span<double> rhs) {
  Stopwatch watch(solve_seconds_);
  Impl& k = *impl_;
  if (!k.numeric) throw std::logic_error("KluSolver::solve before a successful factor()");
  if (static_cast<Index>(rhs.size()) != pattern_.size()) {
    throw std::invalid_argument("KluSolver::solve: right-hand side has the wrong size");
  }
  if (extracted_valid_) {
    k.factors.solve(rhs);
    return;
  }
  if (klu_l_solve(k.symbolic, k.numeric, pattern_.size(), 1, rhs.data(), &k.common) != 1) {
    throw SolverError("KLU solve failed, status " + std::to_string(k.common.status));
  }
}

double KluSolver::rcond() {
  Impl& k = *impl_;
  if (!k.numeric) return 0.0;
  if (runs_rcond_ >= 0.0) return runs_rcond_;  // KLU's numeric object holds older values
  klu_l_rcond(k.symbolic, k.numeric, &k.common);
  return k.common.rcond;
}

}  // namespace ancf
