#include "ancf/scenes/cantilever.hpp"

#include <cmath>

#include "ancf/system/model_builder.hpp"
#include "ancf/system/static_model_problem.hpp"

namespace ancf {

Model cantilever_model(const CantileverSpec& spec) {
  ModelBuilder b;
  CableSection section;
  section.strain = spec.strain;
  section.axial_stiffness = spec.axial_stiffness;
  section.bending_stiffness = spec.bending_stiffness;
  section.mass_per_length = 1.0;
  const Index cable =
      b.add_cable("cantilever", straight_cable(Vec3::Zero(), spec.length * Vec3::UnitX(), spec.elements),
                  section);
  b.pin("root position", {cable, 0}, Vec3::Zero());
  b.align_slope("root slope", {cable, 0}, Vec3::UnitX());
  b.add_node_force({cable, -1}, -spec.tip_load * Vec3::UnitY());
  return b.finalize();
}

CantileverTip solve_cantilever(const CantileverSpec& spec, int load_steps) {
  const Model model = cantilever_model(spec);
  StaticModelProblem problem(model);
  StaticSolverOptions options;
  options.load_steps = load_steps;
  StaticSolver solver(problem, options);
  VecX y = problem.initial_guess();
  CantileverTip tip;
  tip.stats = solver.solve(y);
  const Index k = model.node_coordinate(0, -1);
  tip.displacement = y.segment<3>(k) - spec.length * Vec3::UnitX();
  const Vec3 slope = y.segment<3>(k + 3);
  tip.rotation = std::atan2(-slope.y(), slope.x());
  return tip;
}

}  // namespace ancf
