// IdaIntegrator refuses relative tolerances looser than kIdaMaxRtol (ida_integrator.hpp).
// Before the guard, the stability stress study (ancf-study-stability, group large_h) found IDA
// "succeeding" on the benchmark cable pendulum at rtol 3e-2 and 0.3 while the energy grew to 8.6
// and 12.8 times the swing's potential energy in 2 s: the local error test accepted steps with
// errors of the size of the solution and nothing reported a failure. The refusal must name rtol,
// and the loosest accepted value must still run.
#include <gtest/gtest.h>

#include <string>

#include "ancf/core/error.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/ggl_problem.hpp"

namespace ancf {
namespace {

TEST(IdaRtolGuard, RefusesLooserThanTheLimitWithAMessageNamingRtol) {
  const Model model = cable_pendulum_model(benchmark_cable_pendulum(4));
  GglProblem problem(model);
  for (const double rtol : {3e-2, 0.3}) {
    IdaOptions o;
    o.rtol = rtol;
    try {
      IdaIntegrator ida(problem, o);
      FAIL() << "rtol " << rtol << " was accepted";
    } catch (const SolverError& e) {
      EXPECT_NE(std::string(e.what()).find("rtol"), std::string::npos) << e.what();
    }
  }
}

TEST(IdaRtolGuard, AcceptsTheLimitAndIntegrates) {
  const Model model = cable_pendulum_model(benchmark_cable_pendulum(4));
  GglProblem problem(model);
  IdaOptions o;
  o.rtol = kIdaMaxRtol;
  IdaIntegrator ida(problem, o);
  EXPECT_EQ(ida.advance(0.2), IdaStop::reached);
  EXPECT_DOUBLE_EQ(ida.time(), 0.2);
}

}  // namespace
}  // namespace ancf
