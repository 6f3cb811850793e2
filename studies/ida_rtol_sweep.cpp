// Work–precision of IDA on the benchmark cable pendulum (REFERENCES §9, §10): how the tip error
// against a tight reference on the same mesh, the wall time and the counters depend on rtol.
//
// Usage: ancf-study-ida-rtol [csv = out/ida_rtol_sweep.csv] [max_order = 5] [elements = 20]
//                            [reference rtol = 1e-11]
// rtol = 1e-3, 1e-4, …, 1e-10; one row per rtol. The error is max over t = 0.25, 0.5, 1.0 s of
// |tip − tip_ref| [m]; scd = −log10(error / |tip_ref(1 s)|) (significant correct digits). Lines
// starting with '#' are metadata.
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "ancf/scenes/pendulums.hpp"
#include "ida_cable_pendulum.hpp"

using namespace ancf;

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "out/ida_rtol_sweep.csv";
  const int max_order = argc > 2 ? std::atoi(argv[2]) : 5;
  const Index elements = argc > 3 ? std::atol(argv[3]) : 20;
  const double reference_rtol = argc > 4 ? std::atof(argv[4]) : 1e-11;
  const std::vector<double> times = {0.25, 0.5, 1.0};
  const Model model = cable_pendulum_model(benchmark_cable_pendulum(elements));

  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  std::FILE* csv = std::fopen(path.c_str(), "w");
  if (!csv) {
    fmt::print(stderr, "cannot write {}\n", path);
    return 1;
  }
  const studies::TipRun reference =
      studies::run_tip(model, times, {.rtol = reference_rtol, .max_order = 5});
  const double tip_scale = reference.tips.back().norm();
  fmt::print(csv, "# ancf-study-ida-rtol: benchmark cable pendulum (REFERENCES §10), {} elements\n",
             elements);
  fmt::print(csv, "# reference: rtol {:.0e}, BDF order <= 5, {} steps; sweep: BDF order <= {}\n",
             reference_rtol, reference.statistics.steps, max_order);
  fmt::print(
      csv,
      "max_order,rtol,tip_error_m,scd,wall_time_s,steps,residual_evaluations,jacobian_evaluations,"
      "linear_solver_setups,nonlinear_iterations,error_test_failures,convergence_failures,klu_"
      "repivots,"
      "last_order,last_step_s\n");
  fmt::print("{:>9} {:>11} {:>6} {:>10} {:>8} {:>8} {:>6}\n", "rtol", "tip err [m]", "scd",
             "time [s]", "steps", "res", "jac");
  for (int k = 3; k <= 10; ++k) {
    const double rtol = std::pow(10.0, -k);
    const studies::TipRun run =
        studies::run_tip(model, times, {.rtol = rtol, .max_order = max_order});
    const double error = studies::tip_error(run, reference);
    const double scd = -std::log10(error / tip_scale);
    const IdaStatistics& s = run.statistics;
    fmt::print(csv, "{},{:.1e},{:.6e},{:.3f},{:.6f},{},{},{},{},{},{},{},{},{},{:.6e}\n", max_order,
               rtol, error, scd, run.wall_time, s.steps, s.residual_evaluations,
               s.jacobian_evaluations, s.linear_solver_setups, s.nonlinear_iterations,
               s.error_test_failures, s.convergence_failures, s.klu_repivots, s.last_order,
               s.last_step);
    std::fflush(csv);
    fmt::print("{:9.1e} {:11.3e} {:6.2f} {:10.4f} {:8} {:8} {:6}\n", rtol, error, scd,
               run.wall_time, s.steps, s.residual_evaluations, s.jacobian_evaluations);
  }
  std::fclose(csv);
  fmt::print("wrote {}\n", path);
  return 0;
}
