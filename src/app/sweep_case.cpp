// One case of `ancf sweep` (sweep_case.hpp).
#include "sweep_case.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <toml++/toml.h>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

namespace ancf::app {

namespace fs = std::filesystem;

namespace {

/// A CSV field: quoted when it holds a comma, quote or line break (RFC 4180); line breaks
/// become spaces so every row stays one line (resume reads the table line by line).
std::string csv_field(std::string s) {
  for (char& ch : s)
    if (ch == '\n' || ch == '\r') ch = ' ';
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

std::string number_text(const toml::node& n) {
  if (auto i = n.value_exact<int64_t>()) return std::to_string(*i);
  if (auto d = n.value_exact<double>()) return fmt::format("{}", *d);
  if (auto s = n.value_exact<std::string>()) return *s;
  if (auto b = n.value_exact<bool>()) return *b ? "true" : "false";
  return "";
}

/// The last non-empty line of the case's log (the error `ancf run` printed).
std::string last_log_line(const std::string& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

std::string row(const SweepContext& ctx, long index, const std::string& status,
                const std::string& message, double wall, const toml::table* results) {
  const SweepSpec& spec = ctx.spec;
  std::string r = std::to_string(index);
  // (appending ',' and the field separately: GCC 12 warns falsely (-Wrestrict) on "," + s)
  for (const std::string& v : spec.cases[static_cast<std::size_t>(index)].shown)
    r.append(",").append(csv_field(v));
  r.append(",").append(status);
  for (const std::string& key : spec.results) {
    const toml::node* n = results ? results->at_path(key).node() : nullptr;
    r.append(",").append(csv_field(n ? number_text(*n) : ""));
  }
  r += fmt::format(",{:.3f},", wall) + csv_field(message);
  return r;
}

}  // namespace

std::string table_header(const SweepSpec& spec) {
  std::string h = "case";
  for (const SweepParameter& p : spec.parameters) h.append(",").append(csv_field(p.name));
  h += ",status";
  for (const std::string& key : spec.results) h.append(",").append(csv_field(key));
  return h + ",wall_s,message";
}

std::string case_dir(const SweepContext& ctx, long index) {
  return fmt::format("{}/cases/case-{:04d}", ctx.out, index);
}

RunningCase start_case(const SweepContext& ctx, const SweepCase& c) {
  RunningCase r;
  r.index = c.index;
  r.start = std::chrono::steady_clock::now();
  const std::string dir = case_dir(ctx, c.index);
  fs::remove_all(dir);  // a case rerun after a stopped sweep starts afresh
  fs::create_directories(dir);
  const std::string scene = dir + "/scene.toml";
  try {
    std::ofstream(scene) << apply_scene_overrides(ctx.base_text, ctx.spec.scene, c.overrides)
                         << '\n';
  } catch (const std::exception& e) {
    r.early_row = row(ctx, c.index, "error", e.what(), 0.0, nullptr);
    return r;
  }
  std::vector<std::string> args = {ctx.ancf,     "run",     scene,       "--out",
                                   dir + "/out", "--quiet", "--results", dir + "/results.toml"};
  args.insert(args.end(), ctx.spec.run_args.begin(), ctx.spec.run_args.end());
  {
    std::ofstream log(dir + "/log.txt");
    for (const std::string& a : args) log << a << ' ';
    log << '\n';
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string log = dir + "/log.txt";
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    r.early_row =
        row(ctx, c.index, "crashed", std::string("fork: ") + std::strerror(errno), 0.0, nullptr);
    return r;
  }
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec.
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);
    const int fd = open(log.c_str(), O_WRONLY | O_APPEND);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
      close(fd);
    }
    execv(argv[0], argv.data());
    _exit(127);
  }
  r.pid = pid;
  return r;
}

void enforce_time_limit(const SweepContext& ctx, RunningCase& r) {
  if (r.pid < 0 || r.timed_out || ctx.spec.time_limit <= 0.0) return;
  const double age =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
  if (age > ctx.spec.time_limit) {
    kill(r.pid, SIGKILL);
    r.timed_out = true;
  }
}

std::string finish_case(const SweepContext& ctx, const RunningCase& r, int wait_status) {
  if (r.pid < 0) return r.early_row;
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - r.start).count();
  const std::string dir = case_dir(ctx, r.index);
  if (r.timed_out)
    return row(ctx, r.index, "timeout",
               fmt::format("killed at the time limit of {} s", ctx.spec.time_limit), wall, nullptr);
  toml::table results;
  bool have = false;
  if (fs::exists(dir + "/results.toml")) {
    try {
      results = toml::parse_file(dir + "/results.toml");
      have = true;
    } catch (const toml::parse_error&) {
    }
  }
  if (WIFSIGNALED(wait_status))
    return row(ctx, r.index, "crashed",
               fmt::format("killed by signal {} ({})", WTERMSIG(wait_status),
                           strsignal(WTERMSIG(wait_status))),
               wall, nullptr);
  if (!have)
    return row(ctx, r.index, "crashed",
               fmt::format("exit status {} without results: {}", WEXITSTATUS(wait_status),
                           last_log_line(dir + "/log.txt")),
               wall, nullptr);
  return row(ctx, r.index, results["status"].value_or(std::string("crashed")),
             results["message"].value_or(std::string()), wall, &results);
}

std::string run_case(const SweepContext& ctx, const SweepCase& c) {
  RunningCase r = start_case(ctx, c);
  int status = 0;
  while (r.pid >= 0) {
    const pid_t done = waitpid(r.pid, &status, WNOHANG);
    if (done == r.pid) break;
    if (done < 0 && errno != EINTR) break;
    enforce_time_limit(ctx, r);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return finish_case(ctx, r, status);
}

}  // namespace ancf::app
