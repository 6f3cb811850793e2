// The static solver on problems it must refuse (issue 17 item 5): a singular tangent whose load
// drives the zero-stiffness motion fails at once with the load factor and the unknowns of that
// motion named, never "succeeds" on a flipped shape; a singular but consistent problem solves
// and says that its equilibrium is not isolated; a non-converging one fails with the load factor;
// an iterate the problem cannot evaluate is a failed iteration (the increment is cut).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>
#include <string>

#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/model_builder.hpp"
#include "ancf/system/static_model_problem.hpp"

namespace ancf {
namespace {

CableSection bending_section() {
  CableSection s;
  s.axial_stiffness = 1e6;
  s.bending_stiffness = 1.0;
  s.mass_per_length = 0.1;
  return s;
}

// Quarter circle of radius 1 in the xy plane, clamped at its start (position and slope), with a
// tip force along z (normal to its plane). The cable has no torsional stiffness: the rigid
// rotation about the clamp's tangent is a mechanism, and the tip force drives it (the rod issue
// 16). Before issue 17 the 4-element case "succeeded" after 2 561 increments on a shape rotated
// by 90° about that axis.
Model clamped_arc(Index elements, double tip_force) {
  ModelBuilder b;
  const Index c = b.add_cable(
      "arc",
      arc_cable(Vec3::Zero(), -Vec3::UnitY(), Vec3::UnitX(), 1.0, 0.5 * std::numbers::pi, elements),
      bending_section());
  b.pin("root", {c, 0}, -Vec3::UnitY());
  b.align_slope("root.slope", {c, 0}, Vec3::UnitX());
  if (tip_force != 0.0) b.add_node_force({c, -1}, tip_force * Vec3::UnitZ());
  return b.finalize();
}

std::string solve_error(const Model& model, StaticSolverOptions options = {}) {
  StaticModelProblem problem(model);
  StaticSolver solver(problem, options);
  VecX y = problem.initial_guess();
  const VecX y0 = y;
  try {
    (void)solver.solve(y);
  } catch (const SingularStaticProblem& e) {
    EXPECT_EQ(y, y0) << "y must hold the last converged state";
    return e.what();
  }
  return "solved";
}

TEST(StaticSolverSingular, ArcWithOutOfPlaneTipForceIsRefusedNamingTheMechanism) {
  for (const Index n : {4, 16, 64}) {
    const std::string what = solve_error(clamped_arc(n, 1e-3));
    std::printf("%ld elements: %s\n", static_cast<long>(n), what.c_str());
    EXPECT_NE(what.find("static solve stopped at load factor 0:"), std::string::npos) << what;
    EXPECT_NE(what.find("cable 'arc' node"), std::string::npos) << what;
  }
}

// A straight cable pinned at one end, horizontal under gravity: the rotation about the pin is a
// mechanism that gravity drives (the hanging equilibrium is a rotation of 90° away).
TEST(StaticSolverSingular, HorizontalPendulumUnderGravityIsRefused) {
  ModelBuilder b;
  const Index c =
      b.add_cable("rope", straight_cable(Vec3::Zero(), Vec3::UnitX(), 8), bending_section());
  b.pin("pivot", {c, 0}, Vec3::Zero());
  b.set_gravity(Vec3(0.0, 0.0, -9.81));
  const std::string what = solve_error(b.finalize());
  std::printf("%s\n", what.c_str());
  EXPECT_NE(what.find("load factor 0:"), std::string::npos) << what;
  EXPECT_NE(what.find("no stiffness against the load"), std::string::npos) << what;
  EXPECT_NE(what.find("cable 'rope' node 8 r.z"), std::string::npos) << what;
}

// Singular but consistent: the stress-free arc without a load is an equilibrium (its zero modes
// are not driven); the solve returns it and reports that it is not isolated. A clamped straight
// cantilever under a tip load is regular.
TEST(StaticSolverSingular, UnloadedArcSolvesAndReportsANonIsolatedEquilibrium) {
  const Model arc = clamped_arc(8, 0.0);
  StaticModelProblem problem(arc);
  StaticSolver solver(problem);
  VecX y = problem.initial_guess();
  const StaticSolverStatistics st = solver.solve(y);
  std::printf("arc: smallest singular value %.2e, direction %s\n", st.smallest_singular_value,
              st.singular_direction.c_str());
  EXPECT_LT((y - problem.initial_guess()).lpNorm<Eigen::Infinity>(), 1e-14);
  EXPECT_LT(st.smallest_singular_value, StaticSolverOptions{}.singular_tolerance);
  EXPECT_NE(st.singular_direction.find("cable 'arc' node"), std::string::npos);

  ModelBuilder b;
  const Index c =
      b.add_cable("beam", straight_cable(Vec3::Zero(), Vec3::UnitX(), 8), bending_section());
  b.pin("root", {c, 0}, Vec3::Zero());
  b.align_slope("root.slope", {c, 0}, Vec3::UnitX());
  b.add_node_force({c, -1}, Vec3(0.0, -2.0, 0.0));  // k = PL²/EI = 2
  const Model beam = b.finalize();
  StaticModelProblem beam_problem(beam);
  StaticSolver beam_solver(beam_problem, {.load_steps = 4});
  VecX yb = beam_problem.initial_guess();
  const StaticSolverStatistics sb = beam_solver.solve(yb);
  std::printf("beam: smallest singular value %.2e, residual %.2e\n", sb.smallest_singular_value,
              sb.residual_norm);
  EXPECT_TRUE(sb.singular_direction.empty());
  EXPECT_GT(sb.smallest_singular_value, 1e3 * StaticSolverOptions{}.singular_tolerance);
  // Converged to ‖Δq‖ ≤ 1e-11 (q ~ 1 m): the force residual is at most that times the largest
  // stiffness, EA/l = 8e6 N/m.
  EXPECT_LT(sb.residual_norm, 8e6 * StaticSolverOptions{}.increment_tolerance);
}

// Non-converging (not singular): the k = 10 cantilever in one increment with 3 Newton iterations
// and no cuts fails as an ordinary SolverError that names the load factor.
TEST(StaticSolverNonConverging, FailsWithTheLoadFactor) {
  ModelBuilder b;
  const Index c =
      b.add_cable("beam", straight_cable(Vec3::Zero(), Vec3::UnitX(), 8), bending_section());
  b.pin("root", {c, 0}, Vec3::Zero());
  b.align_slope("root.slope", {c, 0}, Vec3::UnitX());
  b.add_node_force({c, -1}, Vec3(0.0, -10.0, 0.0));
  const Model beam = b.finalize();
  StaticModelProblem problem(beam);
  StaticSolver solver(problem, {.max_iterations = 3, .max_step_cuts = 0});
  VecX y = problem.initial_guess();
  try {
    (void)solver.solve(y);
    ADD_FAILURE() << "converged";
  } catch (const SingularStaticProblem& e) {
    ADD_FAILURE() << "reported as singular: " << e.what();
  } catch (const SolverError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("static solve stopped at load factor 0 after 0 step cuts"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("did not converge in 3 iterations"), std::string::npos) << what;
  }
}

/// R(y, s) = atan(y) − s·atan(30), not evaluable beyond y = 5 (std::domain_error, as a rod past
/// its singular configuration): Newton from 0 climbs 1.54, 3.37, 6.51, … at s = 1.
class AtanBeyondAWall final : public StaticProblem {
 public:
  AtanBeyondAWall() : pattern_(1) {
    pattern_.add(0, 0);
    pattern_.freeze();
  }
  Index size() const override { return 1; }
  const SparsityPattern& jacobian_pattern() const override { return pattern_; }
  Index coordinate_count() const override { return 1; }
  void residual(std::span<const double> y, double s, std::span<double> r) override {
    if (y[0] > 5.0) throw std::domain_error("atan problem: not evaluable beyond y = 5");
    r[0] = std::atan(y[0]) - s * std::atan(30.0);
  }
  void jacobian(std::span<const double> y, double, std::span<double> values) override {
    values[0] = 1.0 / (1.0 + y[0] * y[0]);
  }
  std::string describe_row(Index) const override { return "y"; }

