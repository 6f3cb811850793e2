// Kirchhoff rod dynamics: a straight cantilever whirled by a suddenly applied end moment inclined
// to it (bending, torsion and the twist inertia all act), and a helix clamped at its base released
// under a sideways gravity or a suddenly applied distributed moment (curved reference:
// bending–torsion coupling, the interior twist coordinates moving), integrated by IDA (GGL index 2,
// BDF) and by generalized-α (index 3), with a realistic twist inertia ρJ = ρA r²/2. Both commit the
// rod history on accepted steps only (DaeProblem/SecondOrderProblem::commit_step); they must agree
// to within generalized-α's own time-discretisation error, estimated from its runs at h and h/2
// (second order: e_{h/2} ≈ |q_h − q_{h/2}|/3).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>

#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ancf/system/model_builder.hpp"
#include "ancf/system/multibody_problem.hpp"
#include "ancf/system/rod_history.hpp"

namespace ancf {
namespace {

RodSection damped_section() {
  RodSection r;
  r.axial_stiffness = 1e4;
  r.torsional_stiffness = 0.8;
  r.bending_stiffness_2 = 1.0;
  r.bending_stiffness_3 = 1.3;
  r.mass_per_length = 0.1;
  r.polar_inertia = 0.1 * 0.01 * 0.01 / 2;  // ρA r²/2 of a solid 1 cm radius section
  // Kelvin–Voigt damping on every strain rate: the suddenly applied moment excites axial and
  // twist waves that an accurate IDA run would otherwise have to resolve for the whole interval.
  r.axial_damping = 2.0;       // relaxation time c/EA = 2e-4 s
  r.torsional_damping = 0.01;  // 1.25e-2 s
  r.bending_damping = 0.01;
  return r;
}

// Clamp node 0 of a straight rod along x from the origin: position, slope and twist.
void clamp_along_x(ModelBuilder& b, Index rod) {
  b.pin("clamp.r", {rod, 0}, Vec3::Zero());
  b.align_slope("clamp.t", {rod, 0}, Vec3::UnitX());
  b.fix_twist("clamp.twist", {rod, 0});
}

Model whirled_rod() {
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(1, 0, 0), 6);
  const RodSection r = damped_section();
  ModelBuilder b;
  const Index rod =
      b.add_rod("rod", g, CableSection{}, r, rod_frames_with_normal(g, Vec3::UnitY()));
  clamp_along_x(b, rod);
  b.add_node_moment({rod, -1}, Vec3(1.0, 0.0, 1.0));
  return b.finalize();
}

// One turn of a helix (radius 0.1 m, rise 0.3 m, 8 elements) clamped with its twist at the base,
// free at the top, released under gravity across its axis, or (distributed_moment ≠ 0) loaded
// suddenly by a distributed dead moment instead. Softer than the whirled rod so that it swings by
// centimetres within kT.
Model released_helix(const Vec3& distributed_moment = Vec3::Zero()) {
  const CableGeometry g = helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), 0.1, 0.0,
                                      2.0 * std::numbers::pi, 0.3, 8);
  RodSection r = damped_section();
  r.torsional_stiffness = 0.16;
  r.bending_stiffness_2 = 0.2;
  r.bending_stiffness_3 = 0.26;
  ModelBuilder b;
  const bool moment = distributed_moment.squaredNorm() > 0.0;
  if (!moment) b.set_gravity(Vec3(0.0, -9.81, 0.0));
  const Index rod = b.add_rod("helix", g, CableSection{}, r,
                              rod_frames_toward_axis(g, Vec3::Zero(), Vec3::UnitZ()));
  b.pin("clamp.r", {rod, 0}, Vec3(g.nodes[0].head<3>()));
  b.align_slope("clamp.t", {rod, 0}, Vec3(g.nodes[0].tail<3>()));
  b.fix_twist("clamp.twist", {rod, 0});
  if (moment) b.add_distributed_moment("m", rod, distributed_moment);
  return b.finalize();
}

