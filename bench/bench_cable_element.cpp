// Micro-benchmarks of one ANCF cable element through evaluate_cable_element: internal force
// alone (residual assembly) and force + tangent stiffness (Jacobian assembly), for every
// formulation the element supports. Project goal: the paper's axial-only element, force +
// tangent, below 1 µs.
#include <benchmark/benchmark.h>

#include "ancf/physics/cable_element.hpp"

namespace {

using ancf::CableElementReference;
using ancf::CableElementResult;
using ancf::CableEvalRequest;
using ancf::CableSection;
using ancf::StrainMeasure;
using ancf::Vec12;
using ancf::Vec3;

enum class Formulation {
  green_axial,           ///< Green–Lagrange ε, EI = 0: the paper's element
  elastic_line_axial,    ///< ε = |r_x| − 1, EI = 0
  green_bending,         ///< Green ε + Gerstmayr–Shabana curvature
  elastic_line_bending,  ///< elastic-line ε + Gerstmayr–Irschik curvature
  green_bending_damped,  ///< Green + bending + Kelvin–Voigt axial and bending damping
};

// Steel-like thin rope. The values only have to be non-zero where a formulation uses them: the
// element dispatches on has_bending()/has_damping(), so zeros select the cheaper code paths.
CableSection section_for(Formulation f) {
  CableSection s;
  s.axial_stiffness = 4e6;  // EA [N]
  s.mass_per_length = 0.15;
  switch (f) {
    case Formulation::green_axial:
      break;
    case Formulation::elastic_line_axial:
      s.strain = StrainMeasure::elastic_line;
      break;
    case Formulation::green_bending:
      s.bending_stiffness = 6.0;  // EI [N m²]
      break;
    case Formulation::elastic_line_bending:
      s.strain = StrainMeasure::elastic_line;
      s.bending_stiffness = 6.0;
      break;
    case Formulation::green_bending_damped:
      s.bending_stiffness = 6.0;
      s.axial_damping = 40.0;   // c_a [N s]
      s.bending_damping = 0.1;  // c_b [N m² s]
      break;
  }
  return s;
}

constexpr double kLength = 0.1;  // element length l [m]

// Straight stress-free reference along +x: e0 = [r_i, r_i,x, r_j, r_j,x].
Vec12 straight_reference() {
  Vec12 e0;
  e0 << 0, 0, 0, 1, 0, 0, kLength, 0, 0, 1, 0, 0;
  return e0;
}

// A realistic deformed state: the reference stretched by ~1 % and bent out of its axis in both
// transverse directions. The curvature is non-zero at every Gauss point, so no κ = 0 branch of
// the bending/damping code is taken and every point does the full work.
Vec12 deformed_configuration() {
  Vec12 e = 1.01 * straight_reference();
  e.segment<3>(0) += Vec3(0.001, 0.0005, -0.0003);
  e.segment<3>(3) += Vec3(0.0, 0.02, 0.01);
  e.segment<3>(6) += Vec3(-0.0005, 0.002, 0.0012);
  e.segment<3>(9) += Vec3(0.0, -0.015, 0.03);
  return e;
}

// Non-zero nodal velocities, so the Kelvin–Voigt terms (ε̇, κ̇) are really evaluated.
Vec12 some_velocity() {
  Vec12 v;
  v << 0.01, -0.2, 0.1, 0.05, 0.3, -0.1, 0.02, 0.4, -0.3, -0.02, 0.1, 0.2;
  return v;
}

void run_element(benchmark::State& state, Formulation f, CableEvalRequest request) {
  const CableSection section = section_for(f);
  const CableElementReference ref =
      CableElementReference::from_reference(straight_reference(), kLength, section.strain);
  Vec12 e = deformed_configuration();
  Vec12 e_dot = some_velocity();
  CableElementResult out;
  for (auto _ : state) {
    // The inputs are "possibly modified" each iteration and the result is "possibly read", so
    // the compiler can neither hoist the evaluation out of the loop nor drop it.
    benchmark::DoNotOptimize(e);
    benchmark::DoNotOptimize(e_dot);
    ancf::evaluate_cable_element(section, ref, e, e_dot, request, out);
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());  // items/s = elements per second
}

// Force (and energy) only: what the residual assembly does per element.
void BM_ElementForce(benchmark::State& state, Formulation f) {
  run_element(state, f, CableEvalRequest{});
}

// The same with the pointwise kernel of the matrix path (CableForceKernel::pointwise, the
// force-only kernel before the invariant one): the ratio of the two is what the residual gains.
void BM_ElementForcePointwise(benchmark::State& state, Formulation f) {
  run_element(state, f, CableEvalRequest{.force_kernel = ancf::CableForceKernel::pointwise});
}

// Force + tangent stiffness ∂f/∂e: what the static Jacobian assembly does per element.
void BM_ElementForceTangent(benchmark::State& state, Formulation f) {
  run_element(state, f, CableEvalRequest{.stiffness = true});
}

// Force + ∂f/∂e + ∂f/∂ė: what an implicit dynamic step's iteration matrix needs per element.
void BM_ElementForceTangentDamping(benchmark::State& state, Formulation f) {
  run_element(state, f, CableEvalRequest{.stiffness = true, .damping_matrix = true});
}

}  // namespace

BENCHMARK_CAPTURE(BM_ElementForceTangent, green_axial, Formulation::green_axial);
BENCHMARK_CAPTURE(BM_ElementForceTangent, elastic_line_axial, Formulation::elastic_line_axial);
BENCHMARK_CAPTURE(BM_ElementForceTangent, green_bending, Formulation::green_bending);
BENCHMARK_CAPTURE(BM_ElementForceTangent, elastic_line_bending, Formulation::elastic_line_bending);
BENCHMARK_CAPTURE(BM_ElementForceTangentDamping, green_bending_damped,
                  Formulation::green_bending_damped);

BENCHMARK_CAPTURE(BM_ElementForce, green_axial, Formulation::green_axial);
BENCHMARK_CAPTURE(BM_ElementForce, elastic_line_axial, Formulation::elastic_line_axial);
BENCHMARK_CAPTURE(BM_ElementForce, green_bending, Formulation::green_bending);
BENCHMARK_CAPTURE(BM_ElementForce, elastic_line_bending, Formulation::elastic_line_bending);
BENCHMARK_CAPTURE(BM_ElementForce, green_bending_damped, Formulation::green_bending_damped);

BENCHMARK_CAPTURE(BM_ElementForcePointwise, green_axial, Formulation::green_axial);
BENCHMARK_CAPTURE(BM_ElementForcePointwise, elastic_line_axial, Formulation::elastic_line_axial);
BENCHMARK_CAPTURE(BM_ElementForcePointwise, green_bending, Formulation::green_bending);
BENCHMARK_CAPTURE(BM_ElementForcePointwise, elastic_line_bending,
                  Formulation::elastic_line_bending);
BENCHMARK_CAPTURE(BM_ElementForcePointwise, green_bending_damped,
                  Formulation::green_bending_damped);
