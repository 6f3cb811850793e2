// Core layer: quadrature exactness, the fixed sparsity pattern and the KLU wrapper.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <thread>

#include "ancf/core/error.hpp"
#include "ancf/core/gauss_legendre.hpp"
#include "ancf/core/klu_solver.hpp"
#include "ancf/core/stopwatch.hpp"

namespace ancf {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// ∞-norm condition number ‖A‖∞ ‖A⁻¹‖∞ of `dense`, with its LU.
double infinity_condition(const Eigen::PartialPivLU<MatX>& lu, const MatX& dense) {
  return lu.inverse().cwiseAbs().rowwise().sum().maxCoeff() *
         dense.cwiseAbs().rowwise().sum().maxCoeff();
}

TEST(GaussLegendre, IntegratesMonomialsUpToDegree2nMinus1Exactly) {
  for (int n = 1; n <= 8; ++n) {
    const GaussRule rule = gauss_legendre_unit(n);
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      double sum = 0.0;
      for (int g = 0; g < n; ++g) sum += rule.weights[g] * std::pow(rule.points[g], degree);
      // ∫₀¹ ξ^d dξ = 1/(d+1); summation of n positive terms: error ≤ n ε.
      EXPECT_NEAR(sum, 1.0 / (degree + 1), 4 * n * kEps) << "n = " << n << ", degree " << degree;
    }
    // Degree 2n is not exact: the rule is genuinely of order 2n − 1.
    double sum = 0.0;
    for (int g = 0; g < n; ++g) sum += rule.weights[g] * std::pow(rule.points[g], 2 * n);
    EXPECT_GT(std::abs(sum - 1.0 / (2 * n + 1)), 1e3 * kEps) << "n = " << n;
  }
  EXPECT_THROW((void)gauss_legendre_unit(0), std::invalid_argument);
  EXPECT_THROW((void)gauss_legendre_unit(9), std::invalid_argument);
}

TEST(SparsityPattern, DeduplicatesSortsAndFindsSlots) {
  SparsityPattern p(4);
  p.add(3, 0);
  p.add(0, 0);
  p.add(3, 0);
  p.add(1, 2);
  p.add(2, 3);
  p.freeze();
  EXPECT_EQ(p.nonzeros(), 4);
  EXPECT_EQ(p.column_start(), (std::vector<Index>{0, 2, 2, 3, 4}));
  EXPECT_EQ(p.row_index(), (std::vector<Index>{0, 3, 1, 2}));
  EXPECT_EQ(p.slot(3, 0), 1);
  EXPECT_EQ(p.slot(2, 3), 3);
  EXPECT_THROW((void)p.slot(1, 1), std::out_of_range);
  EXPECT_THROW(p.add(0, 1), std::logic_error);
}

// A random sparse, diagonally dominant matrix: KLU must reproduce a dense LU solve.
TEST(KluSolver, SolvesAndRefactorsOnAFixedPattern) {
  const Index n = 30;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SparsityPattern p(n);
  MatX dense = MatX::Zero(n, n);
  for (Index i = 0; i < n; ++i) {
    p.add(i, i);
    p.add((i * 7 + 3) % n, i);
    p.add(i, (i * 11 + 5) % n);
  }
  p.freeze();
  KluSolver klu(p);
  for (int round = 0; round < 3; ++round) {
    VecX values(p.nonzeros());
    dense.setZero();
    for (Index c = 0; c < n; ++c)
      for (Index k = p.column_start()[c]; k < p.column_start()[c + 1]; ++k) {
        const Index r = p.row_index()[k];
        values[k] = r == c ? 10.0 + round : u(rng);
        dense(r, c) = values[k];
      }
    klu.factor(as_span(values));
    VecX b = VecX::NullaryExpr(n, [&] { return u(rng); });
    const VecX expected = dense.partialPivLu().solve(b);
    klu.solve(as_span(b));
    // Backward-stable solves of a well-conditioned system agree to a few ε·cond.
    EXPECT_LT((b - expected).lpNorm<Eigen::Infinity>(),
              100 * kEps * expected.lpNorm<Eigen::Infinity>());
  }
  EXPECT_EQ(klu.full_factorizations(), 1);
  EXPECT_EQ(klu.refactorizations(), 2);
  EXPECT_GT(klu.rcond(), 0.0);
}

