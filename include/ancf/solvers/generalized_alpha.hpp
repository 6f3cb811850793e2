// Generalized-α time stepper for M q'' + F(q, q', t) − Q + Φ_qᵀλ = 0, Φ(q, t) = 0 (DESIGN §6).
//
// Scheme: Arnold & Brüls (2007), "Convergence of the generalized-α scheme for constrained
// mechanical systems", Multibody Syst. Dyn. 18:185–202, Algorithm 1, with the Chung & Hulbert
// (1993) parameters from the spectral radius at infinity ρ∞ (REFERENCES §8):
//
//   α_m = (2ρ∞ − 1)/(ρ∞ + 1),  α_f = ρ∞/(ρ∞ + 1),  γ = ½ − α_m + α_f,  β = ¼(1 − α_m + α_f)².
//
// Per step, with q'' the true acceleration and a the auxiliary ("pseudo") acceleration,
//
//   (1 − α_m) a_{n+1} + α_m a_n = (1 − α_f) q''_{n+1} + α_f q''_n                         (AB 7)
//   q_{n+1} = q_n + h v_n + h²(½ − β) a_n + h² β a_{n+1}
//   v_{n+1} = v_n + h(1 − γ) a_n + h γ a_{n+1}
//   M q''_{n+1} + F(q_{n+1}, v_{n+1}, t_{n+1}) − Q + Φ_qᵀ λ_{n+1} = 0,   Φ(q_{n+1}, t_{n+1}) = 0,
//
// i.e. the equilibrium is enforced at t_{n+1} and the α-weights enter only through (AB 7). Newton
// runs on Δq with v += γ'Δq, q'' += β'Δq, β' = (1 − α_m)/(βh²(1 − α_f)), γ' = γ/(βh), and the
// iteration matrix S_t = [β'M + γ'C_t + K_t, Φ_qᵀ; Φ_q, 0].
//
// Scaling (Bottasso, Dopico & Trainelli 2008, "On the optimal scaling of index three DAEs in
// multibody dynamics", Multibody Syst. Dyn. 19:3–20): the dynamic rows are multiplied by βh² and
// the multipliers by 1/(βh²), so the matrix actually factorized is
//   [(1 − α_m)/(1 − α_f) M + γh C_t + βh² K_t, Φ_qᵀ; Φ_q, 0],
// whose condition number does not grow as h → 0 (the unscaled one grows like h⁻⁴). Convergence is
// judged on the unscaled increments Δq, Δv = γ'Δq and Δλ.
//
// Formulations:
//  * index3: the scheme above. Unstable for ρ∞ = 1 (the multiplier recursion has a double root
//    at −1); the constructor refuses that combination.
//  * stabilized_index2: the velocity constraint Φ_q v + Φ_t = 0 is enforced by λ and the position
//    constraint by an extra multiplier μ acting on the coordinates only, as in the stabilized
//    index-2 generalized-α scheme of Arnold, Cardona & Brüls (2016), "A Lie algebra approach to Lie
//    group time integration of constrained systems" (in: Structure-preserving Integrators in
//    Nonlinear Structural Dynamics and Flexible Multibody Dynamics, CISM 565, Springer), which
//    discretizes the Gear–Gupta–Leimkuhler (1985) form q' = v + (·)μ. Here the correction
//    direction is mass-weighted, q_{n+1} = (generalized-α update) + M⁻¹Φ_qᵀμ_{n+1}, so it is the
//    M-orthogonal projection onto Φ = 0 and reuses the (n + m) pattern. Stable at ρ∞ = 1.
//    Its Newton iteration is a block Gauss–Seidel one: (Δq, Δλ) from the iteration matrix with
//    the velocity constraint linearized as γ'Φ_q Δq (its (Φ_q v)_q Δq part, O(h) relative, is
//    left out), then μ from [M Φ_qᵀ; Φ_q 0]; it converges linearly to the same solution.
//
// Starting values: q''_0 and λ_0 from the index-1 system [M Φ_qᵀ; Φ_q 0][q''; λ] = [Q − F; γ]
// after projecting q_0, v_0 onto the constraints. With a_0 = q''_0 (start = consistent) λ has an
// O(h) error in the first steps that decays like nρ∞ⁿ; start = perturbed uses starting values
// consistent with the asymptotic expansion of the numerical solution (Arnold, Brüls & Cardona 2015,
// "Error analysis of generalized-α Lie group time integration methods for constrained mechanical
// systems", Numer. Math. 129:149–179): a_0 ≈ q''(t_0 + (α_m − α_f)h) and, for index 3, an O(h²)
// correction of the constraint-normal part of v_0 (derived in generalized_alpha.cpp), which
// removes that transient.
#pragma once

