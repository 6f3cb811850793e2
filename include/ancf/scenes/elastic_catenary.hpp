// The elastic catenary (Irvine, Cable Structures, 1981; REFERENCES §3): closed form and the cable
// model that converges to it, shared by test_statics_reference and the mesh-convergence study.
#pragma once

#include "ancf/solvers/static_solver.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/model.hpp"

namespace ancf {

/// Supports at equal height, span D, unstretched length L₀, weight w = ρA g per unstretched length.
struct ElasticCatenarySpec {
  double span = 0.8;             ///< D [m]
  double length = 1.0;           ///< L₀ [m]
  double mass_per_length = 0.1;  ///< ρA [kg/m]
  double gravity = 9.81;         ///< g [m/s²], along −z
  double axial_stiffness = 1e3;  ///< EA [N]
};

/// Irvine's closed form: horizontal tension H, mid-span sag and support tension.
struct CatenaryValues {
  double horizontal_tension = 0.0;  ///< H [N]
  double sag = 0.0;                 ///< f [m], depth of the mid-span point below the supports
  double support_tension = 0.0;     ///< T(0) = √(H² + V²) [N]
};

/// Solves x(L₀) = D for H (x(L₀) = H L₀/EA + (2H/w) asinh(V/H), V = wL₀/2, increasing in H) and
/// evaluates z(L₀/2) and T(0). Irvine's strain is T = EA (stretch − 1): the elastic-line measure.
[[nodiscard]] CatenaryValues irvine_catenary(const ElasticCatenarySpec& spec);

/// Inextensible catenary parameter a of 2a sinh(D/(2a)) = L (monotone in a; bisection).
[[nodiscard]] double catenary_parameter(double span, double length);

/// Inextensible catenary of a cable stretched by `stretch` (> 1 keeps a pure cable taut, its
/// tangent non-singular) as nodal coordinates of `elements` equal elements of the unstretched
/// cable: the initial guess of the Newton iteration.
[[nodiscard]] CableGeometry catenary_guess(const ElasticCatenarySpec& spec, Index elements,
                                           double stretch);

/// Elastic-line cable, EI = 0, straight reference along +x, started from catenary_guess(1.001),
/// pinned at (0, 0, 0) ("left support") and (D, 0, 0) ("right support"), gravity −g ẑ.
[[nodiscard]] Model elastic_catenary_model(const ElasticCatenarySpec& spec, Index elements);

struct CatenarySolution {
  double sag = 0.0;            ///< −z of the mid-span node (elements must be even) [m]
  double tension_left = 0.0;   ///< |λ| of the left pin = support tension [N]
  double tension_right = 0.0;  ///< |λ| of the right pin [N]
  StaticSolverStatistics stats;
};

/// Static solution of elastic_catenary_model. Precondition: `elements` even.
[[nodiscard]] CatenarySolution solve_elastic_catenary(const ElasticCatenarySpec& spec,
                                                      Index elements);

}  // namespace ancf
