// The integrator driver shared by `ancf run`, the studies and the Python module (simulation.hpp):
// one backend per integrator behind Simulation, and simulate() as Simulation in a loop.
#include "ancf/io/simulation.hpp"

#include <cmath>
#include <stdexcept>

#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ancf/system/multibody_problem.hpp"

namespace ancf {

struct Simulation::Backend {
  virtual ~Backend() = default;
  virtual const SystemState& state() const = 0;
  /// Integrate to t_out; progress after every step where the integrator reports steps.
  /// step(t_limit): one step, ending at t_limit at the latest (Simulation::step).
  virtual void advance(double t_out, const std::function<void(double)>& progress) = 0;
  virtual void step(double t_limit) = 0;
  virtual void set_state(const VecX& q, const VecX& v) = 0;
  virtual void statistics(SimulationCounters& c, SimulationTimings& timings) const = 0;
  /// Fills time, step size, steps, component of the failure `e` (thrown by this backend).
  virtual void describe(const SolverError& e, SimulationFailure& f) const = 0;
};

namespace {

/// Rod scenes: how often the node frames were updated (docs/rod.md, "Frame updates"; each update
/// re-bases the twist's spin for the constant twist inertia, so the count belongs to the run's
/// record as the step counts do).
void add_rod_counters(const Model& model, const Workspace& ws, SimulationCounters& c) {
  if (model.has_rods()) c.push_back({"rod frame updates", ws.rods.frame_updates});
}

class IdaBackend final : public Simulation::Backend {
 public:
  IdaBackend(const Model& model, const IntegratorSettings& s, const std::vector<double>& times)
      : problem_(model, ida_scales(s), ContactPatternOptions{.policy = s.contact_pattern}),
        // The cable tangent is chosen before IDA computes consistent initial values with it.
        ida_((problem_.set_cable_tangent(s.cable_tangent),
              problem_.set_rod_frame_turn(s.rod_frame_turn), problem_),
             options(s, times)),
        state_(SystemState::initial(model)) {
    state_.rod_history = &problem_.workspace().rods;
    problem_.unpack(0.0, ida_.y(), ida_.yp(), state_);  // consistent initial values
  }

  const SystemState& state() const override { return state_; }

  void advance(double t_out, const std::function<void(double)>& progress) override {
    if (t_out > ida_.time()) ida_.advance(t_out);
    problem_.unpack(ida_.time(), ida_.y(), ida_.yp(), state_);
    if (progress) progress(ida_.time());
  }

  void step(double t_limit) override {
    ida_.one_step(t_limit);
    if (ida_.time() > t_limit) ida_.advance(t_limit);  // interpolation within the last step
    problem_.unpack(ida_.time(), ida_.y(), ida_.yp(), state_);
  }

  void set_state(const VecX& q, const VecX& v) override {
    VecX y = VecX::Zero(problem_.size());
    y.head(q.size()) = q;
    y.segment(problem_.velocity_offset(), v.size()) = v;
    ida_.reinitialize(ida_.time(), std::span<const double>(y.data(), y.size()));
    problem_.unpack(ida_.time(), ida_.y(), ida_.yp(), state_);
  }

  void statistics(SimulationCounters& c, SimulationTimings& timings) const override {
    const IdaStatistics st = ida_.statistics();
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
         {"pattern non-zeros (largest)", problem_.contact_pattern().statistics().most_nonzeros},
         {"contact samples evaluated", problem_.workspace().narrow_phase_samples}};
    add_rod_counters(problem_.model(), problem_.workspace(), c);
    const Workspace& ws = problem_.workspace();
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
  }

  void describe(const SolverError& e, SimulationFailure& f) const override {
    f.steps = ida_.statistics().steps;
    f.t = ida_.time();
    if (const auto* failure = dynamic_cast<const IdaFailure*>(&e)) {
      const IdaFailureReport& r = failure->report();
      f.t = r.t;
      f.step_size = r.step;
      f.component = r.component_name.empty() ? "-" : r.component_name;
    }
  }

