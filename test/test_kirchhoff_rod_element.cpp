// Kirchhoff rod element (docs/rod.md): exact force, tangent and damping matrix against central
// differences with error-estimated tolerances (fd_check.hpp), on straight, arc and helix
// references with twisted material frames, also far from the reference and after large rigid
// rotations; objectivity and exact stress-freeness; the torsion strain is the twist rate of the
// interpolated triad; the end-moment load is the moment's virtual work.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "ancf/physics/hermite_shape.hpp"
#include "ancf/physics/kirchhoff_rod_distributed_moment.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "fd_check.hpp"
#include "random_geometry.hpp"

namespace {
using namespace ancf;
constexpr double kEps = std::numeric_limits<double>::epsilon();
using random_geometry::random_rotation;
using random_geometry::random_vec3;

// Triad [t̂, d₂, d₃] from the tangent t and a helper direction, turned by `twist` about t̂.
Mat3 frame_from(const Vec3& t, const Vec3& helper, double twist) {
  const Vec3 g = t.normalized();
  const Vec3 d2 = (helper - helper.dot(g) * g).normalized();
  const Vec3 d3 = g.cross(d2);
  Mat3 f;
  f.col(0) = g;
  f.col(1) = std::cos(twist) * d2 + std::sin(twist) * d3;
  f.col(2) = std::cos(twist) * d3 - std::sin(twist) * d2;
  return f;
}

struct Case {
  std::string name;
  Vec12 e0;
  double length;
  RodElementHistory history;  // reference triads (twisted: the two nodes differ by 0.3 rad)
};

std::vector<Case> cases() {
  const CableGeometry s = straight_cable(Vec3(0.1, -0.2, 0.3), Vec3(0.4, 0.2, 0.3), 2);
  const CableGeometry a =
      arc_cable(Vec3(0.2, 0.1, -0.1), Vec3(1, 0, 0), Vec3(0, 0.6, 0.8), 0.4, 1.2, 3);
  const CableGeometry h =
      helix_cable(Vec3::Zero(), Vec3(0, 0, 1), Vec3(1, 0, 0), 0.15, 0.3, 4.0, 0.3, 4);
  std::vector<Case> out;
  auto add = [&](const char* name, const CableGeometry& g, Index j) {
    Case c{name, g.element_coordinates(j), g.element_lengths[j], {}};
    const Vec3 helper(0.3, -0.5, 0.8);
    c.history.frame1 = frame_from(c.e0.segment<3>(3), helper, 0.1);
    c.history.frame2 = frame_from(c.e0.segment<3>(9), helper, 0.4);
    out.push_back(c);
  };
  add("straight", s, 1);
  add("arc", a, 1);
  add("helix", h, 2);
  return out;
}

RodSection section(bool damping, RodAxialStrain axial = RodAxialStrain::collocated,
                   RodTorsionStrain torsion = RodTorsionStrain::projected) {
  RodSection s;
  s.axial_strain = axial;
  s.torsion_strain = torsion;
  s.axial_stiffness = 3e3;  // comparable terms, so no block hides in round-off of another
  s.torsional_stiffness = 0.7;
  s.bending_stiffness_2 = 1.1;
  s.bending_stiffness_3 = 1.6;
  if (damping) {
    s.axial_damping = 2.0;
    s.torsional_damping = 0.03;
    s.bending_damping = 0.05;
  }
  return s;
}

Vec15 with_twist(const Vec12& e, double a1, double a2, double beta = 0.0) {
  Vec15 x;
  x << e, a1, a2, beta;
  return x;
}

// The case's centreline perturbed by amp (random, from rng) with twist (α₁, α₂, β).
Vec15 deformed(const Vec12& e0, std::mt19937& rng, double amp, double a1, double a2, double beta) {
  Vec15 e = with_twist(e0, a1, a2, beta);
  for (int i = 0; i < 12; ++i) e[i] += amp * random_vec3(rng, 1.0)[i % 3];
  return e;
}

// Rigid rotation Q of coordinates (positions about the origin) and of the history.
Vec15 rotated(const Mat3& q, const Vec15& e) {
  Vec15 out = e;
  for (int k = 0; k < 4; ++k) out.segment<3>(3 * k) = q * e.segment<3>(3 * k);
  return out;
}
RodElementHistory rotated(const Mat3& q, RodElementHistory h) {
  h.frame1 = q * h.frame1;
  h.frame2 = q * h.frame2;
  return h;
}

RodElementResult eval(const RodSection& s, const RodElementReference& ref,
                      const RodElementHistory& h, const Vec15& e, const Vec15& ed, bool k, bool d) {
  RodElementResult r;
  evaluate_rod_element(s, ref, h, e, ed, {.stiffness = k, .damping_matrix = d}, r);
  return r;
}

TEST(KirchhoffRod, ReferenceIsExactlyStressFree) {
  for (const Case& c : cases()) {
    RodElementHistory h = c.history;
    const auto ref = RodElementReference::from_reference(c.e0, c.length, h);
    const Vec15 e = with_twist(c.e0, 0.0, 0.0);
    const auto r = eval(section(false), ref, h, e, Vec15::Zero(), false, false);
    // K − K⁰ vanishes exactly (same operations); ε = |r_x|/J₀ − 1 to a few ulps.
    const double ea = section(false).axial_stiffness;
    EXPECT_LE(r.energy, 64 * kEps * kEps * ea * c.length) << c.name;
    EXPECT_LE(r.force.norm(), 64 * kEps * ea) << c.name;
  }
}

TEST(KirchhoffRod, RigidRotationOfCurvedTwistedRod) {
  std::mt19937 rng(7);
  for (const Case& c : cases()) {
    RodElementHistory h = c.history;
    const auto ref = RodElementReference::from_reference(c.e0, c.length, h);
    const RodSection s = section(false);
    // A deformed, twisted state and its rigidly rotated copy (history rotated with it).
    const Vec15 e = deformed(c.e0, rng, 0.02, 0.2, -0.3, 0.15);
    const auto r0 = eval(s, ref, h, e, Vec15::Zero(), false, false);
    for (int trial = 0; trial < 3; ++trial) {
      const Mat3 q = random_rotation(rng);
      const auto rq = eval(s, ref, rotated(q, h), rotated(q, e), Vec15::Zero(), false, false);
      EXPECT_NEAR(rq.energy, r0.energy, 64 * kEps * r0.energy) << c.name;
      const Vec15 f_back = rotated(q.transpose(), rq.force);
      EXPECT_LE((f_back - r0.force).norm(), 1e3 * kEps * r0.force.norm()) << c.name;
      // The stress-free reference rotated rigidly stays stress-free (to round-off).
      const auto z = eval(s, ref, rotated(q, h), rotated(q, with_twist(c.e0, 0, 0)), Vec15::Zero(),
                          false, false);
      EXPECT_LE(z.energy, 1e3 * kEps * kEps * s.axial_stiffness * c.length) << c.name;
      EXPECT_LE(z.force.norm(), 1e3 * kEps * s.axial_stiffness) << c.name;
    }
  }
}

// A uniform change of the twist angles at both nodes is a rigid rotation about a straight
// reference's axis: no energy. A differential twist Δ gives K₁ = Δ/l exactly.
TEST(KirchhoffRod, TwistRateOfStraightRod) {
  const Case c = cases()[0];
  RodElementHistory h = c.history;
  const auto ref = RodElementReference::from_reference(c.e0, c.length, h);
  const RodSection s = section(false);
  EXPECT_LE(eval(s, ref, h, with_twist(c.e0, 0.7, 0.7), Vec15::Zero(), false, false).energy, 1e-28);
  const double delta = 0.25;
  const auto r = eval(s, ref, h, with_twist(c.e0, 0.0, delta), Vec15::Zero(), false, false);
  // U = ½ GJ (Δ/l)² l
  EXPECT_NEAR(r.energy, 0.5 * s.torsional_stiffness * delta * delta / c.length, 1e-13 * r.energy);
  // The interior twist β alone: ψ_x = 4(1 − 2ξ)β/l, U = ½ GJ ∫ ψ_x² dx = 8 GJ β²/(3 l); the
  // 4-point Gauss rule integrates the quadratic exactly.
  const double beta = 0.3;
  const auto rb = eval(s, ref, h, with_twist(c.e0, 0.0, 0.0, beta), Vec15::Zero(), false, false);
  EXPECT_NEAR(rb.energy, 8.0 * s.torsional_stiffness * beta * beta / (3.0 * c.length),
              1e-13 * rb.energy);
}

// K₁ equals the twist rate d₂′·d₃ of the interpolated triad, and K₂, K₃ the curvature in it:
// checked by central differences of the triad field along the element (error O(h²) ≈ 1e-8).
TEST(KirchhoffRod, StrainsAreThoseOfTheInterpolatedTriad) {
  std::mt19937 rng(3);
  for (const Case& c : cases()) {
    RodElementHistory h = c.history;
    const auto ref = RodElementReference::from_reference(c.e0, c.length, h);
    const Vec15 e = deformed(c.e0, rng, 0.03, 0.3, -0.5, 0.4);
    for (const double xi : {0.2, 0.5, 0.8}) {
      Vec3 a0 = Vec3::Zero();
      const Vec4 d1 = hermite::first_derivative(xi, c.length);
      for (int k = 0; k < 4; ++k) a0 += d1[k] * c.e0.segment<3>(3 * k);
      const double j0 = a0.norm();
      const double dx = 1e-4;
      const auto p = rod_point_state(ref, h, e, xi);
      const auto pp = rod_point_state(ref, h, e, xi + dx);
      const auto pm = rod_point_state(ref, h, e, xi - dx);
      // dΛ/ds Λᵀ = [Ω]×; Ω·d₁ = d₂′·d₃, Ω·d₂ = d₃′·d₁, Ω·d₃ = d₁′·d₂ (per unit x, ÷ J₀).
      const Mat3 dl = (pp.triad - pm.triad) / (2.0 * dx * c.length * j0);
      const double k1 = dl.col(1).dot(p.triad.col(2));
      const double k2 = dl.col(2).dot(p.triad.col(0));
      const double k3 = dl.col(0).dot(p.triad.col(1));
      EXPECT_NEAR(p.curvature[0], k1, 1e-6) << c.name << " ξ=" << xi;
      EXPECT_NEAR(p.curvature[1], k2, 1e-6) << c.name;  // κ = d₁ × d₁′ = Ω⊥
      EXPECT_NEAR(p.curvature[2], k3, 1e-6) << c.name;
      EXPECT_LE((p.triad.transpose() * p.triad - Mat3::Identity()).norm(), 1e-14);
    }
  }
}

// rod_torsion_strain (the rod probe's torque ÷ GJ) is the strain the energy squares: with only GJ
// in the section, U = Σ_p w_p ½GJ s(ξ_p)² for either torsion strain, on curved, twisted, rotated
// states; the projected s is linear in ξ. On the curved cases the two strains differ, so reporting
// the pointwise K₁ − K₁⁰ for the projected section would fail the energy check.
TEST(KirchhoffRod, TorsionStrainIsTheOneTheEnergySees) {
  std::mt19937 rng(5);
  for (const Case& c : cases()) {
    RodElementHistory reference = c.history;
    const auto ref = RodElementReference::from_reference(c.e0, c.length, reference);
    const Mat3 q = random_rotation(rng);
    const Vec15 e = rotated(q, deformed(c.e0, rng, 0.1, 1.2, -1.9, 0.9));
    const RodElementHistory now = rotated(q, reference);
    double energy[2] = {0.0, 0.0};
    for (const RodTorsionStrain torsion :
         {RodTorsionStrain::projected, RodTorsionStrain::gauss_points}) {
      RodSection s = section(false, RodAxialStrain::collocated, torsion);
      s.axial_stiffness = s.bending_stiffness_2 = s.bending_stiffness_3 = 0.0;
      const double gj = s.torsional_stiffness;
      const auto strain = [&](double xi) {
        return rod_torsion_strain(s, ref, reference, now, e, xi);
      };
      double u = 0.0;
      for (int p = 0; p < kRodGaussPoints; ++p)
        u += 0.5 * ref.weight[p] * gj * strain(ref.xi[p]) * strain(ref.xi[p]);
      const double energy_of_element = eval(s, ref, now, e, Vec15::Zero(), false, false).energy;
      EXPECT_NEAR(u, energy_of_element, 64 * kEps * energy_of_element) << c.name;
      energy[torsion == RodTorsionStrain::projected ? 0 : 1] = energy_of_element;
      if (torsion == RodTorsionStrain::projected) {
        EXPECT_NEAR(strain(0.5), 0.5 * (strain(0.2) + strain(0.8)),
                    64 * kEps * (std::abs(strain(0.2)) + std::abs(strain(0.8))))
            << c.name;
      }
    }
    std::printf("  %-8s torsion energy projected %.9e, Gauss points %.9e\n", c.name.c_str(),
                energy[0], energy[1]);
    if (c.name != "straight") {  // the energy check above resolves the difference 10⁶-fold
      EXPECT_GT(std::abs(energy[0] - energy[1]), 1e6 * 64 * kEps * energy[1]) << c.name;
    }
  }
}

struct FdCase {
  std::string name;
  RodElementHistory history;
  RodElementReference ref;
  Vec15 e, e_dot;
};

// States: moderately deformed; strongly deformed (large twist, bent); rigidly rotated by a large
// random rotation (history with it) plus deformation.
std::vector<FdCase> fd_cases() {
  std::mt19937 rng(11);
  std::vector<FdCase> out;
  for (const Case& c : cases()) {
    RodElementHistory h = c.history;
    const auto ref = RodElementReference::from_reference(c.e0, c.length, h);
    for (int kind = 0; kind < 3; ++kind) {
      const double amp = kind == 0 ? 0.02 : 0.1;
      Vec15 e = deformed(c.e0, rng, amp, kind == 0 ? 0.1 : 1.2, kind == 0 ? -0.2 : -1.9,
                         kind == 0 ? 0.05 : 0.9);
      RodElementHistory hk = h;
      if (kind == 2) {
        const Mat3 q = random_rotation(rng);
        e = rotated(q, e);
        hk = rotated(q, h);
      }
      Vec15 ed;
      for (int i = 0; i < 15; ++i) ed[i] = random_vec3(rng, 1.0)[i % 3];
      out.push_back({c.name + " state " + std::to_string(kind), hk, ref, e, ed});
    }
  }
  return out;
}

// The strain choices of the section (RodAxialStrain × RodTorsionStrain), with and without
// damping: every derivative check runs on each.
struct Variant {
  bool damping;
  RodAxialStrain axial;
  RodTorsionStrain torsion;
};
std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const bool damping : {false, true})
    for (const RodAxialStrain axial : {RodAxialStrain::collocated, RodAxialStrain::gauss_points})
      for (const RodTorsionStrain torsion :
           {RodTorsionStrain::projected, RodTorsionStrain::gauss_points})
        out.push_back({damping, axial, torsion});
  return out;
}

