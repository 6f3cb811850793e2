#include "ancf/solvers/generalized_alpha.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ancf/core/error.hpp"
#include "ancf/core/stopwatch.hpp"

namespace ancf {

GeneralizedAlphaParameters GeneralizedAlphaParameters::chung_hulbert(double rho) {
  if (!(rho >= 0.0 && rho <= 1.0))
    throw std::invalid_argument(fmt::format("generalized-α: ρ∞ must lie in [0, 1], got {}", rho));
  // Chung & Hulbert (1993), eqs. (25), (17), (20): second order, maximal high-frequency
  // dissipation for the given ρ∞ (REFERENCES §8).
  GeneralizedAlphaParameters p;
  p.rho_infinity = rho;
  p.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
  p.alpha_f = rho / (rho + 1.0);
  p.gamma = 0.5 - p.alpha_m + p.alpha_f;
  p.beta = 0.25 * (1.0 - p.alpha_m + p.alpha_f) * (1.0 - p.alpha_m + p.alpha_f);
  return p;
}

double GeneralizedAlphaParameters::local_error_constant() const {
  // docs/time_step_control.md: with exact q_n, v_n and a_n = q''(t_n + Δh) the position update
  // differs from the Taylor series of q by (Δ/2 + β − 1/6) h³ q''' + O(h⁴).
  return 0.5 * (alpha_m - alpha_f) + beta - 1.0 / 6.0;
}

GeneralizedAlphaStepper::GeneralizedAlphaStepper(SecondOrderProblem& problem,
                                                 GeneralizedAlphaOptions options)
    : problem_(problem),
      options_(options),
      params_(GeneralizedAlphaParameters::chung_hulbert(options.rho_infinity)),
      n_(problem.coordinate_count()),
      m_(problem.multiplier_count()),
      klu_(problem.iteration_pattern()),
      projector_(problem.iteration_pattern()),
      controller_(options.controller, 2) {
  klu_.set_refactor_check(options_.refactor_check);
  projector_.set_refactor_check(options_.refactor_check);
  klu_.set_solve(options_.klu_solve);
  projector_.set_solve(options_.klu_solve);
  klu_.set_refactor(options_.klu_refactor);
  projector_.set_refactor(options_.klu_refactor);
  if (!(options_.step_size > 0.0))
    throw std::invalid_argument("generalized-α: the step size must be positive");
  if (options_.formulation == GeneralizedAlphaFormulation::index3 && options_.rho_infinity == 1.0)
    throw std::invalid_argument(
        "generalized-α: index 3 with ρ∞ = 1 is unstable (the multiplier recursion has a double "
        "root at −1, Arnold & Brüls 2007); use ρ∞ < 1 or the stabilized index-2 formulation");
  if (options_.max_iterations < 1 || options_.rtol < 0.0 || options_.atol_position <= 0.0 ||
      options_.atol_velocity <= 0.0 || options_.atol_multiplier <= 0.0)
    throw std::invalid_argument("generalized-α: tolerances must be positive, max_iterations ≥ 1");
  const Index size = problem.system_size();
  for (VecX* v : {&q_, &v_, &acc_, &a_, &q1_, &v1_, &acc1_, &a1_, &acc_previous_, &increment_})
    v->setZero(n_);
  for (VecX* v : {&lambda_, &lambda1_, &lambda_previous_, &velocity_residual_, &phi_})
    v->setZero(m_);
  weight_q_.setZero(n_);
  weight_v_.setZero(n_);
  residual_.setZero(size);
  rhs_.setZero(size);
  last_step_.setZero(size);
  last_q_step_.setZero(n_);
  values_.setZero(problem.iteration_pattern().nonzeros());
  projector_values_.setZero(problem.iteration_pattern().nonzeros());
}

MatrixWeights GeneralizedAlphaStepper::iteration_weights(double h, bool scaled) const {
  const GeneralizedAlphaParameters& p = params_;
  const double gamma_prime = p.gamma / (p.beta * h);
  const double beta_prime = (1.0 - p.alpha_m) / (p.beta * h * h * (1.0 - p.alpha_f));
  // Bottasso et al. (2008): multiplying the dynamic rows by βh² makes the block
  // (1 − α_m)/(1 − α_f) M + γh C + βh² K, O(1) as h → 0 next to the unweighted Φ_q blocks.
  const double s = scaled ? p.beta * h * h : 1.0;
  return {s, s * gamma_prime, s * beta_prime};
}

// --- start ---------------------------------------------------------------------------------------

void GeneralizedAlphaStepper::update_pattern(double t, const VecX& q, const VecX& v, double h) {
  // The problem's pattern may follow the state (contact pairs that are near, DESIGN §5): then the
  // value arrays take its new size and each factorization re-runs its symbolic analysis first.
  if (!problem_.update_pattern(t, as_span(q), as_span(v), h)) return;
  ++pattern_revision_;
  ++stats_.pattern_changes;
  const Index nnz = problem_.iteration_pattern().nonzeros();
  values_.setZero(nnz);
  projector_values_.setZero(nnz);
}

void GeneralizedAlphaStepper::factor(KluSolver& klu, long& revision, const VecX& values) {
  if (revision != pattern_revision_) {
    klu.analyze();
    revision = pattern_revision_;
  }
  klu.factor(as_span(values));
}

void GeneralizedAlphaStepper::refresh_projector(double t, const VecX& q) {
  // [M Φ_qᵀ; Φ_q 0] (weights (0, 0, 1): no stiffness, damping or geometric term). v, a and λ do
  // not enter; acc1_ is only a correctly sized argument.
  problem_.iteration_matrix(t, as_span(q), as_span(v_), as_span(acc1_), as_span(lambda_),
                            MatrixWeights{0.0, 0.0, 1.0}, as_span(projector_values_));
  ++stats_.matrix_evaluations;
  factor(projector_, projector_revision_, projector_values_);
}

void GeneralizedAlphaStepper::project_positions(double t, VecX& q, int max_iterations) {
  // Newton for min ½‖q⁺ − q‖²_M subject to Φ(q⁺) = 0: [M Φ_qᵀ; Φ_q 0][Δq; μ] = [0; −Φ].
  for (int it = 0; it < max_iterations; ++it) {
    problem_.constraints(t, as_span(q), as_span(phi_));
    if (m_ == 0 || phi_.lpNorm<Eigen::Infinity>() == 0.0) return;
    refresh_projector(t, q);
    rhs_.head(n_).setZero();
    rhs_.tail(m_) = -phi_;
    projector_.solve(as_span(rhs_));
    q += rhs_.head(n_);
    if (rhs_.head(n_).lpNorm<Eigen::Infinity>() <=
        1e-14 * std::max(1.0, q.lpNorm<Eigen::Infinity>()))
      return;
  }
  problem_.constraints(t, as_span(q), as_span(phi_));
  Index worst = 0;
  const double value = phi_.cwiseAbs().maxCoeff(&worst);
  throw SolverError(fmt::format(
      "generalized-α: projecting the initial coordinates onto Φ = 0 did not converge in {} "
      "iterations; |Φ| = {:.3e} at {}",
      max_iterations, value, problem_.describe_row(n_ + worst)));
}

void GeneralizedAlphaStepper::project_velocities(double t, const VecX& q, VecX& v) {
  // M-orthogonal projection onto Φ_q v + Φ_t = 0 (linear: one solve, projector factored at q).
  if (m_ == 0) return;
  problem_.velocity_constraint(t, as_span(q), as_span(v), as_span(velocity_residual_));
  rhs_.head(n_).setZero();
  rhs_.tail(m_) = -velocity_residual_;
  projector_.solve(as_span(rhs_));
  v += rhs_.head(n_);
}

void GeneralizedAlphaStepper::solve_index1(double t, const VecX& q, const VecX& v, VecX& acc,
                                           VecX& lambda) {
  // [M Φ_qᵀ; Φ_q 0][q''; λ] = [Q − F; γ] with the projector factored at q (DESIGN §6).
  acc1_.setZero();
  lambda1_.setZero();
  problem_.residual(t, as_span(q), as_span(v), as_span(acc1_), as_span(lambda1_),
                    as_span(residual_));
  ++stats_.residual_evaluations;
  rhs_.head(n_) = -residual_.head(n_);
  if (m_ > 0) {
    problem_.acceleration_rhs(t, as_span(q), as_span(v), as_span(velocity_residual_));
    rhs_.tail(m_) = velocity_residual_;
  }
  projector_.solve(as_span(rhs_));
  acc = rhs_.head(n_);
  lambda = rhs_.tail(m_);
}

void GeneralizedAlphaStepper::initialize(double t0) {
  initialize(t0, problem_.initial_coordinates(), problem_.initial_velocities());
}

void GeneralizedAlphaStepper::initialize(double t0, const VecX& q0, const VecX& v0) {
  if (q0.size() != n_ || v0.size() != n_)
    throw std::invalid_argument("generalized-α: initial q, v have the wrong size");
  stats_ = {};
  klu_base_[0] = klu_.full_factorizations();
  klu_base_[1] = klu_.refactorizations();
  klu_base_[2] = projector_.full_factorizations();
  klu_base_[3] = projector_.refactorizations();
  klu_base_[4] = klu_.symbolic_analyses() + projector_.symbolic_analyses();
  klu_seconds_base_[0] = klu_.factor_seconds() + projector_.factor_seconds();
  klu_seconds_base_[1] = klu_.solve_seconds() + projector_.solve_seconds();
  Stopwatch timer(stats_.wall_seconds);
  t_ = t0;
  t_base_ = t0;
  steps_from_base_ = 0;
  q_ = q0;
  v_ = v0;
  project_positions(t0, q_, 20);
  h_ = options_.step_size;
  restart(t0, h_);
  matrix_h_ = -1.0;
  matrix_stale_ = true;
  matrix_age_ = 0;
  eta_ = 1.0;
  steps_since_halving_ = 0;
  recovery_wait_ = options_.recovery_steps;
  steps_since_climb_ = -1;
  halvings_in_a_row_ = 0;
  stats_.min_step = h_;
  stats_.max_step = 0.0;
  initialized_ = true;
  update_factorization_counters();
}

// --- one step ------------------------------------------------------------------------------------

void GeneralizedAlphaStepper::predict(double h) {
  // Newton's starting point; the converged step does not depend on it (up to the tolerance).
  // constant: q''_{n+1} = q''_n, λ_{n+1} = λ_n, exact when q'' is constant. extrapolated: linear
  // extrapolation from the last two accepted steps (the constant one right after a restart), one
  // order more accurate for the smooth part of the motion; q, v follow from the update formulas.
  const GeneralizedAlphaParameters& p = params_;
  acc1_ = acc_;
  lambda1_ = lambda_;
  if (options_.predictor == GeneralizedAlphaPredictor::extrapolated && have_previous_) {
    const double r = h / previous_h_;
    acc1_ += r * (acc_ - acc_previous_);
    lambda1_ += r * (lambda_ - lambda_previous_);
  }
  // a_{n+1} from (AB 7), kept in increment_ as scratch.
  increment_ = (p.alpha_f * acc_ - p.alpha_m * a_ + (1.0 - p.alpha_f) * acc1_) / (1.0 - p.alpha_m);
  v1_ = v_ + h * (1.0 - p.gamma) * a_ + h * p.gamma * increment_;
  q1_ = q_ + h * v_ + h * h * (0.5 - p.beta) * a_ + h * h * p.beta * increment_;
}

void GeneralizedAlphaStepper::refresh_matrix(double t1, double h) {
  update_pattern(t1, q1_, v1_, h);
  problem_.iteration_matrix(t1, as_span(q1_), as_span(v1_), as_span(acc1_), as_span(lambda1_),
                            iteration_weights(h, options_.scaling), as_span(values_));
  ++stats_.matrix_evaluations;
  factor(klu_, klu_revision_, values_);
  matrix_signature_ = problem_.active_set_signature();  // of the residual at this iterate
  matrix_h_ = h;
  matrix_age_ = 0;
  matrix_stale_ = false;
  // The stabilized index-2 position correction uses the projector at a recent iterate: the
  // direction M⁻¹Φ_qᵀ only has to be a smooth full-rank field (μ itself is small).
  if (options_.formulation == GeneralizedAlphaFormulation::stabilized_index2 && m_ > 0)
    refresh_projector(t1, q1_);
}

double GeneralizedAlphaStepper::attempt_size(double remaining, bool& last) const {
  if (adaptive()) {
    // n = ⌈remaining/h_⌉ equal steps to t_limit: an output interval is crossed at one h (no
    // sliver, and the same h in every interval while h_ holds). A size within 1e-9 of the one the
    // state is calibrated to is taken as that one (no rescale; the factorization stays valid).
    const double n = std::ceil(remaining / h_ * (1.0 - 1e-9));
    last = n <= 1.0;
    double h = !(n < 1e9) ? h_ : last ? remaining : remaining / n;
    if (std::abs(h - a_h_) <= 1e-9 * a_h_) h = a_h_;
    return h;
  }
  // Fixed: snap to t_limit when it is within round-off of one step, so output times are hit
  // exactly (keeping h_ itself then, so the factorization stays valid). When t_limit is more than
  // one but less than 1.5 steps away, take two equal steps of remaining/2 instead of h_ and a
  // sliver: a sliver (t drifts against the output grid after halvings) restarts the scheme at a
  // tiny h, where the index-3 multipliers carry round-off amplified by h⁻² and Newton fails.
  const bool snap = std::abs(remaining - h_) <= 1e-8 * h_;
  const double h = snap                   ? h_
                   : remaining < h_       ? remaining
                   : remaining < 1.5 * h_ ? 0.5 * remaining
                                          : h_;
  last = snap || h == remaining;
  return h;
}

double GeneralizedAlphaStepper::local_error(double h) {
  // a_{n+1} from (AB 7); the position error of the step is C h³ q''' + O(h⁴) and
  // a_{n+1} − a_n = h q''' + O(h²) (docs/time_step_control.md). increment_ is scratch here.
  const GeneralizedAlphaParameters& p = params_;
  a1_ = (p.alpha_f * acc_ - p.alpha_m * a_ + (1.0 - p.alpha_f) * acc1_) / (1.0 - p.alpha_m);
  if (!adaptive()) return 0.0;
  increment_ = (p.local_error_constant() * h * h) * (a1_ - a_);
  if (options_.filter_error_estimate) {
    // Filtered estimate ẽ = S⁻¹[w_a M e; 0] with the factorized iteration matrix S (Shampine's
    // filter, as Radau5 applies (I − hγJ)⁻¹ to its estimate: Hairer & Wanner II, §IV.8). A mode of
    // frequency ω is scaled by 1/(1 + (βh²(1 − α_f)/(1 − α_m))ω²): resolved modes keep their
    // error to O(h²ω²), unresolved stiff ones (axial, contact), which the scheme damps instead of
    // resolving, drop out, and the constraint rows remove the normal part the scheme enforces.
    // M e from the n×n block of [M Φ_qᵀ; Φ_q 0], assembled once per pattern (M is constant).
    if (mass_revision_ != pattern_revision_) {
      mass_values_.setZero(problem_.iteration_pattern().nonzeros());
      problem_.iteration_matrix(t_, as_span(q_), as_span(v_), as_span(acc_), as_span(lambda_),
                                MatrixWeights{0.0, 0.0, 1.0}, as_span(mass_values_));
      mass_revision_ = pattern_revision_;
    }
    const MatrixWeights w = iteration_weights(h, options_.scaling);
    const std::vector<Index>& start = problem_.iteration_pattern().column_start();
    const std::vector<Index>& row = problem_.iteration_pattern().row_index();
    rhs_.setZero();
    for (Index c = 0; c < n_; ++c)
      for (Index k = start[c]; k < start[c + 1] && row[k] < n_; ++k)
        rhs_[row[k]] += w.w_a * mass_values_[k] * increment_[c];
    klu_.solve(as_span(rhs_));
    increment_ = rhs_.head(n_);
  }
  return controller_.error_norm(as_span(increment_), as_span(q_), as_span(q1_));
}

void GeneralizedAlphaStepper::accept(double t1, double h, bool on_base, bool last) {
  a_.swap(a1_);
  q_.swap(q1_);
  v_.swap(v1_);
  acc_previous_.swap(acc_);
  acc_.swap(acc1_);
  lambda_previous_.swap(lambda_);
  lambda_.swap(lambda1_);
  problem_.commit_step(t1, as_span(q_), as_span(v_));
  have_previous_ = true;
  previous_h_ = h;
  // t = t_base + n h (one rounding) rather than t += h (n roundings): far from t = 0 the
  // accumulated round-off would otherwise exceed the snap tolerance within an output interval.
  t_ = t1;
  if (on_base && !last) {
    ++steps_from_base_;
  } else {
    t_base_ = t1;
    base_h_ = h;
    steps_from_base_ = 0;
  }
  ++stats_.steps;
  stats_.min_step = std::min(stats_.min_step, h);
  stats_.max_step = std::max(stats_.max_step, h);
  ++matrix_age_;
  halvings_in_a_row_ = 0;
  // Modified Newton keeps the factorization while it contracts well ("while the contraction
  // rate is good"); a slow step means the matrix has drifted from the current state.
  if (options_.newton == NewtonStrategy::modified &&
      (step_max_rate_ > options_.max_reuse_rate || matrix_age_ >= options_.max_matrix_age))
    matrix_stale_ = true;
}

void GeneralizedAlphaStepper::step(double t_limit) {
  if (!initialized_) throw std::logic_error("GeneralizedAlphaStepper::step before initialize()");
  Stopwatch timer(stats_.wall_seconds);
  const double remaining = t_limit - t_;
  if (!(remaining > 0.0)) return;
  const double h_min = controller_.options().h_min;
  bool retried_stale = false;
  for (;;) {
    bool last = false;
    const double h = attempt_size(remaining, last);
    change_step_size(h);
    const bool on_base = h == base_h_;
    const double t1 = last      ? t_limit
                      : on_base ? t_base_ + static_cast<double>(steps_from_base_ + 1) * h
                                : t_ + h;
    predict(h);
    const Outcome outcome = newton(t1, h);
    if (outcome == Outcome::converged) {
      const double err = local_error(h);
      if (adaptive()) {
        const StepDecision d = controller_.decide(h, err, step_max_rate_);
        if (!d.accept) {
          ++stats_.error_test_failures;
          ++stats_.rejected_steps;
          if (h <= h_min * (1.0 + 1e-12))
            throw GeneralizedAlphaFailure(
                fmt::format(
                    "generalized-α: local error estimate {:.3e} > 1 at t = {:.9g} with h = h_min "
                    "= {:.3e}; loosen the error tolerances or lower h_min",
                    err, t_, h),
                t_, h, "-");
          h_ = d.h_next;
          retried_stale = false;
          continue;
        }
        // A step shortened to reach t_limit does not shrink the controller's h_ unless its own
        // error asks for a smaller step.
        h_ = h < h_ && d.h_next >= h ? std::max(h_, d.h_next) : d.h_next;
      }
      last_error_ = err;
      accept(t1, h, on_base, last);
      unevaluable_.clear();  // keeps its capacity: no allocation in later steps
      if (steps_since_climb_ >= 0 && ++steps_since_climb_ > recovery_wait_) {
        recovery_wait_ = options_.recovery_steps;  // the climb held
        steps_since_climb_ = -1;
      }
      if (!adaptive() && h_ < options_.step_size && ++steps_since_halving_ >= recovery_wait_) {
        // Back up the ladder step_size·2⁻ᵏ (the largest rung ≤ 2h_): a halving of a shortened
        // step leaves h_ off the ladder, and doubling it would keep it off (and t off the grid).
        double rung = options_.step_size;
        while (rung > 2.0 * h_ * (1.0 + 1e-12)) rung *= 0.5;
        h_ = rung;
        steps_since_halving_ = 0;
        steps_since_climb_ = 0;
      }
      break;
    }
    ++stats_.convergence_failures;
    matrix_stale_ = true;
    if (outcome == Outcome::diverged_stale && !retried_stale) {
      retried_stale = true;  // same h with a fresh matrix before reducing it
      continue;
    }
    // Fixed stepping: at most max_step_halvings halvings in a row, and the step ladder h_ never
    // below step_size·2^−max_step_halvings. Accepted steps between failures reset the count, so
    // without the floor h could ratchet down without bound (a violent scene reached 1e-110 s,
    // where t + h == t and the run makes no progress). The capture scenes go down to 2^−8.
    const double h_floor = std::ldexp(options_.step_size, -options_.max_step_halvings);
    const bool in_a_row = !adaptive() && ++halvings_in_a_row_ > options_.max_step_halvings;
    const bool exhausted =
        adaptive() ? h <= h_min * (1.0 + 1e-12) : in_a_row || h_ <= h_floor * (1.0 + 1e-12);
    if (exhausted) {
      Index worst = -1;
      const double norm = increment_norm(&worst);
      const std::string where = worst < 0 ? std::string("-") : problem_.describe_row(worst);
      throw GeneralizedAlphaFailure(
          fmt::format("generalized-α: Newton failed at t = {:.9g} with h = {:.3e} ({}); last "
                      "weighted increment norm {:.3e}, largest at {}{}{}",
                      t_, h,
                      adaptive() ? std::string("h_min reached")
                      : in_a_row ? fmt::format("after {} step halvings", options_.max_step_halvings)
                                 : fmt::format("h at its floor step·2^−{} = {:.3e}",
                                               options_.max_step_halvings, h_floor),
                      norm, where,
                      unevaluable_.empty() ? "" : "; an iterate was not evaluable: ", unevaluable_),
          t_, h, where);
    }
    if (adaptive()) {
      ++stats_.rejected_steps;
      h_ = controller_.after_failure(h);
    } else {
      h_ = 0.5 * h;
      steps_since_halving_ = 0;
      ++stats_.step_halvings;
      // A climb that failed again at once: wait twice as long before the next one (the wait
      // returns to recovery_steps once a climb holds, in the accept branch above).
      // (steps_since_climb_ ≥ 0 only within the wait after a climb: accept resets it past that.)
      if (options_.recovery_backoff && steps_since_climb_ >= 0)
        recovery_wait_ = std::min(2 * recovery_wait_, options_.max_recovery_steps);
      steps_since_climb_ = -1;
    }
    retried_stale = false;
    klu_.reset_pivoting();
  }
  update_factorization_counters();
}

void GeneralizedAlphaStepper::update_factorization_counters() {
  stats_.full_factorizations =
      klu_.full_factorizations() - klu_base_[0] + projector_.full_factorizations() - klu_base_[2];
  stats_.factorizations = stats_.full_factorizations + klu_.refactorizations() - klu_base_[1] +
                          projector_.refactorizations() - klu_base_[3];
  stats_.symbolic_analyses =
      klu_.symbolic_analyses() + projector_.symbolic_analyses() - klu_base_[4];
  stats_.factor_seconds =
      klu_.factor_seconds() + projector_.factor_seconds() - klu_seconds_base_[0];
  stats_.solve_seconds = klu_.solve_seconds() + projector_.solve_seconds() - klu_seconds_base_[1];
}

void GeneralizedAlphaStepper::advance_to(double t_end) {
  while (t_ < t_end) step(t_end);
}

}  // namespace ancf
