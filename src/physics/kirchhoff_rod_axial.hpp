// Private to the physics layer: the Kirchhoff rod's axial energy with the collocated
// (re-interpolated) axial strain, RodAxialStrain::collocated (kirchhoff_rod_axial.cpp), shared
// by both rod kernels.
#pragma once

#include "ancf/physics/kirchhoff_rod_element.hpp"

namespace ancf::rod_detail {

/// Quadratic Lagrange polynomials on the collocation points ξ_c = 0, ½, 1 at ξ.
[[nodiscard]] std::array<double, 3> collocation_lagrange(double xi);

/// Adds ½ Σ_p w_p EA ε̃_p² and its Kelvin–Voigt damping c_a ε̃̇_p to out (energy, force, and the
/// stiffness / damping matrix as requested), with ε̃_p = Σ_c L_c(ξ_p) (|r_x(ξ_c)|/J₀(ξ_c) − 1).
/// The kernels then leave the axial strain out of their Gauss-point loops.
void add_collocated_axial(const RodSection& section, const RodElementReference& ref, const Vec15& e,
                          const Vec15& e_dot, const RodEvalRequest& request, RodElementResult& out);

}  // namespace ancf::rod_detail
