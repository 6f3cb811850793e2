// Constraint kinds of DESIGN §4 as dot-product rows Φ = u·w + c (dot_constraint.hpp).
//
// Conventions shared by every kind:
//  * vector equations x = 0 (positions, node-to-node) become three rows ē_r·x = 0 with the constant
//    global unit vectors ē_r as u and the difference expression x as w;
//  * "direction ∥ d" becomes two rows t_i·x = 0 with (t₁, t₂) the orthonormal pair of
//    perpendicular_pair(d); the perpendiculars are fixed where d is fixed (ground, body frame or
//    driven frame) and x is the other direction;
//  * directions given by the caller are normalised, so every row has unit-scale coefficients and
//    the Jacobian's rows are comparable in size whatever length the caller's vectors have.
#include "ancf/physics/joints.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/physics/rigid_body.hpp"

namespace ancf {
namespace {

Vec3 unit(const Vec3& d, const char* what) {
  const double n = d.norm();
  if (!(n > 0.0) || !std::isfinite(n))
    throw ModelError(std::string(what) + ": direction must be a non-zero finite vector");
  return d / n;
}

void require_finite(const Vec3& p, const char* what) {
  if (!p.allFinite()) throw ModelError(std::string(what) + ": point must be finite");
}

void require_rotation(const Mat3& r, const char* what) {
  if (!r.allFinite() || (r.transpose() * r - Mat3::Identity()).norm() > 1e-9 ||
      !(r.determinant() > 0.0))
    throw ModelError(std::string(what) + ": rotation must be a finite proper orthonormal matrix");
}

/// Three rows ē_r · w = 0 (r = 0, 1, 2) with w built by `fill`.
template <class Fill>
void add_vector_rows(ConstraintRows& rows, Fill&& fill) {
  for (int r = 0; r < 3; ++r) {
    DotConstraintRow& row = rows.add();
    row.u = AffineVector::constant(Vec3::Unit(r));
    fill(row.w);
  }
}

/// A body point r_O + Σ p̄_k a_k with coefficient `sign` added to w.
void add_body_point(AffineVector& w, Index body, const Vec3& p_body, double sign) {
  w.add_body(body, point_weights(p_body), sign);
}

/// Rows (A₁ t̄_i)·(A₂ ū₂) = 0, i = 1, 2, keeping body direction ū₁ of `body1` parallel to
/// body direction ū₂ of `body2` (t̄_i ⊥ ū₁ fixed in body 1).
void add_body_axis_rows(ConstraintRows& rows, Index body1, const Vec3& axis1, Index body2,
                        const Vec3& axis2) {
  Vec3 t[2];
  perpendicular_pair(unit(axis1, "revolute joint axis of body 1"), t[0], t[1]);
  const Vec3 u2 = unit(axis2, "revolute joint axis of body 2");
  for (const Vec3& ti : t) {
    DotConstraintRow& row = rows.add();
    row.u.add_body(body1, direction_weights(ti));
    row.w.add_body(body2, direction_weights(u2));
  }
}

/// The body coordinate block of a_k (k = 0, 1, 2).
Index axis_block(Index body, int k) {
  return body + 3 * (k + 1);
}

}  // namespace

void perpendicular_pair(const Vec3& d, Vec3& t1, Vec3& t2) {
  const Vec3 n = d.normalized();
  // The coordinate axis least aligned with n: |e × n| ≥ √(2/3), so t₁ is well conditioned.
  Index k = 0;
  n.cwiseAbs().minCoeff(&k);
  t1 = Vec3::Unit(k).cross(n).normalized();
  t2 = n.cross(t1);  // t₁ × t₂ = t₁ × (n × t₁) = n
}

// --- cable node attachments ---------------------------------------------------------------

ConstraintRows node_position_to_ground(Index node, const Vec3& p) {
  require_finite(p, "node position to ground");
  ConstraintRows rows;
  add_vector_rows(rows, [&](AffineVector& w) {
    w.add(node, 1.0);
    w.offset = -p;
  });
  return rows;
}

ConstraintRows node_slope_to_ground(Index node, const Vec3& d) {
  Vec3 t[2];
  perpendicular_pair(unit(d, "node slope to ground"), t[0], t[1]);
  ConstraintRows rows;
  for (const Vec3& ti : t) {
    DotConstraintRow& row = rows.add();
    row.u = AffineVector::constant(ti);
    row.w.add(node + 3, 1.0);
  }
  return rows;
}

ConstraintRows node_position_to_body(Index node, Index body, const Vec3& p_body) {
  require_finite(p_body, "node position to body");
  ConstraintRows rows;
  add_vector_rows(rows, [&](AffineVector& w) {
    w.add(node, 1.0);
    add_body_point(w, body, p_body, -1.0);
  });
  return rows;
}

ConstraintRows node_slope_to_body(Index node, Index body, const Vec3& d_body) {
  Vec3 t[2];
  perpendicular_pair(unit(d_body, "node slope to body"), t[0], t[1]);
  ConstraintRows rows;
  for (const Vec3& ti : t) {
    DotConstraintRow& row = rows.add();
    row.u.add_body(body, direction_weights(ti));
    row.w.add(node + 3, 1.0);
  }
  return rows;
}

ConstraintRows node_position_to_frame(Index node, int frame, const Vec3& p_frame) {
  require_finite(p_frame, "node position to driven frame");
  if (frame < 0) throw ModelError("node position to driven frame: invalid frame index");
  ConstraintRows rows;
  add_vector_rows(rows, [&](AffineVector& w) {
    w.add(node, 1.0);
    w.frame = frame;  // − (r_F(t) + A_F(t) p̄)
    w.frame_position_scale = -1.0;
    w.frame_vector = -p_frame;
  });
  return rows;
}

ConstraintRows node_slope_to_frame(Index node, int frame, const Vec3& d_frame) {
  if (frame < 0) throw ModelError("node slope to driven frame: invalid frame index");
  Vec3 t[2];
  perpendicular_pair(unit(d_frame, "node slope to driven frame"), t[0], t[1]);
  ConstraintRows rows;
  for (const Vec3& ti : t) {
    DotConstraintRow& row = rows.add();
    row.u.frame = frame;  // A_F(t) t̄_i
    row.u.frame_vector = ti;
    row.w.add(node + 3, 1.0);
  }
  return rows;
}

ConstraintRows node_to_node(Index node_a, Index node_b) {
  ConstraintRows rows;
  add_vector_rows(rows, [&](AffineVector& w) { w.add(node_a, 1.0).add(node_b, -1.0); });
  return rows;
}

ConstraintRows node_slope_to_node_slope(Index node_a, Index node_b) {
  ConstraintRows rows;
  add_vector_rows(rows, [&](AffineVector& w) { w.add(node_a + 3, 1.0).add(node_b + 3, -1.0); });
  return rows;
}

// --- rigid-body joints -----------------------------------------------------------------------

ConstraintRows body_spherical_to_ground(Index body, const Vec3& p_body, const Vec3& p) {
  require_finite(p_body, "spherical joint to ground (body point)");
  require_finite(p, "spherical joint to ground (ground point)");
  ConstraintRows rows;
  add_vector_rows(rows, [&](AffineVector& w) {
    add_body_point(w, body, p_body, 1.0);
    w.offset = -p;
  });
  return rows;
}

ConstraintRows body_revolute_to_ground(Index body, const Vec3& p_body, const Vec3& axis_body,
                                       const Vec3& p, const Vec3& axis) {
  ConstraintRows rows = body_spherical_to_ground(body, p_body, p);
  // t_i ⊥ n fixed in the ground, dotted with the body axis A ū.
  Vec3 t[2];
  perpendicular_pair(unit(axis, "revolute joint to ground (ground axis)"), t[0], t[1]);
  const Vec3 u = unit(axis_body, "revolute joint to ground (body axis)");
  for (const Vec3& ti : t) {
    DotConstraintRow& row = rows.add();
    row.u = AffineVector::constant(ti);
    row.w.add_body(body, direction_weights(u));
  }
  return rows;
}

ConstraintRows body_fixed_to_ground(Index body, const Vec3& p_body, const Vec3& p,
                                    const Mat3& rotation) {
  require_rotation(rotation, "fixed joint to ground");
  ConstraintRows rows = body_spherical_to_ground(body, p_body, p);
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {  // (A ē_i)·(R ē_j) = a_i · R_:j
      DotConstraintRow& row = rows.add();
      row.u.add(axis_block(body, i), 1.0);
      row.w = AffineVector::constant(rotation.col(j));
    }
  return rows;
}

ConstraintRows body_spherical(Index body1, const Vec3& p1, Index body2, const Vec3& p2) {
  require_finite(p1, "spherical joint (point of body 1)");
  require_finite(p2, "spherical joint (point of body 2)");
  ConstraintRows rows;
  add_vector_rows(rows, [&](AffineVector& w) {  // up to 4 + 4 block terms
    add_body_point(w, body1, p1, 1.0);
    add_body_point(w, body2, p2, -1.0);
  });
  return rows;
}

ConstraintRows body_revolute(Index body1, const Vec3& p1, const Vec3& axis1, Index body2,
                             const Vec3& p2, const Vec3& axis2) {
  ConstraintRows rows = body_spherical(body1, p1, body2, p2);
  add_body_axis_rows(rows, body1, axis1, body2, axis2);
  return rows;
}

ConstraintRows body_fixed(Index body1, const Vec3& p1, Index body2, const Vec3& p2,
                          const Mat3& relative_rotation) {
  require_rotation(relative_rotation, "fixed joint (relative rotation)");
  ConstraintRows rows = body_spherical(body1, p1, body2, p2);
  // A₂ R̄ᵀ ē_j = Σ_k R̄_jk a₂,k: the body-2 direction with body coordinates R̄ᵀ ē_j (row j of R̄).
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) {
      DotConstraintRow& row = rows.add();
      row.u.add(axis_block(body1, i), 1.0);
      row.w.add_body(body2, direction_weights(relative_rotation.row(j).transpose()));
    }
  return rows;
}

ConstraintRows body_orthonormality(Index body) {
  ConstraintRows rows;
  for (int i = 0; i < 3; ++i)
    for (int j = i; j < 3; ++j) {
      DotConstraintRow& row = rows.add();
      row.u.add(axis_block(body, i), 1.0);
      row.w.add(axis_block(body, j), 1.0);
      row.c = i == j ? -1.0 : 0.0;
    }
  return rows;
}

}  // namespace ancf
