// Gradient-deficient 3D ANCF cable element: elastic and Kelvin–Voigt internal forces with their
// analytic Jacobians (paper eqs. S1–S5; DESIGN §3).
//
// Coordinates e = [r_i, r_i,x, r_j, r_j,x] ∈ R¹² (positions in m, slopes dimensionless).
// With a = r_x and b = r_xx at a Gauss point and J₀ = |r⁰_x| of the stress-free reference:
//   Green–Lagrange (paper, S3):  ε = ½(a·a − J₀²)/J₀²,   κ = |a × b| / |a|³ (Gerstmayr–Shabana)
//   elastic line:                ε = |a|/J₀ − 1,           κ = |a × b| / |a|² (Gerstmayr–Irschik)
// Strain energy per element (S5 generalised):
//   U = ∫ [½ EA (ε + ε_p)² + ½ EI (κ − κ₀)²] J₀ dx,
// with ε_p the prestrain and κ₀ the reference curvature, so any reference (straight, arc, helix)
// is exactly stress-free when ε_p = 0. For a straight reference along its arc length J₀ = 1 and
// κ₀ = 0, and with EI = 0 this is exactly the paper's element. Damping (Kelvin–Voigt) adds the
// generalised force ∫ [c_a ε̇ ∂ε/∂e + c_b κ̃̇ ∂κ̃/∂e] J₀ dx with the regularized curvature
// κ̃ = √(κ² + κ_s²), which is smooth and objective (docs/formulation.md).
#pragma once

#include <array>
#include <cmath>
#include <numbers>

#include "ancf/core/gauss_legendre.hpp"
#include "ancf/core/types.hpp"

namespace ancf {

enum class StrainMeasure {
  green_lagrange,  ///< paper (S3) with Gerstmayr–Shabana curvature
  elastic_line,    ///< ε = |r_x| − 1, K = r_x × r_xx / |r_x|² (Gerstmayr & Irschik 2008)
};

/// Largest Gauss–Legendre rule per term (fixed-size arrays in CableElementReference).
inline constexpr int kMaxCableGaussPoints = 5;

/// Gauss–Legendre points per element for each term, 1 … kMaxCableGaussPoints. The default 5/5
/// integrates the Green axial force exactly (a polynomial of degree 8 in ξ, DESIGN §3) and
/// bending with the same points. An established elastic-line code integrates axial/bending with
/// 5/3, or reduced with 4/2; the linearized (straight, stress-free) stiffness is exact with ≥ 3
/// axial and ≥ 2 bending points (integrands of degree 4 and 2).
struct CableQuadrature {
  int axial = 5;    ///< axial strain and axial damping
  int bending = 5;  ///< curvature and bending damping
  friend bool operator==(const CableQuadrature&, const CableQuadrature&) = default;
};

/// Section-level constitutive data of one cable (all elements of a cable share it).
struct CableSection {
  StrainMeasure strain = StrainMeasure::green_lagrange;
  double axial_stiffness = 0.0;    ///< EA [N] (E₁A of the transversely isotropic law, S4)
  double bending_stiffness = 0.0;  ///< EI [N m²]; 0 → the paper's pure cable, no bending terms
  double mass_per_length = 0.0;    ///< ρA [kg/m]
  double prestrain = 0.0;          ///< ε_p [-]: the reference carries axial force EA·ε_p
  double axial_damping = 0.0;      ///< c_a [N s]: Kelvin–Voigt axial force c_a ε̇
  double bending_damping = 0.0;    ///< c_b [N m² s]: Kelvin–Voigt bending moment c_b κ̃̇
  /// κ_s [1/m] > 0: the bending damping acts on κ̃ = √(κ² + κ_s²), smooth and objective; it is
  /// c_b κ̇ for κ ≫ κ_s and fades like (κ/κ_s)² below (docs/formulation.md, "Bending damping").
  double bending_damping_curvature = 1.0;
  /// α [1/s]: mass-proportional (Rayleigh) damping, the distributed force −α ρA ṙ per unit length
  /// (consistent: −α M v on the cable's coordinates). Unlike Kelvin–Voigt it acts on every motion,
  /// rigid and zero-stiffness ones included (a drag against the inertial frame), so it does not
  /// conserve momentum. Applied by the system assembly, not by the element kernel.
  double mass_damping = 0.0;
  double radius = 0.0;           ///< r [m] of the cross-section; used only by contact (> 0 there)
  CableQuadrature quadrature{};  ///< Gauss points per term (per cable)

