// IDA's vector operations compiled with the project (src/solvers/ida_vector_ops.hpp) against
// SUNDIALS' own serial ones: every operation, every special case of the linear sum (coefficients
// ±1, a = ±b, z aliasing x or y) and the fused forms with their aliasing, bit for bit; and an IDA
// run of the cable pendulum with either set giving the same counters and the same state bits.
#include <gtest/gtest.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ida_vector_ops.hpp"

namespace ancf {
namespace {

constexpr sunindextype kLength = 37;

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Serial vectors in pairs: `ours` carries the compiled ops, `theirs` SUNDIALS' (with its fused
// operations enabled, which is what the compiled set replaces); both hold the same values.
class VectorOps : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_EQ(SUNContext_Create(nullptr, &context_), 0);
    ours_template_ = N_VNew_Serial(kLength, context_);
    detail::use_compiled_serial_ops(ours_template_);
    theirs_template_ = N_VNew_Serial(kLength, context_);
    N_VEnableFusedOps_Serial(theirs_template_, SUNTRUE);
  }
  void TearDown() override {
    for (N_Vector v : vectors_) N_VDestroy(v);
    N_VDestroy(ours_template_);
    N_VDestroy(theirs_template_);
    SUNContext_Free(&context_);
  }
  struct Pair {
    N_Vector ours, theirs;
  };
  // Values of several magnitudes and signs, some exact zeros (seeded, so reproducible).
  Pair make(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Pair p{N_VClone(ours_template_), N_VClone(theirs_template_)};
    vectors_.push_back(p.ours);
    vectors_.push_back(p.theirs);
    for (sunindextype i = 0; i < kLength; ++i) {
      const double x = i % 11 == 5 ? 0.0 : u(rng) * std::pow(10.0, 6.0 * u(rng));
      NV_Ith_S(p.ours, i) = x;
      NV_Ith_S(p.theirs, i) = x;
    }
    return p;
  }
  Pair mask() {
    Pair p = make(99);
    for (sunindextype i = 0; i < kLength; ++i)
      NV_Ith_S(p.ours, i) = NV_Ith_S(p.theirs, i) = i % 3 == 0 ? 0.0 : 1.0;
    return p;
  }
  static void expect_same(const Pair& p, const char* what) {
    for (sunindextype i = 0; i < kLength; ++i)
      ASSERT_TRUE(same_bits(NV_Ith_S(p.ours, i), NV_Ith_S(p.theirs, i)))
          << what << ": element " << i << ": " << NV_Ith_S(p.ours, i) << " against "
          << NV_Ith_S(p.theirs, i);
  }
  SUNContext context_ = nullptr;
  N_Vector ours_template_ = nullptr, theirs_template_ = nullptr;
  std::vector<N_Vector> vectors_;
};

TEST_F(VectorOps, LinearSumInEverySpecialCaseAndAliasing) {
  const double c = 0.3721, d = -2.75;
  const std::vector<std::pair<double, double>> coefficients = {{1, 1},  {1, -1}, {-1, 1}, {1, d},
                                                               {c, 1},  {-1, d}, {c, -1}, {c, c},
                                                               {c, -c}, {c, d},  {0, d},  {-1, -1}};
  int round = 0;
  for (const auto& [a, b] : coefficients) {
    for (int alias = 0; alias < 3; ++alias) {  // z distinct, z = x, z = y
      const Pair x = make(2 * round + 1), y = make(2 * round + 2), z = make(7);
      ++round;
      const Pair& out = alias == 1 ? x : alias == 2 ? y : z;
      N_VLinearSum(a, x.ours, b, y.ours, out.ours);
      N_VLinearSum(a, x.theirs, b, y.theirs, out.theirs);
      expect_same(out, "linear sum");
    }
  }
}

TEST_F(VectorOps, ElementwiseOperations) {
  const Pair x = make(1), y = make(2);
  for (double c : {1.0, -1.0, 0.37}) {
    Pair z = make(3);
    N_VScale(c, x.ours, z.ours);
    N_VScale(c, x.theirs, z.theirs);
    expect_same(z, "scale");
    N_VScale(c, z.ours, z.ours);
    N_VScale(c, z.theirs, z.theirs);
    expect_same(z, "scale in place");
  }
  Pair z = make(4);
  N_VConst(0.125, z.ours);
  N_VConst(0.125, z.theirs);
  expect_same(z, "const");
  N_VProd(x.ours, y.ours, z.ours);
  N_VProd(x.theirs, y.theirs, z.theirs);
  expect_same(z, "prod");
  N_VDiv(x.ours, y.ours, z.ours);
  N_VDiv(x.theirs, y.theirs, z.theirs);
  expect_same(z, "div");
  N_VAbs(x.ours, z.ours);
  N_VAbs(x.theirs, z.theirs);
  expect_same(z, "abs");
  N_VInv(y.ours, z.ours);
  N_VInv(y.theirs, z.theirs);
  expect_same(z, "inv");
  N_VAddConst(x.ours, 3.5, z.ours);
  N_VAddConst(x.theirs, 3.5, z.theirs);
  expect_same(z, "add const");
}

