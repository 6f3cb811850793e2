// [[rod]]: Kirchhoff rods that can twist (kirchhoff_rod_element.hpp, docs/rod.md): the cable's
// geometry keys, a reference material frame and a section with torsion and two bending
// stiffnesses. A rod shares the cables' namespace: joints, loads, contact and probes name it as
// `cable`.
#include <cmath>
#include <numbers>

#include "ancf/io/run_limits.hpp"
#include "scene_parts.hpp"
#include "scene_velocity.hpp"

namespace ancf::io {
namespace {

struct RodInput {
  RodSection rod;
  CableSection cable;  // ρA, radius, mass damping (contact and system terms)
};

RodInput read_rod_section(TableReader s) {
  RodInput in;
  RodSection& r = in.rod;
  const auto d = s.optional_number("diameter", Range::positive);
  const auto e = s.optional_number("E", Range::positive);
  const auto g = s.optional_number("G", Range::positive);
  const double pi = std::numbers::pi;
  const double area = d ? pi * *d * *d / 4.0 : 0.0, second = d ? pi * std::pow(*d, 4) / 64.0 : 0.0;
  auto need_d = [&](const char* key) {
    if (!d) s.fail(key, std::string(key) + " needs 'diameter' (solid circular section)");
  };
  // EA
  if (auto ea = s.optional_number("EA", Range::positive)) {
    if (e) s.fail("E", "give either EA or E (with diameter), not both");
    r.axial_stiffness = *ea;
  } else if (e) {
    need_d("E");
    r.axial_stiffness = *e * area;
  } else {
    s.fail_here("missing required key 'EA' (or 'E' with 'diameter') [N]");
  }
  // EI₂, EI₃: EI for both, or each
  const auto ei = s.optional_number("EI", Range::non_negative);
  const auto ei2 = s.optional_number("EI2", Range::non_negative);
  const auto ei3 = s.optional_number("EI3", Range::non_negative);
  if (ei && (ei2 || ei3)) s.fail("EI", "give either EI (isotropic) or EI2 and EI3, not both");
  if (ei2.has_value() != ei3.has_value()) s.fail(ei2 ? "EI2" : "EI3", "give both EI2 and EI3");
  if (ei) {
    r.bending_stiffness_2 = r.bending_stiffness_3 = *ei;
  } else if (ei2) {
    r.bending_stiffness_2 = *ei2;
    r.bending_stiffness_3 = *ei3;
  } else if (e && d) {
    r.bending_stiffness_2 = r.bending_stiffness_3 = *e * second;
  } else {
    s.fail_here("missing required key 'EI' (or 'EI2' and 'EI3', or 'E' with 'diameter') [N m²]");
  }
  // GJ
  if (auto gj = s.optional_number("GJ", Range::positive)) {
    if (g) s.fail("G", "give either GJ or G (with diameter), not both");
    r.torsional_stiffness = *gj;
  } else if (g) {
    need_d("G");
    r.torsional_stiffness = *g * 2.0 * second;  // J = πd⁴/32
  } else {
    s.fail_here("missing required key 'GJ' (or 'G' with 'diameter') [N m²]");
  }
  // ρA and ρJ
  const auto rho_a = s.optional_number("mass_per_length", Range::positive);
  const auto rho = s.optional_number("density", Range::positive);
  if (rho_a && rho) s.fail("density", "give either mass_per_length or density, not both");
  if (rho_a) {
    r.mass_per_length = *rho_a;
  } else if (rho) {
    need_d("density");
    r.mass_per_length = *rho * area;
  } else {
    s.fail_here("missing required key 'mass_per_length' (or 'density' with 'diameter') [kg/m]");
  }
  in.cable.radius = s.number_or("radius", d ? *d / 2.0 : 0.0, Range::non_negative);
  if (auto pj = s.optional_number("polar_inertia", Range::positive)) {
    r.polar_inertia = *pj;
  } else if (in.cable.radius > 0.0) {
    r.polar_inertia = 0.5 * r.mass_per_length * in.cable.radius * in.cable.radius;  // solid disc
  } else {
    s.fail_here(
        "missing required key 'polar_inertia' [kg m] (rhoJ; default rhoA r²/2 needs 'radius' or "
        "'diameter')");
  }
  r.axial_damping = s.number_or("axial_damping", 0.0, Range::non_negative);
  r.torsional_damping = s.number_or("torsional_damping", 0.0, Range::non_negative);
  r.bending_damping = s.number_or("bending_damping", 0.0, Range::non_negative);
  in.cable.mass_damping = s.number_or("mass_damping", 0.0, Range::non_negative);
  r.axial_strain =
      s.choice("axial_strain", {"collocated", "gauss_points"}, "collocated") == "gauss_points"
          ? RodAxialStrain::gauss_points
          : RodAxialStrain::collocated;
  r.twist = s.choice("twist_interpolation", {"quadratic", "linear"}, "quadratic") == "linear"
                ? RodTwist::linear
                : RodTwist::quadratic;
  r.torsion_strain =
      s.choice("torsion_strain", {"projected", "gauss_points"}, "projected") == "gauss_points"
          ? RodTorsionStrain::gauss_points
          : RodTorsionStrain::projected;
  in.cable.mass_per_length = r.mass_per_length;
  s.finish();
  return in;
}

}  // namespace

void read_rods(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("rod")) {
    const std::string name = t.string("name");
    if (b.names.cables.count(name))
      t.fail("name", "the cable/rod name '" + name + "' is used twice");
    const Index elements = t.integer("elements", 1);
    b.elements += static_cast<double>(elements);
    try {
      require_memory_for_elements(b.elements, b.limits.memory_bytes);
    } catch (const ModelError& e) {
      t.fail("elements", e.what());
    }
    const CableMesh mesh = read_cable_mesh(t, elements);
    const CableGeometry& initial = mesh.initial;
    const CableGeometry& reference = mesh.reference;
    const GeometryAxis& ref_axis = mesh.reference_axis;
    // Reference material frame: d₂ along `normal` (⊥ tangent part), or towards the axis of a
    // helix/arc reference.
    std::vector<Mat3> frames;
    std::optional<Vec3> normal;
    if (auto f = t.optional_table("frame")) {
      normal = f->optional_direction("normal");
      f->finish();
    }
    if (!normal && !ref_axis.valid)
      t.fail_here(
          "a straight or polyline rod needs 'frame = { normal = [x, y, z] }' (the direction of "
          "the material axis d2 of the reference)");
    const RodInput section = read_rod_section(t.table("section"));
    const auto velocities = read_cable_velocities(t, initial);
    t.finish();
    b.build(t, [&] {
      frames = normal ? rod_frames_with_normal(reference, *normal)
                      : rod_frames_toward_axis(reference, ref_axis.point, ref_axis.direction);
      const Index c = b.builder.add_rod(name, reference, section.cable, section.rod, frames);
      if (t.has("reference") || velocities)
        b.builder.set_initial_configuration(c, initial, velocities ? &*velocities : nullptr);
      b.names.cables[name] = c;
      b.cable_initial.push_back(initial);
      b.cable_radius.push_back(section.cable.radius);
      b.cable_names.push_back(name);
      b.cable_origins[name] = {t.path(), t.line()};
      b.cable_is_rod.push_back(1);
    });
  }
}

}  // namespace ancf::io
