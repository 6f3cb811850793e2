// Adapter: a Model's equations of motion as the abstract SecondOrderProblem the time integrators
// see (DESIGN §6, §7). Everything goes through the public functions of assembly.hpp, so the
// integrators and the static solver share one residual and one iteration matrix.
#pragma once

#include "ancf/core/second_order_problem.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/contact_pattern.hpp"

namespace ancf {

/// q, v, a = q'' in the model's coordinate numbering, λ its constraint rows; SI units.
/// residual = [M a + F(q, v) − Q(q, v, t) + Φ_qᵀλ; Φ(q, t)] (assemble_residual with load factor 1),
/// iteration_matrix = assemble_iteration_matrix in the contact pattern (the model's pattern plus
/// the coupling blocks of the contact pairs that are near, contact_pattern.hpp).
/// Ownership: keeps a reference to `model`, which must outlive the problem; owns a Workspace, a
/// ContactPattern and a SystemState used as scratch (no heap allocation per call while the
/// pattern does not change).
class MultibodyProblem final : public SecondOrderProblem {
 public:
  explicit MultibodyProblem(const Model& model, ContactPatternOptions contact = {});

  [[nodiscard]] Index coordinate_count() const override { return model_.coordinate_count(); }
  [[nodiscard]] Index multiplier_count() const override { return model_.multiplier_count(); }
  [[nodiscard]] const SparsityPattern& iteration_pattern() const override {
    return contact_.pattern();
  }
  /// ContactPattern::update at (t, q, v).
  bool update_pattern(double t, std::span<const double> q, std::span<const double> v,
                      double horizon) override;

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
  /// Commits the rod history at the accepted state (rod_history.hpp).
  void commit_step(double, std::span<const double> q, std::span<const double>) override {
    commit_rod_history(model_, q, workspace_.rods, workspace_.rod_frame_turn);
  }
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
  [[nodiscard]] const ContactPattern& contact_pattern() const { return contact_; }
  /// The scratch workspace, for its counters (contact samples, kernel times).
  [[nodiscard]] const Workspace& workspace() const { return workspace_; }
  /// Tangent of the cable elements in the iteration matrix (CableTangent; default exact). The
  /// residual does not depend on it.
  void set_cable_tangent(CableTangent tangent) { workspace_.cable_tangent = tangent; }
  /// Turn [rad] ≥ 0 of a rod node's tangent after which a commit updates the node's frame
  /// (default kRodCommitTurn; 0: every step). See rod_history.hpp and docs/rod.md, "Frame updates".
  void set_rod_frame_turn(double turn) { workspace_.rod_frame_turn = turn; }
  /// Force-only cable kernel of the residual (CableKernel; default invariant).
  void set_cable_force_kernel(CableKernel kernel) { workspace_.cable_force_kernel = kernel; }
  /// Stiffness kernel of undamped cables in the iteration matrix (CableKernel; default invariant).
  void set_cable_stiffness_kernel(CableKernel kernel) {
    workspace_.cable_stiffness_kernel = kernel;
  }
  /// Wall time spent in residual() and in iteration_matrix() [s], cumulative.
  [[nodiscard]] double residual_seconds() const { return residual_seconds_; }
  [[nodiscard]] double matrix_seconds() const { return matrix_seconds_; }

 private:
  // Copy the given vectors into state_ (same sizes, so no allocation after the first call).
  void load(double t, std::span<const double> q, std::span<const double> v,
            std::span<const double> a, std::span<const double> lambda);
  const Model& model_;
  SystemState state_;
  Workspace workspace_;
  ContactPattern contact_;
  double residual_seconds_ = 0.0, matrix_seconds_ = 0.0;
};

}  // namespace ancf
