// Smooth penalty contact law (contact_law.hpp, DESIGN §5).
//
// The pressure is a quadratic ramp over the onset depth δ_s followed by a straight line with the
// full stiffness k: p(δ) = kδ²/(2δ_s) on (0, δ_s) and k(δ − δ_s/2) beyond. Both p and p' are
// continuous at δ = 0 (0 and 0) and at δ = δ_s (kδ_s/2 and k), so the residual seen by the Newton
// iterations of both integrators is C¹ in the penetration.
#include "ancf/physics/contact_law.hpp"

#include <cmath>
#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

void ContactLaw::validate(const std::string& owner) const {
  auto fail = [&](const std::string& parameter, const std::string& expected, double got) {
    throw ModelError("contact law of '" + owner + "': " + parameter + " must be " + expected +
                     ", got " + std::to_string(got));
  };
  if (!(stiffness > 0.0) || !std::isfinite(stiffness))
    fail("stiffness k", "finite and > 0 N/m^2", stiffness);
  if (!(onset_depth > 0.0) || !std::isfinite(onset_depth))
    fail("onset depth", "finite and > 0 m", onset_depth);
  if (!(damping >= 0.0) || !std::isfinite(damping))
    fail("Hunt-Crossley damping c_HC", "finite and >= 0 s/m", damping);
  if (!(friction >= 0.0) || !std::isfinite(friction))
    fail("friction coefficient mu", "finite and >= 0", friction);
  // v_ε only enters the friction law; with μ = 0 its value is irrelevant and not checked.
  if (friction > 0.0 && (!(regularization_speed > 0.0) || !std::isfinite(regularization_speed)))
    fail("friction regularization speed", "finite and > 0 m/s when mu > 0", regularization_speed);
}

ContactLaw::Pressure ContactLaw::pressure(double penetration) const {
  const double d = penetration;
  if (!(d > 0.0)) return {};
  if (d < onset_depth) return {0.5 * stiffness * d * d / onset_depth, stiffness * d / onset_depth};
  return {stiffness * (d - 0.5 * onset_depth), stiffness};
}

double ContactLaw::static_penetration(double force_per_length) const {
  const double f = force_per_length;
  if (!(f > 0.0)) return 0.0;
  // p(δ_s) = kδ_s/2 separates the two branches; invert the quadratic or the linear one.
  if (f < 0.5 * stiffness * onset_depth) return std::sqrt(2.0 * onset_depth * f / stiffness);
  return f / stiffness + 0.5 * onset_depth;
}

}  // namespace ancf
