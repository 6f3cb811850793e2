// [[body]] (rigid bodies) and [[frame]] (driven frames with a prescribed rotation law).
#include "scene_parts.hpp"
#include "scene_velocity.hpp"

namespace ancf::io {

namespace {

void require_new_entity_name(TableReader& t, const SceneBuild& b, const std::string& name) {
  // Bodies and frames share one namespace: joints and attachments name either with `to`.
  if (name == "ground") t.fail("name", "'ground' is reserved (it names the fixed world frame)");
  if (b.names.bodies.count(name) || b.names.frames.count(name))
    t.fail("name", "the name '" + name + "' is already used by a body or frame");
}

/// [Ixx, Iyy, Izz] (principal moments) or a symmetric 3×3 matrix by rows [kg m²].
Mat3 read_inertia(TableReader& t) {
  const toml::node* n = t.get("inertia");
  if (!n)
    t.fail_here(
        "missing required key 'inertia' ([Ixx, Iyy, Izz] or 3×3 about the centre of mass) [kg m²]");
  const toml::array* a = n->as_array();
  if (a && a->size() == 3 && a->get(0)->is_number()) {
    const Vec3 d = t.vec3("inertia");
    if (!(d.minCoeff() > 0.0)) t.fail("inertia", "expected principal moments > 0");
    return d.asDiagonal();
  }
  if (a && a->size() == 3 && a->get(0)->is_array()) {
    Mat3 m;
    for (int i = 0; i < 3; ++i) {
      const toml::array* row = a->get(static_cast<std::size_t>(i))->as_array();
      if (!row || row->size() != 3) t.fail("inertia", "expected a 3×3 matrix: 3 rows of 3 numbers");
      for (int j = 0; j < 3; ++j) {
        const toml::node* x = row->get(static_cast<std::size_t>(j));
        if (!x->is_number()) t.fail("inertia", "expected numbers, got " + type_name(*x));
        m(i, j) = *x->value<double>();
      }
    }
    return m;
  }
  t.fail("inertia", "expected [Ixx, Iyy, Izz] or a 3×3 matrix [[..], [..], [..]] [kg m²]");
}

}  // namespace

void read_bodies(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("body")) {
    const std::string name = t.string("name");
    require_new_entity_name(t, b, name);
    RigidBodyInertia inertia;
    inertia.mass = t.number("mass", Range::positive);
    inertia.centre_of_mass = t.vec3_or("centre_of_mass", Vec3::Zero());
    inertia.inertia = read_inertia(t);
    const Vec3 position = t.vec3_or("position", Vec3::Zero());
    const Mat3 rotation = read_rotation(t, "rotation");
    // velocity: of rotation_centre (default: the body origin, so that it is the origin's).
    const RigidVelocity v = read_rigid_velocity(t, position);
    t.finish();
    b.build(t, [&] {
      inertia.validate(name);
      b.names.bodies[name] =
          b.builder.add_body(name, inertia, position, rotation, v.at(position), v.omega);
    });
  }
}

void read_frames(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("frame")) {
    DrivenFrame f;
    f.name = t.string("name");
    require_new_entity_name(t, b, f.name);
    f.origin = t.vec3_or("origin", Vec3::Zero());
    f.initial_rotation = read_rotation(t, "rotation");
    f.axis = t.optional_direction("axis").value_or(Vec3::UnitZ());
    f.law = read_angle_law(t, "law");
    t.finish();
    b.build(t, [&] { b.names.frames[f.name] = b.builder.add_driven_frame(f); });
  }
}

}  // namespace ancf::io
