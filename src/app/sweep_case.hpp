// One case of `ancf sweep`: its folder, its own `ancf run` process, and its row of the results
// table. Shared by the local worker pool (sweep_command.cpp) and the MPI workers (sweep_mpi.cpp).
//
// Why a process per case (fork/exec of the ancf executable) rather than running cases in threads
// or in a long-lived worker: a case that crashes (a segfault, an abort, running out of memory)
// takes only its own process down and is recorded as "crashed"; a per-case time limit is a
// SIGKILL, which needs no cooperation from the solver; every case starts from a clean process
// (no state, allocator growth or ru_maxrss carried over), and a case can be rerun by hand with
// the command in its log. Process start-up (~10 ms) is negligible against runs of seconds.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <string>
#include <vector>

#include "ancf/io/sweep_design.hpp"

namespace ancf::app {

/// What every case of one sweep shares.
struct SweepContext {
  SweepSpec spec;
  std::string base_text;  ///< the base scene's text
  std::string out;        ///< sweep folder
  std::string ancf;       ///< executable run for each case
};

/// A started case: its `ancf run` child, or no child when the case failed before starting.
struct RunningCase {
  long index = 0;
  pid_t pid = -1;
  std::chrono::steady_clock::time_point start;
  bool timed_out = false;
  std::string early_row;  ///< the finished row when pid < 0
};

/// Header of the results table: case, the parameters, status, the results, wall_s, message.
[[nodiscard]] std::string table_header(const SweepSpec& spec);
/// Folder of case `index` inside the sweep folder (cases/case-NNNN).
[[nodiscard]] std::string case_dir(const SweepContext& ctx, long index);

/// Write the case's scene (base scene with its overrides) and start its `ancf run` child, which
/// is killed if this process dies (PR_SET_PDEATHSIG) so a killed sweep leaves no orphan runs.
[[nodiscard]] RunningCase start_case(const SweepContext& ctx, const SweepCase& c);
/// Kill the case's child if it is past the sweep's time limit (marks it timed out).
void enforce_time_limit(const SweepContext& ctx, RunningCase& r);
/// The table row of a case whose child ended with waitpid status `wait_status` (the row's
/// status: its run's own status; "timeout"; "crashed" with the signal or exit status).
[[nodiscard]] std::string finish_case(const SweepContext& ctx, const RunningCase& r,
                                      int wait_status);
/// start_case, wait (enforcing the time limit) and finish_case: one case, blocking.
[[nodiscard]] std::string run_case(const SweepContext& ctx, const SweepCase& c);

}  // namespace ancf::app
