// Invariances and exact integrals of the cable element (DESIGN §8):
//  * a rigid motion of the stress-free reference carries no elastic force or energy, and rigid
//    velocities no Kelvin–Voigt force (both formulations, with and without bending, straight and
//    curved references);
//  * the consistent mass matrix integrates ρA r·r exactly for cubic r(x) (Hermite interpolation
//    reproduces cubics), so it gives the total mass, first and second moments in closed form —
//    per element and assembled through ModelBuilder;
//  * hermite::load_weights is ∫S dx, and the assembled gravity load is M times the gravity field.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ancf/physics/cable_element.hpp"
#include "ancf/physics/hermite_shape.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/model_builder.hpp"
#include "dense_matrix.hpp"
#include "random_geometry.hpp"

namespace {

using ancf::testing::dense;
using namespace ancf;
constexpr double kEps = std::numeric_limits<double>::epsilon();

using random_geometry::random_rotation;
using random_geometry::random_vec3;

struct ReferenceElement {
  std::string name;
  Vec12 e0;
  double length;
};

std::vector<ReferenceElement> reference_elements() {
  const CableGeometry s = straight_cable(Vec3(0.1, -0.2, 0.3), Vec3(0.4, 0.2, 0.3), 2);
  const CableGeometry a =
      arc_cable(Vec3(0.2, 0.1, -0.1), Vec3(1, 0, 0), Vec3(0, 0.6, 0.8), 0.4, 1.2, 3);
  const CableGeometry h =
      helix_cable(Vec3::Zero(), Vec3(0, 0, 1), Vec3(1, 0, 0), 0.15, 0.3, 4.0, 0.3, 4);
  return {{"straight", s.element_coordinates(1), s.element_lengths[1]},
          {"arc", a.element_coordinates(1), a.element_lengths[1]},
          {"helix", h.element_coordinates(2), h.element_lengths[2]}};
}

// x ↦ R x + t on positions, R on slopes.
Vec12 rigid_motion(const Vec12& e, const Mat3& rot, const Vec3& shift) {
  Vec12 out;
  for (int n = 0; n < 2; ++n) {
    out.segment<3>(6 * n) = rot * e.segment<3>(6 * n) + shift;
    out.segment<3>(6 * n + 3) = rot * e.segment<3>(6 * n + 3);
  }
  return out;
}

double max_position(const Vec12& e) {
  return std::max(e.segment<3>(0).lpNorm<Eigen::Infinity>(),
                  e.segment<3>(6).lpNorm<Eigen::Infinity>());
}

// Tolerance: forming r_x, r_xx from positions of size |r| over an element of length l leaves a
// strain round-off δ ≈ eps·(1 + |r|/l) (curvature δ/l); forces are then ≈ (EA + EI/l²)·δ and the
// energy ≈ ½ l (EA + EI/l²) δ². The factor 16 covers the handful of roundings per Gauss point.
TEST(CableInvariants, RigidMotionOfReferenceIsStressFree) {
  double worst_f = 0.0, worst_u = 0.0;
  for (StrainMeasure m : {StrainMeasure::green_lagrange, StrainMeasure::elastic_line})
    for (const ReferenceElement& r : reference_elements())
      for (double ei : {0.0, 0.7}) {
        const CableSection sec{.strain = m, .axial_stiffness = 3e5, .bending_stiffness = ei};
        const auto ref = CableElementReference::from_reference(r.e0, r.length, m);
        for (unsigned seed = 1; seed <= 5; ++seed) {
          std::mt19937 rng(seed);
          const Vec12 e = rigid_motion(r.e0, random_rotation(rng), random_vec3(rng, 1.0));
          CableElementResult res;
          evaluate_cable_element(sec, ref, e, Vec12::Zero(), {}, res);
          const double stiffness = sec.axial_stiffness + ei / (r.length * r.length);
          const double delta = 16.0 * kEps * (1.0 + max_position(e) / r.length);
          const double tol_f = stiffness * delta,
                       tol_u = 0.5 * r.length * stiffness * delta * delta;
          const std::string what =
              r.name + (m == StrainMeasure::green_lagrange ? " green" : " elastic-line") +
              " EI=" + std::to_string(ei) + " seed " + std::to_string(seed);
          EXPECT_LE(res.force.lpNorm<Eigen::Infinity>(), tol_f) << what;
          EXPECT_LE(std::abs(res.energy), tol_u) << what;
          worst_f = std::max(worst_f, res.force.lpNorm<Eigen::Infinity>() / tol_f);
          worst_u = std::max(worst_u, std::abs(res.energy) / tol_u);
        }
      }
  std::printf(
      "rigid motion: max |f|/tol %.2e, max |U|/tol %.2e (tol_f = 16 eps (1+|r|/l)(EA+EI/l^2))\n",
      worst_f, worst_u);
}

// Kelvin–Voigt damping acts on strain rates, which vanish for rigid velocities ṙ = v + ω × r at ANY
// configuration (a·(ω × a) = 0, and K² is rotation invariant). Tolerance as above with the rate
// scale |ω| + |ṙ|/l.
TEST(CableInvariants, RigidVelocityGivesNoDampingForce) {
  double worst = 0.0;
  for (StrainMeasure m : {StrainMeasure::green_lagrange, StrainMeasure::elastic_line})
    for (const ReferenceElement& r : reference_elements()) {
      const CableSection sec{.strain = m,
                             .axial_stiffness = 3e5,
                             .bending_stiffness = 0.7,
                             .axial_damping = 3e3,
                             .bending_damping = 7e-3};
      const auto ref = CableElementReference::from_reference(r.e0, r.length, m);
      for (unsigned seed = 1; seed <= 5; ++seed) {
        std::mt19937 rng(100 + seed);
        Vec12 e = rigid_motion(r.e0, random_rotation(rng), random_vec3(rng, 1.0));
        for (int k = 0; k < 4; ++k)
          e.segment<3>(3 * k) += random_vec3(rng, 0.05 * (k % 2 ? 1.0 : r.length));
        const Vec3 v = random_vec3(rng, 1.0), omega = random_vec3(rng, 2.0);
        Vec12 e_dot;
        for (int n = 0; n < 2; ++n) {
          e_dot.segment<3>(6 * n) = v + omega.cross(e.segment<3>(6 * n));
          e_dot.segment<3>(6 * n + 3) = omega.cross(e.segment<3>(6 * n + 3));
        }
        CableElementResult moving, still;
        evaluate_cable_element(sec, ref, e, e_dot, {}, moving);
        evaluate_cable_element(sec, ref, e, Vec12::Zero(), {}, still);
        const double rate = omega.norm() + max_position(e_dot) / r.length;
        const double tol = (sec.axial_damping + sec.bending_damping / (r.length * r.length)) *
                           rate * 16.0 * kEps * (1.0 + max_position(e) / r.length);
        const double err = (moving.force - still.force).lpNorm<Eigen::Infinity>();
        EXPECT_LE(err, tol) << r.name << " seed " << seed;
        worst = std::max(worst, err / tol);
      }
    }
  std::printf("rigid velocity: max |f_damping|/tol %.2e\n", worst);
}

// ---- Mass matrix ------------------------------------------------------------------------------

// r(x) = Σ c_m x^m on [0, L] and its exact integrals.
struct Cubic {
  std::array<Vec3, 4> c;
  Vec3 r(double x) const { return c[0] + x * (c[1] + x * (c[2] + x * c[3])); }
  Vec3 dr(double x) const { return c[1] + x * (2.0 * c[2] + x * 3.0 * c[3]); }
  // ∫₀ᴸ r_a r_b dx; with abs = true, the same sum of |terms| (its round-off scale).
  Mat3 second_moment(double len, bool abs = false) const {
    Mat3 s = Mat3::Zero();
    for (int m = 0; m < 4; ++m)
      for (int n = 0; n < 4; ++n) {
        const Mat3 t = c[m] * c[n].transpose() * std::pow(len, m + n + 1) / (m + n + 1);
        s += abs ? Mat3(t.cwiseAbs()) : t;
      }
    return s;
  }
  Vec3 first_moment(double len, bool abs = false) const {
    Vec3 s = Vec3::Zero();
    for (int m = 0; m < 4; ++m)
      s += (abs ? Vec3(c[m].cwiseAbs()) : c[m]) * std::pow(len, m + 1) / (m + 1);
    return s;
  }
};

// Nodal coordinates of r on `elements` equal elements of [0, L]: [r(x_k), r'(x_k)] per node.
VecX nodal(const Cubic& cubic, double len, int elements) {
  VecX q(6 * (elements + 1));
  for (int k = 0; k <= elements; ++k) {
    const double x = len * k / elements;
    q.segment<6>(6 * k) << cubic.r(x), cubic.dr(x);
  }
  return q;
}

// Scalar fields carried by the x slots (M = m4 ⊗ I₃ couples only equal components): component d
// of q moved into x, or the unit translation along d.
VecX component_in_x(const VecX& q, int d) {
  VecX out = VecX::Zero(q.size());
  for (Index k = 0; k < q.size(); k += 6) {
    out[k] = q[k + d];
    out[k + 3] = q[k + 3 + d];
  }
  return out;
}
VecX translation(Index size, int d) {
  VecX out = VecX::Zero(size);
  for (Index k = 0; k < size; k += 6) out[k + d] = 1.0;
  return out;
}

// Checks the mass moments through the quadratic form of M: T_aᵀMT_b = ρA L δ_ab,
// T_aᵀMq = ρA ∫r_a, C_aᵀMC_b = ρA ∫r_a r_b, qᵀMq = ρA ∫|r|². Round-off bound of uᵀMv with
// N-term sums: (2N + 20)·eps·(|u|ᵀ|M||v| + the closed form's sum of |terms|) (standard bound).
double check_moments(const MatX& mass, const Cubic& cubic, double rho_a, double len, int elements,
                     const char* what) {
  const VecX q = nodal(cubic, len, elements);
  const double gamma = (2.0 * q.size() + 20.0) * kEps;
  const Mat3 second = rho_a * cubic.second_moment(len),
             second_abs = rho_a * cubic.second_moment(len, true);
  const Vec3 first = rho_a * cubic.first_moment(len),
             first_abs = rho_a * cubic.first_moment(len, true);
  const MatX abs_m = mass.cwiseAbs();
  double worst = 0.0;
  auto expect = [&](const VecX& u, const VecX& v, double exact, double exact_abs,
                    const std::string& name) {
    const double tol = gamma * (u.cwiseAbs().dot(abs_m * v.cwiseAbs()) + exact_abs);
    const double err = std::abs(u.dot(mass * v) - exact);
    EXPECT_LE(err, tol) << what << ": " << name;
    worst = std::max(worst, err / tol);
  };
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      const std::string ab = std::to_string(a) + std::to_string(b);
      expect(translation(q.size(), a), translation(q.size(), b), a == b ? rho_a * len : 0.0,
             rho_a * len, "mass " + ab);
      expect(component_in_x(q, a), component_in_x(q, b), second(a, b), second_abs(a, b),
             "second moment " + ab);
    }
    expect(translation(q.size(), a), q, first[a], first_abs[a],
           "first moment " + std::to_string(a));
  }
  expect(q, q, second.trace(), second_abs.trace(), "integral of |r|^2");
  return worst;
}

