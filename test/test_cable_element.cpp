// Cable element (DESIGN §3, §8): the analytic force, stiffness and damping matrix are the
// derivatives they claim to be, checked by central differences with an error-estimated tolerance
// (fd_check.hpp) at seeded random configurations; and with EI = 0 on a straight reference the
// element is the paper's (S5), checked against an independent quadrature written here.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/physics/cable_element.hpp"
#include "ancf/physics/hermite_shape.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "fd_check.hpp"
#include "random_geometry.hpp"

namespace {
using namespace ancf;
constexpr double kEps = std::numeric_limits<double>::epsilon();

using random_geometry::random_rotation;
using random_geometry::random_vec3;

// ---- Test configurations ------------------------------------------------------------------------

struct ReferenceElement {
  std::string name;
  Vec12 e0;  // stress-free nodal coordinates (slopes: unit tangents of the reference shape)
  double length;
};

// One interior element of a straight, an arc and a helix cable (l = 0.25, 0.16, 0.17 m).
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

// Which terms are on. The EA = 0 kinds isolate the bending block, which is otherwise small
// next to EA ~ 1e6 in the sum.
struct SectionKind {
  const char* name;
  bool axial, bending, axial_damping, bending_damping;
};
constexpr SectionKind kKinds[] = {
    {"axial", true, false, false, false},
    {"axial+bending", true, true, false, false},
    {"bending", false, true, false, false},
    {"axial+axial-damping", true, false, true, false},
    {"bending+bending-damping", false, true, false, true},
    {"all", true, true, true, true},
};

struct Case {
  std::string label;  // measure / reference / kind: the aggregation key of the printed table
  std::string detail;
  CableSection section;
  CableElementReference ref;
  Vec12 e, e_dot;
};

const char* measure_name(StrainMeasure m) {
  return m == StrainMeasure::green_lagrange ? "green" : "elastic-line";
}

// Seeded random state: the reference scaled by 1 + s (s = 1…5 %) about its midpoint, rigidly
// rotated and moved, plus random slope/position perturbations (curvature of order 1/m on a
// straight reference). Velocities ~0.2 m/s, slope rates ~1/s. Damping time τ = 0.01 s makes the
// Kelvin–Voigt forces comparable to the elastic ones. The three seeds use the Gauss rules
// (axial/bending) 5/5 (default, one loop), 5/3 and 4/2 (separate loops), so that every term is
// checked with each.
constexpr CableQuadrature kRules[] = {{5, 5}, {5, 3}, {4, 2}};
std::vector<Case> make_cases() {
  std::vector<Case> cases;
  constexpr int kSeeds = 3;  // = the number of rules in kRules
  unsigned seed = 12345;
  for (StrainMeasure m : {StrainMeasure::green_lagrange, StrainMeasure::elastic_line})
    for (const ReferenceElement& r : reference_elements())
      for (const SectionKind& k : kKinds)
        for (int s = 0; s < kSeeds; ++s) {
          std::mt19937 rng(++seed);
          std::uniform_real_distribution<double> u(0.0, 1.0);
          Case c;
          c.section.strain = m;
          c.section.axial_stiffness = k.axial ? std::pow(10.0, 3.0 + 3.0 * u(rng)) : 0.0;
          c.section.bending_stiffness = k.bending ? std::pow(10.0, -2.0 + 2.0 * u(rng)) : 0.0;
          c.section.prestrain = s == 0 ? 0.0 : -0.01 + 0.03 * u(rng);
          const double tau = 0.01;
          c.section.axial_damping =
              k.axial_damping ? tau * std::max(c.section.axial_stiffness, 1e3) : 0.0;
          c.section.bending_damping = k.bending_damping ? tau * c.section.bending_stiffness : 0.0;
          c.section.quadrature = kRules[s];
          c.ref = CableElementReference::from_reference(r.e0, r.length, m, c.section.quadrature);

          const double stretch = 0.01 + 0.04 * u(rng);
          const Mat3 rot = random_rotation(rng);
          const Vec3 shift = random_vec3(rng, 0.5);
          const Vec3 mid = 0.5 * (r.e0.segment<3>(0) + r.e0.segment<3>(6));
          for (int n = 0; n < 2; ++n) {
            c.e.segment<3>(6 * n) = mid + shift +
                                    (1.0 + stretch) * rot * (r.e0.segment<3>(6 * n) - mid) +
                                    random_vec3(rng, 0.05 * r.length);
            c.e.segment<3>(6 * n + 3) =
                (1.0 + stretch) * rot * r.e0.segment<3>(6 * n + 3) + random_vec3(rng, 0.05);
            c.e_dot.segment<3>(6 * n) = random_vec3(rng, 0.2);
            c.e_dot.segment<3>(6 * n + 3) = random_vec3(rng, 1.0);
          }
          c.label = std::string(measure_name(m)) + " / " + r.name + " / " + k.name;
          c.detail = c.label + " seed " + std::to_string(seed) +
                     " EA=" + std::to_string(c.section.axial_stiffness) +
                     " EI=" + std::to_string(c.section.bending_stiffness) +
                     " eps_p=" + std::to_string(c.section.prestrain) + " rule " +
                     std::to_string(kRules[s].axial) + "/" + std::to_string(kRules[s].bending);
          cases.push_back(c);
        }
  return cases;
}

CableElementResult evaluate(const CableSection& s, const CableElementReference& ref, const Vec12& e,
                            const Vec12& e_dot) {
  CableElementResult out;
  evaluate_cable_element(s, ref, e, e_dot, {.stiffness = true, .damping_matrix = true}, out);
  return out;
}

std::string describe(const fdcheck::Result& r) {
  char buf[200];
  std::snprintf(
      buf, sizeof buf, "worst entry (%ld,%ld): analytic %.9g, fd %.9g, tol %.3g, ratio %.3g",
      static_cast<long>(r.row), static_cast<long>(r.col), r.analytic, r.fd, r.tol, r.max_ratio);
  return buf;
}

// Worst case per label, printed as a table so the measured margins show in the test output.
void print_table(const char* what, const std::map<std::string, fdcheck::Result>& worst) {
  std::printf("%s: max |fd-analytic|/tol, max |fd-analytic|/max|J|, max tol/max|J|\n", what);
  for (const auto& [label, r] : worst)
    std::printf("  %-48s %8.2e %8.2e %8.2e\n", label.c_str(), r.max_ratio, r.max_rel,
                r.max_tol_rel);
}

// ---- Derivative checks --------------------------------------------------------------------------

TEST(CableElement, ForceIsEnergyGradient) {
  std::map<std::string, fdcheck::Result> worst;
  for (const Case& c : make_cases()) {
    CableSection elastic = c.section;  // damping forces do not derive from U
    elastic.axial_damping = elastic.bending_damping = 0.0;
    if (elastic.axial_stiffness == 0.0 && elastic.bending_stiffness == 0.0) continue;
    const auto energy = [&](const VecX& e) {
      return evaluate(elastic, c.ref, e, Vec12::Zero()).energy;
    };
    const fdcheck::Result r =
        fdcheck::check_gradient(energy, c.e, evaluate(elastic, c.ref, c.e, Vec12::Zero()).force);
    EXPECT_TRUE(r.ok()) << c.detail << ": " << describe(r);
    worst[c.label].merge(r);
  }
  print_table("force vs dU/de", worst);
}

TEST(CableElement, StiffnessIsForceJacobian) {
  std::map<std::string, fdcheck::Result> worst;
  double max_asym = 0.0;
  for (const Case& c : make_cases()) {
    const auto force = [&](const VecX& e) {
      return VecX(evaluate(c.section, c.ref, e, c.e_dot).force);
    };
    const CableElementResult res = evaluate(c.section, c.ref, c.e, c.e_dot);
    const fdcheck::Result r = fdcheck::check_jacobian(force, c.e, res.stiffness);
    EXPECT_TRUE(r.ok()) << c.detail << ": " << describe(r);
    worst[c.label].merge(r);
    if (!c.section.has_damping()) {  // Hessian of U: symmetric up to round-off of its terms
      const double asym = (res.stiffness - res.stiffness.transpose()).norm() / res.stiffness.norm();
      EXPECT_LE(asym, 8 * kEps) << c.detail;
      max_asym = std::max(max_asym, asym);
    }
  }
  print_table("stiffness vs df/de", worst);
  std::printf("max ||K - K^T|| / ||K|| (no damping): %.2e\n", max_asym);
}

TEST(CableElement, ForceOnlyRequestGivesTheSameForceAndEnergy) {
  // The residual path (no stiffness requested) is its own compile-time instantiation without the
  // Hessian: it must give the force and energy of the full evaluation (same formulas; a few ε of
  // reassociation at most).
  for (const Case& c : make_cases()) {
    const CableElementResult full = evaluate(c.section, c.ref, c.e, c.e_dot);
    CableElementResult force_only;
    evaluate_cable_element(c.section, c.ref, c.e, c.e_dot,
                           {.force_kernel = CableForceKernel::pointwise}, force_only);
    EXPECT_LE((force_only.force - full.force).norm(), 4 * kEps * full.force.norm()) << c.detail;
    EXPECT_LE(std::abs(force_only.energy - full.energy), 4 * kEps * std::abs(full.energy))
        << c.detail;
  }
}

TEST(CableElement, InvariantForceKernelGivesTheSameForceAndEnergy) {
  // CableForceKernel::invariant (the default of force-only requests) evaluates the same formulas
  // through s₁ = a·a, s₂ = a·b, s₃ = b·b on translation-free coordinates: the force and energy of
  // the pointwise kernel up to round-off, and the nodal position forces cancel exactly. The
  // pointwise kernel forms r_x from the absolute positions (cancellation of order |r|/l in a, and
  // of a·a − J₀² in ε); it is compared here at the element translated to r_i = 0, where that
  // round-off is absent (the force is translation invariant).
  double worst_force = 0.0, worst_energy = 0.0;
  for (const Case& c : make_cases()) {
    CableElementResult pointwise, invariant;
    Vec12 moved = c.e;
    moved.segment<3>(6) -= c.e.segment<3>(0);
    moved.segment<3>(0).setZero();
    evaluate_cable_element(c.section, c.ref, moved, c.e_dot,
                           {.force_kernel = CableForceKernel::pointwise}, pointwise);
    evaluate_cable_element(c.section, c.ref, c.e, c.e_dot, {}, invariant);
    const double df = (invariant.force - pointwise.force).norm() / pointwise.force.norm();
    const double de = std::abs(invariant.energy - pointwise.energy) / std::abs(pointwise.energy);
    EXPECT_LE(df, 16 * kEps) << c.detail;
    EXPECT_LE(de, 16 * kEps) << c.detail;
    EXPECT_EQ(invariant.force.segment<3>(0), (-invariant.force.segment<3>(6)).eval()) << c.detail;
    worst_force = std::max(worst_force, df);
    worst_energy = std::max(worst_energy, de);
  }
  std::printf(
      "invariant vs pointwise force kernel: max relative difference force %.2e, energy "
      "%.2e\n",
      worst_force, worst_energy);
}

TEST(CableElement, InvariantForceIsEnergyGradient) {
  // The invariant kernel checked on its own against central differences of its energy.
  std::map<std::string, fdcheck::Result> worst;
  for (const Case& c : make_cases()) {
    CableSection elastic = c.section;
    elastic.axial_damping = elastic.bending_damping = 0.0;
    if (elastic.axial_stiffness == 0.0 && elastic.bending_stiffness == 0.0) continue;
    auto force_only = [&](const Vec12& e) {
      CableElementResult out;
      evaluate_cable_element(elastic, c.ref, e, Vec12::Zero(), {}, out);
      return out;
    };
    const auto energy = [&](const VecX& e) { return force_only(Vec12(e)).energy; };
    const fdcheck::Result r = fdcheck::check_gradient(energy, c.e, force_only(c.e).force);
    EXPECT_TRUE(r.ok()) << c.detail << ": " << describe(r);
    worst[c.label].merge(r);
  }
  print_table("invariant force vs dU/de", worst);
}

TEST(CableElement, DampingMatrixIsForceVelocityJacobian) {
  std::map<std::string, fdcheck::Result> worst;
  for (const Case& c : make_cases()) {
    if (!c.section.has_damping()) continue;
    const auto force = [&](const VecX& v) {
      return VecX(evaluate(c.section, c.ref, c.e, v).force);
    };
    const CableElementResult res = evaluate(c.section, c.ref, c.e, c.e_dot);
    const fdcheck::Result r = fdcheck::check_jacobian(force, c.e_dot, res.damping);
    EXPECT_TRUE(r.ok()) << c.detail << ": " << describe(r);
    worst[c.label].merge(r);
    const double asym = (res.damping - res.damping.transpose()).norm() / res.damping.norm();
    EXPECT_LE(asym, 8 * kEps) << c.detail;  // D = ∫ c ∇ε ∇εᵀ: symmetric
  }
  print_table("damping matrix vs df/de_dot", worst);
}

// The check above has teeth: an error of 1e-6 · max|K| in one entry of K is reported.
TEST(CableElement, FdCheckDetectsSmallStiffnessError) {
  for (const Case& c : make_cases()) {
    if (c.label != "green / arc / all") continue;
    const auto force = [&](const VecX& e) {
      return VecX(evaluate(c.section, c.ref, e, c.e_dot).force);
    };
    MatX k = evaluate(c.section, c.ref, c.e, c.e_dot).stiffness;
    ASSERT_TRUE(fdcheck::check_jacobian(force, c.e, k).ok());
    k(4, 7) += 1e-6 * k.cwiseAbs().maxCoeff();
    EXPECT_FALSE(fdcheck::check_jacobian(force, c.e, k).ok()) << c.detail;
  }
}

// ---- The paper's element (S5) by an independent quadrature --------------------------------------

// n-point Gauss–Legendre rule on [0, 1] by Newton's method on P_n (independent of ancf's table).
void gauss_rule(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5)), dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;  // P_{k-1}, P_k
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-17) break;
    }
    x[i] = 0.5 * (1.0 - z);
    w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

