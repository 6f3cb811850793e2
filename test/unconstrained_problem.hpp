// Test helper: a SecondOrderProblem without constraints (m = 0), for small hand-written problems
// that only need their residual, iteration matrix, energy and initial state (test_step_control's
// two oscillators, test_generalized_alpha's oscillator with a time wall).
#pragma once

#include <span>

#include "ancf/core/second_order_problem.hpp"

namespace ancf {

class UnconstrainedProblem : public SecondOrderProblem {
 public:
  Index multiplier_count() const override { return 0; }
  void constraints(double, std::span<const double>, std::span<double>) override {}
  void velocity_constraint(double, std::span<const double>, std::span<const double>,
                           std::span<double>) override {}
  void acceleration_rhs(double, std::span<const double>, std::span<const double>,
                        std::span<double>) override {}
};

}  // namespace ancf
