#include "ancf/scenes/contact_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf {
namespace {

// A unit-speed curve as nodes (position, unit tangent) at the given arc lengths.
template <class Curve>
CableGeometry sample_curve(const Curve& curve, const std::vector<double>& s) {
  CableGeometry g;
  for (std::size_t k = 0; k < s.size(); ++k) {
    const auto [r, t] = curve(s[k]);
    NodeCoordinates n;
    n << r, t;
    g.nodes.push_back(n);
    if (k > 0) g.element_lengths.push_back(s[k] - s[k - 1]);
  }
  return g;
}

void append_uniform(std::vector<double>& s, double from, double to, double target) {
  const int n = std::max(1, static_cast<int>(std::ceil((to - from) / target - 1e-9)));
  for (int k = s.empty() ? 0 : 1; k <= n; ++k) s.push_back(from + (to - from) * k / n);
}

}  // namespace

Model capstan_model(const CapstanSpec& spec) {
  if (!(spec.wrap_angle > 0.0 && spec.wrap_angle < 2.0 * std::numbers::pi))
    throw ModelError("capstan: wrap angle must be in (0, 2 pi)");
  const double rho = spec.drum_radius + spec.cable_radius;  // centreline radius on the drum
  const double theta = spec.wrap_angle, ls = spec.straight_length;
  // Arc symmetric about +y, travelled clockwise (decreasing polar angle φ) from φ0 to φ1.
  const double phi0 = 0.5 * std::numbers::pi + 0.5 * theta, phi1 = phi0 - theta;
  const Vec3 p0 = rho * Vec3(std::cos(phi0), std::sin(phi0), 0.0);
  const Vec3 t0(std::sin(phi0), -std::cos(phi0), 0.0);
  const Vec3 t1(std::sin(phi1), -std::cos(phi1), 0.0);
  const Vec3 p1 = rho * Vec3(std::cos(phi1), std::sin(phi1), 0.0);
  const double arc = rho * theta;
  auto curve = [&](double s) -> std::pair<Vec3, Vec3> {
    if (s <= ls) return {p0 - (ls - s) * t0, t0};
    if (s <= ls + arc) {
      const double phi = phi0 - (s - ls) / rho;
      return {rho * Vec3(std::cos(phi), std::sin(phi), 0.0),
              Vec3(std::sin(phi), -std::cos(phi), 0.0)};
    }
    return {p1 + (s - ls - arc) * t1, t1};
  };
  std::vector<double> s;
  append_uniform(s, 0.0, ls, spec.element_length);
  append_uniform(s, ls, ls + arc, spec.element_length);
  append_uniform(s, ls + arc, 2.0 * ls + arc, spec.element_length);

  ModelBuilder b;
  CableSection section;  // steel-like wire, r = 2 mm: EA ≈ 2.5e6 N; EI small (statics regular)
  section.axial_stiffness = 2.5e6;
  section.bending_stiffness = 1e-4;
  section.mass_per_length = 0.1;
  section.radius = spec.cable_radius;
  const Index cable = b.add_cable("rope", sample_curve(curve, s), section);
  DrivenFrame drum;
  drum.name = "drum";
  drum.axis = Vec3::UnitZ();
  drum.law = AngleLaw::constant_rate(-spec.surface_speed / rho);  // clockwise: anchor → load
  const int frame = b.add_driven_frame(drum);
  CappedCylinderShape cylinder;
  cylinder.axis = Vec3::UnitZ();
  cylinder.radius = spec.drum_radius;
  cylinder.half_length = 0.1;
  const Index shape = b.add_frame_shape("drum surface", frame, cylinder);
  ContactLaw law;
  // Penalty: pressure T/ρ ≈ 200–1000 N/m gives ≈ 1e-4 m penetration (≪ r) at k = 1e7 N/m².
  law.stiffness = 1e7;
  law.onset_depth = 1e-5;
  law.friction = spec.friction;
  law.regularization_speed = spec.regularization_speed;
  b.add_cable_shape_contact("rope on drum", cable, shape, law, spec.samples_per_element);
  b.pin(kCapstanAnchor, {cable, 0}, p0 - ls * t0);
  b.add_node_force({cable, -1}, spec.low_tension * t1);
  return b.finalize();
}

Model drop_on_plane_model(const DropSpec& spec) {
  ModelBuilder b;
  CableSection section;
  section.axial_stiffness = 1e4;
  section.bending_stiffness = 1e-3;
  section.mass_per_length = 0.1;
  section.axial_damping = 1.0;
  section.bending_damping = 1e-4;
  section.radius = 0.005;
  const double z = section.radius + spec.drop_height;
  const Index cable =
      b.add_cable("rope", straight_cable(Vec3(0.0, 0.0, z), Vec3(0.5, 0.0, z), 10), section);
  const Index ground = b.add_ground_shape("floor", PlaneShape{Vec3::Zero(), Vec3::UnitZ()});
  ContactLaw law;
  law.stiffness = spec.stiffness;
  law.onset_depth = spec.onset_depth;
  law.damping = spec.damping;
  law.friction = spec.friction;
  law.regularization_speed = 1e-3;
  b.add_cable_shape_contact("rope on floor", cable, ground, law, spec.samples_per_element);
  b.set_gravity(Vec3(0.0, 0.0, -9.81));
  return b.finalize();
}

Model cable_impact_model(double speed, double contact_damping) {
  ModelBuilder b;
  CableSection section;
  section.axial_stiffness = 1e4;
  section.bending_stiffness = 1e-2;
  section.mass_per_length = 0.1;
  section.radius = 0.005;
  const Index a =
      b.add_cable("a", straight_cable(Vec3(-0.25, 0.03, 0.0), Vec3(0.25, 0.03, 0.0), 8), section);
  const Index c =
      b.add_cable("b", straight_cable(Vec3(0.05, -0.2, 0.02), Vec3(0.05, 0.2, 0.02), 6), section);
  std::vector<NodeCoordinates> v(7, NodeCoordinates::Zero());
  for (auto& n : v) n.head<3>() = Vec3(0.0, 0.0, -speed);
  b.set_initial_configuration(c, straight_cable(Vec3(0.05, -0.2, 0.02), Vec3(0.05, 0.2, 0.02), 6),
                              &v);
  ContactLaw law;
  law.stiffness = 1e5;
  law.onset_depth = 1e-4;
  law.damping = contact_damping;
  b.add_cable_cable_contact("crossing", a, c, law, 4);
  return b.finalize();
}

}  // namespace ancf
