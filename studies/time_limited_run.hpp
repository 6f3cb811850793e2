// Run one study case in a forked child process under a wall-time limit, and read the child's
// peak memory (shared by the stability study and, through child_process.hpp, the scaling study).
//
// Why a child: a stress case may hang (a solver that makes no progress), crash (a signal) or run
// far too long; in-process, none of these can be stopped or told apart from the study itself.
// The child writes its report into an anonymous shared mapping as it goes (time reached, counters,
// outcome), so the parent can still read how far a case got after killing it at the limit
// (SIGKILL) or after it died of a signal. `Report` must be trivially copyable (it lives in raw
// shared memory and is never constructed there by the child).
#pragma once

#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <new>
#include <stdexcept>
#include <thread>
#include <type_traits>

namespace ancf::studies {

enum class ChildEnd {
  returned,          ///< the case function returned; its report is complete
  time_limit,        ///< killed at the wall-time limit; the report holds the progress so far
  signalled,         ///< died of a signal (crash)
  exception_escaped  ///< the case function let an exception escape (exit status 3)
};

template <class Report>
struct TimeLimitedResult {
  ChildEnd end = ChildEnd::returned;
  int signal = 0;             ///< the signal for ChildEnd::signalled
  double wall_seconds = 0.0;  ///< measured by the parent, fork to reap
  long max_rss_kib = 0;       ///< the child's peak resident set (wait4's ru_maxrss, KiB on Linux)
  Report report{};
};

/// Runs `run_case(Report&)` in a child; `report` starts value-initialized. `limit_seconds` may be
/// +∞ (no limit). Throws std::runtime_error only if fork or mmap fail.
template <class Report, class Function>
TimeLimitedResult<Report> run_with_time_limit(Function&& run_case, double limit_seconds) {
  static_assert(std::is_trivially_copyable_v<Report>);
  void* memory =
      mmap(nullptr, sizeof(Report), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (memory == MAP_FAILED) throw std::runtime_error("run_with_time_limit: mmap failed");
  Report* shared = new (memory) Report{};
  std::fflush(nullptr);  // the child must not flush the parent's buffered output a second time
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid < 0) {
    munmap(memory, sizeof(Report));
    throw std::runtime_error("run_with_time_limit: fork failed");
  }
  if (pid == 0) {
    int status = 0;
    try {
      run_case(*shared);
    } catch (...) {
      status = 3;
    }
    std::fflush(nullptr);
    _exit(status);
  }
  TimeLimitedResult<Report> result;
  int status = 0;
  struct rusage usage {};
  for (;;) {
    const pid_t done = wait4(pid, &status, WNOHANG, &usage);
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) break;
    if (elapsed > limit_seconds) {
      kill(pid, SIGKILL);
      wait4(pid, &status, 0, &usage);
      result.end = ChildEnd::time_limit;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(elapsed < 1.0 ? 2 : 20));
  }
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.max_rss_kib = usage.ru_maxrss;
  if (result.end != ChildEnd::time_limit) {
    if (WIFSIGNALED(status)) {
      result.end = ChildEnd::signalled;
      result.signal = WTERMSIG(status);
    } else if (WIFEXITED(status) && WEXITSTATUS(status) == 3) {
      result.end = ChildEnd::exception_escaped;
    }
  }
  result.report = *shared;
  munmap(memory, sizeof(Report));
  return result;
}

}  // namespace ancf::studies