TEST(KirchhoffRod, ForceIsEnergyGradient) {
  for (const Variant& v : variants()) {
    if (v.damping) continue;
    const RodSection s = section(false, v.axial, v.torsion);
    for (const FdCase& c : fd_cases()) {
      const auto r = eval(s, c.ref, c.history, c.e, c.e_dot, false, false);
      const auto energy = [&](const fdcheck::Vec& x) {
        return eval(s, c.ref, c.history, Vec15(x), c.e_dot, false, false).energy;
      };
      const auto res = fdcheck::check_gradient(energy, c.e, r.force);
      EXPECT_TRUE(res.ok()) << c.name << ": ratio " << res.max_ratio << " at " << res.col;
    }
  }
}

TEST(KirchhoffRod, StiffnessAndDampingMatrices) {
  for (const Variant& v : variants()) {
    const bool damping = v.damping;
    const RodSection s = section(damping, v.axial, v.torsion);
    for (const FdCase& c : fd_cases()) {
      const auto r = eval(s, c.ref, c.history, c.e, c.e_dot, true, damping);
      // Residual-only and full evaluations agree (two jet types, same operations).
      const auto f_only = eval(s, c.ref, c.history, c.e, c.e_dot, false, false);
      EXPECT_LE((f_only.force - r.force).norm(), 16 * kEps * r.force.norm()) << c.name;
      const auto force_q = [&](const fdcheck::Vec& x) {
        return fdcheck::Vec(eval(s, c.ref, c.history, Vec15(x), c.e_dot, false, false).force);
      };
      const auto kq = fdcheck::check_jacobian(force_q, c.e, r.stiffness);
      EXPECT_TRUE(kq.ok()) << c.name << " damping " << damping << ": K ratio " << kq.max_ratio
                           << " at (" << kq.row << ", " << kq.col << ") " << kq.analytic << " vs "
                           << kq.fd;
      EXPECT_LE((r.stiffness - r.stiffness.transpose()).norm(),
                damping ? 1e300 : 1e3 * kEps * r.stiffness.norm())
          << c.name;  // without damping K is a Hessian
      if (!damping) continue;
      const auto force_v = [&](const fdcheck::Vec& velocity) {
        return fdcheck::Vec(eval(s, c.ref, c.history, c.e, Vec15(velocity), false, false).force);
      };
      const auto dv = fdcheck::check_jacobian(force_v, c.e_dot, r.damping);
      EXPECT_TRUE(dv.ok()) << c.name << ": D ratio " << dv.max_ratio;
    }
  }
}