#include <limits>
#include <string>
#include <utility>

#include "ancf/core/error.hpp"
#include "ancf/core/klu_solver.hpp"
#include "ancf/core/second_order_problem.hpp"
#include "ancf/solvers/step_controller.hpp"

namespace ancf {

/// Chung–Hulbert parameters for a given ρ∞ ∈ [0, 1].
struct GeneralizedAlphaParameters {
  double rho_infinity = 0.0, alpha_m = 0.0, alpha_f = 0.0, gamma = 0.0, beta = 0.0;
  /// Throws std::invalid_argument unless 0 ≤ ρ∞ ≤ 1.
  [[nodiscard]] static GeneralizedAlphaParameters chung_hulbert(double rho_infinity);
  /// C of the local position error C h³ q''' + O(h⁴) of one step, C = Δ/2 + β − 1/6 with
  /// Δ = α_m − α_f (docs/time_step_control.md); 1/12 + Δ²/4 for the Chung–Hulbert parameters.
  [[nodiscard]] double local_error_constant() const;
};

enum class GeneralizedAlphaFormulation { index3, stabilized_index2 };
enum class GeneralizedAlphaStart {
  consistent,  ///< a_0 = q''(t_0)
  perturbed,  ///< a_0 ≈ q''(t_0 + (α_m − α_f)h), index 3 also v_0 + O(h²) normal part (ABC 2015)
};
/// Newton's starting point for q'' and λ (q, v follow from the update formulas).
enum class GeneralizedAlphaPredictor {
  constant,      ///< q''_{n+1} = q''_n, λ_{n+1} = λ_n (exact for constant acceleration)
  extrapolated,  ///< linear extrapolation from the last two steps
};
/// Step-size selection.
enum class GeneralizedAlphaStepping {
  fixed,             ///< the nominal h; halved on Newton failure, then doubled back (default)
  error_controlled,  ///< h from the local error estimate C h²(a_{n+1} − a_n) and a StepController
};
/// What a change of h does to the h-dependent parts of the state (see step(),
/// docs/time_step_control.md for the measurements behind the default).
enum class GeneralizedAlphaStepChange {
  automatic,  ///< rescale_climbs for fixed stepping, rescale for error-controlled stepping
  restart,    ///< the starting procedure of initialize() at the accepted (t, q, v)
  rescale,    ///< a ← q'' + (h_new/h_old)(a − q''); λ keeps an O(h) transient per change
  rescale_with_velocity,  ///< rescale, and (index 3) the normal part of v: λ second order on
                          ///< smooth motion, but amplifies noise in a − q'' (stiff contact)
  rescale_climbs,  ///< restart where h falls (a halving), rescale where it grows (a climb back)
};
enum class NewtonStrategy {
  full,      ///< new analytic iteration matrix and factorization at every iteration
  modified,  ///< keep the factorization across iterations and steps while it contracts well
};

struct GeneralizedAlphaOptions {
  double step_size = 1e-3;    ///< nominal h [s]; > 0
  double rho_infinity = 0.8;  ///< spectral radius at infinity, [0, 1]
  GeneralizedAlphaFormulation formulation = GeneralizedAlphaFormulation::index3;
  GeneralizedAlphaStart start = GeneralizedAlphaStart::consistent;
  NewtonStrategy newton = NewtonStrategy::modified;
  GeneralizedAlphaPredictor predictor = GeneralizedAlphaPredictor::constant;
  /// Bottasso–Dopico–Trainelli scaling of the iteration matrix. Switching it off changes only the
  /// conditioning (and so round-off), never the converged solution.
  bool scaling = true;

