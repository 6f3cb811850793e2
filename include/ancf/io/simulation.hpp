// One driver for both integrators on a Model: IDA on the GGL index-2 DAE (GglProblem) or
// generalized-α on the index-3 / stabilized index-2 form (MultibodyProblem), reporting the full
// state at given output times. Used by `ancf run` and by the study executables, so that every
// run of a scene goes through the same code.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ancf/io/scene.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/ggl_problem.hpp"

namespace ancf {

/// Deterministic counters of a run (name, value), in the integrator's own terms.
using SimulationCounters = std::vector<std::pair<std::string, long>>;
/// Where the wall time of a run went (name, seconds): element kernels, contact, the rest of the
/// assembly, factorization, solves, the integrator's own work. Timings are not deterministic.
using SimulationTimings = std::vector<std::pair<std::string, double>>;

struct SimulationHooks {
  /// Called at t = 0 (consistent initial values) and at every output time with t, q, v, a = q''
  /// and λ. The state is only valid during the call.
  std::function<void(const SystemState&)> output;
  /// Called after every accepted step of generalized-α / every output of IDA with the time.
  std::function<void(double)> progress;
};

/// The scales of IDA's absolute tolerances that `s` selects ([integrator.ida] slope_scale and
/// twist_scale; the rest derived from the model).
[[nodiscard]] GglScales ida_scales(const IntegratorSettings& s);

/// Output times interval, 2·interval, … below t_end, and t_end itself. Preconditions: > 0.
[[nodiscard]] std::vector<double> output_times(double interval, double t_end);

/// Where and why a run stopped short: the time of the last accepted state, the step size being
/// tried, the steps taken and the unknown the integrator names as the worst ("-" if none).
struct SimulationFailure {
  double t = 0.0;          ///< [s]
  double step_size = 0.0;  ///< [s]
  long steps = 0;
  std::string component = "-";
};

/// A run in progress: the problem and integrator of settings.kind for `model`, started at t = 0
/// from consistent initial values, advanced through `times` (output times) on demand. simulate()
/// is this class in a loop, so a run driven step by step through the output times is the same
/// computation, bit for bit. Ownership: keeps a reference to `model`, which must outlive it.
class Simulation {
 public:
  /// Throws SolverError if the initial values cannot be made consistent, std::invalid_argument
  /// for inadmissible integrator options. `times` as for simulate().
  Simulation(const Model& model, const IntegratorSettings& settings, std::vector<double> times);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// t, q, v, a = q'', λ at time(); one object, updated in place (references stay valid).
  [[nodiscard]] const SystemState& state() const;
  [[nodiscard]] double time() const { return state().t; }
  [[nodiscard]] const std::vector<double>& times() const { return times_; }
  /// Index into times() of the next output time; times().size() once t_end is reached.
  [[nodiscard]] std::size_t next_output() const { return next_; }
  [[nodiscard]] bool finished() const { return next_ >= times_.size(); }
  [[nodiscard]] IntegratorKind kind() const { return kind_; }

  /// Integrate to the next output time, calling `progress` after every generalized-α step or
  /// at the output (IDA). Returns false, doing nothing, when finished(). On a solver failure the
  /// state is the last one reached and the exception propagates (see failure()).
  bool advance_to_next_output(const std::function<void(double)>& progress = {});
  /// Integrate to `t` (time() < t ≤ t_end): through the output times ≤ t, calling hooks.output
  /// at each, then on to t itself if it is not one. Landing on t shortens the last
  /// generalized-α step (its later steps then differ from a run that did not stop at t); IDA
  /// interpolates, which leaves its steps unchanged.
  void advance_to(double t, const SimulationHooks& hooks = {});
  /// One step that ends at the next output time at the latest: one accepted generalized-α step
  /// (shortened to land on it); one internal IDA step, interpolated back to the output time if
  /// it went beyond (IDA's own steps are unchanged; the call after such an output returns the
  /// end of the IDA step that passed it, without a new step). Returns true when the step reached
  /// the next output time (then passed: next_output() moves on), false otherwise and when
  /// finished(). Stepping through a run gives the same output states as advance_to_next_output, bit
  /// for bit.
  bool step();
  /// Restart from q, v (model.coordinate_count() each) at time(): generalized-α projects them
  /// onto Φ = 0, Φ_q v + Φ_t = 0 and solves for q'' and λ; IDA makes the GGL values consistent
  /// (λ, μ and the derivatives from the DAE). Throws std::invalid_argument for wrong sizes.
  void set_state(const VecX& q, const VecX& v);

  /// Counters and time shares so far (simulate()'s, in the same order).
  [[nodiscard]] SimulationCounters counters() const;
  [[nodiscard]] SimulationTimings timings() const;
  /// The failure of the last call that threw a solver error (t, step size, steps, component).
  [[nodiscard]] const SimulationFailure& failure() const { return failure_; }

  struct Backend;  // one per integrator (simulation.cpp)

 private:
  template <class F>
  void guarded(F&& f);  // runs f, filling failure_ from a SolverError before rethrowing
  IntegratorKind kind_;
  std::vector<double> times_;
  std::size_t next_ = 0;
  std::unique_ptr<Backend> backend_;
  SimulationFailure failure_;
};

/// Integrate `model` from t = 0 to settings.t_end. `counters` is filled also when a solver
/// failure is thrown (the integrator's own exception, which names the time, the step size and the
/// worst component), so that a caller can report how far it got. `times` must be increasing and
/// end at settings.t_end.
void simulate(const Model& model, const IntegratorSettings& settings,
              const std::vector<double>& times, const SimulationHooks& hooks,
              SimulationCounters& counters);
/// The same, also filling `timings` (also when a solver failure is thrown).
void simulate(const Model& model, const IntegratorSettings& settings,
              const std::vector<double>& times, const SimulationHooks& hooks,
              SimulationCounters& counters, SimulationTimings& timings);

}  // namespace ancf
