// Generalized-α: the Newton iteration of one step (generalized_alpha.hpp): error weights, the
// weighted increment norm, modified Newton with rescue and the optional damping (Deuflhard).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "ancf/core/error.hpp"
#include "ancf/solvers/generalized_alpha.hpp"

namespace ancf {

void GeneralizedAlphaStepper::update_weights(double gamma_prime) {
  // Inverse error weights, fixed for the step attempt (as CVODE/IDA fix theirs per step): from
  // the larger of the last accepted and the predicted values. Δv = γ'Δq is folded into the v
  // weights. Multipliers get one norm-wise weight: individual ones pass through zero (and have
  // unrelated units), so a per-component relative test would demand absolute accuracy atol_λ there.
  const double rtol = options_.rtol;
  weight_q_ =
      (options_.atol_position + rtol * q_.cwiseAbs().cwiseMax(q1_.cwiseAbs()).array()).inverse();
  weight_v_ = gamma_prime /
              (options_.atol_velocity + rtol * v_.cwiseAbs().cwiseMax(v1_.cwiseAbs()).array());
  weight_lambda_ =
      1.0 / (options_.atol_multiplier + rtol * std::max(lambda_.lpNorm<Eigen::Infinity>(),
                                                        lambda1_.lpNorm<Eigen::Infinity>()));
}

namespace {

/// max |x_i| and its index, a non-finite entry counting as +∞ (Eigen's maxCoeff is unspecified
/// with NaN, and a failure message must name the row the NaN is in).
double largest_entry(const Eigen::ArrayXd& x, Index& index) {
  index = 0;
  double largest = -1.0;
  for (Index i = 0; i < x.size(); ++i) {
    const double a = std::isfinite(x[i]) ? std::abs(x[i]) : std::numeric_limits<double>::infinity();
    if (a > largest) largest = a, index = i;
    if (a == std::numeric_limits<double>::infinity()) break;
  }
  return std::max(largest, 0.0);
}

}  // namespace

double GeneralizedAlphaStepper::increment_norm(Index* worst) const {
  // Largest of the weighted RMS norms of Δq (increment_), Δv = γ'δ (δ = rhs_ head, γ' folded into
  // weight_v_) and Δλ (rhs_ tail).
  const double n = static_cast<double>(std::max<Index>(n_, 1));
  const double nq = std::sqrt((increment_.array() * weight_q_).square().sum() / n);
  const double nv = std::sqrt((rhs_.head(n_).array() * weight_v_).square().sum() / n);
  const double nl =
      m_ == 0 ? 0.0 : rhs_.tail(m_).norm() * weight_lambda_ / std::sqrt(static_cast<double>(m_));
  if (worst) {
    // Only for error messages: the component with the largest weighted increment.
    Index iq = 0, iv = 0, il = 0;
    const double wq = largest_entry(increment_.array() * weight_q_, iq);
    const double wv = largest_entry(rhs_.head(n_).array() * weight_v_, iv);
    const double wl = m_ == 0 ? 0.0 : largest_entry(rhs_.tail(m_).array(), il) * weight_lambda_;
    *worst = wl > std::max(wq, wv) ? n_ + il : (wq >= wv ? iq : iv);
  }
  return std::max({nq, nv, nl});
}

GeneralizedAlphaStepper::Outcome GeneralizedAlphaStepper::newton(double t1, double h) {
  const GeneralizedAlphaParameters& p = params_;
  const double gamma_prime = p.gamma / (p.beta * h);
  const double beta_prime = (1.0 - p.alpha_m) / (p.beta * h * h * (1.0 - p.alpha_f));
  const double s = options_.scaling ? p.beta * h * h : 1.0;
  const bool index2 = options_.formulation == GeneralizedAlphaFormulation::stabilized_index2;
  const bool full = options_.newton == NewtonStrategy::full;
  update_weights(gamma_prime);
  bool fresh = false;  // the matrix in use was built during this attempt
  int k = 0;           // iterations (modified Newton: with the matrix in use)
  int rescues = 0;     // matrices rebuilt because the iteration stalled
  double previous_norm = 0.0;
  step_max_rate_ = 0.0;
  // Before a rate has been measured in this attempt, the remaining error after the first
  // iteration is bounded by ‖Δ_1‖ only if the contraction rate is ≤ ½; the rate of the previous
  // step (modified Newton) may only tighten that test, never relax it: rates measured near a
  // solution underestimate those further away, and accepting a large first increment on an old
  // small rate lets index-3 position errors (amplified by h⁻² in λ and q'') build up.
  double eta = full ? 1.0 : std::max(1.0, eta_);
  // Damped Newton (Deuflhard, Newton Methods for Nonlinear Problems, Springer 2004, §3.3: the
  // natural monotonicity test): with the chord matrix S fixed, Δ̄ = −S⁻¹F(x_k + λΔ_k) is the
  // simplified correction at the trial point, and ‖Δ̄‖ ≤ (1 − λ/4)‖Δ_k‖ accepts it. A full step
  // (λ = 1) that diverges (θ ≥ 0.99) with a matrix built in this attempt is not given up but
  // halved along Δ_k, up to max_damping_halvings times: across the penalty onset or a cable
  // going slack the full step overshoots while the direction is good. x moves along Δ_k through
  // the update maps (q, v = γ'Δq, q'' = β'Δq, λ), so no state is copied.
  double damping = 1.0;  // λ of the trial point x_{k−1} + λΔ_k
  int damping_halvings = 0;
  const bool may_damp = !full && options_.max_damping_halvings > 0;
  auto move_along_last = [&](double factor) {
    q1_ += factor * last_q_step_;
    v1_ += (factor * gamma_prime) * last_step_.head(n_);
    acc1_ += (factor * beta_prime) * last_step_.head(n_);
    lambda1_ += factor * last_step_.tail(m_);
  };
  auto damp = [&]() {  // back along Δ_k to half the current λ
    move_along_last(-0.5 * damping);
    damping *= 0.5;
    ++damping_halvings;
    ++stats_.damped_iterations;
  };
  for (int left = options_.max_iterations; left > 0; --left) {
    // An iterate the problem cannot evaluate (std::domain_error: e.g. a rod tangent turned
    // against its committed frame by an overshooting correction) is treated as one with a
    // non-finite residual: damped back along Δ_k, or the attempt fails and h is reduced.
    bool evaluable = true;
    try {
      problem_.residual(t1, as_span(q1_), as_span(v1_), as_span(acc1_), as_span(lambda1_),
                        as_span(residual_));
      if (index2 && m_ > 0)
        problem_.velocity_constraint(t1, as_span(q1_), as_span(v1_), as_span(velocity_residual_));
    } catch (const std::domain_error& e) {
      unevaluable_ = e.what();
      evaluable = false;
    }
    ++stats_.residual_evaluations;
    if (!evaluable || !residual_.allFinite()) {
      if (may_damp && fresh && k >= 1 && damping_halvings < options_.max_damping_halvings) {
        damp();
        continue;
      }
      return fresh ? Outcome::failed : Outcome::diverged_stale;
    }
    // A contact that became active (or inactive) since the chord matrix was built changes the
    // stiffness by the penalty k: rebuild now rather than let the old matrix fail first.
    if (options_.refresh_on_active_set_change && !full && !matrix_stale_ &&
        problem_.active_set_signature() != matrix_signature_) {
      matrix_stale_ = true;
      ++stats_.active_set_refreshes;
    }
    if (full || matrix_stale_ || matrix_h_ != h) {
      try {
        refresh_matrix(t1, h);
      } catch (const SolverError&) {
        return Outcome::failed;
      } catch (const std::domain_error& e) {
        unevaluable_ = e.what();
        return Outcome::failed;
      }
      fresh = true;
      if (!full) k = 0;  // a new chord matrix: its rate is yet unknown
    }
    ++k;
    // Scaled right-hand side: dynamic rows × s; constraint rows: Φ (index 3) or, index 2,
    // (Φ_q v + Φ_t)/γ' (the velocity constraint linearized through Δv = γ'Δq).
    rhs_.head(n_) = -s * residual_.head(n_);
    if (m_ > 0) {
      if (index2)
        rhs_.tail(m_) = -velocity_residual_ / gamma_prime;
      else
        rhs_.tail(m_) = -residual_.tail(m_);
    }
    klu_.solve(as_span(rhs_));
    ++stats_.newton_iterations;
    rhs_.tail(m_) /= s;  // Δλ = Δλ̃ / (βh²)
    q1_ += rhs_.head(n_);
    v1_ += gamma_prime * rhs_.head(n_);
    acc1_ += beta_prime * rhs_.head(n_);
    lambda1_ += rhs_.tail(m_);
    increment_ = rhs_.head(n_);
    if (index2 && m_ > 0) {
      // Position constraint through μ: q ← q + M⁻¹Φ_qᵀμ with Φ_q M⁻¹Φ_qᵀμ = −Φ (block
      // Gauss–Seidel on the GGL system: the μ correction hardly changes the dynamic residual).
      try {
        problem_.constraints(t1, as_span(q1_), as_span(phi_));
      } catch (const std::domain_error& e) {
        unevaluable_ = e.what();
        return fresh ? Outcome::failed : Outcome::diverged_stale;
      }
      residual_.head(n_).setZero();  // residual_ reused as the projection right-hand side
      residual_.tail(m_) = -phi_;
      projector_.solve(as_span(residual_));
      q1_ += residual_.head(n_);
      increment_ += residual_.head(n_);
    }
    const double norm = increment_norm();
    if (k > 1 && may_damp && fresh && damping_halvings < options_.max_damping_halvings &&
        !(norm <= (damping < 1.0 ? 1.0 - 0.25 * damping : 0.99) * previous_norm)) {
      // The trial point fails the monotonicity test: undo the correction just applied, then
      // go back along Δ_k.
      q1_ -= increment_;
      v1_ -= gamma_prime * rhs_.head(n_);
      acc1_ -= beta_prime * rhs_.head(n_);
      lambda1_ -= rhs_.tail(m_);
      damp();
      continue;
    }
    last_step_ = rhs_;
    last_q_step_ = increment_;
    if (!std::isfinite(norm)) return fresh ? Outcome::failed : Outcome::diverged_stale;
    if (norm == 0.0) return Outcome::converged;
    if (k > 1 && damping < 1.0) {
      // An accepted damped trial: go on with full steps from here; its ratio is no contraction
      // rate of the iteration, so η keeps its value.
      damping = 1.0;
      step_max_rate_ = std::max(step_max_rate_, norm / previous_norm);
    } else if (k > 1) {
      const double theta = norm / previous_norm;
      step_max_rate_ = std::max(step_max_rate_, theta);
      // Divergence (θ ≥ 0.99), or predicted failure: at this rate the remaining iterations cannot
      // reach the tolerance (Hairer & Wanner §IV.8). Modified Newton then rebuilds the matrix at
      // the current iterate and goes on with a fresh iteration budget (at most 3 times per
      // attempt) — unless a matrix built in this attempt diverges outright: the step is then too
      // long. Full Newton only stops on divergence: its early rates, far from the solution,
      // improve as it converges quadratically.
      const bool diverging = theta >= 0.99;
      const bool predicted = std::pow(theta, left - 1) * theta / (1.0 - theta) * norm > 1.0;
      if (diverging || (predicted && !full)) {
        if (full || rescues >= 3 || (fresh && diverging))
          return fresh ? Outcome::failed : Outcome::diverged_stale;
        ++rescues;
        matrix_stale_ = true;
        damping_halvings = 0;
        left = options_.max_iterations + 1;
        previous_norm = 0.0;
        eta = std::max(1.0, eta);  // no rate known for the new matrix yet
        continue;
      }
      eta = theta / (1.0 - theta);
      eta_ = eta;
    }
    // Converged when the estimated remaining error η‖Δ_k‖ (Hairer & Wanner §IV.8) is ≤ 1; full
    // Newton converges quadratically, so ‖Δ_k‖ ≤ 1 leaves an error far below the tolerance.
    if (eta * norm <= 1.0 || (full && norm <= 1.0)) return Outcome::converged;
    previous_norm = norm;
  }
  return fresh ? Outcome::failed : Outcome::diverged_stale;
}

}  // namespace ancf