TEST(KluSolver, DiagonalRefactorCheckPivotsAfreshWhenTheOldPivotVanishes) {
  // Dense 2×2: the first factorization pivots on a00 = 2; with a00 = 1e-15 the old order gives
  // u00 = 1e-15, u11 ≈ −1e15 (rcond ~1e-30), which RefactorCheck::diagonal must refuse.
  SparsityPattern p(2);
  for (Index c = 0; c < 2; ++c)
    for (Index r = 0; r < 2; ++r) p.add(r, c);
  p.freeze();
  for (const RefactorCheck check : {RefactorCheck::diagonal, RefactorCheck::pivot_growth}) {
    KluSolver klu(p);
    klu.set_refactor_check(check);
    klu.factor(std::vector<double>{2.0, 1.0, 1.0, 1.0});  // column-major [[2, 1], [1, 1]]
    klu.factor(std::vector<double>{3.0, 1.0, 1.0, 1.0});  // same pivots fine: a refactorization
    EXPECT_EQ(klu.refactorizations(), 1);
    klu.factor(std::vector<double>{1e-15, 1.0, 1.0, 1.0});
    EXPECT_EQ(klu.full_factorizations(), 2);
    std::vector<double> b{1.0, 2.0};  // x0 = 1/(1 − 1e-15), x1 = 1 − 1e-15 x0
    klu.solve(b);
    const double x0 = 1.0 / (1.0 - 1e-15);
    EXPECT_NEAR(b[0], x0, 4 * kEps);
    EXPECT_NEAR(b[1], 1.0 - 1e-15 * x0, 4 * kEps);
  }
}

