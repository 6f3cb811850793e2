// One kernel for every holonomic constraint row of the model: Φ = u(q, t)·w(q, t) + c.
//
// In natural coordinates every joint and attachment of DESIGN §4 is at most bilinear in q: a body
// point or direction is linear in the body's coordinates, a node position or slope is a block of q,
// and a driven frame contributes known functions of time. Each row is therefore the dot product of
// two affine vector expressions
//   u(q, t) = Σ_k α_k q[b_k : b_k+3] + ū(t),   ū(t) = o + s·r_F(t) + A_F(t)·f
// plus a constant. From this single form all derivatives the integrators need follow exactly:
//   Φ_q      : block b_k of u gets α_k w, block of w gets α_k u
//   Φ_t      = u̇·w + u·ẇ               (˙ = explicit time derivative of the frame part)
//   Φ_tt     = ü·w + 2u̇·ẇ + u·ẅ
//   Φ_q v    = U·w + u·W                 (U = Σ α_k v[b_k], the velocity part of u)
//   (Φ_q v)_q: block of u gets α_k W, block of w gets α_k U
//   Φ_qt v   = U·ẇ + u̇·W
//   (Φ_t)_q  : block of u gets α_k ẇ, block of w gets α_k u̇   (u̇, ẇ do not depend on q)
//   ∂(Φ_qᵀλ)/∂q = λ Σ_{k∈u, m∈w} α_k β_m (I₃ at (b_k, b_m) and (b_m, b_k))
#pragma once

#include <array>
#include <span>

#include "ancf/core/types.hpp"
#include "ancf/physics/driven_frame.hpp"

namespace ancf {

/// α·q[block : block + 3] with `block` the global index of the first coordinate of a 3-block.
struct BlockTerm {
  Index block = 0;
  double coefficient = 0.0;
};

/// Affine vector expression in q and t (see file comment). Up to 8 block terms (two bodies).
struct AffineVector {
  static constexpr int kMaxTerms = 8;
  std::array<BlockTerm, kMaxTerms> terms{};
  int term_count = 0;
  Vec3 offset = Vec3::Zero();  ///< o
  int frame = -1;              ///< driven frame index, or −1
  double frame_position_scale = 0.0;    ///< s (multiplies the frame origin r_F(t))
  Vec3 frame_vector = Vec3::Zero();     ///< f (frame-fixed vector, multiplied by A_F(t))

  /// Append α·q[block : block + 3]; throws std::length_error beyond kMaxTerms.
  AffineVector& add(Index block, double coefficient);
  /// Append α·(c(p̄) ⊗ I₃) q_b of a body with first coordinate `body` (weights from rigid_body.hpp).
  AffineVector& add_body(Index body, const Vec4& weights, double coefficient = 1.0);
  [[nodiscard]] static AffineVector constant(const Vec3& value);
};

/// Time-derivative parts of an affine vector at (q, v, t).
struct AffineVectorState {
  Vec3 value;         ///< u
  Vec3 velocity;      ///< U = Σ α_k v[b_k]
  Vec3 time_rate;     ///< u̇ (explicit, from the frame)
  Vec3 time_accel;    ///< ü (explicit, from the frame)
};

[[nodiscard]] AffineVectorState evaluate(const AffineVector& u, std::span<const double> q,
                                         std::span<const double> v,
                                         std::span<const FrameKinematics> frames);

/// Φ = u·w + c.
struct DotConstraintRow {
  AffineVector u, w;
  double c = 0.0;
};

/// Per-row scalar results.
struct DotConstraintValues {
  double phi = 0.0;       ///< Φ
  double phi_t = 0.0;     ///< Φ_t
  double phi_q_v = 0.0;   ///< Φ_q v
  double gamma = 0.0;     ///< −[(Φ_q v)_q v + 2 Φ_qt v + Φ_tt]: acceleration-level right-hand side
};

[[nodiscard]] DotConstraintValues evaluate(const DotConstraintRow& row, std::span<const double> q,
                                           std::span<const double> v,
                                           std::span<const FrameKinematics> frames);

/// Which gradient gradient_blocks() returns.
enum class RowGradient {
  phi,                ///< Φ_q: u-blocks α_k w, w-blocks β_m u
  velocity,           ///< (Φ_q v)_q: u-blocks α_k W, w-blocks β_m U
  velocity_and_time,  ///< ∂(Φ_q v + Φ_t)/∂q: u-blocks α_k (W + ẇ), w-blocks β_m (U + u̇);
                      ///< the Jacobian of the velocity-level constraint (GGL, index 2)
};

/// Gradient blocks of a row: for term j of u (j < u.term_count) the 3-vector at block u.terms[j],
/// then the terms of w. `out_u` has u.term_count entries, `out_w` w.term_count. Blocks may repeat
/// (a_i·a_i, or one block in u and w): the caller accumulates.
void gradient_blocks(const DotConstraintRow& row, const AffineVectorState& u,
                     const AffineVectorState& w, RowGradient which, std::span<Vec3> out_u,
                     std::span<Vec3> out_w);
/// Same with `velocity = true` meaning RowGradient::velocity, false RowGradient::phi.
void gradient_blocks(const DotConstraintRow& row, const AffineVectorState& u,
                     const AffineVectorState& w, bool velocity, std::span<Vec3> out_u,
                     std::span<Vec3> out_w);

/// Geometric stiffness of one row, λ ∂(Φ_qᵀ)/∂q = λ Σ_{k∈u, m∈w} α_k β_m (I₃ at (b_k, b_m) and at
/// (b_m, b_k)): constant in q and t, symmetric. Calls add(row_block, col_block, coefficient) once per
/// 3×3 block, meaning K(row_block + i, col_block + i) += coefficient for i = 0, 1, 2. Both orders
/// are visited, so a pair sharing one block (a_i·a_i) correctly contributes 2λαβ to it; blocks
/// repeat, and the callback must accumulate.
template <class Add>
void add_geometric_stiffness(const DotConstraintRow& row, double lambda, Add&& add) {
  for (int k = 0; k < row.u.term_count; ++k)
    for (int m = 0; m < row.w.term_count; ++m) {
      const BlockTerm& a = row.u.terms[k];
      const BlockTerm& b = row.w.terms[m];
      const double coefficient = lambda * a.coefficient * b.coefficient;
      add(a.block, b.block, coefficient);
      add(b.block, a.block, coefficient);
    }
}

}  // namespace ancf
