// Private to the physics layer: the rod element frame with each intermediate as a jet in only the
// variables it depends on (node 1's frame in t₁, ζ = α₂ + ω in (t₁, t₂)), for the local-chain
// kernels (kirchhoff_rod_local_chain.cpp, kirchhoff_rod_distributed_moment.cpp). Same operations
// as element_frame (kirchhoff_rod_strains.hpp), so the values are bitwise equal.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "ancf/physics/jet.hpp"
#include "kirchhoff_rod_strains.hpp"

namespace ancf::rod_detail {

// Element coordinates of (t₁, t₂), the variables of ω's jets.
inline constexpr std::array<int, 6> kTangents{3, 4, 5, 9, 10, 11};

// A jet in N variables as one in M ⊇ them, its variables at [offset, offset + N).
template <int M, int N, bool S>
Jet<M, S> promote(const Jet<N, S>& x, int offset) {
  Jet<M, S> y(x.v);
  y.g.template segment<N>(offset) = x.g;
  if constexpr (S) y.h.template block<N, N>(offset, offset) = x.h;
  return y;
}
template <int M, int N, bool S>
V3<Jet<M, S>> promote(const V3<Jet<N, S>>& v, int offset) {
  return {promote<M>(v.x, offset), promote<M>(v.y, offset), promote<M>(v.z, offset)};
}

template <class J>
V3<J> variables(const V3<double>& v, int first) {
  return {J::variable(v.x, first), J::variable(v.y, first + 1), J::variable(v.z, first + 2)};
}

// Node 1's untwisted frame (t̂₁, d₂, d₃ of SR(R₁ → t̂₁)) as jets in t₁, and ζ = α₂ + ω as a
// jet in (t₁, t₂).
template <bool S>
struct NodeFrame {
  V3<Jet<3, S>> t1, n2, n3;
  Jet<6, S> zeta;
};

// element_frame (kirchhoff_rod_strains.hpp) with the same operations, each node's quantities as
// jets in its own tangent (3 variables) and only SR(Λ̄₁ → t̂₂) and ω in both (6).
template <bool S>
NodeFrame<S> staged_element_frame(const RodElementHistory& h, const Vec15& e) {
  using std::sqrt;
  using J3 = Jet<3, S>;
  using J6 = Jet<6, S>;
  const V3<J3> t1 = variables<J3>({e[3], e[4], e[5]}, 0),
               t2 = variables<J3>({e[9], e[10], e[11]}, 0);
  const J3 inv1 = 1.0 / sqrt(dot(t1, t1)), inv2 = 1.0 / sqrt(dot(t2, t2));
  const V3<J3> u1 = scale(inv1, t1), u2 = scale(inv2, t2);
  const V3<J3> r11 = constant<J3>(h.frame1.col(0)), r12 = constant<J3>(h.frame1.col(1)),
               r13 = constant<J3>(h.frame1.col(2));
  const J3 i1 = checked_inverse_denominator(1.0 + dot(r11, u1), "node 1 tangent");
  const V3<J3> n12 = sr_column(r11, r12, u1, i1), n13 = sr_column(r11, r13, u1, i1);
  const V3<J3> r21 = constant<J3>(h.frame2.col(0)), r22 = constant<J3>(h.frame2.col(1));
  const J3 i2 = checked_inverse_denominator(1.0 + dot(r21, u2), "node 2 tangent");
  const V3<J3> n22 = sr_column(r21, r22, u2, i2);
  const V3<J6> u1_6 = promote<6>(u1, 0), u2_6 = promote<6>(u2, 3), n22_6 = promote<6>(n22, 3);
  const J6 i12 = checked_inverse_denominator(1.0 + dot(u1_6, u2_6), "element end tangent");
  const V3<J6> m2 = sr_column(u1_6, promote<6>(n12, 0), u2_6, i12),
               m3 = sr_column(u1_6, promote<6>(n13, 0), u2_6, i12);
  J6 omega = atan2(dot(n22_6, m3), dot(n22_6, m2));
  omega =
      omega + 2.0 * std::numbers::pi * std::round((h.omega - omega.v) / (2.0 * std::numbers::pi));
  return {u1, n12, n13, J6(e[13]) + omega};
}

}  // namespace ancf::rod_detail
