// Transversely isotropic material (paper S2–S4, DESIGN §3): under uniaxial stress the law reduces
// to σ₁ = E₁ε₁ with ε₂ = ε₃ = −ν₂₁ε₁, which is why the cable uses EA = E₁A.
//
// Algebra behind the second test: with ε₂ = ε₃ the transverse stresses are equal by symmetry
// (σ₂ = σ₃ = s), and solving ε = Sσ for σ₁ gives
//   σ₁ = [E₁²(1 − ν₃₂) ε₁ + 2E₁E₂ν₂₁ ε₂] / [E₁(1 − ν₃₂) − 2E₂ν₂₁²],
// which is (S4) with numerator and denominator negated. So (S4) is the first row of C = S⁻¹ for
// ANY (ε₁, ε₂ = ε₃), not only under uniaxial stress; both are asserted.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "ancf/core/error.hpp"
#include "ancf/physics/transversely_isotropic_material.hpp"

namespace {
using ancf::Mat3;
using ancf::ModelError;
using ancf::TransverselyIsotropicMaterial;
using ancf::Vec3;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// Positive definiteness of S (see validate()): |ν₃₂| < 1 and ρ = 2ν₂₁²E₂ / (E₁(1 − ν₃₂)) < 1.
double nu21_limit(double e1, double e2, double nu32) {
  return std::sqrt((1.0 - nu32) * e1 / (2.0 * e2));
}

// Random valid set: E₁ in 1e9…3e11 Pa, E₂/E₁ in 0.01…3 (never 1), ν₃₂ in (−0.5, 0.8),
// |ν₂₁| up to 0.9 of its limit (so ρ ≤ 0.81).
TransverselyIsotropicMaterial random_material(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  TransverselyIsotropicMaterial m;
  m.e1 = std::pow(10.0, 9.0 + 2.5 * u(rng));
  m.e2 = m.e1 * std::pow(10.0, -2.0 + 2.5 * u(rng));
  m.nu32 = -0.5 + 1.3 * u(rng);
  m.nu21 = 0.9 * (2.0 * u(rng) - 1.0) * nu21_limit(m.e1, m.e2, m.nu32);
  m.density = 1000.0 + 7000.0 * u(rng);
  return m;
}

// Round-off scales: (S4)'s numerator and denominator cancel by up to 1/(1 − ρ); inverting S loses
// up to cond(S).
double cancellation(const TransverselyIsotropicMaterial& m) {
  return 1.0 / (1.0 - 2.0 * m.nu21 * m.nu21 * m.e2 / (m.e1 * (1.0 - m.nu32)));
}
double condition(const Mat3& s) {
  const Vec3 ev = Eigen::SelfAdjointEigenSolver<Mat3>(s).eigenvalues();
  return ev.cwiseAbs().maxCoeff() / ev.cwiseAbs().minCoeff();
}

TEST(Material, UniaxialStressReducesToE1) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  double worst[4] = {0, 0, 0, 0};  // error/tolerance: ε₂, ε₃, (S4), C·ε
  for (int trial = 0; trial < 50; ++trial) {
    const TransverselyIsotropicMaterial m = random_material(rng);
    ASSERT_NO_THROW(m.validate("random material"));
    ASSERT_NE(m.e1, m.e2);
    const Mat3 s = m.normal_compliance();
    const double sigma1 = m.e1 * u(rng);
    const Vec3 eps = s * Vec3(sigma1, 0.0, 0.0);  // uniaxial stress σ₂ = σ₃ = 0
    const double eps_t = m.uniaxial_transverse_strain(eps[0]);
    const double tol_t = 4.0 * kEps * std::abs(eps_t);
    const double tol_s4 = 16.0 * kEps * cancellation(m) * std::abs(sigma1);
    const double tol_c = 16.0 * kEps * condition(s) * std::abs(sigma1);
    const Vec3 sigma = m.normal_stiffness() * eps;
    const double err[4] = {std::abs(eps[1] - eps_t), std::abs(eps[2] - eps_t),
                           std::abs(m.axial_stress_s4(eps[0], eps[1]) - m.e1 * eps[0]),
                           (sigma - Vec3(m.e1 * eps[0], 0.0, 0.0)).lpNorm<Eigen::Infinity>()};
    const double tol[4] = {tol_t, tol_t, tol_s4, tol_c};
    for (int k = 0; k < 4; ++k) {
      EXPECT_LE(err[k], tol[k]) << "trial " << trial << " check " << k;
      worst[k] = std::max(worst[k], err[k] / tol[k]);
    }
  }
  std::printf("uniaxial: max error/tolerance  eps2 %.2e  eps3 %.2e  S4 %.2e  C*eps %.2e\n",
              worst[0], worst[1], worst[2], worst[3]);
}

