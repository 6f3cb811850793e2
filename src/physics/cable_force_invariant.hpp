// Force-only cable kernel on the strain invariants (private to the physics layer; used by
// evaluate_cable_element when neither matrix is requested, CableForceKernel::invariant).
//
// At a Gauss point the elastic and Kelvin–Voigt energies depend on e only through
//   s₁ = a·a,  s₂ = a·b,  s₃ = b·b     (a = r_x = E d₁, b = r_xx = E d₂, E = [r_i r_i,x r_j
//   r_j,x]),
// ε = ½(s₁/J₀² − 1) or √s₁/J₀ − 1, κ² = (s₁s₃ − s₂²)/s₁ᵖ (p = 3 Gerstmayr–Shabana, 2 Gerstmayr–
// Irschik). With u_I = ∂U/∂s_I (elastic and damping terms alike: both forces are combinations of
// ∂s_I/∂e), ∂s₁/∂E = 2a d₁ᵀ, ∂s₂/∂E = a d₂ᵀ + b d₁ᵀ, ∂s₃/∂E = 2b d₂ᵀ, so the force of the point is
// the rank-2 update  F += a (2u₁ d₁ + u₂ d₂)ᵀ + b (u₂ d₁ + 2u₃ d₂)ᵀ  of the 3×4 matrix F = ∂U/∂E.
// The position parts of d₁, d₂ of the Hermite shapes satisfy d_0 = −d_2 (S₁ + S₃ = 1), so a and b
// are formed from X = [r_i,x, r_j − r_i, r_j,x] and (d_1, d_2, d_3): 3×3 work instead of 3×4, the
// element's translation drops out exactly, and f_{r_i} = −f_{r_j}.
// Same formulas as the pointwise kernel of cable_element.cpp (its force is this one up to
// round-off; tests compare both and check the force against the energy gradient).
#pragma once

#include "ancf/physics/cable_element.hpp"

namespace ancf::detail {

/// Below this fraction of κ₀ the current curvature direction is undefined (κ − κ₀ is not
/// differentiable at κ = 0); the κ₀-terms are dropped there (a subgradient choice). Shared by both
/// kernels.
inline constexpr double kVanishingCurvatureRatio = 1e-8;

/// Force and energy of one element (out.stiffness and out.damping untouched).
void evaluate_cable_force_invariant(const CableSection& section, const CableElementReference& ref,
                                    const Vec12& e, const Vec12& e_dot, CableElementResult& out);

}  // namespace ancf::detail