struct PaperElement {
  double energy = 0.0;
  Vec12 force = Vec12::Zero();
  double max_a2 = 0.0;  // max |r_x|² (the magnitude of the terms in ε)
};

// U = ∫₀¹ ½ E₁A l (ε + ε_p)² dξ with ε = ½(eᵀS'ᵀS'e / l² − 1), S' = dS/dξ (S1); for ε_p = 0 this is
// (S5): U = 1/8 ∫ E₁A l (eᵀS'ᵀS'e/l² − 1)² dξ. f = ∂U/∂e = ∫ E₁A (ε + ε_p) S'ᵀS'e / l dξ.
// Composite `panels` × `points` Gauss rule.
PaperElement paper_element(const Vec12& e, double l, double ea, double eps_p, int panels,
                           int points) {
  std::vector<double> x, w;
  gauss_rule(points, x, w);
  PaperElement p;
  for (int panel = 0; panel < panels; ++panel)
    for (int g = 0; g < points; ++g) {
      const double xi = (panel + x[g]) / panels, wt = w[g] / panels;
      const double ds[4] = {6 * xi * xi - 6 * xi, l * (1 - 4 * xi + 3 * xi * xi),
                            6 * xi - 6 * xi * xi, l * (3 * xi * xi - 2 * xi)};
      Vec3 r_xi = Vec3::Zero();
      for (int k = 0; k < 4; ++k) r_xi += ds[k] * e.segment<3>(3 * k);
      const double a2 = r_xi.squaredNorm() / (l * l);
      const double strain = 0.5 * (a2 - 1.0) + eps_p;
      p.energy += wt * 0.5 * ea * l * strain * strain;
      for (int k = 0; k < 4; ++k)
        p.force.segment<3>(3 * k) += (wt * ea * strain * ds[k] / l) * r_xi;
      p.max_a2 = std::max(p.max_a2, a2);
    }
  return p;
}

