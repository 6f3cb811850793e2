// Reference tip displacements of the clamped cantilever under a transverse dead tip load
// (REFERENCES §1–§2), shared by test_statics_reference and the mesh-convergence study.
#pragma once

#include <array>

#include "ancf/scenes/cantilever.hpp"

namespace ancf {

/// Mattiasson (1981), inextensible elastica: tip of a cantilever of length L with k = P L²/EI.
struct MattiassonTip {
  double k;         ///< load parameter P L² / EI
  double u;         ///< (L − x_tip) / L
  double w;         ///< transverse tip deflection / L
  double rotation;  ///< tip rotation [rad]
};

/// The rows of Mattiasson's table (REFERENCES §1, 8 digits).
inline constexpr std::array<MattiassonTip, 6> kMattiassonTable{{
    {1, 0.05643324, 0.30172077, 0.46135195},
    {2, 0.16064172, 0.49345748, 0.78174983},
    {3, 0.25442018, 0.60325344, 0.98601695},
    {4, 0.32894124, 0.66996418, 1.12123935},
    {5, 0.38762836, 0.71379152, 1.21536812},
    {10, 0.55499560, 0.81060902, 1.43028554},
}};

/// Cantilever of the Mattiasson case `tip` with L = 1 m, EI = 1 N m², EA = `axial_stiffness`
/// (EA L²/EI ≥ 1e7 keeps the extensibility error, O(P/EA), below 1e-6 for k ≤ 10).
[[nodiscard]] inline CantileverSpec mattiasson_cantilever(const MattiassonTip& tip, Index elements,
                                                          double axial_stiffness = 1e7) {
  CantileverSpec spec;
  spec.length = 1.0;
  spec.bending_stiffness = 1.0;
  spec.axial_stiffness = axial_stiffness;
  spec.tip_load = tip.k;
  spec.elements = elements;
  return spec;
}

/// Extensible elastica of REFERENCES §2: L = 2 m, EA = 2.07e9 N, EI = 1.725e6 N m²,
/// P = 3 EI/L². It is the continuum limit of the Green–Lagrange / Gerstmayr–Shabana cable only.
[[nodiscard]] inline CantileverSpec extensible_elastica_cantilever(Index elements) {
  CantileverSpec spec;
  spec.length = 2.0;
  spec.axial_stiffness = 2.07e9;
  spec.bending_stiffness = 1.725e6;
  spec.tip_load = 3.0 * spec.bending_stiffness / (spec.length * spec.length);
  spec.elements = elements;
  spec.strain = StrainMeasure::green_lagrange;
  return spec;
}

/// Tip displacement (x, y) [m] of extensible_elastica_cantilever (shooting method, 12 digits).
inline constexpr double kElasticaTipDx = -0.508922870415;
inline constexpr double kElasticaTipDy = -1.208398131108;

}  // namespace ancf
