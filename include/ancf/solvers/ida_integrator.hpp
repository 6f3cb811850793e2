// SUNDIALS IDA (variable-order BDF) on an abstract DaeProblem, with the problem's analytic sparse
// Jacobian factorized by KLU (DESIGN §6). The adapter knows vectors, a fixed pattern and variable
// classes only; the physics (and the GGL index-2 form) live in the problem.
//
//  * λ-type (algebraic) unknowns are marked with IDASetId and left out of the local error test
//    (IDASetSuppressAlg): index-2 multipliers are only first-order accurate in BDF, and testing
//    them makes IDA crawl.
//  * Consistent initial values come from the problem (DaeProblem::consistent_values), not from
//    IDACalcIC, which returns success with a wrong λ₀ when v₀ ≠ 0.
//  * The linear solver is the project's KluSolver behind a SUNLinearSolver (IdaLinearSolver::
//    ancf_klu, klu_linear_solver.hpp): refactorization in the first pivot order guarded by KLU's
//    pivot growth. SUNDIALS' own SUNLinSol_KLU (IdaLinearSolver::sundials_klu, kept to measure
//    against) also refactorizes, but then re-factorizes from scratch whenever its condition
//    estimate exceeds 1/ε^(2/3), which the GGL Jacobian of a stiff scene always does.
//    The symbolic analysis runs once, and again when the problem's pattern changes
//    (DaeProblem::update_jacobian_pattern, asked before every Jacobian evaluation). SUNDIALS 6.4
//    zeroes the sparse matrix, index arrays included, before every Jacobian call, so the pattern
//    is copied in each call. When c_j has changed by more than klu_repivot_ratio since the last
//    pivoting (the step size changed by orders of magnitude, so the balance of c_j M against K
//    did too), KLU pivots afresh.
//  * C callbacks never let an exception cross into C: std::domain_error, SolverError and
//    non-finite residuals are recoverable (+1: IDA retries with a smaller step), anything else is
//    fatal (−1) and is rethrown after IDA returns.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "ancf/core/dae_problem.hpp"
#include "ancf/core/error.hpp"
#include "ancf/core/klu_solver.hpp"

namespace ancf {

/// Largest relative tolerance IdaIntegrator accepts (see IdaOptions::rtol).
inline constexpr double kIdaMaxRtol = 1e-2;

/// Who factorizes IDA's Jacobian (see the file comment).
enum class IdaLinearSolver { ancf_klu, sundials_klu };

struct IdaOptions {
  /// Relative tolerance, in (0, kIdaMaxRtol]. Looser values are refused: the SUNDIALS IDA guide
  /// does not recommend rtol > 1e-3, and above 1e-2 the local error test accepts steps whose error
  /// is of the size of the solution itself — on the benchmark cable pendulum rtol 3e-2 and 0.3
  /// gained 8.6 and 12.8 times the swing's potential energy within 2 s, without any failure
  /// (ancf-study-stability, studies/README.md).
  double rtol = 1e-6;
  /// Absolute tolerance per variable class in units of DaeProblem::variable_scale(i):
  /// atol_i = atol_class × variable_scale(i). Negative: equal to rtol (error relative to the
  /// larger of |y_i| and the physical size of y_i).
  double atol_position = -1.0, atol_velocity = -1.0, atol_multiplier = -1.0;
  double max_step = 0.0;      ///< [s]; 0: unlimited
  double min_step = 0.0;      ///< [s]; IDA fails rather than step below it (0: no limit)
  int max_order = 5;          ///< BDF order limit, 1 … 5
  double initial_step = 0.0;  ///< [s]; 0: IDA's estimate
  double start_time = 0.0;    ///< t₀ [s]
  /// Output times for run() (increasing, > start_time); the observer is called at each.
  std::vector<double> output_times;
  /// IDA never steps past this time (IDASetStopTime); +∞: no stop time.
  double stop_time = std::numeric_limits<double>::infinity();
  long max_steps = 1'000'000;  ///< steps per call of advance() (IDASetMaxNumSteps)
  int max_nonlinear_iterations = 4, max_convergence_failures = 10, max_error_test_failures = 10;
  double klu_repivot_ratio = 1e3;  ///< see the file comment; ≤ 1 disables re-pivoting
  IdaLinearSolver linear_solver = IdaLinearSolver::ancf_klu;
  /// ancf_klu only: how the KluSolver solves and refactorizes (KluSolve, KluRefactor).
  KluSolve klu_solve = KluSolve::reciprocal;
  KluRefactor klu_refactor = KluRefactor::runs;
  /// IDA's vector work compiled with the project, same arithmetic: its serial N_Vector
  /// operations (Debian's SUNDIALS 6.4.1 is built at -O0; src/solvers/ida_vector_ops.hpp),
  /// single-pass fused operations, and the error weights 1/(rtol |y_i| + atol_i) in one loop
  /// (IDAWFtolerances instead of IDASVtolerances' four vector passes). Results are bit-identical.
  /// false: SUNDIALS' own operations (3e3daf4 … issue 20, third pass).
  bool compiled_vector_ops = true;
  /// Per event function: +1 report only increasing, −1 only decreasing zero crossings, 0 both.
  /// Empty: both for all. (After a bounce the state sits just past the root; a direction keeps
  /// the reversed motion from re-triggering the event at once.)
  std::vector<int> root_directions;
};

/// Counters of one integrator (cumulative since construction) and wall time spent in advance().
struct IdaStatistics {
  long steps = 0, residual_evaluations = 0, jacobian_evaluations = 0, linear_solver_setups = 0;
  long nonlinear_iterations = 0, error_test_failures = 0, convergence_failures = 0;
  long root_evaluations = 0, klu_repivots = 0, reinitializations = 0;
  long pattern_changes = 0;  ///< Jacobian pattern changes (contact pairs near, DESIGN §5)
  /// ancf_klu only (0 with sundials_klu): numeric factorizations with fresh pivoting, and in the
  /// first pivot order; wall time in KLU analysis + factorization and in solves [s].
  long full_factorizations = 0, refactorizations = 0;
  double factor_seconds = 0.0, solve_seconds = 0.0;
  long symbolic_analyses = 0;  ///< KLU symbolic analyses (first setup, re-pivotings, changes)
  int last_order = 0;
  double last_step = 0.0;  ///< [s]
  double wall_time = 0.0;  ///< [s]
  /// Wall time inside the residual and Jacobian callbacks [s]; the rest of wall_time is IDA's
  /// own work (BDF, Newton, KLU factorization and solves).
  double residual_seconds = 0.0, jacobian_seconds = 0.0;
  /// Two-column text table, one counter per line.
  [[nodiscard]] std::string table() const;
};

/// Where and why an integration failed; `component` is an unknown of the problem (also a residual
/// row), named by DaeProblem::describe_row.
struct IdaFailureReport {
  int flag = 0;                  ///< IDA return flag
  std::string flag_name;         ///< e.g. "IDA_CONV_FAIL"
  std::string ida_message;       ///< IDA's own message
  std::string callback_message;  ///< last recoverable error raised in a callback, if any
  double t = 0.0;                ///< time reached [s]
  double step = 0.0;             ///< step size being tried [s]
  Index component = -1;          ///< worst component, or −1
  std::string component_name;
  std::string
      measure;  ///< what made it worst: "local error", "Newton correction", "singular column"
  double value = 0.0;  ///< that measure (weighted by the error weights where applicable)
};

class IdaFailure : public SolverError {
 public:
  explicit IdaFailure(IdaFailureReport report);
  [[nodiscard]] const IdaFailureReport& report() const { return report_; }

