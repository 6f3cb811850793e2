// Static reference problems with closed-form or high-accuracy solutions (REFERENCES §1–§3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "ancf/scenes/cantilever.hpp"
#include "ancf/system/model_builder.hpp"
#include "ancf/system/static_model_problem.hpp"

namespace ancf {
namespace {

// ---------------------------------------------------------------------------------------------
// Mattiasson (1981) inextensible elastica, REFERENCES §1. EA L²/EI = 1e7 keeps the extensibility
// error (O(P/EA) ≤ 1e-6 for k = 10) below the 1e-5 target; 64 elements put the discretisation
// error (membrane locking decays like h⁴ here) below 2e-6.
struct MattiassonCase {
  double k, u, w, rotation;
};

class Mattiasson : public ::testing::TestWithParam<MattiassonCase> {};

TEST_P(Mattiasson, TipDisplacementAndRotationWithin1e5Relative) {
  const MattiassonCase ref = GetParam();
  CantileverSpec spec;
  spec.length = 1.0;
  spec.bending_stiffness = 1.0;
  spec.axial_stiffness = 1e7;
  spec.tip_load = ref.k;
  spec.elements = 64;
  const CantileverTip tip = solve_cantilever(spec, 10);
  const double u = -tip.displacement.x(), w = -tip.displacement.y();
  const double eu = std::abs(u / ref.u - 1), ew = std::abs(w / ref.w - 1);
  const double er = std::abs(tip.rotation / ref.rotation - 1);
  std::printf("Mattiasson k = %g, 64 elements: rel. errors u %.2e, w %.2e, rotation %.2e\n", ref.k,
              eu, ew, er);
  EXPECT_LT(eu, 1e-5);
  EXPECT_LT(ew, 1e-5);
  EXPECT_LT(er, 1e-5);
  EXPECT_NEAR(tip.displacement.z(), 0.0, 1e-12);  // planar problem stays planar
}

INSTANTIATE_TEST_SUITE_P(K, Mattiasson,
                         ::testing::Values(MattiassonCase{1, 0.05643324, 0.30172077, 0.46135195},
                                           MattiassonCase{3, 0.25442018, 0.60325344, 0.98601695},
                                           MattiassonCase{10, 0.55499560, 0.81060902, 1.43028554}));

// ---------------------------------------------------------------------------------------------
// Extensible elastica, REFERENCES §2: the continuum limit of the Green/Gerstmayr–Shabana element.
TEST(ExtensibleElastica, ConvergesAtOrderAbove3p5To1e8Metre) {
  const double dx_ref = -0.508922870415, dy_ref = -1.208398131108;
  std::vector<double> errors;
  const std::vector<Index> meshes{4, 8, 16, 32, 64};
  for (Index n : meshes) {
    CantileverSpec spec;
    spec.length = 2.0;
    spec.axial_stiffness = 2.07e9;
    spec.bending_stiffness = 1.725e6;
    spec.tip_load = 3.0 * spec.bending_stiffness / (spec.length * spec.length);
    spec.elements = n;
    const CantileverTip tip = solve_cantilever(spec, 4);
    errors.push_back(std::hypot(tip.displacement.x() - dx_ref, tip.displacement.y() - dy_ref));
    std::printf("elastica %3ld elements: tip error %.3e m\n", static_cast<long>(n), errors.back());
  }
  // Least-squares slope of log(error) against log(h) over the mesh sequence.
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double m = static_cast<double>(meshes.size());
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const double x = std::log(1.0 / meshes[i]), y = std::log(errors[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double order = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  std::printf("elastica observed nodal convergence order %.2f\n", order);
  EXPECT_GE(order, 3.5);
  EXPECT_LT(errors.back(), 1e-8);
}

// ---------------------------------------------------------------------------------------------
// Elastic catenary, REFERENCES §3 (Irvine 1981). Irvine's tension is T = EA(stretch − 1), which is
// exactly the elastic-line strain measure, so that formulation is used; EI = 0.
struct Catenary {
  double span = 0.8, length = 1.0, rho_a = 0.1, g = 9.81, ea = 1e3;
};

// Inextensible catenary parameter a from 2a sinh(D/(2a)) = L (bisection on a monotone function).
double catenary_parameter(double span, double length) {
  double lo = 1e-3, hi = 1e3;
  for (int i = 0; i < 200; ++i) {
    const double a = 0.5 * (lo + hi);
    (2 * a * std::sinh(span / (2 * a)) > length ? lo : hi) = a;
  }
  return 0.5 * (lo + hi);
}

// Initial guess: the inextensible catenary of a slightly longer cable (stretch 1 + δ), so that the
// guess is taut (a slack pure cable has a singular tangent) while close to the solution.
CableGeometry catenary_guess(const Catenary& c, Index elements, double stretch) {
  const double a = catenary_parameter(c.span, c.length * stretch);
  CableGeometry g;
  for (Index k = 0; k <= elements; ++k) {
    const double s = c.length * stretch * k / elements;  // stretched arc length
    const double xc = a * std::asinh(s / a - std::sinh(c.span / (2 * a)));
    NodeCoordinates n;
    n << xc + 0.5 * c.span, 0.0, a * (std::cosh(xc / a) - std::cosh(c.span / (2 * a))),
        stretch / std::cosh(xc / a), 0.0, stretch * std::tanh(xc / a);
    g.nodes.push_back(n);
  }
  g.element_lengths.assign(elements, c.length / elements);
  return g;
}

TEST(ElasticCatenary, SagAndSupportTensionWithin1e4Relative) {
  const Catenary c;
  const double sag_ref = 0.2657655657, tension_ref = 0.5919137430;
  for (Index n : {16, 32}) {
    ModelBuilder b;
    CableSection s;
    s.strain = StrainMeasure::elastic_line;
    s.axial_stiffness = c.ea;
    s.mass_per_length = c.rho_a;
    const Index cable =
        b.add_cable("catenary", straight_cable(Vec3::Zero(), c.length * Vec3::UnitX(), n), s);
    b.set_initial_configuration(cable, catenary_guess(c, n, 1.001));
    b.set_gravity({0.0, 0.0, -c.g});
    b.pin("left support", {cable, 0}, Vec3::Zero());
    b.pin("right support", {cable, -1}, c.span * Vec3::UnitX());
    const Model model = b.finalize();
    StaticModelProblem problem(model);
    StaticSolver solver(problem);
    VecX y = problem.initial_guess();
    const StaticSolverStatistics stats = solver.solve(y);
    const double sag = -y[model.node_coordinate(cable, n / 2) + 2];
    // The pin's multiplier is minus the support reaction on the cable: |λ| = T at the support.
    const double tension_left = y.segment<3>(model.coordinate_count()).norm();
    const double tension_right = y.segment<3>(model.coordinate_count() + 3).norm();
    const double e_sag = std::abs(sag / sag_ref - 1), e_t = std::abs(tension_left / tension_ref - 1);
    std::printf("catenary %2ld elements: sag rel. error %.2e, support tension rel. error %.2e (%d Newton)\n",
                static_cast<long>(n), e_sag, e_t, stats.newton_iterations);
    EXPECT_LT(e_sag, 1e-4);
    EXPECT_LT(e_t, 1e-4);
    EXPECT_NEAR(tension_left, tension_right, 1e-12 * tension_ref);  // symmetry
  }
}

}  // namespace
}  // namespace ancf
