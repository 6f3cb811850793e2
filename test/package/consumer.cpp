// Uses the installed headers and libraries: loads a scene, overrides a value, runs it through
// the io layer's Simulation and prints the tip height at t_end (exit 0 when it is finite and
// the pendulum has fallen).
#include <cmath>
#include <cstdio>

#include "ancf/io/scene_overrides.hpp"
#include "ancf/io/simulation.hpp"

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const ancf::Scene scene =
      ancf::load_scene(argv[1], {{"cable[0].elements", "4"}, {"integrator.t_end", "0.02"}});
  ancf::Simulation run(scene.model, scene.integrator,
                       ancf::output_times(scene.output.interval, scene.integrator.t_end));
  while (run.advance_to_next_output()) {
  }
  const double z = run.state().q(run.state().q.size() - 4);  // last node's z
  std::printf("t = %g s, tip z = %.9f m\n", run.time(), z);
  return std::isfinite(z) && z < 0.0 ? 0 : 1;
}
