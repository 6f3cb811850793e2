// Force-only cable kernel on the strain invariants s₁ = a·a, s₂ = a·b, s₃ = b·b
// (cable_force_invariant.hpp for the derivation; paper eqs. S3–S5, DESIGN §3). All Gauss points of
// a term are processed at once, one point per column (CableElementReference::Points lanes), so
// every operation is a fixed-size array or matrix product.
#include "cable_force_invariant.hpp"

#include <cmath>

namespace ancf::detail {
namespace {

constexpr int kLanes = kMaxCableGaussPoints;
using Lanes = Eigen::Array<double, 1, kLanes>;
using Mat3L = Eigen::Matrix<double, 3, kLanes>;

// ∂U/∂s_I per Gauss point.
struct Partials {
  Lanes u1 = Lanes::Zero(), u2 = Lanes::Zero(), u3 = Lanes::Zero();
};

// Axial terms: U = ½ w EA (ε + ε_p)², Kelvin–Voigt force w c_a ε̇ ∂ε/∂e; both are multiples of
// ∂s₁/∂e, with ∂ε/∂s₁ = 1/(2J₀²) (Green) or 1/(2J₀√s₁) (elastic line). ad = a·ȧ.
template <bool kDamping>
inline void add_axial(const CableSection& sec, const CableElementReference::Points& pts,
                      const Lanes& s1, const Lanes& ad, Partials& u, double& energy) {
  Lanes eps, deps;  // ε and ∂ε/∂s₁
  if (sec.strain == StrainMeasure::green_lagrange) {
    const Lanes ij2 = pts.lane_inv_j0.square();
    eps = 0.5 * (s1 * ij2 - 1.0);
    deps = 0.5 * ij2;
  } else {
    const Lanes na = s1.sqrt();
    eps = na * pts.lane_inv_j0 - 1.0;
    deps = 0.5 * pts.lane_inv_j0 / na;
  }
  const Lanes strain = eps + sec.prestrain;
  Lanes n = sec.axial_stiffness * strain;  // axial force conjugate to ε
  energy += 0.5 * (pts.lane_weight * n * strain).sum();
  if constexpr (kDamping) n += (2.0 * sec.axial_damping) * deps * ad;  // + c_a ε̇
  u.u1 += pts.lane_weight * n * deps;
}

// Bending terms: U = w EI h(κ²) (h = ½κ² for κ₀ = 0, ½(√κ² − κ₀)² otherwise) and the
// Kelvin–Voigt force w c_b φ χ̇ ∇χ on χ = κ², φ = 1/(4(χ + κ_s²)) (docs/formulation.md), both
// multiples of ∇κ² = Σ_I (∂κ²/∂s_I) ∇s_I. r1, r2, r3 = ṡ₁, ṡ₂, ṡ₃.
template <bool kDamping>
inline void add_bending(const CableSection& sec, const CableElementReference::Points& pts,
                        const Lanes& s1, const Lanes& s2, const Lanes& s3, const Lanes& r1,
                        const Lanes& r2, const Lanes& r3, Partials& u, double& energy) {
  const double ei = sec.bending_stiffness;
  const bool gs = sec.strain == StrainMeasure::green_lagrange;  // κ² = φ/s₁³, else φ/s₁²
  const Lanes inv = s1.inverse();
  const Lanes psi = gs ? Lanes(inv * inv * inv) : Lanes(inv * inv);  // s₁⁻ᵖ
  const Lanes phi = (s1 * s3 - s2 * s2).max(0.0);                    // |a × b|²
  const Lanes k2 = phi * psi;
  // ∂κ²/∂s_I (the derivative of the clamped φ taken as that of s₁s₃ − s₂², as the pointwise
  // kernel does).
  const Lanes k1 = s3 * psi - (gs ? 3.0 : 2.0) * phi * psi * inv;
  const Lanes k2b = -2.0 * s2 * psi, k3 = s1 * psi;
  Lanes c;  // w EI h'(κ²)
  if (pts.straight) {
    energy += 0.5 * ei * (pts.lane_weight * k2).sum();
    c = (0.5 * ei) * pts.lane_weight;
  } else {
    for (int g = 0; g < kLanes; ++g) {
      const double kappa_ref = pts.lane_kappa0[g], w = pts.lane_weight[g];
      const double kappa = kappa_ref > 0.0 ? std::sqrt(k2[g]) : 0.0;
      energy += kappa_ref > 0.0 ? 0.5 * w * ei * (kappa - kappa_ref) * (kappa - kappa_ref)
                                : 0.5 * w * ei * k2[g];
      const double kappa0 = kappa > kVanishingCurvatureRatio * kappa_ref ? kappa_ref : 0.0;
      c[g] = w * ei * (kappa0 > 0.0 ? 0.5 - 0.5 * kappa0 / kappa : 0.5);
    }
  }
  if constexpr (kDamping) {
    if (sec.bending_damping > 0.0) {
      const double ks2 = sec.bending_damping_curvature * sec.bending_damping_curvature;
      const Lanes chi_dot = k1 * r1 + k2b * r2 + k3 * r3;
      c += (0.25 * sec.bending_damping) * pts.lane_weight * chi_dot / (k2 + ks2);
    }
  }
  u.u1 += c * k1;
  u.u2 += c * k2b;
  u.u3 += c * k3;
}

inline Lanes column_dots(const Mat3L& x, const Mat3L& y) {
  return x.cwiseProduct(y).colwise().sum().array();
}

template <bool kBending, bool kDamping>
void evaluate(const CableSection& sec, const CableElementReference& ref, const Vec12& e,
              const Vec12& e_dot, CableElementResult& out) {
  // X = [r_i,x, r_j − r_i, r_j,x]; the points' a = X d₁' with d₁' = (d_1, d_2, d_3).
  Mat3 x, xd;
  x << e.segment<3>(3), e.segment<3>(6) - e.segment<3>(0), e.segment<3>(9);
  if constexpr (kDamping)
    xd << e_dot.segment<3>(3), e_dot.segment<3>(6) - e_dot.segment<3>(0), e_dot.segment<3>(9);
  Mat3 f = Mat3::Zero();  // ∂U/∂X
  double energy = 0.0;
  const Lanes zero = Lanes::Zero();

  // Bending (with the axial terms of the same points when the rules coincide): F += A P₁ᵀ + B P₂ᵀ
  // with P₁ = 2u₁∘d₁ + u₂∘d₂, P₂ = u₂∘d₁ + 2u₃∘d₂ (column-wise products).
  auto bending = [&](const CableElementReference::Points& pts, bool with_axial) {
    const Mat3L a = x * pts.lane_d1, b = x * pts.lane_d2;
    const Lanes s1 = a.colwise().squaredNorm().array();
    Lanes r1 = zero, r2 = zero, r3 = zero;
    if constexpr (kDamping) {
      const Mat3L ad = xd * pts.lane_d1, bd = xd * pts.lane_d2;
      r1 = 2.0 * column_dots(a, ad);
      r2 = column_dots(a, bd) + column_dots(ad, b);
      r3 = 2.0 * column_dots(b, bd);
    }
    Partials u;
    if (with_axial) add_axial<kDamping>(sec, pts, s1, 0.5 * r1, u, energy);
    add_bending<kDamping>(sec, pts, s1, column_dots(a, b), b.colwise().squaredNorm().array(), r1,
                          r2, r3, u, energy);
    const Mat3L p1 =
        (pts.lane_d1.array().rowwise() * (2.0 * u.u1) + pts.lane_d2.array().rowwise() * u.u2)
            .matrix();
    const Mat3L p2 =
        (pts.lane_d1.array().rowwise() * u.u2 + pts.lane_d2.array().rowwise() * (2.0 * u.u3))
            .matrix();
    f.noalias() += a * p1.transpose();
    f.noalias() += b * p2.transpose();
  };

  if (kBending && ref.shared_points) {
    bending(ref.axial, true);
  } else {
    const CableElementReference::Points& pts = ref.axial;
    const Mat3L a = x * pts.lane_d1;
    Lanes ad = zero;
    if constexpr (kDamping) ad = column_dots(a, xd * pts.lane_d1);
    Partials u;
    add_axial<kDamping>(sec, pts, a.colwise().squaredNorm().array(), ad, u, energy);
    f.noalias() += a * (pts.lane_d1.array().rowwise() * (2.0 * u.u1)).matrix().transpose();
    if constexpr (kBending) bending(ref.bending, false);
  }
  // Back to e: ∂U/∂r_i = −∂U/∂(r_j − r_i), ∂U/∂r_j = +∂U/∂(r_j − r_i).
  out.energy = energy;
  out.force << -f.col(1), f.col(0), f.col(1), f.col(2);
}

}  // namespace

void evaluate_cable_force_invariant(const CableSection& section, const CableElementReference& ref,
                                    const Vec12& e, const Vec12& e_dot, CableElementResult& out) {
  if (section.has_bending()) {
    if (section.has_damping())
      evaluate<true, true>(section, ref, e, e_dot, out);
    else
      evaluate<true, false>(section, ref, e, e_dot, out);
  } else {
    if (section.has_damping())
      evaluate<false, true>(section, ref, e, e_dot, out);
    else
      evaluate<false, false>(section, ref, e, e_dot, out);
  }
}

}  // namespace ancf::detail
