// Exact minimum gaps of a contact pair for the outputs (contact_min_gap.hpp), by branch and bound.
//
// Lower bounds of the gap over a whole element (or, for one sample, over a whole element of the
// other cable) follow from the element's Bézier control points (contact_bounds.hpp). An element
// whose bound is ≥ the smallest gap found so far cannot hold a strictly smaller one and is
// skipped; the minimum of the rest is the same number, bit for bit, as the exhaustive search,
// since min is exact and each evaluated value is computed by the same code. The element with the
// smallest bound is searched first.
#include "contact_min_gap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "ancf/physics/hermite_shape.hpp"
#include "contact_bounds.hpp"

namespace ancf::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Vec12 cable_element(const CableData& cable, Index element, const SystemState& state) {
  return state.q.segment<12>(cable.first_coordinate + 6 * element);
}

// Calls search(local) for local = 0 … count − 1, the one with the smallest bound first, skipping
// those whose bound(local) ≥ best() at the time they come up (all are searched when !prune). Each
// bound is evaluated once (outputs run between steps: the vector may allocate).
template <class Bound, class Best, class Search>
void branch_and_bound(Index count, bool prune, Bound&& bound, Best&& best, Search&& search) {
  if (count <= 0) return;
  std::vector<double> bounds;
  Index first = 0;
  if (prune) {
    bounds.resize(static_cast<std::size_t>(count));
    for (Index k = 0; k < count; ++k) {
      bounds[k] = bound(k);
      if (bounds[k] < bounds[first]) first = k;
    }
  }
  search(first);
  for (Index k = 0; k < count; ++k)
    if (k != first && (!prune || bounds[k] < best())) search(k);
}

// Lower bound on the surface gap between a placed shape and a cable element, from its hull.
double shape_element_bound(const ShapeDistanceBound& shape_bound, const CableData& cable,
                           Index element, const SystemState& state) {
  return shape_bound(
             element_hull(cable_element(cable, element, state), cable.elements[element].length)) -
         cable.section.radius;
}

double shape_sample_min_gap(const Model& model, const SystemState& state, Workspace& ws, Index pair,
                            bool prune) {
  const CableShapeContactData& c = model.cable_shape_contacts()[pair];
  const ContactShapeData& shape = model.shapes()[c.shape];
  const CableData& cable = model.cables()[c.cable];
  const ShapeOwnerPose pose = owner_pose(shape, state, ws.frames_at(model, state.t));
  const ShapeDistanceBound shape_bound(shape.shape, pose);
  double smallest = kInf;
  branch_and_bound(
      c.count, prune,
      [&](Index local) { return shape_element_bound(shape_bound, cable, c.first + local, state); },
      [&] { return smallest; },
      [&](Index local) {
        for (int k = 0; k < c.samples; ++k) {
          ++ws.narrow_phase_samples;
          evaluate_cable_shape_contact(c.law, shape.shape, pose,
                                       sample_of(cable, c.first + local, k, c.samples, state),
                                       false, ws.contact);
          smallest = std::min(smallest, ws.contact.gap);
        }
      });
  return smallest;
}

double cable_sample_min_gap(const Model& model, const SystemState& state, Workspace& ws, Index pair,
                            bool prune) {
  const CableCableContactData& c = model.cable_cable_contacts()[pair];
  const CableData& a = model.cables()[c.cable_a];
  const CableData& b = model.cables()[c.cable_b];
  const double reach = a.section.radius + b.section.radius;
  // Hulls of the elements of both sides (outputs run between steps: these may allocate).
  std::vector<ElementHull> hulls_a, hulls_b;
  if (prune) {
    for (Index li = 0; li < c.count_a; ++li)
      hulls_a.push_back(
          element_hull(cable_element(a, c.first_a + li, state), a.elements[c.first_a + li].length));
    for (Index lj = 0; lj < c.count_b; ++lj)
      hulls_b.push_back(
          element_hull(cable_element(b, c.first_b + lj, state), b.elements[c.first_b + lj].length));
  }
  double smallest = kInf;
  const auto element_bound = [&](Index li) {
    // min over j of max(box distance, chord bound): the chord bound only where the box distance
    // is below the running minimum (it can only raise the value).
    double d = kInf;
    for (Index lj = 0; lj < c.count_b; ++lj)
      if (box_distance(hulls_a[li].box, hulls_b[lj].box) < d)
        d = std::min(d, hull_distance_bound(hulls_a[li], hulls_b[lj]));
    return d - reach;
  };
  branch_and_bound(
      c.count_a, prune, element_bound, [&] { return smallest; },
      [&](Index li) {
        const Index i = c.first_a + li;
        for (int k = 0; k < c.samples; ++k) {
          const CableSample s = sample_of(a, i, k, c.samples, state);
          const Vec3 x = centreline_point(hermite::values(s.xi, s.length), s.e);
          // The closest element of b (first of equals, as the exhaustive loop finds it); an element
          // whose box is no nearer than the best so far, or than smallest + reach, cannot change
          // the minimum.
          ElementProjection best{0.0, kInf};
          Index best_local = -1;
          const double slack = 1e-12 * (1.0 + x.cwiseAbs().maxCoeff());
          for (Index lj = 0; lj < c.count_b; ++lj) {
            const Index j = c.first_b + lj;
            if (prune && point_hull_distance_bound(x, hulls_b[lj]) >=
                             std::min(best.distance, smallest + reach + slack))
              continue;
            const ElementProjection p = project_onto_element(
                state.q.segment<12>(b.first_coordinate + 6 * j), b.elements[j].length, x);
            if (p.distance < best.distance) best = p, best_local = lj;
          }
          if (best_local < 0) continue;
          const Index best_j = c.first_b + best_local;
          const Index eb = b.first_coordinate + 6 * best_j;
          ++ws.narrow_phase_samples;
          evaluate_cable_cable_contact(c.law, s, state.q.segment<12>(eb), state.v.segment<12>(eb),
                                       b.elements[best_j].length, b.section.radius, best.xi, false,
                                       ws.contact);
          smallest = std::min(smallest, ws.contact.gap);
        }
      });
  return smallest;
}

}  // namespace

