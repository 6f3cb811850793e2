// A distributed moment on a Kirchhoff rod element (kirchhoff_rod_element.hpp): a moment per unit
// reference length m [N m/m], fixed in space, acting on the material triad along the element.
#pragma once

#include "ancf/core/types.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"

namespace ancf {

/// Generalised force of m on the 15 element coordinates and its derivative. With the material
/// triad Λ = [g₁, g₂, g₃] of the element at ξ (the one its strains use, kirchhoff_rod_strains.hpp),
/// the virtual rotation is δθ = ½ Σ_k g_k × δg_k, so
///   Q_i = ∫ m·θ_{,i} ds = Σ_p w_p ½ Σ_k (m × g_k)·∂g_k/∂e_i,
///   ∂Q_i/∂e_j = Σ_p w_p ½ Σ_k [∂g_k/∂e_iᵀ [m]× ∂g_k/∂e_j + (m × g_k)·∂²g_k/∂e_i∂e_j]
/// over the element's Gauss points (weights w_p = w l J₀: reference arc length). The load is not
/// conservative (a dead moment on finite rotations): the Jacobian is not symmetric. The load
/// stiffness is its negative. A linear-twist element uses the first 14 entries (β = 0).
struct RodDistributedMomentLoad {
  Vec15 force;     ///< Q [N m] on (r₁, t₁, r₂, t₂, α₁, α₂, β)
  Mat15 jacobian;  ///< ∂Q/∂e
};

/// Evaluate under `history` (as evaluate_rod_element). `jacobian` only if requested. No heap
/// allocation. Throws std::domain_error as evaluate_rod_element does. `kernel` as for the element:
/// local_chain (jets in the triad's nine local variables, chained to e) or element_jets (jets in
/// all 15 coordinates; the first version, kept for comparison); both agree to round-off.
void rod_distributed_moment(const RodElementReference& ref, const RodElementHistory& history,
                            const Vec15& e, const Vec3& moment_per_length, bool jacobian,
                            RodDistributedMomentLoad& out,
                            RodKernel kernel = RodKernel::local_chain);

}  // namespace ancf