  /// Newton convergence: the estimated remaining error of the iterate, measured as the largest of
  /// the weighted RMS norms of Δq, Δv = γ'Δq (weights atol + rtol·|x_i|, units of q and v) and
  /// Δλ (weight atol_multiplier + rtol·‖λ‖∞: multipliers pass through zero), must be ≤ 1. The
  /// estimate is η‖Δ_k‖ with η = θ/(1 − θ) and θ the contraction rate observed in the step
  /// (Hairer & Wanner, Solving ODEs II, §IV.8); before θ is known, η = max(1, η of the last step).
  /// Since Δv = γ'Δq ≈ (2/h)Δq, the velocity test usually decides, and the Newton error left in
  /// q is ≈ rtol·|v|·h/2 per step.
  double rtol = 1e-6;
  double atol_position = 1e-8;    ///< [m] (or the unit of q)
  double atol_velocity = 1e-6;    ///< [m/s]
  double atol_multiplier = 1e-6;  ///< [N] (or the unit of λ)
  int max_iterations = 10;        ///< per step attempt

  /// Modified Newton: the factorization is kept for the next step while the contraction rate θ
  /// of this step stays ≤ this value (and at most max_matrix_age steps); a stale matrix whose
  /// iteration diverges (or is predicted not to converge) is rebuilt at the current iterate.
  double max_reuse_rate = 0.1;
  int max_matrix_age = 1000;
  /// Modified Newton: a full step that diverges with a matrix built in the attempt is halved
  /// back along its direction (Deuflhard's natural monotonicity test) up to this many times per
  /// matrix before the attempt fails; 0: off.
  int max_damping_halvings = 0;
  /// How a KLU refactorization with the old pivot order is checked (klu_solver.hpp): the O(n)
  /// diagonal estimate (default) or KLU's pivot growth, a pass over A and U that was ~20 % of
  /// each refactorization on the benchmark pendulum (studies/README.md).
  RefactorCheck refactor_check = RefactorCheck::diagonal;
  /// Solve of the factorized iteration matrix (KluSolve; klu = klu_l_solve as before issue 20c).
  KluSolve klu_solve = KluSolve::reciprocal;
  /// Refactorization of the iteration matrix (KluRefactor; klu = klu_l_refactor as before).
  KluRefactor klu_refactor = KluRefactor::runs;

  /// On Newton failure (with a fresh matrix) the step is halved from the last accepted state, at
  /// most this many times in a row and never below step_size·2^−max_step_halvings (a failure at
  /// that size ends the run); after recovery_steps accepted steps at a reduced size it is
  /// doubled again (towards step_size). A halving restarts the scheme, a climb rescales it
  /// (step_change = automatic; see change_step_size()).
  int max_step_halvings = 12;
  int recovery_steps = 4;
  /// Fixed stepping: when the step right after climbing back to a larger h fails again (within
  /// the wait that preceded the climb), the next wait is doubled, up to max_recovery_steps; a
  /// failure later, or a climb that holds, returns it to recovery_steps. A cascade of
  /// fail–halve–climb–fail (with step_change = restart each climb restarts the scheme and
  /// re-excites the modes that made the step fail: 1 719 failures in 1 s of the 1000-element
  /// benchmark pendulum) then costs a few failures. false: climb after recovery_steps always
  /// (3e3daf4 … issue 20, third session).
  bool recovery_backoff = true;
  int max_recovery_steps = 256;