constexpr double kT = 0.1;

// Tip position and the tip material triad's d₂ at t = kT.
struct Tip {
  Vec3 r, d2;
};

Tip genalpha_tip(const Model& m, double h, double frame_turn) {
  MultibodyProblem problem(m);
  problem.set_rod_frame_turn(frame_turn);
  GeneralizedAlphaOptions o;
  o.step_size = h;
  o.rho_infinity = 0.9;
  o.rtol = 1e-9;
  o.atol_position = 1e-11;
  o.atol_velocity = 1e-9;
  o.atol_multiplier = 1e-9;
  GeneralizedAlphaStepper stepper(problem, o);
  stepper.initialize(0.0);
  stepper.advance_to(kT);
  const VecX& q = stepper.positions();
  return {q.segment<3>(m.node_coordinate(0, -1)),
          rod_node_triad(m, 0, -1, as_span(q), problem.workspace().rods).col(1)};
}

// Richardson estimate of the error of the finest of three runs at h, h/2, h/4 (values a, b, c)
// with the observed order p = log₂(|a − b|/|b − c|): e_c ≈ |b − c|/(2^p − 1).
struct Estimate {
  double order, error;
};
Estimate richardson(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double p = std::log2((a - b).norm() / (b - c).norm());
  return {p, (b - c).norm() / (std::exp2(p) - 1.0)};
}

// IDA (rtol 1e-8) against generalized-α at h = 5e-4, 2.5e-4 and 1.25e-4 on the tip position and
// d₂ at kT: within 3× generalized-α's own error estimated with its observed order (second order
// in positions; the tip triad under a suddenly applied moment converges more slowly, measured
// ≈ 1.2 for the distributed moment's d₂, so a second-order estimate would understate it).
// `scales` sets IDA's absolute tolerances (GglScales: slope and twist scales). Returns the
// estimate for d₂, IDA's frame updates (RodHistory::frame_updates) and its steps.
struct Agreement {
  Estimate d2;
  long frame_updates, ida_steps;
};
Agreement expect_integrators_agree(const Model& m, const char* name,
                                   double frame_turn = kRodCommitTurn, GglScales scales = {}) {
  const Tip a = genalpha_tip(m, 5e-4, frame_turn), b = genalpha_tip(m, 2.5e-4, frame_turn),
            c = genalpha_tip(m, 1.25e-4, frame_turn);
  GglProblem ggl(m, scales);
  ggl.set_rod_frame_turn(frame_turn);
  IdaOptions o;
  o.rtol = 1e-8;
  o.output_times = {kT};
  IdaIntegrator ida(ggl, o);
  ida.run({});
  const Vec3 ida_r = Vec3(ida.y()[m.node_coordinate(0, -1)], ida.y()[m.node_coordinate(0, -1) + 1],
                          ida.y()[m.node_coordinate(0, -1) + 2]);
  const Vec3 ida_d2 = rod_node_triad(m, 0, -1, ida.y(), ggl.workspace().rods).col(1);
  const Estimate est_r = richardson(a.r, b.r, c.r), est_d2 = richardson(a.d2, b.d2, c.d2);
  const double diff_r = (ida_r - c.r).norm(), diff_d2 = (ida_d2 - c.d2).norm();
  const Vec3 r0 = m.initial_coordinates().segment<3>(m.node_coordinate(0, -1));
  std::printf(
      "%s, t = %.2f s: tip moved %.4f m; IDA (%.6f %.6f %.6f), generalized-α h=1.25e-4 "
      "(%.6f %.6f %.6f)\n",
      name, kT, (c.r - r0).norm(), ida_r.x(), ida_r.y(), ida_r.z(), c.r.x(), c.r.y(), c.r.z());
  std::printf(
      "|IDA − gα| = %.2e m (gα error estimate %.2e, order %.2f), tip d2: %.2e (estimate %.2e, "
      "order %.2f); IDA steps %ld\n",
      diff_r, est_r.error, est_r.order, diff_d2, est_d2.error, est_d2.order,
      ida.statistics().steps);
  EXPECT_GT((c.r - r0).norm(), 0.02) << name;  // the rod has moved substantially
  EXPECT_GT(est_r.order, 0.5) << name;         // generalized-α converges
  EXPECT_GT(est_d2.order, 0.5) << name;
  // IDA at rtol 1e-8 is far more accurate than generalized-α at h = 1.25e-4 (measured: rtol 1e-10
  // moves d₂ by ≤ 2e-8): the difference is generalized-α's error, up to the factor the estimate
  // may be off by; 1e-8 is IDA's own share (rtol 1e-8 on coordinates of O(1) m). d₂ turns with
  // the twist: with TwistScale::position_equivalent IDA's share there is rtol × the twist scale.
  const double twist_share = o.rtol * ggl.variable_scale(m.cables()[0].rod->twist_first);
  EXPECT_LT(diff_r, 3.0 * est_r.error + 1e-8) << name;
  EXPECT_LT(diff_d2, 3.0 * est_d2.error + std::max(1e-8, twist_share)) << name;
  return {est_d2, ggl.workspace().rods.frame_updates, ida.statistics().steps};
}

