// Step-size controller for a one-step method of order p with a local error estimate
// (docs/time_step_control.md). The integrator measures the local error of a step as a weighted
// RMS norm ‖e‖ (weights atol + rtol·|y_i|, so that ‖e‖ ≤ 1 is the tolerance); the controller
// accepts or rejects the step and proposes the next h from the asymptotic model ‖e‖ ≈ C h^(p+1):
//
//   h_new = h · clamp(safety · ‖e‖^(−1/(p+1)), shrink limit, growth limit)
//
// (the elementary controller, Hairer, Nørsett & Wanner, Solving ODEs I, §II.4, eq. (4.13)). After
// an accepted step the optional PI term of Gustafsson (1991), "Control theoretic techniques for
// stepsize selection in explicit Runge–Kutta methods", ACM TOMS 17:533–554, damps the oscillation
// of h that the elementary controller shows near the stability boundary:
//
//   h_new = h · safety · ‖e_n‖^(−k_I) · (‖e_{n−1}‖/‖e_n‖)^(k_P),  k_I = 0.7/(p+1), k_P = 0.4/(p+1).
//
// After a failure of the nonlinear solver at h, the step is limited to a ceiling just below h that
// relaxes geometrically with each accepted step whose iteration converged easily.
//
// Hysteresis: an accepted step keeps h unless the proposal is smaller or at least growth_threshold
// times larger. An implicit integrator whose iteration matrix depends on h then rebuilds it only
// when the gain is worth it (IDA does the same with a threshold of 2).
#pragma once

#include <span>

namespace ancf {

struct StepControllerOptions {
  double rtol = 1e-3;           ///< relative tolerance of the local error estimate (> 0)
  double atol = 1e-6;           ///< absolute tolerance, in the unit of the estimated variable (> 0)
  double h_min = 1e-8;          ///< [s] smallest step; the integrator fails below it (> 0)
  double h_max = 0.0;           ///< [s] largest step; 0: no limit
  double safety = 0.9;          ///< factor on the asymptotically optimal step, (0, 1]
  double max_growth = 2.0;      ///< largest h_new/h after an accepted step (≥ 1)
  double max_shrink = 0.2;      ///< smallest h_new/h after a rejected step, (0, 1)
  double failure_shrink = 0.5;  ///< h_new/h after a failure of the nonlinear solver, (0, 1)
  /// After a failure at h the step stays ≤ ceiling = h·failure_ceiling: the nonlinear solver, not
  /// the error, limits h there, and jumping straight back to the failing size fails again. The
  /// ceiling grows by ceiling_growth per accepted step whose nonlinear iteration contracted at a
  /// rate ≤ easy_rate (the solver has room), and stays otherwise.
  double failure_ceiling = 0.9;   ///< (0, 1]
  double ceiling_growth = 1.05;   ///< ≥ 1
  double easy_rate = 0.1;         ///< (0, 1)
  double growth_threshold = 1.2;  ///< hysteresis: keep h unless h_new/h ≥ this or < 1 (≥ 1)
  bool pi = true;                 ///< Gustafsson's PI control (false: elementary controller)
};

/// What the controller decided about a step.
struct StepDecision {
  bool accept = false;
  double h_next = 0.0;  ///< [s] size of the next step (or of the retry), in [h_min, h_max]
};

/// Deterministic, no allocation. Copyable value type.
class StepController {
 public:
  /// order: p of the method (local error O(h^(p+1))). Throws std::invalid_argument for options
  /// outside the documented ranges.
  StepController(const StepControllerOptions& options, int order);

  /// Weighted RMS norm √(Σ (e_i / w_i)² / n) with w_i = atol + rtol·max(|y0_i|, |y1_i|): e is
  /// the error estimate of a step from y0 to y1. All spans have the same size (0: returns 0).
  [[nodiscard]] double error_norm(std::span<const double> e, std::span<const double> y0,
                                  std::span<const double> y1) const;

  /// Decide on a step of size h whose error norm is err (≥ 0; NaN or ∞ count as a rejection) and
  /// whose nonlinear iteration contracted at rate θ (largest ratio of successive corrections).
  /// A rejection shrinks h by safety·err^(−1/(p+1)) (at least to max_shrink·h); after one, the
  /// next accepted step does not grow h (Hairer, Nørsett & Wanner §II.4).
  [[nodiscard]] StepDecision decide(double h, double err, double rate = 0.0);
  /// The nonlinear solver failed at step size h: the size of the retry.
  [[nodiscard]] double after_failure(double h);
  /// Forget the error history (a restart of the integrator).
  void reset();

  [[nodiscard]] const StepControllerOptions& options() const { return options_; }
  /// h clamped to [h_min, h_max].
  [[nodiscard]] double clamp(double h) const;

 private:
  StepControllerOptions options_;
  double exponent_;               // 1/(p+1)
  double previous_error_ = -1.0;  // ‖e‖ of the last accepted step (−1: none)
  double ceiling_ = 0.0;          // limit after a nonlinear-solver failure (0: none)
  bool after_rejection_ = false;
};

}  // namespace ancf
