// The twist condition of a rod end fixed to a rigid body or a driven frame (d₂·b = 0,
// rod_twist_constraint.hpp): every derivative block against central differences with
// error-estimated tolerances (fd_check.hpp), also at large rotations; the assembled iteration
// matrix and the GGL Jacobian against central differences of their residuals on a model with
// rods clamped into a body and into a rotating frame; a static twist by a torque on the body
// (closed form θ = τL/GJ, reactions ±τ); and the torsional oscillation of a body on a revolute
// joint held by a rod clamped into it (closed-form frequency), with generalized-α and IDA.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "ancf/io/probe_recorder.hpp"
#include "ancf/io/scene.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"
#include "ancf/physics/rigid_body.hpp"
#include "ancf/physics/rod_twist_constraint.hpp"
#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/solvers/ida_integrator.hpp"
#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/ggl_problem.hpp"
#include "ancf/system/model_builder.hpp"
#include "ancf/system/multibody_problem.hpp"
#include "ancf/system/static_model_problem.hpp"
#include "dense_matrix.hpp"
#include "fd_check.hpp"
#include "iteration_matrix_check.hpp"

namespace ancf {
namespace {

constexpr double kPi = std::numbers::pi;

Mat3 rotation(const Vec3& axis_angle) {
  const double a = axis_angle.norm();
  return a == 0.0 ? Mat3::Identity()
                  : Mat3(Eigen::AngleAxisd(a, axis_angle / a).toRotationMatrix());
}

Vec3 random_unit(std::mt19937& rng) {
  std::normal_distribution<double> nd(0.0, 1.0);
  return Vec3(nd(rng), nd(rng), nd(rng)).normalized();
}

// A reference triad R, a slope turned by `turn` rad from R's tangent (|r_x| = 1.3), α and b.
struct LocalCase {
  Mat3 reference;
  Vec3 slope, b;
  double alpha;
};
LocalCase local_case(unsigned seed, double turn, double alpha) {
  std::mt19937 rng(seed);
  LocalCase c;
  c.reference = rotation(2.0 * random_unit(rng));
  const Vec3 t0 = c.reference.col(0);
  const Vec3 axis = t0.cross(random_unit(rng)).normalized();
  c.slope = 1.3 * (rotation(turn * axis) * t0);
  c.alpha = alpha;
  c.b = 0.8 * random_unit(rng);
  return c;
}

fdcheck::Vec z_of(const LocalCase& c) {
  fdcheck::Vec z(7);
  z << c.slope, c.alpha, c.b;
  return z;
}

TEST(RodTwistConstraint, LocalValueGradientAndHessianMatchCentralDifferences) {
  int cases = 0;
  for (const double turn : {0.0, 0.9, 2.6})
    for (const double alpha : {0.0, 1.9, -2.8}) {
      const LocalCase c = local_case(7u + static_cast<unsigned>(cases), turn, alpha);
      ++cases;
      const RodTwistLocal l = rod_twist_condition(c.reference, c.slope, c.alpha, c.b);
      // φ is d₂·b with d₂ the material triad's second column, as the rod element has it.
      const Vec3 d2 = rod_material_triad(c.reference, c.slope, c.alpha).col(1);
      EXPECT_NEAR(l.phi, d2.dot(c.b), 4e-16 * c.b.norm() * 4);
      const auto phi = [&](const fdcheck::Vec& z) {
        return rod_twist_condition(c.reference, z.head<3>(), z[3], z.tail<3>()).phi;
      };
      const auto gradient = [&](const fdcheck::Vec& z) {
        return fdcheck::Vec(
            rod_twist_condition(c.reference, z.head<3>(), z[3], z.tail<3>()).gradient);
      };
      const fdcheck::Result g = fdcheck::check_gradient(phi, z_of(c), l.gradient);
      const fdcheck::Result h = fdcheck::check_jacobian(gradient, z_of(c), l.hessian);
      EXPECT_TRUE(g.ok()) << "turn " << turn << " alpha " << alpha << ": gradient ratio "
                          << g.max_ratio << " at " << g.col;
      EXPECT_TRUE(h.ok()) << "turn " << turn << " alpha " << alpha << ": Hessian ratio "
                          << h.max_ratio << " at (" << h.row << ", " << h.col << ")";
      EXPECT_LE((l.hessian - l.hessian.transpose()).cwiseAbs().maxCoeff(), 1e-15);
      EXPECT_EQ((l.hessian.bottomRightCorner<3, 3>().cwiseAbs().maxCoeff()), 0.0);
    }
}

// Global layout of the row tests: r_x at 0, α at 3, a body at 4 (r_O, a₁, a₂, a₃ at 4, 7, 10, 13).
constexpr Index kSlope = 0, kTwist = 3, kBody = 4, kN = 16;

struct RowCase {
  RodTwistRow row;
  Mat3 reference;
  std::vector<DrivenFrame> frames;
  double t = 0.4;
  VecX q, v, a;
};

// b fixed in a body (on_body) or in a frame rotating by a smooth ramp about a tilted axis.
RowCase row_case(bool on_body, double turn, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> nd(0.0, 1.0);
  RowCase c;
  const LocalCase l = local_case(seed, turn, 2.3);
  c.reference = l.reference;
  c.row.slope = kSlope;
  c.row.twist = kTwist;
  const Vec3 b_local = random_unit(rng);
  if (on_body) {
    c.row.b.add_body(kBody, direction_weights(b_local));
  } else {
    DrivenFrame f;
    f.initial_rotation = rotation(Vec3(0.3, -0.5, 0.2));
    f.axis = random_unit(rng);
    f.law = AngleLaw::smooth_ramp(1.7, 1.0, 0.4);
    c.frames.push_back(f);
    c.row.b.frame = 0;
    c.row.b.frame_vector = b_local;
  }
  c.q = VecX::Zero(kN);
  c.q.segment<3>(kSlope) = l.slope;
  c.q[kTwist] = l.alpha;
  // Body coordinates of a large rotation, perturbed off orthonormality (the row is not
  // restricted to orthonormal axes).
  const Mat3 a = rotation(Vec3(1.1, 2.0, -0.7));
  c.q.segment<3>(kBody) = Vec3(0.1, 0.2, 0.3);
  for (int k = 0; k < 3; ++k) c.q.segment<3>(kBody + 3 + 3 * k) = a.col(k);
  c.v = VecX::Zero(kN), c.a = VecX::Zero(kN);
  for (Index i = 0; i < kN; ++i) {
    if (i >= kBody) c.q[i] += 0.02 * nd(rng);
    c.v[i] = nd(rng);
    c.a[i] = nd(rng);
  }
  return c;
}

RodTwistRowValues values_at(const RowCase& c, const VecX& q, const VecX& v, double t) {
  std::vector<FrameKinematics> k;
  for (const DrivenFrame& f : c.frames) k.push_back(f.at(t));
  RodTwistRowValues out;
  evaluate(c.row, c.reference, as_span(q), as_span(v), k, out);
  return out;
}

VecX dense(const RodTwistRowValues& r, const Eigen::Matrix<double, 13, 1>& x) {
  VecX d = VecX::Zero(kN);
  for (int k = 0; k < r.column_count; ++k) d[r.columns[k]] += x[k];
  return d;
}

MatX dense_hessian(const RodTwistRowValues& r) {
  MatX d = MatX::Zero(kN, kN);
  for (int j = 0; j < r.column_count; ++j)
    for (int i = 0; i < r.column_count; ++i) d(r.columns[i], r.columns[j]) += r.phi_qq(i, j);
  return d;
}

TEST(RodTwistConstraint, RowBlocksMatchCentralDifferences) {
  int count = 0;
  for (const bool on_body : {true, false})
    for (const double turn : {0.3, 2.4}) {
      const RowCase c = row_case(on_body, turn, 30u + static_cast<unsigned>(count++));
      const RodTwistRowValues r = values_at(c, c.q, c.v, c.t);
      const std::string where =
          std::string(on_body ? "body" : "frame") + ", turn " + std::to_string(turn);
      // Φ_q = ∂Φ/∂q
      const auto phi = [&](const fdcheck::Vec& q) { return values_at(c, q, c.v, c.t).phi; };
      const fdcheck::Result g = fdcheck::check_gradient(phi, c.q, dense(r, r.phi_q));
      EXPECT_TRUE(g.ok()) << where << ": Φ_q ratio " << g.max_ratio << " at " << g.col;
      // Φ_qq = ∂Φ_q/∂q
      const auto phi_q = [&](const fdcheck::Vec& q) {
        const RodTwistRowValues x = values_at(c, q, c.v, c.t);
        return fdcheck::Vec(dense(x, x.phi_q));
      };
      const fdcheck::Result h = fdcheck::check_jacobian(phi_q, c.q, dense_hessian(r));
      EXPECT_TRUE(h.ok()) << where << ": Φ_qq ratio " << h.max_ratio << " at (" << h.row << ", "
                          << h.col << ")";
      // ∂(Φ_q v + Φ_t)/∂q at fixed v
      const auto psi = [&](const fdcheck::Vec& q) {
        const RodTwistRowValues x = values_at(c, q, c.v, c.t);
        return x.phi_q_v + x.phi_t;
      };
      const fdcheck::Result p = fdcheck::check_gradient(psi, c.q, dense(r, r.psi_q));
      EXPECT_TRUE(p.ok()) << where << ": Ψ_q ratio " << p.max_ratio << " at " << p.col;
      // Φ_q v is the product (an identity up to round-off)
      EXPECT_NEAR(r.phi_q_v, dense(r, r.phi_q).dot(c.v), 1e-14 * (1.0 + c.v.norm()));
      // Φ_t = ∂Φ/∂t (zero for a body)
      const auto phi_of_t = [&](const fdcheck::Vec& t) { return values_at(c, c.q, c.v, t[0]).phi; };
      const fdcheck::Result pt = fdcheck::check_gradient(phi_of_t, fdcheck::Vec::Constant(1, c.t),
                                                         fdcheck::Vec::Constant(1, r.phi_t));
      EXPECT_TRUE(pt.ok()) << where << ": Φ_t ratio " << pt.max_ratio;
      if (on_body) {
        EXPECT_EQ(r.phi_t, 0.0);
      }
      // γ: along q(s) = q + v s + ½ a s², v(s) = v + a s, t + s, d/ds (Φ_q v + Φ_t) = Φ_q a − γ.
      const auto psi_along = [&](const fdcheck::Vec& s) {
        const VecX q = c.q + c.v * s[0] + 0.5 * c.a * s[0] * s[0], v = c.v + c.a * s[0];
        const RodTwistRowValues x = values_at(c, q, v, c.t + s[0]);
        return x.phi_q_v + x.phi_t;
      };
      const double expected = dense(r, r.phi_q).dot(c.a) - r.gamma;
      const fdcheck::Result ga = fdcheck::check_gradient(psi_along, fdcheck::Vec::Zero(1),
                                                         fdcheck::Vec::Constant(1, expected));
      EXPECT_TRUE(ga.ok()) << where << ": γ ratio " << ga.max_ratio << " (" << ga.analytic << " vs "
                           << ga.fd << ")";
      std::printf("  %s: Φ_q %.2e, Φ_qq %.2e, Ψ_q %.2e, Φ_t %.2e, γ %.2e (error/max|J|)\n",
                  where.c_str(), g.max_rel, h.max_rel, p.max_rel, pt.max_rel, ga.max_rel);
    }
}

// --- in the model ---------------------------------------------------------------------------

RodSection rod_section(double gj) {
  RodSection r;
  r.axial_stiffness = 2e3;
  r.torsional_stiffness = gj;
  r.bending_stiffness_2 = 0.5;
  r.bending_stiffness_3 = 0.7;
  r.mass_per_length = 0.2;
  r.polar_inertia = 2e-3;
  return r;
}

// Rod 1 from a ground clamp (twist included) to a free body, clamped into it including twist;
// rod 2 (curved) clamped including twist into a frame that rotates about a tilted axis.
Model clamped_into_body_and_frame() {
  ModelBuilder b;
  const CableGeometry g1 = straight_cable(Vec3::Zero(), Vec3(0.2, 0.1, 1.0), 3);
  const Index r1 = b.add_rod("r1", g1, CableSection{}, rod_section(0.4),
                             rod_frames_with_normal(g1, Vec3::UnitX()));
  const Vec3 end1 = g1.nodes.back().head<3>();
  RigidBodyInertia in{2.0, Vec3(0.05, 0.0, 0.1), Vec3(0.02, 0.03, 0.04).asDiagonal()};
  const Index body = b.add_body("disk", in, end1, rotation(Vec3(0.3, 0.5, -0.4)));
  b.pin("c1", {r1, 0}, Vec3::Zero());
  b.align_slope("c1.slope", {r1, 0}, Vec3(g1.nodes[0].tail<3>()));
  b.fix_twist("c1.twist", {r1, 0});
  b.attach_node_to_body("a1", {r1, -1}, body);
  b.align_slope_to_body("a1.slope", {r1, -1}, body);
  b.tie_twist_to_body("a1.twist", {r1, -1}, body);

  const CableGeometry g2 =
      helix_cable(Vec3(1, 0, 0), Vec3::UnitZ(), Vec3::UnitX(), 0.3, 0.2, 2.0, 0.4, 3);
  const Index r2 = b.add_rod("r2", g2, CableSection{}, rod_section(0.3),
                             rod_frames_toward_axis(g2, Vec3(1, 0, 0), Vec3::UnitZ()));
  DrivenFrame f;
  f.origin = Vec3(1.0, 0.0, 0.0);
  f.axis = Vec3(0.2, 0.3, 1.0).normalized();
  f.law = AngleLaw::smooth_ramp(1.2, 0.5);
  const int frame = b.add_driven_frame(f);
  b.attach_node_to_frame("a2", {r2, -1}, frame);
  b.align_slope_to_frame("a2.slope", {r2, -1}, frame);
  b.tie_twist_to_frame("a2.twist", {r2, -1}, frame);
  return b.finalize();
}

TEST(RodTwistConstraint, ModelHasTheTwistRowsAfterTheDotRows) {
  const Model m = clamped_into_body_and_frame();
  ASSERT_EQ(m.twist_rows().size(), 2u);
  const Index a1 = m.find_constraint("a1.twist"), a2 = m.find_constraint("a2.twist");
  ASSERT_GE(a1, 0);
  ASSERT_GE(a2, 0);
  EXPECT_EQ(m.constraints()[a1].first_row,
            m.coordinate_count() + static_cast<Index>(m.rows().size()));
  EXPECT_EQ(m.constraints()[a2].row_count, 1);
  // Satisfied at the initial configuration.
  SystemState s = SystemState::initial(m);
  Workspace ws(m);
  EXPECT_LT(constraint_violation(m, s, ws).position, 1e-15);
}

TEST(RodTwistConstraint, RedundantTwistConditionIsReported) {
  ModelBuilder b;
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3(0, 0, 1), 2);
  const Index r =
      b.add_rod("r", g, CableSection{}, rod_section(0.4), rod_frames_with_normal(g, Vec3::UnitX()));
  DrivenFrame f;
  const int frame = b.add_driven_frame(f);
  b.pin("p", {r, 0}, Vec3::Zero());
  b.align_slope("p.slope", {r, 0}, Vec3::UnitZ());
  b.fix_twist("p.twist", {r, 0});
  b.tie_twist_to_frame("again", {r, 0}, frame);
  try {
    (void)b.finalize();
    FAIL() << "expected a redundancy error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("'again'"), std::string::npos) << e.what();
  }
}

// A generic state: coordinates off the constraints, random v, a and λ.
SystemState generic_state(const Model& m, unsigned seed) {
  SystemState s = SystemState::initial(m);
  s.t = 0.3;
  std::mt19937 rng(seed);
  std::normal_distribution<double> nd(0.0, 1.0);
  for (Index i = 0; i < s.q.size(); ++i) {
    s.q[i] += 0.03 * nd(rng);
    s.v[i] = nd(rng);
    s.a[i] = nd(rng);
  }
  for (Index i = 0; i < s.lambda.size(); ++i) s.lambda[i] = nd(rng);
  return s;
}

TEST(RodTwistConstraint, AssembledMatrixMatchesResidualDifferences) {
  const Model m = clamped_into_body_and_frame();
  const SystemState s = generic_state(m, 4);
  const IterationWeights w{.w_q = 1.0, .w_v = 0.6, .w_a = 0.25, .load_factor = 1.0};
  Workspace ws(m);
  const auto res = testing::check_iteration_matrix(m, s, w, ws);
  std::printf("  assembled matrix: worst error/tolerance %.3f, error/max|J| %.2e\n", res.max_ratio,
              res.max_rel);
  EXPECT_TRUE(res.ok()) << "ratio " << res.max_ratio << " at (" << m.describe_row(res.row) << ", "
                        << m.describe_row(res.col) << "): " << res.analytic << " vs " << res.fd;
  // The velocity constraint of the twist rows against differences of Φ along a motion (γ is
  // checked row by row in RowBlocksMatchCentralDifferences).
  const Index n = m.coordinate_count(), nn = m.system_size();
  const Index k0 = static_cast<Index>(m.rows().size());
  VecX psi(m.multiplier_count());
  assemble_velocity_constraint(m, s, ws, as_span(psi));
  for (Index k = k0; k < m.multiplier_count(); ++k) {
    const auto phi_along = [&](const fdcheck::Vec& x) {
      SystemState t = s;
      t.q += s.v * x[0];
      t.t += x[0];
      VecX r(nn);
      assemble_residual(m, t, 1.0, ws, as_span(r));
      return r[n + k];
    };
    const fdcheck::Result r = fdcheck::check_gradient(phi_along, fdcheck::Vec::Zero(1),
                                                      fdcheck::Vec::Constant(1, psi[k]));
    EXPECT_TRUE(r.ok()) << m.describe_row(n + k) << ": Φ_q v + Φ_t ratio " << r.max_ratio;
  }
}

TEST(RodTwistConstraint, GglJacobianMatchesResidualDifferences) {
  const Model m = clamped_into_body_and_frame();
  GglProblem ggl(m);
  const Index n = m.coordinate_count(), size = ggl.size();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  VecX y = VecX::Zero(size), yp = VecX::Zero(size);
  ggl.initial_state(as_span(y));
  for (Index i = 0; i < n; ++i) {
    y[i] += 0.02 * u(rng);
    y[n + i] += 0.5 * u(rng);
    yp[i] = y[n + i] + 0.1 * u(rng);
    yp[n + i] = 2.0 * u(rng);
  }
  for (Index i = 2 * n; i < size; ++i) y[i] = (i < ggl.mu_offset() ? 3.0 : 0.3) * u(rng);
  const double t = 0.37, c_j = 1.5e3;
  const SparsityPattern& pattern = ggl.jacobian_pattern();
  VecX values(pattern.nonzeros());
  ggl.jacobian(t, as_span(y), as_span(yp), 0.0, as_span(values));
  const MatX d_dy = testing::dense(pattern, values);
  ggl.jacobian(t, as_span(y), as_span(yp), c_j, as_span(values));
  const MatX d_dyp = (testing::dense(pattern, values) - d_dy) / c_j;
  for (const bool derivative : {false, true}) {
    const auto residual = [&](const fdcheck::Vec& x) {
      VecX r(size);
      ggl.residual(t, as_span(derivative ? y : x), as_span(derivative ? x : yp), as_span(r));
      return fdcheck::Vec(r);
    };
    const fdcheck::Result r =
        fdcheck::check_jacobian(residual, derivative ? yp : y, derivative ? d_dyp : d_dy);
    std::printf("  GGL dF/d%s: worst error/tolerance %.3f, error/max|J| %.2e\n",
                derivative ? "y'" : "y", r.max_ratio, r.max_rel);
    EXPECT_TRUE(r.ok()) << (derivative ? "dF/dy'" : "dF/dy") << ": row " << ggl.describe_row(r.row)
                        << ", column " << ggl.describe_row(r.col) << ": analytic " << r.analytic
                        << ", FD " << r.fd;
  }
}

// --- statics and dynamics --------------------------------------------------------------------

// A straight rod along z of length L, clamped (twist included) at z = 0 and clamped including
// twist into a disk at z = L that turns on a revolute joint about z. Scene file form, so that
// the reaction probes (io) are exercised as a user gets them.
std::string torsion_scene(double torque, double gj, double polar_inertia, double disk_inertia,
                          const std::string& integrator) {
  return R"(
[[rod]]
name = "shaft"
elements = 6
geometry = { kind = "straight", start = [0.0, 0.0, 0.0], end = [0.0, 0.0, 0.5] }
frame = { normal = [1.0, 0.0, 0.0] }
[rod.section]
EA = 1.0e5
EI = 2.0
GJ = )" + std::to_string(gj) +
         R"(
mass_per_length = 0.3
polar_inertia = )" +
         std::to_string(polar_inertia) + R"(

