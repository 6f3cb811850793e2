// Kirchhoff rod element that can twist: the cable's cubic Hermite position/slope centreline plus a
// twist angle per node, carrying a material frame (docs/rod.md). After Meier, Popp & Wall,
// "An objective 3D large deformation finite element formulation for geometrically exact curved
// Kirchhoff rods", CMAME 278 (2014) 445–478, tangent-based nodal parametrisation ("TAN"), with the
// triad field interpolated from node 1 by the smallest rotation (SR) and a quadratic twist angle
// (Meier et al.'s three twist collocation points, here as a hierarchical bubble).
//
// Element coordinates e = [r₁, t₁, r₂, t₂, α₁, α₂, β] ∈ R¹⁵ (r in m, t = r_x dimensionless, α and
// the element's interior twist β in rad).
// Each node i keeps a committed untwisted reference triad R_i (history, columns [tangent, d₂, d₃]);
// its material triad is Λ_i = Rot_{t̂ᵢ}(αᵢ) · SR(R_i → t̂ᵢ). Inside the element
//   Λ(ξ) = Rot_{g₁}(ψ(ξ)) · SR(Λ̄₁ → g₁(ξ)),  g₁ = r_x/|r_x|,  Λ̄₁ = SR(R₁ → t̂₁),
//   ψ(ξ) = (1 − ξ) α₁ + ξ (α₂ + ω) + 4ξ(1 − ξ) β,
// where ω is the angle about t̂₂ from SR(Λ̄₁ → t̂₂) to Λ̄₂ = SR(R₂ → t̂₂), tracked continuously from
// its committed value ω_c (no ±π wrap). So Λ(0) = Λ₁ and Λ(1) = Λ₂: the frame is continuous
// across elements; β = 0 is the linear twist (RodTwist::linear gives β no coordinate). Strains per
// unit reference arc length s (J₀ = |r⁰_x|, κ = r_x × r_xx/|r_x|²):
//   ε = |r_x|/J₀ − 1,  K₁ = [ψ_x − (t̂₁·κ)/(1 + t̂₁·g₁)]/J₀,  K₂ = κ·g₂/J₀,  K₃ = κ·g₃/J₀,
// energy U = ∫ ½[EA ε² + GJ (K₁−K₁⁰)² + EI₂ (K₂−K₂⁰)² + EI₃ (K₃−K₃⁰)²] J₀ dx with K⁰ the same
// formulas at the reference configuration and reference triads (exactly stress-free); by default
// ε is collocated and K₁ projected over the element (RodAxialStrain, RodTorsionStrain: against
// membrane and twist locking).
// Kelvin–Voigt damping adds Σ c_k K̇_k ∂K_k/∂e. Force and tangent are exact (second-order
// forward differentiation, jet.hpp); no finite differences.
#pragma once

#include <array>

#include "ancf/core/types.hpp"

