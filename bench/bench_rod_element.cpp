// Cost of the Kirchhoff rod element (kirchhoff_rod_element.hpp) against the cable element on the
// same helix element: force only, and force + tangent, for both rod kernels (RodKernel). Ratios are
// only meaningful within one run.
#include <benchmark/benchmark.h>

#include "ancf/physics/cable_element.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"
#include "ancf/system/cable_geometry.hpp"

namespace {
using namespace ancf;

struct Setup {
  CableGeometry g = helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), 0.1, 0.3, 2.0, 0.15, 4);
  Vec12 e0 = g.element_coordinates(1);
  Vec12 e = e0 + 0.01 * Vec12::LinSpaced(-1.0, 1.0);
};

void BM_CableElement(benchmark::State& state) {
  const Setup s;
  CableSection section;
  section.strain = StrainMeasure::elastic_line;
  section.axial_stiffness = 3e5;
  section.bending_stiffness = 0.5;
  section.mass_per_length = 0.02;
  const auto ref = CableElementReference::from_reference(
      s.e0, s.g.element_lengths[1], section.strain, {.axial = 4, .bending = 4});
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
  const Setup s;
  RodSection section;
  section.axial_stiffness = 3e5;
  section.torsional_stiffness = 0.4;
  section.bending_stiffness_2 = section.bending_stiffness_3 = 0.5;
  section.mass_per_length = 0.02;
  section.polar_inertia = 1e-7;
  const auto frames = rod_frames_toward_axis(s.g, Vec3::Zero(), Vec3::UnitZ());
  RodElementHistory h{frames[1], frames[2], 0.0};
  const auto ref = RodElementReference::from_reference(s.e0, s.g.element_lengths[1], h);
  Vec14 e;
  e << s.e, 0.05, -0.03;
  RodElementResult out;
  const bool tangent = state.range(0) != 0;
  const RodKernel kernel = state.range(1) != 0 ? RodKernel::element_jets : RodKernel::local_chain;
  for (auto _ : state) {
    evaluate_rod_element(section, ref, h, e, Vec14::Zero(),
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
