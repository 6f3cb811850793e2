// Rigid bodies in natural coordinates, angle laws and driven frames (DESIGN §2; ring drive of
// CAPTURE.md): the constant mass matrix (∫ρ c cᵀ dV) ⊗ I₃ carries the mass, first moment and
// inertia (kinetic energy of a rigid motion, independent quadrature of solid bodies), the
// coordinate maps round-trip, validation rejects what it must, and the prescribed motions have the
// derivatives they claim (central differences with the error-estimated tolerance of fd_check.hpp).
//
// Tolerances are c · eps · (natural scale of the quantity); each c is derived in a comment from the
// number of rounded operations between the inputs and the compared values. The measured worst
// errors, in the same units, are printed.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/physics/angle_law.hpp"
#include "ancf/physics/driven_frame.hpp"
#include "ancf/physics/rigid_body.hpp"
#include "fd_check.hpp"
#include "random_geometry.hpp"

namespace {
using namespace ancf;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

// ---- Helpers ------------------------------------------------------------------------------------

using random_geometry::random_rotation;
using random_geometry::random_vec3;

double log_uniform(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(std::log(lo), std::log(hi));
  return std::exp(u(rng));
}

Mat3 skew(const Vec3& n) {
  Mat3 s;
  s << 0, -n.z(), n.y(), n.z(), 0, -n.x(), -n.y(), n.x(), 0;
  return s;
}

// Rodrigues' formula, written independently of Eigen::AngleAxis.
Mat3 rodrigues(const Vec3& unit_axis, double angle) {
  const Mat3 k = skew(unit_axis);
  return Mat3::Identity() + std::sin(angle) * k + (1.0 - std::cos(angle)) * k * k;
}

// A physically valid body: principal second moments J_i = ∫ρ s_i² > 0 (radii of gyration from
// 1 cm to 1 m, masses from 0.1 to 100 kg), I_c = R diag(J₂+J₃, J₁+J₃, J₁+J₂) Rᵀ — which satisfies
// the triangle inequalities by construction — and a centre of mass offset ~0.5 m.
RigidBodyInertia random_inertia(std::mt19937& rng) {
  RigidBodyInertia in;
  in.mass = log_uniform(rng, 0.1, 100.0);
  Vec3 j;
  for (int k = 0; k < 3; ++k) j[k] = in.mass * std::pow(log_uniform(rng, 0.01, 1.0), 2);
  const Mat3 r = random_rotation(rng);
  const Mat3 i = r * Vec3(j[1] + j[2], j[0] + j[2], j[0] + j[1]).asDiagonal() * r.transpose();
  in.inertia = 0.5 * (i + i.transpose());
  in.centre_of_mass = random_vec3(rng, 0.5);
  return in;
}

// The pole of CAPTURE.md: 10 kg uniform rod, I⊥ = 0.0627, I∥ = 1.125e-3 about the centre of
// mass; body origin at its base, axis along the body z axis (length implied: ≈ 0.273 m for a
// solid cylinder of radius 15 mm; the offset only matters as an offset here).
RigidBodyInertia capture_pole() {
  RigidBodyInertia in;
  in.mass = 10.0;
  in.centre_of_mass = Vec3(0.0, 0.0, 0.195);
  in.inertia = Vec3(0.0627, 0.0627, 1.125e-3).asDiagonal();
  return in;
}

Mat12 full_mass_matrix(const Mat4& m4) {  // m4 ⊗ I₃, written out
  Mat12 m = Mat12::Zero();
  for (int k = 0; k < 4; ++k)
    for (int l = 0; l < 4; ++l) m.block<3, 3>(3 * k, 3 * l) = m4(k, l) * Mat3::Identity();
  return m;
}

// Worst measured error in units of eps · scale, with the case that produced it.
struct Worst {
  double value = 0.0;
  std::string where;
  void update(double err, double scale, const std::string& label) {
    const double v = err / (kEps * scale);
    if (v > value || where.empty()) {
      value = v;
      where = label;
    }
  }
};

void report(const char* what, const Worst& w, double tol) {
  std::printf("  %-58s %7.2f eps*scale (tol %4.0f)  [%s]\n", what, w.value, tol, w.where.c_str());
}

std::string describe(const fdcheck::Result& r) {
  char buf[200];
  std::snprintf(
      buf, sizeof buf, "worst entry (%ld,%ld): analytic %.12g, fd %.12g, tol %.3g, ratio %.3g",
      static_cast<long>(r.row), static_cast<long>(r.col), r.analytic, r.fd, r.tol, r.max_ratio);
  return buf;
}

void report_fd(const char* what, const fdcheck::Result& r) {
  std::printf("  %-44s max |fd-J|/tol %8.2e, max |fd-J|/max|J| %8.2e, tol/max|J| %8.2e\n", what,
              r.max_ratio, r.max_rel, r.max_tol_rel);
}

// Neumaier-compensated sum: |error| ≤ 2 eps |Σx| + O(n eps²) Σ|x|, so a quadrature reference with
// thousands of points is rounded like a handful of operations.
struct CompensatedSum {
  double sum = 0.0, carry = 0.0;
  void add(double x) {
    const double t = sum + x;
    carry += std::abs(sum) >= std::abs(x) ? (sum - t) + x : (x - t) + sum;
    sum = t;
  }
  [[nodiscard]] double value() const { return sum + carry; }
};

// Composite 2-point Gauss–Legendre rule on [a, b]: exact for cubics on every cell.
std::vector<std::pair<double, double>> gauss2(double a, double b, int cells) {
  const double g = 1.0 / std::sqrt(3.0), h = (b - a) / cells;
  std::vector<std::pair<double, double>> r;
  for (int i = 0; i < cells; ++i) {
    const double mid = a + (i + 0.5) * h;
    r.emplace_back(mid - 0.5 * h * g, 0.5 * h);
    r.emplace_back(mid + 0.5 * h * g, 0.5 * h);
  }
  return r;
}

// ∫ρ c cᵀ dV from weighted body points (p̄, w): c = [1, p̄].
struct MomentQuadrature {
  std::array<CompensatedSum, 16> s;
  int points = 0;
  void add(const Vec3& p, double w) {
    const Vec4 c = point_weights(p);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) s[4 * i + j].add(w * c[i] * c[j]);
    ++points;
  }
  [[nodiscard]] Mat4 value() const {
    Mat4 m;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) m(i, j) = s[4 * i + j].value();
    return m;
  }
};

// ---- Mass matrix --------------------------------------------------------------------------------

