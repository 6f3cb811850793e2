// The abstract constrained second-order problem the time integrators see (DESIGN §6, §7):
//
//   M q'' + F(q, q', t) − Q(q, q', t) + Φ_qᵀ λ = 0,     Φ(q, t) = 0,
//
// with M constant. No elements, no bodies: only vectors and one frozen sparse pattern. The
// generalized-α stepper (and any other integrator) is written against this interface, so it can
// be tested on anything that implements it.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/core/types.hpp"

namespace ancf {

/// Weights of the dynamic block of the iteration matrix, w_q ∂R/∂q + w_v ∂R/∂q' + w_a ∂R/∂q''
/// (R the dynamic residual; ∂R/∂q'' = M). Generalized-α: (1, γ', β'); statics: (1, 0, 0);
/// the index-1 solve for q'' and λ: (0, 0, 1).
struct MatrixWeights {
  double w_q = 1.0;
  double w_v = 0.0;
  double w_a = 0.0;
};

/// n coordinates q (velocities v = q', accelerations a = q''), m multipliers λ. Units are those of
/// the implementation (SI for the multibody model). All spans have the documented sizes; the
/// implementation may keep scratch state, so calls are not thread-safe. The problem owns its data.
class SecondOrderProblem {
 public:
  virtual ~SecondOrderProblem() = default;

  /// n: number of coordinates.
  [[nodiscard]] virtual Index coordinate_count() const = 0;
  /// m: number of constraint rows / multipliers.
  [[nodiscard]] virtual Index multiplier_count() const = 0;
  /// n + m.
  [[nodiscard]] Index system_size() const { return coordinate_count() + multiplier_count(); }

  /// Frozen (n + m)² pattern of [w_q K + w_v D + w_a M, Φ_qᵀ; Φ_q, 0]. It changes only in
  /// update_pattern(); the reference stays valid (the object is updated in place).
  [[nodiscard]] virtual const SparsityPattern& iteration_pattern() const = 0;

  /// Bring iteration_pattern() up to date for matrices evaluated at (t, q, v) that are to serve
  /// for about `horizon` seconds (a contact pattern follows the pairs that are near, DESIGN §5).
  /// Returns true if the pattern changed: the caller then sizes its value arrays to the new
  /// nonzeros() and re-runs the symbolic analysis (KluSolver::analyze) before it factorizes.
  /// Integrators call it before every matrix evaluation; it allocates only when the pattern
  /// changes. Default: the pattern never changes.
  virtual bool update_pattern(double /*t*/, std::span<const double> /*q*/,
                              std::span<const double> /*v*/, double /*horizon*/) {
    return false;
  }

  /// r (n + m) = [M a + F(q, v, t) − Q(q, v, t) + Φ_qᵀλ; Φ(q, t)]. q, v, a: n; λ: m.
  /// May throw std::domain_error: the state is not evaluable here (e.g. a rod tangent turned
  /// against its committed frame); generalized-α takes the iterate as one with a non-finite
  /// residual and retries with a smaller step. Anything else is fatal. The same holds for
  /// iteration_matrix(), constraints() and velocity_constraint().
  virtual void residual(double t, std::span<const double> q, std::span<const double> v,
                        std::span<const double> a, std::span<const double> lambda,
                        std::span<double> r) = 0;

  /// Values (one per pattern non-zero) of [w_q K + w_v D + w_a M, Φ_qᵀ; Φ_q, 0] with
  /// K = ∂(F − Q + Φ_qᵀλ)/∂q and D = ∂(F − Q)/∂v at (t, q, v, λ). The constraint blocks carry no
  /// weight. `a` is passed for implementations whose matrix depends on it (the multibody one's
  /// does not: M is constant).
  virtual void iteration_matrix(double t, std::span<const double> q, std::span<const double> v,
                                std::span<const double> a, std::span<const double> lambda,
                                const MatrixWeights& weights, std::span<double> values) = 0;

  /// Φ(q, t) (m).
  virtual void constraints(double t, std::span<const double> q, std::span<double> phi) = 0;
  /// Φ_q v + Φ_t (m): the velocity-level constraint.
  virtual void velocity_constraint(double t, std::span<const double> q, std::span<const double> v,
                                   std::span<double> out) = 0;
  /// γ = −[(Φ_q v)_q v + 2Φ_qt v + Φ_tt] (m), so that Φ_q a = γ on the constraint manifold.
  virtual void acceleration_rhs(double t, std::span<const double> q, std::span<const double> v,
                                std::span<double> gamma) = 0;

  /// Total mechanical energy (kinetic + potential of conservative forces) for monitoring [J].
  [[nodiscard]] virtual double energy(double t, std::span<const double> q,
                                      std::span<const double> v) = 0;

  /// A cheap signature of the set of active unilateral contacts (penalty samples with g < 0) at
  /// the last residual() call; equal signatures mean (up to hash collisions) the same set. An
  /// integrator that keeps an iteration matrix compares it to decide whether that matrix still has
  /// the contact stiffness of the current iterate. Default: 0 (no contacts).
  [[nodiscard]] virtual std::uint64_t active_set_signature() const { return 0; }

  /// Called with each accepted step's state (t, q, v), before the next step is attempted: an
  /// implementation with history commits it here. Newton iterates and rejected steps are never
  /// passed, so nothing needs rolling back. Default: nothing.
  virtual void commit_step(double /*t*/, std::span<const double> /*q*/,
                           std::span<const double> /*v*/) {}
  /// Human-readable name of unknown / residual row i (i < n: a coordinate, else a constraint row).
  [[nodiscard]] virtual std::string describe_row(Index i) const = 0;

  /// Initial coordinates and velocities (n each) as given by the problem; they need not satisfy
  /// the constraints to round-off (integrators project them).
  [[nodiscard]] virtual const VecX& initial_coordinates() const = 0;
  [[nodiscard]] virtual const VecX& initial_velocities() const = 0;
};

}  // namespace ancf