TEST(KirchhoffRodDynamics, IdaAndGeneralizedAlphaAgree) {
  expect_integrators_agree(whirled_rod(), "whirled straight rod");
}

TEST(KirchhoffRodDynamics, ReleasedHelixIdaAndGeneralizedAlphaAgree) {
  expect_integrators_agree(released_helix(), "released helix");
}

// The distributed moment's load and load stiffness in both integrators (IDA's Newton matrix and
// generalized-α's iteration matrix take −∂Q/∂q).
TEST(KirchhoffRodDynamics, HelixUnderDistributedMomentIdaAndGeneralizedAlphaAgree) {
  expect_integrators_agree(released_helix(Vec3(0.3, 0.0, 0.2)), "helix under a distributed moment");
}

// docs/rod.md, "Frame updates": the same run with the node frames updated only after a 2 rad turn
// ([integrator] rod_frame_turn) has none within kT, and the tip triad then converges at second
// order in generalized-α (with updates after 0.1 rad: order 1.15, the test above).
TEST(KirchhoffRodDynamics, WithoutFrameUpdatesTheTriadConvergesAtSecondOrder) {
  const Model m = released_helix(Vec3(0.3, 0.0, 0.2));
  const Agreement updating = expect_integrators_agree(m, "frames updated after 0.1 rad");
  const Agreement fixed = expect_integrators_agree(m, "frames updated after 2 rad", 2.0);
  std::printf("frame updates in IDA: %ld (0.1 rad), %ld (2 rad); d2 order %.2f / %.2f\n",
              updating.frame_updates, fixed.frame_updates, updating.d2.order, fixed.d2.order);
  EXPECT_GT(updating.frame_updates, 0);
  EXPECT_EQ(fixed.frame_updates, 0);
  EXPECT_GT(fixed.d2.order, 1.7);  // second order, against 1.15 with the updates
}

