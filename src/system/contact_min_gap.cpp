// Exact minimum gaps of a contact pair for the outputs (contact_min_gap.hpp), by branch and bound.
//
// Every point of a cable element's centreline lies in the box of its Bézier control points
// (element_bounding_box), so a lower bound L of the gap over a whole element follows from boxes:
//  * sphere or capped cylinder on an owner (r_O, A): outside the shape the kernel's signed
//    distance is the Euclidean distance d_y from y = Aᵀ(x − r_O) to the shape in owner
//    coordinates. With the shape's global box B (of the image r_O + A·shape) at distance D > 0
//    from the element box and e = ‖I − A Aᵀ‖ (zero for an orthonormal A; natural coordinates of
//    a body satisfy it to the Newton tolerance), |x − z| ≤ ‖A‖ d_y + e|x − r_O| for the image z of
//    the closest shape point, hence d_y ≥ (D − e ρ)/√(1 + e) with ρ ≥ |x − r_O| over the box; a
//    point inside the shape (d_y ≤ 0) has z = r_O + A y in B, |x − z| ≤ e ρ, so D > e ρ also
//    rules that out. D ≤ e ρ: no bound.
//  * plane: its kernel distance n·(Aᵀ(x − r_O) − p) is affine in x: its minimum over the box is at
//    a corner, exactly the bound.
//  * cable–cable: the projection distance of a sample onto an element of cable b is at least the
//    distance of the sample point to that element's box, and over an element of cable a at least
//    the box–box distance.
// Each bound is lowered by a round-off allowance of 1e-12 (1 + |coordinates|). An element (or
// an element of cable b for one sample) whose bound is ≥ the smallest gap found so far cannot
// hold a strictly smaller one and is skipped; the minimum of the rest is the same number, bit for
// bit, as the exhaustive search, since min is exact and each evaluated value is computed by the
// same code. The element with the smallest bound is searched first.
#include "contact_min_gap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

#include "ancf/physics/hermite_shape.hpp"

namespace ancf::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double box_distance(const Aabb& a, const Aabb& b) {
  const Eigen::Array3d gap =
      (a.lower.array() - b.upper.array()).max(b.lower.array() - a.upper.array()).max(0.0);
  return std::sqrt(gap.square().sum());
}

double point_box_distance(const Vec3& x, const Aabb& b) {
  const Eigen::Array3d gap =
      (b.lower.array() - x.array()).max(x.array() - b.upper.array()).max(0.0);
  return std::sqrt(gap.square().sum());
}

// Distance from x to the segment [a, b] (a == b: the point).
double segment_distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double s = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (x - (a + s * ab)).norm();
}

double round_off(const Aabb& box) {
  return 1e-12 * (1.0 + std::max(box.lower.cwiseAbs().maxCoeff(), box.upper.cwiseAbs().maxCoeff()));
}

// Lower bound of the kernel's signed distance (before subtracting the cable radius) over every
// point of `box`, for a shape placed by `pose` (see the file comment).
class ShapeBound {
 public:
  ShapeBound(const ContactShape& shape, const ShapeOwnerPose& pose) : broad_(shape, pose) {
    const Mat3& a = pose.rotation;
    e_ = (Mat3::Identity() - a * a.transpose()).norm();  // Frobenius ≥ spectral norm
    norm_a_ = std::sqrt(1.0 + e_);                       // ‖A‖² = ‖A Aᵀ‖ ≤ 1 + e
    if (const auto* sphere = std::get_if<SphereShape>(&shape)) {
      axis_start_ = axis_end_ = pose.origin + a * sphere->centre;
      radius_ = sphere->radius;
    } else if (const auto* cyl = std::get_if<CappedCylinderShape>(&shape)) {
      axis_start_ = pose.origin + a * (cyl->centre - cyl->half_length * cyl->axis);
      axis_end_ = pose.origin + a * (cyl->centre + cyl->half_length * cyl->axis);
      radius_ = cyl->radius;
    }
  }
  [[nodiscard]] double operator()(const Aabb& box) const {
    const ShapeOwnerPose& pose = broad_.pose;
    if (const auto* plane = std::get_if<PlaneShape>(&broad_.shape)) {
      double lowest = kInf;
      for (int corner = 0; corner < 8; ++corner) {
        const Vec3 z((corner & 1) ? box.upper.x() : box.lower.x(),
                     (corner & 2) ? box.upper.y() : box.lower.y(),
                     (corner & 4) ? box.upper.z() : box.lower.z());
        lowest = std::min(lowest, plane->normal.dot(pose.rotation.transpose() * (z - pose.origin) -
                                                    plane->point));
      }
      return lowest - round_off(box) * (1.0 + pose.rotation.norm());
    }
    // D: a lower bound of the global distance from the box to the image of the shape, the larger
    // of the distance to its box and that from the box (centre c, half diagonal) to the image of
    // the sphere's centre or the cylinder's axis minus ‖A‖R (the image of the ball of radius R
    // lies within ‖A‖R of the image of its centre; the capped cylinder within its axis's reach).
    const Vec3 c = 0.5 * (box.lower + box.upper);
    const double half_diagonal = 0.5 * (box.upper - box.lower).norm();
    const double d =
        std::max(box_distance(box, broad_.box),
                 segment_distance(c, axis_start_, axis_end_) - half_diagonal - norm_a_ * radius_);
    if (!(e_ <= 0.1)) return -kInf;
    double rho = 0.0;  // farthest corner of the box from the owner's origin
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 z((corner & 1) ? box.upper.x() : box.lower.x(),
                   (corner & 2) ? box.upper.y() : box.lower.y(),
                   (corner & 4) ? box.upper.z() : box.lower.z());
      rho = std::max(rho, (z - pose.origin).norm());
    }
    // A point inside the shape has its image z in B with |x − z| ≤ e ρ: D > e ρ rules that out.
    const double allowance = round_off(box) + 1e-12 * rho;
    if (!(d - e_ * rho > allowance)) return -kInf;
    return (d - e_ * rho) / norm_a_ - allowance;
  }

 private:
  ShapeBroadPhase broad_;
  double e_ = 0.0, norm_a_ = 1.0;
  Vec3 axis_start_ = Vec3::Zero(), axis_end_ = Vec3::Zero();  // image of the centre or axis
  double radius_ = 0.0;
};