[[body]]
name = "disk"
mass = 1.0
inertia = [)" +
         std::to_string(disk_inertia) + ", " + std::to_string(disk_inertia) + ", " +
         std::to_string(disk_inertia) + R"(]
position = [0.0, 0.0, 0.5]

[[joint]]
kind = "revolute"
name = "hinge"
body = "disk"
point = [0.0, 0.0, 0.5]
axis = [0.0, 0.0, 1.0]

[[joint]]
kind = "clamp"
name = "root"
at = { cable = "shaft", node = 0 }

[[joint]]
kind = "attach"
name = "end"
at = { cable = "shaft", node = -1 }
to = "disk"
slope = true

[[load]]
kind = "torque"
name = "tau"
body = "disk"
torque = [0.0, 0.0, )" +
         std::to_string(torque) + R"(]

[integrator]
)" + integrator +
         R"(

[output]
vtk = false
[[output.probe]]
kind = "reaction"
joint = "end"
[[output.probe]]
kind = "reaction"
joint = "root"
[[output.probe]]
kind = "rod"
at = { cable = "shaft", node = 2 }
label = "mid"
[[output.probe]]
kind = "body"
body = "disk"
)";
}

// Disk angle about z from its body coordinates.
double disk_angle(const Model& m, const VecX& q) {
  const Index b = m.bodies()[0].first_coordinate;
  return std::atan2(q[b + 4], q[b + 3]);  // a₁ = (cos θ, sin θ, 0)
}