// docs/rod.md, "Frame updates": with a frame update at every accepted step (rod_frame_turn = 0)
// α̇ is the spin about the tangent relative to a frame re-based each step, whose own spin is then
// O(h), and the tip triad converges at second order again. How much the three settings differ
// from each other at the finest step is the twist-inertia model's own error (the smallest-rotation
// frame's spin the constant twist mass leaves out), printed for the docs.
TEST(KirchhoffRodDynamics, FrameUpdatesAtEveryStepConvergeAtSecondOrder) {
  const Model m = released_helix(Vec3(0.3, 0.0, 0.2));
  const Agreement every_step = expect_integrators_agree(m, "frames updated at every step", 0.0);
  std::printf("frame updates in IDA: %ld, IDA steps %ld; d2 order %.2f\n", every_step.frame_updates,
              every_step.ida_steps, every_step.d2.order);
  EXPECT_GT(every_step.frame_updates, 100);  // IDA updated at (nearly) every one of its steps
  EXPECT_GT(every_step.d2.order, 1.7);       // second order, against 1.15 with updates after 0.1
  const Tip t0 = genalpha_tip(m, 1.25e-4, 0.0), t1 = genalpha_tip(m, 1.25e-4, kRodCommitTurn),
            t2 = genalpha_tip(m, 1.25e-4, 2.0);
  std::printf(
      "generalized-α, h = 1.25e-4: tip d2 with updates after 0.1 / 2 rad against every step: "
      "%.2e / %.2e (its time-step error: %.2e)\n",
      (t1.d2 - t0.d2).norm(), (t2.d2 - t0.d2).norm(), every_step.d2.error);
}

// What a frame update changes (docs/rod.md, "Frame updates"). Committing the history at a state q
// leaves the triads, the strains, the centreline forces and the twist forces at q as they were, but
// not the slope forces: δα now rotates about the tangent relative to a different smallest-rotation
// frame. With a = R_i e₁ the old reference tangent, t = r'/|r'| and P = (I − t tᵀ)/|r'| = ∂t/∂r',
// the twist a slope change brings along is c·δr', c = −Pᵀ(a × t)/(1 + a·t) (0 once a = t), so
// the slope force changes by exactly −f_α c, f_α the twist row's force. In a twist equilibrium
// (f_α = Q_α, statics) the residual is unchanged; in dynamics f_α − Q_α = −ρJ α̈, and every
// update moves the slope equations by the twist inertia force times c. (Not what makes the tip
// triad converge at first order where frames update: removing it leaves the order; docs/rod.md.)
TEST(KirchhoffRodDynamics, FrameUpdateChangesTheSlopeForcesByTheTwistForce) {
  const Model m = released_helix();
  const CableData& cable = m.cables()[0];
  const RodData& rod = *cable.rod;
  SystemState state = SystemState::initial(m);
  for (Index k = 0; k < cable.node_count; ++k) {  // turn the tangents, twist the rod
    const Index c = m.node_coordinate(0, k);
    state.q[c + 3] += 0.2 * std::sin(1.0 + static_cast<double>(k));
    state.q[c + 4] += 0.15 * std::cos(2.0 + static_cast<double>(k));
  }
  for (Index i = 0; i < rod.twist_block_size(cable.node_count); ++i)
    state.q[rod.twist_first + i] += 0.3 * std::sin(0.7 * static_cast<double>(i));
  Workspace ws(m);
  VecX before(m.system_size()), after(m.system_size());
  assemble_residual(m, state, 1.0, ws, as_span(before));
  const RodHistory old_history = ws.rods;
  commit_rod_history(m, as_span(state.q), ws.rods, 0.0);
  ASSERT_EQ(ws.rods.frame_updates, 1);
  assemble_residual(m, state, 1.0, ws, as_span(after));
  const double scale = before.lpNorm<Eigen::Infinity>();
  double largest_change = 0.0, largest_twist_force = 0.0;
  for (Index k = 0; k < cable.node_count; ++k) {
    const Index c = m.node_coordinate(0, k);
    const Vec3 a = old_history.frames[0][static_cast<std::size_t>(k)].col(0);
    const Vec3 slope = state.q.segment<3>(c + 3), t = slope.normalized();
    const Mat3 p = (Mat3::Identity() - t * t.transpose()) / slope.norm();
    const Vec3 spin = -(p.transpose() * a.cross(t)) / (1.0 + a.dot(t));
    const double f_alpha = before[rod.twist_first + k];
    const Vec3 change = after.segment<3>(c + 3) - before.segment<3>(c + 3);
    EXPECT_LT((after.segment<3>(c) - before.segment<3>(c)).norm(), 1e-14 * scale) << k;
    EXPECT_LT(std::abs(after[rod.twist_first + k] - before[rod.twist_first + k]), 1e-14 * scale);
    EXPECT_LT((change + f_alpha * spin).norm(), 1e-14 * scale) << k;
    largest_change = std::max(largest_change, change.norm());
    largest_twist_force = std::max(largest_twist_force, std::abs(f_alpha));
  }
  std::printf(
      "slope-force change at the update up to %.3e (twist forces up to %.3e, all up to %.3e)\n",
      largest_change, largest_twist_force, scale);
  // The effect is there (the tangents turned by up to ≈ 0.2 rad, |c| ≈ turn/|r'|), and the formula
  // above is all of it.
  EXPECT_GT(largest_change, 1e-2 * largest_twist_force);
}

