// The twist condition that ties a Kirchhoff rod node's material triad to a vector b fixed in a
// rigid body, in a driven frame or in space (docs/rod.md, "Rod end fixed to a body or frame"):
//
//   Φ = d₂ · b = 0,   d₂ = cos α s₂ + sin α s₃,   s_k = R_k − (R_k·t̂)/(1 + R₁·t̂) (t̂ + R₁),
//
// with R the node's committed reference triad (history, rod_history.hpp), t̂ = r_x/|r_x| and α
// the node's twist angle: d₂ is the second column of Λ = Rot_t̂(α) SR(R → t̂) (Meier, Popp & Wall,
// CMAME 278 (2014), TAN parametrisation; kirchhoff_rod_element.hpp). b is chosen as the node's d₃
// at the initial configuration, so Φ = 0 there and ∂Φ/∂α = d₃·b = 1: together with the slope
// kept parallel to a body direction (joints.hpp, two dot rows) the whole material triad is fixed
// in the body. The row is not bilinear in q (α enters through cos, sin; t through t̂ and the
// smallest rotation), so it is not a DotConstraintRow.
//
// b(q, t) is an AffineVector (dot_constraint.hpp): Σ b̄_k a_k of a body (three terms, linear in
// q), A_F(t) b̄ of a driven frame, or a constant. With z = (r_x, α, b) ∈ R⁷ and φ(z) = d₂·b:
//   Φ_q      = Jᵀ ∇φ,   J = ∂z/∂q (identity on r_x and α, b̄_k I₃ on a body's a_k)
//   Φ_qq     = Jᵀ ∇²φ J                    (∂²φ/∂b² = 0: linear in b)
//   Φ_q v    = ∇φ · (v_x, U),  Φ_t = φ_b · ḃ_F          (U = Σ b̄_k v(a_k), ḃ_F the frame part)
//   ∂(Φ_q v + Φ_t)/∂q = Jᵀ ∇²φ ż,   ż = (v_x, U + ḃ_F)
//   γ = −[(Φ_q v)_q v + 2 Φ_qt v + Φ_tt] = −[żᵀ ∇²φ ż + φ_b · b̈_F]
// The derivatives of d₂ come from second-order forward differentiation (jet.hpp), exact to
// round-off; test_rod_twist_constraint checks every block against central differences.
#pragma once

#include <array>
#include <span>

#include "ancf/core/types.hpp"
#include "ancf/physics/dot_constraint.hpp"
#include "ancf/physics/driven_frame.hpp"

namespace ancf {

/// One twist row of a rod node, in global coordinate indices.
struct RodTwistRow {
  Index slope = 0;  ///< global index of the node's r_x (3 coordinates)
  Index twist = 0;  ///< global index of the node's twist angle α
  AffineVector b;   ///< b(q, t), at most kMaxBodyTerms block terms
  static constexpr int kMaxBodyTerms = 3;
  static constexpr int kMaxColumns = 4 + 3 * kMaxBodyTerms;  ///< r_x, α, 3 per term of b
};

using Vec7 = Eigen::Matrix<double, 7, 1>;
using Mat7 = Eigen::Matrix<double, 7, 7>;

/// φ = d₂(r_x, α; R)·b with gradient and Hessian in z = (r_x, α, b).
struct RodTwistLocal {
  double phi = 0.0;
  Vec7 gradient;
  Mat7 hessian;
};
/// Throws std::domain_error if the tangent turned against R's first column (1 + R₁·t̂ ≤ 10⁻⁸),
/// as the rod element does, and std::invalid_argument if r_x = 0.
[[nodiscard]] RodTwistLocal rod_twist_condition(const Mat3& reference, const Vec3& slope,
                                                double alpha, const Vec3& b);

/// The row's values and derivatives on its columns at (q, v, t).
struct RodTwistRowValues {
  static constexpr int kN = RodTwistRow::kMaxColumns;
  int column_count = 0;
  std::array<Index, kN> columns{};       ///< r_x (3), α, then 3 per term of b
  Eigen::Matrix<double, kN, 1> phi_q;    ///< Φ_q
  Eigen::Matrix<double, kN, 1> psi_q;    ///< ∂(Φ_q v + Φ_t)/∂q (zero if v is empty)
  Eigen::Matrix<double, kN, kN> phi_qq;  ///< Φ_qq (symmetric)
  double phi = 0.0, phi_t = 0.0, phi_q_v = 0.0;
  double gamma = 0.0;  ///< acceleration-level right-hand side (see file comment)
};

/// The columns of a row (the same order evaluate() uses); returns their count.
int rod_twist_columns(const RodTwistRow& row, std::array<Index, RodTwistRow::kMaxColumns>& out);

/// Evaluate the row under the node's committed reference triad. `v` may be empty (then v = 0).
void evaluate(const RodTwistRow& row, const Mat3& reference, std::span<const double> q,
              std::span<const double> v, std::span<const FrameKinematics> frames,
              RodTwistRowValues& out);

}  // namespace ancf
