// A fixed number of evaluations of the element of bench_rod_element.cpp, for instruction counts
// under callgrind (docs/rod.md, "Cost"), which are reproducible where timings on loaded shared
// cores are not. Usage: ancf-rod-element-calls KERNEL TANGENT CALLS, KERNEL = local_chain,
// element_jets or cable, TANGENT = 0 or 1, e.g.
//   valgrind --tool=callgrind ancf-rod-element-calls local_chain 1 100
// and read the inclusive count of evaluate_rod_element (evaluate_cable_element) ÷ CALLS.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ancf/physics/cable_element.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"
#include "ancf/system/cable_geometry.hpp"

int main(int argc, char** argv) {
  using namespace ancf;
  const std::string kernel = argc > 1 ? argv[1] : "";
  if (argc != 4 || (kernel != "local_chain" && kernel != "element_jets" && kernel != "cable")) {
    std::fprintf(stderr, "usage: %s local_chain|element_jets|cable TANGENT(0|1) CALLS\n", argv[0]);
    return 2;
  }
  const bool tangent = std::atoi(argv[2]) != 0;
  const int calls = std::atoi(argv[3]);
  // The element and sections of bench_rod_element.cpp.
  const CableGeometry g =
      helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), 0.1, 0.3, 2.0, 0.15, 4);
  const Vec12 e0 = g.element_coordinates(1);
  Vec12 e12 = e0 + 0.01 * Vec12::LinSpaced(-1.0, 1.0);
  double sum = 0.0;  // keeps the results alive
  if (kernel == "cable") {
    CableSection section;
    section.strain = StrainMeasure::elastic_line;
    section.axial_stiffness = 3e5;
    section.bending_stiffness = 0.5;
    section.mass_per_length = 0.02;
    const auto ref = CableElementReference::from_reference(e0, g.element_lengths[1], section.strain,
                                                           {.axial = 4, .bending = 4});
    CableElementResult out;
    for (int i = 0; i < calls; ++i) {
      e12[0] += 1e-9;
      evaluate_cable_element(section, ref, e12, Vec12::Zero(), {.stiffness = tangent}, out);
      sum += out.force[0] + (tangent ? out.stiffness(3, 4) : 0.0);
    }
  } else {
    RodSection section;
    section.axial_stiffness = 3e5;
    section.torsional_stiffness = 0.4;
    section.bending_stiffness_2 = section.bending_stiffness_3 = 0.5;
    section.mass_per_length = 0.02;
    section.polar_inertia = 1e-7;
    const auto frames = rod_frames_toward_axis(g, Vec3::Zero(), Vec3::UnitZ());
    RodElementHistory h{frames[1], frames[2], 0.0};
    const auto ref = RodElementReference::from_reference(e0, g.element_lengths[1], h);
    Vec14 e;
    e << e12, 0.05, -0.03;
    const RodKernel k = kernel == "local_chain" ? RodKernel::local_chain : RodKernel::element_jets;
    RodElementResult out;
    for (int i = 0; i < calls; ++i) {
      e[0] += 1e-9;
      evaluate_rod_element(section, ref, h, e, Vec14::Zero(), {.stiffness = tangent, .kernel = k},
                           out);
      sum += out.force[0] + (tangent ? out.stiffness(3, 4) : 0.0);
    }
  }
  std::printf("%.17g\n", sum);
  return 0;
}
