// Run a measurement in a forked child process and report its peak resident memory.
//
// Why a child: ru_maxrss is a high-water mark that never goes down within a process, so measuring
// several cases in one process would report the largest case so far for all of them. A forked
// child starts with the parent's resident pages (counted in its RSS, shared copy-on-write), so
// the memory a case needs is its child's ru_maxrss minus that of a child that does nothing (the
// baseline), both read by the parent with wait4 (getrusage(2): ru_maxrss in KiB on Linux).
#pragma once

#include <sys/resource.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <exception>
#include <string>
#include <type_traits>

namespace ancf::studies {

template <class Result>
struct ChildOutcome {
  bool ok = false;
  Result result{};
  long max_rss_kib = 0;  ///< peak resident set of the child [KiB]
  std::string error;     ///< what went wrong when !ok
};

namespace detail {
template <class Result>
struct ChildMessage {
  bool ok = false;
  Result result{};
  char error[256] = {};
};

inline bool write_all(int fd, const void* data, std::size_t size) {
  const char* p = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, p, size);
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

inline bool read_all(int fd, void* data, std::size_t size) {
  char* p = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t n = ::read(fd, p, size);
    if (n <= 0) return false;
    p += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}
}  // namespace detail

/// Fork, run `measure()` (returning a trivially copyable Result) in the child, pass the result
/// back through a pipe and reap the child with wait4. An exception in the child becomes !ok with
/// its message; so does a child that dies without answering.
template <class Result, class Measure>
ChildOutcome<Result> run_in_child(Measure&& measure) {
  static_assert(std::is_trivially_copyable_v<Result>);
  using Message = detail::ChildMessage<Result>;
  ChildOutcome<Result> outcome;
  int fds[2];
  if (::pipe(fds) != 0) {
    outcome.error = "pipe failed";
    return outcome;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    outcome.error = "fork failed";
    return outcome;
  }
  if (pid == 0) {
    ::close(fds[0]);
    Message message;
    try {
      message.result = measure();
      message.ok = true;
    } catch (const std::exception& e) {
      std::strncpy(message.error, e.what(), sizeof(message.error) - 1);
    }
    const bool sent = detail::write_all(fds[1], &message, sizeof(message));
    ::close(fds[1]);
    ::_exit(sent ? 0 : 1);  // no exit handlers or stream flushes of the parent's state
  }
  ::close(fds[1]);
  Message message;
  const bool received = detail::read_all(fds[0], &message, sizeof(message));
  ::close(fds[0]);
  int status = 0;
  struct rusage usage {};
  ::wait4(pid, &status, 0, &usage);
  outcome.max_rss_kib = usage.ru_maxrss;
  if (!received || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    outcome.error = "child process died without a result";
    return outcome;
  }
  outcome.ok = message.ok;
  outcome.result = message.result;
  if (!message.ok) outcome.error = message.error;
  return outcome;
}

}  // namespace ancf::studies