TEST(CableElementPaper, OwnGaussRuleIsExact) {  // the reference quadrature itself
  std::vector<double> x, w;
  gauss_rule(10, x, w);
  double moment = 0.0;
  for (int g = 0; g < 10; ++g) moment += w[g] * std::pow(x[g], 19);
  // Nodes good to ~eps shift Σw ξ¹⁹ by ≈ eps·Σw·19ξ¹⁸ = eps; weights to a few eps relative.
  EXPECT_NEAR(moment, 1.0 / 20.0, 4.0 * kEps * (1.0 + 1.0 / 20.0));
  std::printf("own 10-point Gauss rule: |sum w x^19 - 1/20| = %.2e\n",
              std::abs(moment - 1.0 / 20.0));
}

// Relative round-off of U or f: each quadrature value carries an absolute error of a few eps·|a|²
// in ε, i.e. a relative one of eps·|a|²/|ε|; |ε| is taken as the RMS strain √(2U / EA l).
double roundoff_tolerance(const PaperElement& p, double ea, double l) {
  return 32.0 * kEps * (1.0 + p.max_a2 / std::sqrt(2.0 * p.energy / (ea * l)));
}

void compare_with_paper(double eps_p, int panels, const char* what) {
  const ReferenceElement straight = reference_elements()[0];
  double worst_u = 0.0, worst_f = 0.0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    CableSection sec{.strain = StrainMeasure::green_lagrange,
                     .axial_stiffness = std::pow(10.0, 3.0 + 3.0 * u(rng)),
                     .prestrain = eps_p};
    const auto ref =
        CableElementReference::from_reference(straight.e0, straight.length, sec.strain);
    Vec12 e = straight.e0;
    const double stretch = 0.01 + 0.04 * u(rng);
    for (int n = 0; n < 2; ++n) {
      e.segment<3>(6 * n) =
          (1.0 + stretch) * e.segment<3>(6 * n) + random_vec3(rng, 0.05 * straight.length);
      e.segment<3>(6 * n + 3) = (1.0 + stretch) * e.segment<3>(6 * n + 3) + random_vec3(rng, 0.05);
    }
    const CableElementResult res = evaluate(sec, ref, e, Vec12::Zero());
    const PaperElement p =
        paper_element(e, straight.length, sec.axial_stiffness, eps_p, panels, 10);
    const double tol = roundoff_tolerance(p, sec.axial_stiffness, straight.length);
    const double err_u = std::abs(res.energy - p.energy) / p.energy;
    const double err_f =
        (res.force - p.force).lpNorm<Eigen::Infinity>() / p.force.lpNorm<Eigen::Infinity>();
    EXPECT_LE(err_u, tol) << what << " seed " << seed;
    EXPECT_LE(err_f, tol) << what << " seed " << seed;
    worst_u = std::max(worst_u, err_u / tol);
    worst_f = std::max(worst_f, err_f / tol);
    if (seed == 1)
      std::printf("%s: rel. error U %.2e, f %.2e (tolerance %.2e)\n", what, err_u, err_f, tol);
  }
  std::printf("%s: max error/tolerance over seeds: U %.2e, f %.2e\n", what, worst_u, worst_f);
}

