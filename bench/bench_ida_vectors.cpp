// IDA's hottest vector operations on a vector of the benchmark pendulum's GGL size (258), compiled
// with the project (src/solvers/ida_vector_ops.hpp, Arg 1) against Debian's SUNDIALS serial ones
// (Arg 0, built at -O0): the masked WRMS norm of IDA's error test, a general linear sum and the
// four-term linear combination of its predictor. The results are the same bits
// (test_ida_vector_ops).
#include <benchmark/benchmark.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <vector>

#include "ida_vector_ops.hpp"

namespace {

constexpr sunindextype kLength = 258;

struct Vectors {
  explicit Vectors(bool compiled) {
    SUNContext_Create(nullptr, &context);
    base = N_VNew_Serial(kLength, context);
    if (compiled)
      ancf::detail::use_compiled_serial_ops(base);
    else
      N_VEnableFusedOps_Serial(base, SUNTRUE);
    for (int k = 0; k < 6; ++k) v.push_back(N_VClone(base));
    for (sunindextype i = 0; i < kLength; ++i) {
      for (int k = 0; k < 6; ++k) NV_Ith_S(v[k], i) = 1.0 + 0.001 * static_cast<double>(i + k);
      NV_Ith_S(v[5], i) = i % 4 == 0 ? 0.0 : 1.0;  // the mask
    }
  }
  ~Vectors() {
    for (N_Vector x : v) N_VDestroy(x);
    N_VDestroy(base);
    SUNContext_Free(&context);
  }
  SUNContext context = nullptr;
  N_Vector base = nullptr;
  std::vector<N_Vector> v;
};

void BM_IdaWrmsNormMask(benchmark::State& state) {
  Vectors s(state.range(0) != 0);
  for (auto _ : state) benchmark::DoNotOptimize(N_VWrmsNormMask(s.v[0], s.v[1], s.v[5]));
}

void BM_IdaLinearSum(benchmark::State& state) {
  Vectors s(state.range(0) != 0);
  for (auto _ : state) {
    N_VLinearSum(0.3, s.v[0], 0.7, s.v[1], s.v[2]);
    benchmark::ClobberMemory();
  }
}

void BM_IdaLinearCombination(benchmark::State& state) {
  Vectors s(state.range(0) != 0);
  double c[4] = {0.5, 0.25, -0.125, 0.0625};
  N_Vector x[4] = {s.v[0], s.v[1], s.v[2], s.v[3]};
  for (auto _ : state) {
    N_VLinearCombination(4, c, x, s.v[4]);
    benchmark::ClobberMemory();
  }
}

}  // namespace

BENCHMARK(BM_IdaWrmsNormMask)->Arg(1)->Arg(0);
BENCHMARK(BM_IdaLinearSum)->Arg(1)->Arg(0);
BENCHMARK(BM_IdaLinearCombination)->Arg(1)->Arg(0);