Cubic random_cubic(std::mt19937& rng, double len) {  // terms of order 0.3 m over [0, L]
  Cubic c;
  for (int m = 0; m < 4; ++m) c.c[m] = random_vec3(rng, 0.3 / std::pow(len, m));
  return c;
}

TEST(CableMass, ElementMassMatrixIntegratesCubicsExactly) {
  const double rho_a = 0.37, len = 0.45;
  const Mat4 m4 = hermite::mass_matrix(rho_a, len);
  MatX m12 = MatX::Zero(12, 12);  // m4 ⊗ I₃
  for (int p = 0; p < 4; ++p)
    for (int s = 0; s < 4; ++s) m12.block<3, 3>(3 * p, 3 * s) = m4(p, s) * Mat3::Identity();
  Cubic along_x;  // straight cable along x from x = 0.3: r = (0.3 + x, 0, 0)
  along_x.c = {Vec3(0.3, 0, 0), Vec3(1, 0, 0), Vec3::Zero(), Vec3::Zero()};
  double worst = check_moments(m12, along_x, rho_a, len, 1, "straight element");
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial)
    worst =
        std::max(worst, check_moments(m12, random_cubic(rng, len), rho_a, len, 1, "cubic element"));
  std::printf("element mass moments: max error/tolerance %.2e\n", worst);
}

