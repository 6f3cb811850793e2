// "A scene pays only for what it has", checked exactly instead of timed (the timing side is
// bench/bench_assembly_features.cpp). Timings are noisy; these checks are deterministic:
//  * an undamped cable never reads velocities nor evaluates a damping matrix: NaN velocities and
//    any w_v give bit-identical residual and iteration matrix (code that ran with c = 0 would
//    propagate the NaN through 0·NaN, or read an unset damping block);
//  * an EI = 0 cable never evaluates curvature: at a collapsed element (r_x = 0) the curvature
//    terms are 0·∞ = NaN, yet residual and matrix stay finite;
//  * constant loads (gravity) do not enter the iteration matrix at all.
// Each probe has a control (damped / EI > 0 section) showing that it would detect the code
// running, so the checks cannot pass vacuously.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <random>

#include "ancf/system/assembly.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf {
namespace {

// A 20-element cable pinned at node 0, deformed (stretched, bent, rotated), with random nodal
// velocities; only the section (and gravity) vary.
Model cable_scene(const CableSection& section, const Vec3& gravity = Vec3::Zero()) {
  constexpr Index kElements = 20;
  ModelBuilder b;
  const CableGeometry reference = straight_cable(Vec3::Zero(), Vec3(2.0, 0.0, 0.0), kElements);
  const Index cable = b.add_cable("cable", reference, section);
  const Mat3 rot = Eigen::AngleAxisd(0.2, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  CableGeometry current = reference;
  std::vector<NodeCoordinates> velocities(current.nodes.size());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (std::size_t n = 0; n < current.nodes.size(); ++n) {
    const double s = 0.1 * static_cast<double>(n);
    current.nodes[n] << rot * Vec3(1.01 * s, 0.05 * std::sin(2.0 * s), 0.02 * s * s),
        rot * Vec3(1.01, 0.1 * std::cos(2.0 * s), 0.04 * s);
    for (int i = 0; i < 6; ++i) velocities[n][i] = u(rng);
  }
  velocities[0].head<3>().setZero();
  b.set_initial_configuration(cable, current, &velocities);
  b.pin("pin", {cable, 0}, Vec3::Zero());
  b.set_gravity(gravity);
  return b.finalize();
}

SystemState state_of(const Model& model) {
  SystemState s = SystemState::initial(model);
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (Index i = 0; i < model.coordinate_count(); ++i) s.a[i] = u(rng);
  for (Index i = 0; i < model.multiplier_count(); ++i) s.lambda[i] = 10.0 * u(rng);
  return s;
}

// Generalized-α weights (1, γ/(βh), 1/(βh²)); `with_velocity_weight = false` drops the middle one.
IterationWeights weights(bool with_velocity_weight) {
  const double h = 1e-3, gamma = 0.6, beta = 0.3025;
  return {.w_q = 1.0, .w_v = with_velocity_weight ? gamma / (beta * h) : 0.0, .w_a = 1.0 / (beta * h * h)};
}

VecX residual(const Model& model, const SystemState& s) {
  Workspace ws(model);
  VecX r(model.system_size());
  assemble_residual(model, s, 1.0, ws, as_span(r));
  return r;
}

VecX matrix(const Model& model, const SystemState& s, const IterationWeights& w) {
  Workspace ws(model);
  VecX values(model.pattern().nonzeros());
  assemble_iteration_matrix(model, s, w, ws, as_span(values));
  return values;
}

CableSection axial_section() {
  CableSection s;
  s.axial_stiffness = 4e6;
  s.mass_per_length = 0.15;
  return s;
}

// Bit-identical (==, not a tolerance): the skipped code contributes nothing, not "almost nothing".
TEST(AssemblyCost, UndampedCableReadsNoVelocitiesAndNoDampingMatrix) {
  CableSection bending = axial_section();
  bending.bending_stiffness = 6.0;
  for (const CableSection& section : {axial_section(), bending}) {
    const Model model = cable_scene(section);
    const SystemState s = state_of(model);
    SystemState s_nan = s;
    s_nan.v.setConstant(std::numeric_limits<double>::quiet_NaN());

    const VecX k_only = matrix(model, s, weights(false));
    EXPECT_TRUE(k_only.allFinite());
    EXPECT_TRUE(matrix(model, s, weights(true)) == k_only);
    EXPECT_TRUE(matrix(model, s_nan, weights(true)) == k_only);
    EXPECT_TRUE(residual(model, s_nan) == residual(model, s));
  }

  // Control: with c_a > 0 the same probes do see the damping code.
  CableSection damped = axial_section();
  damped.axial_damping = 40.0;
  const Model model = cable_scene(damped);
  const SystemState s = state_of(model);
  SystemState s_nan = s;
  s_nan.v.setConstant(std::numeric_limits<double>::quiet_NaN());
  EXPECT_FALSE(matrix(model, s, weights(true)) == matrix(model, s, weights(false)));
  EXPECT_FALSE(residual(model, s_nan).allFinite());
}

// Collapse element 5 to a point (both nodes at the same place, zero slopes): r_x = 0 at its Gauss
// points, where the Green axial force and stiffness are finite but |r_x × r_xx|/|r_x|³ is 0·∞.
TEST(AssemblyCost, AxialOnlyCableEvaluatesNoCurvature) {
  auto collapsed = [](const Model& model) {
    SystemState s = state_of(model);
    const Index first = model.node_coordinate(0, 5);
    s.q.segment<12>(first).setZero();
    return s;
  };
  const Model axial = cable_scene(axial_section());
  const SystemState s = collapsed(axial);
  EXPECT_TRUE(residual(axial, s).allFinite());
  EXPECT_TRUE(matrix(axial, s, weights(true)).allFinite());

  // Control: with EI > 0 the curvature code runs and the probe turns non-finite.
  CableSection bending = axial_section();
  bending.bending_stiffness = 6.0;
  const Model model = cable_scene(bending);
  EXPECT_FALSE(residual(model, collapsed(model)).allFinite());
}

// Gravity is a constant load: the iteration matrix is bit-identical with and without it.
TEST(AssemblyCost, ConstantLoadsDoNotTouchTheMatrix) {
  const Model plain = cable_scene(axial_section());
  const Model heavy = cable_scene(axial_section(), Vec3(0.0, 0.0, -9.81));
  ASSERT_EQ(plain.pattern().nonzeros(), heavy.pattern().nonzeros());
  ASSERT_FALSE(heavy.constant_load().isZero());
  const SystemState s = state_of(plain);
  EXPECT_TRUE(matrix(heavy, s, weights(true)) == matrix(plain, s, weights(true)));
}

}  // namespace
}  // namespace ancf
