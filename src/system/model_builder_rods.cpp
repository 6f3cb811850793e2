// The rod parts of ModelBuilder: adding a Kirchhoff rod, its end moments and twist conditions,
// and its per-element data at finalize() (kirchhoff_rod_element.hpp, docs/rod.md).
#include <cmath>
#include <stdexcept>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/physics/joints.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf {
namespace {

void validate_rod(const std::string& name, const RodSection& r) {
  auto fail = [&](const std::string& what) { throw ModelError("rod '" + name + "': " + what); };
  auto positive = [&](double x, const char* key) {
    if (!(x > 0.0) || !std::isfinite(x)) fail(std::string(key) + " must be finite and > 0");
  };
  auto non_negative = [&](double x, const char* key) {
    if (!(x >= 0.0) || !std::isfinite(x)) fail(std::string(key) + " must be finite and >= 0");
  };
  positive(r.axial_stiffness, "EA");
  positive(r.torsional_stiffness, "GJ");
  non_negative(r.bending_stiffness_2, "EI2");
  non_negative(r.bending_stiffness_3, "EI3");
  positive(r.mass_per_length, "rhoA");
  positive(r.polar_inertia, "rhoJ (the twist needs a rotary inertia, else M is singular)");
  non_negative(r.axial_damping, "axial damping");
  non_negative(r.torsional_damping, "torsional damping");
  non_negative(r.bending_damping, "bending damping");
}

// A single-coordinate row q[k] − value = 0, as the dot row q[k : k+3]·e_x − value. The two
// coordinates after k get zero gradient entries (the twist block is followed by the centreline).
DotConstraintRow coordinate_row(Index k, double coefficient_other_k, Index other) {
  DotConstraintRow row;
  row.u.add(k, 1.0);
  if (other >= 0) row.u.add(other, coefficient_other_k);
  row.w = AffineVector::constant(Vec3::UnitX());
  return row;
}

}  // namespace

Index ModelBuilder::add_rod(std::string name, const CableGeometry& reference, CableSection section,
                            const RodSection& rod, const std::vector<Mat3>& frames) {
  validate_rod(name, rod);
  if (static_cast<Index>(frames.size()) != reference.node_count())
    throw ModelError("rod '" + name + "': needs one reference frame per node (" +
                     std::to_string(reference.node_count()) + "), got " +
                     std::to_string(frames.size()));
  section.axial_stiffness = rod.axial_stiffness;
  section.bending_stiffness = 0.0;
  section.axial_damping = section.bending_damping = 0.0;
  section.mass_per_length = rod.mass_per_length;
  const Index c = add_cable(name, reference, section);
  cables_[c].rod = rod;
  cables_[c].frames = frames;
  return c;
}

void ModelBuilder::add_node_moment(NodeRef node, const Vec3& moment) {
  node = resolve(node, "add_node_moment");
  if (!cables_[node.cable].rod)
    throw ModelError("add_node_moment: cable '" + cables_[node.cable].name +
                     "' is not a rod (a cable node has no rotation to load)");
  if (!moment.allFinite()) throw ModelError("add_node_moment: non-finite moment");
  node_moments_.emplace_back(node, moment);
}

void ModelBuilder::add_distributed_moment(const std::string& name, Index cable,
                                          const Vec3& moment_per_length, ElementRange range) {
  const PendingCable& c = cable_at(cable, "add_distributed_moment");
  if (!c.rod)
    throw ModelError("distributed moment '" + name + "': cable '" + c.name +
                     "' is not a rod (a cable has no material triad to load)");
  if (!moment_per_length.allFinite())
    throw ModelError("distributed moment '" + name + "': non-finite moment per length");
  const auto [first, count] = resolve_element_range("distributed moment '" + name + "'", c.name,
                                                    range, c.reference.element_count());
  distributed_moments_.push_back({cable, first, count, moment_per_length});
}

void ModelBuilder::fix_twist(std::string name, NodeRef node) {
  node = resolve(node, "fix_twist");
  if (!cables_[node.cable].rod)
    throw ModelError("fix_twist '" + name + "': cable '" + cables_[node.cable].name +
                     "' is not a rod");
  add_constraint(std::move(name), [=](const Offsets& o) {
    ConstraintRows rows;
    rows.add() = coordinate_row(o.twist(node), 0.0, -1);  // α₀ = 0
    return rows;
  });
}