 private:
  SparsityPattern pattern_;
};

// StaticProblem's contract: an iterate the problem cannot evaluate is a failed iteration, and the
// increment is cut — also when it is the last iterate of an increment that ran out of iterations
// (evaluated for the report: 6.51 after 3 iterations here). Before, that exception left the
// solver (`ancf static` aborted without outputs). With no cuts allowed the failure is reported at
// once, with the problem's message, y at the last converged state.
TEST(StaticSolverNonConverging, UnevaluableIteratesAreFailedIterations) {
  AtanBeyondAWall problem;
  StaticSolver solver(problem, {.max_iterations = 3, .max_step_cuts = 0});
  VecX y = VecX::Zero(1);
  try {
    (void)solver.solve(y);
    ADD_FAILURE() << "converged";
  } catch (const SolverError& e) {
    const std::string what = e.what();
    std::printf("reported: %s; y = %g\n", what.c_str(), y[0]);
    EXPECT_NE(what.find("after 0 step cuts"), std::string::npos) << what;
    EXPECT_NE(what.find("not evaluable beyond y = 5 at iteration 4"), std::string::npos) << what;
    EXPECT_EQ(y[0], 0.0);  // the last converged state: the start
  }
  // With cuts the increments below the wall converge; the solution (30) stays out of reach.
  StaticSolver cutting(problem, {.max_iterations = 30});
  y.setZero();
  EXPECT_THROW((void)cutting.solve(y), SolverError);
  std::printf("with cuts: stopped at y = %.6f (tan of the last load factor times atan 30)\n", y[0]);
  EXPECT_GT(y[0], 1.0);
  EXPECT_LE(y[0], 5.0);
}

}  // namespace
}  // namespace ancf
