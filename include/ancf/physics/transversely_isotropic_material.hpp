// Transversely isotropic linear-elastic material of the cable (paper eqs. S2–S4).
#pragma once

#include "ancf/core/types.hpp"

namespace ancf {

/// Axis 1 is the cable axis; the 2–3 plane is the plane of isotropy (S2: E₂ = E₃, ν₂₁ = ν₃₁).
/// Poisson ratios follow the paper: under uniaxial stress along 1, ε₂ = ε₃ = −ν₂₁ ε₁; ν₃₂ couples
/// the transverse directions. Units: moduli in Pa, density in kg/m³.
struct TransverselyIsotropicMaterial {
  double e1 = 0.0;      ///< axial Young's modulus E₁ [Pa]
  double e2 = 0.0;      ///< transverse Young's modulus E₂ = E₃ [Pa]
  double nu21 = 0.0;    ///< axial–transverse Poisson ratio ν₂₁ [-]
  double nu32 = 0.0;    ///< transverse–transverse Poisson ratio ν₃₂ [-]
  double density = 0.0; ///< ρ [kg/m³]

  /// Isotropic special case E₁ = E₂ = E, ν₂₁ = ν₃₂ = ν.
  static TransverselyIsotropicMaterial isotropic(double e, double nu, double rho) {
    return {e, e, nu, nu, rho};
  }

  /// Compliance of the normal components: ε = S σ for (ε₁, ε₂, ε₃), (σ₁, σ₂, σ₃).
  [[nodiscard]] Mat3 normal_compliance() const;
  /// Stiffness of the normal components, C = S⁻¹.
  [[nodiscard]] Mat3 normal_stiffness() const;
  /// Axial stress of eq. (S4) for an axial strain ε₁ and equal transverse strains ε₂ = ε₃.
  [[nodiscard]] double axial_stress_s4(double eps1, double eps2) const;
  /// Transverse strain under uniaxial stress along 1: ε₂ = −ν₂₁ ε₁.
  [[nodiscard]] double uniaxial_transverse_strain(double eps1) const { return -nu21 * eps1; }

  /// Throws ModelError naming `what` if a modulus or density is not positive, or the compliance
  /// is not positive definite.
  void validate(const char* what) const;
};

}  // namespace ancf