CableSample sample_at(const CableData& cable, Index element, int k, int samples,
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

// Calls search(local) for local = 0 … count − 1, the one with the smallest bound first, skipping
// those whose bound(local) ≥ best() at the time they come up (all are searched when !prune).
template <class Bound, class Best, class Search>
void branch_and_bound(Index count, bool prune, Bound&& bound, Best&& best, Search&& search) {
  Index first = 0;
  if (prune) {
    double lowest = kInf;
    for (Index k = 0; k < count; ++k)
      if (const double b = bound(k); b < lowest) lowest = b, first = k;
  }
  if (count > 0) search(first);
  for (Index k = 0; k < count; ++k)
    if (k != first && (!prune || bound(k) < best())) search(k);
}

double shape_sample_min_gap(const Model& model, const SystemState& state, Workspace& ws, Index pair,
                            bool prune) {
  const CableShapeContactData& c = model.cable_shape_contacts()[pair];
  const ContactShapeData& shape = model.shapes()[c.shape];
  const CableData& cable = model.cables()[c.cable];
  const ShapeOwnerPose pose = owner_pose(shape, state, ws.frames_at(model, state.t));
  const ShapeBound shape_bound(shape.shape, pose);
  const std::vector<Aabb>* boxes = prune ? &element_boxes_of(model, state, ws, c.cable) : nullptr;
  double smallest = kInf;
  branch_and_bound(
      c.count, prune,
      [&](Index local) { return shape_bound((*boxes)[c.first + local]) - cable.section.radius; },
      [&] { return smallest; },
      [&](Index local) {
        for (int k = 0; k < c.samples; ++k) {
          ++ws.narrow_phase_samples;
          evaluate_cable_shape_contact(c.law, shape.shape, pose,
                                       sample_at(cable, c.first + local, k, c.samples, state),
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
  const std::vector<Aabb>* boxes_a =
      prune ? &element_boxes_of(model, state, ws, c.cable_a) : nullptr;
  const std::vector<Aabb>* boxes_b =
      prune ? &element_boxes_of(model, state, ws, c.cable_b) : nullptr;
  double smallest = kInf;
  const auto element_bound = [&](Index li) {
    const Aabb& box = (*boxes_a)[c.first_a + li];
    double d = kInf;
    for (Index lj = 0; lj < c.count_b; ++lj)
      d = std::min(d, box_distance(box, (*boxes_b)[c.first_b + lj]));
    return d - round_off(box) - reach;
  };
  branch_and_bound(
      c.count_a, prune, element_bound, [&] { return smallest; },
      [&](Index li) {
        const Index i = c.first_a + li;
        for (int k = 0; k < c.samples; ++k) {
          const CableSample s = sample_at(a, i, k, c.samples, state);
          const Vec4 shape = hermite::values(s.xi, s.length);
          Vec3 x = Vec3::Zero();  // as in visit_cable_cable, so the projections are the same
          for (int n = 0; n < 4; ++n) x += shape[n] * s.e.segment<3>(3 * n);
          // The closest element of b (first of equals, as the exhaustive loop finds it); an element
          // whose box is no nearer than the best so far, or than smallest + reach, cannot change
          // the minimum.
          ElementProjection best{0.0, kInf};
          Index best_local = -1;
          const double slack = 1e-12 * (1.0 + x.cwiseAbs().maxCoeff());
          for (Index lj = 0; lj < c.count_b; ++lj) {
            const Index j = c.first_b + lj;
            if (prune && point_box_distance(x, (*boxes_b)[j]) - slack >=
                             std::min(best.distance, smallest + reach))
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
  const ShapeBound shape_bound(shape.shape, pose);
  const std::vector<Aabb>* boxes = prune ? &element_boxes_of(model, state, ws, c.cable) : nullptr;
  // Scan each element at kScan + 1 points (ends included), then refine the smallest by a
  // golden-section search on its two neighbouring intervals: the gap along a cubic centreline
  // near a smooth convex shape is unimodal on that scale, and 60 reductions of 0.618 shrink the
  // bracket below 1e-12 of the element.
  constexpr int kScan = 16, kGoldenIterations = 60;
  double smallest = kInf;
  branch_and_bound(
      c.count, prune,
      [&](Index local) { return shape_bound((*boxes)[c.first + local]) - cable.section.radius; },
      [&] { return smallest; },
      [&](Index local) {
        const Index j = c.first + local;
        const Vec12 e = state.q.segment<12>(cable.first_coordinate + 6 * j);
        const double l = cable.elements[j].length;
        auto gap = [&](double xi) {
          const Vec4 s = hermite::values(xi, l);
          Vec3 x = Vec3::Zero();
          for (int n = 0; n < 4; ++n) x += s[n] * e.segment<3>(3 * n);
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