// EI = 0, straight reference, no prestrain: the element energy is the paper's (S5).
TEST(CableElementPaper, GreenEnergyAndForceEqualS5) {
  compare_with_paper(0.0, 1, "S5, 10-point Gauss");
}

// The Green axial integrands are polynomials of degree 8 in ξ, so 5 Gauss points are exact:
// agreement with an 80-point composite rule to round-off, with prestrain.
TEST(CableElementPaper, FiveGaussPointsExactForGreenAxial) {
  compare_with_paper(0.013, 8, "8 x 10-point composite Gauss, eps_p = 0.013");
}

// ---- Bending damping: Kelvin–Voigt on κ̃ = √(κ² + κ_s²) (issue 17 item 6) -------------------

// A straight cable of 0.25 m along x (κ = 0 everywhere), a bending-only section with damping.
CableSection damped_bending_section(double kappa_s) {
  return CableSection{.strain = StrainMeasure::green_lagrange,
                      .bending_stiffness = 0.3,
                      .bending_damping = 0.02,
                      .bending_damping_curvature = kappa_s};
}

// Scalar curvature κ = |r' × r''|/|r'|^p of the Hermite interpolant at ξ (p = 3, Green), from
// the shape functions: an independent evaluation of what the damping law is written in.
double curvature_at(const Vec12& e, double xi, double l) {
  const Vec4 d1 = hermite::first_derivative(xi, l), d2 = hermite::second_derivative(xi, l);
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    a += d1[k] * e.segment<3>(3 * k);
    b += d2[k] * e.segment<3>(3 * k);
  }
  return a.cross(b).norm() / std::pow(a.norm(), 3);
}

