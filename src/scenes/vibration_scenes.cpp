#include "ancf/scenes/vibration_scenes.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ancf/system/model_builder.hpp"

namespace ancf {

namespace {

CableSection section_of(const UniformCableSpec& spec) {
  CableSection s;
  s.strain = spec.strain;
  s.axial_stiffness = spec.axial_stiffness;
  s.bending_stiffness = spec.bending_stiffness;
  s.mass_per_length = spec.mass_per_length;
  return s;
}

CableGeometry reference_of(const UniformCableSpec& spec) {
  return straight_cable(Vec3::Zero(), spec.length * Vec3::UnitX(), spec.elements);
}

}  // namespace

Model fixed_free_bar_model(const UniformCableSpec& spec,
                           const std::vector<NodeCoordinates>* velocities) {
  ModelBuilder b;
  const CableGeometry g = reference_of(spec);
  const Index c = b.add_cable("bar", g, section_of(spec));
  if (velocities) b.set_initial_configuration(c, g, velocities);
  b.pin("root", {c, 0}, Vec3::Zero());
  return b.finalize();
}

Model taut_string_model(const UniformCableSpec& spec, double stretch,
                        const std::vector<NodeCoordinates>* velocities) {
  ModelBuilder b;
  const Index c = b.add_cable("string", reference_of(spec), section_of(spec));
  CableGeometry g =
      straight_cable(Vec3::Zero(), stretch * spec.length * Vec3::UnitX(), spec.elements);
  for (NodeCoordinates& node : g.nodes) node.tail<3>() = stretch * Vec3::UnitX();  // r_x = λ x̂
  b.set_initial_configuration(c, g, velocities);
  b.pin("left", {c, 0}, Vec3::Zero());
  b.pin("right", {c, -1}, stretch * spec.length * Vec3::UnitX());
  return b.finalize();
}

Model clamped_free_beam_model(const UniformCableSpec& spec) {
  ModelBuilder b;
  const Index c = b.add_cable("beam", reference_of(spec), section_of(spec));
  b.pin("root position", {c, 0}, Vec3::Zero());
  b.align_slope("root slope", {c, 0}, Vec3::UnitX());
  return b.finalize();
}

double fixed_free_bar_frequency(const UniformCableSpec& spec, int n) {
  const double c = std::sqrt(spec.axial_stiffness / spec.mass_per_length);
  return (2 * n - 1) * std::numbers::pi * c / (2.0 * spec.length);
}

double taut_string_tension(const UniformCableSpec& spec, double stretch) {
  return spec.strain == StrainMeasure::green_lagrange
             ? spec.axial_stiffness * 0.5 * (stretch * stretch - 1.0) * stretch
             : spec.axial_stiffness * (stretch - 1.0);
}

double taut_string_frequency(const UniformCableSpec& spec, double stretch, int n) {
  const double t = taut_string_tension(spec, stretch);
  return n * std::numbers::pi / spec.length * std::sqrt(t / (stretch * spec.mass_per_length));
}

double cantilever_beta_l(int n) {
  if (n < 1) throw std::invalid_argument("cantilever_beta_l: n >= 1");
  // f(x) = 1 + cos x cosh x has one root near (2n − 1)π/2 (within 0.31 for n = 1, closer above);
  // Newton with f'(x) = −sin x cosh x + cos x sinh x.
  double x = (2 * n - 1) * std::numbers::pi / 2.0;
  for (int i = 0; i < 50; ++i) {
    const double f = 1.0 + std::cos(x) * std::cosh(x);
    const double df = -std::sin(x) * std::cosh(x) + std::cos(x) * std::sinh(x);
    const double dx = f / df;
    x -= dx;
    if (std::abs(dx) < 1e-15 * x) break;
  }
  return x;
}

double clamped_free_beam_frequency(const UniformCableSpec& spec, int n) {
  const double bl = cantilever_beta_l(n);
  return bl * bl *
         std::sqrt(spec.bending_stiffness / (spec.mass_per_length * std::pow(spec.length, 4)));
}

}  // namespace ancf
