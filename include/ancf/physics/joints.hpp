// Constraint kinds of DESIGN §4 as DotConstraintRow sets (dot_constraint.hpp). Nodes are given by
// the global index of their first coordinate (r at +0, r_x at +3), bodies by the index of their
// first coordinate (r_O at +0, a_k at +3k), driven frames by their index in the model.
#pragma once

#include <array>

#include "ancf/physics/dot_constraint.hpp"

namespace ancf {

/// Up to six rows of one constraint.
struct ConstraintRows {
  std::array<DotConstraintRow, 6> rows{};
  int count = 0;
  DotConstraintRow& add() { return rows[count++]; }
};

/// Unit vectors t₁, t₂ with (t₁, t₂, d/|d|) right-handed orthonormal. Precondition: |d| > 0.
void perpendicular_pair(const Vec3& d, Vec3& t1, Vec3& t2);

// --- cable node attachments ---------------------------------------------------------------
/// r − p = 0 (3 rows).
[[nodiscard]] ConstraintRows node_position_to_ground(Index node, const Vec3& p);
/// t_i·r_x = 0, t_i ⊥ d (2 rows): slope parallel to d.
[[nodiscard]] ConstraintRows node_slope_to_ground(Index node, const Vec3& d);
/// r − (r_O + Σ p̄_k a_k) = 0 (3 rows).
[[nodiscard]] ConstraintRows node_position_to_body(Index node, Index body, const Vec3& p_body);
/// (Σ t̄_ik a_k)·r_x = 0 with t̄_i ⊥ d̄ (2 rows): slope parallel to the body direction d̄.
[[nodiscard]] ConstraintRows node_slope_to_body(Index node, Index body, const Vec3& d_body);
/// r − (r_F(t) + A_F(t) p̄) = 0 (3 rows, rheonomic).
[[nodiscard]] ConstraintRows node_position_to_frame(Index node, int frame, const Vec3& p_frame);
/// (A_F(t) t̄_i)·r_x = 0 with t̄_i ⊥ d̄ (2 rows, rheonomic).
[[nodiscard]] ConstraintRows node_slope_to_frame(Index node, int frame, const Vec3& d_frame);
/// r_A − r_B = 0 (3 rows): joins two cable nodes.
[[nodiscard]] ConstraintRows node_to_node(Index node_a, Index node_b);
/// r_x,A − r_x,B = 0 (3 rows): equal slopes (a C¹ junction) — use with node_to_node.
[[nodiscard]] ConstraintRows node_slope_to_node_slope(Index node_a, Index node_b);

// --- rigid-body joints -----------------------------------------------------------------------
/// Body point p̄ at the ground point p (3 rows).
[[nodiscard]] ConstraintRows body_spherical_to_ground(Index body, const Vec3& p_body, const Vec3& p);
/// Spherical + body axis ū ∥ ground axis n (5 rows).
[[nodiscard]] ConstraintRows body_revolute_to_ground(Index body, const Vec3& p_body,
                                                     const Vec3& axis_body, const Vec3& p,
                                                     const Vec3& axis);
/// Spherical + rotation fixed at `rotation` (3 rows (A ē_i)·(R ē_j) = 0, i < j) (6 rows).
[[nodiscard]] ConstraintRows body_fixed_to_ground(Index body, const Vec3& p_body, const Vec3& p,
                                                  const Mat3& rotation);
/// Point p̄₁ of body 1 coincides with p̄₂ of body 2 (3 rows).
[[nodiscard]] ConstraintRows body_spherical(Index body1, const Vec3& p1, Index body2, const Vec3& p2);
/// Spherical + axis ū₁ of body 1 ∥ axis ū₂ of body 2 (5 rows).
[[nodiscard]] ConstraintRows body_revolute(Index body1, const Vec3& p1, const Vec3& axis1,
                                           Index body2, const Vec3& p2, const Vec3& axis2);
/// Spherical + relative rotation fixed: (A₁ ē_i)·(A₂ R̄ᵀ ē_j) = 0 for i < j, with R̄ = A₁ᵀA₂ at
/// assembly (`relative_rotation`) (6 rows).
[[nodiscard]] ConstraintRows body_fixed(Index body1, const Vec3& p1, Index body2, const Vec3& p2,
                                        const Mat3& relative_rotation);
/// a_i·a_j − δ_ij = 0 for i ≤ j (6 rows).
[[nodiscard]] ConstraintRows body_orthonormality(Index body);

}  // namespace ancf
