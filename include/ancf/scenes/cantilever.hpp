// The clamped cantilever with a transverse dead tip load: Mattiasson (1981) and the extensible
// elastica (REFERENCES §1–§2). Shared by the demo, the tests and the benchmarks.
#pragma once

#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/model.hpp"

namespace ancf {

struct CantileverSpec {
  double length = 1.0;              ///< L [m], along +x from the origin
  double axial_stiffness = 1e7;     ///< EA [N]
  double bending_stiffness = 1.0;   ///< EI [N m²]
  double tip_load = 1.0;            ///< P [N], applied along −y
  Index elements = 16;
  StrainMeasure strain = StrainMeasure::green_lagrange;
};

/// Cable clamped at x = 0 (pin + slope along +x), load −P ŷ at the tip, ρA = 1 kg/m (unused in statics).
[[nodiscard]] Model cantilever_model(const CantileverSpec& spec);

struct CantileverTip {
  Vec3 displacement;      ///< tip position − (L, 0, 0) [m]
  double rotation = 0.0;  ///< angle of the tip slope from +x [rad]
  StaticSolverStatistics stats;
};

/// Solve the cantilever statically with `load_steps` increments.
[[nodiscard]] CantileverTip solve_cantilever(const CantileverSpec& spec, int load_steps);

}  // namespace ancf
