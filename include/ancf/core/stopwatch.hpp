// Wall time of scopes, summed into the counters behind the time shares of run.json (kernels,
// contact, assembly, factorization, solves), cheap enough to run in every Newton iteration.
//
// Why not std::chrono::steady_clock alone: the vDSO clock_gettime behind it takes ≈ 25 ns here
// and orders the pipeline around its time-stamp read; with 6–9 reads per step it was 4–5 % of a
// 10-element pendulum step (perf). Where the CPU reports an invariant time-stamp counter (CPUID
// 0x80000007, EDX bit 8: constant rate in all power states), the ticks are read with rdtsc
// (≈ 10 ns, not serializing) and converted with a rate measured once per process against
// steady_clock over 1 ms. Elsewhere, or after TickClock::use_steady_clock(true), the ticks are
// steady_clock's nanoseconds.
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <cpuid.h>
#include <x86intrin.h>
#define ANCF_HAS_TSC 1
#else
#define ANCF_HAS_TSC 0
#endif

namespace ancf {

class TickClock {
 public:
  /// Ticks of a monotonic counter (unit: seconds_per_tick()).
  static std::uint64_t now() noexcept {
#if ANCF_HAS_TSC
    if (tsc_) return __rdtsc();
#endif
    return static_cast<std::uint64_t>(std::chrono::duration_cast<std::chrono::nanoseconds>(
                                          std::chrono::steady_clock::now().time_since_epoch())
                                          .count());
  }
  /// Seconds from `start` (a now() reading) to now; 0 if the counter read lower (a time-stamp
  /// counter not synchronized between cores).
  static double seconds_since(std::uint64_t start) noexcept {
    const std::uint64_t end = now();
    return end > start ? static_cast<double>(end - start) * seconds_per_tick() : 0.0;
  }
  /// Seconds per tick of the current source (for tsc: measured at the first call, 1 ms).
  static double seconds_per_tick() noexcept {
#if ANCF_HAS_TSC
    if (tsc_) {
      static const double rate = calibrate();
      return rate;
    }
#endif
    return 1e-9;
  }
  /// true: steady_clock for every reading (the source before issue 20's third pass), e.g. to
  /// measure what the time-stamp counter saves. Not thread-safe against running stopwatches.
  static void use_steady_clock(bool on) noexcept {
    tsc_ = !on && invariant_tsc();
  }

 private:
  static bool invariant_tsc() noexcept {
#if ANCF_HAS_TSC
    unsigned a = 0, b = 0, c = 0, d = 0;
    // GCC's __get_cpuid_max returns unsigned, clang's int: compare as unsigned in both.
    if (static_cast<unsigned>(__get_cpuid_max(0x80000000u, nullptr)) < 0x80000007u) return false;
    __get_cpuid(0x80000007u, &a, &b, &c, &d);
    return (d & (1u << 8)) != 0;
#else
    return false;
#endif
  }
  static double calibrate() noexcept {
#if ANCF_HAS_TSC
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const std::uint64_t c0 = __rdtsc();
    auto t1 = t0;
    while (t1 - t0 < std::chrono::milliseconds(1)) t1 = Clock::now();
    const std::uint64_t c1 = __rdtsc();
    return std::chrono::duration<double>(t1 - t0).count() / static_cast<double>(c1 - c0);
#else
    return 1e-9;
#endif
  }
  static inline bool tsc_ = invariant_tsc();
};

/// Adds the wall time of its scope to `seconds` [s] (also when the scope is left by an exception).
/// `seconds` must outlive the stopwatch.
class Stopwatch {
 public:
  explicit Stopwatch(double& seconds) noexcept : seconds_(seconds), start_(TickClock::now()) {}
  ~Stopwatch() { seconds_ += TickClock::seconds_since(start_); }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  double& seconds_;
  std::uint64_t start_;
};

}  // namespace ancf
