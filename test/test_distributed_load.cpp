// Distributed dead forces ([[load]] kind = "distributed", ModelBuilder::add_distributed_force) on
// cables and rods: a cantilever under a uniform load over the whole span and over its outer
// part. Cubic Hermite elements with consistent loads reproduce the Euler–Bernoulli nodal
// displacements exactly for any load (the beam's Green's functions are cubic between nodes), so
// at small deflections the tip matches the closed form at 2 and 4 elements up to the geometric
// nonlinearity, of relative size (δ/L)²; and the scene reader builds the same load as the builder.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "ancf/io/scene.hpp"
#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/model_builder.hpp"
#include "ancf/system/static_model_problem.hpp"

namespace ancf {
namespace {

constexpr double kLength = 2.0, kEi = 3.0, kEa = 1e7;

// Tip deflection of a cantilever (clamped at x = 0) under q on [b, L]: ∫_b^L q x²(3L − x)/(6EI) dx.
double tip_deflection(double q, double b) {
  const double l = kLength;
  return q / (6.0 * kEi) * (0.75 * l * l * l * l - l * b * b * b + 0.25 * b * b * b * b);
}

// The test beam along x from the origin (EA = kEa, EI = kEi, GJ = 2, ρA = 1, r = 0.01 m, ρJ =
// ρA r²/2 as a scene's default), a cable (rod = false) or a rod; clamped at node 0 if asked.
Index add_beam(ModelBuilder& b, bool rod, Index elements, bool clamped,
               RodTwist twist = RodTwist::quadratic) {
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(kLength, 0, 0), elements);
  CableSection section;
  section.axial_stiffness = kEa;
  section.bending_stiffness = kEi;
  section.mass_per_length = 1.0;
  section.radius = 0.01;
  Index c = 0;
  if (rod) {
    RodSection r;
    r.axial_stiffness = kEa;
    r.torsional_stiffness = 2.0;
    r.bending_stiffness_2 = r.bending_stiffness_3 = kEi;
    r.mass_per_length = 1.0;
    r.polar_inertia = 5e-5;
    r.twist = twist;
    c = b.add_rod("beam", g, section, r, rod_frames_with_normal(g, Vec3::UnitY()));
    if (clamped) b.fix_twist("clamp.twist", {c, 0});
  } else {
    c = b.add_cable("beam", g, section);
  }
  if (clamped) {
    b.pin("clamp.r", {c, 0}, Vec3::Zero());
    b.align_slope("clamp.t", {c, 0}, Vec3::UnitX());
  }
  return c;
}

// Equilibrium of the built model (Newton to 2e-15 m: ≈ 3e-9 of the smallest tip deflection here).
VecX solved(const Model& m) {
  StaticModelProblem problem(m);
  StaticSolver solver(problem, {.increment_tolerance = 1e-15});
  VecX y = problem.initial_guess();
  solver.solve(y);
  return y;
}

// Tip deflection along −z of the clamped beam with q along −z on `range`.
double solved_tip(bool rod, Index elements, double q, ElementRange range) {
  ModelBuilder b;
  const Index c = add_beam(b, rod, elements, true);
  b.add_distributed_force("q", c, Vec3(0, 0, -q), range);
  const Model m = b.finalize();
  return -solved(m)[m.node_coordinate(c, -1) + 2];
}

TEST(DistributedLoad, CantileverTipIsTheEulerBernoulliOne) {
  // δ/L ≈ 3e-7. The geometric nonlinearity scales as q² (measured for the 2-element cable:
  // 1.4e-8 relative at q = 1e-5, 4.5e-12 at 1e-7; its Gauss-point axial strain couples the
  // membrane), ≈ 1.4e-10 here; the rod's is ≈ 1e-12 at 1e-5.
  const double q = 1e-6;
  for (const bool rod : {false, true})
    for (const Index n : {2, 4}) {
      const double full = solved_tip(rod, n, q, {});
      // Outer half loaded: elements [n/2, n), b = L/2.
      const double outer = solved_tip(rod, n, q, {n / 2, n / 2});
      const double exact_full = tip_deflection(q, 0.0),
                   exact_outer = tip_deflection(q, kLength / 2);
      std::printf("  %s %lld el.: uniform %.12e (exact %.12e), outer half %.12e (exact %.12e)\n",
                  rod ? "rod  " : "cable", static_cast<long long>(n), full, exact_full, outer,
                  exact_outer);
      EXPECT_NEAR(full, exact_full, 1e-8 * exact_full);
      EXPECT_NEAR(outer, exact_outer, 1e-8 * exact_outer);
      EXPECT_GT(std::abs(outer - full), 0.1 * exact_full);  // the range is honoured
    }
}

// Consistent nodal loads: the whole load on the range and its moment about the first node.
TEST(DistributedLoad, NodalLoadsAreConsistent) {
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(3.0, 0, 0), 3);
  ModelBuilder b;
  CableSection s;
  s.axial_stiffness = 1e5;
  s.mass_per_length = 0.5;
  const Index c = b.add_cable("rope", g, s);
  const Vec3 w(0.3, -2.0, 0.7);
  b.add_distributed_force("q", c, w, {1, 2});
  const Model m = b.finalize();
  const VecX& load = m.constant_load();
  Vec3 total = Vec3::Zero(), moment = Vec3::Zero();
  for (Index k = 0; k < m.cables()[c].node_count; ++k) {
    const Vec3 f = load.segment<3>(m.node_coordinate(c, k));
    const Vec3 f_slope = load.segment<3>(m.node_coordinate(c, k) + 3);
    total += f;
    // Virtual rotation about z: δr = ẑ × r, δr' = ẑ × r' (slopes along x): moment of both parts.
    moment += Vec3(static_cast<double>(k), 0, 0).cross(f) + Vec3::UnitX().cross(f_slope);
  }
  EXPECT_TRUE(load.segment<3>(m.node_coordinate(c, 0)).isZero());  // element 0 is not loaded
  EXPECT_LE((total - 2.0 * w).norm(), 1e-14 * w.norm());
  EXPECT_LE((moment - Vec3(2.0, 0, 0).cross(2.0 * w)).norm(), 1e-14 * 4 * w.norm());  // at x = 2
}

