// The static equilibrium of a scene under its loads and gravity (load stepping with Newton,
// StaticSolver on StaticModelProblem), shared by `ancf static` and `ancf modes --static`.
#pragma once

#include "ancf/io/run_metadata.hpp"
#include "ancf/io/scene.hpp"
#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/assembly.hpp"

namespace ancf::app {

/// Command-line settings of the static solve (defaults in docs/statics_and_modes.md).
struct StaticSettings {
  int load_steps = 10;                 ///< equal load increments 0 → 1 (each may be halved)
  int max_iterations = 30;             ///< Newton iterations per increment
  double increment_tolerance = 1e-11;  ///< StaticSolverOptions::increment_tolerance
};

/// The result of solve_scene_statics. Not copyable: `state.rod_history` points at `rod_history`.
struct SceneStatics {
  SceneStatics() = default;
  SceneStatics(const SceneStatics&) = delete;
  SceneStatics& operator=(const SceneStatics&) = delete;

  /// The equilibrium at t = 0: q, λ solved; v = a = 0. On failure, the last converged state.
  SystemState state;
  /// The rod frame history committed with `state` (rods' twist coordinates are angles relative
  /// to it, docs/rod.md "History"): outputs and modes must evaluate the state under it, not
  /// under the reference frames, which a rod turned by π or more cannot even be evaluated on.
  RodHistory rod_history;
  StaticSolverStatistics statistics;
};

/// Solve the statics of `scene` from its initial configuration at load factor 1 (gravity, nodal
/// and point loads, body torques; spring-dampers and drives at t = 0). Throws SolverError (the
/// load factor, iteration and worst residual row; SingularStaticProblem for a structural
/// singularity) if an increment cannot be completed; `result.state` then holds the last
/// converged state.
void solve_scene_statics(const Scene& scene, const StaticSettings& settings, SceneStatics& result);

/// The settings and statistics as run.json members ("options", "counters", "results").
void add_static_json(const StaticSettings& settings, const StaticSolverStatistics& statistics,
                     JsonObject& options, JsonObject& counters, JsonObject& results);

}  // namespace ancf::app