// The law is what docs/formulation.md states: the dissipation ė·f_d (f_d the damping part of
// the force) equals ∫ c_b κ̃̇² dx with κ̃ = √(κ² + κ_s²), κ̃̇ by central differences in time along
// e + t ė, integrated with the element's 5 Gauss points (own rule; straight reference, J₀ = 1).
// For κ ≫ κ_s it is the classical c_b κ̇²; at κ ≪ κ_s it fades like (κ/κ_s)². Tolerance: the
// O(h²) error of the time difference at h = 1e-5 s (Richardson estimate from 2h) with a margin.
TEST(BendingDamping, DissipationIsKelvinVoigtOnTheRegularizedCurvature) {
  const ReferenceElement straight = reference_elements()[0];
  const double l = straight.length;
  std::vector<double> x, w;
  gauss_rule(5, x, w);
  for (const double kappa_s : {1e-3, 1.0, 30.0}) {
    const CableSection sec = damped_bending_section(kappa_s);
    const auto ref = CableElementReference::from_reference(straight.e0, l, sec.strain);
    for (unsigned seed = 1; seed <= 4; ++seed) {
      std::mt19937 rng(40 + seed);
      Vec12 e = straight.e0, e_dot;
      for (int k = 0; k < 4; ++k) {
        e.segment<3>(3 * k) += random_vec3(rng, 0.05 * (k % 2 ? 1.0 : l));
        e_dot.segment<3>(3 * k) = random_vec3(rng, k % 2 ? 1.0 : 0.2);
      }
      auto dissipation_by_differences = [&](double h) {
        double sum = 0.0;
        for (int g = 0; g < 5; ++g) {
          auto regularized = [&](double t) {
            const double kappa = curvature_at(e + t * e_dot, x[g], l);
            return std::sqrt(kappa * kappa + kappa_s * kappa_s);
          };
          const double rate = (regularized(h) - regularized(-h)) / (2.0 * h);
          sum += w[g] * l * sec.bending_damping * rate * rate;
        }
        return sum;
      };
      const double expected = dissipation_by_differences(1e-5);
      // Richardson estimate of the O(h²) error, plus the rounding of κ̃ (≲ 30) over 2h.
      const double fd_error = std::abs(expected - dissipation_by_differences(2e-5)) / 3.0 +
                              64.0 * kEps * (30.0 / 1e-5) * expected;
      CableSection still = sec;
      still.bending_damping = 0.0;
      const Vec12 f_d = evaluate(sec, ref, e, e_dot).force - evaluate(still, ref, e, e_dot).force;
      const double dissipation = e_dot.dot(f_d);
      EXPECT_NEAR(dissipation, expected, 10.0 * fd_error) << "kappa_s " << kappa_s;
      if (seed == 1)
        std::printf("kappa_s %g: dissipation %.10e W, c_b ∫ (d kappa~/dt)^2 %.10e W\n", kappa_s,
                    dissipation, expected);
    }
  }
}