  GeneralizedAlphaStepping stepping = GeneralizedAlphaStepping::fixed;
  /// Error-controlled stepping: tolerances of the local position error [m] and step limits;
  /// step_size is the first step. A Newton failure shrinks h by controller.failure_shrink.
  StepControllerOptions controller;
  GeneralizedAlphaStepChange step_change = GeneralizedAlphaStepChange::automatic;
  /// Filter the local error estimate through the iteration matrix (ẽ = S⁻¹[w_a M e; 0]), so that
  /// unresolved stiff modes, which the scheme damps, do not drive h down
  /// (docs/time_step_control.md).
  bool filter_error_estimate = true;
  /// Build a fresh iteration matrix when the problem's active_set_signature() changed since the
  /// matrix in use was built (a contact became active or inactive), instead of first letting the
  /// old factorization fail (modified Newton only).
  bool refresh_on_active_set_change = false;
};

/// Counters; deterministic where wall time is not (REFERENCES §9).
struct GeneralizedAlphaStatistics {
  long steps = 0;              ///< accepted steps
  long newton_iterations = 0;  ///< linear solves of the Newton iteration
  long residual_evaluations = 0;
  long matrix_evaluations = 0;    ///< iteration-matrix assemblies
  long factorizations = 0;        ///< numeric factorizations (full + refactor, both matrices)
  long full_factorizations = 0;   ///< of those, with fresh pivoting
  long convergence_failures = 0;  ///< Newton failures (each followed by a retry or a halving)
  long step_halvings = 0;         ///< fixed stepping: halvings after Newton failures
  long rejected_steps = 0;        ///< error-controlled: error-test and Newton failures, retried
  long error_test_failures = 0;   ///< error-controlled: steps whose local error estimate was > 1
  long step_size_changes = 0;     ///< changes of h between attempts (each a rescale or restart)
  long active_set_refreshes = 0;  ///< matrices rebuilt because the active contact set changed
  long damped_iterations = 0;     ///< Newton trial points halved back (max_damping_halvings)
  long restarts = 0;              ///< starting procedures (initialize and every change of h)
  long pattern_changes = 0;       ///< changes of the problem's pattern (contact pairs near)
  long symbolic_analyses = 0;     ///< KLU symbolic analyses after initialize (both matrices)
  double factor_seconds = 0.0;    ///< wall time in KLU analysis + factorization [s]
  double solve_seconds = 0.0;     ///< wall time in KLU solves [s]
  double min_step = 0.0;          ///< smallest step taken [s]
  double max_step = 0.0;          ///< largest step taken [s]
  double wall_seconds = 0.0;      ///< inside initialize/step/advance_to
};

/// Owns the KLU symbolic analysis of problem.iteration_pattern() (in the constructor, and again
/// whenever problem.update_pattern() reports a change: it is asked before every matrix
/// evaluation with the step size as horizon) and the state (t, q, v, q'', a, λ). No heap allocation
/// per step. Ownership: keeps a reference to `problem`, which must outlive the stepper.
/// A step that could not be completed (Newton failure after the allowed halvings, local error
/// above tolerance at h_min): the time of the last accepted state, the step size tried and the
/// unknown with the largest weighted Newton increment ("-" when not known), also in what().
class GeneralizedAlphaFailure : public SolverError {
 public:
  GeneralizedAlphaFailure(const std::string& message, double t, double step, std::string component)
      : SolverError(message), t_(t), step_(step), component_(std::move(component)) {}
  [[nodiscard]] double time() const { return t_; }          ///< [s]
  [[nodiscard]] double step_size() const { return step_; }  ///< [s]
  [[nodiscard]] const std::string& component() const { return component_; }

