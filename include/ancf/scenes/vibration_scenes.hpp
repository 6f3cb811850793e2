// Straight uniform cables with closed-form small-amplitude frequencies (REFERENCES §4): fixed–free
// axial bar, taut string pinned at both ends, clamped–free Euler–Bernoulli beam. Shared by the
// vibration tests and the mesh-convergence study.
#pragma once

#include <vector>

#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/model.hpp"

namespace ancf {

/// A straight cable along +x from the origin; its reference is stress-free and straight.
struct UniformCableSpec {
  double length = 1.0;             ///< L (unstretched) [m]
  double axial_stiffness = 1e4;    ///< EA [N]
  double bending_stiffness = 0.0;  ///< EI [N m²]
  double mass_per_length = 0.1;    ///< ρA [kg/m] (per unstretched length)
  Index elements = 8;
  StrainMeasure strain = StrainMeasure::green_lagrange;
};

/// Pinned (position) at x = 0, free at x = L. `velocities`: optional initial nodal velocities.
[[nodiscard]] Model fixed_free_bar_model(const UniformCableSpec& spec,
                                         const std::vector<NodeCoordinates>* velocities = nullptr);

/// Stretched uniformly by `stretch` λ (nodes at λx, slopes λx̂) and pinned at 0 and λL.
[[nodiscard]] Model taut_string_model(const UniformCableSpec& spec, double stretch,
                                      const std::vector<NodeCoordinates>* velocities = nullptr);

/// Clamped at x = 0 (pin and slope along +x), free at x = L.
[[nodiscard]] Model clamped_free_beam_model(const UniformCableSpec& spec);

/// Fixed–free bar: ω_n = (2n − 1)π c / (2L), c = √(EA/ρA), n ≥ 1.
[[nodiscard]] double fixed_free_bar_frequency(const UniformCableSpec& spec, int n);

/// Axial force T of the uniformly stretched cable: dU/dλ of U = ½EA ε(λ)² per unstretched length,
/// i.e. EA ε λ for Green (ε = (λ² − 1)/2) and EA (λ − 1) for the elastic line.
[[nodiscard]] double taut_string_tension(const UniformCableSpec& spec, double stretch);

/// Taut string (EI = 0): ω_n = (nπ/L)√(T/(λρA)), n ≥ 1. The transverse equation per unstretched
/// length is ρA ẅ = (T/λ) w'' (the transverse force component is T w'/λ).
[[nodiscard]] double taut_string_frequency(const UniformCableSpec& spec, double stretch, int n);

/// n-th root β_n L of 1 + cos(βL) cosh(βL) = 0 (Newton from (2n − 1)π/2; 1.8751040687, …).
[[nodiscard]] double cantilever_beta_l(int n);

/// Clamped–free Euler–Bernoulli beam: ω_n = (β_n L)² √(EI/(ρA L⁴)).
[[nodiscard]] double clamped_free_beam_frequency(const UniformCableSpec& spec, int n);

}  // namespace ancf
