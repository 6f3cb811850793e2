// Signed distance functions of the rigid contact primitives (contact_shapes.hpp), their gradients
// (unit outward normals) and exact Hessians, and conservative bounding boxes for the broad phase.
//
// The Hessian ∇²d is the derivative of the normal with respect to the point; in the contact
// Jacobian it gives the curvature terms ∂n/∂x of the closest-point projection (Wriggers,
// Computational Contact Mechanics, 2nd ed. 2006, ch. 4). For the distance to a smooth surface it is
// the surface's shape operator scaled to the offset surface through y; for the distance to a curve
// (the cylinder's rim circle) it has, in addition, the in-meridian term t tᵀ/d.
#include "ancf/physics/contact_shapes.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <type_traits>

#include "ancf/core/error.hpp"

namespace ancf {

namespace {

/// A unit vector perpendicular to the unit vector u (any one; used only where the direction is
/// undefined, see the precondition in the header).
Vec3 any_perpendicular(const Vec3& u) {
  const Vec3 other = std::abs(u.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return u.cross(other).normalized();
}

SignedDistance sphere_distance(const SphereShape& s, const Vec3& y) {
  SignedDistance out;
  const Vec3 r = y - s.centre;
  const double rho = r.norm();
  out.distance = rho - s.radius;
  if (!(rho > 0.0)) {  // centre: every direction is a normal
    out.gradient = Vec3::UnitZ();
    return out;
  }
  out.gradient = r / rho;
  // n = r/|r| ⇒ ∂n/∂y = (I − n nᵀ)/|r|: the sphere's curvature 1/R scaled to the sphere through y.
  out.hessian = (Mat3::Identity() - out.gradient * out.gradient.transpose()) / rho;
  return out;
}

SignedDistance plane_distance(const PlaneShape& s, const Vec3& y) {
  SignedDistance out;
  out.distance = s.normal.dot(y - s.point);
  out.gradient = s.normal;  // flat: zero Hessian
  return out;
}

// Capped cylinder. With z = u·(y − c) the axial and r_⊥ = (y − c) − z u the radial part,
// ρ = |r_⊥|, e_r = r_⊥/ρ, d_r = ρ − R and d_z = |z| − H, the nearest surface feature is
//   side  (d_r > 0 ≥ d_z):   d = d_r,            n = e_r,
//   cap   (d_z > 0 ≥ d_r):   d = d_z,            n = sign(z) u,
//   rim   (d_r > 0, d_z > 0): d = √(d_r² + d_z²), n = (d_r e_r + d_z sign(z) u)/d  (circle edge),
//   inside (d_r, d_z ≤ 0):   the nearer face, d = max(d_r, d_z) (side when d_r ≥ d_z).
// Hessians (e_θ = u × e_r the circumferential direction):
//   side: moving along e_θ turns e_r at the rate 1/ρ, nothing else turns n ⇒ e_θ e_θᵀ/ρ;
//   cap:  0;
//   rim:  distance to a circle of radius R: t tᵀ/d + (d_r/(ρ d)) e_θ e_θᵀ, where t is the unit
//         vector of the meridian plane perpendicular to n (moving along t rotates n at rate 1/d;
//         moving along e_θ rotates its radial part d_r/d · e_r at rate 1/ρ).
SignedDistance cylinder_distance(const CappedCylinderShape& s, const Vec3& y) {
  SignedDistance out;
  const Vec3& u = s.axis;
  const Vec3 rel = y - s.centre;
  const double z = u.dot(rel);
  const Vec3 radial = rel - z * u;
  const double rho = radial.norm();
  const bool on_axis = !(rho > 0.0);
  const Vec3 e_r = on_axis ? any_perpendicular(u) : Vec3(radial / rho);
  const double sign = z >= 0.0 ? 1.0 : -1.0;
  const double d_r = rho - s.radius, d_z = std::abs(z) - s.half_length;
  const Vec3 e_theta = u.cross(e_r);

  if (d_r > 0.0 && d_z > 0.0) {  // rim edge
    const double d = std::hypot(d_r, d_z);
    out.distance = d;
    out.gradient = (d_r * e_r + (d_z * sign) * u) / d;
    const Vec3 t = (d_r * sign * u - d_z * e_r) / d;
    out.hessian = t * t.transpose() / d + (d_r / (rho * d)) * e_theta * e_theta.transpose();
    return out;
  }
  const bool side = d_z <= 0.0 && d_r >= d_z;  // outside beside the side, or inside nearer to it
  if (side) {
    out.distance = d_r;
    out.gradient = e_r;
    if (!on_axis) out.hessian = e_theta * e_theta.transpose() / rho;
    return out;
  }
  out.distance = d_z;  // cap (outside, or the nearer face inside)
  out.gradient = sign * u;
  return out;
}

void check_positive(double value, const char* what, const std::string& owner) {
  if (!(value > 0.0) || !std::isfinite(value))
    throw ModelError("contact shape of '" + owner + "': " + what +
                     " must be finite and > 0 m, got " + std::to_string(value));
}
void check_unit(const Vec3& v, const char* what, const std::string& owner) {
  if (!v.allFinite() || !(std::abs(v.norm() - 1.0) <= 1e-12))
    throw ModelError(
        "contact shape of '" + owner + "': " + what +
        " must be a unit vector (| |v| - 1 | <= 1e-12), got |v| = " + std::to_string(v.norm()));
}
void check_finite(const Vec3& v, const char* what, const std::string& owner) {
  if (!v.allFinite())
    throw ModelError("contact shape of '" + owner + "': " + what + " must be finite");
}

}  // namespace

SignedDistance signed_distance(const ContactShape& shape, const Vec3& y) {
  return std::visit(
      [&](const auto& s) -> SignedDistance {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, SphereShape>)
          return sphere_distance(s, y);
        else if constexpr (std::is_same_v<T, CappedCylinderShape>)
          return cylinder_distance(s, y);
        else
          return plane_distance(s, y);
      },
      shape);
}

void validate_shape(const ContactShape& shape, const std::string& owner) {
  std::visit(
      [&](const auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, SphereShape>) {
          check_finite(s.centre, "sphere centre", owner);
          check_positive(s.radius, "sphere radius", owner);
        } else if constexpr (std::is_same_v<T, CappedCylinderShape>) {
          check_finite(s.centre, "cylinder centre", owner);
          check_unit(s.axis, "cylinder axis", owner);
          check_positive(s.radius, "cylinder radius", owner);
          check_positive(s.half_length, "cylinder half-length", owner);
        } else {
          check_finite(s.point, "plane point", owner);
          check_unit(s.normal, "plane normal", owner);
        }
      },
      shape);
}