TEST(Material, S4IsFirstRowOfStiffnessForEqualTransverseStrains) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(-0.05, 0.05);
  double worst = 0.0;
  for (int trial = 0; trial < 50; ++trial) {
    const TransverselyIsotropicMaterial m = random_material(rng);
    const Mat3 c = m.normal_stiffness();
    const double e1 = u(rng), e2 = u(rng);  // arbitrary, not uniaxial
    const double row = c(0, 0) * e1 + c(0, 1) * e2 + c(0, 2) * e2;
    const double scale = std::abs(c(0, 0) * e1) + std::abs(c(0, 1) * e2) + std::abs(c(0, 2) * e2);
    const double tol = 16.0 * kEps * (condition(m.normal_compliance()) + cancellation(m)) * scale;
    const double err = std::abs(m.axial_stress_s4(e1, e2) - row);
    EXPECT_LE(err, tol) << "trial " << trial;
    worst = std::max(worst, err / tol);
  }
  std::printf("S4 vs first row of C: max error/tolerance %.2e\n", worst);
}

TEST(Material, ValidateRejectsNonPhysicalParameters) {
  const TransverselyIsotropicMaterial good{1e10, 2e9, 0.3, 0.4, 1100.0};
  EXPECT_NO_THROW(good.validate("good"));
  auto with = [&](auto change) {
    TransverselyIsotropicMaterial m = good;
    change(m);
    return m;
  };
  // Non-positive moduli and density.
  EXPECT_THROW(with([](auto& m) { m.e1 = 0.0; }).validate("E1 = 0"), ModelError);
  EXPECT_THROW(with([](auto& m) { m.e1 = -1e10; }).validate("E1 < 0"), ModelError);
  EXPECT_THROW(with([](auto& m) { m.e2 = 0.0; }).validate("E2 = 0"), ModelError);
  EXPECT_THROW(with([](auto& m) { m.e2 = -2e9; }).validate("E2 < 0"), ModelError);
  EXPECT_THROW(with([](auto& m) { m.density = 0.0; }).validate("rho = 0"), ModelError);
  // Indefinite compliance: |ν₃₂| ≥ 1, or ν₂₁ past its limit (checked on both sides of it).
  EXPECT_THROW(with([](auto& m) { m.nu32 = 1.2; }).validate("nu32 > 1"), ModelError);
  EXPECT_THROW(with([](auto& m) { m.nu32 = -1.5; }).validate("nu32 < -1"), ModelError);
  const double limit = nu21_limit(good.e1, good.e2, good.nu32);
  EXPECT_NO_THROW(with([&](auto& m) { m.nu21 = 0.99 * limit; }).validate("nu21 below limit"));
  EXPECT_THROW(with([&](auto& m) { m.nu21 = 1.01 * limit; }).validate("nu21 above limit"),
               ModelError);
  EXPECT_THROW(with([&](auto& m) { m.nu21 = -1.01 * limit; }).validate("-nu21 above limit"),
               ModelError);
  // Isotropic special case: the familiar −1 < ν < ½.
  EXPECT_NO_THROW(
      TransverselyIsotropicMaterial::isotropic(2e11, 0.49, 7800).validate("steel-like"));
  EXPECT_THROW(TransverselyIsotropicMaterial::isotropic(2e11, 0.51, 7800).validate("nu > 1/2"),
               ModelError);
  EXPECT_THROW(TransverselyIsotropicMaterial::isotropic(2e11, -1.01, 7800).validate("nu < -1"),
               ModelError);
}

}  // namespace