// The same moments from the global matrix w_a·M of assemble_iteration_matrix({0, 0, 1}) over five
// elements (a cubic stays exact across element boundaries), and from kinetic_energy.
TEST(CableMass, AssembledMassMatrixIntegratesCubicsExactly) {
  const double rho_a = 0.37, len = 1.3;
  const int elements = 5;
  ModelBuilder builder;
  builder.add_cable("rope", straight_cable(Vec3::Zero(), Vec3(len, 0, 0), elements),
                    CableSection{.axial_stiffness = 1e4, .mass_per_length = rho_a});
  const Model model = builder.finalize();
  std::vector<double> values(model.pattern().nonzeros());
  assemble_iteration_matrix(model, SystemState::initial(model),
                            {.w_q = 0.0, .w_v = 0.0, .w_a = 1.0}, values);
  const MatX mass = dense(model.pattern(), values);
  ASSERT_EQ(mass.rows(), 6 * (elements + 1));
  std::mt19937 rng(11);
  double worst = 0.0, worst_t = 0.0;
  for (int trial = 0; trial < 5; ++trial) {
    const Cubic cubic = random_cubic(rng, len);
    worst = std::max(worst, check_moments(mass, cubic, rho_a, len, elements, "assembled"));
    // T = ½ vᵀMv = ½ ρA ∫|r|² dx for the velocity field v = r.
    const VecX q = nodal(cubic, len, elements);
    const double t = kinetic_energy(model, q);
    const double exact = 0.5 * rho_a * cubic.second_moment(len).trace();
    const double tol = (2.0 * q.size() + 20.0) * kEps * 0.5 *
                       (q.cwiseAbs().dot(mass.cwiseAbs() * q.cwiseAbs()) +
                        rho_a * cubic.second_moment(len, true).trace());
    EXPECT_NEAR(t, exact, tol);
    worst_t = std::max(worst_t, std::abs(t - exact) / tol);
  }
  std::printf("assembled mass moments: max error/tolerance %.2e, kinetic energy %.2e\n", worst,
              worst_t);
}

