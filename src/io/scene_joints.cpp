// [[joint]]: constraints on cable nodes (pin, align_slope, clamp, attach, join) and rigid-body
// joints (spherical, revolute, fixed) to ground or between bodies; [[drive]] on revolute joints;
// [[load]] (nodal, distributed, body and spring loads).
#include <optional>

#include "scene_parts.hpp"

namespace ancf::io {

namespace {

void read_node_joint(TableReader& t, SceneBuild& b, const std::string& kind,
                     const std::string& name) {
  const NodeRef node = b.node(t, "at");
  b.joint_targets[name] = {false, node.cable, node.node};
  const NodeCoordinates& x0 = b.cable_initial[node.cable].nodes[node.node];
  const std::string slope_name = name + ".slope";
  if (kind == "pin" || kind == "clamp") {
    const Vec3 target = t.vec3_or("position", x0.head<3>());
    b.build(t, [&] { b.builder.pin(name, node, target); });
  }
  if (kind == "align_slope" || kind == "clamp") {
    const Vec3 d = t.optional_direction("direction").value_or(x0.tail<3>());
    if (kind == "clamp") b.declare(t, "name", slope_name);
    b.build(t, [&] { b.builder.align_slope(kind == "clamp" ? slope_name : name, node, d); });
  }
  const bool rod = b.cable_is_rod[node.cable] != 0;
  // A rod's clamp also fixes its twist (the material triad), unless twist = false.
  if (kind == "clamp" && rod && t.boolean_or("twist", true)) {
    b.declare(t, "name", name + ".twist");
    b.build(t, [&] { b.builder.fix_twist(name + ".twist", node); });
  }
  if (kind == "fix_twist") {
    if (!rod) t.fail("at", "fix_twist needs a node of a [[rod]] (a cable has no twist)");
    b.build(t, [&] { b.builder.fix_twist(name, node); });
  }
  if (kind == "attach") {
    const std::string to = t.string("to");
    const bool slope = t.boolean_or("slope", false);
    // A rod's end with its slope fixed in the body/frame also has its twist tied to it (the
    // material triad fixed, rod_twist_constraint.hpp), unless twist = false.
    const bool twist = t.boolean_or("twist", rod && slope);
    if (twist && !rod)
      t.fail("twist", "twist = true needs a node of a [[rod]] (a cable has no twist)");
    if (twist && !slope)
      t.fail("twist", "twist = true needs slope = true (the twist is about the fixed slope)");
    if (slope) b.declare(t, "name", slope_name);
    const std::string twist_name = name + ".twist";
    if (twist) b.declare(t, "name", twist_name);
    if (b.names.bodies.count(to)) {
      const Index body = b.names.bodies.at(to);
      b.build(t, [&] {
        b.builder.attach_node_to_body(name, node, body);
        if (slope) b.builder.align_slope_to_body(slope_name, node, body);
        if (twist) b.builder.tie_twist_to_body(twist_name, node, body);
      });
    } else if (b.names.frames.count(to)) {
      const int frame = static_cast<int>(b.names.frames.at(to));
      b.build(t, [&] {
        b.builder.attach_node_to_frame(name, node, frame);
        if (slope) b.builder.align_slope_to_frame(slope_name, node, frame);
        if (twist) b.builder.tie_twist_to_frame(twist_name, node, frame);
      });
    } else {
      t.fail("to", "no body or frame named '" + to + "' (use pin to fix a node to ground)");
    }
  }
  if (kind == "join") {
    const NodeRef other = b.node(t, "other");
    const bool slopes = t.boolean_or("slopes", false);
    if (other.cable == node.cable && other.node == node.node)
      t.fail("other", "expected a different node than 'at'");
    const bool rods = rod && b.cable_is_rod[other.cable] != 0;
    const bool twist = t.boolean_or("twist", rods && slopes);
    if (twist && !rods) t.fail("twist", "twist = true needs two nodes of [[rod]]s");
    if (twist) b.declare(t, "name", name + ".twist");
    b.build(t, [&] {
      b.builder.join_nodes(name, node, other, slopes);
      if (twist) b.builder.join_twist(name + ".twist", node, other);
    });
  }
}

void read_body_joint(TableReader& t, SceneBuild& b, const std::string& kind,
                     const std::string& name) {
  const Index body = b.body(t, "body");
  b.joint_targets[name] = {true, body, 0};
  if (t.has("to") && b.names.frames.count(t.string("to")))
    t.fail("to", "body joints connect a body to ground or to another body, not to a driven frame");
  const Index other = b.body_or_ground(t, "to");
  if (other == body) t.fail("to", "expected a different body than 'body'");
  if (kind == "spherical") {
    const Vec3 p = t.vec3("point");
    b.build(t, [&] {
      other < 0 ? b.builder.spherical_to_ground(name, body, p)
                : b.builder.spherical(name, other, body, p);
    });
  } else if (kind == "revolute") {
    const Vec3 p = t.vec3("point"), axis = t.direction("axis");
    b.build(t, [&] {
      other < 0 ? b.builder.revolute_to_ground(name, body, p, axis)
                : b.builder.revolute(name, other, body, p, axis);
    });
    b.revolute_joints[name] = t.path();
  } else {
    b.build(t, [&] {
      other < 0 ? b.builder.fixed_to_ground(name, body) : b.builder.fixed(name, other, body);
    });
  }
}

}  // namespace

void read_joints(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("joint")) {
    const std::string kind = t.choice("kind", {"pin", "align_slope", "clamp", "fix_twist", "attach",
                                               "join", "spherical", "revolute", "fixed"});
    const std::string name = t.string_or("name", t.path());
    b.declare(t, "name", name);
    if (kind == "spherical" || kind == "revolute" || kind == "fixed")
      read_body_joint(t, b, kind, name);
    else
      read_node_joint(t, b, kind, name);
    t.finish();
  }
}

