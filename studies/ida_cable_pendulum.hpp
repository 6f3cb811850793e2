// Shared by the IDA benchmark and the rtol study: one timed IDA run of a cable pendulum
// (REFERENCES §10) returning the tip position at the output times, the counters and wall time.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"

namespace ancf::studies {

struct TipRun {
  std::vector<Vec3> tips;  ///< tip position [m] at each output time
  IdaStatistics statistics;
  double wall_time = 0.0;  ///< [s], problem set-up + consistent initial values + integration
};

struct TipOptions {
  double rtol = 1e-6;  ///< atol = rtol × physical scale (IdaOptions defaults)
  int max_order = 5;   ///< BDF order limit
};

/// Integrate `model` (a single cable) with IDA and record the position of its last node at `times`.
inline TipRun run_tip(const Model& model, const std::vector<double>& times, const TipOptions& o) {
  const Index tip = model.node_coordinate(0, -1);
  TipRun out;
  const auto start = std::chrono::steady_clock::now();
  GglProblem problem(model);
  IdaOptions options;
  options.rtol = o.rtol;
  options.max_order = o.max_order;
  options.output_times = times;
  IdaIntegrator ida(problem, options);
  ida.run([&](double, std::span<const double> y, std::span<const double>) {
    out.tips.emplace_back(y[tip], y[tip + 1], y[tip + 2]);
  });
  out.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  out.statistics = ida.statistics();
  return out;
}

/// max_k |tip_k − reference_k| [m].
inline double tip_error(const TipRun& run, const TipRun& reference) {
  double e = 0.0;
  for (std::size_t k = 0; k < run.tips.size(); ++k)
    e = std::max(e, (run.tips[k] - reference.tips[k]).norm());
  return e;
}

}  // namespace ancf::studies