TEST(RodTwistConstraint, StaticTwistByATorqueOnTheBody) {
  const double gj = 0.5, length = 0.5, torque = 2.0;  // θ = τL/GJ = 2 rad
  const Scene scene = load_scene_from_string(
      torsion_scene(torque, gj, 1e-3, 0.01, "method = \"genalpha\"\nt_end = 1.0"), "torsion.toml");
  const Model& m = scene.model;
  EXPECT_GE(m.find_constraint("end.twist"), 0);
  EXPECT_GE(m.find_constraint("root.twist"), 0);
  StaticModelProblem problem(m);
  StaticSolver solver(problem, {.load_steps = 4});
  VecX y = problem.initial_guess();
  (void)solver.solve(y);
  const Index n = m.coordinate_count();
  const double theta = disk_angle(m, y.head(n));
  std::printf("  disk angle %.15f rad (closed form τL/GJ = %.15f)\n", theta, torque * length / gj);
  // Straight torsion is exact in the element (K₁ = ψ_x): to the Newton tolerance.
  EXPECT_NEAR(theta, torque * length / gj, 1e-9);
  SystemState s = SystemState::initial(m);
  s.q = y.head(n);
  s.v.setZero();
  s.lambda = y.tail(m.multiplier_count());
  s.rod_history = &problem.workspace().rods;
  Workspace ws(m);
  ProbeRecorder probes(m, scene.output.probes);
  const std::vector<double>& row = probes.evaluate(s, ws);
  const auto& cols = probes.columns();
  auto value = [&](const std::string& name) {
    for (std::size_t k = 0; k < cols.size(); ++k)
      if (cols[k] == name) return row[k];
    ADD_FAILURE() << "no column " << name;
    return 0.0;
  };
  std::printf("  end.mz %.12f, root.mz %.12f, mid.torque %.12f N m\n", value("end.mz"),
              value("root.mz"), value("mid.torque"));
  // The body pushes the rod end with +τ; the ground clamp holds the root with −τ; the rod
  // carries GJ K₁ = τ.
  EXPECT_NEAR(value("end.mz"), torque, 1e-8);
  EXPECT_NEAR(value("root.mz"), -torque, 1e-8);
  EXPECT_NEAR(value("mid.torque"), torque, 1e-8);
  for (const char* c : {"end.mx", "end.my", "root.mx", "root.my", "end.fx", "end.fy", "end.fz"})
    EXPECT_NEAR(value(c), 0.0, 1e-8) << c;
  // Node 2 of 6 sits at s = L/3: its material axis d₂ (reference (1, 0, 0)) has turned by θ/3
  // about the shaft's axis z.
  const double psi = theta / 3.0;
  std::printf("  mid.d2 (%.12f, %.12f, %.12f), closed form (%.12f, %.12f, 0)\n", value("mid.d2x"),
              value("mid.d2y"), value("mid.d2z"), std::cos(psi), std::sin(psi));
  EXPECT_NEAR(value("mid.d2x"), std::cos(psi), 1e-9);
  EXPECT_NEAR(value("mid.d2y"), std::sin(psi), 1e-9);
  EXPECT_NEAR(value("mid.d2z"), 0.0, 1e-9);
}

