// Step-size controller (step_controller.hpp, docs/time_step_control.md).
#include "ancf/solvers/step_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ancf {

StepController::StepController(const StepControllerOptions& o, int order)
    : options_(o), exponent_(1.0 / (order + 1.0)) {
  const auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("step controller: ") + what);
  };
  require(order >= 1, "the order of the method must be >= 1");
  require(o.rtol > 0.0 && o.atol > 0.0, "rtol and atol must be positive");
  require(o.h_min > 0.0 && o.h_max >= 0.0, "h_min must be positive and h_max >= 0 (0: none)");
  require(o.h_max == 0.0 || o.h_max >= o.h_min, "h_max must be >= h_min");
  require(o.safety > 0.0 && o.safety <= 1.0, "safety must lie in (0, 1]");
  require(o.max_growth >= 1.0, "max_growth must be >= 1");
  require(o.max_shrink > 0.0 && o.max_shrink < 1.0, "max_shrink must lie in (0, 1)");
  require(o.failure_shrink > 0.0 && o.failure_shrink < 1.0, "failure_shrink must lie in (0, 1)");
  require(o.failure_ceiling > 0.0 && o.failure_ceiling <= 1.0,
          "failure_ceiling must lie in (0, 1]");
  require(o.ceiling_growth >= 1.0, "ceiling_growth must be >= 1");
  require(o.easy_rate > 0.0 && o.easy_rate < 1.0, "easy_rate must lie in (0, 1)");
  require(o.growth_threshold >= 1.0 && o.growth_threshold <= o.max_growth,
          "growth_threshold must lie in [1, max_growth]");
}

double StepController::error_norm(std::span<const double> e, std::span<const double> y0,
                                  std::span<const double> y1) const {
  if (e.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    const double w = options_.atol + options_.rtol * std::max(std::abs(y0[i]), std::abs(y1[i]));
    const double x = e[i] / w;
    sum += x * x;
  }
  return std::sqrt(sum / static_cast<double>(e.size()));
}

double StepController::clamp(double h) const {
  if (options_.h_max > 0.0) h = std::min(h, options_.h_max);
  return std::max(h, options_.h_min);
}

StepDecision StepController::decide(double h, double err, double rate) {
  if (!(err <= 1.0)) {
    // Rejected (NaN and ∞ included): shrink by the asymptotic model, at least to max_shrink·h.
    const double ratio =
        std::isfinite(err) ? options_.safety * std::pow(err, -exponent_) : options_.max_shrink;
    after_rejection_ = true;
    return {false, clamp(h * std::clamp(ratio, options_.max_shrink, 1.0))};
  }
  // Accepted. err = 0 (a step that the estimate cannot see) allows the largest growth.
  const double floor_err = std::max(err, 1e-10);
  double ratio = options_.safety * std::pow(floor_err, -exponent_);
  if (options_.pi && previous_error_ > 0.0)
    // Gustafsson's PI form with k_I = 0.7/(p+1), k_P = 0.4/(p+1).
    ratio = options_.safety * std::pow(floor_err, -0.7 * exponent_) *
            std::pow(previous_error_ / floor_err, 0.4 * exponent_);
  previous_error_ = floor_err;
  ratio = std::min(ratio, after_rejection_ ? 1.0 : options_.max_growth);
  after_rejection_ = false;
  // Hysteresis: grow only by a worthwhile factor; shrink whenever the estimate asks for it.
  if (ratio >= 1.0 && ratio < options_.growth_threshold) ratio = 1.0;
  ratio = std::max(ratio, options_.max_shrink);
  double h_next = h * ratio;
  if (ceiling_ > 0.0) {
    h_next = std::min(h_next, ceiling_);
    if (rate <= options_.easy_rate) ceiling_ *= options_.ceiling_growth;
  }
  return {true, clamp(h_next)};
}

double StepController::after_failure(double h) {
  after_rejection_ = true;
  ceiling_ = options_.failure_ceiling * h;
  return clamp(h * options_.failure_shrink);
}

void StepController::reset() {
  previous_error_ = -1.0;
  after_rejection_ = false;
  ceiling_ = 0.0;
}

}  // namespace ancf
