// Linearised eigen-analysis (system/modal_analysis.hpp) against the analytic frequencies of
// REFERENCES §4: clamped–free Euler–Bernoulli beam (first bending mode), fixed–free bar (first
// axial mode), taut string; the βL roots; rejection of a coupled component. Smoke-sized (≤ 16
// elements, dense eigen-solves of ≤ 100 unknowns).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include "ancf/scenes/vibration_scenes.hpp"
#include "ancf/system/modal_analysis.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf {
namespace {

// The Newton roots of 1 + cos βL cosh βL = 0 against the 11 digits of REFERENCES §4.
TEST(CantileverRoots, MatchReferenceDigits) {
  const double expected[] = {1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349};
  for (int n = 1; n <= 4; ++n) EXPECT_NEAR(cantilever_beta_l(n), expected[n - 1], 1e-10) << n;
}

// Cubic Hermite eigenvalues converge as h⁴ for bending and h⁶ for the axial bar (Strang & Fix
// 1973, §6.3): 8 elements put ω₁ within 1e-5 (bending; measured 2.1e-6) and 1e-8 (axial;
// measured 8.2e-10); halving h from 4 to 8 elements must reduce the error by ≥ 2³ (bending,
// measured 15.7) and ≥ 2⁵ (axial, measured 54), i.e. no slower than one order below the theory.
TEST(ModalAnalysis, ClampedBeamFirstBendingMode) {
  double previous = 0.0;
  for (const Index n : {4, 8}) {
    const UniformCableSpec spec{.length = 1.0,
                                .axial_stiffness = 1e4,
                                .bending_stiffness = 1.0,
                                .mass_per_length = 1.0,
                                .elements = n};
    const NaturalModes m =
        natural_modes_at_initial_equilibrium(clamped_free_beam_model(spec), {.component = 1});
    const double exact = clamped_free_beam_frequency(spec, 1);
    const double error = std::abs(m.omega(0) / exact - 1.0);
    std::printf("beam %ld elements: omega_1 %.12f (exact %.12f), rel. error %.2e\n",
                static_cast<long>(n), m.omega(0), exact, error);
    // y-component: 2(N + 1) coordinates, 2 clamped (position and slope at the root).
    EXPECT_EQ(m.selected_coordinates, 2 * (n + 1));
    EXPECT_EQ(m.constraint_rank, 2);
    EXPECT_EQ(m.omega_squared.size(), 2 * n);
    EXPECT_LT(m.asymmetry, 1e-12);
    EXPECT_GT(m.omega(0), exact);  // Rayleigh–Ritz with consistent mass: an upper bound
    if (n == 8) {
      EXPECT_LT(error, 1e-5);
      EXPECT_LT(error, previous / 8.0);
    }
    previous = error;
  }
}

TEST(ModalAnalysis, FixedFreeBarFirstAxialMode) {
  double previous = 0.0;
  for (const Index n : {4, 8}) {
    const UniformCableSpec spec{
        .length = 1.0, .axial_stiffness = 1e4, .mass_per_length = 0.1, .elements = n};
    const NaturalModes m =
        natural_modes_at_initial_equilibrium(fixed_free_bar_model(spec), {.component = 0});
    const double exact = fixed_free_bar_frequency(spec, 1);
    const double error = std::abs(m.omega(0) / exact - 1.0);
    std::printf("bar %ld elements: omega_1 %.12f (exact %.12f), rel. error %.2e\n",
                static_cast<long>(n), m.omega(0), exact, error);
    EXPECT_EQ(m.constraint_rank, 1);
    EXPECT_GT(m.omega(0), exact * (1.0 - 1e-14));
    if (n == 8) {
      EXPECT_LT(error, 1e-8);
      EXPECT_LT(error, previous / 32.0);
    }
    previous = error;
    // The shapes live on the x components only.
    for (Index i = 0; i < m.shapes.rows(); ++i)
      if (i % 3 != 0) {
        EXPECT_EQ(m.shapes.row(i).cwiseAbs().maxCoeff(), 0.0) << "row " << i;
      }
  }
}

// Prestressed string: the geometric stiffness of the tension alone gives the transverse modes;
// 16 elements: modes 1–3 within 1e-6 (measured 9.3e-10, 5.7e-8, 6.1e-7; h⁶ convergence).
TEST(ModalAnalysis, TautStringFirstModes) {
  const double stretch = 1.01;
  const UniformCableSpec spec{
      .length = 1.0, .axial_stiffness = 1e4, .mass_per_length = 0.1, .elements = 16};
  const NaturalModes m =
      natural_modes_at_initial_equilibrium(taut_string_model(spec, stretch), {.component = 1});
  for (int k = 1; k <= 3; ++k) {
    const double exact = taut_string_frequency(spec, stretch, k);
    EXPECT_NEAR(m.omega(k - 1) / exact, 1.0, 1e-6) << "mode " << k;
  }
}

// Free–free beam (no constraints at all) restricted to one component: the constraint Jacobian
// is empty (this crashed: maxCoeff of an empty matrix, issue 17 item 4). The y component has two
// rigid modes (translation, rotation about z) at ω² ≈ 0 and then the free–free bending modes,
// β_n L = 4.730040744862704, 7.853204624095838 (REFERENCES §4). Cubic Hermite bending
// eigenvalues converge as h⁴ (as for the clamped beam above): 16 elements put modes 1 and 2
// within 1e-5 and 1e-4 (measured 5.2e-6 and 3.9e-5), and halving h from 8 to 16 elements must
// reduce the mode-1 error by ≥ 2³.
TEST(ModalAnalysis, FreeFreeBeamWithoutConstraints) {
  const double beta_l[] = {4.730040744862704, 7.853204624095838};
  double previous = 0.0;
  for (const Index n : {8, 16}) {
    ModelBuilder b;
    CableSection s;
    s.axial_stiffness = 1e4;
    s.bending_stiffness = 1.0;
    s.mass_per_length = 1.0;
    (void)b.add_cable("beam", straight_cable(Vec3::Zero(), Vec3::UnitX(), n), s);
    const Model model = b.finalize();
    ASSERT_EQ(model.multiplier_count(), 0);
    const NaturalModes m = natural_modes_at_initial_equilibrium(model, {.component = 1});
    EXPECT_EQ(m.constraint_rank, 0);
    ASSERT_EQ(m.omega_squared.size(), 2 * (n + 1));
    const double scale = m.omega_squared[2];
    EXPECT_LT(std::abs(m.omega_squared[0]), 1e-9 * scale);
    EXPECT_LT(std::abs(m.omega_squared[1]), 1e-9 * scale);
    double error[2];
    for (int k = 0; k < 2; ++k) {
      const double exact = beta_l[k] * beta_l[k];  // √(EI/(ρA L⁴)) = 1
      error[k] = std::abs(m.omega(k + 2) / exact - 1.0);
      std::printf("free-free beam %ld elements: omega_%d %.12f (exact %.12f), rel. error %.2e\n",
                  static_cast<long>(n), k + 1, m.omega(k + 2), exact, error[k]);
    }
    if (n == 16) {
      EXPECT_LT(error[0], 1e-5);
      EXPECT_LT(error[1], 1e-4);
      EXPECT_LT(error[0], previous / 8.0);
    }
    previous = error[0];
  }
}

// A 4-element cable from the origin to `end`, pinned at the origin.
Model pinned_cable(const std::string& name, const Vec3& end) {
  ModelBuilder b;
  CableSection s;
  s.axial_stiffness = 1e4;
  s.bending_stiffness = 1.0;
  s.mass_per_length = 1.0;
  const Index c = b.add_cable(name, straight_cable(Vec3::Zero(), end, 4), s);
  b.pin("root", {c, 0}, Vec3::Zero());
  return b.finalize();
}

// A cable along a skew direction (x = y) couples x and y in K and M: restricting to one component
// must be refused, not give wrong frequencies.
TEST(ModalAnalysis, RefusesCoupledComponent) {
  const Model model = pinned_cable("skew", Vec3(1.0, 1.0, 0.0));
  EXPECT_THROW((void)natural_modes(model, SystemState::initial(model), {.component = 0}),
               std::invalid_argument);
  // All components together are fine: 6·5 − 3 unknowns; the two rigid rotations about the pin
  // that move the cable (not the one about its own axis, which changes no coordinate) have
  // ω² = 0 to round-off.
  const NaturalModes all = natural_modes(model, SystemState::initial(model));
  ASSERT_EQ(all.omega_squared.size(), 6 * 5 - 3);
  EXPECT_LT(std::abs(all.omega_squared[0]), 1e-8 * all.omega_squared[2]);
  EXPECT_LT(std::abs(all.omega_squared[1]), 1e-8 * all.omega_squared[2]);
  EXPECT_GT(all.omega_squared[2], 1e-3);
}

// A state at which the model cannot be evaluated gives non-finite matrices: refused as a
// domain_error that names the coordinate, not passed to the eigen-solver (whose failure says
// nothing, and which `ancf modes` once let abort the process).
TEST(ModalAnalysis, RefusesStateWithNonFiniteMatrices) {
  const Model model = pinned_cable("rope", Vec3(1.0, 0.0, 0.0));
  SystemState state = SystemState::initial(model);
  state.q[model.cables()[0].first_coordinate + 6 * 2 + 3] = std::numeric_limits<double>::infinity();
  try {
    (void)natural_modes(model, state);
    FAIL() << "expected std::domain_error";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("not finite in row cable 'rope' node"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace ancf
