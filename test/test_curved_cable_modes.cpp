// Zero-stiffness modes of a pinned–pinned cable with a curved stress-free reference (the capture
// ropes of CAPTURE.md). The gradient-deficient cable's bending energy ½EI(|κ| − κ₀)² sees only the
// magnitude of the curvature: at the reference (|κ| = κ₀) its Hessian is EI ∇κ ∇κᵀ, one rank per
// Gauss point, so bending a curved cable out of its osculating plane (changing the geometric
// torsion) costs nothing to first order. With the ends pinned and the slopes free nothing else
// restrains those motions: the linearised rope has a zero-frequency subspace whose dimension grows
// with the mesh (N − 1 for N elements; 2N − 1 for the pure cable, EI = 0, which is slack at the
// reference). A straight reference (κ₀ = 0, energy ½EI|κ|², full rank transversally) has none.
// The Kelvin–Voigt damping (c_a ε̇, c_b κ̇ with κ = |κ|) has the same null space, so nothing damps
// those motions either.
//
// This is why the slack phase of the capture example (docs/capture.md) — the ropes' first contacts
// with the pole — is not mesh-converged: those contacts are reached through motions that no
// stiffness determines, only inertia, damping and the discretisation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "ancf/system/assembly.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/modal_analysis.hpp"
#include "ancf/system/model_builder.hpp"
#include "dense_matrix.hpp"

namespace ancf {
namespace {

// CAPTURE.md rope: helix on R = 0.10 m over ψ₀ = 2.2256 rad rising h = 0.15 m, EA = 3.1416e5 N,
// ρA = 0.0245 kg/m, both end positions pinned.
Model pinned_rope(Index elements, double bending_stiffness, bool straight, bool damped = false) {
  const double radius = 0.10, twist = 2.2256, rise = 0.15;
  const CableGeometry g =
      straight
          ? straight_cable(Vec3::Zero(), Vec3(std::hypot(rise, radius * twist), 0.0, 0.0), elements)
          : helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), radius, 0.5 * M_PI, twist, rise,
                        elements);
  CableSection section;
  section.axial_stiffness = 3.1416e5;
  section.bending_stiffness = bending_stiffness;
  section.mass_per_length = 0.0245;
  if (damped) {  // the damped variant of docs/capture.md
    section.axial_damping = 0.5;
    section.bending_damping = 2e-5;
  }
  ModelBuilder builder;
  const Index cable = builder.add_cable("rope", g, section);
  builder.pin("anchor_a", {cable, 0}, Vec3(g.nodes.front().head<3>()));
  builder.pin("anchor_b", {cable, elements}, Vec3(g.nodes.back().head<3>()));
  return builder.finalize();
}

struct ModeCount {
  Index zero = 0;
  double smallest_nonzero = 0.0;  ///< ω [rad/s]
  /// Largest |φᵀCφ| over the zero modes and over all modes (M-orthonormal φ: the modal damping
  /// coefficient 2ζω [1/s]), C = ∂F/∂v at rest.
  double zero_mode_damping = 0.0, largest_damping = 0.0;
};

MatX damping_matrix(const Model& model) {
  VecX values(model.pattern().nonzeros());
  assemble_iteration_matrix(model, SystemState::initial(model), {.w_q = 0.0, .w_v = 1.0},
                            as_span(values));
  const Index n = model.coordinate_count();  // the coordinate block; constraint rows follow
  return testing::dense(model.pattern(), values).topLeftCorner(n, n);
}

// An eigenvalue is zero when |ω²| is at the round-off level of the eigen-solve,
// 1e3·ε·max ω² (the zero modes come out at ≈ ε·max ω²; the smallest non-zero one of these ropes
// is ≥ 1e-10·max ω²).
ModeCount count_zero_modes(const Model& model) {
  const NaturalModes modes = natural_modes_at_initial_equilibrium(model);
  const double largest = modes.omega_squared.maxCoeff();
  const double zero_level = 1e3 * std::numeric_limits<double>::epsilon() * largest;
  const MatX damping = damping_matrix(model);
  ModeCount c;
  for (Index i = 0; i < modes.omega_squared.size(); ++i) {
    const VecX phi = modes.shapes.col(i);
    const double modal_damping = std::abs(phi.dot(damping * phi));
    c.largest_damping = std::max(c.largest_damping, modal_damping);
    if (std::abs(modes.omega_squared[i]) <= zero_level) {
      ++c.zero;
      c.zero_mode_damping = std::max(c.zero_mode_damping, modal_damping);
    } else if (c.smallest_nonzero == 0.0) {
      c.smallest_nonzero = modes.omega(i);
    }
  }
  return c;
}

TEST(CurvedCableModes, HelicalRopeHasOneZeroModePerElementBeyondTheFirst) {
  for (const Index n : {6, 12}) {
    const ModeCount c = count_zero_modes(pinned_rope(n, 1e-3, false));
    std::printf("helix, EI = 1e-3, %ld elements: %ld zero modes, next omega %.3g rad/s\n",
                static_cast<long>(n), static_cast<long>(c.zero), c.smallest_nonzero);
    EXPECT_EQ(c.zero, n - 1);
    EXPECT_GT(c.smallest_nonzero, 1.0);  // a clear gap: the next mode is a real bending mode
  }
}

// With c_a = 0.5 N s and c_b = 2e-5 N m² s the zero modes stay undamped to round-off (1e3·ε of
// the largest modal damping coefficient), while the first bending mode has 2ζω ≈ 9 1/s.
TEST(CurvedCableModes, KelvinVoigtDampingLeavesTheZeroModesUndamped) {
  for (const Index n : {6, 12}) {
    const ModeCount c = count_zero_modes(pinned_rope(n, 1e-3, false, true));
    std::printf(
        "helix, EI = 1e-3, damped, %ld elements: %ld zero modes, max 2 zeta omega %.2e 1/s "
        "(largest over all modes %.2e)\n",
        static_cast<long>(n), static_cast<long>(c.zero), c.zero_mode_damping, c.largest_damping);
    EXPECT_EQ(c.zero, n - 1);
    EXPECT_LE(c.zero_mode_damping,
              1e3 * std::numeric_limits<double>::epsilon() * c.largest_damping);
  }
}

TEST(CurvedCableModes, PureHelicalCableHasTwoZeroModesPerElement) {
  for (const Index n : {6, 12}) {
    const ModeCount c = count_zero_modes(pinned_rope(n, 0.0, false));
    std::printf("helix, EI = 0, %ld elements: %ld zero modes, next omega %.3g rad/s\n",
                static_cast<long>(n), static_cast<long>(c.zero), c.smallest_nonzero);
    EXPECT_EQ(c.zero, 2 * n - 1);
  }
}

TEST(CurvedCableModes, StraightReferenceHasNone) {
  for (const Index n : {6, 12}) {
    const ModeCount c = count_zero_modes(pinned_rope(n, 1e-3, true));
    std::printf("straight, EI = 1e-3, %ld elements: %ld zero modes, lowest omega %.3g rad/s\n",
                static_cast<long>(n), static_cast<long>(c.zero), c.smallest_nonzero);
    EXPECT_EQ(c.zero, 0);
  }
}

}  // namespace
}  // namespace ancf
