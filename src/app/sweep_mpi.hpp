// `ancf sweep` over MPI ranks (docs/sweeps.md). Rank 0 only hands out cases and writes the
// table; ranks 1 … N−1 each ask for a case, run it (sweep_case.hpp) and send its row back, until
// none is left. Handing out one case at a time is the dynamic load balancing the cases need:
// a capture case that misses ends early, one that locks runs to t_end. Built only when CMake
// finds MPI (ANCF_HAVE_MPI); otherwise these report that this build has no MPI.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sweep_case.hpp"

namespace ancf::app {

/// True when this build has MPI.
[[nodiscard]] bool mpi_built();
/// True when the process was started by an MPI launcher (mpirun/mpiexec, srun) with > 1 rank.
[[nodiscard]] bool launched_by_mpi();
/// MPI_Init; returns {rank, size}. Throws std::runtime_error without MPI in the build.
std::pair<int, int> mpi_begin();
void mpi_end();
/// Rank 0: hand out `todo` (case indices) to ranks 1 … size−1, calling on_row(index, row) as
/// each row arrives, then tell every rank to stop.
void mpi_dispatch(const std::vector<long>& todo,
                  const std::function<void(long, const std::string&)>& on_row);
/// Ranks > 0: run the cases rank 0 hands out until it says stop.
void mpi_work(const SweepContext& ctx);
/// Rank 0 → all: a flag (true: go on; false: rank 0 failed to set up, stop).
bool mpi_broadcast_ok(bool ok);

}  // namespace ancf::app
