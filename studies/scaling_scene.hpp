// Scene of the scaling study (studies/README.md, "Cost per step against problem size"): K taut
// strings of N elements each whose every element sees the same physics whatever N and K are, so
// that a change of the cost per element per step can only come from the code, not from the
// problem getting harder.
//
// Construction. Each string is straight along +x with the fixed element length of the benchmark
// cable (REFERENCES §10: l = 1 m / 20, E = 1e9 Pa, d = 0.01 m, ρ = 8000 kg/m³, Green strain +
// Gerstmayr–Shabana bending), so more elements make a longer string. Both end nodes are pinned
// (positions only) and the string carries a prestrain ε_p = 1e-3, i.e. a tension T = EA ε_p, so its
// straight reference is an equilibrium without gravity (gravity would make the sag grow with L²).
// It starts straight with the transverse standing-wave velocity
//   v_z(s) = V sin(2π s / λ),   ṙ_x = dv/ds = V (2π/λ) cos(2π s / λ) ẑ,
// with the wavelength λ fixed in elements (20 elements = 1 m), so every element sees the same
// local motion: a transverse wave of speed c = √(T/ρA) ≈ 11 m/s (period λ/c ≈ 0.09 s) and the
// same axial strain field. N must be a multiple of λ/2 = 10 elements so that v vanishes at the
// pinned far end (consistent initial velocities). The K strings are 1 m apart along y and never
// touch (no contact pairs), so K strings are K independent copies of one.
#pragma once

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "ancf/scenes/pendulums.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf::studies {

inline constexpr Index kWaveElements = 20;    ///< λ in elements
inline constexpr double kPrestrain = 1e-3;    ///< ε_p [-]
inline constexpr double kWaveVelocity = 0.5;  ///< V [m/s]: amplitude V λ/(2π c) ≈ 7 mm

/// The benchmark cable's section (pendulums.hpp) with the prestrain of the taut strings.
inline CableSection taut_string_section() {
  const CablePendulumSpec spec = benchmark_cable_pendulum();
  CableSection s;
  s.axial_stiffness = spec.axial_stiffness;
  s.bending_stiffness = spec.bending_stiffness;
  s.mass_per_length = spec.mass_per_length;
  s.prestrain = kPrestrain;
  return s;
}

/// Element length of the benchmark cable [m].
inline double taut_string_element_length() {
  return benchmark_cable_pendulum().length / 20.0;
}

/// `cables` strings of `elements` elements each (elements a positive multiple of λ/2).
inline Model taut_strings_model(Index elements, Index cables) {
  if (elements <= 0 || elements % (kWaveElements / 2) != 0 || cables <= 0)
    throw std::invalid_argument("taut_strings_model: elements must be a positive multiple of 10");
  const double l = taut_string_element_length();
  const double length = static_cast<double>(elements) * l;
  const double k = 2.0 * std::numbers::pi / (static_cast<double>(kWaveElements) * l);
  const CableSection section = taut_string_section();
  ModelBuilder b;
  for (Index c = 0; c < cables; ++c) {
    const Vec3 start(0.0, static_cast<double>(c), 0.0);
    const CableGeometry g = straight_cable(start, start + length * Vec3::UnitX(), elements);
    const std::string name = "string " + std::to_string(c);
    const Index cable = b.add_cable(name, g, section);
    std::vector<NodeCoordinates> v(g.nodes.size());
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
      const double s = static_cast<double>(n) * l;
      v[n] << 0.0, 0.0, kWaveVelocity * std::sin(k * s), 0.0, 0.0,
          kWaveVelocity * k * std::cos(k * s);
    }
    // sin(k L) is round-off, not zero, at the far end: make it exactly consistent with the pin.
    v.back()[2] = 0.0;
    b.set_initial_configuration(cable, g, &v);
    b.pin(name + " start", {cable, 0}, start);
    b.pin(name + " end", {cable, -1}, start + length * Vec3::UnitX());
  }
  return b.finalize();
}

}  // namespace ancf::studies