namespace ancf {

/// Coordinates of a rod element (with the interior twist β last).
inline constexpr int kRodElementCoordinates = 15;
using Vec15 = Eigen::Matrix<double, kRodElementCoordinates, 1>;
using Mat15 = Eigen::Matrix<double, kRodElementCoordinates, kRodElementCoordinates>;

/// Gauss points per rod element (4, as 4C's beam3k: exact for the linearised straight element).
inline constexpr int kRodGaussPoints = 4;

/// The smallest rotation SR(source → g) is (nearly) undefined once 1 + (source tangent)·g is at
/// or below this: the element throws std::domain_error there, and the model builder refuses an
/// initial configuration whose node tangent points that far against the reference frame's.
inline constexpr double kRodSmallestRotationDenominatorMin = 1e-8;

/// Where the axial strain of the energy ½EA ε² is taken.
enum class RodAxialStrain {
  /// ε = |r_x|/J₀ − 1 at each Gauss point. Locks in bending of slender curved elements
  /// (membrane locking: docs/rod.md measures it).
  gauss_points,
  /// ε at the three collocation points ξ = 0, ½, 1, re-interpolated to the Gauss points by the
  /// quadratic Lagrange polynomials (the assumed strain of Meier, Popp & Wall, "A locking-free
  /// finite element formulation and reduced models for geometrically exact Kirchhoff rods",
  /// CMAME 290 (2015) 314–341; 4C's BEAM3K `epsilon_cp`). The default.
  collocated,
};

/// How the twist angle ψ is interpolated along an element.
enum class RodTwist {
  /// ψ = (1 − ξ)α₁ + ξ(α₂ + ω): no interior coordinate. The twist rate is constant per element,
  /// which limits bending–torsion coupling on curved rods to O(h²) (docs/rod.md).
  linear,
  /// Plus the bubble 4ξ(1 − ξ)β with one interior twist coordinate β per element: the same
  /// polynomial space as the quadratic Lagrange twist of Meier, Popp & Wall (2014) and 4C's BEAM3K
  /// (three collocation points), the degree of the centreline's tangent. The default.
  quadratic,
};

/// Where the torsion of the energy ½GJ (K₁ − K₁⁰)² is taken.
enum class RodTorsionStrain {
  /// K₁ at each Gauss point. On a curved element bent out of its plane, keeping K₁ = K₁⁰ at four
  /// points also constrains the centreline (the smallest-rotation twist rate is not polynomial):
  /// torsion-stiff curved rods lock and converge as h² (docs/rod.md).
  gauss_points,
  /// K₁ replaced by its L2 projection onto linear functions over the element (weights of the
  /// Gauss rule): two torsion conditions per element, the number of its twist freedoms. An
  /// assumed-strain choice of ours in the spirit of the collocated axial strain; exact for a
  /// straight rod, where K₁ = ψ_x is linear. The default.
  projected,
};

/// Section data of a rod (all elements of a rod share it). Units SI.
struct RodSection {
  double axial_stiffness = 0.0;      ///< EA [N]
  double torsional_stiffness = 0.0;  ///< GJ [N m²]
  double bending_stiffness_2 = 0.0;  ///< EI₂ [N m²] (bending about d₂: curvature K₂ = κ·d₂)
  double bending_stiffness_3 = 0.0;  ///< EI₃ [N m²]
  double mass_per_length = 0.0;      ///< ρA [kg/m]
  double polar_inertia = 0.0;        ///< ρJ_p [kg m] (rotary inertia of the twist per length)
  double axial_damping = 0.0;        ///< c_a [N s]: axial force c_a ε̇
  double torsional_damping = 0.0;    ///< c_t [N m² s]: torque c_t K̇₁
  double bending_damping = 0.0;      ///< c_b [N m² s]: bending moments c_b K̇₂, c_b K̇₃
  RodAxialStrain axial_strain = RodAxialStrain::collocated;
  RodTwist twist = RodTwist::quadratic;
  RodTorsionStrain torsion_strain = RodTorsionStrain::projected;
  [[nodiscard]] bool has_damping() const {
    return axial_damping > 0.0 || torsional_damping > 0.0 || bending_damping > 0.0;
  }
};

/// History of one element: committed untwisted reference triads of its two nodes and ω_c.
struct RodElementHistory {
  Mat3 frame1 = Mat3::Identity();  ///< R₁, columns [unit tangent, d₂, d₃]
  Mat3 frame2 = Mat3::Identity();  ///< R₂
  double omega = 0.0;              ///< ω_c [rad]
};

/// Data of the stress-free reference at the Gauss points (built once per element).
struct RodElementReference {
  double length = 0.0;                           ///< l [m]
  Vec12 e0;                                      ///< reference centreline coordinates
  std::array<double, kRodGaussPoints> xi{};      ///< Gauss abscissae in [0, 1]
  std::array<Vec4, kRodGaussPoints> d1, d2;      ///< dS/dx, d²S/dx² (hermite_shape.hpp)
  std::array<double, kRodGaussPoints> weight{};  ///< w_g l J₀
  std::array<double, kRodGaussPoints> inv_j0{};  ///< 1/J₀
  std::array<Vec3, kRodGaussPoints> k0{};        ///< (K₁⁰, K₂⁰, K₃⁰)
  /// Axial strain at the collocation points ξ_c = 0, ½, 1 (RodAxialStrain::collocated):
  /// dS/dx there, 1/J₀ there, and the Lagrange weights L_c(ξ_p) of each Gauss point p.
  std::array<Vec4, 3> collocation_d1;
  std::array<double, 3> collocation_inv_j0{};
  std::array<std::array<double, 3>, kRodGaussPoints> collocation_weight{};
  /// RodTorsionStrain::projected: K̃₁(ξ_p) = Σ_q P_pq K₁(ξ_q), the projection onto linear
  /// functions orthogonal in the weights w_q; and the reference's K̃₁⁰ at the Gauss points.
  Eigen::Matrix<double, kRodGaussPoints, kRodGaussPoints> torsion_projection;
  std::array<double, kRodGaussPoints> projected_k10{};