// Fundamental torsional frequency of a shaft (GJ, ρJ, L) fixed at one end with a disk J_d at the
// other: β tan β = ρJ L/J_d, ω = β √(GJ/ρJ)/L.
double torsion_frequency(double gj, double rho_j, double length, double disk) {
  const double mu = rho_j * length / disk;
  double beta = std::sqrt(mu);
  for (int it = 0; it < 50; ++it) {
    const double f = beta * std::tan(beta) - mu;
    const double df = std::tan(beta) + beta / (std::cos(beta) * std::cos(beta));
    beta -= f / df;
  }
  return beta * std::sqrt(gj / rho_j) / length;
}

TEST(RodTwistConstraint, TorsionalOscillationOfABodyHeldByARod) {
  // A suddenly applied torque makes the disk oscillate about θ_s = τL/GJ at the fundamental
  // frequency. ρJ L/J_d = 0.05 keeps the higher modes' share small.
  const double gj = 0.5, length = 0.5, torque = 0.2, rho_j = 1e-3, disk = 0.01;
  const double omega = torsion_frequency(gj, rho_j, length, disk);
  const double period = 2.0 * kPi / omega, theta_s = torque * length / gj;
  const Scene scene = load_scene_from_string(
      torsion_scene(torque, gj, rho_j, disk, "method = \"genalpha\"\nt_end = 1.0"), "torsion.toml");
  const Model& m = scene.model;
  MultibodyProblem problem(m);
  GeneralizedAlphaOptions o;
  o.step_size = period / 400.0;
  o.rho_infinity = 0.9;
  o.rtol = 1e-9;
  o.atol_position = 1e-11;
  o.atol_velocity = 1e-9;
  o.atol_multiplier = 1e-9;
  GeneralizedAlphaStepper stepper(problem, o);
  stepper.initialize(0.0);
  // Upward crossings of θ_s: θ − θ_s = −θ_s cos ωt crosses upward at t = T/4 + kT.
  std::vector<double> crossings;
  double t_prev = 0.0, d_prev = -theta_s, peak = 0.0;
  const double dt = period / 200.0;
  // The torque the rod end takes from the disk (reaction probe of the attach, twist row
  // included) balances the disk: J_d θ̈ = τ − end.mz (the force rows act at the disk origin, the
  // hinge has no z moment). Along the rod it differs from the torque GJ K₁ of element 2 (constant
  // in an element: ψ is linear) only by the twist inertia from that element on:
  // |end.mz − mid.torque| ≤ ρJ (L − s₂) max_k |α̈_k|, s₂ = 2L/6 where element 2 starts.
  ProbeRecorder probes(m, scene.output.probes);
  Workspace ws(m);
  const auto& cols = probes.columns();
  auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(cols.begin(), cols.end(), name) - cols.begin());
  };
  const std::size_t end_mz = column("end.mz"), mid_torque = column("mid.torque");
  ASSERT_LT(end_mz, cols.size());
  ASSERT_LT(mid_torque, cols.size());
  const Index body = m.bodies()[0].first_coordinate;
  double worst_balance = 0.0, worst_along = 0.0, largest_acc = 0.0, largest_torque = 0.0;
  const double s_start = 2.0 / 6.0 * length;  // element 2 of 6 starts here
  const Index twist = m.cables()[0].rod->twist_first;
  for (int k = 1; k <= 200 * 3 + 60; ++k) {
    const double t = k * dt;
    stepper.advance_to(t);
    if (k % 10 == 0) {
      SystemState st = SystemState::initial(m);
      st.t = t;
      st.q = stepper.positions();
      st.v = stepper.velocities();
      st.a = stepper.accelerations();
      st.lambda = stepper.multipliers();
      st.rod_history = &problem.workspace().rods;
      const std::vector<double>& row = probes.evaluate(st, ws);
      const Vec3 a1 = st.q.segment<3>(body + 3), a1_dd = st.a.segment<3>(body + 3);
      const double theta_dd = a1.cross(a1_dd).z();  // d/dt (a₁ × ȧ₁) = a₁ × ä₁ = θ̈ e_z
      worst_balance = std::max(worst_balance, std::abs(disk * theta_dd - (torque - row[end_mz])));
      worst_along = std::max(worst_along, std::abs(row[end_mz] - row[mid_torque]));
      largest_acc = std::max(largest_acc, st.a.segment<7>(twist).cwiseAbs().maxCoeff());
      largest_torque = std::max(largest_torque, std::abs(row[end_mz]));
    }
    const double d = disk_angle(m, stepper.positions()) - theta_s;
    peak = std::max(peak, d + theta_s);
    if (d_prev < 0.0 && d >= 0.0)
      crossings.push_back(t_prev + (t - t_prev) * -d_prev / (d - d_prev));
    t_prev = t;
    d_prev = d;
  }
  ASSERT_GE(crossings.size(), 3u);
  const double measured =
      (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  std::printf(
      "  period %.6f s (closed form %.6f, rel. %.2e), first upward crossing %.5f s "
      "(T/4 = %.5f), peak %.5f rad (2θ_s = %.5f)\n",
      measured, period, measured / period - 1.0, crossings.front(), period / 4.0, peak,
      2.0 * theta_s);
  // Errors expected: linear-twist elements (βh)²-small, generalized-α phase ~(ωh)²/12 ≈ 2e-5,
  // the higher modes' share on the crossings O(ρJL/J_d)² of a per cent: well below 1e-3.
  std::printf(
      "  |J_d θ̈ − (τ − end.mz)| ≤ %.2e N m, |end.mz − mid.torque| ≤ %.2e N m (bound "
      "ρJ (L − s₂) max|α̈| = %.2e), max |end.mz| %.3f N m\n",
      worst_balance, worst_along, rho_j * (length - s_start) * largest_acc, largest_torque);
  EXPECT_GT(largest_torque, 1.5 * torque);  // the rod transmits the oscillating torque
  // The step's equilibrium holds to the Newton tolerance: a position increment δ below
  // atol + rtol·|a₁| (= 1) changes the acceleration by δ/(βh²).
  const double beta = stepper.parameters().beta;
  const double newton = disk * (o.atol_position + o.rtol) / (beta * o.step_size * o.step_size);
  EXPECT_LT(worst_balance, newton);
  EXPECT_LT(worst_along, rho_j * (length - s_start) * largest_acc);
  EXPECT_NEAR(measured / period, 1.0, 1e-3);
  EXPECT_NEAR(peak, 2.0 * theta_s, 0.02 * theta_s);
}

}  // namespace
}  // namespace ancf
