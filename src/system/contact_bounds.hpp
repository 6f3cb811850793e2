// Internal to the system layer: lower bounds of contact gaps over a whole cable element, from its
// Bézier control points, for the broad phase (elements that cannot touch skip the narrow phase)
// and the branch and bound of the output minimum gaps (contact_min_gap.cpp).
//
// The centreline of an element lies in the convex hull of its control points P0 = r_i,
// P1 = r_i + l r_i,x/3, P2 = r_j − l r_j,x/3, P3 = r_j, hence in their box, and within
// δ = max(dist(P1, [P0, P3]), dist(P2, [P0, P3])) of its chord [P0, P3] (the distance to a convex
// set is a convex function, zero at P0 and P3). So the distance from any centreline point to a
// set is at least the chord's distance minus δ, and at least the box's distance. δ is bounded by
// the distances of P1, P2 from the chord's third points (chord_deviation: no projection needed,
// and zero for a straight element parametrized uniformly).
#pragma once

#include "ancf/physics/cable_contact.hpp"

namespace ancf::detail {

/// Chord, deviation δ and box of an element's centreline (see the file comment).
struct ElementHull {
  Vec3 start = Vec3::Zero(), end = Vec3::Zero();
  double deviation = 0.0;
  Aabb box;
  /// Largest |P_k − x| over the control points: bounds |y − x| for every centreline point y.
  [[nodiscard]] double farthest_from(const Vec3& x) const;
  Vec3 p1 = Vec3::Zero(), p2 = Vec3::Zero();
};
[[nodiscard]] ElementHull element_hull(const Vec12& e, double length);
/// max(|P1 − (2P0 + P3)/3|, |P2 − (P0 + 2P3)/3|) ≥ δ.
[[nodiscard]] double chord_deviation(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                     const Vec3& p3);

/// Euclidean distances: box–box, point–box, point–segment, segment–segment (0 when they meet).
[[nodiscard]] double box_distance(const Aabb& a, const Aabb& b);
[[nodiscard]] double point_box_distance(const Vec3& x, const Aabb& b);
[[nodiscard]] double segment_distance(const Vec3& x, const Vec3& a, const Vec3& b);
[[nodiscard]] double segment_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0,
                                              const Vec3& q1);

/// Lower bounds of the distance between every centreline point of one element and a point x or
/// every centreline point of another element, with a round-off allowance (−∞ never; 0 or less
/// when they may meet).
[[nodiscard]] double point_hull_distance_bound(const Vec3& x, const ElementHull& h);
[[nodiscard]] double hull_distance_bound(const ElementHull& a, const ElementHull& b);

/// Lower bound of the contact kernel's signed distance (evaluate_cable_shape_contact, before the
/// cable radius is subtracted) over every centreline point of an element, for a shape placed by
/// its owner's pose (r_O, A). Sphere and capped cylinder: from the distance D to the image of the
/// shape (its global box, and its centre or axis within ‖A‖R), with e = ‖I − A Aᵀ‖ (A need not be
/// orthonormal during Newton iterations): the image z of the closest shape point to
/// y = Aᵀ(x − r_O) has |x − z| ≤ ‖A‖ d_y + e ρ (ρ ≥ |x − r_O|), so d_y ≥ (D − e ρ)/‖A‖, and
/// D > e ρ rules out a point inside the shape; else −∞. Plane: the kernel's distance is affine
/// in x, its minimum over the box is at a corner.
class ShapeDistanceBound {
 public:
  ShapeDistanceBound(const ContactShape& shape, const ShapeOwnerPose& pose);
  [[nodiscard]] double operator()(const ElementHull& h) const;

 private:
  const ContactShape& shape_;
  const ShapeOwnerPose& pose_;
  Aabb box_;  // global box of a sphere or cylinder
  double e_ = 0.0, norm_a_ = 1.0, radius_ = 0.0;
  Vec3 axis_start_ = Vec3::Zero(), axis_end_ = Vec3::Zero();  // image of the centre or axis
};

}  // namespace ancf::detail
