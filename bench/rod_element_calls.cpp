// A fixed number of evaluations of the element of bench_rod_element.cpp, for instruction counts
// under callgrind (docs/rod.md, "Cost"), which are reproducible where timings on loaded shared
// cores are not. Usage: ancf-rod-element-calls KERNEL TANGENT CALLS, KERNEL = local_chain,
// element_jets, cable, distributed_moment or distributed_moment_jets (rod_distributed_moment on
// the same element with the local-chain or the element-jets kernel),
// TANGENT = 0 or 1, e.g.
//   valgrind --tool=callgrind ancf-rod-element-calls local_chain 1 100
// and read the inclusive count of evaluate_rod_element (evaluate_cable_element,
// rod_distributed_moment) ÷ CALLS.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ancf/physics/kirchhoff_rod_distributed_moment.hpp"
#include "helix_element_case.hpp"

int main(int argc, char** argv) {
  using namespace ancf;
  const std::string kernel = argc > 1 ? argv[1] : "";
  const bool moment = kernel == "distributed_moment" || kernel == "distributed_moment_jets";
  if (argc != 4 ||
      (kernel != "local_chain" && kernel != "element_jets" && kernel != "cable" && !moment)) {
    std::fprintf(stderr,
                 "usage: %s local_chain|element_jets|cable|distributed_moment[_jets] TANGENT(0|1) "
                 "CALLS\n",
                 argv[0]);
    return 2;
  }
  const bool tangent = std::atoi(argv[2]) != 0;
  const int calls = std::atoi(argv[3]);
  const bench::HelixElementCase c;  // the element and sections of bench_rod_element.cpp
  Vec12 e12 = c.e;
  double sum = 0.0;  // keeps the results alive
  if (kernel == "cable") {
    const CableSection section = bench::HelixElementCase::cable_section();
    const auto ref = c.cable_reference();
    CableElementResult out;
    for (int i = 0; i < calls; ++i) {
      e12[0] += 1e-9;
      evaluate_cable_element(section, ref, e12, Vec12::Zero(), {.stiffness = tangent}, out);
      sum += out.force[0] + (tangent ? out.stiffness(3, 4) : 0.0);
    }
  } else if (moment) {
    const RodKernel k =
        kernel == "distributed_moment" ? RodKernel::local_chain : RodKernel::element_jets;
    RodElementHistory h = c.rod_history();
    const auto ref = c.rod_reference(h);
    Vec15 e = c.rod_coordinates();
    RodDistributedMomentLoad out;
    for (int i = 0; i < calls; ++i) {
      e[0] += 1e-9;
      rod_distributed_moment(ref, h, e, Vec3(0.3, -0.2, 0.5), tangent, out, k);
      sum += out.force[0] + (tangent ? out.jacobian(3, 4) : 0.0);
    }
  } else {
    const RodSection section = bench::HelixElementCase::rod_section();
    RodElementHistory h = c.rod_history();
    const auto ref = c.rod_reference(h);
    Vec15 e = c.rod_coordinates();
    const RodKernel k = kernel == "local_chain" ? RodKernel::local_chain : RodKernel::element_jets;
    RodElementResult out;
    for (int i = 0; i < calls; ++i) {
      e[0] += 1e-9;
      evaluate_rod_element(section, ref, h, e, Vec15::Zero(), {.stiffness = tangent, .kernel = k},
                           out);
      sum += out.force[0] + (tangent ? out.stiffness(3, 4) : 0.0);
    }
  }
  std::printf("%.17g\n", sum);
  return 0;
}