// Translation field and first moment. Tolerances:
//  * M₄(0,0) = m and M₄(0,1:3) = m c̄ are single products: exact resp. ≤ 1 ulp.
//  * (M q)₀ = m r_O + Σ m c̄_k a_k = m (r_O + A c̄): a 4-term sum of products of rounded
//    entries (≤ 2 ulp each) — γ₆ ≈ 6 eps of the abs scale m(|r_O| + |c̄|); the reference m(r_O + A
//    c̄) another ~5 eps. Tolerance 16 eps · m(|r_O| + |c̄|).
//  * (M v)₀ = m v_C with ȧ_k = ω × a_k (2 products + 1 sum, γ₃ of |ω|): same count plus 3 eps,
//    scale m(|v_O| + |ω||c̄|); tolerance 16.
//  * translation only (ȧ_k = ω × a_k = 0 exactly): ½ vᵀMv = ½ m v·v with M v rounded to 1 ulp and a
//    3-term dot (γ₃): ≤ 4 eps relative; the reference ½ m |v|² ≤ 4 eps; tolerance 8 eps · ½ m|v|².
TEST(RigidBodyMass, TotalMassAndFirstMoment) {
  std::mt19937 rng(101);
  constexpr double kTolMoment = 16, kTolMomentum = 16, kTolTranslation = 8;
  Worst first, momentum, translation;
  for (int trial = 0; trial < 500; ++trial) {
    const RigidBodyInertia in = trial == 0 ? capture_pole() : random_inertia(rng);
    const Mat4 m4 = natural_mass_matrix(in);
    const Mat12 m12 = full_mass_matrix(m4);
    const double m = in.mass;
    const Vec3& c = in.centre_of_mass;
    const std::string label = "trial " + std::to_string(trial);
    EXPECT_EQ(m4(0, 0), m) << label;
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(m4(0, k + 1), m * c[k]) << label;
      EXPECT_EQ(m4(k + 1, 0), m * c[k]) << label;
    }
    EXPECT_EQ(m4, m4.transpose()) << label;  // exactly, for an exactly symmetric I_c
    // ∫ρ c cᵀ of a body with 3-D extent is positive definite.
    EXPECT_EQ(Eigen::LLT<Mat4>(m4).info(), Eigen::Success) << label;

    const Mat3 a = random_rotation(rng);
    const Vec3 r = random_vec3(rng, 1.0), v = random_vec3(rng, 1.0), w = random_vec3(rng, 1.0);
    const BodyCoordinates q = body_coordinates(r, a);

    // First moment about the global origin: m r_C = m (r_O + A c̄).
    const Vec3 mr = (m12 * q).head<3>();
    const double e1 = (mr - m * (r + a * c)).cwiseAbs().maxCoeff();
    EXPECT_LE(e1, kTolMoment * kEps * m * (r.norm() + c.norm())) << label;
    first.update(e1, m * (r.norm() + c.norm()), label);

    // Linear momentum: (M v)₀ = m v_C, v_C = v_O + ω × A c̄.
    const BodyCoordinates qd = body_velocities(a, v, w);
    const Vec3 p = (m12 * qd).head<3>();
    const double e2 = (p - m * (v + w.cross(a * c))).cwiseAbs().maxCoeff();
    const double s2 = m * (v.norm() + w.norm() * c.norm());
    EXPECT_LE(e2, kTolMomentum * kEps * s2) << label;
    momentum.update(e2, s2, label);

    // Pure translation: T = ½ m |v|².
    const BodyCoordinates qt = body_velocities(a, v, Vec3::Zero());
    const double t = 0.5 * qt.dot(m12 * qt), t_ref = 0.5 * m * v.squaredNorm();
    EXPECT_LE(std::abs(t - t_ref), kTolTranslation * kEps * t_ref) << label;
    translation.update(std::abs(t - t_ref), t_ref, label);
  }
  std::printf("mass matrix, translation field and first moment (500 seeded bodies):\n");
  report("(M q)_0 - m (r_O + A c)   / m(|r_O|+|c|)", first, kTolMoment);
  report("(M v)_0 - m v_C           / m(|v_O|+|w||c|)", momentum, kTolMomentum);
  report("1/2 v'Mv - 1/2 m|v|^2     / 1/2 m|v|^2", translation, kTolTranslation);
}

