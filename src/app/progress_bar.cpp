#include "progress_bar.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace ancf::app {

ProgressBar::ProgressBar(double t_end, bool enabled)
    : t_end_(t_end), enabled_(enabled), start_(Clock::now()), last_draw_(start_) {}

void ProgressBar::update(double t) {
  if (!enabled_ || finished_) return;
  last_t_ = t;
  const auto now = Clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(100)) return;
  last_draw_ = now;
  draw(t);
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  draw(last_t_);
  std::fputc('\n', stderr);
  finished_ = true;
}

void ProgressBar::draw(double t) {
  constexpr int kWidth = 30;
  const double f = std::clamp(t / t_end_, 0.0, 1.0);
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const int filled = static_cast<int>(f * kWidth);
  const std::string eta = f > 0.0 ? fmt::format("{:.1f} s", elapsed * (1.0 - f) / f) : "?";
  fmt::print(stderr, "\r[{}{}] {:5.1f}%  t = {:.4g} / {:.4g} s  elapsed {:.1f} s  ETA {}   ",
             std::string(filled, '#'), std::string(kWidth - filled, ' '), 100.0 * f, t, t_end_,
             elapsed, eta);
  std::fflush(stderr);
}

}  // namespace ancf::app
