#include "ancf/system/multibody_problem.hpp"

#include "ancf/core/stopwatch.hpp"

namespace ancf {

MultibodyProblem::MultibodyProblem(const Model& model, ContactPatternOptions contact)
    : model_(model),
      state_(SystemState::initial(model)),
      workspace_(model),
      contact_(model, contact) {}

bool MultibodyProblem::update_pattern(double t, std::span<const double> q,
                                      std::span<const double> v, double horizon) {
  load(t, q, v, {}, {});
  return contact_.update(state_, horizon, workspace_);
}

void MultibodyProblem::load(double t, std::span<const double> q, std::span<const double> v,
                            std::span<const double> a, std::span<const double> lambda) {
  const Index n = model_.coordinate_count(), m = model_.multiplier_count();
  state_.t = t;
  state_.q = Eigen::Map<const VecX>(q.data(), n);
  if (!v.empty()) state_.v = Eigen::Map<const VecX>(v.data(), n);
  if (!a.empty()) state_.a = Eigen::Map<const VecX>(a.data(), n);
  if (!lambda.empty()) state_.lambda = Eigen::Map<const VecX>(lambda.data(), m);
}

void MultibodyProblem::residual(double t, std::span<const double> q, std::span<const double> v,
                                std::span<const double> a, std::span<const double> lambda,
                                std::span<double> r) {
  const auto start = TickClock::now();
  load(t, q, v, a, lambda);
  assemble_residual(model_, state_, 1.0, workspace_, r);
  residual_seconds_ += TickClock::seconds_since(start);
}

void MultibodyProblem::iteration_matrix(double t, std::span<const double> q,
                                        std::span<const double> v, std::span<const double> a,
                                        std::span<const double> lambda, const MatrixWeights& w,
                                        std::span<double> values) {
  const auto start = TickClock::now();
  load(t, q, v, a, lambda);
  assemble_iteration_matrix(model_, state_, IterationWeights{w.w_q, w.w_v, w.w_a, 1.0}, contact_,
                            workspace_, values);
  matrix_seconds_ += TickClock::seconds_since(start);
}

void MultibodyProblem::constraints(double t, std::span<const double> q, std::span<double> phi) {
  // Φ alone, without the element loop of assemble_residual: each row is u·w + c
  // (dot_constraint.hpp).
  const auto frames = workspace_.frames_at(model_, t);
  const Index dot_rows = static_cast<Index>(model_.rows().size());
  for (Index i = 0; i < dot_rows; ++i) {
    const DotConstraintRow& row = model_.rows()[i];
    phi[i] = evaluate(row.u, q, {}, frames).value.dot(evaluate(row.w, q, {}, frames).value) + row.c;
  }
  RodTwistRowValues tv;  // twist rows (rod_twist_constraint.hpp) under the committed history
  for (std::size_t k = 0; k < model_.twist_rows().size(); ++k) {
    const RodTwistRowData& tr = model_.twist_rows()[k];
    evaluate(tr.row, workspace_.rods.frames[tr.cable][tr.node], q, {}, frames, tv);
    phi[dot_rows + static_cast<Index>(k)] = tv.phi;
  }
}

void MultibodyProblem::velocity_constraint(double t, std::span<const double> q,
                                           std::span<const double> v, std::span<double> out) {
  load(t, q, v, {}, {});
  assemble_velocity_constraint(model_, state_, workspace_, out);
}

void MultibodyProblem::acceleration_rhs(double t, std::span<const double> q,
                                        std::span<const double> v, std::span<double> gamma) {
  load(t, q, v, {}, {});
  assemble_acceleration_rhs(model_, state_, workspace_, gamma);
}

double MultibodyProblem::energy(double t, std::span<const double> q, std::span<const double> v) {
  load(t, q, v, {}, {});
  return energies(model_, state_, workspace_).total();
}

}  // namespace ancf