// ∫₀ˡ S dx three ways: load_weights, Simpson's rule (exact for the cubic S), and M·(1,0,1,0)/ρA
// (S1 + S3 = 1 is the translation field). Then the assembled gravity load equals M times the
// gravity field and sums to the weight ρA L g.
TEST(CableMass, LoadWeightsAreIntegralOfShapeFunctions) {
  double worst = 0.0;
  for (double l : {0.1, 0.45, 2.0}) {
    const Vec4 w = hermite::load_weights(l);
    const Vec4 simpson = (l / 6.0) * (hermite::values(0.0, l) + 4.0 * hermite::values(0.5, l) +
                                      hermite::values(1.0, l));
    const Vec4 from_mass = hermite::mass_matrix(1.0, l) * Vec4(1.0, 0.0, 1.0, 0.0);
    for (int k = 0; k < 4; ++k) {
      const double tol = 16.0 * kEps * std::abs(w[k]);
      EXPECT_NEAR(simpson[k], w[k], tol) << "l = " << l << " k = " << k;
      EXPECT_NEAR(from_mass[k], w[k], tol) << "l = " << l << " k = " << k;
      worst =
          std::max({worst, std::abs(simpson[k] - w[k]) / tol, std::abs(from_mass[k] - w[k]) / tol});
    }
  }
  const double rho_a = 0.37, len = 1.3;
  const Vec3 g(0.3, -9.81, 1.2);
  ModelBuilder builder;
  builder.add_cable("rope", straight_cable(Vec3(1, 2, 3), Vec3(1 + len, 2, 3), 4),
                    CableSection{.axial_stiffness = 1e4, .mass_per_length = rho_a});
  builder.set_gravity(g);
  const Model model = builder.finalize();
  std::vector<double> values(model.pattern().nonzeros());
  assemble_iteration_matrix(model, SystemState::initial(model),
                            {.w_q = 0.0, .w_v = 0.0, .w_a = 1.0}, values);
  const MatX mass = dense(model.pattern(), values);
  VecX field = VecX::Zero(model.coordinate_count());
  Vec3 total = Vec3::Zero();
  for (Index k = 0; k < field.size(); k += 6) {
    field.segment<3>(k) = g;
    total += model.constant_load().segment<3>(k);
  }
  const double tol = (2.0 * field.size() + 20.0) * kEps * rho_a * len * g.norm();
  const double err_field = (mass * field - model.constant_load()).lpNorm<Eigen::Infinity>();
  const double err_total = (total - rho_a * len * g).lpNorm<Eigen::Infinity>();
  EXPECT_LE(err_field, tol);
  EXPECT_LE(err_total, tol);
  std::printf(
      "load weights: max error/tolerance %.2e; gravity load vs M g %.2e, total weight %.2e\n",
      worst, err_field / tol, err_total / tol);
}

}  // namespace
