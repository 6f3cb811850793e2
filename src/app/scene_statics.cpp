#include "scene_statics.hpp"

#include "ancf/system/static_model_problem.hpp"

namespace ancf::app {

void solve_scene_statics(const Scene& scene, const StaticSettings& settings, SceneStatics& result) {
  const Model& model = scene.model;
  const Index n = model.coordinate_count();
  StaticModelProblem problem(model);
  VecX y = problem.initial_guess();
  result.state = SystemState::initial(model);
  result.state.v.setZero();
  result.state.a = VecX::Zero(n);
  StaticSolverOptions options;
  options.load_steps = settings.load_steps;
  options.max_iterations = settings.max_iterations;
  options.increment_tolerance = settings.increment_tolerance;
  StaticSolver solver(problem, options);
  // The state and the history it was committed with, also for the last converged state of a
  // failed solve.
  auto keep = [&] {
    result.state.q = y.head(n);
    result.state.lambda = y.tail(model.multiplier_count());
    result.rod_history = problem.workspace().rods;
    result.state.rod_history = &result.rod_history;
  };
  try {
    result.statistics = solver.solve(y);
  } catch (...) {
    keep();
    throw;
  }
  keep();
}

void add_static_json(const StaticSettings& settings, const StaticSolverStatistics& statistics,
                     JsonObject& options, JsonObject& counters, JsonObject& results) {
  options.set("load_steps", static_cast<long>(settings.load_steps))
      .set("max_iterations", static_cast<long>(settings.max_iterations))
      .set("increment_tolerance", settings.increment_tolerance);
  counters.set("load steps", static_cast<long>(statistics.load_steps))
      .set("step cuts", static_cast<long>(statistics.step_cuts))
      .set("Newton iterations", static_cast<long>(statistics.newton_iterations))
      .set("full factorizations", static_cast<long>(statistics.full_factorizations))
      .set("refactorizations", static_cast<long>(statistics.refactorizations));
  results.set("residual_norm", statistics.residual_norm)
      .set("smallest_singular_value", statistics.smallest_singular_value)
      .set("singular_direction", statistics.singular_direction);
}

}  // namespace ancf::app