// The clamped rod beam under a distributed moment m [N m/m].
struct RodCantilever {
  Model model;
  VecX y;
};
RodCantilever solved_rod(Index elements, const Vec3& moment_per_length,
                         RodTwist twist = RodTwist::quadratic) {
  ModelBuilder b;
  const Index c = add_beam(b, true, elements, true, twist);
  b.add_distributed_moment("m", c, moment_per_length);
  RodCantilever out{b.finalize(), {}};
  out.y = solved(out.model);
  return out;
}

// A uniform torque m along a straight rod twists it as φ(s) = m(Ls − s²/2)/GJ, a quadratic that
// the quadratic twist holds exactly, also at a large angle (φ(L) = 1 rad here: on a straight rod
// the Kirchhoff torsion is linear and the dead moment stays on the axis). The linear twist with
// consistent loads is nodally exact too (linear elements for φ″ = −m/GJ).
TEST(DistributedLoad, RodUnderUniformTorqueTwistsAsTheClosedForm) {
  const double m = 1.0, gj = 2.0;
  for (const RodTwist twist : {RodTwist::quadratic, RodTwist::linear})
    for (const Index n : {1, 3}) {
      const RodCantilever r = solved_rod(n, Vec3(m, 0, 0), twist);
      const RodData& rod = *r.model.cables()[0].rod;
      double worst = 0.0;
      for (Index k = 0; k <= n; ++k) {
        const double s = kLength * static_cast<double>(k) / static_cast<double>(n);
        worst = std::max(worst,
                         std::abs(r.y[rod.twist_first + k] - m * (kLength * s - 0.5 * s * s) / gj));
      }
      std::printf(
          "  %s twist, %lld el.: tip twist %.15f rad (closed form %.15f), worst node %.2e\n",
          twist == RodTwist::linear ? "linear" : "quadratic", static_cast<long long>(n),
          r.y[rod.twist_first + n], m * kLength * kLength / (2 * gj), worst);
      EXPECT_LE(worst, 1e-12);
    }
}

// A small uniform bending moment m about +y: M(s) = m(L − s), tip z = −mL³/(3EI); nodally exact
// (see the file comment), up to the geometric nonlinearity (δ/L)² ≈ 1e-13.
TEST(DistributedLoad, RodUnderDistributedBendingMoment) {
  const double m = 1e-6;
  for (const Index n : {2, 4}) {
    const RodCantilever r = solved_rod(n, Vec3(0, m, 0));
    const double tip = r.y[r.model.node_coordinate(0, -1) + 2];
    const double exact = -m * kLength * kLength * kLength / (3 * kEi);
    std::printf("  %lld el.: tip z %.12e (closed form %.12e)\n", static_cast<long long>(n), tip,
                exact);
    EXPECT_NEAR(tip, exact, 1e-8 * std::abs(exact));
  }
}

TEST(DistributedLoad, SceneBuildsTheBuildersLoad) {
  const char* text = R"(
[[rod]]
name = "beam"
elements = 4
geometry = { kind = "straight", start = [0, 0, 0], end = [2, 0, 0] }
frame = { normal = [0, 1, 0] }
[rod.section]
EA = 1e7
EI = 3.0
GJ = 2.0
mass_per_length = 1.0
radius = 0.01

[[load]]
name = "wind"
kind = "distributed"
cable = "beam"
force = [0.0, 0.5, -1.5]
moment = [0.2, 0.0, -0.1]
elements = [1, 2]
)";
  const Scene scene = load_scene_from_string(text, "distributed.toml");
  const Model& m = scene.model;
  ModelBuilder b;
  const Index c = add_beam(b, true, 4, false);
  b.add_distributed_force("wind", c, Vec3(0, 0.5, -1.5), {1, 2});
  const Model expected = b.finalize();
  ASSERT_EQ(m.rod_distributed_moments().size(), 1u);
  const RodDistributedMomentData& d = m.rod_distributed_moments()[0];
  EXPECT_EQ(d.first, 1);
  EXPECT_EQ(d.count, 2);
  EXPECT_EQ(d.moment_per_length, Vec3(0.2, 0.0, -0.1));
  ASSERT_EQ(m.constant_load().size(), expected.constant_load().size());
  EXPECT_LE((m.constant_load() - expected.constant_load()).norm(), 1e-15);
  EXPECT_GT(m.constant_load().norm(), 0.5);  // not two empty loads
}

}  // namespace
}  // namespace ancf
