// Graded meshes (mesh_grading.hpp): the node fractions of the fixed mapping (uniform bit for bit,
// nested under refinement, end elements end_ratio times the others), the graded generators, and
// what grading is for: a clamped rod under tension turns within ℓ = √(EI/T) of the clamp, and a
// graded mesh resolves that layer (docs/capture.md, "A clamped end has a bending boundary
// layer"; closed form of the elastica under tension below).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/mesh_grading.hpp"
#include "ancf/system/model_builder.hpp"
#include "ancf/system/static_model_problem.hpp"

namespace ancf {
namespace {

TEST(MeshGrading, UniformIsExactlyKOverN) {
  const std::vector<double> f = node_fractions(7, 0.3, MeshGrading{});
  for (Index k = 0; k <= 7; ++k) EXPECT_EQ(f[k], static_cast<double>(k) / 7.0);
  const CableGeometry a =
      helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), 0.1, 0.3, 2.0, 0.15, 7);
  const CableGeometry b =
      helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), 0.1, 0.3, 2.0, 0.15, 7, f);
  for (Index k = 0; k <= 7; ++k) EXPECT_EQ(a.nodes[k], b.nodes[k]);
  // Given fractions, a length is L(f_{k+1} − f_k): L/n to the round-off of two fractions ≤ 1
  // (half an ulp of 1 each) and the product, i.e. within 4 ε L.
  const double length = std::hypot(0.1 * 2.0, 0.15);
  for (Index k = 0; k < 7; ++k)
    EXPECT_NEAR(a.element_lengths[k], b.element_lengths[k],
                4.0 * std::numeric_limits<double>::epsilon() * length);
}

TEST(MeshGrading, RefinementIsNestedAndEndsAreGraded) {
  const MeshGrading g{.end_ratio = 0.1, .end_length = 0.02};
  const double length = 0.268;
  const std::vector<double> coarse = node_fractions(12, length, g);
  const std::vector<double> fine = node_fractions(24, length, g);
  for (Index k = 0; k <= 12; ++k) EXPECT_NEAR(fine[2 * k], coarse[k], 4e-16);
  for (Index k = 0; k < 24; ++k) EXPECT_GT(fine[k + 1], fine[k]);
  // Symmetric, and where the elements are small against ℓ the end element is end_ratio times the
  // middle one up to the O(h/ℓ) variation of the density across it.
  const std::vector<double> f = node_fractions(400, length, g);
  for (Index k = 0; k <= 400; ++k) EXPECT_NEAR(f[k] + f[400 - k], 1.0, 1e-15);
  const double end = f[1] - f[0], middle = f[201] - f[200];
  EXPECT_NEAR(end / middle, 0.1, 0.1 * 0.1);
  // One end only: the other end's elements are those of the middle.
  const std::vector<double> s =
      node_fractions(400, length, {.end_ratio = 0.1, .end_length = 0.02, .at_end = false});
  EXPECT_NEAR((s[1] - s[0]) / (s[400] - s[399]), 0.1, 0.1 * 0.1);
  EXPECT_THROW((void)node_fractions(4, length, {.end_ratio = 0.0, .end_length = 0.02}), ModelError);
  EXPECT_THROW((void)node_fractions(4, length, {.end_ratio = 0.5, .end_length = 0.0}), ModelError);
  // ℓ/L below round-off (found by the fuzzer): refused, not returned as NaN fractions.
  EXPECT_THROW((void)node_fractions(8, 1e150, {.end_ratio = 0.5, .end_length = 1e-300}),
               ModelError);
}

// A refinement band inside: nested, element at the band centre band_ratio times the far ones
// (with and without graded ends), the band where it is asked for, and the band's checks.
TEST(MeshGrading, BandIsNestedAndRefinesWhereAsked) {
  const double length = 0.268;
  const MeshGrading band{.band_ratio = 0.25, .band_width = 0.01, .band_centre = 0.3};
  const std::vector<double> coarse = node_fractions(12, length, band);
  const std::vector<double> fine = node_fractions(24, length, band);
  for (Index k = 0; k <= 12; ++k) EXPECT_NEAR(fine[2 * k], coarse[k], 4e-16);
  const std::vector<double> f = node_fractions(800, length, band);
  Index smallest = 0;
  for (Index k = 0; k < 800; ++k) {
    EXPECT_GT(f[k + 1], f[k]);
    if (f[k + 1] - f[k] < f[smallest + 1] - f[smallest]) smallest = k;
  }
  // The smallest element sits at the band centre (to an element) and is band_ratio times the end
  // elements (e^{−(0.3L/μ)²} ≈ 0 there) up to the O(h/μ) variation of the density across it.
  EXPECT_NEAR(0.5 * (f[smallest] + f[smallest + 1]), 0.3, 2.0 / 800);
  EXPECT_NEAR((f[smallest + 1] - f[smallest]) / (f[800] - f[799]), 0.25, 0.25 * 0.05);
  // Ends and band together: both refine, the middle of the free span stays the coarsest.
  const std::vector<double> both = node_fractions(
      800, length, {.end_ratio = 0.2, .end_length = 0.01, .band_ratio = 0.5, .band_width = 0.02});
  const double end = both[1] - both[0], centre = both[401] - both[400],
               free = both[201] - both[200];
  EXPECT_NEAR(end / free, 0.2, 0.2 * 0.05);
  EXPECT_NEAR(centre / free, 0.5, 0.5 * 0.05);
  EXPECT_THROW((void)node_fractions(4, length, {.band_ratio = 0.5, .band_width = 0.0}), ModelError);
  EXPECT_THROW((void)node_fractions(4, length, {.band_ratio = 1.5, .band_width = 0.01}),
               ModelError);
  EXPECT_THROW(
      (void)node_fractions(4, length, {.band_ratio = 0.5, .band_width = 0.01, .band_centre = 1.2}),
      ModelError);
}

