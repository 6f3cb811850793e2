// The integrator driver shared by `ancf run` and the studies (simulation.hpp).
#include "ancf/io/simulation.hpp"

#include <cmath>

#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ancf/system/multibody_problem.hpp"

namespace ancf {

namespace {

void run_ida(const Model& model, const IntegratorSettings& s, const std::vector<double>& times,
             const SimulationHooks& hooks, SimulationCounters& c, SimulationTimings& timings) {
  GglScales scales;
  if (s.ida_slope_position_scale) scales.slope = SlopeScale::position_equivalent;
  GglProblem problem(model, scales, ContactPatternOptions{.policy = s.contact_pattern});
  IdaOptions o;
  o.rtol = s.rtol;
  o.atol_position = s.ida_atol_position;
  o.atol_velocity = s.ida_atol_velocity;
  o.atol_multiplier = s.ida_atol_multiplier;
  o.max_step = s.max_step;
  o.max_order = s.max_order;
  o.linear_solver = s.ida_sundials_klu ? IdaLinearSolver::sundials_klu : IdaLinearSolver::ancf_klu;
  o.output_times = times;
  o.stop_time = s.t_end;
  IdaIntegrator ida(problem, o);
  SystemState state = SystemState::initial(model);
  state.rod_history = &problem.workspace().rods;
  problem.unpack(0.0, ida.y(), ida.yp(), state);  // consistent initial values
  if (hooks.output) hooks.output(state);
  auto counters = [&] {
    const IdaStatistics st = ida.statistics();
    c = {{"steps", st.steps},
         {"residual evaluations", st.residual_evaluations},
         {"Jacobian evaluations", st.jacobian_evaluations},
         {"linear solver setups", st.linear_solver_setups},
         {"Newton iterations", st.nonlinear_iterations},
         {"error test failures", st.error_test_failures},
         {"convergence failures", st.convergence_failures},
         {"KLU re-pivotings", st.klu_repivots},
         {"full factorizations", st.full_factorizations},
         {"refactorizations", st.refactorizations},
         {"pattern changes", st.pattern_changes},
         {"symbolic analyses", st.symbolic_analyses},
         {"pattern non-zeros (largest)", problem.contact_pattern().statistics().most_nonzeros},
         {"contact samples evaluated", problem.workspace().narrow_phase_samples}};
    const Workspace& ws = problem.workspace();
    const double kernels = ws.element_seconds, contact = ws.contact_seconds;
    timings = {
        {"wall", st.wall_time},
        {"element kernels", kernels},
        {"contact", contact},
        {"assembly (rest of residual and Jacobian)",
         st.residual_seconds + st.jacobian_seconds - kernels - contact},
        {"factorization", st.factor_seconds},
        {"solves", st.solve_seconds},
        {"IDA (BDF, Newton, error test)", st.wall_time - st.residual_seconds - st.jacobian_seconds -
                                              st.factor_seconds - st.solve_seconds}};
  };
  try {
    ida.run([&](double t, std::span<const double> y, std::span<const double> yp) {
      problem.unpack(t, y, yp, state);
      if (hooks.output) hooks.output(state);
      if (hooks.progress) hooks.progress(t);
    });
  } catch (...) {
    counters();
    throw;
  }
  counters();
}

void run_genalpha(const Model& model, const IntegratorSettings& s, const std::vector<double>& times,
                  const SimulationHooks& hooks, SimulationCounters& c, SimulationTimings& timings) {
  MultibodyProblem problem(model, ContactPatternOptions{.policy = s.contact_pattern});
  GeneralizedAlphaOptions o;
  o.step_size = s.step;
  o.rho_infinity = s.rho_infinity;
  o.formulation = s.stabilized_index2 ? GeneralizedAlphaFormulation::stabilized_index2
                                      : GeneralizedAlphaFormulation::index3;
  o.start =
      s.perturbed_start ? GeneralizedAlphaStart::perturbed : GeneralizedAlphaStart::consistent;
  o.rtol = s.rtol;
  o.atol_position = s.ga_atol_position;
  o.atol_velocity = s.ga_atol_velocity;
  o.atol_multiplier = s.ga_atol_multiplier;
  o.stepping = s.ga_error_controlled ? GeneralizedAlphaStepping::error_controlled
                                     : GeneralizedAlphaStepping::fixed;
  o.controller = s.ga_controller;
  o.step_change = s.ga_step_change;
  o.refresh_on_active_set_change = s.ga_refresh_on_contact_change;
  o.max_damping_halvings = s.ga_max_damping_halvings;
  o.filter_error_estimate = s.ga_filter_error_estimate;
  GeneralizedAlphaStepper ga(problem, o);
  SystemState state = SystemState::initial(model);
  state.rod_history = &problem.workspace().rods;
  auto snapshot = [&] {
    state.t = ga.time();
    state.q = ga.positions();
    state.v = ga.velocities();
    state.a = ga.accelerations();
    state.lambda = ga.multipliers();
    if (hooks.output) hooks.output(state);
  };
  auto counters = [&] {
    const GeneralizedAlphaStatistics& st = ga.statistics();
    c = {{"steps", st.steps},
         {"Newton iterations", st.newton_iterations},
         {"residual evaluations", st.residual_evaluations},
         {"matrix evaluations", st.matrix_evaluations},
         {"factorizations", st.factorizations},
         {"full factorizations", st.full_factorizations},
         {"refactorizations", st.factorizations - st.full_factorizations},
         {"symbolic analyses", st.symbolic_analyses},
         {"pattern changes", st.pattern_changes},
         {"pattern non-zeros (largest)", problem.contact_pattern().statistics().most_nonzeros},
         {"contact samples evaluated", problem.workspace().narrow_phase_samples},
         {"convergence failures", st.convergence_failures},
         {"step halvings", st.step_halvings},
         {"restarts", st.restarts}};
    if (o.stepping == GeneralizedAlphaStepping::error_controlled)
      c.insert(c.end(), {{"rejected steps", st.rejected_steps},
                         {"error test failures", st.error_test_failures},
                         {"step size changes", st.step_size_changes},
                         {"min step [ns]", std::lround(1e9 * st.min_step)},
                         {"max step [ns]", std::lround(1e9 * st.max_step)}});
    if (o.max_damping_halvings > 0) c.push_back({"damped iterations", st.damped_iterations});
    if (o.refresh_on_active_set_change)
      c.push_back({"active-set refreshes", st.active_set_refreshes});
    const Workspace& ws = problem.workspace();
    const double kernels = ws.element_seconds, contact = ws.contact_seconds;
    timings = {{"wall", st.wall_seconds},
               {"element kernels", kernels},
               {"contact", contact},
               {"assembly (rest of residual and matrix)",
                problem.residual_seconds() + problem.matrix_seconds() - kernels - contact},
               {"factorization", st.factor_seconds},
               {"solves", st.solve_seconds},
               {"stepper (predictor, updates, tests)",
                st.wall_seconds - problem.residual_seconds() - problem.matrix_seconds() -
                    st.factor_seconds - st.solve_seconds}};
  };
  ga.initialize(0.0);
  snapshot();
  try {
    // Step by step (not advance_to) so that progress is reported within an output interval.
    for (const double t_out : times) {
      while (ga.time() < t_out) {
        ga.step(t_out);
        if (hooks.progress) hooks.progress(ga.time());
      }
      snapshot();
    }
  } catch (...) {
    counters();
    throw;
  }
  counters();
}

}  // namespace

std::vector<double> output_times(double interval, double t_end) {
  std::vector<double> t;
  for (long k = 1; static_cast<double>(k) * interval < t_end * (1.0 - 1e-12); ++k)
    t.push_back(static_cast<double>(k) * interval);
  t.push_back(t_end);
  return t;
}

void simulate(const Model& model, const IntegratorSettings& settings,
              const std::vector<double>& times, const SimulationHooks& hooks,
              SimulationCounters& counters, SimulationTimings& timings) {
  if (settings.kind == IntegratorKind::ida)
    run_ida(model, settings, times, hooks, counters, timings);
  else
    run_genalpha(model, settings, times, hooks, counters, timings);
}

void simulate(const Model& model, const IntegratorSettings& settings,
              const std::vector<double>& times, const SimulationHooks& hooks,
              SimulationCounters& counters) {
  SimulationTimings timings;
  simulate(model, settings, times, hooks, counters, timings);
}

}  // namespace ancf