 private:
  static IdaOptions options(const IntegratorSettings& s, const std::vector<double>& times) {
    IdaOptions o;
    o.rtol = s.rtol;
    o.atol_position = s.ida_atol_position;
    o.atol_velocity = s.ida_atol_velocity;
    o.atol_multiplier = s.ida_atol_multiplier;
    o.max_step = s.max_step;
    o.max_order = s.max_order;
    o.compiled_vector_ops = !s.ida_sundials_vector_ops;
    o.linear_solver =
        s.ida_sundials_klu ? IdaLinearSolver::sundials_klu : IdaLinearSolver::ancf_klu;
    o.output_times = times;
    o.stop_time = s.t_end;
    return o;
  }

  GglProblem problem_;
  IdaIntegrator ida_;
  SystemState state_;
};

class GeneralizedAlphaBackend final : public Simulation::Backend {
 public:
  GeneralizedAlphaBackend(const Model& model, const IntegratorSettings& s)
      : problem_(model, ContactPatternOptions{.policy = s.contact_pattern}),
        ga_((problem_.set_cable_tangent(s.cable_tangent),
             problem_.set_rod_frame_turn(s.rod_frame_turn), problem_),
            options(s)),
        state_(SystemState::initial(model)) {
    state_.rod_history = &problem_.workspace().rods;
    ga_.initialize(0.0);
    snapshot();
  }

  const SystemState& state() const override { return state_; }

  void advance(double t_out, const std::function<void(double)>& progress) override {
    // Step by step (not advance_to) so that progress is reported within an output interval.
    while (ga_.time() < t_out) {
      ga_.step(t_out);
      if (progress) progress(ga_.time());
    }
    snapshot();
  }

  void step(double t_limit) override {
    ga_.step(t_limit);
    snapshot();
  }

  void set_state(const VecX& q, const VecX& v) override {
    ga_.initialize(ga_.time(), q, v);
    snapshot();
  }

  void statistics(SimulationCounters& c, SimulationTimings& timings) const override {
    const GeneralizedAlphaStatistics& st = ga_.statistics();
    const GeneralizedAlphaOptions& o = ga_.options();
    c = {{"steps", st.steps},
         {"Newton iterations", st.newton_iterations},
         {"residual evaluations", st.residual_evaluations},
         {"matrix evaluations", st.matrix_evaluations},
         {"factorizations", st.factorizations},
         {"full factorizations", st.full_factorizations},
         {"refactorizations", st.factorizations - st.full_factorizations},
         {"symbolic analyses", st.symbolic_analyses},
         {"pattern changes", st.pattern_changes},
         {"pattern non-zeros (largest)", problem_.contact_pattern().statistics().most_nonzeros},
         {"contact samples evaluated", problem_.workspace().narrow_phase_samples},
         {"convergence failures", st.convergence_failures},
         {"step halvings", st.step_halvings},
         {"restarts", st.restarts}};
    if (o.stepping == GeneralizedAlphaStepping::error_controlled)
      c.insert(c.end(), {{"rejected steps", st.rejected_steps},
                         {"error test failures", st.error_test_failures},
                         {"step size changes", st.step_size_changes}});
    // Fixed stepping too: how deep the halvings went.
    c.insert(c.end(), {{"min step [ns]", std::lround(1e9 * st.min_step)},
                       {"max step [ns]", std::lround(1e9 * st.max_step)}});
    if (o.max_damping_halvings > 0) c.push_back({"damped iterations", st.damped_iterations});
    if (o.refresh_on_active_set_change)
      c.push_back({"active-set refreshes", st.active_set_refreshes});
    add_rod_counters(problem_.model(), problem_.workspace(), c);
    const Workspace& ws = problem_.workspace();
    const double kernels = ws.element_seconds, contact = ws.contact_seconds;
    timings = {{"wall", st.wall_seconds},
               {"element kernels", kernels},
               {"contact", contact},
               {"assembly (rest of residual and matrix)",
                problem_.residual_seconds() + problem_.matrix_seconds() - kernels - contact},
               {"factorization", st.factor_seconds},
               {"solves", st.solve_seconds},
               {"stepper (predictor, updates, tests)",
                st.wall_seconds - problem_.residual_seconds() - problem_.matrix_seconds() -
                    st.factor_seconds - st.solve_seconds}};
  }