 private:
  IdaFailureReport report_;
};

/// Outcome of advance(): the target was reached, a root of the event functions was found, or the
/// stop time was reached.
enum class IdaStop { reached, root, stop_time };

/// What run() does after an event: go on, return, or make the (changed) state consistent and
/// restart the integrator from it (a discrete event: impact, switching, ...).
enum class EventAction { resume, stop, reinitialize };

class IdaIntegrator {
 public:
  using Observer =
      std::function<void(double t, std::span<const double> y, std::span<const double> yp)>;
  /// Called at a root with the roots found (±1: direction, 0: none, per event function); may
  /// change y (not yp) before returning EventAction::reinitialize.
  using EventHandler = std::function<EventAction(double t, std::span<const int> roots,
                                                 std::span<double> y, std::span<const double> yp)>;

  /// Computes consistent initial values at options.start_time and sets IDA up.
  /// Ownership: keeps a reference to `problem`, which must outlive the integrator.
  IdaIntegrator(DaeProblem& problem, IdaOptions options);
  ~IdaIntegrator();
  IdaIntegrator(const IdaIntegrator&) = delete;
  IdaIntegrator& operator=(const IdaIntegrator&) = delete;

  /// Integrate to t_out (> time()), or to an earlier root / the stop time. Throws IdaFailure.
  IdaStop advance(double t_out);
  /// One internal step towards t_out (IDA_ONE_STEP): time() is then where the step ended, which
  /// may lie beyond t_out (a later advance(t_out) interpolates back to it), never beyond the stop
  /// time. Throws IdaFailure.
  IdaStop one_step(double t_out);
  /// advance() through options.output_times, calling `observer` at each output time; roots go to
  /// `on_event` (without one, integration resumes). Returns early on EventAction::stop or at the
  /// stop time. On failure the observer has seen every output before it, and IdaFailure is thrown.
  IdaStop run(const Observer& observer, const EventHandler& on_event = {});

  /// Restart from y at time t: make it consistent (DaeProblem::consistent_values) and
  /// re-initialize IDA. With pattern_changed, the problem's (new) Jacobian pattern is read and KLU
  /// is fully re-initialized.
  void reinitialize(double t, std::span<const double> y, bool pattern_changed = false);

  [[nodiscard]] double time() const { return t_; }
  [[nodiscard]] std::span<const double> y() const;
  [[nodiscard]] std::span<const double> yp() const;
  [[nodiscard]] IdaStatistics statistics() const;
  [[nodiscard]] const IdaOptions& options() const { return options_; }
  /// The differential unknown with the largest weighted local error estimate of the last step
  /// (IDAGetEstLocalErrors × error weights, 1 = at the tolerance), and that value; −1 if none.
  /// A diagnostic: which unknowns limit the step size (allocates).
  [[nodiscard]] Index worst_local_error(double& weighted) const;

 private:
  IdaStop solve(double t_out, int task);  // IDASolve with IDA_NORMAL or IDA_ONE_STEP
  struct Impl;
  IdaOptions options_;  // before impl_, which refers to it
  std::unique_ptr<Impl> impl_;
  double t_ = 0.0;
};

}  // namespace ancf
