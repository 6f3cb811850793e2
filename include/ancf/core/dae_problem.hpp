// The abstract implicit DAE the time integrators see: no elements, only vectors and a fixed
// sparse pattern (DESIGN §7: solvers never see physics). Counterpart of StaticProblem.
#pragma once

#include <span>
#include <string>

#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/core/types.hpp"

namespace ancf {

/// Role of an unknown, for the integrator's error control: differential variables are in the
/// local error test, algebraic ones (multipliers) are not (IDASetSuppressAlg) but still enter the
/// Newton convergence test. Each class gets its own absolute tolerance (IdaOptions).
enum class VariableClass { position, velocity, algebraic };

/// Find y(t) with F(t, y, y') = 0 from consistent initial values. Implementations own their data;
/// every function may be called many times per step and must not allocate on the heap in
/// residual() and jacobian().
class DaeProblem {
 public:
  virtual ~DaeProblem() = default;

  /// Number of unknowns N (= number of residual rows).
  [[nodiscard]] virtual Index size() const = 0;
  /// Frozen pattern of J = ∂F/∂y + c_j ∂F/∂y'. It changes only in update_jacobian_pattern();
  /// the reference stays valid (the object is updated in place).
  [[nodiscard]] virtual const SparsityPattern& jacobian_pattern() const = 0;

  /// Bring jacobian_pattern() up to date for a Jacobian at (t, y) that is to serve for about
  /// `horizon` seconds (a contact pattern follows the pairs that are near, DESIGN §5). Returns
  /// true if the pattern changed: the integrator then re-sizes its matrix and re-runs the
  /// symbolic analysis. Called before every Jacobian evaluation; allocates only when the pattern
  /// changes. Default: the pattern never changes.
  virtual bool update_jacobian_pattern(double /*t*/, std::span<const double> /*y*/,
                                       double /*horizon*/) {
    return false;
  }

  /// F(t, y, y') into `r` (all spans of size()). May throw: std::domain_error or SolverError mean
  /// "not evaluable here" (the integrator retries with a smaller step), anything else is fatal.
  virtual void residual(double t, std::span<const double> y, std::span<const double> yp,
                        std::span<double> r) = 0;
  /// Values of J = ∂F/∂y + c_j ∂F/∂y' (one per pattern non-zero, CSC order) into `values`.
  virtual void jacobian(double t, std::span<const double> y, std::span<const double> yp, double c_j,
                        std::span<double> values) = 0;

  /// Class of unknown i (position and velocity classes are differential).
  [[nodiscard]] virtual VariableClass variable_class(Index i) const = 0;
  /// Physical size of unknown i (> 0, in its own unit): the absolute tolerance of i is
  /// atol_class × variable_scale(i), so one dimensionless atol serves metres, slopes and newtons.
  [[nodiscard]] virtual double variable_scale(Index i) const = 0;

  /// Characteristic time of the dynamics [s] (0: unknown). Used for the first step size: IDA's
  /// own estimate 0.5/‖y'‖ is first-order and, at tight tolerances, so small that the iteration
  /// matrix of an index-2 system (condition ~ c_j²) becomes singular in floating point.
  [[nodiscard]] virtual double time_scale() const { return 0.0; }

  /// The state the problem starts from (e.g. the model's initial q, v), not necessarily consistent.
  virtual void initial_state(std::span<double> y) const = 0;
  /// Make (y, y') consistent at time t: on entry y holds an estimate (initial_state, or the state
  /// after a discrete event); on exit F(t, y, y') = 0. Throws SolverError if that fails.
  virtual void consistent_values(double t, std::span<double> y, std::span<double> yp) = 0;

  /// Consistent values at t0 from the initial state: initial_state(), then consistent_values().
  void initial_values(double t0, std::span<double> y, std::span<double> yp) {
    initial_state(y);
    consistent_values(t0, y, yp);
  }

  /// True if the problem keeps history that must be committed on accepted steps: the integrator
  /// then returns after every internal step (not only at output times) to call commit_step().
  [[nodiscard]] virtual bool keeps_history() const { return false; }
  /// Called with the state of each accepted internal step (and of event points); rejected steps
  /// and Newton iterates are never passed (BDF history stays consistent). Default: nothing.
  virtual void commit_step(double /*t*/, std::span<const double> /*y*/) {}

  /// Name of unknown i and of residual row i (rows and unknowns pair up one to one), e.g.
  /// "v of cable 'rope' node 3 r.z" — used to report where an integration failed.
  [[nodiscard]] virtual std::string describe_row(Index i) const = 0;

  /// Event functions g(t, y, y') (roots located by the integrator); none by default.
  [[nodiscard]] virtual int root_count() const { return 0; }
  virtual void roots(double /*t*/, std::span<const double> /*y*/, std::span<const double> /*yp*/,
                     std::span<double> /*g*/) {}
};

}  // namespace ancf
