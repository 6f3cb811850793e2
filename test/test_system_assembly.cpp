// The assembled iteration matrix against central finite differences of the assembled residual
// (DESIGN §8), the velocity-level constraint against the time derivative of Φ, the zero resultant
// of internal forces in a free system, and redundancy detection.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <chrono>
#include <cstdio>
#include <random>

#include "ancf/core/error.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/model_builder.hpp"
#include "dense_matrix.hpp"
#include "fd_check.hpp"
#include "multibody_scenes.hpp"

namespace ancf {
namespace {

using testing::dense;

using testing::JointVariant;
using testing::multibody_scene;

// A generic state near the initial one: perturbed coordinates (constraints violated on purpose,
// so every term is exercised), random velocities, accelerations and multipliers, t inside the
// drive ramps.
SystemState random_state(const Model& model, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SystemState s = SystemState::initial(model);
  s.t = 0.37;
  for (Index i = 0; i < model.coordinate_count(); ++i) {
    s.q[i] += 0.02 * u(rng);
    s.v[i] += 0.5 * u(rng);
    s.a[i] = 2.0 * u(rng);
  }
  for (Index i = 0; i < model.multiplier_count(); ++i) s.lambda[i] = 5.0 * u(rng);
  return s;
}

class AssembledMatrix : public ::testing::TestWithParam<JointVariant> {};

// Each weight in turn isolates ∂R/∂q (with the geometric stiffness and the constraint columns
// ∂R/∂λ = Φ_qᵀ), ∂R/∂v and ∂R/∂a; then the combinations used by IDA and generalized-α.
TEST_P(AssembledMatrix, EqualsFiniteDifferencesOfTheResidual) {
  const Model model = multibody_scene(GetParam());
  Workspace ws(model);
  const Index n = model.coordinate_count(), m = model.multiplier_count(),
              size = model.system_size();
  const SystemState s0 = random_state(model, 11);
  VecX values(model.pattern().nonzeros());

  // Residual as a function of y = [x; λ] where x is q, v or a.
  auto residual_of = [&](int which) {
    return [&, which](const VecX& y) {
      SystemState s = s0;
      VecX& x = which == 0 ? s.q : which == 1 ? s.v : s.a;
      x = y.head(n);
      s.lambda = y.tail(m);
      VecX r(size);
      assemble_residual(model, s, 1.0, ws, as_span(r));
      return r;
    };
  };
  double worst = 0.0;
  for (int which = 0; which < 3; ++which) {
    const IterationWeights w{which == 0 ? 1.0 : 0.0, which == 1 ? 1.0 : 0.0,
                             which == 2 ? 1.0 : 0.0};
    assemble_iteration_matrix(model, s0, w, ws, as_span(values));
    MatX j = dense(model.pattern(), values);
    VecX y(size);
    y << (which == 0 ? s0.q : which == 1 ? s0.v : s0.a), s0.lambda;
    if (which != 0) j.bottomRows(m).setZero();  // Φ depends on q only
    const fdcheck::Result r = fdcheck::check_jacobian(residual_of(which), y, j);
    std::printf("  d/d%s: worst error/tolerance %.3f, error/max|J| %.2e\n",
                which == 0   ? "q"
                : which == 1 ? "v"
                             : "a",
                r.max_ratio, r.max_rel);
    EXPECT_TRUE(r.ok()) << "d/d" << which << ": row " << model.describe_row(r.row) << ", column "
                        << model.describe_row(r.col) << ": analytic " << r.analytic << ", FD "
                        << r.fd;
    worst = std::max(worst, r.max_ratio);
  }
  // The weighted matrix is linear in the weights: generalized-α (h = 1e-3, ρ∞ = 0.8) and IDA.
  const double h = 1e-3, am = (2 * 0.8 - 1) / 1.8, af = 0.8 / 1.8, gamma = 0.5 - am + af;
  const double beta = 0.25 * (1 - am + af) * (1 - am + af);
  for (const IterationWeights w : {IterationWeights{1.0, gamma / (beta * h), 1.0 / (beta * h * h)},
                                   IterationWeights{0.0, 1.0, 2.5e3}}) {
    assemble_iteration_matrix(model, s0, w, ws, as_span(values));
    const MatX combined = dense(model.pattern(), values);
    MatX expected = MatX::Zero(size, size);
    for (int which = 0; which < 3; ++which) {
      const double wk = which == 0 ? w.w_q : which == 1 ? w.w_v : w.w_a;
      assemble_iteration_matrix(
          model, s0,
          IterationWeights{which == 0 ? 1.0 : 0.0, which == 1 ? 1.0 : 0.0, which == 2 ? 1.0 : 0.0},
          ws, as_span(values));
      MatX part = dense(model.pattern(), values);
      part.bottomRows(m).setZero();
      part.rightCols(m).setZero();
      expected += wk * part;
    }
    assemble_iteration_matrix(model, s0, IterationWeights{0, 0, 0}, ws, as_span(values));
    expected += dense(model.pattern(), values);  // constraint blocks, unweighted
    const double scale = expected.cwiseAbs().maxCoeff();
    EXPECT_LT((combined - expected).cwiseAbs().maxCoeff(),
              64 * std::numeric_limits<double>::epsilon() * scale);
  }
}

// Φ_q v + Φ_t is the total time derivative of Φ along q + v τ (central difference in τ).
TEST_P(AssembledMatrix, VelocityConstraintIsTimeDerivativeOfPhi) {
  const Model model = multibody_scene(GetParam());
  Workspace ws(model);
  const SystemState s0 = random_state(model, 5);
  const Index n = model.coordinate_count(), m = model.multiplier_count();
  VecX phi_dot(m);
  assemble_velocity_constraint(model, s0, ws, as_span(phi_dot));
  const fdcheck::Function phi_along = [&](const VecX& tau) {
    SystemState s = s0;
    s.t += tau[0];
    s.q += tau[0] * s0.v;
    s.lambda.setZero();
    VecX r(model.system_size());
    assemble_residual(model, s, 1.0, ws, as_span(r));
    return VecX(r.tail(m));
  };
  const fdcheck::Result r = fdcheck::check_jacobian(phi_along, VecX::Zero(1), phi_dot);
  std::printf("  Phi_q v + Phi_t: worst error/tolerance %.3f\n", r.max_ratio);
  EXPECT_TRUE(r.ok()) << model.describe_row(n + r.row);
}

INSTANTIATE_TEST_SUITE_P(Joints, AssembledMatrix,
                         ::testing::Values(JointVariant::revolute, JointVariant::spherical,
                                           JointVariant::fixed),
                         [](const ::testing::TestParamInfo<JointVariant>& p) {
                           return p.param == JointVariant::revolute    ? "Revolute"
                                  : p.param == JointVariant::spherical ? "Spherical"
                                                                       : "Fixed";
                         });

// Internal forces of a free system have zero resultant force and moment: cable elastic and
// damping forces, joint reactions Φ_qᵀλ, spring-dampers and drives between bodies. The resultant
// of a generalised force G is Σ_blocks t_b·G_b (translation field) and the moment Σ_b x_b × G_b.
TEST(FreeSystem, InternalForcesHaveZeroResultantForceAndMoment) {
  for (const JointVariant variant :
       {JointVariant::revolute, JointVariant::spherical, JointVariant::fixed}) {
    const Model model = multibody_scene(variant, false);
    Workspace ws(model);
    // Position rows e·(P₁ − P₂) are rotation invariant only where they hold, so positions of the
    // nodes in position constraints (cable0 nodes 3, 5; cable1 nodes 2, 4) and the bodies keep
    // their (consistent) initial values; every other coordinate is perturbed to load the cables.
    SystemState s = random_state(model, 3);
    const SystemState s_init = SystemState::initial(model);
    for (const auto& [cable, node] : {std::pair{0, 3}, {0, 5}, {1, 2}, {1, 4}})
      s.q.segment<3>(model.node_coordinate(cable, node)) =
          s_init.q.segment<3>(model.node_coordinate(cable, node));
    for (const BodyData& b : model.bodies())
      s.q.segment<12>(b.first_coordinate) = s_init.q.segment<12>(b.first_coordinate);
    s.a.setZero();
    const Index n = model.coordinate_count();
    VecX r(model.system_size());
    assemble_residual(model, s, 1.0, ws, as_span(r));
    Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
    double scale = 0.0;
    auto add_block = [&](Index b, bool translates) {
      const Vec3 g = r.segment<3>(b);
      if (translates) force += g;
      moment += s.q.segment<3>(b).cross(g);
      scale += g.norm() * (1.0 + s.q.segment<3>(b).norm());
    };
    for (const CableData& c : model.cables())
      for (Index k = 0; k < c.node_count; ++k) {
        add_block(c.first_coordinate + 6 * k, true);
        add_block(c.first_coordinate + 6 * k + 3, false);
      }
    for (const BodyData& b : model.bodies())
      for (int k = 0; k < 4; ++k) add_block(b.first_coordinate + 3 * k, k == 0);
    ASSERT_EQ(n, model.coordinate_count());
    // Summation of O(n) terms of size ≤ scale: round-off ≤ a few ε·scale.
    const double tol = 16 * std::numeric_limits<double>::epsilon() * scale;
    std::printf("  free system: |resultant| %.2e, |moment| %.2e, tolerance %.2e\n", force.norm(),
                moment.norm(), tol);
    EXPECT_LT(force.norm(), tol);
    EXPECT_LT(moment.norm(), tol);
  }
}

// Mass-proportional damping −α ρA ṙ on a rigid translation ṙ = v₀ of a curved, stress-free cable
// (Kelvin–Voigt terms on as well, which a rigid motion must not excite): the residual's resultant
// over the position rows is α m v₀ with m = ρA L (the Hermite position shape functions sum to 1),
// to round-off.
TEST(MassDamping, RigidTranslationFeelsAlphaTimesMassTimesVelocity) {
  CableSection s;
  s.axial_stiffness = 1e5;
  s.bending_stiffness = 0.2;
  s.mass_per_length = 0.3;
  s.axial_damping = 5.0;
  s.bending_damping = 0.01;
  s.mass_damping = 2.5;
  const double radius = 0.4, angle = 2.0;
  ModelBuilder b;
  b.add_cable("arc", arc_cable(Vec3::Zero(), Vec3::UnitX(), Vec3::UnitY(), radius, angle, 7), s);
  const Model model = b.finalize();
  SystemState state = SystemState::initial(model);
  const Vec3 v0(0.3, -1.2, 0.7);
  const CableData& c = model.cables()[0];
  for (Index k = 0; k < c.node_count; ++k) state.v.segment<3>(c.first_coordinate + 6 * k) = v0;
  state.a.setZero();
  Workspace ws(model);
  VecX r(model.system_size());
  assemble_residual(model, state, 1.0, ws, as_span(r));
  Vec3 position_rows = Vec3::Zero();
  double scale = 0.0;
  for (Index k = 0; k < c.node_count; ++k) {
    position_rows += r.segment<3>(c.first_coordinate + 6 * k);
    scale += r.segment<6>(c.first_coordinate + 6 * k).norm();
  }
  const Vec3 expected = s.mass_damping * s.mass_per_length * radius * angle * v0;
  const double tol = 16 * std::numeric_limits<double>::epsilon() * (scale + expected.norm());
  std::printf("  rigid translation: |resultant - alpha m v0| %.2e, tolerance %.2e\n",
              (position_rows - expected).norm(), tol);
  EXPECT_LT((position_rows - expected).norm(), tol);
}

// The cable tangent chosen in the Workspace (CableTangent) reaches the assembled matrix and
// nothing else: the residual is the same; a stretched EI = 0 cable gets the exact matrix, a
// uniformly compressed one a positive semidefinite stiffness (no compressive geometric term)
// where the exact one has negative eigenvalues.
TEST(CableTangentOption, ReachesTheIterationMatrixOnly) {
  CableSection s;
  s.axial_stiffness = 3e5;
  s.mass_per_length = 0.02;
  ModelBuilder b;
  b.add_cable("rope", straight_cable(Vec3::Zero(), 0.3 * Vec3::UnitX(), 4), s);
  const Model model = b.finalize();
  const Index size = model.system_size();
  for (const double stretch : {1.01, 0.99}) {
    SystemState state = SystemState::initial(model);
    state.q *= stretch;  // positions along x and slopes: uniform axial strain stretch − 1
    VecX r_exact(size), r_tension(size), values(model.pattern().nonzeros());
    Workspace exact(model), tension(model);
    tension.cable_tangent = CableTangent::tension_only;
    assemble_residual(model, state, 1.0, exact, as_span(r_exact));
    assemble_residual(model, state, 1.0, tension, as_span(r_tension));
    EXPECT_EQ(r_exact, r_tension);
    assemble_iteration_matrix(model, state, IterationWeights{}, exact, as_span(values));
    const MatX k_exact = dense(model.pattern(), values);
    assemble_iteration_matrix(model, state, IterationWeights{}, tension, as_span(values));
    const MatX k_tension = dense(model.pattern(), values);
    const double scale = k_exact.cwiseAbs().maxCoeff();
    if (stretch > 1.0) {
      EXPECT_EQ(k_exact, k_tension);
    } else {
      const Eigen::SelfAdjointEigenSolver<MatX> ee(k_exact), et(k_tension);
      EXPECT_LT(ee.eigenvalues().minCoeff(), -1e-3 * scale);
      EXPECT_GT(et.eigenvalues().minCoeff(),
                -64 * std::numeric_limits<double>::epsilon() * scale * static_cast<double>(size));
    }
  }
}

// Redundant constraints are reported by name at finalize().
TEST(Redundancy, IsReportedByName) {
  CableSection s;
  s.axial_stiffness = 1e3;
  s.mass_per_length = 0.1;
  {
    ModelBuilder b;
    const Index c = b.add_cable("rope", straight_cable(Vec3::Zero(), Vec3::UnitX(), 4), s);
    b.pin("first pin", {c, 0}, Vec3::Zero());
    b.pin("second pin", {c, 0}, Vec3::Zero());
    try {
      (void)b.finalize();
      FAIL() << "expected ModelError";
    } catch (const ModelError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("'second pin'"), std::string::npos) << msg;
      EXPECT_NE(msg.find("'first pin'"), std::string::npos) << msg;
    }
  }
  {
    ModelBuilder b;
    const Index body = b.add_body(
        "block", testing::box_inertia(1.0, Vec3(0.1, 0.1, 0.1), Vec3::Zero()), Vec3::Zero());
    b.fixed_to_ground("weld", body);
    b.revolute_to_ground("hinge", body, Vec3(0.05, 0.0, 0.0), Vec3::UnitZ());
    try {
      (void)b.finalize();
      FAIL() << "expected ModelError";
    } catch (const ModelError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("'hinge'"), std::string::npos) << msg;
      EXPECT_NE(msg.find("'weld'"), std::string::npos) << msg;
    }
  }
  // A well-posed scene passes (no exception).
  EXPECT_NO_THROW((void)multibody_scene(JointVariant::revolute));
}

