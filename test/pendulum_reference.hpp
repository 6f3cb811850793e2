// Shared by the generalized-α tests: the exact rigid pendulum (elliptic functions), the exact
// multipliers of an exact state from the index-1 system, and Newton options tight enough that
// only discretization errors are measured.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "ancf/core/klu_solver.hpp"
#include "ancf/core/second_order_problem.hpp"
#include "ancf/physics/rigid_body.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/generalized_alpha.hpp"

namespace ancf::testing {

/// Jacobi elliptic functions sn, cn, dn of (u, m = k²) by the descending Landen / AGM scale
/// (Abramowitz & Stegun 16.4).
inline void jacobi_sn_cn_dn(double u, double m, double& sn, double& cn, double& dn) {
  double a[16], c[16];
  a[0] = 1.0;
  double b = std::sqrt(1.0 - m);
  c[0] = std::sqrt(m);
  int n = 0;
  while (std::abs(c[n]) > 1e-17 && n < 15) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = std::sqrt(a[n] * b);
    ++n;
  }
  double phi = std::ldexp(1.0, n) * a[n] * u, phi_next = phi;
  for (int j = n; j > 0; --j) {
    phi_next = phi;
    phi = 0.5 * (phi + std::asin(c[j] / a[j] * std::sin(phi)));
  }
  sn = std::sin(phi);
  cn = std::cos(phi);
  dn = n > 0 ? cn / std::cos(phi_next - phi) : 1.0;
}

/// Exact motion of the rod pendulum of rigid_pendulum_model: θ'' = −ω₀² sin θ, θ(0) = θ₀,
/// θ'(0) = 0: sin(θ/2) = k sn(K − ω₀t, k), θ' = −2kω₀ cn(K − ω₀t, k), k = sin(θ₀/2).
struct ExactPendulum {
  RigidPendulumSpec spec;
  double omega0, k, big_k;
  explicit ExactPendulum(const RigidPendulumSpec& s) : spec(s) {
    omega0 = std::sqrt(1.5 * s.gravity / s.length);
    k = std::sin(0.5 * s.initial_angle);
    big_k = rigid_pendulum_period(s) * omega0 / 4.0;
  }
  void state(double t, VecX& q, VecX& v) const {
    double sn, cn, dn;
    jacobi_sn_cn_dn(big_k - omega0 * t, k * k, sn, cn, dn);
    const double theta = 2.0 * std::asin(k * sn), theta_dot = -2.0 * k * omega0 * cn;
    // Body x axis (sin θ, 0, −cos θ): rotation by π/2 − θ about +y, angular velocity −θ' ŷ.
    const Mat3 rot =
        Eigen::AngleAxisd(0.5 * std::numbers::pi - theta, Vec3::UnitY()).toRotationMatrix();
    q = body_coordinates(Vec3::Zero(), rot);
    v = body_velocities(rot, Vec3::Zero(), -theta_dot * Vec3::UnitY());
  }
};

/// q'' and λ from the index-1 system [M Φ_qᵀ; Φ_q 0][q''; λ] = [Q − F; γ] at (t, q, v): the exact
/// multipliers of an exact state, computed independently of the stepper.
inline void index1_solution(SecondOrderProblem& p, double t, const VecX& q, const VecX& v,
                            VecX& acc, VecX& lambda) {
  const Index n = p.coordinate_count(), m = p.multiplier_count();
  VecX zero_a = VecX::Zero(n), zero_l = VecX::Zero(m), r(n + m),
       values(p.iteration_pattern().nonzeros());
  p.residual(t, as_span(q), as_span(v), as_span(zero_a), as_span(zero_l), as_span(r));
  p.iteration_matrix(t, as_span(q), as_span(v), as_span(zero_a), as_span(zero_l), {0.0, 0.0, 1.0},
                     as_span(values));
  KluSolver klu(p.iteration_pattern());
  klu.factor(as_span(values));
  VecX rhs(n + m), gamma(m);
  p.acceleration_rhs(t, as_span(q), as_span(v), as_span(gamma));
  rhs << -r.head(n), gamma;
  klu.solve(as_span(rhs));
  acc = rhs.head(n);
  lambda = rhs.tail(m);
}

inline GeneralizedAlphaOptions tight(double h, double rho) {
  GeneralizedAlphaOptions o;
  o.step_size = h;
  o.rho_infinity = rho;
  // Newton errors far below the discretization errors of every step size used (≳ 1e-7), yet
  // above the round-off floor of the multipliers (≈ ε·cond of the scaled matrix).
  o.rtol = 1e-11;
  o.atol_position = 1e-13;
  o.atol_velocity = 1e-11;
  o.atol_multiplier = 1e-11;
  o.newton = NewtonStrategy::full;
  return o;
}

/// Sup-norm errors of a stepper's q, v and λ against the exact pendulum, over the output times at
/// which add() is called, and the sup norms of the exact values (for relative errors).
struct PendulumErrors {
  double q = 0, v = 0, lambda = 0;
  double q_scale = 0, v_scale = 0, lambda_scale = 0;
  void add(SecondOrderProblem& problem, const ExactPendulum& exact,
           const GeneralizedAlphaStepper& stepper) {
    VecX qe, ve, acc, le;
    exact.state(stepper.time(), qe, ve);
    index1_solution(problem, stepper.time(), qe, ve, acc, le);
    q = std::max(q, (stepper.positions() - qe).lpNorm<Eigen::Infinity>());
    v = std::max(v, (stepper.velocities() - ve).lpNorm<Eigen::Infinity>());
    lambda = std::max(lambda, (stepper.multipliers() - le).lpNorm<Eigen::Infinity>());
    q_scale = std::max(q_scale, qe.lpNorm<Eigen::Infinity>());
    v_scale = std::max(v_scale, ve.lpNorm<Eigen::Infinity>());
    lambda_scale = std::max(lambda_scale, le.lpNorm<Eigen::Infinity>());
  }
};

}  // namespace ancf::testing
