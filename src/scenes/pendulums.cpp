#include "ancf/scenes/pendulums.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "ancf/system/model_builder.hpp"

namespace ancf {

CablePendulumSpec benchmark_cable_pendulum(Index elements) {
  const CircularSection section = circular_section(0.01);
  CablePendulumSpec s;
  s.length = 1.0;
  s.axial_stiffness = 1e9 * section.area;
  s.bending_stiffness = 1e9 * section.second_moment;
  s.mass_per_length = 8000.0 * section.area;
  s.elements = elements;
  s.gravity = Vec3(0.0, 0.0, -9.81);
  return s;
}

CablePendulumSpec gerstmayr_shabana_pendulum(double f, Index elements) {
  const double area = 1e-6 * f * f, e = 1e9 / std::pow(f, 4), rho = 8000.0 / (f * f);
  const double inertia = area * area / (4.0 * std::numbers::pi);  // πd⁴/64 with A = πd²/4
  CablePendulumSpec s;
  s.length = 1.0;
  s.axial_stiffness = e * area;
  s.bending_stiffness = e * inertia;
  s.mass_per_length = rho * area;
  s.elements = elements;
  s.gravity = Vec3(0.0, -9.81, 0.0);
  s.initial_spin = 4.0;
  return s;
}

Model cable_pendulum_model(const CablePendulumSpec& spec) {
  ModelBuilder b;
  CableSection s;
  s.strain = spec.strain;
  s.axial_stiffness = spec.axial_stiffness;
  s.bending_stiffness = spec.bending_stiffness;
  s.mass_per_length = spec.mass_per_length;
  s.axial_damping = spec.axial_damping;
  s.bending_damping = spec.bending_damping;
  const CableGeometry g = straight_cable(Vec3::Zero(), spec.length * Vec3::UnitX(), spec.elements);
  const Index c = b.add_cable("pendulum", g, s);
  if (spec.initial_spin != 0.0) {
    // Rigid rotation ω ŷ: ṙ = ω ŷ × r = −ω x ẑ, ṙ_x = ω ŷ × x̂ = −ω ẑ.
    const Vec3 w = spec.initial_spin * Vec3::UnitY();
    std::vector<NodeCoordinates> v(g.nodes.size());
    for (std::size_t k = 0; k < g.nodes.size(); ++k) v[k] << w.cross(g.nodes[k].head<3>()), w.cross(g.nodes[k].tail<3>());
    b.set_initial_configuration(c, g, &v);
  }
  b.pin("pivot", {c, 0}, Vec3::Zero());
  b.set_gravity(spec.gravity);
  return b.finalize();
}

Model rigid_pendulum_model(const RigidPendulumSpec& spec) {
  ModelBuilder b;
  RigidBodyInertia rod;
  rod.mass = spec.mass;
  // Body frame: origin at the hinge, rod along the body x axis; a slender rod has no axial
  // inertia, which natural coordinates allow only as a limit, so a tiny radius is given.
  rod.centre_of_mass = Vec3(0.5 * spec.length, 0.0, 0.0);
  const double i_perp = spec.mass * spec.length * spec.length / 12.0, i_axial = 1e-6 * i_perp;
  rod.inertia = Vec3(i_axial, i_perp, i_perp).asDiagonal();
  // Start at θ₀ from the downward vertical, in the x–z plane: body x axis = (sin θ₀, 0, −cos θ₀).
  const Mat3 rot = Eigen::AngleAxisd(0.5 * std::numbers::pi - spec.initial_angle, Vec3::UnitY()).toRotationMatrix();
  const Index body = b.add_body("rod", rod, Vec3::Zero(), rot);
  b.revolute_to_ground("hinge", body, Vec3::Zero(), Vec3::UnitY());
  b.set_gravity(Vec3(0.0, 0.0, -spec.gravity));
  return b.finalize();
}

double rigid_pendulum_period(const RigidPendulumSpec& spec) {
  // Physical pendulum: ω₀² = m g (L/2) / I_O with I_O = m L²/3 (+ the tiny axial part does not
  // enter: the rotation is about an axis ⊥ the rod). K(k) = π / (2 AGM(1, √(1 − k²))).
  const double i_o = spec.mass * spec.length * spec.length / 3.0;
  const double omega0 = std::sqrt(spec.mass * spec.gravity * 0.5 * spec.length / i_o);
  const double k = std::sin(0.5 * spec.initial_angle);
  double a = 1.0, g = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40 && std::abs(a - g) > 1e-16 * a; ++i) {
    const double an = 0.5 * (a + g);
    g = std::sqrt(a * g);
    a = an;
  }
  const double big_k = std::numbers::pi / (2.0 * a);
  return 4.0 * big_k / omega0;
}

}  // namespace ancf