// Kinetic energy of a rigid motion: ½ q̇ᵀ M q̇ = ½ m |v_C|² + ½ ωᵀ (A I_c Aᵀ) ω.
// Scale S: every term of either side is bounded by it. With ȧ_k = ω × a_k (|ȧ_k| ≤ |ω|) and
// J̄ = ∫ρ p̄p̄ᵀ positive semi-definite (|J̄_kl| ≤ √(J̄_kk J̄_ll), Σ|J̄_kl| ≤ 3 tr J̄),
//   Σ|v_i||M_ij||v_j| ≤ m|v_O|² + 2√3 m|v_O||c̄||ω| + 3|ω|² (m|c̄|² + ½ tr I_c)
//                     ≤ 3 m (|v_O| + |ω||c̄|)² + 2 |ω|² tr I_c =: S,
// and m|v_C|², |ω|²‖I_c‖ ≤ S too. Left side: the 12-term products M v and vᵀ(Mv) (γ₂₄ on S), the
// entries of J̄ (m c̄c̄ᵀ + ½tr I − I, ≤ 4 eps of their abs scale, itself ≤ S/|ω|²) and ȧ_k (γ₃):
// ≲ 32 eps S; right side: v_C, A I Aᵀ (two 3-term products) and the dots: ≲ 16 eps S.
// Tolerance 64 eps · S (realistic errors are √n smaller than these worst-case bounds).
TEST(RigidBodyMass, KineticEnergyOfRigidMotion) {
  std::mt19937 rng(202);
  constexpr double kTol = 64;
  Worst generic, about_com, about_origin, global_axis, body_axis;
  auto check = [&](const RigidBodyInertia& in, const Mat3& a, const Vec3& vo, const Vec3& w,
                   Worst& worst, const std::string& label) {
    const Mat12 m12 = full_mass_matrix(natural_mass_matrix(in));
    const BodyCoordinates qd = body_velocities(a, vo, w);
    const double t = 0.5 * qd.dot(m12 * qd);
    const Vec3 vc = vo + w.cross(a * in.centre_of_mass);
    const Mat3 i_global = a * in.inertia * a.transpose();
    const double t_ref = 0.5 * in.mass * vc.squaredNorm() + 0.5 * w.dot(i_global * w);
    const double s = 3.0 * in.mass * std::pow(vo.norm() + w.norm() * in.centre_of_mass.norm(), 2) +
                     2.0 * w.squaredNorm() * in.inertia.trace();
    EXPECT_LE(std::abs(t - t_ref), kTol * kEps * s) << label << ": T " << t << " ref " << t_ref;
    worst.update(std::abs(t - t_ref), s, label);
    return t;
  };
  for (int trial = 0; trial < 500; ++trial) {
    const RigidBodyInertia in = trial == 0 ? capture_pole() : random_inertia(rng);
    const Mat3 a = random_rotation(rng);
    const Vec3 vo = random_vec3(rng, 1.0), w = random_vec3(rng, 1.0);
    const Vec3& c = in.centre_of_mass;
    const std::string label = "trial " + std::to_string(trial);
    check(in, a, vo, w, generic, label);

    // Pure rotation about the centre of mass (v_C = 0): T = ½ ωᵀ (A I_c Aᵀ) ω.
    const Vec3 vo_com = -w.cross(a * c);
    const double t_com = check(in, a, vo_com, w, about_com, label + " about C");
    const double t_rot = 0.5 * w.dot(a * in.inertia * a.transpose() * w);
    const double s_com = 3.0 * in.mass * std::pow(2.0 * w.norm() * c.norm(), 2) +
                         2.0 * w.squaredNorm() * in.inertia.trace();
    EXPECT_LE(std::abs(t_com - t_rot), kTol * kEps * s_com) << label;
    about_com.update(std::abs(t_com - t_rot), s_com, label + " about C, 1/2 w'Iw");

    // Rotation about the body origin (v_O = 0): parallel-axis theorem, I_O = I_c + m(|c̄|²1 − c̄c̄ᵀ).
    const Mat3 i_o =
        in.inertia + in.mass * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
    const double t_o = check(in, a, Vec3::Zero(), w, about_origin, label + " about O");
    const double t_o_ref = 0.5 * w.dot(a * i_o * a.transpose() * w);
    const double s_o = 3.0 * in.mass * std::pow(w.norm() * c.norm(), 2) +
                       2.0 * w.squaredNorm() * in.inertia.trace();
    EXPECT_LE(std::abs(t_o - t_o_ref), kTol * kEps * s_o) << label;
    about_origin.update(std::abs(t_o - t_o_ref), s_o, label + " about O, parallel axis");

    // About each global axis and each body axis a_k, with a translation.
    for (int k = 0; k < 3; ++k) {
      const double rate = w.norm();
      check(in, a, vo, rate * Vec3::Unit(k), global_axis,
            label + " global axis " + std::to_string(k));
      check(in, a, vo, rate * a.col(k), body_axis, label + " body axis " + std::to_string(k));
      // Spin about a principal body axis through C with diagonal I_c: T = ½ I_kk ω².
      if (trial == 0) {
        const double tk = check(in, a, -(rate * a.col(k)).cross(a * c), rate * a.col(k), body_axis,
                                "pole principal axis " + std::to_string(k));
        EXPECT_NEAR(tk, 0.5 * in.inertia(k, k) * rate * rate,
                    kTol * kEps *
                        (3.0 * in.mass * std::pow(2.0 * rate * c.norm(), 2) +
                         2.0 * rate * rate * in.inertia.trace()));
      }
    }
  }
  std::printf("kinetic energy 1/2 v'Mv vs 1/2 m|v_C|^2 + 1/2 w'(A I_c A')w (500 seeded bodies):\n");
  report("generic motion", generic, kTol);
  report("rotation about the centre of mass (incl. 1/2 w'Iw)", about_com, kTol);
  report("rotation about the body origin (incl. parallel axis)", about_origin, kTol);
  report("rotation about a global axis", global_axis, kTol);
  report("rotation about a body axis", body_axis, kTol);
}