// The two kernels (RodKernel): same operations for the values, so energy and strains are bitwise
// equal; force, tangent and damping matrix agree to round-off.
TEST(KirchhoffRod, LocalChainKernelEqualsElementJets) {
  for (const Variant& v : variants()) {
    const bool damping = v.damping;
    const RodSection s = section(damping, v.axial, v.torsion);
    for (const FdCase& c : fd_cases()) {
      for (const bool k : {false, true}) {
        RodElementResult local, full;
        evaluate_rod_element(s, c.ref, c.history, c.e, c.e_dot,
                             {.stiffness = k, .damping_matrix = damping}, local);
        evaluate_rod_element(
            s, c.ref, c.history, c.e, c.e_dot,
            {.stiffness = k, .damping_matrix = damping, .kernel = RodKernel::element_jets}, full);
        EXPECT_EQ(local.energy, full.energy) << c.name;
        EXPECT_EQ(local.strain_mid, full.strain_mid) << c.name;
        EXPECT_LE((local.force - full.force).norm(), 16 * kEps * full.force.norm()) << c.name;
        if (k) {
          EXPECT_LE((local.stiffness - full.stiffness).norm(), 64 * kEps * full.stiffness.norm())
              << c.name << " damping " << damping;
        }
        if (damping) {
          EXPECT_LE((local.damping - full.damping).norm(), 16 * kEps * full.damping.norm())
              << c.name;
        }
      }
    }
  }
}

