// Dynamic reference scenes shared by integrator tests, benchmarks and studies
// (REFERENCES §5, §7, §10).
#pragma once

#include "ancf/system/model.hpp"

namespace ancf {

/// Cable pendulum pinned (position only) at the origin, initially straight along +x, gravity
/// along `gravity`. With initial_spin ≠ 0 the initial velocity is a rigid rotation about +y
/// (v_z = −ω x), as in Gerstmayr & Shabana (2006).
struct CablePendulumSpec {
  double length = 1.0;               ///< L [m]
  double axial_stiffness = 0.0;      ///< EA [N]
  double bending_stiffness = 0.0;    ///< EI [N m²]
  double mass_per_length = 0.0;      ///< ρA [kg/m]
  double axial_damping = 0.0;        ///< c_a [N s]
  double bending_damping = 0.0;      ///< c_b [N m² s]
  StrainMeasure strain = StrainMeasure::green_lagrange;
  Index elements = 20;
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);
  double initial_spin = 0.0;         ///< ω about +y [rad/s]
};

/// REFERENCES §10: L = 1 m, E = 1e9 Pa, d = 0.01 m, ρ = 8000 kg/m³, Green + Gerstmayr–Shabana
/// bending, no damping, gravity −9.81 ẑ, at rest. The benchmark scene for speed comparisons.
[[nodiscard]] CablePendulumSpec benchmark_cable_pendulum(Index elements = 20);

/// REFERENCES §7: Gerstmayr & Shabana (2006) flexible pendulum with stiffness-ratio parameter f:
/// A = 1e-6 f² m², E = 1e9/f⁴ Pa, ρ = 8000/f² kg/m³, circular section; gravity −9.81 ŷ;
/// initial rigid rotation 4 rad/s about +y.
[[nodiscard]] CablePendulumSpec gerstmayr_shabana_pendulum(double f, Index elements = 20);

[[nodiscard]] Model cable_pendulum_model(const CablePendulumSpec& spec);

/// Rigid pendulum in natural coordinates: a uniform slender rod of length L and mass m hinged
/// (revolute joint about +y) at one end at the origin, released at rest at angle θ₀ from the
/// downward vertical (gravity −g ẑ). Period T = 4 √(I_O/(m g L/2)) K(sin(θ₀/2)).
struct RigidPendulumSpec {
  double length = 1.0;
  double mass = 1.0;
  double gravity = 9.81;
  double initial_angle = 1.0;  ///< θ₀ [rad]
};

[[nodiscard]] Model rigid_pendulum_model(const RigidPendulumSpec& spec);
/// Exact period of the rod pendulum via the arithmetic–geometric mean.
[[nodiscard]] double rigid_pendulum_period(const RigidPendulumSpec& spec);

}  // namespace ancf
