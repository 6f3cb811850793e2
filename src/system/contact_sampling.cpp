#include "contact_sampling.hpp"

#include <algorithm>
#include <limits>
#include <optional>

#include "ancf/physics/hermite_shape.hpp"
#include "ancf/system/contact_pattern.hpp"
#include "contact_bounds.hpp"

namespace ancf::detail {

// Pose of a shape's owner at the current state: ground (identity), driven frame (prescribed), or
// rigid body (read from its natural coordinates; P then includes the body's 12 coordinates).
ShapeOwnerPose owner_pose(const ContactShapeData& s, const SystemState& state,
                          std::span<const FrameKinematics> frames) {
  ShapeOwnerPose pose;
  switch (s.owner) {
    case ContactShapeData::Owner::ground:
      break;
    case ContactShapeData::Owner::frame: {
      const FrameKinematics& f = frames[s.owner_index];
      pose.origin = f.r;
      pose.origin_velocity = f.r_dot;
      pose.rotation = f.a;
      pose.rotation_rate = f.a_dot;
      break;
    }
    case ContactShapeData::Owner::body: {
      const Index b = s.body_coordinate;
      pose.origin = state.q.segment<3>(b);
      pose.origin_velocity = state.v.segment<3>(b);
      for (int k = 0; k < 3; ++k) {
        pose.rotation.col(k) = state.q.segment<3>(b + 3 + 3 * k);
        pose.rotation_rate.col(k) = state.v.segment<3>(b + 3 + 3 * k);
      }
      pose.is_body = true;
      break;
    }
  }
  return pose;
}

ShapeBroadPhase::ShapeBroadPhase(const ContactShape& s, const ShapeOwnerPose& p)
    : shape(s), pose(p) {
  if (const auto* sphere = std::get_if<SphereShape>(&s))
    box = shape_bounding_box(*sphere, p.origin, p.rotation);
  if (const auto* cyl = std::get_if<CappedCylinderShape>(&s))
    box = shape_bounding_box(*cyl, p.origin, p.rotation);
}

bool ShapeBroadPhase::may_touch(const Aabb& element_box) const {
  if (const auto* plane = std::get_if<PlaneShape>(&shape))
    return may_touch_plane(*plane, pose.origin, pose.rotation, element_box);
  return element_box.overlaps(box);
}

// Whole-cable boxes of every cable that takes part in a contact pair: the box of the Bézier
// control points of all its elements (each element's box is that of its four control points, and
// the end point of one element is the start of the next). The element boxes come out of the same
// pass (element_bounding_box's arithmetic), so pairs that are far apart cost one pass over the
// nodes per cable and call, and pairs that pass need no second one.
void refresh_cable_boxes(const Model& model, const SystemState& state, Workspace& ws) {
  for (std::size_t c = 0; c < ws.element_boxes.size(); ++c) {
    if (ws.element_boxes[c].empty()) continue;
    const CableData& cable = model.cables()[c];
    Vec3 lower = state.q.segment<3>(cable.first_coordinate), upper = lower;
    for (std::size_t j = 0; j < cable.elements.size(); ++j) {
      const Index base = cable.first_coordinate + 6 * static_cast<Index>(j);
      const double third = cable.elements[j].length / 3.0;
      const Vec3 start = state.q.segment<3>(base);
      const Vec3 a = start + third * state.q.segment<3>(base + 3);
      const Vec3 b = state.q.segment<3>(base + 6) - third * state.q.segment<3>(base + 9);
      const Vec3 end = state.q.segment<3>(base + 6);
      Aabb& box = ws.element_boxes[c][j];
      box.lower = start.cwiseMin(a).cwiseMin(b).cwiseMin(end);
      box.upper = start.cwiseMax(a).cwiseMax(b).cwiseMax(end);
      ws.element_deviations[c][j] = -1.0;  // computed on demand (stored_hull)
      lower = lower.cwiseMin(box.lower);
      upper = upper.cwiseMax(box.upper);
    }
    ws.cable_boxes[c].lower = lower;
    ws.cable_boxes[c].upper = upper;
    ws.element_boxes_current[c] = 1;
  }
}

// Element boxes of one cable at the current state (computed at most once per refresh).
const std::vector<Aabb>& element_boxes_of(const Model& model, const SystemState& state,
                                          Workspace& ws, Index c) {
  auto& boxes = ws.element_boxes[c];
  if (!ws.element_boxes_current[c]) {
    const CableData& cable = model.cables()[c];
    for (std::size_t j = 0; j < boxes.size(); ++j)
      boxes[j] = element_bounding_box(
          state.q.segment<12>(cable.first_coordinate + 6 * static_cast<Index>(j)),
          cable.elements[j].length);
    ws.element_boxes_current[c] = 1;
  }
  return boxes;
}

CableSample sample_of(const CableData& cable, Index element, int k, int samples,
                      const SystemState& state) {
  CableSample s;
  const Index base = cable.first_coordinate + 6 * element;
  s.e = state.q.segment<12>(base);
  s.e_dot = state.v.segment<12>(base);
  s.length = cable.elements[element].length;
  s.xi = (k + 0.5) / samples;
  s.weight = s.length / samples;
  s.radius = cable.section.radius;
  return s;
}

namespace {

// The hull of element j of cable c from the boxes of the last refresh_cable_boxes (which must have
// been at `state`); its chord deviation is computed at the first request after the refresh.
ElementHull stored_hull(const Model& model, const SystemState& state, Workspace& ws, Index c,
                        Index j) {
  const CableData& cable = model.cables()[c];
  const Index base = cable.first_coordinate + 6 * j;
  const double third = cable.elements[j].length / 3.0;
  ElementHull h;
  h.start = state.q.segment<3>(base);
  h.end = state.q.segment<3>(base + 6);
  h.p1 = h.start + third * state.q.segment<3>(base + 3);
  h.p2 = h.end - third * state.q.segment<3>(base + 9);
  double& deviation = ws.element_deviations[c][j];
  if (deviation < 0.0) deviation = chord_deviation(h.start, h.p1, h.p2, h.end);
  h.deviation = deviation;
  h.box = ws.element_boxes[c][j];
  return h;
}

void visit_cable_shape(const Model& model, const SystemState& state, Workspace& ws,
                       ContactVisit how, Index pair, ContactSink& sink) {
  const CableShapeContactData& c = model.cable_shape_contacts()[pair];
  const ContactShapeData& shape = model.shapes()[c.shape];
  const CableData& cable = model.cables()[c.cable];
  const ShapeOwnerPose pose = owner_pose(shape, state, ws.frames_at(model, state.t));
  const ShapeBroadPhase broad(shape.shape, pose);
  // Whole-cable test first: a pair that cannot touch costs O(1) beyond the box refresh.
  if (!how.all_samples && !broad.may_touch(inflated(ws.cable_boxes[c.cable], cable.section.radius)))
    return;
  const std::vector<Aabb>* boxes =
      how.all_samples ? nullptr : &element_boxes_of(model, state, ws, c.cable);
  ContactSampleBlocks blocks;
  blocks.pair = pair;
  blocks.cable = c.cable;
  const bool body = shape.owner == ContactShapeData::Owner::body;
  if (body)
    blocks.first_b = shape.body_coordinate, blocks.bb = &model.body_slots(shape.owner_index);
  const bool hull_test = !how.all_samples && ws.hull_broad_phase;
  std::optional<ShapeDistanceBound> hull_bound;  // made for the first element past the box test
  for (Index local = 0; local < c.count; ++local) {
    const Index j = c.first + local;
    if (!how.all_samples && !broad.may_touch(inflated((*boxes)[j], cable.section.radius))) continue;
    // Second level: an element whose centreline provably keeps a gap ≥ 0 everywhere
    // (contact_bounds.hpp) has no active sample.
    if (hull_test) {
      if (!hull_bound) hull_bound.emplace(shape.shape, pose);
      if ((*hull_bound)(stored_hull(model, state, ws, c.cable, j)) >= cable.section.radius)
        continue;
    }
    blocks.first_a = cable.first_coordinate + 6 * j;
    blocks.aa = &model.element_slots(c.cable, j);
    if (body) {
      const Index k = ws.coupling ? ws.coupling->shape_block[pair][local] : -1;
      blocks.ab = k >= 0 ? &ws.coupling->blocks[2 * k] : nullptr;
      blocks.ba = k >= 0 ? &ws.coupling->blocks[2 * k + 1] : nullptr;
    }
    for (int k = 0; k < c.samples; ++k) {
      const CableSample s = sample_of(cable, j, k, c.samples, state);
      ++ws.narrow_phase_samples;
      if (evaluate_cable_shape_contact(c.law, shape.shape, pose, s, how.jacobians, ws.contact) ||
          how.all_samples)
        sink.add(ws.contact, blocks);
    }
  }
}

void visit_cable_cable(const Model& model, const SystemState& state, Workspace& ws,
                       ContactVisit how, Index pair, ContactSink& sink) {
  const CableCableContactData& c = model.cable_cable_contacts()[pair];
  const CableData& a = model.cables()[c.cable_a];
  const CableData& b = model.cables()[c.cable_b];
  const double reach = a.section.radius + b.section.radius;
  const Index nb = c.count_b;
  if (!how.all_samples &&
      !inflated(ws.cable_boxes[c.cable_a], reach).overlaps(ws.cable_boxes[c.cable_b]))
    return;
  const std::vector<Aabb>* boxes_a =
      how.all_samples ? nullptr : &element_boxes_of(model, state, ws, c.cable_a);
  const std::vector<Aabb>* boxes_b =
      how.all_samples ? nullptr : &element_boxes_of(model, state, ws, c.cable_b);

  ContactSampleBlocks blocks;
  blocks.pair = static_cast<Index>(model.cable_shape_contacts().size()) + pair;
  blocks.cable = c.cable_a;
  for (Index li = 0; li < c.count_a; ++li) {
    const Index i = c.first_a + li;
    // Candidate elements of b (local indices): those whose box comes within `reach` of element i's.
    ws.candidates.clear();
    if (how.all_samples) {
      for (Index lj = 0; lj < nb; ++lj) ws.candidates.push_back(lj);
    } else {
      const Aabb box_i = inflated((*boxes_a)[i], reach);
      if (box_i.overlaps(ws.cable_boxes[c.cable_b])) {
        // Second level: element pairs whose centrelines provably stay ≥ reach apart
        // (contact_bounds.hpp) have no active sample and do not change the closest element.
        const ElementHull hull_i =
            ws.hull_broad_phase ? stored_hull(model, state, ws, c.cable_a, i) : ElementHull{};
        for (Index lj = 0; lj < nb; ++lj) {
          const Index j = c.first_b + lj;
          if (!box_i.overlaps((*boxes_b)[j])) continue;
          if (ws.hull_broad_phase &&
              hull_distance_bound(hull_i, stored_hull(model, state, ws, c.cable_b, j)) >= reach)
            continue;
          ws.candidates.push_back(lj);
        }
      }
    }
    if (ws.candidates.empty()) continue;
    blocks.first_a = a.first_coordinate + 6 * i;
    blocks.aa = &model.element_slots(c.cable_a, i);
    for (int k = 0; k < c.samples; ++k) {
      const CableSample s = sample_of(a, i, k, c.samples, state);
      ++ws.narrow_phase_samples;
      const Vec3 x = centreline_point(hermite::values(s.xi, s.length), s.e);
      // The closest point on cable b is the best projection over the candidates: any element
      // outside them is farther than `reach` from this sample.
      ElementProjection best{0.0, std::numeric_limits<double>::infinity()};
      Index best_local = -1;
      for (const Index lj : ws.candidates) {
        const Index j = c.first_b + lj;
        const ElementProjection p = project_onto_element(
            state.q.segment<12>(b.first_coordinate + 6 * j), b.elements[j].length, x);
        if (p.distance < best.distance) best = p, best_local = lj;
      }
      if (!how.all_samples && best.distance >= reach) continue;
      const Index best_j = c.first_b + best_local;
      const Index eb = b.first_coordinate + 6 * best_j;
      blocks.first_b = eb;
      blocks.bb = &model.element_slots(c.cable_b, best_j);
      const Index kb = ws.coupling ? ws.coupling->cable_block[pair][li * nb + best_local] : -1;
      blocks.ab = kb >= 0 ? &ws.coupling->blocks[2 * kb] : nullptr;
      blocks.ba = kb >= 0 ? &ws.coupling->blocks[2 * kb + 1] : nullptr;
      if (evaluate_cable_cable_contact(c.law, s, state.q.segment<12>(eb), state.v.segment<12>(eb),
                                       b.elements[best_j].length, b.section.radius, best.xi,
                                       how.jacobians, ws.contact) ||
          how.all_samples)
        sink.add(ws.contact, blocks);
    }
  }
}

}  // namespace

void visit_contact_samples(const Model& model, const SystemState& state, Workspace& ws,
                           ContactVisit how, ContactSink& sink) {
  if (model.contact_pair_count() == 0) return;
  if (!how.all_samples) refresh_cable_boxes(model, state, ws);
  for (Index p = 0; p < static_cast<Index>(model.cable_shape_contacts().size()); ++p)
    visit_cable_shape(model, state, ws, how, p, sink);
  for (Index p = 0; p < static_cast<Index>(model.cable_cable_contacts().size()); ++p)
    visit_cable_cable(model, state, ws, how, p, sink);
}

}  // namespace ancf::detail
