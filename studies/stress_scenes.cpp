#include "stress_scenes.hpp"

#include <cmath>
#include <numbers>

#include "ancf/scenes/pendulums.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf::studies {

namespace {

double swing_potential(const CablePendulumSpec& s) {
  return s.mass_per_length * s.gravity.norm() * s.length * s.length / 2.0;
}

}  // namespace

StressScene gerstmayr_shabana_scene(double f, Index elements) {
  const CablePendulumSpec s = gerstmayr_shabana_pendulum(f, elements);
  const double spin_energy =
      s.mass_per_length * s.initial_spin * s.initial_spin * std::pow(s.length, 3) / 6.0;
  return {cable_pendulum_model(s), swing_potential(s) + spin_energy};
}

StressScene benchmark_pendulum_scene(Index elements) {
  const CablePendulumSpec s = benchmark_cable_pendulum(elements);
  return {cable_pendulum_model(s), swing_potential(s)};
}

StressScene steel_wire_scene(Index elements) {
  const double e = 2.1e11, rho = 7850.0;
  const CircularSection section = circular_section(1e-3);
  CablePendulumSpec s;
  s.length = 0.1;
  s.axial_stiffness = e * section.area;
  s.bending_stiffness = e * section.second_moment;
  s.mass_per_length = rho * section.area;
  s.elements = elements;
  s.gravity = Vec3(0.0, 0.0, -9.81);
  return {cable_pendulum_model(s), swing_potential(s)};
}

StressScene slack_snap_scene(double tip_mass, Index elements) {
  const CablePendulumSpec cable = benchmark_cable_pendulum(elements);
  const double length = cable.length, radius = length / std::numbers::pi;
  ModelBuilder b;
  CableSection section;
  section.axial_stiffness = cable.axial_stiffness;
  section.bending_stiffness = cable.bending_stiffness;
  section.mass_per_length = cable.mass_per_length;
  const Index c =
      b.add_cable("rope", straight_cable(Vec3::Zero(), length * Vec3::UnitX(), elements), section);
  // Semicircle of arc length L below the pivot: starts at the origin heading down (−ẑ), centre
  // (R, 0, 0), ends at (2R, 0, 0) heading up. Same arc length as the reference, so the initial
  // axial strain is zero and only the bending energy EI π²/(2L) is stored.
  const CableGeometry slack = arc_cable(Vec3(radius, 0.0, 0.0), -Vec3::UnitX(), -Vec3::UnitZ(),
                                        radius, std::numbers::pi, elements);
  b.set_initial_configuration(c, slack);
  b.pin("pivot", {c, 0}, Vec3::Zero());
  RigidBodyInertia sphere;
  const double r = 0.05;
  sphere.mass = tip_mass;
  sphere.inertia = (0.4 * tip_mass * r * r) * Mat3::Identity();
  const Index body = b.add_body("tip mass", sphere, Vec3(2.0 * radius, 0.0, 0.0));
  b.attach_node_to_body("rope end", {c, -1}, body);
  b.set_gravity(Vec3(0.0, 0.0, -9.81));
  const double g = 9.81;
  return {b.finalize(), tip_mass * g * length + cable.mass_per_length * g * length * length / 2.0};
}

}  // namespace ancf::studies