// ω stays continuous across ±π: a rigid rotation of node 2's reference history by 2π·k + small
// about its tangent changes nothing physical, so the energy must not jump.
TEST(KirchhoffRod, OmegaIsTrackedWithoutWrap) {
  const Case c = cases()[2];
  RodElementHistory h = c.history;
  (void)RodElementReference::from_reference(c.e0, c.length, h);  // sets h.omega
  const Vec15 e = with_twist(c.e0, 0.0, 0.0);
  RodElementHistory far = h;
  far.omega = h.omega + 2.0 * std::numbers::pi;  // a committed value one turn away
  const double w = rod_element_omega(far, e);
  EXPECT_NEAR(w, h.omega + 2.0 * std::numbers::pi, 1e-12);
}

// The nodal end moment: Q·δq equals M·δθ with δθ the virtual rotation of the material triad
// (from central differences of rod_material_triad), and the load Jacobian is ∂Q/∂q.
TEST(KirchhoffRod, EndMomentIsVirtualWorkOfTheMoment) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    const Mat3 r = random_rotation(rng);
    const Vec3 t = 1.3 * (r.col(0) + 0.4 * random_vec3(rng, 1.0));
    const Vec3 m = random_vec3(rng, 2.0);
    const double alpha = 0.4;
    const RodMomentLoad load = rod_end_moment(r, t, m);
    for (int j = 0; j < 4; ++j) {
      const double h = 1e-6;
      Vec4 x(t.x(), t.y(), t.z(), alpha), xp = x, xm = x;
      xp[j] += h;
      xm[j] -= h;
      const Mat3 lp = rod_material_triad(r, xp.head<3>(), xp[3]);
      const Mat3 lm = rod_material_triad(r, xm.head<3>(), xm[3]);
      const Mat3 l0 = rod_material_triad(r, t, alpha);
      const Mat3 w = (lp - lm) / (2 * h) * l0.transpose();  // [δθ]× per unit δq_j
      const Vec3 dtheta(w(2, 1), w(0, 2), w(1, 0));
      EXPECT_NEAR(load.force[j], m.dot(dtheta), 1e-7 * (1.0 + m.norm())) << "trial " << trial;
    }
    const auto q = [&](const fdcheck::Vec& x) {
      return fdcheck::Vec(rod_end_moment(r, x.head<3>(), m).force);
    };
    fdcheck::Vec x(4);
    x << t, alpha;
    const auto res = fdcheck::check_jacobian(q, x, load.jacobian);
    EXPECT_TRUE(res.ok()) << "trial " << trial << " ratio " << res.max_ratio;
  }
}