TEST(MeshGrading, GradedHelixNodesLieOnTheHelix) {
  const double radius = 0.1, twist = 2.2256, rise = 0.15, length = std::hypot(radius * twist, rise);
  const std::vector<double> f = node_fractions(24, length, {.end_ratio = 0.2, .end_length = 0.01});
  const CableGeometry g =
      helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), radius, 1.57, twist, rise, 24, f);
  double sum = 0.0;
  for (Index k = 0; k < 24; ++k) {
    sum += g.element_lengths[k];
    const Vec3 r = g.nodes[k].head<3>();
    EXPECT_NEAR(std::hypot(r.x(), r.y()), radius, 1e-15);
    EXPECT_NEAR(r.z(), rise * f[k], 1e-15);
    EXPECT_NEAR(g.nodes[k].tail<3>().norm(), 1.0, 1e-15);
  }
  EXPECT_NEAR(sum, length, 1e-15);
  EXPECT_LT(g.element_lengths[0], 0.5 * g.element_lengths[12]);
}

// A straight rod along x, clamped at x = 0 (position, slope, twist), pulled at its free end by a
// dead force T at φ = 65° to the clamped direction, in the x–y plane. Away from the clamp the rod
// lies along the force; at the clamp it turns within ℓ = √(EI/T) by the elastica under tension,
// θ' = −(2/ℓ) sin(θ/2) (θ the angle to the force, semi-infinite layer), which shortens the
// projection on the force by 2ℓ(1 − cos(φ/2)) and offsets the rod sideways by 2ℓ sin(φ/2).
// The rope values of studies/scenes/capture_rod.toml: ℓ = 2.9 mm on L = 0.268 m.
struct LayerRun {
  double along, across;  // tip relative to the clamp, along the force and across it [m]
};
LayerRun clamp_layer(Index elements, const MeshGrading& grading) {
  const double length = 0.268, tension = 145.0, phi = 65.0 * std::numbers::pi / 180.0;
  const std::vector<double> f = node_fractions(elements, length, grading);
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(length, 0, 0), elements, f);
  RodSection r;
  r.axial_stiffness = 3.1416e5;
  r.torsional_stiffness = 9.26e-4;
  r.bending_stiffness_2 = r.bending_stiffness_3 = 1.20e-3;
  r.mass_per_length = 0.024504;
  r.polar_inertia = 1.23e-8;
  ModelBuilder b;
  const Index rod =
      b.add_rod("rope", g, CableSection{}, r, rod_frames_with_normal(g, Vec3::UnitY()));
  b.pin("clamp.r", {rod, 0}, Vec3::Zero());
  b.align_slope("clamp.t", {rod, 0}, Vec3::UnitX());
  b.fix_twist("clamp.twist", {rod, 0});
  const Vec3 e_force(std::cos(phi), std::sin(phi), 0.0), e_across(std::sin(phi), -std::cos(phi), 0);
  b.add_node_force({rod, -1}, tension * e_force);
  const Model m = b.finalize();
  StaticModelProblem problem(m);
  StaticSolver solver(problem, {.load_steps = 20});
  VecX y = problem.initial_guess();
  (void)solver.solve(y);
  const Vec3 tip = y.segment<3>(m.node_coordinate(0, -1));
  return {tip.dot(e_force), tip.dot(e_across)};
}

TEST(MeshGrading, GradedMeshResolvesTheClampLayerOfATautRod) {
  const double length = 0.268, tension = 145.0, ea = 3.1416e5,
               phi = 65.0 * std::numbers::pi / 180.0;
  const double ell = std::sqrt(1.20e-3 / tension);
  const MeshGrading graded{.end_ratio = 0.1, .end_length = 0.01, .at_end = false};
  // Closed form (inextensible layer; the stretch T/EA = 4.6e-4 changes the layer terms by that
  // fraction, ~1e-6 m, and e^{−L/ℓ} is nil).
  const double along = length * (1.0 + tension / ea) - 2.0 * ell * (1.0 - std::cos(phi / 2.0));
  const double across = 2.0 * ell * std::sin(phi / 2.0);
  const LayerRun reference = clamp_layer(96, graded);
  std::printf(
      "clamp layer: ℓ = %.3f mm; closed form along %.6f mm, across %.6f mm; graded 96 "
      "elements %.6f / %.6f mm\n",
      1e3 * ell, 1e3 * along, 1e3 * across, 1e3 * reference.along, 1e3 * reference.across);
  EXPECT_NEAR(reference.along, along, 5e-6);
  EXPECT_NEAR(reference.across, across, 5e-6);
  for (const Index n : {12, 24}) {
    const LayerRun u = clamp_layer(n, MeshGrading{}), gr = clamp_layer(n, graded);
    const double eu = std::hypot(u.along - reference.along, u.across - reference.across);
    const double eg = std::hypot(gr.along - reference.along, gr.across - reference.across);
    std::printf("  %2lld elements: tip error uniform %.3e m, graded %.3e m (ratio %.1f)\n",
                static_cast<long long>(n), eu, eg, eu / eg);
    EXPECT_LT(eg, 0.2 * eu);
  }
}

}  // namespace
}  // namespace ancf