// Smooth at κ = 0, where a straight cable starts: the force, stiffness and damping matrix pass
// the central-difference checks at an exactly straight configuration moving with a rigid
// rotation plus a bending rate, and the damping matrix is continuous there (the previous law,
// c_b κ̇ ∇κ, tends to c_b ∇κ∇κᵀ whose limit depends on the direction of approach).
TEST(BendingDamping, SmoothAtZeroCurvature) {
  const ReferenceElement straight = reference_elements()[0];
  const double l = straight.length;
  const CableSection sec = damped_bending_section(1.0);
  const auto ref = CableElementReference::from_reference(straight.e0, l, sec.strain);
  std::mt19937 rng(5);
  const Vec3 omega(0.0, 4.0, 0.0);
  Vec12 e_dot;
  for (int n = 0; n < 2; ++n) {
    e_dot.segment<3>(6 * n) =
        omega.cross(Vec3(straight.e0.segment<3>(6 * n))) + random_vec3(rng, 0.1);
    e_dot.segment<3>(6 * n + 3) =
        omega.cross(Vec3(straight.e0.segment<3>(6 * n + 3))) + random_vec3(rng, 0.5);
  }
  const Vec12& e = straight.e0;
  const CableElementResult at = evaluate(sec, ref, e, e_dot);
  const auto force = [&](const VecX& q) { return VecX(evaluate(sec, ref, q, e_dot).force); };
  const auto force_v = [&](const VecX& v) { return VecX(evaluate(sec, ref, e, v).force); };
  const fdcheck::Result k = fdcheck::check_jacobian(force, e, at.stiffness);
  const fdcheck::Result d = fdcheck::check_jacobian(force_v, e_dot, at.damping);
  EXPECT_TRUE(k.ok()) << describe(k);
  EXPECT_TRUE(d.ok()) << describe(d);
  // Continuity: approaching κ = 0 along two perpendicular bending directions.
  const double d_scale = sec.bending_damping / (l * l * l);
  for (const int axis : {1, 2}) {
    const Vec3 dir = Vec3::Unit(axis);
    double previous = 0.0;
    for (const double delta : {1e-2, 1e-3, 1e-4}) {
      Vec12 bent = e;
      bent.segment<3>(3) += delta * dir;  // slope at node i: a bend in the plane of x and dir
      const double change =
          (evaluate(sec, ref, bent, e_dot).damping - at.damping).cwiseAbs().maxCoeff() / d_scale;
      if (previous > 0.0) {
        EXPECT_LT(change, 0.02 * previous) << "delta " << delta;  // O(δ²)
      }
      previous = change;
    }
    EXPECT_LT(previous, 1e-4);  // → 0: the limit does not depend on the direction
  }
}