// The distributed moment: Q·δe equals Σ_p w_p m·δθ(ξ_p), with δθ the virtual rotation of the
// strains' material triad (central differences of rod_point_state), on curved, twisted and
// rotated states; the load Jacobian is ∂Q/∂e (check_jacobian's error-estimate tolerance); both
// kernels agree.
TEST(KirchhoffRod, DistributedMomentIsVirtualWorkOfTheMoment) {
  std::mt19937 rng(17);
  for (const FdCase& c : fd_cases()) {
    const Vec3 m = random_vec3(rng, 2.0);
    RodDistributedMomentLoad full, force_only;
    rod_distributed_moment(c.ref, c.history, c.e, m, true, full);
    rod_distributed_moment(c.ref, c.history, c.e, m, false, force_only);
    EXPECT_LE((full.force - force_only.force).norm(), 16 * kEps * full.force.norm()) << c.name;
    // The local-chain kernel (default) and jets in all 15 coordinates: the same Q and ∂Q/∂e up
    // to round-off of their different operation orders.
    RodDistributedMomentLoad jets;
    rod_distributed_moment(c.ref, c.history, c.e, m, true, jets, RodKernel::element_jets);
    EXPECT_LE((full.force - jets.force).norm(), 1e3 * kEps * jets.force.norm()) << c.name;
    EXPECT_LE((full.jacobian - jets.jacobian).norm(), 1e3 * kEps * jets.jacobian.norm()) << c.name;
    for (int trial = 0; trial < 3; ++trial) {
      Vec15 de;
      for (int i = 0; i < 15; ++i) de[i] = random_vec3(rng, 1.0)[i % 3];
      const double h = 1e-6;
      double work = 0.0;
      for (int p = 0; p < kRodGaussPoints; ++p) {
        const Mat3 lp = rod_point_state(c.ref, c.history, c.e + h * de, c.ref.xi[p]).triad;
        const Mat3 lm = rod_point_state(c.ref, c.history, c.e - h * de, c.ref.xi[p]).triad;
        const Mat3 l0 = rod_point_state(c.ref, c.history, c.e, c.ref.xi[p]).triad;
        const Mat3 w = (lp - lm) / (2 * h) * l0.transpose();  // [δθ]×
        work += c.ref.weight[p] * m.dot(Vec3(w(2, 1), w(0, 2), w(1, 0)));
      }
      // Central differences of the triad: O(h²) truncation and ε/h round-off, both ≲ 1e-9 here.
      EXPECT_NEAR(full.force.dot(de), work, 1e-7 * (1.0 + std::abs(work))) << c.name;
    }
    const auto q = [&](const fdcheck::Vec& x) {
      RodDistributedMomentLoad out;
      rod_distributed_moment(c.ref, c.history, Vec15(x), m, false, out);
      return fdcheck::Vec(out.force);
    };
    const auto res = fdcheck::check_jacobian(q, c.e, full.jacobian);
    EXPECT_TRUE(res.ok()) << c.name << ": ratio " << res.max_ratio << " at (" << res.row << ", "
                          << res.col << ") " << res.analytic << " vs " << res.fd;
  }
}