// Independent check of J̄ = ∫ρ p̄p̄ᵀ dV = m c̄c̄ᵀ + ½ tr(I_c) 1 − I_c: integrate ∫ρ c cᵀ dV numerically
// over uniform solids placed with a random orientation R_b and offset c̄ in the body frame, and
// compare with natural_mass_matrix(m, c̄, closed-form I_c).
//  * box a×b×c: integrand quadratic in each coordinate → composite 2-point Gauss (exact for cubics)
//    is exact; I_c = m/12 diag(b²+c², a²+c², a²+b²).
//  * thin rod of length L along d̄: 1-D, same rule exact; I_c = m L²/12 (1 − d̄d̄ᵀ).
//  * solid cylinder (radius ρ₀, height h): in (r, φ, z) the integrand times the Jacobian r is a
//    cubic in r (2-point Gauss exact), a trigonometric polynomial of degree ≤ 2 in φ (trapezoid
//    rule with N = 16 > 2 points exact), quadratic in z; I_c = diag(m(3ρ₀²+h²)/12, same, mρ₀²/2).
// So the quadrature has no truncation error: only round-off is left. Scale of entry (i, j):
// m σ_i σ_j with σ₀ = 1, σ_k = |c̄| + R (R the largest distance from C), which bounds Σ w |c_i c_j|
// (weights positive, summing to m). Each term w c_i c_j is rounded with ≲ 10 eps relative to
// w σ_i σ_j (point coordinates c̄ + R_b s: ≤ 5 eps of σ; weight: ≤ 4 products), the compensated sum
// adds 2 eps, natural_mass_matrix and the closed-form I_c ≲ 8 eps. Tolerance 32 eps · m σ_i σ_j.
TEST(RigidBodyMass, MatchesQuadratureOfUniformSolids) {
  std::mt19937 rng(303);
  constexpr double kTol = 32;
  Worst box_w, rod_w, cyl_w;
  auto compare = [&](const Mat4& quad, const RigidBodyInertia& in, double radius, Worst& worst,
                     const std::string& label) {
    const Mat4 m4 = natural_mass_matrix(in);
    const Vec4 sigma(1.0, in.centre_of_mass.norm() + radius, in.centre_of_mass.norm() + radius,
                     in.centre_of_mass.norm() + radius);
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) {
        const double scale = in.mass * sigma[i] * sigma[j], err = std::abs(quad(i, j) - m4(i, j));
        EXPECT_LE(err, kTol * kEps * scale)
            << label << " entry (" << i << "," << j << "): quadrature " << quad(i, j)
            << ", natural_mass_matrix " << m4(i, j);
        worst.update(err, scale, label);
      }
  };
  for (int trial = 0; trial < 20; ++trial) {
    const std::string label = "trial " + std::to_string(trial);
    const Mat3 rb = random_rotation(rng);
    const Vec3 c = random_vec3(rng, 0.5);
    const double m = log_uniform(rng, 0.1, 100.0);

    {  // Box.
      const Vec3 l(log_uniform(rng, 0.02, 1.0), log_uniform(rng, 0.02, 1.0),
                   log_uniform(rng, 0.02, 1.0));
      const double rho = m / (l.x() * l.y() * l.z());
      MomentQuadrature q;
      for (const auto& [x, wx] : gauss2(-0.5 * l.x(), 0.5 * l.x(), 6))
        for (const auto& [y, wy] : gauss2(-0.5 * l.y(), 0.5 * l.y(), 6))
          for (const auto& [z, wz] : gauss2(-0.5 * l.z(), 0.5 * l.z(), 6))
            q.add(c + rb * Vec3(x, y, z), rho * wx * wy * wz);
      RigidBodyInertia in;
      in.mass = m;
      in.centre_of_mass = c;
      const Vec3 l2 = l.cwiseProduct(l);
      in.inertia =
          rb * (m / 12.0 * Vec3(l2.y() + l2.z(), l2.x() + l2.z(), l2.x() + l2.y())).asDiagonal() *
          rb.transpose();
      in.validate("box");
      compare(q.value(), in, 0.5 * l.norm(), box_w, label + " box");
    }
    {  // Thin rod along d̄ = R_b e_z.
      const double len = log_uniform(rng, 0.05, 2.0);
      const Vec3 d = rb.col(2);
      MomentQuadrature q;
      for (const auto& [z, wz] : gauss2(-0.5 * len, 0.5 * len, 16)) q.add(c + z * d, m / len * wz);
      RigidBodyInertia in;
      in.mass = m;
      in.centre_of_mass = c;
      in.inertia = m * len * len / 12.0 * (Mat3::Identity() - d * d.transpose());
      compare(q.value(), in, 0.5 * len, rod_w, label + " thin rod");
    }
    {  // Solid cylinder, axis R_b e_z; trial 0 is the CAPTURE pole's section (r = 15 mm).
      const double r0 = trial == 0 ? 0.015 : log_uniform(rng, 0.005, 0.3);
      const double h = trial == 0 ? 0.2731 : log_uniform(rng, 0.05, 2.0);
      const double mass = trial == 0 ? 10.0 : m;
      const double rho = mass / (kPi * r0 * r0 * h);
      constexpr int kPhi = 16;
      MomentQuadrature q;
      for (const auto& [r, wr] : gauss2(0.0, r0, 3))
        for (int k = 0; k < kPhi; ++k) {
          const double phi = 2.0 * kPi * k / kPhi;
          for (const auto& [z, wz] : gauss2(-0.5 * h, 0.5 * h, 6))
            q.add(c + rb * Vec3(r * std::cos(phi), r * std::sin(phi), z),
                  rho * r * wr * (2.0 * kPi / kPhi) * wz);
        }
      RigidBodyInertia in;
      in.mass = mass;
      in.centre_of_mass = c;
      const double i_perp = mass * (3.0 * r0 * r0 + h * h) / 12.0, i_axial = 0.5 * mass * r0 * r0;
      in.inertia = rb * Vec3(i_perp, i_perp, i_axial).asDiagonal() * rb.transpose();
      in.validate("cylinder");
      if (trial == 0) {  // CAPTURE pole: I⊥ = 0.0627, I∥ = 1.125e-3 (to the 3 digits given)
        EXPECT_NEAR(i_perp, 0.0627, 1e-4);
        EXPECT_NEAR(i_axial, 1.125e-3, 1e-9);
      }
      compare(q.value(), in, std::hypot(r0, 0.5 * h), cyl_w, label + " cylinder");
    }
  }
  std::printf(
      "natural_mass_matrix vs exact quadrature of int rho c c' dV (20 seeded solids each):\n");
  report("box (12^3 Gauss points)", box_w, kTol);
  report("thin rod (32 Gauss points)", rod_w, kTol);
  report("solid cylinder (6 x 16 x 12 points)", cyl_w, kTol);
}

// ---- Coordinate maps ----------------------------------------------------------------------------

// angular_velocity = ½ Σ a_k × ȧ_k = ½ (3ω − A Aᵀ ω): ȧ_k = ω × a_k (γ₂ per component, ≤ 2 eps|ω|),
// a_k × ȧ_k (another γ₂), 3-term sum and the orthonormality defect of A (≤ ~4 eps, entering as
// ½ (1 − AAᵀ) ω): ≲ 12 eps |ω|. Tolerance 16 eps |ω|.
// Points: (c(p̄)ᵀ ⊗ I₃) q = r_O + A p̄, the same 4 products and sums on both sides in another
// order: ≤ 4 eps of |r_O| + |p̄|; tolerance 8.
TEST(RigidBodyKinematics, CoordinateMapsRoundTrip) {
  std::mt19937 rng(404);
  constexpr double kTolOmega = 16, kTolPoint = 8;
  Worst omega, point;
  for (int trial = 0; trial < 1000; ++trial) {
    const std::string label = "trial " + std::to_string(trial);
    const Mat3 a = random_rotation(rng);
    const Vec3 r = random_vec3(rng, 1.0), v = random_vec3(rng, 1.0);
    const Vec3 w = random_vec3(rng, std::pow(10.0, trial % 5 - 2));  // 0.01 … 100 rad/s
    const BodyCoordinates q = body_coordinates(r, a);
    EXPECT_EQ(q.head<3>(), r) << label;
    EXPECT_EQ(rotation_of(q), a) << label;  // a copy: exact
    const BodyCoordinates qd = body_velocities(a, v, w);
    EXPECT_EQ(qd.head<3>(), v) << label;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(Vec3(qd.segment<3>(3 + 3 * k)), w.cross(a.col(k)));
    const double e = (angular_velocity(q, qd) - w).cwiseAbs().maxCoeff();
    EXPECT_LE(e, kTolOmega * kEps * w.norm()) << label;
    omega.update(e, w.norm(), label);

    const Vec3 p = random_vec3(rng, 0.5);
    Vec3 rp = Vec3::Zero(), dp = Vec3::Zero();
    const Vec4 cw = point_weights(p), dw = direction_weights(p);
    for (int k = 0; k < 4; ++k) {
      rp += cw[k] * q.segment<3>(3 * k);
      dp += dw[k] * q.segment<3>(3 * k);
    }
    const double ep =
        std::max((rp - (r + a * p)).cwiseAbs().maxCoeff(), (dp - a * p).cwiseAbs().maxCoeff());
    EXPECT_LE(ep, kTolPoint * kEps * (r.norm() + p.norm())) << label;
    point.update(ep, r.norm() + p.norm(), label);
  }
  // Zero angular velocity gives exactly zero.
  const Mat3 a = random_rotation(rng);
  EXPECT_EQ(angular_velocity(body_coordinates(Vec3::Zero(), a),
                             body_velocities(a, Vec3::UnitX(), Vec3::Zero())),
            Vec3::Zero());
  std::printf("coordinate maps (1000 seeded states, |w| from 0.01 to 100 rad/s):\n");
  report("angular_velocity(q, v) - w   / |w|", omega, kTolOmega);
  report("(c(p)' x I3) q - (r_O + A p) / (|r_O|+|p|)", point, kTolPoint);
}