// A step whose Newton iterate turns a node's tangent over (the element throws std::domain_error:
// the smallest rotation from the committed frame is undefined) is a failed attempt, and the step
// is halved (SecondOrderProblem's contract, as IDA's DaeProblem has it). A straight cantilever
// rolled up by a suddenly applied end moment 2πEI/L with a first step of 0.1 s overshoots at t = 0;
// before this was handled the run ended there with the element's message.
TEST(KirchhoffRodDynamics, StepWhoseIterateTurnsATangentOverIsHalved) {
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(1, 0, 0), 16);
  RodSection r;
  r.axial_stiffness = 1e4;
  r.torsional_stiffness = 1.0;
  r.bending_stiffness_2 = r.bending_stiffness_3 = 1.0;
  r.mass_per_length = 1.0;
  r.polar_inertia = 1e-4;
  ModelBuilder b;
  const Index rod =
      b.add_rod("rod", g, CableSection{}, r, rod_frames_with_normal(g, Vec3::UnitY()));
  clamp_along_x(b, rod);
  b.add_node_moment({rod, -1}, Vec3(0.0, 0.0, 2.0 * std::numbers::pi));
  const Model m = b.finalize();
  MultibodyProblem problem(m);
  GeneralizedAlphaOptions o;
  o.step_size = 0.1;
  GeneralizedAlphaStepper stepper(problem, o);
  stepper.initialize(0.0);
  ASSERT_NO_THROW(stepper.advance_to(0.2));
  const GeneralizedAlphaStatistics& st = stepper.statistics();
  std::printf("roll-up, h = 0.1 s: %ld steps, %ld halvings, %ld Newton iterations to t = 0.2 s\n",
              static_cast<long>(st.steps), static_cast<long>(st.step_halvings),
              static_cast<long>(st.newton_iterations));
  EXPECT_GE(st.step_halvings, 1);
  EXPECT_TRUE(stepper.positions().allFinite());
}

// IDA's position-equivalent slope and twist tolerances ([integrator.ida] slope_scale and
// twist_scale, GglScales): a twist error counts as the motion r_g δα it gives the section's
// points. The integrators still agree as above (the tip position to generalized-α's error, d₂ to
// that plus rtol × L/r_g), and IDA takes no more steps than with unit scales.
TEST(KirchhoffRodDynamics, PositionEquivalentTolerancesKeepTheAgreement) {
  const GglScales scaled{.slope = SlopeScale::position_equivalent,
                         .twist = TwistScale::position_equivalent};
  for (const auto& [model, name] : {std::pair{whirled_rod(), "whirled straight rod"},
                                    std::pair{released_helix(), "released helix"}}) {
    const Agreement unit = expect_integrators_agree(model, name);
    const Agreement position = expect_integrators_agree(model, name, kRodCommitTurn, scaled);
    std::printf("%s: IDA steps %ld (unit scales), %ld (position-equivalent)\n", name,
                unit.ida_steps, position.ida_steps);
    EXPECT_LE(position.ida_steps, unit.ida_steps) << name;
  }
}

}  // namespace
}  // namespace ancf
