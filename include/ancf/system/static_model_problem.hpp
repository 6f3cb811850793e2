// Adapter: a Model's equilibrium equations as the abstract StaticProblem the solvers see.
#pragma once

#include "ancf/core/static_problem.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/contact_pattern.hpp"

namespace ancf {

/// y = [q; λ]; R(y, s) = [F(q) − sQ + Φ_qᵀλ; Φ(q)], ∂R/∂y in the model's pattern plus every
/// candidate contact coupling block (ContactPatternPolicy::all: a static solve keeps its pattern).
/// Ownership: keeps a reference to `model`, which must outlive the problem.
class StaticModelProblem final : public StaticProblem {
 public:
  explicit StaticModelProblem(const Model& model);

  [[nodiscard]] Index size() const override { return model_.system_size(); }
  [[nodiscard]] const SparsityPattern& jacobian_pattern() const override {
    return contact_.pattern();
  }
  [[nodiscard]] Index coordinate_count() const override { return model_.coordinate_count(); }
  void residual(std::span<const double> y, double load_factor, std::span<double> r) override;
  void jacobian(std::span<const double> y, double load_factor, std::span<double> values) override;
  [[nodiscard]] std::string describe_row(Index i) const override { return model_.describe_row(i); }
  /// Commits the rod history at the converged state (rod_history.hpp).
  void commit(std::span<const double> y) override {
    commit_rod_history(model_, y, workspace_.rods, kRodCommitTurn);
  }
  [[nodiscard]] const Workspace& workspace() const { return workspace_; }

  /// y from the model's initial configuration, λ = 0.
  [[nodiscard]] VecX initial_guess() const;

 private:
  void load_state(std::span<const double> y);
  const Model& model_;
  SystemState state_;  // q, λ copied from y; v = 0 and no inertia
  Workspace workspace_;
  ContactPattern contact_;
};

}  // namespace ancf
