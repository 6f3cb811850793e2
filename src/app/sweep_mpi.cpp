// `ancf sweep` over MPI ranks (sweep_mpi.hpp).
#include "sweep_mpi.hpp"

#include <cstdlib>
#include <stdexcept>
#include <thread>

#ifdef ANCF_HAVE_MPI
#include <mpi.h>
#endif

namespace ancf::app {

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE", "MPI_LOCALNRANKS"})
    if (const char* s = std::getenv(v); s && std::atoi(s) > 1) return true;
  // srun sets SLURM_STEP_NUM_TASKS for the tasks it starts (a batch script itself has none), also
  // without an MPI plug-in: then each task would otherwise run the whole sweep.
  const char* tasks = std::getenv("SLURM_STEP_NUM_TASKS");
  return tasks && std::atoi(tasks) > 1 && std::getenv("SLURM_PROCID");
}

#ifdef ANCF_HAVE_MPI

namespace {

enum Tag : int { kReady = 1, kRow = 2, kCase = 3 };

/// Receive from anyone without spinning: Open MPI's blocking receive polls at full speed, which
/// on an oversubscribed node takes a core from the ranks that run cases.
MPI_Status patient_probe(int source, int tag) {
  MPI_Status status;
  for (int flag = 0;;) {
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
    if (flag) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace

bool mpi_built() {
  return true;
}

std::pair<int, int> mpi_begin() {
  MPI_Init(nullptr, nullptr);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return {rank, size};
}

void mpi_end() {
  MPI_Finalize();
}

bool mpi_broadcast_ok(bool ok) {
  int flag = ok ? 1 : 0;
  MPI_Bcast(&flag, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return flag != 0;
}

void mpi_dispatch(const std::vector<long>& todo,
                  const std::function<void(long, const std::string&)>& on_row) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::size_t next = 0;
  int stopped = 0;
  while (stopped < size - 1) {
    // A message from a worker: kReady (first request) or kRow (a finished case, then next).
    const MPI_Status st = patient_probe(MPI_ANY_SOURCE, MPI_ANY_TAG);
    int count = 0;
    MPI_Get_count(&st, MPI_CHAR, &count);
    std::string text(static_cast<std::size_t>(count), '\0');
    MPI_Recv(text.data(), count, MPI_CHAR, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    if (st.MPI_TAG == kRow) {
      const long index = std::stol(text.substr(0, text.find(',')));
      on_row(index, text);
    }
    long give = -1;
    if (next < todo.size())
      give = todo[next++];
    else
      ++stopped;
    MPI_Send(&give, 1, MPI_LONG, st.MPI_SOURCE, kCase, MPI_COMM_WORLD);
  }
}

void mpi_work(const SweepContext& ctx) {
  MPI_Send(nullptr, 0, MPI_CHAR, 0, kReady, MPI_COMM_WORLD);
  for (;;) {
    patient_probe(0, kCase);
    long index = -1;
    MPI_Recv(&index, 1, MPI_LONG, 0, kCase, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (index < 0) return;
    const std::string row = run_case(ctx, ctx.spec.cases[static_cast<std::size_t>(index)]);
    MPI_Send(row.data(), static_cast<int>(row.size()), MPI_CHAR, 0, kRow, MPI_COMM_WORLD);
  }
}

#else

namespace {
[[noreturn]] void no_mpi() {
  throw std::runtime_error(
      "this ancf was built without MPI (CMake found no MPI; install libopenmpi-dev openmpi-bin and "
      "reconfigure): run `ancf sweep` without mpirun/srun to use worker processes on one machine");
}
}  // namespace

bool mpi_built() {
  return false;
}
std::pair<int, int> mpi_begin() {
  no_mpi();
}
void mpi_end() {}
bool mpi_broadcast_ok(bool) {
  no_mpi();
}
void mpi_dispatch(const std::vector<long>&, const std::function<void(long, const std::string&)>&) {
  no_mpi();
}
void mpi_work(const SweepContext&) {
  no_mpi();
}

#endif

}  // namespace ancf::app