// ---- Gauss rules per term (CableQuadrature) ---------------------------------------------------

// The rule is the one asked for: with 4 axial points the degree-8 Green energy is no longer
// exact (relative error far above round-off), with 5 it is; the bending rule does not touch
// an EI = 0 element.
TEST(CableQuadrature, FourAxialPointsAreNotExactForGreenAxial) {
  const ReferenceElement straight = reference_elements()[0];
  std::mt19937 rng(7);
  Vec12 e = straight.e0;
  for (int n = 0; n < 2; ++n) {
    e.segment<3>(6 * n) = 1.03 * e.segment<3>(6 * n) + random_vec3(rng, 0.05 * straight.length);
    e.segment<3>(6 * n + 3) = 1.03 * e.segment<3>(6 * n + 3) + random_vec3(rng, 0.05);
  }
  const PaperElement p = paper_element(e, straight.length, 1e5, 0.0, 8, 10);
  const double tol = roundoff_tolerance(p, 1e5, straight.length);
  for (const CableQuadrature q : {CableQuadrature{5, 1}, CableQuadrature{4, 5}}) {
    const CableSection sec{
        .strain = StrainMeasure::green_lagrange, .axial_stiffness = 1e5, .quadrature = q};
    const auto ref =
        CableElementReference::from_reference(straight.e0, straight.length, sec.strain, q);
    const double err = std::abs(evaluate(sec, ref, e, Vec12::Zero()).energy / p.energy - 1.0);
    std::printf("Green axial energy, rule %d/%d: rel. error %.2e (round-off %.2e)\n", q.axial,
                q.bending, err, tol);
    if (q.axial == 5)
      EXPECT_LE(err, tol);
    else
      EXPECT_GT(err, 1e3 * tol);
  }
}

