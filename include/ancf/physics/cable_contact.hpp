// Contact kernels of one sample point of a cable element's centreline (DESIGN §5): against a rigid
// shape (on ground, a driven frame or a rigid body) and against another cable element.
//
// Both kernels follow one scheme. With P the position and V the velocity unknowns involved
// ([e] or [e; q_body] or [e_a; e_b]):
//   x   = S(ξ) e                       sample point on the cable centreline
//   x_o = material point of the other side that currently coincides with (or is closest to) x:
//         body: r_O + Σ y_k a_k with y_k = a_k·(x − r_O);  cable b: S(ξ_b) e_b at its projection
//         ξ_b
//   g   = signed distance − radii,  n = unit normal (towards the cable point)
//   v_rel = G V = ẋ − ẋ_o  (G = ∂(x − x_o)/∂P with the material points held fixed)
//   F   = f_n n + f_t       (contact_law.hpp) per unit length, times the sample's length weight w
//   Q   = w Gᵀ F            generalised EXTERNAL force on P (cable receives +F, the other side −F
//                           at the same point, so linear momentum is conserved exactly)
// Jacobians ∂Q/∂P (with the curvature terms ∂n/∂P, ∂y/∂P or ∂ξ_b/∂P) and ∂Q/∂V are analytic.
#pragma once

#include "ancf/core/types.hpp"
#include "ancf/physics/contact_law.hpp"
#include "ancf/physics/contact_shapes.hpp"

namespace ancf {

/// One sample of a cable element: nodal coordinates e, velocities ė, element reference length l
/// [m], local coordinate ξ ∈ [0, 1], cross-section radius [m] and length weight w [m] (the share
/// of the element's reference length the sample represents).
struct CableSample {
  Vec12 e = Vec12::Zero();
  Vec12 e_dot = Vec12::Zero();
  double length = 0.0;
  double xi = 0.0;
  double radius = 0.0;
  double weight = 0.0;
};

/// Pose of a shape's owner. For ground and driven frames the pose is known (no unknowns); for a
/// rigid body it is read from its natural coordinates: origin = r_O, rotation = [a₁ a₂ a₃],
/// and the rates from its velocities.
struct ShapeOwnerPose {
  Vec3 origin = Vec3::Zero(), origin_velocity = Vec3::Zero();
  Mat3 rotation = Mat3::Identity(), rotation_rate = Mat3::Zero();
  bool is_body = false;  ///< true: the 12 body coordinates are unknowns (P = [e; q_b])
};

/// Result of one sample. Q and its Jacobians are over P = [first 12 | other 12]; the second half
/// is unused (and not written) when the other side has no unknowns.
struct ContactSampleResult {
  using Vec24 = Eigen::Matrix<double, 24, 1>;
  using Mat24 = Eigen::Matrix<double, 24, 24>;
  bool active = false;        ///< g < 0
  double gap = 0.0;           ///< g [m] (set also when inactive)
  double xi_other = 0.0;      ///< ξ_b (cable–cable only)
  Vec3 point = Vec3::Zero();  ///< x [m]
  Vec3 normal = Vec3::Zero();
  Vec3 normal_force = Vec3::Zero();    ///< w f_n n [N] on the cable
  Vec3 friction_force = Vec3::Zero();  ///< w f_t [N] on the cable
  Vec24 force;                         ///< Q (valid when active)
  Mat24 d_force_dq, d_force_dv;        ///< ∂Q/∂P, ∂Q/∂V (valid when active and requested)
};

/// Sample against a shape. Returns `out.active`; when inactive only gap, point and normal are set.
bool evaluate_cable_shape_contact(const ContactLaw& law, const ContactShape& shape,
                                  const ShapeOwnerPose& owner, const CableSample& sample,
                                  bool jacobians, ContactSampleResult& out);

/// Closest point of the centreline of element (e, l) to x over ξ ∈ [0, 1] (global minimum: coarse
/// sampling, then safeguarded Newton on (r(ξ) − x)·r'(ξ) = 0 to round-off).
struct ElementProjection {
  double xi = 0.0;
  double distance = 0.0;
};
[[nodiscard]] ElementProjection project_onto_element(const Vec12& e, double length, const Vec3& x);

/// Sample of cable a against element b, whose closest point to the sample is at xi_b (from
/// project_onto_element; an interior xi_b is treated as stationary, ξ_b ∈ {0, 1} as clamped).
/// P = [e_a; e_b]. Returns `out.active`.
bool evaluate_cable_cable_contact(const ContactLaw& law, const CableSample& a, const Vec12& e_b,
                                  const Vec12& e_b_dot, double length_b, double radius_b,
                                  double xi_b, bool jacobians, ContactSampleResult& out);

/// Conservative global box of an element's centreline: the box of its Bézier control points
/// r_i, r_i + l r_i,x/3, r_j − l r_j,x/3, r_j (convex-hull property), not inflated.
[[nodiscard]] Aabb element_bounding_box(const Vec12& e, double length);

}  // namespace ancf