// ---- Validation ---------------------------------------------------------------------------------

void expect_rejected(const RigidBodyInertia& in, const std::string& reason,
                     const std::string& label) {
  try {
    in.validate("probe");
    ADD_FAILURE() << label << ": accepted, expected a ModelError about '" << reason << "'";
  } catch (const ModelError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("probe"), std::string::npos) << label << ": " << msg;
    EXPECT_NE(msg.find(reason), std::string::npos) << label << ": " << msg;
  }
}

TEST(RigidBodyInertia, ValidateRejectsInvalidAndAcceptsValid) {
  std::mt19937 rng(505);
  const RigidBodyInertia pole = capture_pole();
  EXPECT_NO_THROW(pole.validate("pole"));
  for (int trial = 0; trial < 200; ++trial) EXPECT_NO_THROW(random_inertia(rng).validate("random"));

  const Mat3 r = random_rotation(rng);
  auto rotated = [&](const Vec3& principal) {
    const Mat3 i = r * principal.asDiagonal() * r.transpose();
    return Mat3(0.5 * (i + i.transpose()));
  };
  // A thin plate sits on the boundary I₃ = I₁ + I₂ (rotated: computed eigenvalues off by ~eps):
  // accepted.
  RigidBodyInertia plate = pole;
  plate.inertia = rotated(Vec3(1.0, 2.0, 3.0));
  EXPECT_NO_THROW(plate.validate("plate"));

  for (double m : {0.0, -1.0, -1e-300, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()}) {
    RigidBodyInertia in = pole;
    in.mass = m;
    expect_rejected(in, "mass", "mass " + std::to_string(m));
  }
  {
    RigidBodyInertia in = pole;
    in.centre_of_mass.y() = std::numeric_limits<double>::quiet_NaN();
    expect_rejected(in, "centre of mass", "NaN centre of mass");
  }
  {
    RigidBodyInertia in = pole;
    in.inertia(0, 1) = 1e-3;  // I(1,0) stays 0
    expect_rejected(in, "symmetric", "non-symmetric");
    in.inertia = rotated(Vec3(1.0, 1.5, 2.0));
    in.inertia(2, 0) *= 1.0 + 1e-6;
    expect_rejected(in, "symmetric", "slightly non-symmetric");
    in.inertia = pole.inertia;
    in.inertia(1, 1) = std::numeric_limits<double>::infinity();
    expect_rejected(in, "finite", "infinite moment");
  }
  {
    RigidBodyInertia in = pole;
    in.inertia = Mat3::Zero();
    expect_rejected(in, "positive definite", "zero inertia");
    in.inertia = rotated(Vec3(1.0, 1.0, -0.5));
    expect_rejected(in, "positive definite", "indefinite");
    in.inertia = -rotated(Vec3(1.0, 1.5, 2.0));
    expect_rejected(in, "positive definite", "negative definite");
    // An ideal thin rod (I∥ = 0) is only semi-definite (and makes M singular): rejected as
    // documented, whatever its orientation — rotated, its computed smallest eigenvalue is ±eps.
    in.inertia = Vec3(1.0, 1.0, 0.0).asDiagonal();
    expect_rejected(in, "positive definite", "thin rod");
    for (int k = 0; k < 50; ++k) {
      const Mat3 rk = random_rotation(rng);
      const Mat3 i = rk * Vec3(1.0, 1.0, 0.0).asDiagonal() * rk.transpose();
      in.inertia = 0.5 * (i + i.transpose());
      expect_rejected(in, "positive definite", "rotated thin rod " + std::to_string(k));
    }
    // A thin wire (I∥ / I⊥ = 1e-6) is a valid body.
    in.inertia = rotated(Vec3(1.0, 1.0, 1e-6));
    EXPECT_NO_THROW(in.validate("wire"));
  }
  {
    RigidBodyInertia in = pole;
    in.inertia = rotated(Vec3(1.0, 1.0, 2.5));
    expect_rejected(in, "triangle", "I3 = 2.5 > I1 + I2 = 2");
    in.inertia = rotated(Vec3(3.0, 1.0, 1.0 + 1e-9));
    expect_rejected(in, "triangle", "I3 just above I1 + I2 (first principal moment largest)");
  }
}

// ---- Angle laws ---------------------------------------------------------------------------------

AngleState callback_state(double t) {  // θ = 0.4 sin(1.3 t) + 0.2 t² − 0.1
  return {0.4 * std::sin(1.3 * t) + 0.2 * t * t - 0.1, 0.52 * std::cos(1.3 * t) + 0.4 * t,
          -0.676 * std::sin(1.3 * t) + 0.4};
}

// θ and θ̇ as functions of t; their claimed derivatives θ̇ and θ̈, checked by central differences.
fdcheck::Result check_angle_law(const AngleLaw& law, double t) {
  const fdcheck::Function f = [&](const fdcheck::Vec& x) {
    const AngleState s = law.at(x[0]);
    return fdcheck::Vec(Eigen::Vector2d(s.angle, s.rate));
  };
  const AngleState s = law.at(t);
  return fdcheck::check_jacobian(f, fdcheck::Vec::Constant(1, t),
                                 fdcheck::Mat(Eigen::Vector2d(s.rate, s.acceleration)));
}