void read_drives(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("drive")) {
    const std::string name = t.string("name");
    b.declare(t, "name", name);
    const std::string joint = t.string("joint");
    if (!b.revolute_joints.count(joint))
      t.fail("joint", "no revolute joint named '" + joint +
                          "' (a drive acts on a [[joint]] of kind \"revolute\")");
    const AngleLaw reference = read_angle_law(t, "reference");
    const double kp = t.number("kp", Range::non_negative), kd = t.number("kd", Range::non_negative);
    const double torque_max = t.number("torque_max", Range::positive);
    t.finish();
    b.build(t, [&] {
      b.builder.add_revolute_drive(name, joint, reference, kp, kd, torque_max);
      b.names.drives[name] = static_cast<Index>(b.names.drives.size());
    });
  }
}

void read_loads(TableReader& root, SceneBuild& b) {
  for (TableReader& t : root.tables("load")) {
    const std::string kind =
        t.choice("kind", {"force", "distributed", "torque", "moment", "spring"});
    const std::string name = t.string_or("name", t.path());
    b.declare(t, "name", name);
    if (kind == "force") {
      const AttachmentPoint at = b.attachment(t, "at");
      const Vec3 force = t.vec3("force");
      if (std::holds_alternative<GroundPoint>(at))
        t.fail("at", "a force on ground does nothing: attach it to a cable node or a body");
      b.build(t, [&] {
        if (const auto* n = std::get_if<NodeRef>(&at))
          b.builder.add_node_force(*n, force);
        else
          b.builder.add_point_force(name, at, force);
      });
    } else if (kind == "distributed") {
      const Index cable = b.cable(t, "cable");
      const std::optional<Vec3> force = t.optional_vec3("force");
      const std::optional<Vec3> moment = t.optional_vec3("moment");
      if (!force && !moment)
        t.fail_here("a distributed load needs 'force' [N/m] or 'moment' [N m/m] (or both)");
      if (moment && !b.cable_is_rod[cable])
        t.fail("moment", "a distributed moment acts on a [[rod]] (a cable has no material triad)");
      const ElementRange range = b.element_range(t, "elements", cable);
      b.build(t, [&] {
        if (force) b.builder.add_distributed_force(name, cable, *force, range);
        if (moment) b.builder.add_distributed_moment(name, cable, *moment, range);
      });
    } else if (kind == "moment") {
      const NodeRef node = b.node(t, "at");
      if (!b.cable_is_rod[node.cable])
        t.fail("at", "a moment acts on a node of a [[rod]] (a cable node has no rotation)");
      const Vec3 moment = t.vec3("moment");
      b.build(t, [&] { b.builder.add_node_moment(node, moment); });
    } else if (kind == "torque") {
      const Index body = b.body(t, "body");
      const Vec3 torque = t.vec3("torque");
      b.build(t, [&] { b.builder.add_body_torque(name, body, torque); });
    } else {
      const AttachmentPoint p1 = b.attachment(t, "a"), p2 = b.attachment(t, "b");
      const double k = t.number("stiffness", Range::non_negative);
      const double c = t.number_or("damping", 0.0, Range::non_negative);
      const double rest = t.number_or("rest_length", -1.0, Range::non_negative);
      b.build(t, [&] { b.builder.add_spring_damper(name, p1, p2, k, c, rest); });
    }
    t.finish();
  }
}

}  // namespace ancf::io
