// `ancf sweep SWEEP.toml` (docs/sweeps.md): run the cases of a sweep file in worker processes on
// this machine, or over MPI ranks, and keep one results table.
//
// Nothing is lost: each finished case is appended to results.csv as one line (one write) the
// moment it finishes; a rerun of the same sweep reads the complete lines back and runs only the
// cases missing from them. At the end the table is rewritten sorted by case, so it is the same
// whichever worker finished first.
#include <fcntl.h>
#include <fmt/format.h>
#include <sched.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "ancf/io/run_metadata.hpp"
#include "commands.hpp"
#include "sweep_case.hpp"
#include "sweep_mpi.hpp"

namespace ancf::app {

namespace fs = std::filesystem;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

long default_workers() {
  cpu_set_t set;  // the cores this process may use (a Slurm or taskset allocation)
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

std::string self_executable(const char* argv0) {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string(argv0) : p.string();
}

double load_average() {
  double l[1] = {0.0};
  return getloadavg(l, 1) == 1 ? l[0] : -1.0;
}

/// The table's rows so far: complete lines (ending in a newline) of results.csv under the
/// expected header. A line cut short by a crash is dropped and its case rerun.
std::map<long, std::string> read_finished(const std::string& table, const std::string& header) {
  std::map<long, std::string> rows;
  const std::string text = slurp(table);
  if (text.empty()) return rows;
  std::size_t begin = 0;
  bool first = true;
  while (begin < text.size()) {
    const std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) break;
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    if (first) {
      if (line != header)
        throw std::runtime_error(
            table + " has another header than this sweep's table; use --restart or another --out");
      first = false;
      continue;
    }
    try {
      rows[std::stol(line.substr(0, line.find(',')))] = line;
    } catch (const std::exception&) {
    }
  }
  return rows;
}

/// Appends rows to the table, one write(2) per row, so each finished case is on disk at once.
class TableAppender {
 public:
  explicit TableAppender(const std::string& path)
      : fd_(open(path.c_str(), O_WRONLY | O_APPEND | O_CREAT, 0644)) {
    if (fd_ < 0) throw std::runtime_error("cannot write " + path);
  }
  ~TableAppender() { close(fd_); }
  TableAppender(const TableAppender&) = delete;
  TableAppender& operator=(const TableAppender&) = delete;
  void line(const std::string& text) {
    const std::string l = text + "\n";
    if (write(fd_, l.data(), l.size()) != static_cast<ssize_t>(l.size()))
      throw std::runtime_error("short write to the results table");
  }