TEST(AngleLaw, FixedAndConstantRate) {
  std::mt19937 rng(606);
  std::uniform_real_distribution<double> u(-3.0, 10.0);
  const AngleLaw fixed = AngleLaw::fixed(0.7), zero = AngleLaw::fixed();
  const AngleLaw constant = AngleLaw::constant_rate(-0.35, 1.2);
  EXPECT_TRUE(fixed.is_fixed());
  EXPECT_TRUE(zero.is_fixed());
  EXPECT_FALSE(constant.is_fixed());
  EXPECT_FALSE(AngleLaw::constant_rate(0.0).is_fixed());
  EXPECT_FALSE(AngleLaw::smooth_ramp(1.0, 1.0).is_fixed());
  EXPECT_FALSE(AngleLaw::callback(callback_state).is_fixed());
  for (int i = 0; i < 100; ++i) {
    const double t = u(rng);
    const AngleState f = fixed.at(t), z = zero.at(t), c = constant.at(t);
    EXPECT_EQ(f.angle, 0.7);
    EXPECT_EQ(f.rate, 0.0);
    EXPECT_EQ(f.acceleration, 0.0);
    EXPECT_EQ(z.angle, 0.0);
    // θ₀ + ω t: one product and one sum, ≤ 2 ulp of |θ₀| + |ω t|.
    EXPECT_LE(std::abs(c.angle - (1.2 - 0.35 * t)), 2 * kEps * (1.2 + 0.35 * std::abs(t)));
    EXPECT_EQ(c.rate, -0.35);
    EXPECT_EQ(c.acceleration, 0.0);
  }
}

// Composite 5-point Gauss–Legendre on [a, b].
double gauss5(const std::function<double(double)>& f, double a, double b, int cells) {
  static constexpr std::array<double, 5> x = {0.0, -0.5384693101056831, 0.5384693101056831,
                                              -0.9061798459386640, 0.9061798459386640};
  static constexpr std::array<double, 5> w = {0.5688888888888889, 0.4786286704993665,
                                              0.4786286704993665, 0.2369268850561891,
                                              0.2369268850561891};
  CompensatedSum s;
  const double h = (b - a) / cells;
  for (int i = 0; i < cells; ++i)
    for (int k = 0; k < 5; ++k) s.add(0.5 * h * w[k] * f(a + (i + 0.5) * h + 0.5 * h * x[k]));
  return s.value();
}

// The ring drive of CAPTURE.md: ω_ref = ω_max (1 − cos(πt/t_a))/2 for t < t_a, then ω_max;
// ω_max = 12°/s, t_a = 1 s; θ_ref = θ₀ + ∫ω_ref.
//  * θ̇ against the same law written as ω_max sin²(πt/2t_a): ≤ 4 eps ω_max (a cos/sin, a
//    product, and 1 − cos near t = 0 is exact by Sterbenz); tolerance 8 eps ω_max.
//  * θ against ∫θ̇ by composite 5-point Gauss (32 cells on [0, t_a]): truncation error
//    ≤ (t_a/32)¹⁰ ω_max (π/t_a)¹⁰ (5!)⁴/(11 (10!)³) · t_a ≈ 1e-24 rad — nothing; round-off: nodes
//    and weights to 1 ulp, compensated sum; θ itself ~4 operations. Tolerance 16 eps (|θ₀| + ω_max
//    t).
//  * θ̈ against the derivative of ω_max sin²(πt/2t_a) written as ω_max π/t_a sin x cos x
//    (x = πt/2t_a; the law uses ½ sin 2x): ≤ 4 eps on each side; tolerance 8 eps ω_max π/t_a.
TEST(AngleLaw, SmoothRampIsTheCaptureDriveLaw) {
  constexpr double w_max = 12.0 * kPi / 180.0, ta = 1.0, th0 = 0.4;
  constexpr double kTolRate = 8, kTolAngle = 16, kTolAcc = 8;
  const AngleLaw law = AngleLaw::smooth_ramp(w_max, ta, th0);
  const auto rate_ref = [&](double t) {
    return t < ta ? w_max * std::pow(std::sin(0.5 * kPi * t / ta), 2) : w_max;
  };
  std::mt19937 rng(707);
  std::uniform_real_distribution<double> u(0.0, 4.0 * ta);
  Worst rate, angle, acc;
  for (int i = 0; i <= 400; ++i) {
    const double t = i < 200 ? i * ta / 100.0 : u(rng);  // grid 0 … 2 t_a, then random up to 4 t_a
    const std::string label = "t = " + std::to_string(t);
    const AngleState s = law.at(t);
    EXPECT_LE(std::abs(s.rate - rate_ref(t)), kTolRate * kEps * w_max) << label;
    rate.update(std::abs(s.rate - rate_ref(t)), w_max, label);
    const double th_ref =
        th0 + gauss5(rate_ref, 0.0, std::min(t, ta), 32) + (t > ta ? w_max * (t - ta) : 0.0);
    const double scale = std::abs(th0) + w_max * t;
    EXPECT_LE(std::abs(s.angle - th_ref), kTolAngle * kEps * scale) << label;
    angle.update(std::abs(s.angle - th_ref), scale, label);
    const double x = 0.5 * kPi * t / ta;  // d/dt ω_max sin²x = ω_max π/t_a sin x cos x
    const double acc_ref = t < ta ? w_max * kPi / ta * std::sin(x) * std::cos(x) : 0.0;
    EXPECT_LE(std::abs(s.acceleration - acc_ref), kTolAcc * kEps * w_max * kPi / ta) << label;
    acc.update(std::abs(s.acceleration - acc_ref), w_max * kPi / ta, label);
  }
  // Starts from rest: θ(0) = θ₀, θ̇(0) = θ̈(0) = 0 exactly (sin 0 = 0, 1 − cos 0 = 0).
  EXPECT_EQ(law.at(0.0).angle, th0);
  EXPECT_EQ(law.at(0.0).rate, 0.0);
  EXPECT_EQ(law.at(0.0).acceleration, 0.0);
  // Reaches ω_max: θ(t_a) = θ₀ + ½ ω_max t_a.
  EXPECT_NEAR(law.at(ta).angle, th0 + 0.5 * w_max * ta, 4 * kEps * (th0 + w_max * ta));

  // Continuity at t_a between t_a⁻ = the double below t_a and t_a. θ: jump ≤ ω_max (t_a − t_a⁻)
  // plus the rounding of two ~4-operation evaluations. θ̇: ½ ω_max (1 − cos(π − δ)) with
  // δ ≈ πeps/2, so 1 − cos = 2 − O(δ²) rounds to 2: equal to ≤ 2 ulp. θ̈ is continuous (→ 0) only
  // because sin(π) = 0: at t_a⁻, sin(fl(π t_a⁻/t_a)) = (π − fl(π)) + πeps/2 + rounding of the
  // argument ≲ 0.6 eps + 1.6 eps + 1.6 eps, times ½ ω_max π/t_a: tolerance 4 eps ω_max π/t_a.
  const double tm = std::nextafter(ta, 0.0);
  const AngleState left = law.at(tm), right = law.at(ta);
  std::printf("smooth ramp (w_max = 12 deg/s, t_a = 1 s, 401 times in [0, 4 t_a]):\n");
  report("theta_dot - w_max sin^2(pi t/2t_a)   / w_max", rate, kTolRate);
  report("theta - (theta0 + Gauss int theta_dot) / (|theta0|+w_max t)", angle, kTolAngle);
  report("theta_ddot - d/dt w_max sin^2        / (w_max pi/t_a)", acc, kTolAcc);
  const double jump_angle = std::abs(right.angle - left.angle);
  EXPECT_LE(jump_angle, w_max * (ta - tm) + 8 * kEps * (th0 + w_max * ta));
  EXPECT_LE(std::abs(right.rate - left.rate), 2 * kEps * w_max);
  EXPECT_LE(std::abs(left.acceleration), 4 * kEps * w_max * kPi / ta);
  EXPECT_EQ(right.acceleration, 0.0);
  std::printf(
      "  at t_a: |theta jump| %.2e eps*theta, |theta_dot jump| %.2f eps*w_max, "
      "|theta_ddot(t_a-)| %.2f eps*w_max*pi/t_a\n",
      jump_angle / (kEps * (th0 + w_max * ta)), std::abs(right.rate - left.rate) / (kEps * w_max),
      std::abs(left.acceleration) / (kEps * w_max * kPi / ta));

  // Negative rate (reverse drive), other ramp times: the same law scaled.
  const AngleLaw rev = AngleLaw::smooth_ramp(-2.0, 0.25, -1.0);
  EXPECT_NEAR(rev.at(0.125).rate, -1.0, 4 * kEps * 2.0);
  EXPECT_NEAR(rev.at(0.25).angle, -1.0 - 0.25, 8 * kEps * 1.5);
  EXPECT_EQ(rev.at(3.0).rate, -2.0);
}

