// Error-controlled generalized-α (docs/time_step_control.md) and its step controller. What is
// checked, and why it would catch a mistake:
//  * the controller's norm, accept/reject decisions, growth limits, hysteresis and the ceiling
//  after
//    a nonlinear-solver failure, against hand-computed values;
//  * the error constant C = Δ/2 + β − 1/6 = 1/12 + Δ²/4 and the estimate itself: on the rigid
//    pendulum the estimate of one step divided by its true local error tends to 1 as h → 0 (a wrong
//    constant, a wrong a_{n+1} or a filter that distorts resolved modes shows as another limit);
//  * order 2 of the variable-step mode: a tolerance sweep on the rigid pendulum (exact elliptic
//    solution) gives global errors ∝ N⁻² in q and v (N accepted steps), with step sizes that vary;
//  * step changes: forced changes every one or two steps keep order 2 in q, v, λ with restart and
//    with rescale_with_velocity; index-3 rescale keeps q, v at order 2 and leaves λ an O(h)
//    transient; the stabilized index-2 formulation (velocity constraint enforced) needs no velocity
//    shift: rescale keeps λ at order 2 too;
//  * the filtered estimate lets a cable pendulum with unresolved axial modes run at large steps,
//    where the unfiltered one resolves them (many more steps) — the capture scene's failure mode;
//  * h_min is enforced with a clear message; the active-contact-set refresh counts and does not
//    change the converged solution.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/core/fitted_order.hpp"
#include "ancf/scenes/contact_scenes.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/solvers/step_controller.hpp"
#include "ancf/system/multibody_problem.hpp"
#include "pendulum_reference.hpp"
#include "unconstrained_problem.hpp"