 private:
  int fd_;
};

/// Run `todo` in up to `workers` child processes at a time.
void run_local(const SweepContext& ctx, const std::vector<long>& todo, long workers,
               const std::function<void(long, const std::string&)>& on_row) {
  std::map<pid_t, RunningCase> running;
  std::size_t next = 0;
  while (next < todo.size() || !running.empty()) {
    while (static_cast<long>(running.size()) < workers && next < todo.size()) {
      RunningCase r = start_case(ctx, ctx.spec.cases[static_cast<std::size_t>(todo[next++])]);
      if (r.pid < 0)
        on_row(r.index, r.early_row);
      else
        running.emplace(r.pid, r);
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0) {
      if (const auto it = running.find(pid); it != running.end()) {
        on_row(it->second.index, finish_case(ctx, it->second, status));
        running.erase(it);
      }
      continue;
    }
    for (auto& [p, r] : running) enforce_time_limit(ctx, r);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

}  // namespace

int sweep_command(const SweepOptions& options, const char* argv0) {
  bool mpi = options.mpi || launched_by_mpi();
  int rank = 0, ranks = 1;
  try {
    if (mpi) std::tie(rank, ranks) = mpi_begin();
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
  const auto start = std::chrono::steady_clock::now();
  const double load_start = load_average();
  SweepContext ctx;
  std::map<long, std::string> rows;
  std::vector<long> todo;
  std::string table, header;
  bool ok = true;
  std::size_t resumed = 0;
  try {
    ctx.spec = load_sweep(options.sweep_path);
    ctx.base_text = read_scene_text(ctx.spec.scene);
    ctx.out = options.out_dir.empty() ? ctx.spec.out : options.out_dir;
    ctx.ancf = options.ancf.empty() ? self_executable(argv0) : options.ancf;
    table = ctx.out + "/results.csv";
    header = table_header(ctx.spec);
    if (rank == 0) {
      if (options.restart) fs::remove_all(ctx.out);
      fs::create_directories(ctx.out);
      const std::string copy = ctx.out + "/sweep.toml";
      const std::string text = slurp(options.sweep_path);
      if (fs::exists(copy) && slurp(copy) != text)
        throw std::runtime_error(ctx.out + " holds another sweep (its sweep.toml differs from " +
                                 options.sweep_path + "); use --restart or another --out");
      std::ofstream(copy) << text;
      rows = read_finished(table, header);
      for (auto it = rows.begin(); it != rows.end();)  // rows of cases this design no longer has
        it = it->first < static_cast<long>(ctx.spec.cases.size()) ? std::next(it) : rows.erase(it);
      resumed = rows.size();
      for (const SweepCase& c : ctx.spec.cases)
        if (!rows.count(c.index)) todo.push_back(c.index);
      if (!fs::exists(table) || fs::file_size(table) == 0) std::ofstream(table) << header << '\n';
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    ok = false;
  }
  if (mpi && !mpi_broadcast_ok(ok)) ok = false;
  if (!ok) {
    if (mpi) mpi_end();
    return 1;
  }
  if (mpi && rank > 0) {
    mpi_work(ctx);
    mpi_end();
    return 0;
  }

  if (mpi && ranks < 2) {
    // One rank (`mpirun -n 1`, or --mpi without a launcher): nobody to hand cases to.
    fmt::print("one MPI rank: running the cases in worker processes instead\n");
    mpi_end();
    mpi = false;
  }
  const long workers =
      mpi ? ranks - 1 : (options.workers > 0 ? options.workers : default_workers());
  fmt::print("sweep {}: {} cases, {} already finished, {} to run on {} {}\n", options.sweep_path,
             ctx.spec.cases.size(), resumed, todo.size(), workers,
             mpi ? "MPI worker ranks" : "worker processes");
  std::fflush(stdout);
  std::size_t done = 0;
  int exit_status = 0;
  try {
    TableAppender append(table);
    const auto on_row = [&](long index, const std::string& row) {
      append.line(row);
      rows[index] = row;
      ++done;
      fmt::print("[{}/{}] case {}: {}\n", done, todo.size(), index,
                 row.substr(0, std::min<std::size_t>(row.size(), 160)));
      std::fflush(stdout);
    };
    if (mpi) {
      mpi_dispatch(todo, on_row);
    } else {
      run_local(ctx, todo, workers, on_row);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    exit_status = 1;
  }

  // The final table, sorted by case; written aside and renamed so it is never half written.
  std::map<std::string, long> statuses;
  {
    std::ofstream sorted(table + ".tmp");
    sorted << header << '\n';
    const std::size_t status_field = 1 + ctx.spec.parameters.size();
    for (const auto& [index, row] : rows) {
      sorted << row << '\n';
      // The status column (parameters before it may be quoted, so split respecting quotes).
      std::size_t field = 0;
      bool quoted = false;
      std::string value;
      for (char ch : row) {
        if (ch == '"')
          quoted = !quoted;
        else if (ch == ',' && !quoted) {
          if (field++ == status_field) break;
          value.clear();
        } else
          value += ch;
      }
      ++statuses[value];
    }
  }
  fs::rename(table + ".tmp", table);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  JsonObject counts, meta;
  for (const auto& [s, n] : statuses) counts.set(s, static_cast<long>(n));
  char host[256] = {};
  gethostname(host, sizeof(host) - 1);
  meta.set("sweep", options.sweep_path)
      .set("scene", ctx.spec.scene)
      .set("design", ctx.spec.design)
      .set("cases", static_cast<long>(ctx.spec.cases.size()))
      .set("finished_before", static_cast<long>(resumed))
      .set("run_now", static_cast<long>(done))
      .set("statuses", counts)
      .set("mode", mpi ? "mpi" : "processes")
      .set("workers", workers)
      .set("ranks", static_cast<long>(ranks))
      .set("ancf", ctx.ancf)
      .set("host", std::string(host))
      .set("cores", default_workers())
      .set("load_average_start", load_start)
      .set("load_average_end", load_average())
      .set("wall_seconds", wall)
      .set("table", table);
  std::ofstream(ctx.out + "/run.json") << meta.text() << '\n';
  fmt::print("sweep done: {} cases in the table, {} run now, wall {:.1f} s; {}\n", rows.size(),
             done, wall, table);
  if (mpi) mpi_end();
  return exit_status;
}

}  // namespace ancf::app
