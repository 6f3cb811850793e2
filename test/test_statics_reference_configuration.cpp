// Stress-free references and prestrain in assembled static solves.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "ancf/system/model_builder.hpp"
#include "ancf/system/static_model_problem.hpp"
#include "ancf/solvers/static_solver.hpp"

namespace ancf {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

class BothStrainMeasures : public ::testing::TestWithParam<StrainMeasure> {};

// A quarter circle with bending, clamped at one end and unloaded, must stay where it is: its
// reference is stress-free, so the residual vanishes and Newton takes a zero step. The same holds
// for a rigidly rotated and translated copy of it (objectivity of ε and κ).
TEST_P(BothStrainMeasures, QuarterCircleReferenceStaysForceFree) {
  CableSection s;
  s.strain = GetParam();
  s.axial_stiffness = 1e6;
  s.bending_stiffness = 10.0;
  s.mass_per_length = 1.0;
  const CableGeometry arc = arc_cable(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), 1.0,
                                      0.5 * std::numbers::pi, 8);
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(0.7, Vec3(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  CableGeometry moved = arc;
  for (NodeCoordinates& n : moved.nodes) {
    n.head<3>() = rot * n.head<3>() + Vec3(0.3, -1.0, 2.0);
    n.tail<3>() = rot * n.tail<3>();
  }
  for (const CableGeometry* placement : std::array<const CableGeometry*, 2>{&arc, &moved}) {
    ModelBuilder b;
    const Index cable = b.add_cable("arc", arc, s);
    b.set_initial_configuration(cable, *placement);
    b.pin("root", {cable, 0}, placement->nodes[0].head<3>());
    b.align_slope("root slope", {cable, 0}, placement->nodes[0].tail<3>());
    const Model model = b.finalize();
    StaticModelProblem problem(model);
    VecX y = problem.initial_guess();
    VecX r(problem.size());
    problem.residual(as_span(y), 1.0, as_span(r));
    // Force scale EA (axial) and EI/l² (bending); round-off of the kernels is a few hundred ε.
    const double force_scale = s.axial_stiffness + s.bending_stiffness / std::pow(arc.element_lengths[0], 2);
    const double rmax = r.lpNorm<Eigen::Infinity>();
    std::printf("quarter circle (%s): max residual / force scale = %.2e\n",
                placement == &arc ? "reference" : "rotated", rmax / force_scale);
    EXPECT_LT(rmax, 1e3 * kEps * force_scale);
    StaticSolver solver(problem);
    const VecX y0 = y;
    solver.solve(y);
    EXPECT_LT((y - y0).head(model.coordinate_count()).lpNorm<Eigen::Infinity>(), 1e3 * kEps);
  }
}

// A straight cable pinned at both ends in its reference with prestrain ε₀ carries N = EA ε₀: the
// support reactions (multipliers) equal EA ε₀ along the axis and the geometry does not move.
TEST_P(BothStrainMeasures, PrestrainedStraightCableCarriesEAEpsilon0) {
  CableSection s;
  s.strain = GetParam();
  s.axial_stiffness = 2e5;
  s.prestrain = 1.5e-3;
  s.mass_per_length = 0.1;
  const Vec3 end(1.2, 0.4, -0.3);
  ModelBuilder b;
  const Index cable = b.add_cable("taut", straight_cable(Vec3::Zero(), end, 10), s);
  b.pin("start", {cable, 0}, Vec3::Zero());
  b.pin("end", {cable, -1}, end);
  const Model model = b.finalize();
  StaticModelProblem problem(model);
  StaticSolver solver(problem);
  VecX y = problem.initial_guess();
  const VecX y0 = y;
  solver.solve(y);
  const double n_expected = s.axial_stiffness * s.prestrain;
  const Index m0 = model.coordinate_count();
  // Residual F + Φ_qᵀλ = 0 with F the cable's pull on the node: λ_start = +N t, λ_end = −N t.
  const Vec3 t = end.normalized();
  const Vec3 lambda_start = y.segment<3>(m0), lambda_end = y.segment<3>(m0 + 3);
  std::printf("prestrain: |lambda| / (EA eps0) - 1 = %.2e\n", lambda_start.norm() / n_expected - 1);
  // The strain is evaluated to round-off (≈ ε), so forces are exact to a few ε·EA.
  EXPECT_LT((lambda_start - n_expected * t).norm(), 100 * kEps * s.axial_stiffness);
  EXPECT_LT((lambda_end + n_expected * t).norm(), 100 * kEps * s.axial_stiffness);
  EXPECT_LT((y - y0).head(m0).lpNorm<Eigen::Infinity>(), 100 * kEps);
}

INSTANTIATE_TEST_SUITE_P(Formulation, BothStrainMeasures,
                         ::testing::Values(StrainMeasure::green_lagrange, StrainMeasure::elastic_line),
                         [](const ::testing::TestParamInfo<StrainMeasure>& p) {
                           return p.param == StrainMeasure::green_lagrange ? "GreenLagrange"
                                                                           : "ElasticLine";
                         });

}  // namespace
}  // namespace ancf
