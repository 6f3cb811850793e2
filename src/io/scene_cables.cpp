// [[cable]]: geometry (straight, polyline, helix, arc), optional stress-free reference, section.
#include <cmath>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "ancf/io/run_limits.hpp"
#include "ancf/system/mesh_grading.hpp"
#include "scene_parts.hpp"
#include "scene_velocity.hpp"

namespace ancf::io {

namespace {

/// Nodes through the points of a polyline; `elements` (≥ segments) are shared among the segments
/// in proportion to their length. A corner node's slope is the bisector of the adjacent unit
/// tangents, so the reference is the smooth Hermite curve through the points (docs/scenes.md).
CableGeometry polyline_cable(TableReader& g, const std::vector<Vec3>& p, Index elements) {
  const std::size_t segments = p.size() - 1;
  if (static_cast<std::size_t>(elements) < segments)
    g.fail("points", "a polyline of " + std::to_string(segments) +
                         " segments needs elements >= " + std::to_string(segments));
  std::vector<double> length(segments);
  for (std::size_t s = 0; s < segments; ++s) {
    length[s] = (p[s + 1] - p[s]).norm();
    if (!(length[s] > 0.0))
      g.fail("points", "points " + std::to_string(s) + " and " + std::to_string(s + 1) +
                           " coincide (zero-length segment)");
  }
  // One element per segment, then the rest by largest remaining length per element.
  std::vector<Index> count(segments, 1);
  for (Index extra = elements - static_cast<Index>(segments); extra > 0; --extra) {
    std::size_t best = 0;
    for (std::size_t s = 1; s < segments; ++s)
      if (length[s] / count[s] > length[best] / count[best]) best = s;
    ++count[best];
  }
  CableGeometry geo;
  auto tangent = [&](std::size_t s) -> Vec3 { return (p[s + 1] - p[s]) / length[s]; };
  for (std::size_t s = 0; s < segments; ++s) {
    const Vec3 t = tangent(s);
    for (Index k = 0; k < count[s]; ++k) {
      NodeCoordinates node;
      Vec3 slope = t;
      if (k == 0 && s > 0) {
        const Vec3 bisector = tangent(s - 1) + t;
        if (!(bisector.norm() > 1e-12))
          g.fail("points", "the polyline turns back on itself at point " + std::to_string(s));
        slope = bisector.normalized();
      }
      node << p[s] + (static_cast<double>(k) / count[s]) * (p[s + 1] - p[s]), slope;
      geo.nodes.push_back(node);
      geo.element_lengths.push_back(length[s] / count[s]);
    }
  }
  NodeCoordinates last;
  last << p.back(), tangent(segments - 1);
  geo.nodes.push_back(last);
  return geo;
}

void require_perpendicular(TableReader& g, std::string_view key, const Vec3& a, const Vec3& b,
                           const char* other) {
  if (std::abs(a.dot(b)) > 1e-9)
    g.fail(key, std::string("expected a direction perpendicular to ") + other);
}

/// Numbers near the double range pass the reader (they are finite), but the distances between
/// them overflow (a norm squares its components), which the generators would turn into a zero
/// slope or NaN fractions far from this table (found by the fuzzer, 2026-12-06).
void require_finite_extent(TableReader& g, std::string_view key, const CableGeometry& geo) {
  for (double l : geo.element_lengths)
    if (!(std::isfinite(l) && l > 0.0))
      g.fail(key,
             "expected a geometry whose element lengths are finite and positive in double "
             "precision, got " +
                 fmt::format("{:g}", l) + " m (coordinates or radius too large)");
  for (const NodeCoordinates& n : geo.nodes)
    if (!n.allFinite())
      g.fail(key,
             "expected a geometry whose node coordinates are finite in double precision "
             "(coordinates or radius too large)");
}

}  // namespace

CableGeometry read_geometry(TableReader g, Index elements, GeometryAxis* axis_out,
                            std::span<const double> fractions) {
  const std::string kind = g.choice("kind", {"straight", "polyline", "helix", "arc"});
  CableGeometry geo;
  if (kind == "straight") {
    const Vec3 a = g.vec3("start"), b = g.vec3("end");
    if (!((b - a).norm() > 0.0))
      g.fail("end", "expected an end point different from start (zero length)");
    geo = straight_cable(a, b, elements, fractions);
    require_finite_extent(g, "end", geo);
  } else if (kind == "polyline") {
    if (!fractions.empty())
      g.fail("kind",
             "a graded mesh ('grading') needs a straight, helix or arc geometry, not a "
             "polyline (its elements follow the segments)");
    geo = polyline_cable(g, g.vec3_list("points", 2), elements);
    require_finite_extent(g, "points", geo);
  } else if (kind == "helix") {
    const Vec3 base = g.vec3_or("base", Vec3::Zero());
    const Vec3 axis = g.optional_direction("axis").value_or(Vec3::UnitZ());
    const Vec3 u = g.optional_direction("u").value_or(
        std::abs(axis.x()) < 0.9 ? axis.cross(Vec3::UnitX()).cross(axis).normalized()
                                 : axis.cross(Vec3::UnitY()).cross(axis).normalized());
    require_perpendicular(g, "u", u, axis, "axis");
    const double radius = g.number("radius", Range::positive);
    const double phi0 = g.number_or("phi0", 0.0), twist = g.number("twist"),
                 rise = g.number("rise");
    if (!(std::hypot(radius * twist, rise) > 0.0))
      g.fail("twist", "expected twist or rise non-zero (zero length)");
    geo = helix_cable(base, axis, u, radius, phi0, twist, rise, elements, fractions);
    require_finite_extent(g, "radius", geo);
    if (axis_out) *axis_out = {true, base, axis};
  } else {
    const Vec3 centre = g.vec3_or("centre", Vec3::Zero());
    const Vec3 u = g.direction("u"), w = g.direction("w");
    require_perpendicular(g, "w", w, u, "u");
    const double radius = g.number("radius", Range::positive), angle = g.number("angle");
    if (angle == 0.0) g.fail("angle", "expected a non-zero angle [rad] (zero length)");
    geo = arc_cable(centre, u, w, radius, angle, elements, fractions);
    require_finite_extent(g, "radius", geo);
    if (axis_out) *axis_out = {true, centre, u.cross(w)};
  }
  g.finish();
  return geo;
}

CableMesh read_cable_mesh(TableReader& t, Index elements) {
  CableMesh mesh;
  std::vector<double> fractions;
  if (auto gr = t.optional_table("grading")) {
    MeshGrading grading;
    const bool band = gr->has("band_ratio");
    // Without a band the ends are what is graded: end_ratio and end_length are required.
    grading.end_ratio = band ? gr->number_or("end_ratio", 1.0, Range::positive)
                             : gr->number("end_ratio", Range::positive);
    if (grading.end_ratio > 1.0)
      gr->fail("end_ratio", "expected the end elements' length over the others', in (0, 1]");
    grading.end_length = grading.end_ratio < 1.0
                             ? gr->number("end_length", Range::positive)
                             : gr->number_or("end_length", 0.0, Range::non_negative);
    const std::string ends = gr->choice("ends", {"both", "start", "end"}, "both");
    grading.at_start = ends != "end";
    grading.at_end = ends != "start";
    if (band) {
      grading.band_ratio = gr->number("band_ratio", Range::positive);
      if (grading.band_ratio > 1.0)
        gr->fail("band_ratio", "expected the band elements' length over the others', in (0, 1]");
      grading.band_width = gr->number("band_width", Range::positive);
      grading.band_centre = gr->number_or("band_centre", 0.5, Range::non_negative);
      if (grading.band_centre > 1.0)
        gr->fail("band_centre",
                 "expected the band's centre as a fraction of the length, in [0, 1]");
    }
    gr->finish();
    // The fractions need the geometry's arc length: take it from the equal-element mesh (a
    // load-time cost of one more small mesh; each kind's length formula then lives in its generator
    // only).
    const CableGeometry uniform = read_geometry(t.table("geometry"), elements);
    double length = 0.0;
    for (double l : uniform.element_lengths) length += l;
    try {
      fractions = node_fractions(elements, length, grading);
    } catch (const ModelError& e) {
      t.fail("grading", e.what());
    }
  }
  mesh.initial = read_geometry(t.table("geometry"), elements, &mesh.axis, fractions);
  mesh.reference_axis = mesh.axis;
  mesh.reference = t.has("reference") ? read_geometry(t.table("reference"), elements,
                                                      &mesh.reference_axis, fractions)
                                      : mesh.initial;
  return mesh;
}

namespace {

CableSection read_section(TableReader s) {
  CableSection c;
  c.strain = s.choice("strain", {"green", "elastic_line"}, "green") == "green"
                 ? StrainMeasure::green_lagrange
                 : StrainMeasure::elastic_line;
  const auto ea = s.optional_number("EA", Range::positive);
  const auto e = s.optional_number("E", Range::positive);
  const auto d = s.optional_number("diameter", Range::positive);
  const CircularSection round = d ? circular_section(*d) : CircularSection{};
  const double area = round.area;
  if (ea && e) s.fail("E", "give either EA or E (with diameter), not both");
  if (ea) {
    c.axial_stiffness = *ea;
  } else if (e) {
    if (!d) s.fail("E", "E needs the diameter (A = π d²/4), or give EA instead");
    c.axial_stiffness = *e * area;
  } else {
    s.fail_here("missing required key 'EA' (or 'E' with 'diameter') [N]");
  }
  const auto rho_a = s.optional_number("mass_per_length", Range::positive);
  const auto rho = s.optional_number("density", Range::positive);
  if (rho_a && rho) s.fail("density", "give either mass_per_length or density, not both");
  if (rho_a) {
    c.mass_per_length = *rho_a;
  } else if (rho) {
    if (!d) s.fail("density", "density needs the diameter, or give mass_per_length instead");
    c.mass_per_length = *rho * area;
  } else {
    s.fail_here("missing required key 'mass_per_length' (or 'density' with 'diameter') [kg/m]");
  }
  const bool bending = s.boolean_or("bending", true);
  const auto ei = s.optional_number("EI", Range::non_negative);
  if (bending) {
    if (ei) {
      c.bending_stiffness = *ei;
    } else if (e && d) {
      c.bending_stiffness = *e * round.second_moment;
    } else {
      s.fail_here(
          "bending = true needs 'EI' [N m²], or 'E' with 'diameter' "
          "(set bending = false for the paper's pure cable)");
    }
  } else if (ei && *ei > 0.0) {
    s.fail("EI", "EI > 0 given with bending = false");
  }
  c.prestrain = s.number_or("prestrain", 0.0);
  if (c.prestrain <= -1.0) s.fail("prestrain", "expected a prestrain > -1");
  c.axial_damping = s.number_or("axial_damping", 0.0, Range::non_negative);
  c.bending_damping = s.number_or("bending_damping", 0.0, Range::non_negative);
  if (!bending && c.bending_damping > 0.0)
    s.fail("bending_damping", "bending damping given with bending = false");
  c.bending_damping_curvature =
      s.number_or("bending_damping_curvature", c.bending_damping_curvature, Range::positive);
  c.mass_damping = s.number_or("mass_damping", 0.0, Range::non_negative);
  c.radius = s.number_or("radius", d ? *d / 2.0 : 0.0, Range::non_negative);
  for (auto [key, points] : {std::pair{"axial_gauss_points", &c.quadrature.axial},
                             std::pair{"bending_gauss_points", &c.quadrature.bending}}) {
    *points = static_cast<int>(s.integer_or(key, *points, 1));
    if (*points > kMaxCableGaussPoints)
      s.fail(key, "expected 1 … " + std::to_string(kMaxCableGaussPoints) + " Gauss points, got " +
                      std::to_string(*points));
  }
  s.finish();
  return c;
}

}  // namespace

void read_cables(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("cable")) {
    const std::string name = t.string("name");
    if (b.names.cables.count(name)) t.fail("name", "the cable name '" + name + "' is used twice");
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
    const CableSection section = read_section(t.table("section"));
    const auto velocities = read_cable_velocities(t, initial);
    t.finish();
    b.build(t, [&] {
      const Index c = b.builder.add_cable(name, reference, section);
      if (t.has("reference") || velocities)
        b.builder.set_initial_configuration(c, initial, velocities ? &*velocities : nullptr);
      b.names.cables[name] = c;
      b.cable_initial.push_back(initial);
      b.cable_radius.push_back(section.radius);
      b.cable_names.push_back(name);
      b.cable_origins[name] = {t.path(), t.line()};
      b.cable_is_rod.push_back(0);
    });
  }
}

}  // namespace ancf::io
