// Private to the physics layer: the Kirchhoff rod's torsion energy with the projected torsion
// strain, RodTorsionStrain::projected (kirchhoff_rod_torsion.cpp), shared by both rod kernels.
#pragma once

#include <array>

#include "ancf/physics/kirchhoff_rod_element.hpp"

namespace ancf::rod_detail {

/// K₁ at one Gauss point with its derivatives in the 15 element coordinates (the Hessian only
/// where the stiffness is requested).
struct TorsionAtPoint {
  double value = 0.0;
  Vec15 gradient;
  Mat15 hessian;
};

using TorsionPoints = std::array<TorsionAtPoint, kRodGaussPoints>;

/// The weights r_q with which the w-orthogonal projection of values at the Gauss points onto
/// linear functions takes the value Σ_q r_q v_q at ξ = at (row p of P_pq for at = ξ_p).
[[nodiscard]] std::array<double, kRodGaussPoints> linear_projection_row(
    const std::array<double, kRodGaussPoints>& xi,
    const std::array<double, kRodGaussPoints>& weight, double at);

/// P_pq of RodElementReference::torsion_projection from the Gauss abscissae and weights.
[[nodiscard]] Eigen::Matrix<double, kRodGaussPoints, kRodGaussPoints> linear_projection(
    const std::array<double, kRodGaussPoints>& xi,
    const std::array<double, kRodGaussPoints>& weight);

/// Adds Σ_p w_p ½GJ (K̃₁_p − K̃₁⁰_p)² with its Kelvin–Voigt damping c_t K̃̇₁_p to out (energy,
/// force, and the stiffness / damping matrix as requested), K̃₁_p = Σ_q P_pq K₁_q. The kernels
/// then leave the torsion out of their Gauss-point loops.
void add_projected_torsion(const RodSection& section, const RodElementReference& ref,
                           const TorsionPoints& k1, const Vec15& e_dot,
                           const RodEvalRequest& request, RodElementResult& out);

}  // namespace ancf::rod_detail
