// Generalized-α: the h-dependent parts of the state (generalized_alpha.hpp). The numerical
// solution follows an asymptotic expansion in which a_n = q''(t_n + Δh) + O(h²), Δ = α_m − α_f
// (Arnold & Brüls 2007), and, for index 3, the constraint-normal part of v_n = v(t_n) + c h² q'''
// (c = 1/6 − Δ/2 − β, derived in shift_normal_velocity). The starting procedure sets these parts
// for the first h; a change of h either repeats it (restart) or moves them to the new h
// (rescale). docs/time_step_control.md measures the variants.
#include <cmath>

#include "ancf/solvers/generalized_alpha.hpp"

namespace ancf {

void GeneralizedAlphaStepper::restart(double t, double h) {
  // Consistent starting values at (t, q_) for step size h (q_ satisfies Φ = 0).
  refresh_projector(t, q_);
  project_velocities(t, q_, v_);
  solve_index1(t, q_, v_, acc_, lambda_);
  a_h_ = h;
  have_previous_ = false;
  if (options_.start == GeneralizedAlphaStart::perturbed && params_.alpha_m != params_.alpha_f)
    perturbed_start(t, h);
  else
    a_ = acc_;
  matrix_stale_ = true;
  controller_.reset();
  ++stats_.restarts;
}

void GeneralizedAlphaStepper::perturbed_start(double t0, double h) {
  // Starting values that agree with the asymptotic expansion of the numerical solution, so the
  // O(h) start-up transient of λ (and q'') does not arise (Arnold, Brüls & Cardona 2015).
  //
  // (i) a_n approximates q''(t_n + Δh), Δ = α_m − α_f, to O(h²) (AB 7 is then consistent to
  // second order). We evaluate q'' at t_0 + Δh by the index-1 solve at the Taylor state
  // q_0 + s v_0 + ½s² q''_0, v_0 + s q''_0 (s = Δh), whose errors O(s³), O(s²) change q'' by O(h²).
  // q1_, v1_ and phi_ hold the Taylor state and the (unused) multipliers there: no allocation.
  const GeneralizedAlphaParameters& p = params_;
  const double delta = p.alpha_m - p.alpha_f, s = delta * h;
  q1_ = q_ + s * v_ + 0.5 * s * s * acc_;
  v1_ = v_ + s * acc_;
  refresh_projector(t0 + s, q1_);
  solve_index1(t0 + s, q1_, v1_, a_, phi_);
  // (ii) Index 3: the constraint-normal part of v_0 as the expansion has it (see
  // shift_normal_velocity), c h² q'''_0 with q'''_0 = (a_0 − q''_0)/(Δh) + O(h).
  shift_normal_velocity(t0, (1.0 / 6.0 - 0.5 * delta - p.beta) * h * h / s);
}

void GeneralizedAlphaStepper::shift_normal_velocity(double t, double factor) {
  // Index 3: Φ(q_{n+1}) = 0 fixes the constraint-normal part of the position update,
  // h v_n + h²(½ − β) a_n + h²β a_{n+1} = q(t_{n+1}) − q(t_n) to O(h⁴). With a_n = q''(t_n + Δh)
  // the Taylor expansion leaves h³q'''(Δ/2 + β − 1/6), so the normal part of v_n follows
  // v(t_n) + c h² q''' with c = 1/6 − Δ/2 − β. A v_n that differs from this by O(h²) (an exact
  // v_0, or the v_n of another step size) is turned into an O(h) transient of λ by the h⁻² of
  // the multipliers; it decays like n ρ∞ⁿ (the (v, a) recursion has the double root −ρ∞).
  // Here v += x, the M-orthogonal correction x = M⁻¹Φ_qᵀy with Φ_q x = Φ_q δ, δ = factor·(a − q'')
  // (a − q'' = Δh q''' + O(h²)); the tangential part of δ would only change the error constant.
  if (options_.formulation != GeneralizedAlphaFormulation::index3 || m_ == 0 || factor == 0.0)
    return;
  v1_ = factor * (a_ - acc_);  // δ (v1_, q1_ are free outside a step)
  q1_.setZero();
  refresh_projector(t, q_);
  problem_.velocity_constraint(t, as_span(q_), as_span(v1_), as_span(phi_));  // Φ_q δ + Φ_t
  problem_.velocity_constraint(t, as_span(q_), as_span(q1_), as_span(velocity_residual_));  // Φ_t
  rhs_.head(n_).setZero();
  rhs_.tail(m_) = phi_ - velocity_residual_;
  projector_.solve(as_span(rhs_));
  v_ += rhs_.head(n_);
}

void GeneralizedAlphaStepper::rescale(double h_new) {
  // Move the h-dependent parts of the expansion from a_h_ to h_new: a − q'' = Δh q''' + O(h²)
  // scales with h, and (index 3, rescale_with_velocity) the normal part of v moves by
  // c(h_new² − h_old²) q''' with q''' = (a_new − q'')/(Δ h_new) + O(h); the shift uses the factor
  // on (a_new − q'') that shift_normal_velocity expects. No residual, no index-1 solve: λ and q''
  // keep their values. Without the velocity shift the O(h²) normal-velocity mismatch becomes an
  // O(h) transient of λ that decays like nρ∞ⁿ (as after the consistent start); with it, a − q''
  // that is not Δh q''' (unresolved stiff contact) is amplified by h_old²/h_new into v.
  const GeneralizedAlphaParameters& p = params_;
  const double delta = p.alpha_m - p.alpha_f, h_old = a_h_;
  a_ = acc_ + (h_new / h_old) * (a_ - acc_);
  a_h_ = h_new;
  if (delta != 0.0 && options_.step_change == GeneralizedAlphaStepChange::rescale_with_velocity)
    shift_normal_velocity(
        t_, (1.0 / 6.0 - 0.5 * delta - p.beta) * (h_new * h_new - h_old * h_old) / (delta * h_new));
}

void GeneralizedAlphaStepper::change_step_size(double h_new) {
  // restart: the starting procedure of initialize() from (t, q, v) for the new h. It is what
  // fixed stepping does after a halving: the index-3 (v, a) recursion amplifies O(h²) velocity
  // errors by h⁻² in the multipliers, and a run of successive halvings without a restart made
  // that grow without bound. Error-controlled stepping changes h by bounded ratios and moves the
  // h-dependent parts instead (rescale): no O(h) λ transient and no index-1 solve per change.
  if (h_new == a_h_) return;
  ++stats_.step_size_changes;
  // rescale_climbs: a climb back after a halving is one bounded ratio (2) after accepted steps,
  // which is what the rescale is safe for; restarting there re-excites the modes that made the
  // step fail (docs/time_step_control.md, "Recovery after halvings").
  const bool climb = h_new > a_h_;
  bool rescaling = false;
  switch (options_.step_change) {
    case GeneralizedAlphaStepChange::automatic:
      rescaling = adaptive() || climb;
      break;
    case GeneralizedAlphaStepChange::restart:
      rescaling = false;
      break;
    case GeneralizedAlphaStepChange::rescale_climbs:
      rescaling = climb;
      break;
    case GeneralizedAlphaStepChange::rescale:
    case GeneralizedAlphaStepChange::rescale_with_velocity:
      rescaling = true;
      break;
  }
  if (rescaling)
    rescale(h_new);
  else
    restart(t_, h_new);
}

}  // namespace ancf
