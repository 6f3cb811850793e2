// Adapter: a Model's equations of motion as the abstract SecondOrderProblem the time integrators
// see (DESIGN §6, §7). Everything goes through the public functions of assembly.hpp, so the
// integrators and the static solver share one residual and one iteration matrix.
#pragma once

#include "ancf/core/second_order_problem.hpp"
#include "ancf/system/assembly.hpp"

namespace ancf {

/// q, v, a = q'' in the model's coordinate numbering, λ its constraint rows; SI units.
/// residual = [M a + F(q, v) − Q(q, v, t) + Φ_qᵀλ; Φ(q, t)] (assemble_residual with load factor 1),
/// iteration_matrix = assemble_iteration_matrix in model.pattern().
/// Ownership: keeps a reference to `model`, which must outlive the problem; owns a Workspace and
/// a SystemState used as scratch (no heap allocation per call).
class MultibodyProblem final : public SecondOrderProblem {
 public:
  explicit MultibodyProblem(const Model& model);

  [[nodiscard]] Index coordinate_count() const override { return model_.coordinate_count(); }
  [[nodiscard]] Index multiplier_count() const override { return model_.multiplier_count(); }
  [[nodiscard]] const SparsityPattern& iteration_pattern() const override {
    return model_.pattern();
  }

  void residual(double t, std::span<const double> q, std::span<const double> v,
                std::span<const double> a, std::span<const double> lambda,
                std::span<double> r) override;
  void iteration_matrix(double t, std::span<const double> q, std::span<const double> v,
                        std::span<const double> a, std::span<const double> lambda,
                        const MatrixWeights& weights, std::span<double> values) override;
  void constraints(double t, std::span<const double> q, std::span<double> phi) override;
  void velocity_constraint(double t, std::span<const double> q, std::span<const double> v,
                           std::span<double> out) override;
  void acceleration_rhs(double t, std::span<const double> q, std::span<const double> v,
                        std::span<double> gamma) override;
  /// Kinetic + strain + spring + constant-load potential (assembly.hpp energies()).
  [[nodiscard]] double energy(double t, std::span<const double> q,
                              std::span<const double> v) override;
  [[nodiscard]] std::string describe_row(Index i) const override { return model_.describe_row(i); }
  /// Hash of the active contact samples of the last residual() (Workspace).
  [[nodiscard]] std::uint64_t active_set_signature() const override {
    return workspace_.active_contact_signature;
  }
  [[nodiscard]] const VecX& initial_coordinates() const override {
    return model_.initial_coordinates();
  }
  [[nodiscard]] const VecX& initial_velocities() const override {
    return model_.initial_velocities();
  }

  [[nodiscard]] const Model& model() const { return model_; }

 private:
  // Copy the given vectors into state_ (same sizes, so no allocation after the first call).
  void load(double t, std::span<const double> q, std::span<const double> v,
            std::span<const double> a, std::span<const double> lambda);
  const Model& model_;
  SystemState state_;
  Workspace workspace_;
};

}  // namespace ancf
