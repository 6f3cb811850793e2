#include "contact_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

namespace ancf::detail {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Allowance for the round-off of centreline points against their control points (and of the
// distance formulas): 1e-12 of the coordinates' magnitude.
double round_off(const Aabb& box) {
  return 1e-12 * (1.0 + std::max(box.lower.cwiseAbs().maxCoeff(), box.upper.cwiseAbs().maxCoeff()));
}

}  // namespace

double chord_deviation(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3) {
  // Distances to the chord's third points, ≥ those to the chord; equal to zero for a straight,
  // uniformly parametrized element (P1, P2 at the thirds).
  return std::max((p1 - (2.0 * p0 + p3) / 3.0).norm(), (p2 - (p0 + 2.0 * p3) / 3.0).norm());
}

double ElementHull::farthest_from(const Vec3& x) const {
  return std::max({(start - x).norm(), (p1 - x).norm(), (p2 - x).norm(), (end - x).norm()});
}

ElementHull element_hull(const Vec12& e, double length) {
  ElementHull h;
  h.start = e.segment<3>(0);
  h.end = e.segment<3>(6);
  h.p1 = h.start + (length / 3.0) * e.segment<3>(3);
  h.p2 = h.end - (length / 3.0) * e.segment<3>(9);
  h.deviation = chord_deviation(h.start, h.p1, h.p2, h.end);
  for (const Vec3* p : {&h.start, &h.p1, &h.p2, &h.end}) h.box.extend(*p);
  return h;
}

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

double segment_distance(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double s = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (x - (a + s * ab)).norm();
}

double segment_segment_distance(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  // min over s, t ∈ [0, 1] of |p0 + s d1 − q0 − t d2|², a convex quadratic: the minimum is the
  // unconstrained one if inside the square, else on an edge; each edge is a clamped 1-D problem,
  // and min over the four edges (plus the interior point) is the exact minimum.
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), b = d1.dot(d2);
  const double c = d1.dot(r), f = d2.dot(r);
  double best = std::min({segment_distance(p0, q0, q1), segment_distance(p1, q0, q1),
                          segment_distance(q0, p0, p1), segment_distance(q1, p0, p1)});
  const double det = a * e - b * b;
  if (det > 1e-14 * a * e) {
    const double s = (b * f - c * e) / det, t = (a * f - b * c) / det;
    if (s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0)
      best = std::min(best, (r + s * d1 - t * d2).norm());
  }
  return best;
}

double point_hull_distance_bound(const Vec3& x, const ElementHull& h) {
  const double slack = round_off(h.box) + 1e-12 * (1.0 + x.cwiseAbs().maxCoeff());
  return std::max(point_box_distance(x, h.box), segment_distance(x, h.start, h.end) - h.deviation) -
         slack;
}

double hull_distance_bound(const ElementHull& a, const ElementHull& b) {
  return std::max(
             box_distance(a.box, b.box),
             segment_segment_distance(a.start, a.end, b.start, b.end) - a.deviation - b.deviation) -
         round_off(a.box) - round_off(b.box);
}

ShapeDistanceBound::ShapeDistanceBound(const ContactShape& shape, const ShapeOwnerPose& pose)
    : shape_(shape), pose_(pose) {
  const Mat3& a = pose.rotation;
  e_ = (Mat3::Identity() - a * a.transpose()).norm();  // Frobenius ≥ spectral norm
  norm_a_ = std::sqrt(1.0 + e_);                       // ‖A‖² = ‖A Aᵀ‖ ≤ 1 + e
  if (const auto* sphere = std::get_if<SphereShape>(&shape)) {
    box_ = shape_bounding_box(*sphere, pose.origin, a);
    axis_start_ = axis_end_ = pose.origin + a * sphere->centre;
    radius_ = sphere->radius;
  } else if (const auto* cyl = std::get_if<CappedCylinderShape>(&shape)) {
    box_ = shape_bounding_box(*cyl, pose.origin, a);
    axis_start_ = pose.origin + a * (cyl->centre - cyl->half_length * cyl->axis);
    axis_end_ = pose.origin + a * (cyl->centre + cyl->half_length * cyl->axis);
    radius_ = cyl->radius;
  }
}

double ShapeDistanceBound::operator()(const ElementHull& h) const {
  const Aabb& box = h.box;
  if (const auto* plane = std::get_if<PlaneShape>(&shape_)) {
    double lowest = kInf;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 z((corner & 1) ? box.upper.x() : box.lower.x(),
                   (corner & 2) ? box.upper.y() : box.lower.y(),
                   (corner & 4) ? box.upper.z() : box.lower.z());
      lowest = std::min(lowest, plane->normal.dot(pose_.rotation.transpose() * (z - pose_.origin) -
                                                  plane->point));
    }
    return lowest - round_off(box) * (1.0 + pose_.rotation.norm());
  }
  if (!(e_ <= 0.1)) return -kInf;
  // The image of the ball of radius R lies within ‖A‖R of the image of its centre, the capped
  // cylinder within ‖A‖R of its axis.
  const double d = std::max(box_distance(box, box_),
                            segment_segment_distance(h.start, h.end, axis_start_, axis_end_) -
                                h.deviation - norm_a_ * radius_);
  const double rho = h.farthest_from(pose_.origin);
  const double allowance = round_off(box) + 1e-12 * rho;
  if (!(d - e_ * rho > allowance)) return -kInf;
  return (d - e_ * rho) / norm_a_ - allowance;
}

}  // namespace ancf::detail