  /// From the reference centreline e0 (12), length l > 0 and the reference history (the nodes'
  /// reference material triads with α = 0; history.omega is set here). Throws ModelError if a
  /// slope vanishes or a triad's first column is not the unit reference tangent.
  static RodElementReference from_reference(const Vec12& e0, double length,
                                            RodElementHistory& history);
};

/// How the element's derivatives are formed; both are exact and agree to round-off (the values,
/// energy and strains are bitwise the same).
enum class RodKernel {
  /// Per Gauss point, jets in the 12 local variables (r_x, r_xx, t₁, α₁, ζ, β) chained to the
  /// element coordinates by the point's linear map B and ζ's Hessian: K = Σ Bᵀ H B + c_ζ H_ζ.
  local_chain,
  /// Jets in all 15 element coordinates through every operation (the original kernel, kept for
  /// comparison: test_kirchhoff_rod_element, bench_rod_element).
  element_jets,
};

struct RodEvalRequest {
  bool stiffness = false;       ///< ∂f/∂e (includes ∂(damping force)/∂e)
  bool damping_matrix = false;  ///< ∂f/∂ė
  RodKernel kernel = RodKernel::local_chain;
};

/// Sign convention as the cable's: f = ∂U/∂e plus the damping force (M q'' + f = Q).
struct RodElementResult {
  double energy = 0.0;  ///< U [J]
  Vec15 force;
  Mat15 stiffness;  ///< valid if requested
  Mat15 damping;    ///< valid if requested and the section has damping
  Vec3 strain_mid;  ///< (K₁, K₂, K₃) at the Gauss point nearest ξ = ½ (diagnostics) [1/m]
};

/// Evaluate at e and ė (ė read only with damping). No heap allocation. Throws std::domain_error
/// when a tangent turns against its smallest-rotation source (1 + t̂·R₁ ≤ 10⁻⁸): the step is too
/// large for the committed history or the mesh too coarse (a recoverable "not evaluable here").
void evaluate_rod_element(const RodSection& section, const RodElementReference& ref,
                          const RodElementHistory& history, const Vec15& e, const Vec15& e_dot,
                          const RodEvalRequest& request, RodElementResult& out);

/// Material triad and strains at a point ξ ∈ [0, 1] of the element (diagnostics, outputs, tests).
struct RodPointState {
  Mat3 triad;           ///< columns [g₁, d₂, d₃]
  double axial_strain;  ///< ε = |r_x|/J₀ − 1 at ξ itself (not re-interpolated)
  Vec3 curvature;       ///< (K₁, K₂, K₃) [1/m] (not minus the reference's)
};
[[nodiscard]] RodPointState rod_point_state(const RodElementReference& ref,
                                            const RodElementHistory& history, const Vec15& e,
                                            double xi);

/// The torsion strain K₁ − K₁⁰ [1/m] that the section's energy sees at ξ ∈ [0, 1]; the section
/// torque is GJ times it. RodTorsionStrain::gauss_points: pointwise at ξ, K₁⁰ from the stress-free
/// state (ref.e0, zero twist, under reference_history: the nodes' reference triads and ω).
/// RodTorsionStrain::projected: the element's linear projection of K₁ − K₁⁰ over its Gauss points
/// (RodElementReference::torsion_projection) evaluated at ξ, so that
/// U_torsion = Σ_p w_p ½ GJ s(ξ_p)². history and e as for rod_point_state.
[[nodiscard]] double rod_torsion_strain(const RodSection& section, const RodElementReference& ref,
                                        const RodElementHistory& reference_history,
                                        const RodElementHistory& history, const Vec15& e,
                                        double xi);

/// The current ω of an element (continuous from history.omega), for committing history.
[[nodiscard]] double rod_element_omega(const RodElementHistory& history, const Vec15& e);

/// SR(R → t̂): the triad obtained from R by the smallest rotation taking its first column onto
/// t/|t|. Precondition: t ≠ 0 and not antiparallel to R's first column.
[[nodiscard]] Mat3 smallest_rotation(const Mat3& frame, const Vec3& t);

/// Material triad Λ = Rot_{t̂}(α) SR(R → t̂) of a node (columns [t̂, d₂, d₃]).
[[nodiscard]] Mat3 rod_material_triad(const Mat3& reference, const Vec3& t, double alpha);

/// Generalised force of a moment M [N m] fixed in space acting on a node's material triad, on the
/// node's (t, α): the virtual rotation of Λ = Rot_{t̂}(α) SR(R → t̂) is
///   δθ = t̂ × δt̂ + t̂ [δα − (R₁ × t̂)·δt̂/(1 + R₁·t̂)],   δt̂ = (I − t̂t̂ᵀ) δt/|t|,
/// so Q_t = [M × t̂ − (M·t̂)(R₁ × t̂)/(1 + R₁·t̂)]/|t| and Q_α = M·t̂. `jacobian` = ∂Q/∂(t, α)
/// (4×4; its α column is zero); the load stiffness is its negative.
struct RodMomentLoad {
  Vec4 force;                ///< (Q_t, Q_α)
  Eigen::Matrix4d jacobian;  ///< ∂Q/∂(t, α)
};
[[nodiscard]] RodMomentLoad rod_end_moment(const Mat3& reference, const Vec3& t,
                                           const Vec3& moment);

/// Consistent twist inertia of one element, ρJ_p l ∫ N Nᵀ dξ with N = (1 − ξ, ξ, 4ξ(1 − ξ)), on
/// (α₁, α₂, β): ρJ_p l [[1/3, 1/6, 1/3], [1/6, 1/3, 1/3], [1/3, 1/3, 8/15]] (its upper-left 2×2 is
/// the linear twist's). Neglects the angular rate of the smallest-rotation frame itself (which
/// vanishes at the committed state; docs/rod.md).
[[nodiscard]] Mat3 rod_twist_mass(double polar_inertia, double length);

}  // namespace ancf
