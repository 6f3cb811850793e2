// The static solver on the general multibody system, and the momentum functions.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/static_model_problem.hpp"
#include "multibody_scenes.hpp"

namespace ancf {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// A rigid body hung from three vertical cables (elastic line, EI = 0) under gravity. By symmetry
// each cable carries T(s) = mg/3 + w s (s from the body up, w = ρA g), so the body drops by
//   δ = ∫₀ᴸ T/EA ds = (mg/3 · L + w L²/2) / EA
// and the ceiling reaction of each cable is mg/3 + wL. The strain is linear in s, so z(s) is
// quadratic and the cubic Hermite mesh represents it exactly: the solution is exact up to
// round-off and the Newton tolerance.
TEST(StaticMultibody, BodyHungFromThreeCablesMatchesHandCalculation) {
  const double length = 1.0, radius = 0.2, ea = 1e5, rho_a = 0.01, g = 9.81, mass = 10.0;
  const double pre_stretch = 1e-4;  // start taut: a slack EI = 0 cable has a singular tangent
  ModelBuilder b;
  const Index body = b.add_body("plate", testing::box_inertia(mass, Vec3(0.5, 0.5, 0.05), Vec3::Zero()),
                                Vec3(0.0, 0.0, -length * (1 + pre_stretch)));
  CableSection s;
  s.strain = StrainMeasure::elastic_line;
  s.axial_stiffness = ea;
  s.mass_per_length = rho_a;
  for (int i = 0; i < 3; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / 3.0;
    const Vec3 top(radius * std::cos(phi), radius * std::sin(phi), 0.0);
    const Vec3 bottom = top - length * (1 + pre_stretch) * Vec3::UnitZ();
    const std::string name = "cable" + std::to_string(i);
    const Index c = b.add_cable(name, straight_cable(top, top - length * Vec3::UnitZ(), 4), s);
    b.set_initial_configuration(c, straight_cable(top, bottom, 4));
    b.pin(name + " ceiling", {c, 0}, top);
    b.attach_node_to_body(name + " to plate", {c, -1}, body);
  }
  b.set_gravity(Vec3(0.0, 0.0, -g));
  const Model model = b.finalize();
  StaticModelProblem problem(model);
  StaticSolver solver(problem);
  VecX y = problem.initial_guess();
  const StaticSolverStatistics stats = solver.solve(y);

  const double w = rho_a * g;
  const double drop = (mass * g / 3.0 * length + 0.5 * w * length * length) / ea;
  const Index ob = model.bodies()[0].first_coordinate;
  const double z = y[ob + 2];
  const double error = std::abs(-(z + length) - drop) / drop;
  std::printf("hung body: drop %.12e m, hand calculation %.12e m, rel. error %.2e (%d Newton)\n",
              -(z + length), drop, error, stats.newton_iterations);
  EXPECT_LT(error, 1e-9);
  // No rotation, no lateral motion.
  const Mat3 a = rotation_of(y.segment<12>(ob));
  EXPECT_LT((a - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(y.segment<2>(ob).norm(), 1e-12);
  // Ceiling reactions: the pin multipliers, |λ| = mg/3 + wL (vertical).
  for (int i = 0; i < 3; ++i) {
    const Index row = model.constraints()[model.find_constraint("cable" + std::to_string(i) + " ceiling")].first_row;
    const Vec3 lambda = y.segment<3>(row);
    EXPECT_NEAR(lambda.norm(), mass * g / 3.0 + w * length, 1e-9 * (mass * g));
  }
}

// Momenta are exact through the consistent mass matrices: a rigid body's m v_C and
// r_C × m v_C + A I_c Aᵀ ω; a straight cable's ρA L v and ρA ∫ r × (ω × r) dx.
TEST(Momentum, MatchesRigidBodyAndCableClosedForms) {
  ModelBuilder b;
  const RigidBodyInertia in = testing::box_inertia(3.0, Vec3(0.3, 0.2, 0.1), Vec3(0.05, -0.02, 0.01));
  const Mat3 rot = Eigen::AngleAxisd(0.8, Vec3(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  const Vec3 r0(0.4, -0.3, 1.2), v0(0.5, 0.1, -0.2), w0(1.5, -0.7, 0.3);
  b.add_body("box", in, r0, rot, v0, w0);
  const Model body_model = b.finalize();
  const SystemState s = SystemState::initial(body_model);
  const Momentum p = momentum(body_model, s.q, s.v);
  const Vec3 rc = r0 + rot * in.centre_of_mass, vc = v0 + w0.cross(rot * in.centre_of_mass);
  const Vec3 h = rc.cross(in.mass * vc) + rot * in.inertia * rot.transpose() * w0;
  EXPECT_LT((p.linear - in.mass * vc).norm(), 64 * kEps * in.mass * vc.norm());
  EXPECT_LT((p.angular - h).norm(), 64 * kEps * (rc.norm() * in.mass * vc.norm() + h.norm()));

  // Cable along x from 0 to L rotating rigidly with ω and translating with v.
  const double length = 1.5, rho_a = 0.2;
  ModelBuilder cb;
  CableSection sec;
  sec.axial_stiffness = 1.0;
  sec.mass_per_length = rho_a;
  const CableGeometry g = straight_cable(Vec3::Zero(), length * Vec3::UnitX(), 7);
  const Index c = cb.add_cable("c", g, sec);
  std::vector<NodeCoordinates> vel(g.nodes.size());
  for (std::size_t k = 0; k < g.nodes.size(); ++k)
    vel[k] << v0 + w0.cross(g.nodes[k].head<3>()), w0.cross(g.nodes[k].tail<3>());
  cb.set_initial_configuration(c, g, &vel);
  const Model cable_model = cb.finalize();
  const SystemState cs = SystemState::initial(cable_model);
  const Momentum pc = momentum(cable_model, cs.q, cs.v);
  const Vec3 ex = Vec3::UnitX();
  // ∫ρA r × (v + ω × r) = ρA (L²/2) e_x × v + ρA (L³/3)(ω − e_x (e_x·ω)).
  const Vec3 hc = rho_a * length * length / 2.0 * ex.cross(v0) +
                  rho_a * length * length * length / 3.0 * (w0 - ex * ex.dot(w0));
  const Vec3 lin = rho_a * length * (v0 + w0.cross(0.5 * length * ex));
  EXPECT_LT((pc.linear - lin).norm(), 64 * kEps * lin.norm());
  EXPECT_LT((pc.angular - hc).norm(), 64 * kEps * hc.norm());
}

}  // namespace
}  // namespace ancf
