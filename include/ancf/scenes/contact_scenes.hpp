// Contact reference scenes shared by tests, benchmarks and studies (DESIGN §5, REFERENCES §6).
#pragma once

#include <string>

#include "ancf/system/model.hpp"

namespace ancf {

/// Capstan (Euler–Eytelwein, REFERENCES §6): a cable wrapped through angle θ over a cylinder of
/// radius R (axis +z through the origin, carried by a driven frame turning at ω about −z), pinned
/// at its incoming end ("anchor") and loaded by a dead force T_low along its outgoing end. The
/// cylinder surface slides under the resting cable at speed ω(R + r) ≫ v_ε from the anchor towards
/// the loaded end, so friction (on the cable: along the surface motion) is fully developed
/// everywhere and holds the cable back: the anchor carries T_high = T_low e^{μθ} in the limit
/// v_ε/(ω(R + r)) → 0 (kinematically the cable being pulled over a fixed cylinder towards the
/// anchor).
/// No gravity; small EI keeps the statics regular.
struct CapstanSpec {
  double wrap_angle = 3.141592653589793;  ///< θ [rad], 0 < θ < 2π
  double friction = 0.5;                  ///< μ
  double regularization_speed = 1e-3;     ///< v_ε [m/s]
  double surface_speed = 0.05;            ///< ω(R + r) [m/s]
  double low_tension = 10.0;              ///< T_low [N]
  double drum_radius = 0.05;              ///< R [m]
  double cable_radius = 0.002;            ///< r [m]
  double straight_length = 0.1;           ///< length of each straight end [m]
  double element_length = 0.005;          ///< target element length [m]
  int samples_per_element = 4;
};
[[nodiscard]] Model capstan_model(const CapstanSpec& spec);
/// Name of the anchor constraint (3 rows; its multipliers are the anchor reaction on the cable).
inline const std::string kCapstanAnchor = "anchor";

/// A straight cable (length 0.5 m, 10 elements) lying horizontally a height `drop_height` above
/// a ground plane z = 0, under gravity; Hunt–Crossley and Kelvin–Voigt damping bring it to rest.
struct DropSpec {
  double drop_height = 0.02;  ///< initial gap [m]
  double stiffness = 1e4;     ///< contact k [N/m²]
  double onset_depth = 2e-5;  ///< δ_s [m]
  double damping = 30.0;      ///< c_HC [s/m]
  double friction = 0.3;      ///< μ
  int samples_per_element = 3;
};
[[nodiscard]] Model drop_on_plane_model(const DropSpec& spec);

/// Two free crossing cables without gravity: cable "a" along x at rest, cable "b" along y above
/// it moving towards it at `speed`; frictionless cable–cable contact (no damping unless given).
[[nodiscard]] Model cable_impact_model(double speed = 1.0, double contact_damping = 0.0);

}  // namespace ancf
