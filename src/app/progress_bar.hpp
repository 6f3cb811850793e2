// A one-line progress bar on stderr: simulated time, percentage, elapsed wall time and ETA
// (linear extrapolation of wall time per simulated second). Redraws at most ~10 times a second.
#pragma once

#include <chrono>

namespace ancf::app {

class ProgressBar {
 public:
  /// `enabled` false: every call does nothing. Precondition: t_end > 0.
  ProgressBar(double t_end, bool enabled);
  void update(double t);
  /// Final redraw and newline (once).
  void finish();

 private:
  void draw(double t);
  using Clock = std::chrono::steady_clock;
  double t_end_;
  bool enabled_, finished_ = false;
  double last_t_ = 0.0;
  Clock::time_point start_, last_draw_;
};

}  // namespace ancf::app