namespace ancf {
namespace {

using testing::ExactPendulum;
using testing::tight;

// --- controller ----------------------------------------------------------------------------------

TEST(StepController, NormAndDecisions) {
  StepControllerOptions o;
  o.rtol = 1e-2;
  o.atol = 1e-3;
  o.pi = false;
  StepController c(o, 2);
  // Weights 1e-3 + 1e-2·max(|y0|, |y1|) = 2e-3 and 3e-3: e/w = (1, −2) → RMS √(5/2).
  const std::vector<double> e{2e-3, -6e-3}, y0{0.1, -0.2}, y1{-0.05, 0.1};
  EXPECT_NEAR(c.error_norm(e, y0, y1), std::sqrt(2.5), 1e-14);

  // err = 1/8: h·0.9·8^{1/3} = 1.8 h (≤ max_growth 2).
  StepDecision d = c.decide(1.0, 0.125);
  EXPECT_TRUE(d.accept);
  EXPECT_NEAR(d.h_next, 1.8, 1e-12);
  // err = 8: rejected, 0.9·8^{−1/3} = 0.45.
  d = c.decide(1.0, 8.0);
  EXPECT_FALSE(d.accept);
  EXPECT_NEAR(d.h_next, 0.45, 1e-12);
  // After a rejection the next accepted step does not grow.
  d = c.decide(1.0, 1e-6);
  EXPECT_TRUE(d.accept);
  EXPECT_EQ(d.h_next, 1.0);
  // Hysteresis: a ratio in [1, 1.2) keeps h; below 1 shrinks.
  d = c.decide(1.0, std::pow(0.9 / 1.1, 3.0));
  EXPECT_EQ(d.h_next, 1.0);
  d = c.decide(1.0, 0.9);
  EXPECT_NEAR(d.h_next, 0.9 * std::pow(0.9, -1.0 / 3.0), 1e-12);
  // A non-finite error is a rejection with the largest shrink.
  d = c.decide(1.0, std::nan(""));
  EXPECT_FALSE(d.accept);
  EXPECT_NEAR(d.h_next, o.max_shrink, 1e-15);

  // Nonlinear failure at h = 1: retry at failure_shrink·h, ceiling 0.9 that grows by 1.05 only
  // after easy iterations.
  c.reset();
  EXPECT_NEAR(c.after_failure(1.0), 0.5, 1e-15);
  d = c.decide(0.5, 1e-6, 0.5);       // hard iteration: capped by 0.9, ceiling stays
  EXPECT_NEAR(d.h_next, 0.5, 1e-15);  // (no growth right after a failure)
  d = c.decide(0.5, 1e-6, 0.5);
  EXPECT_NEAR(d.h_next, 0.9, 1e-15);
  d = c.decide(0.9, 1e-6, 0.01);  // easy: ceiling grows after use
  EXPECT_NEAR(d.h_next, 0.9, 1e-15);
  d = c.decide(0.9, 1e-6, 0.01);
  EXPECT_NEAR(d.h_next, 0.9 * 1.05, 1e-15);

  // h_max and h_min clamp.
  StepControllerOptions limited = o;
  limited.h_max = 1.5;
  StepController cl(limited, 2);
  EXPECT_EQ(cl.decide(1.0, 1e-6).h_next, 1.5);
  EXPECT_EQ(cl.clamp(1e-20), limited.h_min);

  for (auto bad : {&StepControllerOptions::rtol, &StepControllerOptions::safety,
                   &StepControllerOptions::max_shrink, &StepControllerOptions::failure_shrink}) {
    StepControllerOptions b = o;
    b.*bad = -1.0;
    EXPECT_THROW(StepController(b, 2), std::invalid_argument);
  }
}

// --- the estimate --------------------------------------------------------------------------------

TEST(GeneralizedAlphaError, ConstantMatchesChungHulbertClosedForm) {
  for (const double rho : {0.0, 0.5, 0.8, 1.0}) {
    const GeneralizedAlphaParameters p = GeneralizedAlphaParameters::chung_hulbert(rho);
    const double delta = p.alpha_m - p.alpha_f;
    EXPECT_NEAR(p.local_error_constant(), 1.0 / 12.0 + 0.25 * delta * delta, 1e-15) << rho;
  }
  // ρ∞ = 1 is the trapezoidal rule: Zienkiewicz & Xie's β − 1/6 with β = 1/4.
  EXPECT_NEAR(GeneralizedAlphaParameters::chung_hulbert(1.0).local_error_constant(), 1.0 / 12.0,
              1e-15);
}

GeneralizedAlphaOptions error_controlled(double h0, double rtol) {
  GeneralizedAlphaOptions o = tight(h0, 0.8);
  o.start = GeneralizedAlphaStart::perturbed;
  o.stepping = GeneralizedAlphaStepping::error_controlled;
  o.controller.rtol = rtol;
  o.controller.atol = 1e-3 * rtol;  // positions are O(1) m
  return o;
}

// One step from the exact state at t0 (perturbed start: a_0 = q''(t0 + Δh) + O(h²)): the estimate
// against the true local error, both in the controller's norm.
TEST(GeneralizedAlphaError, EstimateTendsToTheTrueLocalError) {
  const RigidPendulumSpec spec;
  const ExactPendulum exact(spec);
  const Model model = rigid_pendulum_model(spec);
  MultibodyProblem problem(model);
  std::vector<double> ratios;
  for (const double h : {0.04, 0.02, 0.01, 0.005}) {
    GeneralizedAlphaOptions o = error_controlled(h, 1.0);  // every step accepted
    o.controller.h_max = h;
    GeneralizedAlphaStepper stepper(problem, o);
    VecX q, v;
    exact.state(0.3, q, v);
    stepper.initialize(0.3, q, v);
    const VecX q0 = stepper.positions();
    stepper.step();
    ASSERT_EQ(stepper.time(), 0.3 + h);
    exact.state(stepper.time(), q, v);
    const VecX true_error = stepper.positions() - q;
    StepController norm(o.controller, 2);
    const double truth =
        norm.error_norm(as_span(true_error), as_span(q0), as_span(stepper.positions()));
    ratios.push_back(stepper.last_error_norm() / truth);
    std::printf("h %.3f: estimate %.4e, true local error %.4e, ratio %.4f\n", h,
                stepper.last_error_norm(), truth, ratios.back());
  }
  EXPECT_NEAR(ratios.back(), 1.0, 0.05);
  // The ratio converges: each halving of h moves it at least halfway closer to 1.
  for (std::size_t i = 1; i < ratios.size(); ++i)
    EXPECT_LE(std::abs(ratios[i] - 1.0), 0.6 * std::abs(ratios[i - 1] - 1.0) + 1e-3);
}

// --- order ---------------------------------------------------------------------------------------

struct SweepPoint {
  double mean_step = 0, q = 0, v = 0, lambda = 0;
  GeneralizedAlphaStatistics stats;
};

// Outputs every 0.05 s over [0.25, 1.25] s from the exact state; sup errors relative to the sup of
// the exact values.
SweepPoint pendulum_run(const GeneralizedAlphaOptions& o) {
  const RigidPendulumSpec spec;
  const ExactPendulum exact(spec);
  const Model model = rigid_pendulum_model(spec);
  MultibodyProblem problem(model);
  GeneralizedAlphaStepper stepper(problem, o);
  VecX q, v;
  exact.state(0.25, q, v);
  stepper.initialize(0.25, q, v);
  testing::PendulumErrors e;
  for (int i = 1; i <= 20; ++i) {
    stepper.advance_to(0.25 + 0.05 * i);
    e.add(problem, exact, stepper);
  }
  SweepPoint r;
  r.q = e.q / e.q_scale, r.v = e.v / e.v_scale, r.lambda = e.lambda / e.lambda_scale;
  r.stats = stepper.statistics();
  r.mean_step = 1.0 / static_cast<double>(r.stats.steps);
  return r;
}

TEST(VariableStep, SecondOrderByToleranceSweep) {
  EXPECT_EQ(GeneralizedAlphaOptions{}.stepping, GeneralizedAlphaStepping::fixed);  // the default
  for (const auto change :
       {GeneralizedAlphaStepChange::rescale, GeneralizedAlphaStepChange::restart}) {
    std::vector<double> hs, eq, ev, el;
    for (const double rtol : {1e-4, 1e-5, 1e-6, 1e-7}) {
      GeneralizedAlphaOptions o = error_controlled(0.01, rtol);
      o.step_change = change;
      const SweepPoint r = pendulum_run(o);
      hs.push_back(r.mean_step), eq.push_back(r.q), ev.push_back(r.v), el.push_back(r.lambda);
      std::printf(
          "%s rtol %.0e: %ld steps (h %.2e … %.2e), %ld rejected, %ld changes; sup errors q %.3e "
          "v %.3e lambda %.3e\n",
          change == GeneralizedAlphaStepChange::rescale ? "rescale" : "restart", rtol,
          r.stats.steps, r.stats.min_step, r.stats.max_step, r.stats.rejected_steps,
          r.stats.step_size_changes, r.q, r.v, r.lambda);
      EXPECT_GT(r.stats.step_size_changes, 5);  // the step does vary
      EXPECT_LT(r.stats.min_step, 0.8 * r.stats.max_step);
    }
    const double pq = fitted_order(hs, eq), pv = fitted_order(hs, ev), pl = fitted_order(hs, el);
    std::printf("orders against the mean step: q %.3f v %.3f lambda %.3f\n", pq, pv, pl);
    EXPECT_GE(pq, 1.8);
    EXPECT_LE(pq, 2.2);
    EXPECT_GE(pv, 1.8);
    EXPECT_LE(pv, 2.2);
  }
}

// Outputs alternately h and 1.5 h apart with h_max = h: the steps alternate between h and 0.75 h,
// a change of h at every output.
TEST(VariableStep, StepChangeVariantsKeepTheirOrder) {
  const RigidPendulumSpec spec;
  const ExactPendulum exact(spec);
  const Model model = rigid_pendulum_model(spec);
  MultibodyProblem problem(model);
  struct Case {
    GeneralizedAlphaStepChange change;
    const char* name;
    double min_lambda_order, max_lambda_order;
    GeneralizedAlphaFormulation formulation = GeneralizedAlphaFormulation::index3;
  };
  for (const Case& c :
       {Case{GeneralizedAlphaStepChange::restart, "restart", 1.8, 2.2},
        Case{GeneralizedAlphaStepChange::rescale, "rescale", 0.0, 1.5},
        Case{GeneralizedAlphaStepChange::rescale_with_velocity, "rescale_with_velocity", 1.8, 2.2},
        Case{GeneralizedAlphaStepChange::rescale, "stabilized index 2, rescale", 1.8, 2.2,
             GeneralizedAlphaFormulation::stabilized_index2}}) {
    std::vector<double> hs, eq, ev, el;
    for (const double h : {0.02, 0.01, 0.005, 0.0025}) {
      GeneralizedAlphaOptions o = error_controlled(h, 1e3);  // the error never limits h
      o.controller.h_max = h;
      o.step_change = c.change;
      o.formulation = c.formulation;
      GeneralizedAlphaStepper stepper(problem, o);
      VecX q, v;
      exact.state(0.25, q, v);
      stepper.initialize(0.25, q, v);
      testing::PendulumErrors e;
      double t = 0.25;
      for (int i = 0; t < 1.25; ++i) {
        t += i % 2 == 0 ? h : 1.5 * h;
        stepper.advance_to(t);
        e.add(problem, exact, stepper);
      }
      hs.push_back(h), eq.push_back(e.q), ev.push_back(e.v), el.push_back(e.lambda);
      EXPECT_GT(stepper.statistics().step_size_changes, 20);
    }
    const double pq = fitted_order(hs, eq), pv = fitted_order(hs, ev), pl = fitted_order(hs, el);
    std::printf("%s: orders q %.3f v %.3f lambda %.3f\n", c.name, pq, pv, pl);
    EXPECT_GE(pq, 1.8);
    EXPECT_GE(pv, 1.8);
    EXPECT_GE(pl, c.min_lambda_order);
    EXPECT_LE(pl, c.max_lambda_order);
  }
}

// --- unresolved stiff modes ----------------------------------------------------------------------

/// Two uncoupled unit-mass oscillators, q_i'' + ω_i² q_i = 0, unconstrained: a slow mode and a
/// stiff one (ω_1 = 2π, ω_2 = 1e5 rad/s), both excited, the stiff one at an amplitude (1e-7 m)
/// below the absolute tolerance: unresolved and not of interest, as the axial and contact modes of
/// the capture ropes.
class TwoOscillators final : public UnconstrainedProblem {
 public:
  TwoOscillators() : pattern_(2), q0_(2), v0_(2) {
    pattern_.add(0, 0);
    pattern_.add(1, 1);
    pattern_.freeze();
    q0_ << 1.0, 1e-7;
    v0_.setZero();
  }
  Index coordinate_count() const override { return 2; }
  const SparsityPattern& iteration_pattern() const override { return pattern_; }
  void residual(double, std::span<const double> q, std::span<const double>,
                std::span<const double> a, std::span<const double>, std::span<double> r) override {
    for (int i = 0; i < 2; ++i) r[i] = a[i] + omega2_[i] * q[i];
  }
  void iteration_matrix(double, std::span<const double>, std::span<const double>,
                        std::span<const double>, std::span<const double>, const MatrixWeights& w,
                        std::span<double> values) override {
    for (int i = 0; i < 2; ++i) values[i] = w.w_a + w.w_q * omega2_[i];
  }
  double energy(double, std::span<const double> q, std::span<const double> v) override {
    return 0.5 * (v[0] * v[0] + v[1] * v[1] + omega2_[0] * q[0] * q[0] + omega2_[1] * q[1] * q[1]);
  }
  std::string describe_row(Index i) const override { return "oscillator " + std::to_string(i); }
  const VecX& initial_coordinates() const override { return q0_; }
  const VecX& initial_velocities() const override { return v0_; }