TEST_F(VectorOps, Reductions) {
  const Pair x = make(5), w = make(6), id = mask();
  EXPECT_TRUE(same_bits(N_VDotProd(x.ours, w.ours), N_VDotProd(x.theirs, w.theirs)));
  EXPECT_TRUE(same_bits(N_VMaxNorm(x.ours), N_VMaxNorm(x.theirs)));
  EXPECT_TRUE(same_bits(N_VMin(x.ours), N_VMin(x.theirs)));
  EXPECT_TRUE(same_bits(N_VWrmsNorm(x.ours, w.ours), N_VWrmsNorm(x.theirs, w.theirs)));
  EXPECT_TRUE(same_bits(N_VWrmsNormMask(x.ours, w.ours, id.ours),
                        N_VWrmsNormMask(x.theirs, w.theirs, id.theirs)));
  EXPECT_TRUE(same_bits(N_VWSqrSumLocal(x.ours, w.ours), N_VWSqrSumLocal(x.theirs, w.theirs)));
  EXPECT_TRUE(same_bits(N_VWSqrSumMaskLocal(x.ours, w.ours, id.ours),
                        N_VWSqrSumMaskLocal(x.theirs, w.theirs, id.theirs)));
  // The masked norm leaves out the masked elements, so it is not the full one.
  EXPECT_LT(N_VWrmsNormMask(x.ours, w.ours, id.ours), N_VWrmsNorm(x.ours, w.ours));
}

TEST_F(VectorOps, LinearCombinationWithItsAliasing) {
  for (int nvec = 1; nvec <= 6; ++nvec) {
    // aliasing: 0 none, 1 z = X[0] with c₀ = 1, 2 z = X[0], 3 z = X[nvec − 1] (a later term)
    for (int alias = 0; alias < 4; ++alias) {
      std::vector<Pair> terms;
      for (int k = 0; k < nvec; ++k) terms.push_back(make(10 + k));
      std::vector<double> c = {1.0, -1.0, 0.25, -3.5, 1.0, 7.0};
      if (alias != 1) c[0] = 0.75;
      Pair z = make(30);
      if (alias == 1 || alias == 2) z = terms[0];
      if (alias == 3) z = terms.back();
      std::vector<N_Vector> xo, xt;
      for (const Pair& t : terms) {
        xo.push_back(t.ours);
        xt.push_back(t.theirs);
      }
      ASSERT_EQ(N_VLinearCombination(nvec, c.data(), xo.data(), z.ours), 0);
      ASSERT_EQ(N_VLinearCombination(nvec, c.data(), xt.data(), z.theirs), 0);
      expect_same(z, "linear combination");
    }
  }
}