  void describe(const SolverError& e, SimulationFailure& f) const override {
    f.steps = ga_.statistics().steps;
    f.t = ga_.time();
    f.step_size = ga_.current_step_size();
    if (const auto* failure = dynamic_cast<const GeneralizedAlphaFailure*>(&e)) {
      f.t = failure->time();
      f.step_size = failure->step_size();
      f.component = failure->component();
    }
  }

 private:
  static GeneralizedAlphaOptions options(const IntegratorSettings& s) {
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
    if (s.ga_klu_refactor) o.klu_refactor = KluRefactor::klu;
    o.recovery_backoff = s.ga_recovery_backoff;
    o.filter_error_estimate = s.ga_filter_error_estimate;
    o.max_reuse_rate = s.ga_max_reuse_rate;
    return o;
  }
  void snapshot() {
    state_.t = ga_.time();
    state_.q = ga_.positions();
    state_.v = ga_.velocities();
    state_.a = ga_.accelerations();
    state_.lambda = ga_.multipliers();
  }

  MultibodyProblem problem_;
  GeneralizedAlphaStepper ga_;
  SystemState state_;
};

}  // namespace

Simulation::Simulation(const Model& model, const IntegratorSettings& settings,
                       std::vector<double> times)
    : kind_(settings.kind), times_(std::move(times)) {
  if (kind_ == IntegratorKind::ida)
    backend_ = std::make_unique<IdaBackend>(model, settings, times_);
  else
    backend_ = std::make_unique<GeneralizedAlphaBackend>(model, settings);
}

Simulation::~Simulation() = default;

const SystemState& Simulation::state() const {
  return backend_->state();
}

template <class F>
void Simulation::guarded(F&& f) {
  try {
    f();
  } catch (const SolverError& e) {
    failure_ = {};
    backend_->describe(e, failure_);
    throw;
  }
}

bool Simulation::advance_to_next_output(const std::function<void(double)>& progress) {
  if (finished()) return false;
  guarded([&] { backend_->advance(times_[next_], progress); });
  ++next_;
  return true;
}

void Simulation::advance_to(double t, const SimulationHooks& hooks) {
  while (!finished() && times_[next_] <= t) {
    advance_to_next_output(hooks.progress);
    if (hooks.output) hooks.output(state());
  }
  if (!finished() && time() < t) guarded([&] { backend_->advance(t, hooks.progress); });
}

bool Simulation::step() {
  if (finished()) return false;
  guarded([&] { backend_->step(times_[next_]); });
  if (time() < times_[next_]) return false;
  ++next_;
  return true;
}

void Simulation::set_state(const VecX& q, const VecX& v) {
  const Index n = state().q.size();
  if (q.size() != n || v.size() != n)
    throw std::invalid_argument("Simulation::set_state: q and v need " + std::to_string(n) +
                                " entries each");
  guarded([&] { backend_->set_state(q, v); });
}

SimulationCounters Simulation::counters() const {
  SimulationCounters c;
  SimulationTimings t;
  backend_->statistics(c, t);
  return c;
}

SimulationTimings Simulation::timings() const {
  SimulationCounters c;
  SimulationTimings t;
  backend_->statistics(c, t);
  return t;
}

GglScales ida_scales(const IntegratorSettings& s) {
  GglScales scales;
  if (s.ida_slope_position_scale) scales.slope = SlopeScale::position_equivalent;
  if (s.ida_twist_position_scale) scales.twist = TwistScale::position_equivalent;
  return scales;
}

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
  Simulation run(model, settings, times);
  if (hooks.output) hooks.output(run.state());
  try {
    while (run.advance_to_next_output(hooks.progress))
      if (hooks.output) hooks.output(run.state());
  } catch (...) {
    counters = run.counters();
    timings = run.timings();
    throw;
  }
  counters = run.counters();
  timings = run.timings();
}

void simulate(const Model& model, const IntegratorSettings& settings,
              const std::vector<double>& times, const SimulationHooks& hooks,
              SimulationCounters& counters) {
  SimulationTimings timings;
  simulate(model, settings, times, hooks, counters, timings);
}

}  // namespace ancf