void ModelBuilder::join_twist(std::string name, NodeRef a, NodeRef b) {
  a = resolve(a, "join_twist");
  b = resolve(b, "join_twist");
  for (const NodeRef n : {a, b})
    if (!cables_[n.cable].rod)
      throw ModelError("join_twist '" + name + "': cable '" + cables_[n.cable].name +
                       "' is not a rod");
  const Mat3& fa = cables_[a.cable].frames[a.node];
  const Mat3& fb = cables_[b.cable].frames[b.node];
  if ((fa - fb).norm() > 1e-9)
    throw ModelError("join_twist '" + name +
                     "': the two nodes' reference frames differ; joined twist angles would not "
                     "make their material frames coincide");
  add_constraint(std::move(name), [=](const Offsets& o) {
    ConstraintRows rows;
    rows.add() = coordinate_row(o.twist(a), -1.0, o.twist(b));
    return rows;
  });
}

Mat3 ModelBuilder::initial_rod_triad(NodeRef node, const char* what) const {
  const PendingCable& c = cables_[node.cable];
  if (!c.rod) throw ModelError(std::string(what) + ": cable '" + c.name + "' is not a rod");
  return smallest_rotation(c.frames[node.node], initial_node(node).tail<3>());
}

void ModelBuilder::tie_twist_to_body(std::string name, NodeRef node, Index body) {
  node = resolve(node, "tie_twist_to_body");
  const Mat3 triad = initial_rod_triad(node, "tie_twist_to_body");
  const PendingBody& pb = body_at(body, "tie_twist_to_body");
  const Vec3 b_body = pb.rotation.transpose() * triad.col(2);  // d₃ in body coordinates
  require_new_name(name, "constraint");
  twists_.push_back({std::move(name), node, [=](const Offsets& o) {
                       AffineVector b;
                       return b.add_body(o.body(body), direction_weights(b_body));
                     }});
}

void ModelBuilder::tie_twist_to_frame(std::string name, NodeRef node, int frame) {
  node = resolve(node, "tie_twist_to_frame");
  const Mat3 triad = initial_rod_triad(node, "tie_twist_to_frame");
  if (frame < 0 || frame >= static_cast<int>(frames_.size()))
    throw ModelError("tie_twist_to_frame '" + name + "': no driven frame " + std::to_string(frame));
  const Vec3 b_frame = frames_[frame].at(0.0).a.transpose() * triad.col(2);
  require_new_name(name, "constraint");
  twists_.push_back({std::move(name), node, [=](const Offsets&) {
                       AffineVector b;
                       b.frame = frame;
                       b.frame_vector = b_frame;
                       return b;
                     }});
}

RodData ModelBuilder::make_rod_data(const PendingCable& pc, const CableData& c, Index twist_first) {
  RodData d;
  d.section = *pc.rod;
  d.twist_first = twist_first;
  if (pc.rod->twist == RodTwist::quadratic) d.interior_first = twist_first + c.node_count;
  d.reference_frames = pc.frames;
  for (Index j = 0; j < pc.reference.element_count(); ++j) {
    RodElementHistory h{pc.frames[j], pc.frames[j + 1], 0.0};
    const double l = pc.reference.element_lengths[j];
    try {
      d.elements.push_back(
          RodElementReference::from_reference(pc.reference.element_coordinates(j), l, h));
    } catch (const ModelError& e) {
      throw ModelError("rod '" + c.name + "' element " + std::to_string(j) + ": " + e.what());
    } catch (const std::domain_error& e) {
      // The smallest rotation from the node frame is undefined where the reference tangent
      // points against it: the element's cubic turns over (e.g. an arc of 2π per element, whose
      // end points coincide, or any reference that turns by about π or more in one element).
      throw ModelError("rod '" + c.name + "' element " + std::to_string(j) +
                       ": its reference centreline turns over within the element (" + e.what() +
                       "); use more elements, each turning well below π");
    }
    d.reference_omega.push_back(h.omega);
    d.twist_mass.push_back(rod_twist_mass(pc.rod->polar_inertia, l));
  }
  return d;
}

}  // namespace ancf