TEST_F(VectorOps, VectorArrayOperations) {
  const int nvec = 3;
  std::vector<Pair> x, y, z;
  for (int k = 0; k < nvec; ++k) {
    x.push_back(make(40 + k));
    y.push_back(make(50 + k));
    z.push_back(make(60 + k));
  }
  auto ours = [](const std::vector<Pair>& v) {
    std::vector<N_Vector> r;
    for (const Pair& p : v) r.push_back(p.ours);
    return r;
  };
  auto theirs = [](const std::vector<Pair>& v) {
    std::vector<N_Vector> r;
    for (const Pair& p : v) r.push_back(p.theirs);
    return r;
  };
  auto xo = ours(x), xt = theirs(x), yo = ours(y), yt = theirs(y), zo = ours(z), zt = theirs(z);
  auto check_all = [&](const std::vector<Pair>& v, const char* what) {
    for (const Pair& p : v) expect_same(p, what);
  };
  for (const auto& [a, b] : std::vector<std::pair<double, double>>{
           {1, 1}, {0.5, 1}, {1, -2}, {0.5, 0.5}, {0.5, -0.5}, {0.3, 0.7}}) {
    ASSERT_EQ(N_VLinearSumVectorArray(nvec, a, xo.data(), b, yo.data(), zo.data()), 0);
    ASSERT_EQ(N_VLinearSumVectorArray(nvec, a, xt.data(), b, yt.data(), zt.data()), 0);
    check_all(z, "linear sum array");
    ASSERT_EQ(N_VLinearSumVectorArray(nvec, a, xo.data(), b, yo.data(), yo.data()), 0);
    ASSERT_EQ(N_VLinearSumVectorArray(nvec, a, xt.data(), b, yt.data(), yt.data()), 0);
    check_all(y, "linear sum array, Z = Y");
  }
  std::vector<double> c = {0.5, -1.0, 3.0};
  ASSERT_EQ(N_VScaleVectorArray(nvec, c.data(), xo.data(), zo.data()), 0);
  ASSERT_EQ(N_VScaleVectorArray(nvec, c.data(), xt.data(), zt.data()), 0);
  check_all(z, "scale array");
  ASSERT_EQ(N_VScaleVectorArray(nvec, c.data(), zo.data(), zo.data()), 0);
  ASSERT_EQ(N_VScaleVectorArray(nvec, c.data(), zt.data(), zt.data()), 0);
  check_all(z, "scale array in place");
  ASSERT_EQ(N_VScaleAddMulti(nvec, c.data(), x[0].ours, yo.data(), zo.data()), 0);
  ASSERT_EQ(N_VScaleAddMulti(nvec, c.data(), x[0].theirs, yt.data(), zt.data()), 0);
  check_all(z, "scale add multi");
  ASSERT_EQ(N_VScaleAddMulti(nvec, c.data(), x[0].ours, yo.data(), yo.data()), 0);
  ASSERT_EQ(N_VScaleAddMulti(nvec, c.data(), x[0].theirs, yt.data(), yt.data()), 0);
  check_all(y, "scale add multi in place");
  ASSERT_EQ(N_VConstVectorArray(nvec, -0.5, zo.data()), 0);
  ASSERT_EQ(N_VConstVectorArray(nvec, -0.5, zt.data()), 0);
  check_all(z, "const array");
  std::vector<double> no(nvec), nt(nvec);
  ASSERT_EQ(N_VDotProdMulti(nvec, x[1].ours, yo.data(), no.data()), 0);
  ASSERT_EQ(N_VDotProdMulti(nvec, x[1].theirs, yt.data(), nt.data()), 0);
  for (int k = 0; k < nvec; ++k) EXPECT_TRUE(same_bits(no[k], nt[k])) << "dot multi " << k;
  ASSERT_EQ(N_VWrmsNormVectorArray(nvec, xo.data(), yo.data(), no.data()), 0);
  ASSERT_EQ(N_VWrmsNormVectorArray(nvec, xt.data(), yt.data(), nt.data()), 0);
  for (int k = 0; k < nvec; ++k) EXPECT_TRUE(same_bits(no[k], nt[k])) << "wrms array " << k;
  const Pair id = mask();
  ASSERT_EQ(N_VWrmsNormMaskVectorArray(nvec, xo.data(), yo.data(), id.ours, no.data()), 0);
  ASSERT_EQ(N_VWrmsNormMaskVectorArray(nvec, xt.data(), yt.data(), id.theirs, nt.data()), 0);
  for (int k = 0; k < nvec; ++k) EXPECT_TRUE(same_bits(no[k], nt[k])) << "wrms mask array " << k;
}

// The whole integrator: with the compiled operations and the one-pass error weights IDA takes
// the same steps and ends in the same state, bit for bit.
TEST(IdaCompiledVectorOps, SameStepsAndStateAsSundialsOwnOperations) {
  const Model model = cable_pendulum_model(benchmark_cable_pendulum(6));
  auto run = [&](bool compiled) {
    GglProblem problem(model);
    IdaOptions o;
    o.rtol = 1e-5;
    o.max_order = 5;
    o.output_times = {0.05};
    o.compiled_vector_ops = compiled;
    IdaIntegrator ida(problem, o);
    ida.run([](double, std::span<const double>, std::span<const double>) {});
    return std::pair{std::vector<double>(ida.y().begin(), ida.y().end()), ida.statistics()};
  };
  const auto [y_compiled, s_compiled] = run(true);
  const auto [y_sundials, s_sundials] = run(false);
  EXPECT_GT(s_compiled.steps, 50);
  EXPECT_EQ(s_compiled.steps, s_sundials.steps);
  EXPECT_EQ(s_compiled.residual_evaluations, s_sundials.residual_evaluations);
  EXPECT_EQ(s_compiled.nonlinear_iterations, s_sundials.nonlinear_iterations);
  EXPECT_EQ(s_compiled.error_test_failures, s_sundials.error_test_failures);
  ASSERT_EQ(y_compiled.size(), y_sundials.size());
  for (std::size_t i = 0; i < y_compiled.size(); ++i)
    ASSERT_TRUE(same_bits(y_compiled[i], y_sundials[i])) << "unknown " << i;
}

}  // namespace
}  // namespace ancf
