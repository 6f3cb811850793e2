// Scenes of the numerical stability stress study (studies/README.md, "stability_stress"), each
// with the energy scale its relative energy error is measured against.
#pragma once

#include "ancf/system/model.hpp"

namespace ancf::studies {

struct StressScene {
  Model model;
  double energy_scale = 1.0;  ///< [J] denominator of the relative energy error (E − E₀)/scale
};

/// REFERENCES §7: Gerstmayr–Shabana pendulum with stiffness-ratio parameter f (EA L²/EI =
/// 4π·1e6/f²). Scale: potential energy ρA g L²/2 of the swing plus the initial kinetic energy of
/// the 4 rad/s rigid rotation, ρA ω² L³/6.
[[nodiscard]] StressScene gerstmayr_shabana_scene(double f, Index elements);

/// REFERENCES §10 benchmark pendulum (L = 1 m, E = 1e9 Pa, d = 1 cm), released at rest along +x.
/// Scale ρA g L²/2.
[[nodiscard]] StressScene benchmark_pendulum_scene(Index elements);

/// Steel wire pendulum: L = 0.1 m, E = 2.1e11 Pa, d = 1 mm, ρ = 7850 kg/m³ (EA = 1.65e5 N,
/// EI = 1.03e-2 N m², EA L²/EI = 1.6e5), Green strain with Gerstmayr–Shabana bending, pinned at
/// the origin, released at rest along +x under gravity −9.81 ẑ; element length L/elements.
/// Scale ρA g L²/2.
[[nodiscard]] StressScene steel_wire_scene(Index elements);

/// Slack-to-taut snap: the benchmark cable (L = 1 m, EA = 7.85e4 N, EI = 0.49 N m²) pinned at the
/// origin, its stress-free reference straight, started at rest bent into a semicircle that hangs
/// below the pivot (end-to-end distance 2L/π), with a rigid sphere of mass `tip_mass` (radius
/// 5 cm) attached at the free end, which starts level with the pivot. The sphere falls freely
/// (the bent cable carries no axial force) through ≈ L(1 − 2/π) and then jerks the cable taut:
/// an axial wave and a force jump from ≈ 0 to ≫ m g. Scale m g L + ρA g L²/2.
[[nodiscard]] StressScene slack_snap_scene(double tip_mass, Index elements);

}  // namespace ancf::studies