// Linearized at the straight stress-free reference, U ≈ ½EA∫(δr_x·x̂)² + ½EI∫|δr_xx,⊥|²: the
// tangent is the bar matrix EA/(30l)[36, 3l, −36, 3l; …] on the axial components and the
// Euler–Bernoulli matrix EI/l³[12, 6l, −12, 6l; …] on the transverse ones. Their integrands have
// degree 4 and 2, so every rule with ≥ 3 axial and ≥ 2 bending points gives them to round-off;
// 2 axial or 1 bending point does not (the 1-point bending matrix has rank 1).
TEST(CableQuadrature, LinearStiffnessIsExactWithThreeAxialAndTwoBendingPoints) {
  const double l = 0.3, ea = 2e4, ei = 3.0;
  Mat4 bar, beam;
  bar << 36, 3 * l, -36, 3 * l, 3 * l, 4 * l * l, -3 * l, -l * l, -36, -3 * l, 36, -3 * l, 3 * l,
      -l * l, -3 * l, 4 * l * l;
  beam << 12, 6 * l, -12, 6 * l, 6 * l, 4 * l * l, -6 * l, 2 * l * l, -12, -6 * l, 12, -6 * l,
      6 * l, 2 * l * l, -6 * l, 4 * l * l;
  bar *= ea / (30 * l);
  beam *= ei / (l * l * l);
  Mat12 exact = Mat12::Zero();
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      exact(3 * i, 3 * j) = bar(i, j);
      exact(3 * i + 1, 3 * j + 1) = exact(3 * i + 2, 3 * j + 2) = beam(i, j);
    }
  const CableGeometry g = straight_cable(Vec3::Zero(), l * Vec3::UnitX(), 1);
  const Vec12 e0 = g.element_coordinates(0);
  for (const StrainMeasure m : {StrainMeasure::green_lagrange, StrainMeasure::elastic_line})
    for (int na = 2; na <= 5; ++na)
      for (int nb = 1; nb <= 5; ++nb) {
        const CableSection sec{
            .strain = m, .axial_stiffness = ea, .bending_stiffness = ei, .quadrature = {na, nb}};
        const auto ref = CableElementReference::from_reference(e0, l, m, sec.quadrature);
        const Mat12 k = evaluate(sec, ref, e0, Vec12::Zero()).stiffness;
        const double err = (k - exact).cwiseAbs().maxCoeff() / exact.cwiseAbs().maxCoeff();
        if (na >= 3 && nb >= 2)
          EXPECT_LT(err, 64 * kEps) << measure_name(m) << " rule " << na << "/" << nb;
        else
          EXPECT_GT(err, 1e-3) << measure_name(m) << " rule " << na << "/" << nb;
      }
}

// CableTangent::tension_only drops the geometric stiffness N ∂²ε/∂a² where N < 0 and nothing
// else: forces are unchanged, a stretched element's matrix is the exact one, and a uniformly
// compressed EI = 0 element, whose exact tangent has the negative transverse eigenvalues of its
// compressive geometric stiffness, gets a positive semidefinite matrix (its axial part only).
TEST(CableTangent, TensionOnlyDropsOnlyTheCompressiveGeometricStiffness) {
  const double l = 0.25, ea = 3e5;
  const CableGeometry g = straight_cable(Vec3::Zero(), l * Vec3::UnitX(), 1);
  const Vec12 e0 = g.element_coordinates(0);
  for (const StrainMeasure m : {StrainMeasure::green_lagrange, StrainMeasure::elastic_line}) {
    const CableSection sec{.strain = m, .axial_stiffness = ea};
    const auto ref = CableElementReference::from_reference(e0, l, m, sec.quadrature);
    for (const double stretch : {1.01, 0.99}) {
      const Vec12 e = stretch * e0;  // uniform axial strain of sign stretch − 1
      CableElementResult exact, tension_only;
      evaluate_cable_element(sec, ref, e, Vec12::Zero(), {.stiffness = true}, exact);
      evaluate_cable_element(sec, ref, e, Vec12::Zero(),
                             {.stiffness = true, .tangent = CableTangent::tension_only},
                             tension_only);
      EXPECT_EQ(exact.force, tension_only.force) << measure_name(m);
      EXPECT_EQ(exact.energy, tension_only.energy) << measure_name(m);
      const Eigen::SelfAdjointEigenSolver<Mat12> ek(exact.stiffness), et(tension_only.stiffness);
      const double scale = exact.stiffness.cwiseAbs().maxCoeff();
      if (stretch > 1.0) {
        EXPECT_EQ(exact.stiffness, tension_only.stiffness) << measure_name(m);
      } else {
        EXPECT_LT(ek.eigenvalues().minCoeff(), -1e-3 * scale) << measure_name(m);
        EXPECT_GT(et.eigenvalues().minCoeff(), -64 * kEps * scale) << measure_name(m);
        EXPECT_GT((exact.stiffness - tension_only.stiffness).cwiseAbs().maxCoeff(), 1e-3 * scale);
      }
    }
  }
}

TEST(CableQuadrature, RulesOutsideOneToFiveAreRefused) {
  const CableGeometry g = straight_cable(Vec3::Zero(), Vec3::UnitX(), 1);
  for (const CableQuadrature q : {CableQuadrature{0, 3}, CableQuadrature{5, 6}})
    EXPECT_THROW((void)CableElementReference::from_reference(g.element_coordinates(0), 1.0,
                                                             StrainMeasure::green_lagrange, q),
                 ModelError);
}

}  // namespace