// Many independent cables (K = 1000, each pinned at both ends: 6000 constraint rows): the check
// works group by group (rows sharing no column are independent), so it is fast (it was a dense
// Gram–Schmidt over all rows, O(K³): minutes here), and a redundancy inside one group is still
// found and attributed to the constraints of that group only, in row order.
TEST(Redundancy, ManyIndependentCablesAreCheckedGroupByGroup) {
  CableSection s;
  s.axial_stiffness = 1e3;
  s.mass_per_length = 0.1;
  constexpr int kCables = 1000;
  auto build = [&](bool redundant) {
    ModelBuilder b;
    for (int k = 0; k < kCables; ++k) {
      const Vec3 start(0.0, static_cast<double>(k), 0.0);
      const std::string name = "cable " + std::to_string(k);
      const Index c = b.add_cable(name, straight_cable(start, start + Vec3::UnitX(), 1), s);
      b.pin(name + " start", {c, 0}, start);
      b.pin(name + " end", {c, -1}, start + Vec3::UnitX());
      if (redundant && (k == 300 || k == 700))
        b.pin(name + " again", {c, -1}, start + Vec3::UnitX());
    }
    return b.finalize();
  };
  const auto begin = std::chrono::steady_clock::now();
  const Model model = build(false);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  std::printf("  finalize of %d pinned cables: %.3f s\n", kCables, seconds);
  EXPECT_EQ(model.multiplier_count(), 6 * kCables);
  EXPECT_LT(seconds, 10.0);  // ~0.05 s in Release; the dense check needed minutes
  try {
    (void)build(true);
    FAIL() << "expected ModelError";
  } catch (const ModelError& e) {
    const std::string msg = e.what();
    const std::size_t first = msg.find("'cable 300 again'"), second = msg.find("'cable 700 again'");
    ASSERT_NE(first, std::string::npos) << msg;
    ASSERT_NE(second, std::string::npos) << msg;
    EXPECT_LT(first, second) << msg;  // row order
    EXPECT_NE(msg.find("'cable 300 end'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'cable 700 end'"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("start'"), std::string::npos) << msg;  // other groups are not partners
    EXPECT_EQ(msg.find("'cable 299"), std::string::npos) << msg;
  }
}

}  // namespace
}  // namespace ancf
