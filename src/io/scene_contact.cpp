// [[shape]] (sphere, cylinder, plane on ground, a frame or a body) and [[contact]] pairs
// (cable–shape, cable–cable) with their penalty law.
#include "scene_parts.hpp"

namespace ancf::io {

namespace {

ContactShape read_shape_geometry(TableReader& t) {
  const std::string kind = t.choice("kind", {"sphere", "cylinder", "plane"});
  if (kind == "sphere")
    return SphereShape{t.vec3_or("centre", Vec3::Zero()), t.number("radius", Range::positive)};
  if (kind == "cylinder") {
    CappedCylinderShape c;
    c.centre = t.vec3_or("centre", Vec3::Zero());
    c.axis = t.optional_direction("axis").value_or(Vec3::UnitZ());
    c.radius = t.number("radius", Range::positive);
    c.half_length = t.number("half_length", Range::positive);
    return c;
  }
  return PlaneShape{t.vec3_or("point", Vec3::Zero()),
                    t.optional_direction("normal").value_or(Vec3::UnitZ())};
}

ContactLaw read_law(TableReader t) {
  ContactLaw law;
  law.stiffness = t.number("stiffness", Range::positive);
  law.onset_depth = t.number_or("onset_depth", law.onset_depth, Range::positive);
  law.damping = t.number_or("damping", law.damping, Range::non_negative);
  law.friction = t.number_or("friction", law.friction, Range::non_negative);
  law.regularization_speed =
      t.number_or("regularization_speed", law.regularization_speed, Range::positive);
  t.finish();
  return law;
}

}  // namespace

void read_shapes(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("shape")) {
    const std::string name = t.string("name");
    if (b.names.shapes.count(name)) t.fail("name", "the shape name '" + name + "' is used twice");
    const ContactShape shape = read_shape_geometry(t);
    const std::string on = t.string_or("on", "ground");
    Index index = -1;
    if (on == "ground") {
      b.build(t, [&] { index = b.builder.add_ground_shape(name, shape); });
    } else if (b.names.bodies.count(on)) {
      b.build(t, [&] { index = b.builder.add_body_shape(name, b.names.bodies.at(on), shape); });
    } else if (b.names.frames.count(on)) {
      b.build(t, [&] {
        index = b.builder.add_frame_shape(name, static_cast<int>(b.names.frames.at(on)), shape);
      });
    } else {
      t.fail("on", "no body or frame named '" + on + "' (or \"ground\")");
    }
    t.finish();
    b.names.shapes[name] = index;
  }
}

void read_contacts(TableReader& root, SceneBuild& b) {
  // Pairs are numbered as the Model numbers them: cable–shape first, then cable–cable.
  std::vector<std::string> shape_pairs, cable_pairs;
  for (TableReader& t : root.tables("contact")) {
    const std::string name = t.string("name");
    b.declare(t, "name", name);
    const Index cable = b.cable(t, "cable");
    if (t.has("shape") == t.has("other_cable"))
      t.fail_here(
          "expected exactly one of 'shape' (cable–shape pair) or 'other_cable' (cable–cable pair)");
    const int samples = static_cast<int>(t.integer_or("samples_per_element", 4, 1));
    const ContactLaw law = read_law(t.table("law"));
    const ElementRange range = b.element_range(t, "elements", cable);
    if (!(b.cable_radius[cable] > 0.0))
      t.fail("cable", "cable '" + b.cable_names[cable] +
                          "' needs section.radius > 0 (or a diameter) for contact");
    if (t.has("shape")) {
      const std::string shape = t.string("shape");
      if (!b.names.shapes.count(shape)) t.fail("shape", "no shape named '" + shape + "'");
      b.build(t, [&] {
        b.builder.add_cable_shape_contact(name, cable, b.names.shapes.at(shape), law, samples,
                                          range);
      });
      shape_pairs.push_back(name);
    } else {
      const Index other = b.cable(t, "other_cable");
      if (other == cable) t.fail("other_cable", "self-contact of a cable is not supported");
      if (!(b.cable_radius[other] > 0.0))
        t.fail("other_cable",
               "cable '" + b.cable_names[other] + "' needs section.radius > 0 for contact");
      const ElementRange other_range = b.element_range(t, "other_elements", other);
      b.build(t, [&] {
        b.builder.add_cable_cable_contact(name, cable, other, law, samples, range, other_range);
      });
      cable_pairs.push_back(name);
    }
    t.finish();
  }
  Index k = 0;
  for (const auto& n : shape_pairs) b.names.contacts[n] = k++;
  for (const auto& n : cable_pairs) b.names.contacts[n] = k++;
}

}  // namespace ancf::io