 private:
  SparsityPattern pattern_;
  VecX q0_, v0_;
  double omega2_[2] = {4.0 * M_PI * M_PI, 1e10};
};

// The unfiltered estimate of an unresolved mode of amplitude X is ≈ C h²ω² X: it sees the stiff
// mode and resolves it; once ωh ≈ 1 the scheme no longer damps it, so it stays excited and h stays
// small (here until the numerical damping at the reduced h has removed it). The filter divides by 1
// + βh²ω²(1 − α_f)/(1 − α_m), leaving ≈ (C/β)X(1 − α_m)/(1 − α_f) ≈ 0.34 X: the stiff mode counts
// with its amplitude, and the slow mode sets h.
TEST(VariableStep, FilteredEstimateIgnoresUnresolvedStiffModes) {
  TwoOscillators problem;
  long steps[2] = {0, 0};
  double slow_error[2] = {0, 0}, min_step[2] = {0, 0};
  for (const bool filter : {true, false}) {
    GeneralizedAlphaOptions o = tight(1e-3, 0.8);
    o.stepping = GeneralizedAlphaStepping::error_controlled;
    o.controller.rtol = 1e-4;
    o.controller.atol = 1e-6;
    o.filter_error_estimate = filter;
    GeneralizedAlphaStepper stepper(problem, o);
    stepper.initialize(0.0);
    stepper.advance_to(1.0);
    steps[filter ? 0 : 1] = stepper.statistics().steps;
    min_step[filter ? 0 : 1] = stepper.statistics().min_step;
    slow_error[filter ? 0 : 1] = std::abs(stepper.positions()[0] - std::cos(2.0 * M_PI));
    std::printf("filter %d: %ld steps (h %.2e … %.2e), slow-mode error %.2e, stiff mode %.2e\n",
                int(filter), stepper.statistics().steps, stepper.statistics().min_step,
                stepper.statistics().max_step, slow_error[filter ? 0 : 1], stepper.positions()[1]);
  }
  // Measured: 78 steps, h ≥ 1e-3 (filtered) against 141 steps, h down to 9e-5 (unfiltered, until
  // the numerical damping at ωh ≈ 9 has removed the stiff mode).
  EXPECT_LT(10 * steps[0], 7 * steps[1]);
  EXPECT_GE(min_step[0], 0.999e-3);
  EXPECT_LT(min_step[1], 2e-4);
  EXPECT_LT(slow_error[0], 1e-3);  // the slow mode to the tolerance's order
}

// --- failures and the active-set refresh
// ----------------------------------------------------------

TEST(VariableStep, ReportsWhenHminIsReached) {
  const Model model = rigid_pendulum_model({});
  MultibodyProblem problem(model);
  GeneralizedAlphaOptions o = error_controlled(0.1, 1e-9);
  o.controller.h_min = 0.05;
  GeneralizedAlphaStepper stepper(problem, o);
  stepper.initialize(0.0);
  try {
    stepper.advance_to(1.0);
    FAIL() << "no failure reported";
  } catch (const SolverError& e) {
    EXPECT_NE(std::string(e.what()).find("h_min"), std::string::npos) << e.what();
    std::printf("reported: %s\n", e.what());
  }
}

TEST(VariableStep, ActiveSetRefreshCountsAndKeepsTheSolution) {
  const Model model = cable_impact_model(1.0, 0.0);
  VecX q[2];
  long refreshes[2] = {0, 0};
  for (const bool refresh : {false, true}) {
    MultibodyProblem problem(model);
    GeneralizedAlphaOptions o;
    o.step_size = 1e-4;
    o.refresh_on_active_set_change = refresh;
    GeneralizedAlphaStepper stepper(problem, o);
    stepper.initialize(0.0);
    stepper.advance_to(0.02);
    q[refresh] = stepper.positions();
    refreshes[refresh] = stepper.statistics().active_set_refreshes;
    std::printf("refresh %d: %ld steps, %ld Newton iterations, %ld factorizations, %ld refreshes\n",
                int(refresh), stepper.statistics().steps, stepper.statistics().newton_iterations,
                stepper.statistics().factorizations, refreshes[refresh]);
  }
  EXPECT_EQ(refreshes[0], 0);
  EXPECT_GT(refreshes[1], 0);
  EXPECT_LT((q[0] - q[1]).lpNorm<Eigen::Infinity>(), 1e-6);
}

}  // namespace
}  // namespace ancf
