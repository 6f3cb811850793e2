// Rigid contact shapes described in their owner's frame (ground, a driven frame or a rigid body)
// and their signed distance functions: value, gradient (unit outward normal) and Hessian (the
// curvature terms of the contact Jacobian).
#pragma once

#include <limits>
#include <string>
#include <variant>

#include "ancf/core/types.hpp"

namespace ancf {

/// Solid sphere: centre c̄ [m] in the owner frame, radius R [m] > 0.
struct SphereShape {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
};

/// Solid cylinder with flat caps: centre c̄ [m], unit axis ū, radius R [m] > 0, half-length H [m] >
/// 0 (caps at c̄ ± H ū).
struct CappedCylinderShape {
  Vec3 centre = Vec3::Zero();
  Vec3 axis = Vec3::UnitZ();
  double radius = 0.0;
  double half_length = 0.0;
};

/// Half-space {y : n̄·(y − p̄) ≤ 0}: point p̄ [m] on the plane and unit outward normal n̄.
struct PlaneShape {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};

using ContactShape = std::variant<SphereShape, CappedCylinderShape, PlaneShape>;

/// Signed distance d(y) [m] of point y (owner frame) to the shape surface, negative inside,
/// its gradient ∇d (the unit outward normal) and Hessian ∇²d [1/m].
///
/// Outside a convex shape d is C¹ (C² away from the cylinder's rim-region boundaries); inside, d is
/// the distance to the nearest face, smooth while the nearest face is unique. Precondition: y is
/// not on the cylinder axis inside the cylinder and not at the sphere centre (the normal is
/// undefined there; the function then returns an arbitrary unit normal and a zero Hessian).
struct SignedDistance {
  double distance = 0.0;
  Vec3 gradient = Vec3::Zero();
  Mat3 hessian = Mat3::Zero();
};
[[nodiscard]] SignedDistance signed_distance(const ContactShape& shape, const Vec3& y);

/// Throws ModelError naming `owner` if a radius or half-length is not positive or a direction is
/// not of unit length (within 1e-12).
void validate_shape(const ContactShape& shape, const std::string& owner);

/// Axis-aligned box [lower, upper] in global coordinates.
struct Aabb {
  Vec3 lower = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 upper = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void extend(const Vec3& p) {
    lower = lower.cwiseMin(p);
    upper = upper.cwiseMax(p);
  }
  void inflate(double margin) {
    lower.array() -= margin;
    upper.array() += margin;
  }
  [[nodiscard]] bool overlaps(const Aabb& o) const {
    return (lower.array() <= o.upper.array()).all() && (o.lower.array() <= upper.array()).all();
  }
};

/// Conservative global box of the shape placed at origin r_O with rotation A (columns a_k; need
/// not be orthonormal during Newton iterations: the box is then of the affine image). A plane has
/// no finite box: use `may_touch_plane` instead.
[[nodiscard]] Aabb shape_bounding_box(const SphereShape& s, const Vec3& origin,
                                      const Mat3& rotation);
[[nodiscard]] Aabb shape_bounding_box(const CappedCylinderShape& s, const Vec3& origin,
                                      const Mat3& rotation);
/// True unless every corner of `box` lies strictly outside the plane (global placement as above).
[[nodiscard]] bool may_touch_plane(const PlaneShape& s, const Vec3& origin, const Mat3& rotation,
                                   const Aabb& box);

}  // namespace ancf