  [[nodiscard]] bool has_bending() const {
    return bending_stiffness > 0.0 || bending_damping > 0.0;
  }
  [[nodiscard]] bool has_damping() const { return axial_damping > 0.0 || bending_damping > 0.0; }
};

/// Area A = πd²/4 [m²] and second moment I = πd⁴/64 [m⁴] of a solid circular section of
/// diameter d [m] (> 0): EA, EI and ρA of a round cable from E and ρ.
struct CircularSection {
  double area = 0.0, second_moment = 0.0;
};
[[nodiscard]] inline CircularSection circular_section(double diameter) {
  return {std::numbers::pi * diameter * diameter / 4.0,
          std::numbers::pi * std::pow(diameter, 4) / 64.0};
}

/// Per-element data that depend only on the stress-free reference: shape-function derivatives,
/// integration weights and reference metric/curvature at the Gauss points of each term. Built
/// once per element.
struct CableElementReference {
  /// One term's Gauss points: the first `count` entries of each array are used.
  struct Points {
    int count = 0;
    std::array<Vec4, kMaxCableGaussPoints> d1;          ///< dS/dx at the Gauss points
    std::array<Vec4, kMaxCableGaussPoints> d2;          ///< d²S/dx² at the Gauss points
    std::array<double, kMaxCableGaussPoints> weight{};  ///< w_g · l · J₀_g (measure of J₀ dx)
    std::array<double, kMaxCableGaussPoints> inv_j0{};  ///< 1/J₀_g
    std::array<double, kMaxCableGaussPoints> kappa0{};  ///< κ₀ (per strain measure)
    /// The same as columns, one Gauss point per column, for the invariant force kernel
    /// (CableForceKernel): rows of d1, d2 are the entries 1…3 of d1[g], d2[g] (entry 0 is the
    /// negative of entry 2 for Hermite shapes). Columns ≥ count repeat the last point with
    /// weight 0, so that every column is finite and contributes nothing.
    Eigen::Matrix<double, 3, kMaxCableGaussPoints> lane_d1, lane_d2;
    Eigen::Array<double, 1, kMaxCableGaussPoints> lane_weight, lane_inv_j0, lane_kappa0;
    bool straight = true;  ///< κ₀ = 0 at every point
  };
  double length = 0.0;  ///< l [m]
  Points axial;         ///< points of the axial terms
  Points bending;       ///< points of the bending terms
  /// Both terms use the same rule: the element evaluates them in one loop.
  bool shared_points = true;

  /// Build from the reference nodal coordinates e0 and length l > 0. Throws ModelError if the
  /// reference has a vanishing slope at a Gauss point or a rule is outside 1 … 5 points.
  static CableElementReference from_reference(const Vec12& e0, double length, StrainMeasure strain,
                                              const CableQuadrature& quadrature = {});
};

/// Which matrix `stiffness` holds.
/// * exact: ∂f/∂e.
/// * tension_only: ∂f/∂e without the geometric term N ∂²ε/∂a² at the Gauss points where the axial
///   force N is compressive (N < 0), i.e. the tangent of a tension-field (string) model that
///   carries no compression stiffness. Force and energy are unchanged, so a Newton iteration with
///   it converges to the same solution as a modified Newton method. Why: a compressed EI = 0
///   element has a negative geometric stiffness (N < 0 along the slope directions of the
///   element) that the exact tangent carries into the iteration matrix of a slack rope, where it
///   makes the matrix indefinite near the slack/taut switch and Newton's full step overshoot
///   (docs/time_step_control.md, "Newton through contact").
enum class CableTangent { exact, tension_only };

/// How a force-only request (no matrix) is evaluated; both give the same force and energy up to
/// round-off.
/// * invariant: through the strain invariants s₁ = a·a, s₂ = a·b, s₃ = b·b, one rank-2 update of
///   ∂U/∂E per Gauss point on the translation-free coordinates [r_i,x, r_j − r_i, r_j,x]
///   (src/physics/cable_force_invariant.hpp); ≈ 3× fewer instructions.
/// * pointwise: the gradients in (a, b) scattered point by point, as the matrix path does (the
///   kernel of 3e3daf4 … issue 20).
enum class CableForceKernel { invariant, pointwise };

/// What to evaluate. Force and energy are always computed.
struct CableEvalRequest {
  bool stiffness = false;  ///< ∂f/∂e (includes ∂(damping force)/∂e when damping is present)
  bool damping_matrix = false;                 ///< ∂f/∂ė
  CableTangent tangent = CableTangent::exact;  ///< what `stiffness` holds (CableTangent)
  /// Kernel of a request without matrices (ignored when a matrix is requested).
  CableForceKernel force_kernel = CableForceKernel::invariant;
};

/// Element results. Sign convention: f is the internal force F of M q'' + F = Q, i.e. ∂U/∂e plus
/// the damping force.
struct CableElementResult {
  double energy = 0.0;  ///< U [J]
  Vec12 force;          ///< f [N]
  Mat12 stiffness;      ///< ∂f/∂e (valid if requested)
  Mat12 damping;        ///< ∂f/∂ė (valid if requested and the section has damping)
};

/// Evaluate the element at coordinates e and velocities e_dot (e_dot is read only when the
/// section has damping). Overwrites `out`. No heap allocation.
void evaluate_cable_element(const CableSection& section, const CableElementReference& ref,
                            const Vec12& e, const Vec12& e_dot, const CableEvalRequest& request,
                            CableElementResult& out);

/// Axial strain ε at ξ for diagnostics (e.g. tension N = EA(ε + ε_p) in outputs).
[[nodiscard]] double cable_axial_strain(StrainMeasure strain, const Vec12& e, double xi,
                                        double length, double j0);

}  // namespace ancf