 private:
  double t_, step_;
  std::string component_;
};

class GeneralizedAlphaStepper {
 public:
  /// Throws std::invalid_argument for bad options, and for index 3 with ρ∞ = 1 (unstable).
  GeneralizedAlphaStepper(SecondOrderProblem& problem, GeneralizedAlphaOptions options);

  /// Start at t0 from the problem's initial q, v (or the given ones): project them onto Φ = 0
  /// and Φ_q v + Φ_t = 0 (mass-weighted), then solve the index-1 system for q'' and λ and set a_0
  /// according to options.start. Throws SolverError if the projection does not converge.
  void initialize(double t0);
  void initialize(double t0, const VecX& q0, const VecX& v0);

  /// One step of the current size, or shorter if `t_limit` is closer (within 1e-8 h of one step,
  /// t_limit is hit with the current h).
  ///  * fixed stepping: the nominal h unless a Newton failure halved it. Throws SolverError after
  ///    max_step_halvings failures in a row, or on a failure at step_size·2^−max_step_halvings.
  ///  * error-controlled: the step is accepted when the weighted RMS norm of the local error
  ///    estimate C h²(a_{n+1} − a_n) (options.controller tolerances) is ≤ 1, and the controller
  ///    proposes the next h; a rejected step or a Newton failure is retried from the accepted state
  ///    with a smaller h. Throws SolverError when that would go below controller.h_min.
  /// A change of h either restarts the scheme from the accepted (t, q, v) (v projected onto the
  /// velocity constraint, q'' and λ from the index-1 system, a and v as options.start says) or
  /// rescales a and, index 3, the constraint-normal part of v to the new h (options.step_change,
  /// docs/time_step_control.md). After a throw the state is the last accepted one.
  void step(double t_limit = std::numeric_limits<double>::infinity());
  /// Steps until t == t_end exactly (the last step is shortened if needed).
  void advance_to(double t_end);

  [[nodiscard]] double time() const { return t_; }
  [[nodiscard]] const VecX& positions() const { return q_; }
  [[nodiscard]] const VecX& velocities() const { return v_; }
  [[nodiscard]] const VecX& accelerations() const { return acc_; }       ///< q''
  [[nodiscard]] const VecX& pseudo_accelerations() const { return a_; }  ///< a of (AB 7)
  [[nodiscard]] const VecX& multipliers() const { return lambda_; }      ///< λ
  [[nodiscard]] double current_step_size() const { return h_; }
  /// Error-controlled stepping: the weighted norm of the local error estimate of the last
  /// accepted step (≤ 1; 0 for fixed stepping).
  [[nodiscard]] double last_error_norm() const { return last_error_; }
  [[nodiscard]] const GeneralizedAlphaParameters& parameters() const { return params_; }
  [[nodiscard]] const GeneralizedAlphaOptions& options() const { return options_; }
  [[nodiscard]] const GeneralizedAlphaStatistics& statistics() const { return stats_; }

  /// Weights of the dynamic block of the matrix factorized for step size h: (1, γ', β') unscaled,
  /// βh²·(1, γ', β') = (βh², γh, (1 − α_m)/(1 − α_f)) scaled.
  [[nodiscard]] MatrixWeights iteration_weights(double h, bool scaled) const;

 private:
  enum class Outcome { converged, diverged_stale, failed };
  Outcome newton(double t1, double h);
  void predict(double h);
  void refresh_matrix(double t1, double h);  // throws SolverError if singular
  void update_pattern(double t, const VecX& q, const VecX& v, double h);
  void factor(KluSolver& klu, long& revision, const VecX& values);
  void update_factorization_counters();
  void refresh_projector(double t, const VecX& q);
  void project_positions(double t, VecX& q, int max_iterations);
  void project_velocities(double t, const VecX& q, VecX& v);
  void restart(double t, double h);
  void perturbed_start(double t0, double h);
  void shift_normal_velocity(double t, double factor);
  void solve_index1(double t, const VecX& q, const VecX& v, VecX& acc, VecX& lambda);
  void update_weights(double gamma_prime);
  [[nodiscard]] double increment_norm(Index* worst = nullptr) const;
  void change_step_size(double h_new);
  void rescale(double h_new);
  [[nodiscard]] double attempt_size(double remaining, bool& last) const;
  [[nodiscard]] double local_error(double h);  // sets a1_ = a_{n+1}; 0 for fixed stepping
  void accept(double t1, double h, bool on_base, bool last);
  [[nodiscard]] bool adaptive() const {
    return options_.stepping == GeneralizedAlphaStepping::error_controlled;
  }

