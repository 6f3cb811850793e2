// Private to the physics layer: the rod element frame with each intermediate as a jet in only the
// variables it depends on (node 1's frame in t₁, ζ = α₂ + ω in (t₁, t₂)), for the local-chain
// kernels (kirchhoff_rod_local_chain.cpp, kirchhoff_rod_distributed_moment.cpp). Same operations
// as element_frame (kirchhoff_rod_strains.hpp), so the values are bitwise equal.
#pragma once

#include <array>

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
  using J3 = Jet<3, S>;
  using J6 = Jet<6, S>;
  const UntwistedNodes<J3> n = untwisted_nodes(h, variables<J3>({e[3], e[4], e[5]}, 0),
                                               variables<J3>({e[9], e[10], e[11]}, 0));
  const V3<J6> u1 = promote<6>(n.u1, 0), u2 = promote<6>(n.u2, 3);
  const J6 i12 = checked_inverse_denominator(1.0 + dot(u1, u2), "element end tangent");
  const V3<J6> m2 = sr_column(u1, promote<6>(n.n12, 0), u2, i12),
               m3 = sr_column(u1, promote<6>(n.n13, 0), u2, i12);
  return {n.u1, n.n12, n.n13, J6(e[13]) + element_omega(promote<6>(n.n22, 3), m2, m3, h.omega)};
}

}  // namespace ancf::rod_detail