// Boxes of the image of the shape under ȳ ↦ r_O + A ȳ. The image of the ball |ȳ − c̄| ≤ R has the
// half-extent R |row_i(A)| along global axis i (max of e_iᵀ A w over |w| ≤ R); that of a disk of
// radius R perpendicular to ū has R |(I − ū ūᵀ) row_i(A)ᵀ|. The capped cylinder is the segment
// between its cap centres swept by that disk.
Aabb shape_bounding_box(const SphereShape& s, const Vec3& origin, const Mat3& rotation) {
  const Vec3 c = origin + rotation * s.centre;
  const Vec3 half = s.radius * rotation.rowwise().norm();
  Aabb box;
  box.extend(c - half);
  box.extend(c + half);
  return box;
}

Aabb shape_bounding_box(const CappedCylinderShape& s, const Vec3& origin, const Mat3& rotation) {
  const Mat3 in_disk = Mat3::Identity() - s.axis * s.axis.transpose();
  const Vec3 half = s.radius * (rotation * in_disk).rowwise().norm();
  Aabb box;
  for (const double end : {-1.0, 1.0}) {
    const Vec3 c = origin + rotation * (s.centre + end * s.half_length * s.axis);
    box.extend(c - half);
    box.extend(c + half);
  }
  return box;
}

bool may_touch_plane(const PlaneShape& s, const Vec3& origin, const Mat3& rotation,
                     const Aabb& box) {
  // Same owner-frame coordinates as the contact kernel, y = Aᵀ(z − r_O), so the test agrees with
  // the kernel's gap also when A is not orthonormal.
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 z((corner & 1) ? box.upper.x() : box.lower.x(),
                 (corner & 2) ? box.upper.y() : box.lower.y(),
                 (corner & 4) ? box.upper.z() : box.lower.z());
    const Vec3 y = rotation.transpose() * (z - origin);
    if (!(s.normal.dot(y - s.point) > 0.0)) return true;
  }
  return false;
}

}  // namespace ancf
