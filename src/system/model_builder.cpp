#include "ancf/system/model_builder.hpp"

#include <Eigen/LU>
#include <cmath>
#include <sstream>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/physics/hermite_shape.hpp"
#include "ancf/physics/joints.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"

namespace ancf {
namespace {

// Consistent nodal loads ∫ Sᵀ w dx of a uniform force per length w [N/m] on elements
// [first, first + count) of cable c, added to `load` (formulation.md, "Distributed loads").
void add_line_load(VecX& load, const CableData& c, const Vec3& w, Index first, Index count) {
  for (Index j = first; j < first + count; ++j) {
    const Vec4 weights = hermite::load_weights(c.elements[j].length);
    for (int s = 0; s < 4; ++s)
      load.segment<3>(c.first_coordinate + 6 * j + 3 * s) += weights[s] * w;
  }
}

void validate_section(const std::string& cable, const CableSection& s) {
  auto fail = [&](const std::string& what) { throw ModelError("cable '" + cable + "': " + what); };
  if (!(s.axial_stiffness > 0.0) || !std::isfinite(s.axial_stiffness))
    fail("axial stiffness EA must be > 0 N, got " + std::to_string(s.axial_stiffness));
  if (!(s.bending_stiffness >= 0.0) || !std::isfinite(s.bending_stiffness))
    fail("bending stiffness EI must be >= 0 N m^2, got " + std::to_string(s.bending_stiffness));
  if (!(s.mass_per_length > 0.0) || !std::isfinite(s.mass_per_length))
    fail("mass per length rhoA must be > 0 kg/m, got " + std::to_string(s.mass_per_length));
  if (!(s.axial_damping >= 0.0) || !(s.bending_damping >= 0.0) || !(s.mass_damping >= 0.0) ||
      !std::isfinite(s.axial_damping) || !std::isfinite(s.bending_damping) ||
      !std::isfinite(s.mass_damping))
    fail("damping coefficients must be finite and >= 0");
  if (!std::isfinite(s.prestrain) || s.prestrain <= -1.0)
    fail("prestrain must be finite and > -1, got " + std::to_string(s.prestrain));
  if (!(s.bending_damping_curvature > 0.0) || !std::isfinite(s.bending_damping_curvature))
    fail("bending damping curvature kappa_s must be finite and > 0 1/m, got " +
         std::to_string(s.bending_damping_curvature));
  for (const int points : {s.quadrature.axial, s.quadrature.bending})
    if (points < 1 || points > kMaxCableGaussPoints)
      fail("Gauss points per element must be 1 … 5, got " + std::to_string(points));
}

void validate_geometry(const std::string& cable, const CableGeometry& g) {
  if (g.element_count() < 1 || g.node_count() != g.element_count() + 1)
    throw ModelError("cable '" + cable + "': needs >= 1 element and one more node than elements");
  for (Index j = 0; j < g.element_count(); ++j) {
    if (!(g.element_lengths[j] > 0.0) || !std::isfinite(g.element_lengths[j]))
      throw ModelError("cable '" + cable + "': element " + std::to_string(j) +
                       " has a non-positive or non-finite length " +
                       std::to_string(g.element_lengths[j]));
  }
  for (Index k = 0; k < g.node_count(); ++k) {
    if (!g.nodes[k].allFinite())
      throw ModelError("cable '" + cable + "': node " + std::to_string(k) +
                       " has non-finite coordinates");
  }
}

}  // namespace

// ----------------------------------------------------------------------------------------------
// Components

void ModelBuilder::require_new_name(const std::string& name, const char* what) const {
  if (name.empty()) throw ModelError(std::string(what) + ": a name is required");
  for (const auto& c : constraints_)
    if (c.name == name)
      throw ModelError(std::string(what) + ": the name '" + name +
                       "' is already used by a constraint");
  for (const auto& c : twists_)
    if (c.name == name)
      throw ModelError(std::string(what) + ": the name '" + name +
                       "' is already used by a constraint");
  for (const auto& f : forces_)
    if (f.name == name)
      throw ModelError(std::string(what) + ": the name '" + name +
                       "' is already used by a force element");
  for (const auto& c : cable_shape_contacts_)
    if (c.name == name)
      throw ModelError(std::string(what) + ": the name '" + name +
                       "' is already used by a contact pair");
  for (const auto& c : cable_cable_contacts_)
    if (c.name == name)
      throw ModelError(std::string(what) + ": the name '" + name +
                       "' is already used by a contact pair");
}

Index ModelBuilder::add_cable(std::string name, const CableGeometry& reference,
                              const CableSection& section) {
  for (const auto& c : cables_)
    if (c.name == name) throw ModelError("cable name '" + name + "' is used twice");
  validate_section(name, section);
  validate_geometry(name, reference);
  cables_.push_back({std::move(name),
                     section,
                     reference,
                     reference,
                     std::vector<NodeCoordinates>(reference.nodes.size(), NodeCoordinates::Zero()),
                     std::nullopt,
                     {}});
  return static_cast<Index>(cables_.size()) - 1;
}

const ModelBuilder::PendingCable& ModelBuilder::cable_at(Index cable, const char* what) const {
  if (cable < 0 || cable >= static_cast<Index>(cables_.size()))
    throw ModelError(std::string(what) + ": no cable with index " + std::to_string(cable));
  return cables_[cable];
}

const ModelBuilder::PendingBody& ModelBuilder::body_at(Index body, const char* what) const {
  if (body < 0 || body >= static_cast<Index>(bodies_.size()))
    throw ModelError(std::string(what) + ": no body with index " + std::to_string(body));
  return bodies_[body];
}

void ModelBuilder::set_initial_configuration(Index cable, const CableGeometry& current,
                                             const std::vector<NodeCoordinates>* velocities) {
  cable_at(cable, "set_initial_configuration");  // validates the index
  PendingCable& c = cables_[cable];
  if (current.node_count() != c.reference.node_count())
    throw ModelError("cable '" + c.name + "': initial configuration has " +
                     std::to_string(current.node_count()) + " nodes, reference has " +
                     std::to_string(c.reference.node_count()));
  validate_geometry(c.name, current);
  if (c.rod) {
    // The node frames start as the reference triads and follow the tangent by the smallest
    // rotation, which is undefined for a tangent turned by π (kirchhoff_rod_element.hpp).
    for (Index k = 0; k < current.node_count(); ++k) {
      const Vec3 t = current.nodes[k].tail<3>().normalized();
      if (!(1.0 + t.dot(c.frames[k].col(0)) > kRodSmallestRotationDenominatorMin))
        throw ModelError("rod '" + c.name + "' node " + std::to_string(k) +
                         ": the initial tangent points against the reference tangent (turned by "
                         "π): the material frame cannot be carried over by the smallest rotation; "
                         "start from a configuration whose tangents turn by less than π from the "
                         "reference's");
    }
  }
  c.initial = current;
  if (velocities) {
    if (velocities->size() != current.nodes.size())
      throw ModelError("cable '" + c.name + "': initial velocity count differs from node count");
    c.velocities = *velocities;
  }
}

Index ModelBuilder::add_body(std::string name, const RigidBodyInertia& inertia,
                             const Vec3& position, const Mat3& rotation, const Vec3& velocity,
                             const Vec3& angular_velocity) {
  for (const auto& b : bodies_)
    if (b.name == name) throw ModelError("body name '" + name + "' is used twice");
  inertia.validate(name);
  if (!position.allFinite() || !velocity.allFinite() || !angular_velocity.allFinite())
    throw ModelError("body '" + name + "': non-finite initial pose or twist");
  if ((rotation.transpose() * rotation - Mat3::Identity()).norm() > 1e-10 ||
      rotation.determinant() < 0.0)
    throw ModelError("body '" + name + "': initial rotation is not a proper orthonormal matrix");
  bodies_.push_back({std::move(name), inertia, position, rotation, velocity, angular_velocity});
  return static_cast<Index>(bodies_.size()) - 1;
}

int ModelBuilder::add_driven_frame(DrivenFrame frame) {
  if (!(frame.axis.norm() > 0.0) || !frame.axis.allFinite())
    throw ModelError("driven frame '" + frame.name +
                     "': the axis must be a non-zero finite vector");
  const Mat3& a0 = frame.initial_rotation;
  if ((a0.transpose() * a0 - Mat3::Identity()).norm() > 1e-10 || a0.determinant() < 0.0)
    throw ModelError("driven frame '" + frame.name +
                     "': initial rotation is not a proper orthonormal matrix");
  frames_.push_back(std::move(frame));
  return static_cast<int>(frames_.size()) - 1;
}

NodeRef ModelBuilder::resolve(NodeRef node, const char* what) const {
  const PendingCable& c = cable_at(node.cable, what);
  const Index n = c.reference.node_count();
  const Index k = node.node < 0 ? n + node.node : node.node;
  if (k < 0 || k >= n)
    throw ModelError(std::string(what) + ": cable '" + c.name + "' has no node " +
                     std::to_string(node.node) + " (it has " + std::to_string(n) + ")");
  return {node.cable, k};
}

const NodeCoordinates& ModelBuilder::initial_node(NodeRef node) const {
  return cables_[node.cable].initial.nodes[node.node];
}

// ----------------------------------------------------------------------------------------------
// Loads and force elements

void ModelBuilder::add_node_force(NodeRef node, const Vec3& force) {
  node = resolve(node, "add_node_force");
  if (!force.allFinite()) throw ModelError("add_node_force: non-finite force");
  node_forces_.emplace_back(node, force);
}

void ModelBuilder::add_distributed_force(const std::string& name, Index cable,
                                         const Vec3& force_per_length, ElementRange range) {
  const PendingCable& c = cable_at(cable, "add_distributed_force");
  if (!force_per_length.allFinite())
    throw ModelError("distributed force '" + name + "': non-finite force per length");
  const auto [first, count] = resolve_element_range("distributed force '" + name + "'", c.name,
                                                    range, c.reference.element_count());
  distributed_forces_.push_back({cable, first, count, force_per_length});
}

AffineVector ModelBuilder::point_expression(const AttachmentPoint& p, const Offsets& o) {
  AffineVector a;
  if (const auto* g = std::get_if<GroundPoint>(&p)) {
    a.offset = g->position;
  } else if (const auto* n = std::get_if<NodeRef>(&p)) {
    a.add(o.node(*n), 1.0);
  } else if (const auto* b = std::get_if<BodyPoint>(&p)) {
    a.add_body(o.body(b->body), point_weights(b->position));
  } else {
    const auto& f = std::get<FramePoint>(p);
    a.frame = f.frame;
    a.frame_position_scale = 1.0;
    a.frame_vector = f.position;
  }
  return a;
}

Vec3 ModelBuilder::point_position(const AttachmentPoint& p) const {
  if (const auto* g = std::get_if<GroundPoint>(&p)) return g->position;
  if (const auto* n = std::get_if<NodeRef>(&p)) return initial_node(*n).head<3>();
  if (const auto* b = std::get_if<BodyPoint>(&p))
    return bodies_[b->body].position + bodies_[b->body].rotation * b->position;
  const auto& f = std::get<FramePoint>(p);
  const FrameKinematics k = frames_[f.frame].at(0.0);
  return k.r + k.a * f.position;
}

namespace {
// Validate indices inside an attachment point (and normalise node indices).
AttachmentPoint checked(const AttachmentPoint& p, const std::function<NodeRef(NodeRef)>& node,
                        Index body_count, int frame_count, const std::string& what) {
  if (const auto* n = std::get_if<NodeRef>(&p)) return node(*n);
  if (const auto* b = std::get_if<BodyPoint>(&p)) {
    if (b->body < 0 || b->body >= body_count)
      throw ModelError(what + ": no body " + std::to_string(b->body));
  }
  if (const auto* f = std::get_if<FramePoint>(&p)) {
    if (f->frame < 0 || f->frame >= frame_count)
      throw ModelError(what + ": no driven frame " + std::to_string(f->frame));
  }
  return p;
}
}  // namespace

void ModelBuilder::add_point_force(std::string name, const AttachmentPoint& point,
                                   const Vec3& force, std::function<Vec3(double)> time_function) {
  require_new_name(name, "add_point_force");
  const AttachmentPoint p = checked(
      point, [&](NodeRef n) { return resolve(n, "add_point_force"); },
      static_cast<Index>(bodies_.size()), static_cast<int>(frames_.size()),
      "point force '" + name + "'");
  if (!force.allFinite()) throw ModelError("point force '" + name + "': non-finite force");
  forces_.push_back({name, [name, p, force, time_function](const Offsets& o, Model& m) {
                       PointForce e{point_expression(p, o), force, time_function};
                       m.point_forces_.push_back({name, e, blocks_of(e), {}});
                     }});
}

void ModelBuilder::add_body_torque(std::string name, Index body, const Vec3& torque,
                                   std::function<Vec3(double)> time_function) {
  require_new_name(name, "add_body_torque");
  body_at(body, "add_body_torque");
  forces_.push_back({name, [name, body, torque, time_function](const Offsets& o, Model& m) {
                       BodyTorque e{o.body(body), torque, time_function};
                       m.torques_.push_back({name, e, blocks_of(e), {}});
                     }});
}

void ModelBuilder::add_spring_damper(std::string name, const AttachmentPoint& a,
                                     const AttachmentPoint& b, double stiffness, double damping,
                                     double rest_length) {
  require_new_name(name, "add_spring_damper");
  auto node = [&](NodeRef n) { return resolve(n, "add_spring_damper"); };
  const std::string what = "spring-damper '" + name + "'";
  const AttachmentPoint pa =
      checked(a, node, static_cast<Index>(bodies_.size()), static_cast<int>(frames_.size()), what);
  const AttachmentPoint pb =
      checked(b, node, static_cast<Index>(bodies_.size()), static_cast<int>(frames_.size()), what);
  if (!(stiffness >= 0.0) || !(damping >= 0.0))
    throw ModelError(what + ": stiffness and damping must be >= 0");
  const double initial = (point_position(pb) - point_position(pa)).norm();
  if (!(initial > 0.0))
    throw ModelError(what + ": its end points coincide initially (zero length)");
  const double l0 = rest_length < 0.0 ? initial : rest_length;
  forces_.push_back(
      {name, [name, pa, pb, stiffness, damping, l0](const Offsets& o, Model& m) {
         SpringDamper e{point_expression(pa, o), point_expression(pb, o), stiffness, damping, l0};
         m.springs_.push_back({name, e, blocks_of(e), {}});
       }});
}

void ModelBuilder::add_revolute_drive(std::string name, const std::string& joint,
                                      AngleLaw reference, double kp, double kd, double torque_max) {
  require_new_name(name, "add_revolute_drive");
  const RevoluteInfo* info = nullptr;
  for (const RevoluteInfo& r : revolutes_)
    if (r.name == joint) info = &r;
  if (!info) throw ModelError("drive '" + name + "': no revolute joint named '" + joint + "'");
  if (!(torque_max > 0.0) || !(kp >= 0.0) || !(kd >= 0.0))
    throw ModelError("drive '" + name + "': need torque_max > 0, kp >= 0, kd >= 0");
  Vec3 e1, e2;
  perpendicular_pair(info->axis, e1, e2);  // (e1, e2, axis) right-handed
  const RevoluteInfo r = *info;
  const Mat3 a_body = bodies_[r.body].rotation;
  const Mat3 a_base = r.base_body >= 0 ? bodies_[r.base_body].rotation : Mat3::Identity();
  forces_.push_back(
      {name, [=](const Offsets& o, Model& m) {
         RevoluteDrive e;
         e.d.add_body(o.body(r.body), direction_weights(a_body.transpose() * e1));
         if (r.base_body >= 0) {
           e.e1.add_body(o.body(r.base_body), direction_weights(a_base.transpose() * e1));
           e.e2.add_body(o.body(r.base_body), direction_weights(a_base.transpose() * e2));
         } else {
           e.e1 = AffineVector::constant(e1);
           e.e2 = AffineVector::constant(e2);
         }
         e.reference = reference;
         e.kp = kp;
         e.kd = kd;
         e.torque_max = torque_max;
         m.drives_.push_back({name, e, blocks_of(e), {}});
       }});
}

// ----------------------------------------------------------------------------------------------
// Constraints

void ModelBuilder::add_constraint(std::string name,
                                  std::function<ConstraintRows(const Offsets&)> rows) {
  require_new_name(name, "constraint");
  constraints_.push_back({std::move(name), std::move(rows)});
}

void ModelBuilder::pin(std::string name, NodeRef node, const Vec3& target) {
  node = resolve(node, "pin");
  add_constraint(std::move(name),
                 [=](const Offsets& o) { return node_position_to_ground(o.node(node), target); });
}

void ModelBuilder::align_slope(std::string name, NodeRef node, const Vec3& direction) {
  node = resolve(node, "align_slope");
  if (!(direction.norm() > 0.0)) throw ModelError("align_slope '" + name + "': zero direction");
  add_constraint(std::move(name),
                 [=](const Offsets& o) { return node_slope_to_ground(o.node(node), direction); });
}

void ModelBuilder::attach_node_to_body(std::string name, NodeRef node, Index body) {
  node = resolve(node, "attach_node_to_body");
  const PendingBody& b = body_at(body, "attach_node_to_body");
  const Vec3 p = b.rotation.transpose() * (initial_node(node).head<3>() - b.position);
  add_constraint(std::move(name), [=](const Offsets& o) {
    return node_position_to_body(o.node(node), o.body(body), p);
  });
}

void ModelBuilder::align_slope_to_body(std::string name, NodeRef node, Index body) {
  node = resolve(node, "align_slope_to_body");
  const PendingBody& b = body_at(body, "align_slope_to_body");
  const Vec3 d = b.rotation.transpose() * initial_node(node).tail<3>();
  add_constraint(std::move(name), [=](const Offsets& o) {
    return node_slope_to_body(o.node(node), o.body(body), d);
  });
}

void ModelBuilder::attach_node_to_frame(std::string name, NodeRef node, int frame) {
  node = resolve(node, "attach_node_to_frame");
  if (frame < 0 || frame >= static_cast<int>(frames_.size()))
    throw ModelError("attach_node_to_frame '" + name + "': no driven frame " +
                     std::to_string(frame));
  const FrameKinematics k = frames_[frame].at(0.0);
  const Vec3 p = k.a.transpose() * (initial_node(node).head<3>() - k.r);
  add_constraint(std::move(name),
                 [=](const Offsets& o) { return node_position_to_frame(o.node(node), frame, p); });
}

void ModelBuilder::align_slope_to_frame(std::string name, NodeRef node, int frame) {
  node = resolve(node, "align_slope_to_frame");
  if (frame < 0 || frame >= static_cast<int>(frames_.size()))
    throw ModelError("align_slope_to_frame '" + name + "': no driven frame " +
                     std::to_string(frame));
  const Vec3 d = frames_[frame].at(0.0).a.transpose() * initial_node(node).tail<3>();
  add_constraint(std::move(name),
                 [=](const Offsets& o) { return node_slope_to_frame(o.node(node), frame, d); });
}

void ModelBuilder::join_nodes(std::string name, NodeRef a, NodeRef b, bool slopes) {
  a = resolve(a, "join_nodes");
  b = resolve(b, "join_nodes");
  add_constraint(std::move(name), [=](const Offsets& o) {
    ConstraintRows rows = node_to_node(o.node(a), o.node(b));
    if (slopes) {
      const ConstraintRows s = node_slope_to_node_slope(o.node(a), o.node(b));
      for (int k = 0; k < s.count; ++k) rows.add() = s.rows[k];
    }
    return rows;
  });
}

void ModelBuilder::spherical_to_ground(std::string name, Index body, const Vec3& point) {
  const PendingBody& b = body_at(body, "spherical_to_ground");
  const Vec3 p = b.rotation.transpose() * (point - b.position);
  add_constraint(std::move(name), [=](const Offsets& o) {
    return body_spherical_to_ground(o.body(body), p, point);
  });
}

void ModelBuilder::revolute_to_ground(std::string name, Index body, const Vec3& point,
                                      const Vec3& axis) {
  const PendingBody& b = body_at(body, "revolute_to_ground");
  if (!(axis.norm() > 0.0)) throw ModelError("revolute_to_ground '" + name + "': zero axis");
  const Vec3 p = b.rotation.transpose() * (point - b.position);
  const Vec3 n = axis.normalized(), u = b.rotation.transpose() * n;
  revolutes_.push_back({name, -1, body, n});
  add_constraint(std::move(name), [=](const Offsets& o) {
    return body_revolute_to_ground(o.body(body), p, u, point, n);
  });
}

void ModelBuilder::fixed_to_ground(std::string name, Index body) {
  const PendingBody& b = body_at(body, "fixed_to_ground");
  const Vec3 r = b.position;
  const Mat3 a = b.rotation;
  add_constraint(std::move(name), [=](const Offsets& o) {
    return body_fixed_to_ground(o.body(body), Vec3::Zero(), r, a);
  });
}

void ModelBuilder::spherical(std::string name, Index body1, Index body2, const Vec3& point) {
  const PendingBody& b1 = body_at(body1, "spherical");
  const PendingBody& b2 = body_at(body2, "spherical");
  const Vec3 p1 = b1.rotation.transpose() * (point - b1.position);
  const Vec3 p2 = b2.rotation.transpose() * (point - b2.position);
  add_constraint(std::move(name), [=](const Offsets& o) {
    return body_spherical(o.body(body1), p1, o.body(body2), p2);
  });
}

void ModelBuilder::revolute(std::string name, Index body1, Index body2, const Vec3& point,
                            const Vec3& axis) {
  const PendingBody& b1 = body_at(body1, "revolute");
  const PendingBody& b2 = body_at(body2, "revolute");
  if (!(axis.norm() > 0.0)) throw ModelError("revolute '" + name + "': zero axis");
  const Vec3 n = axis.normalized();
  const Vec3 p1 = b1.rotation.transpose() * (point - b1.position);
  const Vec3 p2 = b2.rotation.transpose() * (point - b2.position);
  const Vec3 u1 = b1.rotation.transpose() * n, u2 = b2.rotation.transpose() * n;
  revolutes_.push_back({name, body1, body2, n});
  add_constraint(std::move(name), [=](const Offsets& o) {
    return body_revolute(o.body(body1), p1, u1, o.body(body2), p2, u2);
  });
}

void ModelBuilder::fixed(std::string name, Index body1, Index body2) {
  const PendingBody& b1 = body_at(body1, "fixed");
  const PendingBody& b2 = body_at(body2, "fixed");
  const Vec3 p1 = b1.rotation.transpose() * (b2.position - b1.position);
  const Mat3 rel = b1.rotation.transpose() * b2.rotation;
  add_constraint(std::move(name), [=](const Offsets& o) {
    return body_fixed(o.body(body1), p1, o.body(body2), Vec3::Zero(), rel);
  });
}

// ----------------------------------------------------------------------------------------------
// finalize

Model ModelBuilder::finalize() {
  Model m;
  Offsets o;
  Index next = 0;
  for (const PendingCable& pc : cables_) {
    CableData c;
    c.name = pc.name;
    c.section = pc.section;
    const Index twist_first = pc.rod ? next : -1;
    if (pc.rod)  // twist block in front of the centreline
      next += rod_twist_block_size(pc.rod->twist, pc.reference.node_count());
    o.twist_first.push_back(twist_first);
    c.first_coordinate = next;
    c.node_count = pc.reference.node_count();
    for (Index j = 0; j < pc.reference.element_count(); ++j) {
      const double l = pc.reference.element_lengths[j];
      // Named, so that the scene loader can point at the cable's table.
      const std::string element =
          std::string(pc.rod ? "rod '" : "cable '") + pc.name + "' element " + std::to_string(j);
      try {
        c.elements.push_back(CableElementReference::from_reference(
            pc.reference.element_coordinates(j), l, pc.section.strain, pc.section.quadrature));
      } catch (const ModelError& e) {
        throw ModelError(element + ": " + e.what());
      }
      c.mass.push_back(hermite::mass_matrix(pc.section.mass_per_length, l));
      // ρA l³ terms overflow for lengths far beyond any structure (found by the fuzzer).
      if (!c.mass.back().allFinite()) {
        std::ostringstream length;
        length << l;
        throw ModelError(element + ": its mass matrix is not finite in double precision (length " +
                         length.str() + " m)");
      }
    }
    if (pc.rod) c.rod = make_rod_data(pc, c, twist_first);
    o.cable_first.push_back(next);
    next += 6 * c.node_count;
    m.cables_.push_back(std::move(c));
  }
  for (const PendingBody& pb : bodies_) {
    m.bodies_.push_back({pb.name, pb.inertia, next, natural_mass_matrix(pb.inertia)});
    o.body_first.push_back(next);
    next += 12;
  }
  m.n_coordinates_ = next;
  m.frames_ = frames_;

  // Initial state and constant loads.
  m.q0_ = VecX::Zero(next);
  m.v0_ = VecX::Zero(next);
  m.constant_load_ = VecX::Zero(next);
  for (std::size_t ci = 0; ci < cables_.size(); ++ci) {
    const PendingCable& pc = cables_[ci];
    const CableData& c = m.cables_[ci];
    for (Index k = 0; k < c.node_count; ++k) {
      m.q0_.segment<6>(c.first_coordinate + 6 * k) = pc.initial.nodes[k];
      m.v0_.segment<6>(c.first_coordinate + 6 * k) = pc.velocities[k];
    }
    if (gravity_.squaredNorm() > 0.0)  // consistent gravity ρA ∫ Sᵀ g dx
      add_line_load(m.constant_load_, c, c.section.mass_per_length * gravity_, 0,
                    static_cast<Index>(c.elements.size()));
  }
  for (const DistributedForceData& d : distributed_forces_)
    add_line_load(m.constant_load_, m.cables_[d.cable], d.force_per_length, d.first, d.count);
  m.distributed_forces_ = distributed_forces_;
  for (std::size_t bi = 0; bi < bodies_.size(); ++bi) {
    const PendingBody& pb = bodies_[bi];
    const Index b = m.bodies_[bi].first_coordinate;
    m.q0_.segment<12>(b) = body_coordinates(pb.position, pb.rotation);
    m.v0_.segment<12>(b) = body_velocities(pb.rotation, pb.velocity, pb.angular_velocity);
    // Gravity m g at the centre of mass r_O + Σ c̄_k a_k: blocks m c(c̄)_k g.
    const Vec4 c = point_weights(pb.inertia.centre_of_mass);
    for (int k = 0; k < 4; ++k)
      m.constant_load_.segment<3>(b + 3 * k) += pb.inertia.mass * c[k] * gravity_;
  }
  for (const auto& [node, force] : node_forces_) {
    m.constant_load_.segment<3>(o.node(node)) += force;
    m.node_forces_.push_back({node.cable, node.node, force});
  }

  // Constraint rows: each body's orthonormality first, then the user's constraints in order, so
  // that a redundant user constraint is the one reported.
  auto push_rows = [&](const std::string& name, const ConstraintRows& rows) {
    m.constraints_.push_back({name, next + static_cast<Index>(m.rows_.size()), rows.count});
    for (int k = 0; k < rows.count; ++k) m.rows_.push_back(rows.rows[k]);
  };
  for (const BodyData& b : m.bodies_)
    push_rows(b.name + ".orthonormality", body_orthonormality(b.first_coordinate));
  for (const PendingConstraint& pc : constraints_) push_rows(pc.name, pc.rows(o));
  // Twist rows of rods (not bilinear) after all dot rows: multipliers rows_.size() + k.
  for (const PendingTwist& pt : twists_) {
    RodTwistRowData d;
    d.row.slope = o.node(pt.node) + 3;
    d.row.twist = o.twist(pt.node);
    d.row.b = pt.b(o);
    d.cable = pt.node.cable;
    d.node = pt.node.node;
    m.constraints_.push_back(
        {pt.name, next + static_cast<Index>(m.rows_.size() + m.twist_rows_.size()), 1});
    m.twist_rows_.push_back(d);
  }
  for (const PendingForce& f : forces_) f.add(o, m);
  for (const auto& [node, moment] : node_moments_) {
    RodMomentData d{node.cable, node.node, moment, {}, {}};
    for (int k = 0; k < 3; ++k) d.coordinates[k] = o.node(node) + 3 + k;
    d.coordinates[3] = o.twist(node);
    m.rod_moments_.push_back(d);
  }
  m.rod_distributed_moments_ = distributed_moments_;
  finalize_contacts(o, m);

  check_redundancy(m);
  build_pattern_and_slots(m);
  *this = ModelBuilder{};
  return m;
}

}  // namespace ancf