// θ̇ and θ̈ of every law vs central differences of θ and θ̇ in t (fd_check.hpp). Around t_a the
// smooth ramp's θ̈ has a kink (θ⃛ jumps); stencils straddling it have O(h) error, which the
// Richardson estimate also sees (D(2h) − D(h) is of the same order), so they are checked as well.
TEST(AngleLaw, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(808);
  const double w_max = 12.0 * kPi / 180.0, ta = 1.0;
  const double h = std::cbrt(kEps);  // the step fd_check takes at |t| ≤ 1
  std::vector<std::pair<std::string, AngleLaw>> laws = {
      {"fixed", AngleLaw::fixed(0.3)},
      {"constant rate", AngleLaw::constant_rate(0.8, -0.2)},
      {"smooth ramp", AngleLaw::smooth_ramp(w_max, ta, 0.1)},
      {"smooth ramp (fast, reverse)", AngleLaw::smooth_ramp(-3.0, 0.2, 2.0)},
      {"callback", AngleLaw::callback(callback_state)}};
  std::uniform_real_distribution<double> before(0.0, ta), after(ta, 5.0 * ta);
  for (const auto& [name, law] : laws) {
    fdcheck::Result worst, worst_kink;
    const double t_ramp = name == "smooth ramp (fast, reverse)" ? 0.2 : ta;
    for (int i = 0; i < 80; ++i) {  // before and after t_a, stencils clear of it
      const double t = i < 40 ? before(rng) : after(rng);
      const fdcheck::Result r = check_angle_law(law, t);
      EXPECT_TRUE(r.ok()) << name << " at t = " << t << ": " << describe(r);
      if (std::abs(t - t_ramp) > 3 * h)
        worst.merge(r);
      else
        worst_kink.merge(r);
    }
    for (double k : {-3.0, -1.5, -0.5, 0.0, 0.5, 1.5, 3.0}) {  // stencils straddling t_a
      const fdcheck::Result r = check_angle_law(law, t_ramp + k * h);
      EXPECT_TRUE(r.ok()) << name << " at t_a + " << k << " h: " << describe(r);
      worst_kink.merge(r);
    }
    const bool ramp = name.find("ramp") != std::string::npos;
    if (!ramp) worst.merge(worst_kink);  // nothing special happens at t_a
    report_fd(("angle law: " + name).c_str(), worst);
    if (ramp) report_fd(("angle law: " + name + ", stencil across t_a").c_str(), worst_kink);
  }
  // The check can fail: a callback whose θ̈ is off by 0.1 % is caught.
  const AngleLaw wrong = AngleLaw::callback([](double t) {
    AngleState s = callback_state(t);
    s.acceleration *= 1.001;
    return s;
  });
  EXPECT_FALSE(check_angle_law(wrong, 0.7).ok());
}

TEST(AngleLaw, RejectsInvalidParameters) {
  EXPECT_THROW((void)AngleLaw::smooth_ramp(1.0, 0.0), ModelError);
  EXPECT_THROW((void)AngleLaw::smooth_ramp(1.0, -1.0), ModelError);
  EXPECT_THROW((void)AngleLaw::smooth_ramp(1.0, -0.0), ModelError);
  EXPECT_THROW((void)AngleLaw::smooth_ramp(1.0, std::numeric_limits<double>::quiet_NaN()),
               ModelError);
  EXPECT_NO_THROW((void)AngleLaw::smooth_ramp(1.0, 1e-9));
  EXPECT_THROW((void)AngleLaw::callback(std::function<AngleState(double)>{}), ModelError);
}

// ---- Driven frames ------------------------------------------------------------------------------

std::vector<std::pair<std::string, AngleLaw>> frame_laws() {
  return {{"constant rate", AngleLaw::constant_rate(1.7, 0.3)},
          {"smooth ramp", AngleLaw::smooth_ramp(12.0 * kPi / 180.0, 1.0, 2.2256)},
          {"callback", AngleLaw::callback(callback_state)}};
}