TEST(KluSolver, ExtractedSolveEqualsKlusOwnSolve) {
  // A matrix with a block-triangular form of several blocks (three coupled blocks, a singleton,
  // entries above the blocks), rows scaled over 8 decades (KLU's row scaling) and zero diagonals
  // in a saddle-point block (pivoting away from the diagonal). KluSolve::extracted must give
  // klu_l_solve's answer: the same substitutions in the same order per entry, so bit for bit.
  const Index n = 41;
  SparsityPattern p(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Index starts[] = {0, 10, 25, 40, 41};
  for (int blk = 0; blk < 4; ++blk)
    for (Index i = starts[blk]; i < starts[blk + 1]; ++i) {
      p.add(i, i);
      const Index size = starts[blk + 1] - starts[blk];
      if (size > 1) {
        p.add(starts[blk] + (i - starts[blk] + 1) % size, i);  // a cycle: one strong component
        p.add(starts[blk] + (i * 7 + 3) % size, i);
      }
      if (blk > 0) p.add((i * 5) % starts[blk], i);  // above the block
    }
  p.freeze();
  KluSolver klu(p), extracted(p);  // round 1 refactorizes: the values move through the old map
  klu.set_solve(KluSolve::klu);
  extracted.set_solve(KluSolve::extracted);
  extracted.set_refactor(KluRefactor::klu);  // KLU's own refactorization, then extracted
  for (const int round : {0, 1}) {
    VecX values(p.nonzeros());
    MatX dense = MatX::Zero(n, n);
    for (Index c = 0; c < n; ++c)
      for (Index k = p.column_start()[c]; k < p.column_start()[c + 1]; ++k) {
        const Index r = p.row_index()[k];
        const bool saddle = r >= 30 && r < 40 && r == c;  // zero pivots on the diagonal
        values[k] = (saddle ? 0.0 : r == c ? 4.0 + round : u(rng)) * std::pow(10.0, r % 9 - 4);
        dense(r, c) = values[k];
      }
    klu.factor(as_span(values));
    extracted.factor(as_span(values));
    for (int rhs = 0; rhs < 3; ++rhs) {
      VecX b = VecX::NullaryExpr(n, [&] { return u(rng); }), x = b;
      const VecX expected = dense.partialPivLu().solve(b);
      klu.solve(as_span(b));
      extracted.solve(as_span(x));
      for (Index i = 0; i < n; ++i) EXPECT_EQ(x[i], b[i]) << "row " << i;
      EXPECT_LT((x - expected).norm(), 1e-8 * expected.norm());
    }
  }
  EXPECT_EQ(extracted.refactorizations(), 1);
  EXPECT_EQ(klu.refactorizations(), 1);
}

TEST(KluSolver, ExtractedSolveEqualsKlusOwnSolveOnANodeChain) {
  // The structure of a cable: a chain of 12 nodes with 6 unknowns each (dense 6×6 blocks
  // coupling neighbours), plus 3 constraint rows and columns on the first node with zero
  // diagonal (a saddle point: pivots off the diagonal), rows scaled over 6 decades. The
  // extracted solve must give klu_l_solve's answer bit for bit on KLU's factors (round 0); after
  // refactorizations on the runs (rounds 1, 2) the answer must match the dense LU; reciprocal
  // pivots must agree with the dividing solve to a few ε·cond.
  const Index nodes = 12, dofs = 6, n = nodes * dofs + 3;
  SparsityPattern p(n);
  for (Index a = 0; a < nodes; ++a)
    for (Index b = std::max<Index>(0, a - 1); b <= std::min(nodes - 1, a + 1); ++b)
      for (Index i = 0; i < dofs; ++i)
        for (Index j = 0; j < dofs; ++j) p.add(a * dofs + i, b * dofs + j);
  for (Index k = 0; k < 3; ++k) {
    p.add(nodes * dofs + k, k);
    p.add(k, nodes * dofs + k);
    p.add(nodes * dofs + k, nodes * dofs + k);
  }
  p.freeze();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  KluSolver klu(p), runs(p), reciprocal(p);
  Index differing = 0;  // components where the reciprocal solve rounds differently
  klu.set_solve(KluSolve::klu);
  runs.set_solve(KluSolve::extracted);
  reciprocal.set_solve(KluSolve::reciprocal);
  for (const int round : {0, 1, 2}) {
    VecX values(p.nonzeros());
    MatX dense = MatX::Zero(n, n);
    for (Index c = 0; c < n; ++c)
      for (Index k = p.column_start()[c]; k < p.column_start()[c + 1]; ++k) {
        const Index r = p.row_index()[k];
        const bool multiplier = r >= nodes * dofs && r == c;
        values[k] = (multiplier ? 0.0 : r == c ? 20.0 + round : u(rng)) * std::pow(10.0, r % 7 - 3);
        dense(r, c) = values[k];
      }
    klu.factor(as_span(values));
    runs.factor(as_span(values));
    reciprocal.factor(as_span(values));
    const Eigen::PartialPivLU<MatX> lu(dense);
    const double cond = infinity_condition(lu, dense);
    for (int rhs = 0; rhs < 3; ++rhs) {
      VecX b = VecX::NullaryExpr(n, [&] { return u(rng); }), x = b, y = b;
      const VecX expected = lu.solve(b);
      klu.solve(as_span(b));
      runs.solve(as_span(x));
      // Reciprocal pivots: the same factors, one rounding more per pivot, so the answers agree
      // to a few ε·cond, and somewhere they differ (else the reciprocals were not used).
      reciprocal.solve(as_span(y));
      differing += (y.array() != x.array()).count();
      EXPECT_LT((y - x).lpNorm<Eigen::Infinity>(), 16 * kEps * cond * x.lpNorm<Eigen::Infinity>())
          << "round " << round;
      EXPECT_LT((y - expected).norm(), 1e-9 * expected.norm());
      if (round == 0) {
        for (Index i = 0; i < n; ++i) EXPECT_EQ(x[i], b[i]) << "row " << i;
      }
      EXPECT_LT((x - expected).norm(), 1e-9 * expected.norm());
    }
  }
  EXPECT_EQ(runs.full_factorizations(), 1);
  EXPECT_EQ(runs.refactorizations(), 2);
  EXPECT_EQ(reciprocal.refactorizations(), 2);
  EXPECT_GT(differing, 0);
}

TEST(KluSolver, RunsRefactorizationAgreesWithKlus) {
  // The matrix class of ExtractedSolveEqualsKlusOwnSolve (BTF blocks, entries above them, rows
  // scaled over 8 decades, zero diagonals pivoted off the diagonal), refactorized over five
  // rounds of new values by KLU (klu_l_refactor, which rescales the rows) and by the left-looking
  // LU on the runs (the first factorization's scaling). Both are backward stable with the same
  // pivots, so the solutions agree to a few ε·cond; the dense LU checks both.
  const Index n = 41;
  SparsityPattern p(n);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Index starts[] = {0, 10, 25, 40, 41};
  for (int blk = 0; blk < 4; ++blk)
    for (Index i = starts[blk]; i < starts[blk + 1]; ++i) {
      p.add(i, i);
      const Index size = starts[blk + 1] - starts[blk];
      if (size > 1) {
        p.add(starts[blk] + (i - starts[blk] + 1) % size, i);
        p.add(starts[blk] + (i * 7 + 3) % size, i);
      }
      if (blk > 0) p.add((i * 5) % starts[blk], i);
    }
  p.freeze();
  KluSolver klu(p), runs(p);
  klu.set_refactor(KluRefactor::klu);
  klu.set_refactor_check(RefactorCheck::pivot_growth);
  runs.set_refactor_check(RefactorCheck::pivot_growth);
  for (int round = 0; round < 5; ++round) {
    VecX values(p.nonzeros());
    MatX dense = MatX::Zero(n, n);
    for (Index c = 0; c < n; ++c)
      for (Index k = p.column_start()[c]; k < p.column_start()[c + 1]; ++k) {
        const Index r = p.row_index()[k];
        const bool saddle = r >= 30 && r < 40 && r == c;
        values[k] = (saddle ? 0.0 : r == c ? 4.0 + round : u(rng)) * std::pow(10.0, r % 9 - 4);
        dense(r, c) = values[k];
      }
    klu.factor(as_span(values));
    runs.factor(as_span(values));
    const Eigen::PartialPivLU<MatX> lu(dense);
    const double cond = infinity_condition(lu, dense);
    for (int rhs = 0; rhs < 2; ++rhs) {
      VecX b = VecX::NullaryExpr(n, [&] { return u(rng); }), x = b;
      const VecX expected = lu.solve(b);
      klu.solve(as_span(b));
      runs.solve(as_span(x));
      EXPECT_LT((x - b).lpNorm<Eigen::Infinity>(), 100 * kEps * cond * b.lpNorm<Eigen::Infinity>())
          << "round " << round;
      EXPECT_LT((x - expected).lpNorm<Eigen::Infinity>(),
                100 * kEps * cond * expected.lpNorm<Eigen::Infinity>())
          << "round " << round;
    }
    EXPECT_GT(runs.rcond(), 0.0);
  }
  EXPECT_EQ(runs.full_factorizations(), 1);
  EXPECT_EQ(runs.refactorizations(), 4);
  EXPECT_EQ(klu.refactorizations(), 4);
}

TEST(KluSolver, ReportsASingularMatrix) {
  SparsityPattern p(2);
  p.add(0, 0);
  p.add(1, 0);
  p.add(0, 1);
  p.add(1, 1);
  p.freeze();
  KluSolver klu(p);
  const std::vector<double> values{1.0, 2.0, 2.0, 4.0};  // rank 1
  try {
    klu.factor(values);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("singular"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ancf

namespace ancf {
namespace {

// The stopwatch behind the time shares: over three 10 ms sleeps the time-stamp-counter reading
// and the steady_clock reading agree to 2 % with steady_clock intervals read just inside the
// same scopes (the calibration is over 1 ms with ns readings: ~1e-6; the rest is the distance
// between the reads), and the scopes are summed.
TEST(Stopwatch, AgreesWithSteadyClock) {
  for (const bool steady : {false, true}) {
    TickClock::use_steady_clock(steady);
    double seconds = 0.0, reference = 0.0;
    for (int k = 0; k < 3; ++k) {
      const Stopwatch watch(seconds);
      const auto start = std::chrono::steady_clock::now();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      reference += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    EXPECT_GT(seconds, 0.030) << (steady ? "steady_clock" : "time-stamp counter");
    EXPECT_NEAR(seconds, reference, 0.02 * reference)
        << (steady ? "steady_clock" : "time-stamp counter");
  }
  TickClock::use_steady_clock(false);
}

}  // namespace
}  // namespace ancf
