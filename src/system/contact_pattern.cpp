#include "ancf/system/contact_pattern.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <variant>

#include "ancf/system/assembly.hpp"
#include "ancf/system/model.hpp"
#include "contact_sampling.hpp"

namespace ancf {
namespace {

// Calls visit(row, col) for the 144 entries of the block rows [rb, +12) × columns [cb, +12),
// column-major (the BlockSlots order).
template <class Visit>
void visit_block(Index rb, Index cb, Visit&& visit) {
  for (Index c = 0; c < 12; ++c)
    for (Index r = 0; r < 12; ++r) visit(rb + r, cb + c);
}

// Largest distance from the owner's origin of any point of the shape, in the owner frame [m]
// (∞ for a plane): bounds the speed of shape points by |ṙ_O| + this × Σ|ȧ_k|.
double shape_extent(const ContactShape& shape) {
  if (const auto* s = std::get_if<SphereShape>(&shape)) return s->centre.norm() + s->radius;
  if (const auto* c = std::get_if<CappedCylinderShape>(&shape))
    return c->centre.norm() + std::hypot(c->radius, c->half_length);
  return std::numeric_limits<double>::infinity();
}

}  // namespace

ContactPattern::ContactPattern(const Model& model, ContactPatternOptions options)
    : model_(model), options_(options) {
  if (!(options_.reach_factor >= 0.0) || !(options_.look_ahead >= 0.0) ||
      !(options_.leave_factor >= 1.0))
    throw std::invalid_argument(
        "ContactPattern: reach_factor and look_ahead must be >= 0, leave_factor >= 1");
  const bool all = options_.policy == ContactPatternPolicy::all;
  const auto& shape_pairs = model.cable_shape_contacts();
  const auto& cable_pairs = model.cable_cable_contacts();
  coupling_.shape_block.resize(shape_pairs.size());
  shape_near_.resize(shape_pairs.size());
  for (std::size_t p = 0; p < shape_pairs.size(); ++p) {
    const CableShapeContactData& c = shape_pairs[p];
    if (model.shapes()[c.shape].owner != ContactShapeData::Owner::body) continue;
    coupling_.shape_block[p].assign(c.count, -1);
    shape_near_[p].assign(c.count, all ? 1 : 0);
    has_candidates_ = true;
  }
  coupling_.cable_block.resize(cable_pairs.size());
  cable_near_.resize(cable_pairs.size());
  for (std::size_t p = 0; p < cable_pairs.size(); ++p) {
    const CableCableContactData& c = cable_pairs[p];
    coupling_.cable_block[p].assign(c.count_a * c.count_b, -1);
    cable_near_[p].assign(c.count_a * c.count_b, all ? 1 : 0);
    has_candidates_ = true;
  }
  element_speed_.resize(model.cables().size());
  for (const auto& c : shape_pairs)
    element_speed_[c.cable].assign(model.cables()[c.cable].elements.size(), 0.0);
  for (const auto& c : cable_pairs) {
    element_speed_[c.cable_a].assign(model.cables()[c.cable_a].elements.size(), 0.0);
    element_speed_[c.cable_b].assign(model.cables()[c.cable_b].elements.size(), 0.0);
  }
  // Row and column of every entry of the model's pattern: the first assembly slots.
  const SparsityPattern& base = model.pattern();
  rows_.resize(base.nonzeros());
  columns_.resize(base.nonzeros());
  for (Index col = 0; col < base.size(); ++col)
    for (Index k = base.column_start()[col]; k < base.column_start()[col + 1]; ++k)
      rows_[k] = base.row_index()[k], columns_[k] = col;
  rebuild();
  stats_.rebuilds = 0;  // counts changes, not the first build
}

bool ContactPattern::update(const SystemState& state, double horizon, Workspace& ws) {
  ++stats_.updates;
  if (!has_candidates_ || options_.policy == ContactPatternPolicy::all) return false;
  const Model& m = model_;
  detail::refresh_cable_boxes(m, state, ws);
  // Speed bound of every point of an element: the largest speed of its four Bézier control
  // points r_i, r_i + l/3 r_i', r_j − l/3 r_j', r_j (the curve's velocity is the Bézier curve of
  // the control points' velocities, inside their convex hull).
  for (std::size_t c = 0; c < element_speed_.size(); ++c) {
    if (element_speed_[c].empty()) continue;
    const CableData& cable = m.cables()[c];
    for (std::size_t j = 0; j < element_speed_[c].size(); ++j) {
      const Index b = cable.first_coordinate + 6 * static_cast<Index>(j);
      const double third = cable.elements[j].length / 3.0;
      const auto v = state.v.segment<12>(b);
      element_speed_[c][j] =
          std::max({v.segment<3>(0).norm(), (v.segment<3>(0) + third * v.segment<3>(3)).norm(),
                    (v.segment<3>(6) - third * v.segment<3>(9)).norm(), v.segment<3>(6).norm()});
    }
  }
  const double reach = options_.reach_factor, ahead = options_.look_ahead * horizon;
  bool changed = false;
  // A block's margin at which it enters; a near block stays until leave_factor × that.
  auto decide = [&](char& near, double margin, auto&& overlaps) {
    const bool now = overlaps(near ? options_.leave_factor * margin : margin);
    if (now != static_cast<bool>(near)) {
      near = now ? 1 : 0;
      changed = true;
      ++(now ? stats_.blocks_entered : stats_.blocks_left);
    }
  };

  const auto frames = ws.frames_at(m, state.t);
  for (std::size_t p = 0; p < m.cable_shape_contacts().size(); ++p) {
    if (shape_near_[p].empty()) continue;  // not on a body: no coupling blocks
    const CableShapeContactData& c = m.cable_shape_contacts()[p];
    const ContactShapeData& shape = m.shapes()[c.shape];
    const CableData& cable = m.cables()[c.cable];
    const ShapeOwnerPose pose = detail::owner_pose(shape, state, frames);
    const detail::ShapeBroadPhase broad(shape.shape, pose);
    const double spin = pose.rotation_rate.col(0).norm() + pose.rotation_rate.col(1).norm() +
                        pose.rotation_rate.col(2).norm();
    const double extent = shape_extent(shape.shape);
    // A plane on a body has no speed bound: its blocks are always near.
    const double shape_speed = std::isfinite(extent) ? pose.origin_velocity.norm() + extent * spin
                                                     : std::numeric_limits<double>::infinity();
    const auto& boxes = detail::element_boxes_of(m, state, ws, c.cable);
    const double r = cable.section.radius;
    for (Index local = 0; local < c.count; ++local) {
      const Index j = c.first + local;
      const double margin = reach * r + ahead * (element_speed_[c.cable][j] + shape_speed);
      decide(shape_near_[p][local], margin, [&](double mg) {
        return !std::isfinite(mg) || broad.may_touch(detail::inflated(boxes[j], r + mg));
      });
    }
  }
  for (std::size_t p = 0; p < m.cable_cable_contacts().size(); ++p) {
    const CableCableContactData& c = m.cable_cable_contacts()[p];
    const CableData& a = m.cables()[c.cable_a];
    const CableData& b = m.cables()[c.cable_b];
    const double r = a.section.radius + b.section.radius;
    const auto& boxes_a = detail::element_boxes_of(m, state, ws, c.cable_a);
    const auto& boxes_b = detail::element_boxes_of(m, state, ws, c.cable_b);
    for (Index i = 0; i < c.count_a; ++i)
      for (Index j = 0; j < c.count_b; ++j) {
        const double margin = reach * r + ahead * (element_speed_[c.cable_a][c.first_a + i] +
                                                   element_speed_[c.cable_b][c.first_b + j]);
        decide(cable_near_[p][i * c.count_b + j], margin, [&](double mg) {
          return detail::inflated(boxes_a[c.first_a + i], r + mg).overlaps(boxes_b[c.first_b + j]);
        });
      }
  }
  if (changed) rebuild();
  return changed;
}

// Slots of the near blocks, the merged CSC pattern and the slot → position map, from the flags.
void ContactPattern::rebuild() {
  const Model& m = model_;
  const SparsityPattern& base = m.pattern();
  const Index base_count = base.nonzeros();
  // Calls visit(row_base, col_base, k) for both blocks of every near block (k: its index).
  auto for_each_near = [&](auto&& visit) {
    Index k = 0;
    for (std::size_t p = 0; p < shape_near_.size(); ++p) {
      if (shape_near_[p].empty()) continue;
      const CableShapeContactData& c = m.cable_shape_contacts()[p];
      const Index body = m.shapes()[c.shape].body_coordinate;
      const Index first = m.cables()[c.cable].first_coordinate + 6 * c.first;
      for (Index local = 0; local < c.count; ++local) {
        coupling_.shape_block[p][local] = shape_near_[p][local] ? k : -1;
        if (!shape_near_[p][local]) continue;
        visit(first + 6 * local, body, 2 * k);
        visit(body, first + 6 * local, 2 * k + 1);
        ++k;
      }
    }
    for (std::size_t p = 0; p < cable_near_.size(); ++p) {
      const CableCableContactData& c = m.cable_cable_contacts()[p];
      const Index fa = m.cables()[c.cable_a].first_coordinate + 6 * c.first_a;
      const Index fb = m.cables()[c.cable_b].first_coordinate + 6 * c.first_b;
      for (Index i = 0; i < c.count_a; ++i)
        for (Index j = 0; j < c.count_b; ++j) {
          const Index flat = i * c.count_b + j;
          coupling_.cable_block[p][flat] = cable_near_[p][flat] ? k : -1;
          if (!cable_near_[p][flat]) continue;
          visit(fa + 6 * i, fb + 6 * j, 2 * k);
          visit(fb + 6 * j, fa + 6 * i, 2 * k + 1);
          ++k;
        }
    }
    return k;
  };

  // Entries of near blocks that the model's pattern lacks, sorted (col, row) and unique.
  extra_.clear();
  const Index blocks = for_each_near([&](Index rb, Index cb, Index) {
    visit_block(rb, cb, [&](Index r, Index c) {
      if (base.find(r, c) < 0) extra_.emplace_back(c, r);
    });
  });
  std::sort(extra_.begin(), extra_.end());
  extra_.erase(std::unique(extra_.begin(), extra_.end()), extra_.end());
  const Index extra_count = static_cast<Index>(extra_.size());

  coupling_.blocks.resize(2 * blocks);
  for_each_near([&](Index rb, Index cb, Index slot_block) {
    BlockSlots& out = coupling_.blocks[slot_block];
    int e = 0;
    visit_block(rb, cb, [&](Index r, Index c) {
      const Index s = base.find(r, c);
      out[e++] =
          s >= 0 ? s
                 : base_count + static_cast<Index>(std::lower_bound(extra_.begin(), extra_.end(),
                                                                    std::pair<Index, Index>(c, r)) -
                                                   extra_.begin());
    });
  });

  rows_.resize(base_count + extra_count);
  columns_.resize(base_count + extra_count);
  for (Index k = 0; k < extra_count; ++k)
    columns_[base_count + k] = extra_[k].first, rows_[base_count + k] = extra_[k].second;
  pattern_ = SparsityPattern(base.size());
  for (Index s = 0; s < base_count + extra_count; ++s) pattern_.add(rows_[s], columns_[s]);
  pattern_.freeze();
  position_.resize(base_count + extra_count);
  identity_ = extra_count == 0;
  for (Index s = 0; s < base_count + extra_count; ++s) {
    position_[s] = pattern_.slot(rows_[s], columns_[s]);
    identity_ = identity_ && position_[s] == s;
  }
  ++stats_.rebuilds;
  stats_.near_blocks = blocks;
  stats_.most_nonzeros = std::max(stats_.most_nonzeros, pattern_.nonzeros());
}

}  // namespace ancf
