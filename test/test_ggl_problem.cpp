// The GGL (stabilized index-2) DAE of a model: its analytic Jacobian ∂F/∂y + c_j ∂F/∂y' against
// central finite differences of its residual on the multibody scenes (DESIGN §8), and the
// consistent initial values it computes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ancf/system/model_builder.hpp"
#include "dense_matrix.hpp"
#include "fd_check.hpp"
#include "multibody_scenes.hpp"

// Heap allocations, counted by replacing the global operator new (malloc/free underneath; GCC
// cannot see that new and delete are replaced as a pair and warns, hence the pragma).
namespace {
std::size_t g_allocations = 0;
}  // namespace
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
#pragma GCC diagnostic pop

namespace ancf {
namespace {

using testing::dense;
using testing::JointVariant;
using testing::multibody_scene;

// A generic point (t, y, y'): coordinates perturbed off the constraints, random velocities,
// derivatives and multipliers, μ ≠ 0 so that every block of the Jacobian is exercised.
struct Point {
  double t = 0.37;
  VecX y, yp;
};
Point random_point(const GglProblem& ggl, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Index n = ggl.model().coordinate_count(), size = ggl.size();
  Point p;
  p.y = VecX::Zero(size);
  p.yp = VecX::Zero(size);
  ggl.initial_state(as_span(p.y));
  for (Index i = 0; i < n; ++i) {
    p.y[i] += 0.02 * u(rng);
    p.y[n + i] += 0.5 * u(rng);
    p.yp[i] = p.y[n + i] + 0.1 * u(rng);
    p.yp[n + i] = 2.0 * u(rng);
  }
  for (Index i = 2 * n; i < size; ++i) {
    p.y[i] = (i < ggl.mu_offset() ? 5.0 : 0.3) * u(rng);
    p.yp[i] = u(rng);  // λ', μ' do not enter F
  }
  return p;
}

class GglJacobian : public ::testing::TestWithParam<JointVariant> {};

// ∂F/∂y is the Jacobian at c_j = 0; ∂F/∂y' is its c_j-slope (J is affine in c_j). Both against
// central differences with the Richardson-estimated tolerance of fd_check.hpp.
TEST_P(GglJacobian, EqualsFiniteDifferencesOfTheResidual) {
  const Model model = multibody_scene(GetParam());
  GglProblem ggl(model);
  const Point p = random_point(ggl, 17);
  const SparsityPattern& pattern = ggl.jacobian_pattern();
  VecX values(pattern.nonzeros());
  ggl.jacobian(p.t, as_span(p.y), as_span(p.yp), 0.0, as_span(values));
  const MatX d_dy = dense(pattern, values);
  const double c_j = 2.5e3;
  ggl.jacobian(p.t, as_span(p.y), as_span(p.yp), c_j, as_span(values));
  const MatX combined = dense(pattern, values);
  const MatX d_dyp = (combined - d_dy) / c_j;

  auto residual_of = [&](bool derivative) {
    return [&, derivative](const VecX& x) {
      VecX r(ggl.size());
      const VecX& y = derivative ? p.y : x;
      const VecX& yp = derivative ? x : p.yp;
      ggl.residual(p.t, as_span(y), as_span(yp), as_span(r));
      return r;
    };
  };
  for (const bool derivative : {false, true}) {
    const fdcheck::Result r = fdcheck::check_jacobian(
        residual_of(derivative), derivative ? p.yp : p.y, derivative ? d_dyp : d_dy);
    std::printf("  dF/d%s: worst error/tolerance %.3f, error/max|J| %.2e\n",
                derivative ? "y'" : "y", r.max_ratio, r.max_rel);
    EXPECT_TRUE(r.ok()) << (derivative ? "dF/dy'" : "dF/dy") << ": row " << ggl.describe_row(r.row)
                        << ", column " << ggl.describe_row(r.col) << ": analytic " << r.analytic
                        << ", FD " << r.fd;
  }
  // ∂F/∂y' is [I 0 0 0; 0 M 0 0; 0 0 0 0; 0 0 0 0]: the identity block up to the rounding of
  // (c_j + x − x)/c_j with x the ∂F_q/∂q entries sharing the diagonal, the constraint rows exactly.
  const Index n = model.coordinate_count();
  const double eps = std::numeric_limits<double>::epsilon();
  EXPECT_LE((d_dyp.topLeftCorner(n, n) - MatX::Identity(n, n)).cwiseAbs().maxCoeff(),
            4 * eps * (1.0 + d_dy.topLeftCorner(n, n).cwiseAbs().maxCoeff() / c_j));
  EXPECT_EQ(d_dyp.bottomRows(ggl.size() - 2 * n).cwiseAbs().maxCoeff(), 0.0);
}

// The consistent values satisfy every residual row to round-off, starting from a state that
// violates the constraints (the multibody scene's slope join is not satisfied initially) and a
// perturbed, moving one; they also satisfy Φ_q v' = γ (acceleration level).
TEST_P(GglJacobian, ConsistentValuesSatisfyTheResidual) {
  const Model model = multibody_scene(GetParam());
  GglProblem ggl(model);
  const Index n = model.coordinate_count(), m = model.multiplier_count();
  for (const unsigned seed : {0u, 23u}) {
    Point p = random_point(ggl, seed == 0 ? 1 : seed);
    if (seed == 0) ggl.initial_state(as_span(p.y));
    ggl.consistent_values(p.t, as_span(p.y), as_span(p.yp));
    VecX r(ggl.size());
    ggl.residual(p.t, as_span(p.y), as_span(p.yp), as_span(r));
    // Scale of each row's terms: the Jacobian row times the unknowns' scales (fd_check's idea of
    // a rounding scale); the rows must vanish to a few hundred ε of it.
    VecX values(ggl.jacobian_pattern().nonzeros());
    ggl.jacobian(p.t, as_span(p.y), as_span(p.yp), 0.0, as_span(values));
    const MatX j = dense(ggl.jacobian_pattern(), values);
    double worst = 0.0;
    Index worst_row = 0;
    for (Index i = 0; i < ggl.size(); ++i) {
      double scale = 0.0;
      for (Index k = 0; k < ggl.size(); ++k)
        scale += std::abs(j(i, k)) * std::max(std::abs(p.y[k]), ggl.variable_scale(k));
      scale += i < 2 * n ? std::abs(p.yp[i]) : 0.0;
      const double ratio = std::abs(r[i]) / (std::numeric_limits<double>::epsilon() * scale);
      if (ratio > worst) worst = ratio, worst_row = i;
    }
    std::printf("  seed %u: largest |F_i| / (eps * scale_i) = %.1f at %s\n", seed, worst,
                ggl.describe_row(worst_row).c_str());
    EXPECT_LT(worst, 1e3) << ggl.describe_row(worst_row);
    // μ = 0 at consistent values.
    EXPECT_EQ(p.y.tail(m).cwiseAbs().maxCoeff(), 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Joints, GglJacobian,
                         ::testing::Values(JointVariant::revolute, JointVariant::spherical,
                                           JointVariant::fixed),
                         [](const ::testing::TestParamInfo<JointVariant>& p) {
                           return p.param == JointVariant::revolute    ? "Revolute"
                                  : p.param == JointVariant::spherical ? "Spherical"
                                                                       : "Fixed";
                         });

// DaeProblem contract: residual() and jacobian() do not allocate (they run many times per step).
// The counter sees operator new (std::vector, std::string, std::function ...), not Eigen's
// dynamic matrices, which call malloc directly; the control shows the counter works.
TEST(GglProblem, ResidualAndJacobianDoNotAllocate) {
  {
    const std::size_t before = g_allocations;
    std::vector<double> control(7);
    EXPECT_GT(g_allocations, before);
  }
  const Model model = multibody_scene(JointVariant::revolute);
  GglProblem ggl(model);
  const Point p = random_point(ggl, 3);
  VecX r(ggl.size()), values(ggl.jacobian_pattern().nonzeros());
  ggl.residual(p.t, as_span(p.y), as_span(p.yp), as_span(r));  // warm-up (frame cache etc.)
  const std::size_t before = g_allocations;
  for (int k = 0; k < 3; ++k) {
    ggl.residual(p.t + 0.01 * k, as_span(p.y), as_span(p.yp), as_span(r));
    ggl.jacobian(p.t + 0.01 * k, as_span(p.y), as_span(p.yp), 100.0, as_span(values));
  }
  EXPECT_EQ(g_allocations, before);
}

// A rod section of ρA = 0.2 kg/m with the given polar inertia ρJ_p [kg m].
RodSection rod_section(double polar_inertia) {
  RodSection section;
  section.axial_stiffness = 1e3;
  section.torsional_stiffness = 0.3;
  section.bending_stiffness_2 = section.bending_stiffness_3 = 0.5;
  section.mass_per_length = 0.2;
  section.polar_inertia = polar_inertia;
  return section;
}

// The same with Kirchhoff rods clamped into a body and a rotating frame including twist (the
// twist rows of rod_twist_constraint.hpp, evaluated with fixed-size kernels).
TEST(GglProblem, ResidualAndJacobianWithRodTwistRowsDoNotAllocate) {
  ModelBuilder b;
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(0.1, 0.0, 1.0), 3);
  const RodSection section = rod_section(1e-3);
  const Index r1 =
      b.add_rod("r1", g, CableSection{}, section, rod_frames_with_normal(g, Vec3::UnitY()));
  const Index r2 =
      b.add_rod("r2", g, CableSection{}, section, rod_frames_with_normal(g, Vec3::UnitY()));
  RigidBodyInertia in{1.0, Vec3::Zero(), Vec3(0.01, 0.01, 0.02).asDiagonal()};
  const Index body = b.add_body("disk", in, Vec3(g.nodes.back().head<3>()));
  DrivenFrame f;
  f.law = AngleLaw::constant_rate(0.5);
  const int frame = b.add_driven_frame(f);
  b.attach_node_to_body("a", {r1, -1}, body);
  b.align_slope_to_body("a.slope", {r1, -1}, body);
  b.tie_twist_to_body("a.twist", {r1, -1}, body);
  b.attach_node_to_frame("f", {r2, -1}, frame);
  b.align_slope_to_frame("f.slope", {r2, -1}, frame);
  b.tie_twist_to_frame("f.twist", {r2, -1}, frame);
  const Model model = b.finalize();
  ASSERT_EQ(model.twist_rows().size(), 2u);
  GglProblem ggl(model);
  const Point p = random_point(ggl, 5);
  VecX r(ggl.size()), values(ggl.jacobian_pattern().nonzeros());
  ggl.residual(p.t, as_span(p.y), as_span(p.yp), as_span(r));  // warm-up
  const std::size_t before = g_allocations;
  for (int k = 0; k < 3; ++k) {
    ggl.residual(p.t + 0.01 * k, as_span(p.y), as_span(p.yp), as_span(r));
    ggl.jacobian(p.t + 0.01 * k, as_span(p.y), as_span(p.yp), 100.0, as_span(values));
  }
  EXPECT_EQ(g_allocations, before);
}

// Variable classes, scales and names follow the layout y = [q; v; λ; μ].
TEST(GglProblem, LayoutClassesAndNames) {
  const Model model = multibody_scene(JointVariant::spherical);
  const GglProblem ggl(model);
  const Index n = model.coordinate_count(), m = model.multiplier_count();
  ASSERT_EQ(ggl.size(), 2 * n + 2 * m);
  EXPECT_EQ(ggl.variable_class(0), VariableClass::position);
  EXPECT_EQ(ggl.variable_class(n), VariableClass::velocity);
  EXPECT_EQ(ggl.variable_class(2 * n), VariableClass::algebraic);
  EXPECT_EQ(ggl.variable_class(2 * n + 2 * m - 1), VariableClass::algebraic);
  for (Index i = 0; i < ggl.size(); ++i)
    EXPECT_GT(ggl.variable_scale(i), 0.0) << ggl.describe_row(i);
  EXPECT_EQ(ggl.describe_row(0), "q of cable 'cable0' node 0 r.x");
  EXPECT_EQ(ggl.describe_row(n + 5), "v of cable 'cable0' node 0 r_x.z");
  EXPECT_EQ(ggl.describe_row(2 * n + 1), "λ of " + model.describe_row(n + 1));
  EXPECT_EQ(ggl.describe_row(2 * n + m + 1), "μ of " + model.describe_row(n + 1));
  EXPECT_EQ(model.describe_row(n + 1).rfind("constraint '", 0), 0u);
  // Position and slope scales differ by the length scale.
  EXPECT_EQ(ggl.variable_scale(0), ggl.scales().length);
  EXPECT_EQ(ggl.variable_scale(3), 1.0);
}

// TwistScale::position_equivalent: a rod's twist angles (node angles and interior twists) get the
// scale L/r_g, r_g = √(ρJ_p/ρA), their rates that over T; everything else keeps its scale.
TEST(GglProblem, PositionEquivalentTwistScaleIsLengthOverRadiusOfGyration) {
  ModelBuilder b;
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(0.0, 0.0, 1.2), 4);
  const RodSection section = rod_section(0.2 * 0.004 * 0.004 / 2.0);  // ρA r²/2, r = 4 mm
  const Index rod =
      b.add_rod("rod", g, CableSection{}, section, rod_frames_with_normal(g, Vec3::UnitY()));
  b.pin("clamp.r", {rod, 0}, Vec3::Zero());
  b.align_slope("clamp.t", {rod, 0}, Vec3::UnitZ());
  b.fix_twist("clamp.twist", {rod, 0});
  const Model model = b.finalize();
  const RodData& data = *model.cables()[0].rod;
  const Index twists = data.twist_block_size(model.cables()[0].node_count);
  ASSERT_EQ(twists, 2 * 5 - 1);  // quadratic twist: 5 node angles, 4 interior twists
  const GglProblem unit(model);
  const GglProblem scaled(model, GglScales{.twist = TwistScale::position_equivalent});
  const Index n = model.coordinate_count();
  const double r_g = std::sqrt(section.polar_inertia / section.mass_per_length);
  ASSERT_EQ(unit.scales().length, scaled.scales().length);
  ASSERT_EQ(unit.scales().time, scaled.scales().time);
  const double big_l = scaled.scales().length, time = scaled.scales().time;
  for (Index i = 0; i < n; ++i) {
    const bool twist = i >= data.twist_first && i < data.twist_first + twists;
    if (twist) {
      EXPECT_EQ(unit.variable_scale(i), 1.0) << unit.describe_row(i);
      EXPECT_NEAR(scaled.variable_scale(i), big_l / r_g, 1e-12 * big_l / r_g)
          << scaled.describe_row(i);
      EXPECT_NEAR(scaled.variable_scale(n + i), big_l / r_g / time, 1e-12 * big_l / r_g / time);
    } else {
      EXPECT_EQ(scaled.variable_scale(i), unit.variable_scale(i)) << scaled.describe_row(i);
      EXPECT_EQ(scaled.variable_scale(n + i), unit.variable_scale(n + i));
    }
  }
}

}  // namespace
}  // namespace ancf
