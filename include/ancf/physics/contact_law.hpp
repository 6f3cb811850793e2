// Smooth penalty contact law per unit cable length (DESIGN §5).
//
// With gap g [m] (negative when penetrating), penetration δ = −g and penetration rate δ̇ = −ġ:
//   pressure   p(δ) = 0                       δ ≤ 0
//                   = k δ² / (2 δ_s)           0 < δ < δ_s      (C¹ onset: p and p' continuous)
//                   = k (δ − δ_s/2)            δ ≥ δ_s
//   normal     f_n = p(δ) · max(0, 1 + c_HC δ̇)                  (Hunt–Crossley-type damping,
//   vanishes
//                                                                with the penetration; Hunt &
//                                                                Crossley 1975)
//   friction   f_t = −μ f_n v_t / √(|v_t|² + v_ε²)               (regularized Coulomb)
// with v_t the tangential relative velocity. All forces are per unit reference length [N/m]; the
// contact kernels multiply them by the length weight of a sample.
#pragma once

#include <string>

#include "ancf/core/types.hpp"

namespace ancf {

struct ContactLaw {
  double stiffness = 0.0;     ///< k [N/m²] (force per unit length per unit penetration) > 0
  double onset_depth = 1e-4;  ///< δ_s [m] > 0: penetration over which the stiffness ramps up
  double damping = 0.0;       ///< c_HC [s/m] ≥ 0
  double friction = 0.0;      ///< μ [-] ≥ 0
  double regularization_speed = 1e-3;  ///< v_ε [m/s] > 0 (used only when μ > 0)

  /// Throws ModelError naming `owner` and the offending parameter unless the preconditions hold.
  void validate(const std::string& owner) const;

  /// p(δ) and dp/dδ.
  struct Pressure {
    double value = 0.0, derivative = 0.0;
  };
  [[nodiscard]] Pressure pressure(double penetration) const;

  /// Static penetration δ at which p(δ) = f [N/m] (inverse of p, for checks and scene set-up).
  [[nodiscard]] double static_penetration(double force_per_length) const;
};

}  // namespace ancf