  SecondOrderProblem& problem_;
  GeneralizedAlphaOptions options_;
  GeneralizedAlphaParameters params_;
  Index n_ = 0, m_ = 0;
  KluSolver klu_;        // the Newton matrix
  KluSolver projector_;  // [M Φ_qᵀ; Φ_q 0]: start, projections, stabilized index-2 position solve
  bool initialized_ = false;

  // Accepted state.
  double t_ = 0.0;
  VecX q_, v_, acc_, a_, lambda_;
  // Previous accepted step (for the extrapolating predictor).
  VecX acc_previous_, lambda_previous_;
  double previous_h_ = 0.0;
  bool have_previous_ = false;
  // Step attempt (the iterate of step n → n + 1) and its a_{n+1} from (AB 7).
  VecX q1_, v1_, acc1_, lambda1_, a1_;
  // Inverse error weights of the current step attempt (Δv weights include γ').
  Eigen::ArrayXd weight_q_, weight_v_;
  double weight_lambda_ = 1.0;
  // Scratch.
  VecX residual_, rhs_, values_, projector_values_, velocity_residual_, increment_, phi_;
  VecX last_step_, last_q_step_;  // the Newton increment last applied (rhs_, increment_ form)

  double h_ = 0.0;       // current step size
  double t_base_ = 0.0;  // t_ = t_base_ + steps_from_base_ · base_h_ (see step())
  double base_h_ = -1.0;
  long steps_from_base_ = 0;
  double a_h_ = 0.0;          // step size a_ is calibrated to (a ≈ q''(t + (α_m − α_f)h))
  double matrix_h_ = -1.0;    // h the factorized matrix was built for (−1: none)
  int matrix_age_ = 0;        // accepted steps since the matrix was built
  bool matrix_stale_ = true;  // refresh before the next iteration
  double eta_ = 1.0;          // θ/(1 − θ) estimate carried across steps
  int steps_since_halving_ = 0;
  int recovery_wait_ = 4;       // accepted steps at a reduced h before climbing (fixed stepping)
  int steps_since_climb_ = -1;  // accepted steps since the last climb, −1: none since a halving
  int halvings_in_a_row_ = 0;
  double step_max_rate_ = 0.0;          // largest contraction rate θ seen in the current step
  StepController controller_;           // error-controlled stepping
  double last_error_ = 0.0;             // estimate of the last accepted step
  VecX mass_values_;                    // [M Φ_qᵀ; Φ_q 0] values for M·e (filtered estimate)
  long mass_revision_ = -1;             // pattern revision mass_values_ was assembled in
  std::uint64_t matrix_signature_ = 0;  // active_set_signature() when the matrix was built
  long klu_base_[5] = {0, 0, 0, 0, 0};  // KLU counters at initialize()
  double klu_seconds_base_[2] = {0.0, 0.0};  // KLU factor and solve seconds at initialize()
  long pattern_revision_ = 0;                // changes of problem.iteration_pattern() seen so far
  long klu_revision_ = 0, projector_revision_ = 0;  // revision each solver was analysed for
  GeneralizedAlphaStatistics stats_;
  // What the problem said of the last iterate it could not evaluate in the current step
  // (std::domain_error, SecondOrderProblem's contract), for the failure report.
  std::string unevaluable_;
};

}  // namespace ancf