// Tolerances: Eigen's axis-angle matrix and the quaternion-built A₀ are each orthonormal to a few
// eps; A = R A₀ adds 3-term dot products (γ₃); AᵀA then 3-term dots of unit vectors: ‖AᵀA − 1‖_max
// ≲ 4 + 4 + 2·3 + 3 ≈ 17 eps worst case; tolerance 24 eps. The same count bounds A A₀ᵀ n − n
// (|n| = 1; one more product): 24 eps. A(0) vs Rodrigues' formula written here (each entry a sum
// of three O(1) terms, both sides ≲ 6 eps after the product with A₀): 16 eps. Rotation angle of
// A A₀ᵀ: ½ vee(R − Rᵀ) = sin θ n and ½(tr R − 1) = cos θ, ≲ 8 eps from R plus 1 for sin/cos;
// tolerance 16 eps.
TEST(DrivenFrame, RotatesAboutAnInvariantAxis) {
  std::mt19937 rng(909);
  std::uniform_real_distribution<double> u(0.0, 6.0);
  constexpr double kTolOrtho = 24, kTolAxis = 24, kTolInitial = 16, kTolAngle = 16;
  Worst ortho, axis_w, initial, angle_w;
  for (const auto& [name, law] : frame_laws())
    for (int trial = 0; trial < 100; ++trial) {
      DrivenFrame f;
      f.name = "ring";
      f.origin = random_vec3(rng, 1.0);
      f.initial_rotation = random_rotation(rng);
      f.axis = random_vec3(rng, 3.0);  // not unit: the frame normalises it
      f.law = law;
      const Vec3 n = f.axis.normalized();
      const std::string label = name + " trial " + std::to_string(trial);

      const FrameKinematics k0 = f.at(0.0);
      const double e0 =
          (k0.a - rodrigues(n, law.at(0.0).angle) * f.initial_rotation).cwiseAbs().maxCoeff();
      EXPECT_LE(e0, kTolInitial * kEps) << label;
      initial.update(e0, 1.0, label);

      for (int i = 0; i < 5; ++i) {
        const double t = u(rng);
        const FrameKinematics k = f.at(t);
        EXPECT_EQ(k.r, f.origin) << label;
        EXPECT_EQ(k.r_dot, Vec3::Zero()) << label;
        EXPECT_EQ(k.r_ddot, Vec3::Zero()) << label;
        const double eo = (k.a.transpose() * k.a - Mat3::Identity()).cwiseAbs().maxCoeff();
        EXPECT_LE(eo, kTolOrtho * kEps) << label;
        EXPECT_GT(k.a.determinant(), 0.0) << label;
        ortho.update(eo, 1.0, label);
        const Mat3 rel = k.a * f.initial_rotation.transpose();
        const double ea = (rel * n - n).cwiseAbs().maxCoeff();
        EXPECT_LE(ea, kTolAxis * kEps) << label;
        axis_w.update(ea, 1.0, label);
        // Right-handed rotation by θ(t) about n.
        const double th = law.at(t).angle;
        const Vec3 sin_n(0.5 * (rel(2, 1) - rel(1, 2)), 0.5 * (rel(0, 2) - rel(2, 0)),
                         0.5 * (rel(1, 0) - rel(0, 1)));
        const double eth = std::max((sin_n - std::sin(th) * n).cwiseAbs().maxCoeff(),
                                    std::abs(0.5 * (rel.trace() - 1.0) - std::cos(th)));
        EXPECT_LE(eth, kTolAngle * kEps) << label;
        angle_w.update(eth, 1.0, label);
      }
    }
  std::printf("driven frame A(t) = R(n, theta(t)) A0 (300 seeded frames x 5 times):\n");
  report("max |A'A - 1|", ortho, kTolOrtho);
  report("max |A A0' n - n|", axis_w, kTolAxis);
  report("max |A(0) - Rodrigues(n, theta0) A0|", initial, kTolInitial);
  report("rotation angle of A A0' vs theta(t)", angle_w, kTolAngle);
}

TEST(DrivenFrame, DerivativesMatchFiniteDifferences) {
  std::mt19937 rng(1010);
  std::uniform_real_distribution<double> u(0.0, 4.0);
  for (const auto& [name, law] : frame_laws()) {
    fdcheck::Result worst_a, worst_ad;
    for (int trial = 0; trial < 50; ++trial) {
      DrivenFrame f;
      f.origin = random_vec3(rng, 1.0);
      f.initial_rotation = random_rotation(rng);
      f.axis = random_vec3(rng, 1.0);
      f.law = law;
      const double t = u(rng);
      const auto a_of = [&](const fdcheck::Vec& x) {
        const Mat3 a = f.at(x[0]).a;
        return fdcheck::Vec(Eigen::Map<const fdcheck::Vec>(a.data(), 9));
      };
      const auto a_dot_of = [&](const fdcheck::Vec& x) {
        const Mat3 a = f.at(x[0]).a_dot;
        return fdcheck::Vec(Eigen::Map<const fdcheck::Vec>(a.data(), 9));
      };
      const FrameKinematics k = f.at(t);
      const fdcheck::Vec x = fdcheck::Vec::Constant(1, t);
      const fdcheck::Result ra = fdcheck::check_jacobian(
          a_of, x, fdcheck::Mat(Eigen::Map<const fdcheck::Vec>(k.a_dot.data(), 9)));
      const fdcheck::Result rad = fdcheck::check_jacobian(
          a_dot_of, x, fdcheck::Mat(Eigen::Map<const fdcheck::Vec>(k.a_ddot.data(), 9)));
      EXPECT_TRUE(ra.ok()) << name << " trial " << trial << " t = " << t
                           << " A_dot: " << describe(ra);
      EXPECT_TRUE(rad.ok()) << name << " trial " << trial << " t = " << t
                            << " A_ddot: " << describe(rad);
      worst_a.merge(ra);
      worst_ad.merge(rad);
    }
    report_fd(("driven frame A_dot:  " + name).c_str(), worst_a);
    report_fd(("driven frame A_ddot: " + name).c_str(), worst_ad);
  }
}

TEST(DrivenFrame, FixedFrameIsStatic) {
  std::mt19937 rng(1111);
  DrivenFrame f;
  f.origin = random_vec3(rng, 1.0);
  f.initial_rotation = random_rotation(rng);
  f.axis = random_vec3(rng, 1.0);
  for (double t : {0.0, 1.0, 123.4}) {
    const FrameKinematics k = f.at(t);
    EXPECT_EQ(k.r, f.origin);
    // R(n, 0) = 1 exactly (cos 0 = 1, sin 0 = 0), so A = A₀ up to the product 1·A₀ (exact).
    EXPECT_LE((k.a - f.initial_rotation).cwiseAbs().maxCoeff(), 2 * kEps);
    EXPECT_EQ(k.a_dot, Mat3::Zero());
    EXPECT_EQ(k.a_ddot, Mat3::Zero());
  }
  const DrivenFrame ground;  // defaults: identity at the origin
  EXPECT_EQ(ground.at(5.0).a, Mat3::Identity());
}

}  // namespace
