// Private to the physics layer: the Kirchhoff rod's strains as templates over the scalar type
// (double, or a jet of jet.hpp), shared by the element kernels (kirchhoff_rod_element.cpp,
// kirchhoff_rod_local_chain.cpp). Formulas and their source: kirchhoff_rod_element.hpp and
// docs/rod.md (Meier, Popp & Wall, CMAME 278 (2014), tangent-based triads, smallest rotation).
#pragma once

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "ancf/core/types.hpp"
#include "ancf/physics/jet.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"

namespace ancf::rod_detail {

// 1 + (source tangent)·(target tangent) below this: the smallest rotation is (nearly) undefined.
inline constexpr double kSrDenominatorMin = kRodSmallestRotationDenominatorMin;

// A 3-vector of a scalar type T (double or a jet); only the operations the strains need.
template <class T>
struct V3 {
  T x, y, z;
};
template <class T>
V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
V3<T> operator-(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T, class S>
V3<T> scale(const S& s, const V3<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
T dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
V3<T> constant(const Vec3& c) {
  return {T(c.x()), T(c.y()), T(c.z())};
}

// Column k of SR(source → g) for unit g, source columns (s1, s_k):
//   s_k − (s_k·g)/(1 + s1·g) (g + s1)        (Meier et al. 2014; 4C calculate_sr_triads).
template <class T>
V3<T> sr_column(const V3<T>& s1, const V3<T>& sk, const V3<T>& g, const T& inv_denominator) {
  return sk - scale(dot(sk, g) * inv_denominator, g + s1);
}

template <class T>
T checked_inverse_denominator(const T& denominator, const char* where) {
  if (!(value_of(denominator) > kSrDenominatorMin))
    throw std::domain_error(std::string("Kirchhoff rod: ") + where +
                            " turned against its smallest-rotation source (1 + t·t_ref = " +
                            std::to_string(value_of(denominator)) + ")");
  return 1.0 / denominator;
}

template <class T>
V3<T> block(const std::array<T, 15>& e, int k) {
  return {e[3 * k], e[3 * k + 1], e[3 * k + 2]};
}

// Element-level frame data: node 1's unit tangent and untwisted triad, ζ = α₂ + ω.
template <class T>
struct ElementFrame {
  V3<T> t1, n2, n3;
  T zeta, omega;
};

// The untwisted nodal triads Λ̄ᵢ = SR(Rᵢ → t̂ᵢ) of an element, as far as its frame needs them:
// the unit tangents t̂₁, t̂₂, node 1's d₂, d₃ and node 2's d₂. Node i's values depend on tᵢ only
// (staged_element_frame takes each as a jet in its own tangent).
template <class T>
struct UntwistedNodes {
  V3<T> u1, u2, n12, n13, n22;
};
template <class T>
UntwistedNodes<T> untwisted_nodes(const RodElementHistory& h, const V3<T>& t1, const V3<T>& t2) {
  using std::sqrt;
  const T inv1 = 1.0 / sqrt(dot(t1, t1)), inv2 = 1.0 / sqrt(dot(t2, t2));
  const V3<T> u1 = scale(inv1, t1), u2 = scale(inv2, t2);
  const V3<T> r11 = constant<T>(h.frame1.col(0)), r12 = constant<T>(h.frame1.col(1)),
              r13 = constant<T>(h.frame1.col(2));
  const T i1 = checked_inverse_denominator(1.0 + dot(r11, u1), "node 1 tangent");
  const V3<T> r21 = constant<T>(h.frame2.col(0)), r22 = constant<T>(h.frame2.col(1));
  const T i2 = checked_inverse_denominator(1.0 + dot(r21, u2), "node 2 tangent");
  return {u1, u2, sr_column(r11, r12, u1, i1), sr_column(r11, r13, u1, i1),
          sr_column(r21, r22, u2, i2)};
}

// The angle ω about t̂₂ from SR(Λ̄₁ → t̂₂) (columns m₂, m₃) to Λ̄₂ (d₂ = n₂₂), continuous from
// the committed value: the principal value plus the multiple of 2π nearest to `committed`.
template <class T>
T element_omega(const V3<T>& n22, const V3<T>& m2, const V3<T>& m3, double committed) {
  using std::atan2;
  const T omega = atan2(dot(n22, m3), dot(n22, m2));
  return omega + 2.0 * std::numbers::pi *
                     std::round((committed - value_of(omega)) / (2.0 * std::numbers::pi));
}

// From the nodal tangents t₁, t₂ and twist α₂ (any scalar types that mix with T).
template <class T>
ElementFrame<T> element_frame(const RodElementHistory& h, const V3<T>& t1, const V3<T>& t2,
                              const T& alpha2) {
  const UntwistedNodes<T> n = untwisted_nodes(h, t1, t2);
  // SR(Λ̄₁ → t̂₂) and the angle ω about t̂₂ from it to Λ̄₂.
  const T i12 = checked_inverse_denominator(1.0 + dot(n.u1, n.u2), "element end tangent");
  const V3<T> m2 = sr_column(n.u1, n.n12, n.u2, i12), m3 = sr_column(n.u1, n.n13, n.u2, i12);
  const T omega = element_omega(n.n22, m2, m3, h.omega);
  return {n.u1, n.n12, n.n13, alpha2 + omega, omega};
}

template <class T>
ElementFrame<T> element_frame(const RodElementHistory& h, const std::array<T, 15>& e) {
  return element_frame(h, block(e, 1), block(e, 3), e[13]);
}

// The 15 element coordinates as scalars of type T: doubles, or jets with e_i variable number i.
template <class T>
std::array<T, 15> to_array(const Vec15& e) {
  std::array<T, 15> out;
  for (int i = 0; i < 15; ++i) {
    if constexpr (std::is_same_v<T, double>)
      out[i] = e[i];
    else
      out[i] = T::variable(e[i], i);
  }
  return out;
}

// The shape-function data of one point ξ of an element of length l.
struct PointData {
  Vec4 d1, d2;
  double inv_j0, xi, length;
};

inline PointData point_data(const RodElementReference& ref, int p) {
  return {ref.d1[p], ref.d2[p], ref.inv_j0[p], ref.xi[p], ref.length};
}

// Material triad columns at a point (filled by point_strains on request).
template <class T>
struct PointTriad {
  V3<T> g1, g2, g3;
};

// r_x (a) and r_xx (b) at a point: Σ_k S_k′ x_k, Σ_k S_k″ x_k over the four centreline blocks.
template <class T>
void centreline_derivatives(const PointData& pd, const std::array<T, 15>& e, V3<T>& a, V3<T>& b) {
  a = scale(pd.d1[0], block(e, 0));
  b = scale(pd.d2[0], block(e, 0));
  for (int k = 1; k < 4; ++k) {
    a = a + scale(pd.d1[k], block(e, k));
    b = b + scale(pd.d2[k], block(e, k));
  }
}

// Whether the kernels take strain k (ε, K₁, K₂, K₃) at each Gauss point themselves. The
// collocated ε (kirchhoff_rod_axial) and the projected K₁ (kirchhoff_rod_torsion) are added
// element-wide by evaluate_rod_element instead.
inline bool strain_at_gauss_points(const RodSection& section, int k) {
  if (k == 0) return section.axial_strain == RodAxialStrain::gauss_points;
  if (k == 1) return section.torsion_strain == RodTorsionStrain::gauss_points;
  return true;
}

// The twist ψ(ξ) = (1 − ξ)α₁ + ξζ + 4ξ(1 − ξ)β and l ψ_x = ζ − α₁ + 4(1 − 2ξ)β (one expression
// for every scalar type, so that the kernels' values are bitwise equal; β = 0 adds exact zeros).
inline double bubble(double xi) {
  return 4.0 * xi * (1.0 - xi);
}
inline double bubble_slope(double xi) {
  return 4.0 * (1.0 - 2.0 * xi);
}
template <class T>
T twist_angle(double xi, const T& alpha1, const T& zeta, const T& beta) {
  return (1.0 - xi) * alpha1 + xi * zeta + bubble(xi) * beta;
}
template <class T>
T twist_increment(double xi, const T& alpha1, const T& zeta, const T& beta) {
  return zeta - alpha1 + bubble_slope(xi) * beta;
}

// r_x = Σ_k S_k′ x_k in double from d1 = S′ (hermite::first_derivative) and the four centreline
// blocks at x[0, 12) (the reference's e0 or an element's e).
inline Vec3 centreline_slope(const Vec4& d1, const double* x) {
  Vec3 a = Vec3::Zero();
  for (int k = 0; k < 4; ++k) a += d1[k] * Eigen::Map<const Vec3>(x + 3 * k);
  return a;
}

// The untwisted frame at a point from r_x = a: g = a/|a| and the SR(Λ̄₁ → g) columns g₂, g₃ of
// the element frame's node-1 triad, with |a|², |a| and 1/(1 + t̂₁·g) for the strains.
template <class T>
struct PointFrame {
  T saa, na, ic;
  V3<T> g, g2, g3;
};
template <class T>
PointFrame<T> point_frame(const ElementFrame<T>& f, const V3<T>& a) {
  using std::sqrt;
  PointFrame<T> p;
  p.saa = dot(a, a);
  p.na = sqrt(p.saa);
  p.g = scale(1.0 / p.na, a);
  p.ic = checked_inverse_denominator(1.0 + dot(f.t1, p.g), "centreline tangent");
  p.g2 = sr_column(f.t1, f.n2, p.g, p.ic);
  p.g3 = sr_column(f.t1, f.n3, p.g, p.ic);
  return p;
}

// The material triad [g, c g₂ + s g₃, c g₃ − s g₂] at a point, c = cos ψ, s = sin ψ.
template <class T>
PointTriad<T> material_triad(const PointFrame<T>& p, const T& c, const T& s) {
  return {p.g, scale(c, p.g2) + scale(s, p.g3), scale(c, p.g3) - scale(s, p.g2)};
}

// Strains (ε, K₁, K₂, K₃) at a point from r_x = a, r_xx = b, the element frame, α₁ and β.
template <class T>
std::array<T, 4> point_strains(const PointData& pd, const ElementFrame<T>& f, const V3<T>& a,
                               const V3<T>& b, const T& alpha1, const T& beta,
                               PointTriad<T>* triad = nullptr) {
  using std::cos;
  using std::sin;
  const double ij = pd.inv_j0, xi = pd.xi;
  const PointFrame<T> p = point_frame(f, a);
  const V3<T> kappa = scale(1.0 / p.saa, cross(a, b));  // κ = r_x × r_xx / |r_x|² (per dx)
  const T k2 = dot(kappa, p.g2), k3 = dot(kappa, p.g3);
  const T psi = twist_angle(xi, alpha1, f.zeta, beta);
  const T c = cos(psi), s = sin(psi);
  // K₁: ψ_x plus the twist rate of the SR frame, −(t̂₁·κ)/(1 + t̂₁·g₁).
  const T k1 =
      twist_increment(xi, alpha1, f.zeta, beta) * (1.0 / pd.length) - dot(f.t1, kappa) * p.ic;
  if (triad) *triad = material_triad(p, c, s);
  return {p.na * ij - 1.0, k1 * ij, (c * k2 + s * k3) * ij, (c * k3 - s * k2) * ij};
}

// The same from the element coordinates.
template <class T>
std::array<T, 4> point_strains(const PointData& pd, const ElementFrame<T>& f,
                               const std::array<T, 15>& e, PointTriad<T>* triad = nullptr) {
  V3<T> a, b;
  centreline_derivatives(pd, e, a, b);
  return point_strains(pd, f, a, b, e[12], e[14], triad);
}

}  // namespace ancf::rod_detail
