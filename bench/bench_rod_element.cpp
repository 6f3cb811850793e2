// Cost of the Kirchhoff rod element (kirchhoff_rod_element.hpp) against the cable element on the
// same helix element: force only, and force + tangent, for both rod kernels (RodKernel). Ratios are
// only meaningful within one run.
#include <benchmark/benchmark.h>

#include "helix_element_case.hpp"

namespace {
using namespace ancf;
using bench::HelixElementCase;

void BM_CableElement(benchmark::State& state) {
  const HelixElementCase s;
  const CableSection section = HelixElementCase::cable_section();
  const auto ref = s.cable_reference();
  CableElementResult out;
  const bool tangent = state.range(0) != 0;
  for (auto _ : state) {
    evaluate_cable_element(section, ref, s.e, Vec12::Zero(), {.stiffness = tangent}, out);
    benchmark::DoNotOptimize(out.force.data());
    benchmark::DoNotOptimize(out.stiffness.data());
  }
}
BENCHMARK(BM_CableElement)->ArgName("tangent")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_RodElement(benchmark::State& state) {
  const HelixElementCase s;
  const RodSection section = HelixElementCase::rod_section();
  RodElementHistory h = s.rod_history();
  const auto ref = s.rod_reference(h);
  const Vec15 e = s.rod_coordinates();
  RodElementResult out;
  const bool tangent = state.range(0) != 0;
  const RodKernel kernel = state.range(1) != 0 ? RodKernel::element_jets : RodKernel::local_chain;
  for (auto _ : state) {
    evaluate_rod_element(section, ref, h, e, Vec15::Zero(),
                         {.stiffness = tangent, .kernel = kernel}, out);
    benchmark::DoNotOptimize(out.force.data());
    benchmark::DoNotOptimize(out.stiffness.data());
  }
}
// kernel 0: RodKernel::local_chain (default), 1: RodKernel::element_jets (the original).
BENCHMARK(BM_RodElement)
    ->ArgNames({"tangent", "kernel"})
    ->ArgsProduct({{0, 1}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
