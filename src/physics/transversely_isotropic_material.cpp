#include "ancf/physics/transversely_isotropic_material.hpp"

#include <Eigen/Dense>
#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

Mat3 TransverselyIsotropicMaterial::normal_compliance() const {
  // Symmetric compliance: ν₁₂/E₂ = ν₂₁/E₁ (paper's convention, see header).
  Mat3 s;
  s << 1.0 / e1, -nu21 / e1, -nu21 / e1,  //
      -nu21 / e1, 1.0 / e2, -nu32 / e2,   //
      -nu21 / e1, -nu32 / e2, 1.0 / e2;
  return s;
}

Mat3 TransverselyIsotropicMaterial::normal_stiffness() const { return normal_compliance().inverse(); }

double TransverselyIsotropicMaterial::axial_stress_s4(double eps1, double eps2) const {
  // (S4), written as printed in the paper.
  return (e1 * e1 * (nu32 - 1.0) * eps1 - 2.0 * e1 * e2 * nu21 * eps2) /
         (2.0 * e2 * nu21 * nu21 - e1 + e1 * nu32);
}

void TransverselyIsotropicMaterial::validate(const char* what) const {
  auto fail = [&](const std::string& msg) {
    throw ModelError(std::string(what) + ": " + msg);
  };
  if (!(e1 > 0.0)) fail("E1 must be > 0 Pa, got " + std::to_string(e1));
  if (!(e2 > 0.0)) fail("E2 must be > 0 Pa, got " + std::to_string(e2));
  if (!(density > 0.0)) fail("density must be > 0 kg/m^3, got " + std::to_string(density));
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(normal_compliance());
  if (!(eig.eigenvalues().minCoeff() > 0.0)) {
    fail("Poisson ratios nu21 = " + std::to_string(nu21) + ", nu32 = " + std::to_string(nu32) +
         " make the compliance indefinite (need |nu32| < 1 and 2 nu21^2 E2/E1 < 1 - nu32)");
  }
}

}  // namespace ancf
