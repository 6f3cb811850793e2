// Global residual, iteration matrix and energies of a Model, written into preallocated storage.
#pragma once

#include <span>

#include "ancf/system/model.hpp"

namespace ancf {

/// State of the system at time t: coordinates q [m, -], velocities v = q', accelerations a = q''
/// and multipliers λ. Sizes: q, v, a: model.coordinate_count(); λ: model.multiplier_count().
struct SystemState {
  double t = 0.0;
  VecX q, v, a, lambda;

  /// Zero state sized for `model`, q and v taken from the model's initial values.
  static SystemState initial(const Model& model);
};

/// Weights of the iteration matrix w_q ∂R/∂q + w_v ∂R/∂v + w_a ∂R/∂a of the dynamic rows.
struct IterationWeights {
  double w_q = 1.0;
  double w_v = 0.0;
  double w_a = 0.0;
};

/// Residual of the equations of motion and constraints (DESIGN §1, S6):
///   rows [0, n):   M a + F(q, v) − s·Q + Φ_qᵀ λ
///   rows [n, n+m): Φ(q)
/// with s the load factor (1 for dynamics). `r` has model.system_size() entries.
void assemble_residual(const Model& model, const SystemState& state, double load_factor,
                       std::span<double> r);

/// Values of [w_q K + w_v D + w_a M, Φ_qᵀ; Φ_q, 0] in model.pattern(), with K = ∂(F − sQ +
/// Φ_qᵀλ)/∂q and D = ∂F/∂v. `values` has model.pattern().nonzeros() entries.
void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& weights, std::span<double> values);

/// Strain energy of all cables [J].
[[nodiscard]] double strain_energy(const Model& model, const VecX& q);
/// Potential of the constant loads, −Qᵀq [J] (gravity and dead loads).
[[nodiscard]] double load_potential(const Model& model, const VecX& q);
/// Kinetic energy ½ vᵀ M v [J].
[[nodiscard]] double kinetic_energy(const Model& model, const VecX& v);

}  // namespace ancf
