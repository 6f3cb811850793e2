// Run a measurement in a forked child process and report its peak resident memory.
//
// Why a child: ru_maxrss is a high-water mark that never goes down within a process, so measuring
// several cases in one process would report the largest case so far for all of them. A forked
// child starts with the parent's resident pages (counted in its RSS, shared copy-on-write), so
// the memory a case needs is its child's ru_maxrss minus that of a child that does nothing (the
// baseline), both read by the parent with wait4 (getrusage(2): ru_maxrss in KiB on Linux). The
// fork, wait and shared report are those of time_limited_run.hpp.
#pragma once

#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <type_traits>

#include "time_limited_run.hpp"

namespace ancf::studies {

template <class Result>
struct ChildOutcome {
  bool ok = false;
  Result result{};
  long max_rss_kib = 0;  ///< peak resident set of the child [KiB]
  std::string error;     ///< what went wrong when !ok
};

/// Fork, run `measure()` (returning a trivially copyable Result) in the child without a time
/// limit (run_with_time_limit), and return its result with the child's ru_maxrss. An exception in
/// the child becomes !ok with its message; so does a child that dies without finishing.
template <class Result, class Measure>
ChildOutcome<Result> run_in_child(Measure&& measure) {
  static_assert(std::is_trivially_copyable_v<Result>);
  struct Message {
    bool ok;
    Result result;
    char error[256];
  };
  ChildOutcome<Result> outcome;
  TimeLimitedResult<Message> child;
  try {
    child = run_with_time_limit<Message>(
        [&](Message& m) {
          try {
            m.result = measure();
            m.ok = true;
          } catch (const std::exception& e) {
            std::strncpy(m.error, e.what(), sizeof(m.error) - 1);
          }
        },
        std::numeric_limits<double>::infinity());
  } catch (const std::exception& e) {
    outcome.error = e.what();
    return outcome;
  }
  outcome.max_rss_kib = child.max_rss_kib;
  if (child.end != ChildEnd::returned) {
    outcome.error = "child process died without a result";
    return outcome;
  }
  outcome.ok = child.report.ok;
  outcome.result = child.report.result;
  if (!outcome.ok) outcome.error = child.report.error;
  return outcome;
}

}  // namespace ancf::studies