double sample_min_gap(const Model& model, const SystemState& state, Workspace& ws, Index pair,
                      ContactSearch search) {
  const bool prune = search == ContactSearch::pruned;
  const Index shape_pairs = static_cast<Index>(model.cable_shape_contacts().size());
  return pair < shape_pairs ? shape_sample_min_gap(model, state, ws, pair, prune)
                            : cable_sample_min_gap(model, state, ws, pair - shape_pairs, prune);
}

double centreline_min_gap(const Model& model, const SystemState& state, Workspace& ws, Index pair,
                          ContactSearch search) {
  const bool prune = search == ContactSearch::pruned;
  const CableShapeContactData& c = model.cable_shape_contacts()[pair];
  const ContactShapeData& shape = model.shapes()[c.shape];
  const CableData& cable = model.cables()[c.cable];
  const ShapeOwnerPose pose = owner_pose(shape, state, ws.frames_at(model, state.t));
  const ShapeDistanceBound shape_bound(shape.shape, pose);
  // Scan each element at kScan + 1 points (ends included), then refine the smallest by a
  // golden-section search on its two neighbouring intervals: the gap along a cubic centreline
  // near a smooth convex shape is unimodal on that scale, and 60 reductions of 0.618 shrink the
  // bracket below 1e-12 of the element.
  constexpr int kScan = 16, kGoldenIterations = 60;
  double smallest = kInf;
  branch_and_bound(
      c.count, prune,
      [&](Index local) { return shape_element_bound(shape_bound, cable, c.first + local, state); },
      [&] { return smallest; },
      [&](Index local) {
        const Index j = c.first + local;
        const Vec12 e = state.q.segment<12>(cable.first_coordinate + 6 * j);
        const double l = cable.elements[j].length;
        auto gap = [&](double xi) {
          const Vec3 x = centreline_point(hermite::values(xi, l), e);
          return signed_distance(shape.shape, pose.rotation.transpose() * (x - pose.origin))
                     .distance -
                 cable.section.radius;
        };
        int best = 0;
        double best_gap = gap(0.0);
        for (int k = 1; k <= kScan; ++k)
          if (const double g = gap(static_cast<double>(k) / kScan); g < best_gap)
            best = k, best_gap = g;
        double lo = std::max(0, best - 1) / static_cast<double>(kScan);
        double hi = std::min(kScan, best + 1) / static_cast<double>(kScan);
        constexpr double kInverseGolden = 0.6180339887498949;
        double x1 = hi - kInverseGolden * (hi - lo), x2 = lo + kInverseGolden * (hi - lo);
        double g1 = gap(x1), g2 = gap(x2);
        for (int it = 0; it < kGoldenIterations; ++it) {
          if (g1 < g2) {
            hi = x2, x2 = x1, g2 = g1;
            x1 = hi - kInverseGolden * (hi - lo), g1 = gap(x1);
          } else {
            lo = x1, x1 = x2, g1 = g2;
            x2 = lo + kInverseGolden * (hi - lo), g2 = gap(x2);
          }
        }
        smallest = std::min({smallest, best_gap, g1, g2});
      });
  return smallest;
}

}  // namespace ancf::detail