TEST(KirchhoffRod, TwistMassIntegratesTheTwistRate) {
  // ∫ ρJ ψ̇² dx for ψ̇ linear from 1 to 3 on l = 2: ρJ l (1 + 1·3 + 9)/3
  const Mat3 m = rod_twist_mass(0.5, 2.0);
  const Vec3 v(1.0, 3.0, 0.0);
  EXPECT_NEAR(v.dot(m * v), 0.5 * 2.0 * 13.0 / 3.0, 1e-14);
  // With a bubble rate: ψ̇ = (1 − ξ) + 3ξ + 4ξ(1 − ξ)·2, integrated by a 5-point Gauss rule
  // (exact for the quartic).
  const Vec3 w(1.0, 3.0, 2.0);
  const std::array<double, 5> x{-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831,
                                0.9061798459386640};
  const std::array<double, 5> g{0.2369268850561891, 0.4786286704993665, 0.5688888888888889,
                                0.4786286704993665, 0.2369268850561891};
  double integral = 0.0;
  for (int i = 0; i < 5; ++i) {
    const double xi = 0.5 * (x[i] + 1.0);
    const double rate = (1.0 - xi) * w[0] + xi * w[1] + 4.0 * xi * (1.0 - xi) * w[2];
    integral += 0.5 * g[i] * 0.5 * 2.0 * rate * rate;  // dξ = dx/2 on [−1, 1], ρJ l = 1
  }
  EXPECT_NEAR(w.dot(m * w), integral, 1e-14);
}

}  // namespace
