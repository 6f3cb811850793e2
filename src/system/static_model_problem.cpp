#include "ancf/system/static_model_problem.hpp"

namespace ancf {

StaticModelProblem::StaticModelProblem(const Model& model)
    : model_(model),
      workspace_(model),
      contact_(model, ContactPatternOptions{.policy = ContactPatternPolicy::all}) {
  state_ = SystemState::initial(model);
  state_.v.setZero();  // statics: no damping forces
  state_.a.resize(0);  // and no inertia term
}

void StaticModelProblem::load_state(std::span<const double> y) {
  const Index n = model_.coordinate_count();
  state_.q = Eigen::Map<const VecX>(y.data(), n);
  state_.lambda = Eigen::Map<const VecX>(y.data() + n, model_.multiplier_count());
}

void StaticModelProblem::residual(std::span<const double> y, double load_factor,
                                  std::span<double> r) {
  load_state(y);
  assemble_residual(model_, state_, load_factor, workspace_, r);
}

void StaticModelProblem::jacobian(std::span<const double> y, double load_factor,
                                  std::span<double> values) {
  load_state(y);
  assemble_iteration_matrix(model_, state_, IterationWeights{1.0, 0.0, 0.0, load_factor},
                            contact_, workspace_, values);
}

VecX StaticModelProblem::initial_guess() const {
  VecX y = VecX::Zero(size());
  y.head(model_.coordinate_count()) = model_.initial_coordinates();
  return y;
}

}  // namespace ancf
