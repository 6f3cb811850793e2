// Force-only cable kernel on the strain invariants s₁ = a·a, s₂ = a·b, s₃ = b·b
// (cable_force_invariant.hpp for the derivation; paper eqs. S3–S5, DESIGN §3). All Gauss points of
// a term are processed at once, one point per column (CableElementReference::Points lanes), so
// every operation is a fixed-size array or matrix product.
#include "cable_force_invariant.hpp"

#include <array>
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

// --- force and tangent of an undamped section ---------------------------------------------------

// Hessian of the point energies in (s₁, s₂, s₃) (symmetric; h23 = h33 = 0 for these energies).
struct Second {
  Lanes h11 = Lanes::Zero(), h12 = Lanes::Zero(), h13 = Lanes::Zero(), h22 = Lanes::Zero();
};

// K = ∂f/∂X of U = Σ_g U_g(s₁, s₂, s₃):
//   K_(i,m) = S_im I₃ + Σ_g [a b] M_g(i,m) [a b]ᵀ,
// S = Σ_g (2u₁ d₁d₁ᵀ + u₂(d₁d₂ᵀ + d₂d₁ᵀ) + 2u₃ d₂d₂ᵀ) from ∂a/∂X_m = d₁,m I, and
// M_g(i,m) = T(i)ᵀ H_g T(m) with ∂s/∂X_i = T(i) [a b]ᵀ, T(i) = [2d₁,i 0; d₂,i d₁,i; 0 2d₂,i].
// tension_only drops the axial geometric term N ∂²ε/∂a² (its u₁ in S and N ε'' in h₁₁) where
// N < 0, as the pointwise kernel does.
void evaluate_stiffness(const CableSection& sec, const CableElementReference& ref, const Vec12& e,
                        CableTangent tangent, CableElementResult& out) {
  Mat3 x;
  x << e.segment<3>(3), e.segment<3>(6) - e.segment<3>(0), e.segment<3>(9);
  const bool green = sec.strain == StrainMeasure::green_lagrange;
  const double p = green ? 3.0 : 2.0;
  Mat3 f = Mat3::Zero(), geometric = Mat3::Zero();
  Eigen::Matrix<double, 9, 9> k = Eigen::Matrix<double, 9, 9>::Zero();
  double energy = 0.0;

  auto points = [&](const CableElementReference::Points& pts, bool axial, bool bending) {
    const Mat3L a = x * pts.lane_d1;
    Mat3L b = Mat3L::Zero();
    if (bending) b = x * pts.lane_d2;
    const Lanes s1 = a.colwise().squaredNorm().array();
    Partials u, ug;  // ∂U/∂s for the force, and for the geometric stiffness
    Second h;
    const Lanes& w = pts.lane_weight;
    if (axial) {
      Lanes eps, deps, d2eps;  // ε, ∂ε/∂s₁, ∂²ε/∂s₁²
      if (green) {
        const Lanes ij2 = pts.lane_inv_j0.square();
        eps = 0.5 * (s1 * ij2 - 1.0);
        deps = 0.5 * ij2;
        d2eps = Lanes::Zero();
      } else {
        const Lanes na = s1.sqrt();
        eps = na * pts.lane_inv_j0 - 1.0;
        deps = 0.5 * pts.lane_inv_j0 / na;
        d2eps = -0.5 * deps / s1;
      }
      const Lanes strain = eps + sec.prestrain;
      const Lanes n = sec.axial_stiffness * strain;
      energy += 0.5 * (w * n * strain).sum();
      u.u1 += w * n * deps;
      Lanes keep = Lanes::Ones();
      if (tangent == CableTangent::tension_only) keep = (n < 0.0).select(Lanes::Zero(), keep);
      ug.u1 += keep * w * n * deps;
      h.h11 += w * (sec.axial_stiffness * deps * deps + keep * n * d2eps);
    }
    if (bending) {
      const Lanes s2 = column_dots(a, b), s3 = b.colwise().squaredNorm().array();
      const double ei = sec.bending_stiffness;
      const Lanes inv = s1.inverse();
      const Lanes psi = green ? Lanes(inv * inv * inv) : Lanes(inv * inv);  // s₁⁻ᵖ
      const Lanes dpsi = -p * psi * inv, d2psi = p * (p + 1.0) * psi * inv * inv;
      const Lanes phi = (s1 * s3 - s2 * s2).max(0.0);
      const Lanes k2 = phi * psi;
      const Lanes k1 = s3 * psi + phi * dpsi, k2b = -2.0 * s2 * psi, k3 = s1 * psi;
      const Lanes k11 = 2.0 * s3 * dpsi + phi * d2psi, k12 = -2.0 * s2 * dpsi,
                  k13 = psi + s1 * dpsi, k22 = -2.0 * psi;
      Lanes c1, c2;  // w EI h'(κ²), w EI h''(κ²)
      if (pts.straight) {
        energy += 0.5 * ei * (w * k2).sum();
        c1 = (0.5 * ei) * w;
        c2 = Lanes::Zero();
      } else {
        for (int g = 0; g < kLanes; ++g) {
          const double kappa_ref = pts.lane_kappa0[g];
          const double kappa = kappa_ref > 0.0 ? std::sqrt(k2[g]) : 0.0;
          energy += kappa_ref > 0.0 ? 0.5 * w[g] * ei * (kappa - kappa_ref) * (kappa - kappa_ref)
                                    : 0.5 * w[g] * ei * k2[g];
          const double kappa0 = kappa > kVanishingCurvatureRatio * kappa_ref ? kappa_ref : 0.0;
          c1[g] = w[g] * ei * (kappa0 > 0.0 ? 0.5 - 0.5 * kappa0 / kappa : 0.5);
          c2[g] = kappa0 > 0.0 ? w[g] * ei * 0.25 * kappa0 / (kappa * kappa * kappa) : 0.0;
        }
      }
      for (Partials* v : {&u, &ug}) {
        v->u1 += c1 * k1;
        v->u2 += c1 * k2b;
        v->u3 += c1 * k3;
      }
      h.h11 += c1 * k11 + c2 * k1 * k1;
      h.h12 += c1 * k12 + c2 * k1 * k2b;
      h.h13 += c1 * k13 + c2 * k1 * k3;
      h.h22 += c1 * k22 + c2 * k2b * k2b;
      const Lanes h23 = c2 * k2b * k3, h33 = c2 * k3 * k3;
      // Force: F += A P₁ᵀ + B P₂ᵀ.
      const auto d1 = pts.lane_d1.array(), d2 = pts.lane_d2.array();
      f.noalias() += a * (d1.rowwise() * (2.0 * u.u1) + d2.rowwise() * u.u2).matrix().transpose();
      f.noalias() += b * (d1.rowwise() * u.u2 + d2.rowwise() * (2.0 * u.u3)).matrix().transpose();
      geometric.noalias() +=
          pts.lane_d1 * (d1.rowwise() * (2.0 * ug.u1) + d2.rowwise() * ug.u2).matrix().transpose() +
          pts.lane_d2 * (d1.rowwise() * ug.u2 + d2.rowwise() * (2.0 * ug.u3)).matrix().transpose();
      // G_m = H T(m) (3×2 per point), M(i,m) = T(i)ᵀ G_m, block (i,m) = W₁Aᵀ + W₂Bᵀ.
      std::array<std::array<Lanes, 6>, 3> g;  // g[m] = (G00, G10, G20, G01, G11, G21)
      for (int m = 0; m < 3; ++m) {
        const Lanes t1 = 2.0 * d1.row(m), t2 = d2.row(m), t3 = d1.row(m), t4 = 2.0 * d2.row(m);
        g[m] = {h.h11 * t1 + h.h12 * t2, h.h12 * t1 + h.h22 * t2, h.h13 * t1 + h23 * t2,
                h.h12 * t3 + h.h13 * t4, h.h22 * t3 + h23 * t4,   h23 * t3 + h33 * t4};
      }
      for (int i = 0; i < 3; ++i) {
        const Lanes t1 = 2.0 * d1.row(i), t2 = d2.row(i), t3 = d1.row(i), t4 = 2.0 * d2.row(i);
        for (int m = i; m < 3; ++m) {
          const auto& gm = g[m];
          const Lanes m00 = t1 * gm[0] + t2 * gm[1], m01 = t1 * gm[3] + t2 * gm[4];
          const Lanes m10 = t3 * gm[1] + t4 * gm[2], m11 = t3 * gm[4] + t4 * gm[5];
          const Mat3L w1 = (a.array().rowwise() * m00 + b.array().rowwise() * m10).matrix();
          const Mat3L w2 = (a.array().rowwise() * m01 + b.array().rowwise() * m11).matrix();
          const Mat3 block = w1 * a.transpose() + w2 * b.transpose();
          if (m != i) {
            k.block<3, 3>(3 * i, 3 * m) += block;
            k.block<3, 3>(3 * m, 3 * i) += block.transpose();
          } else {  // symmetric up to the round-off of M01 a bᵀ against M10 b aᵀ
            k.block<3, 3>(3 * i, 3 * i) += 0.5 * (block + block.transpose());
          }
        }
      }
    } else {
      const auto d1 = pts.lane_d1.array();
      f.noalias() += a * (d1.rowwise() * (2.0 * u.u1)).matrix().transpose();
      geometric.noalias() += pts.lane_d1 * (d1.rowwise() * (2.0 * ug.u1)).matrix().transpose();
      // Only s₁: block (i,m) = Σ_g 4 d₁,i d₁,m h₁₁ a aᵀ.
      for (int i = 0; i < 3; ++i)
        for (int m = i; m < 3; ++m) {
          const Lanes c = 4.0 * d1.row(i) * d1.row(m) * h.h11;
          const Mat3 block = (a.array().rowwise() * c).matrix() * a.transpose();
          if (m != i) {
            k.block<3, 3>(3 * i, 3 * m) += block;
            k.block<3, 3>(3 * m, 3 * i) += block.transpose();
          } else {
            k.block<3, 3>(3 * i, 3 * i) += 0.5 * (block + block.transpose());
          }
        }
    }
  };

  const bool has_bending = sec.has_bending();
  if (has_bending && ref.shared_points) {
    points(ref.axial, true, true);
  } else {
    points(ref.axial, true, false);
    if (has_bending) points(ref.bending, false, true);
  }
  geometric = 0.5 * (geometric + geometric.transpose()).eval();  // S is symmetric: exactly so
  for (int i = 0; i < 3; ++i)
    for (int m = 0; m < 3; ++m) k.block<3, 3>(3 * i, 3 * m).diagonal().array() += geometric(i, m);
  // Back to e = [r_i, r_i,x, r_j, r_j,x] from X = [r_i,x, r_j − r_i, r_j,x].
  out.energy = energy;
  out.force << -f.col(1), f.col(0), f.col(1), f.col(2);
  constexpr int kFrom[4] = {1, 0, 1, 2};
  constexpr double kSign[4] = {-1.0, 1.0, 1.0, 1.0};
  for (int i = 0; i < 4; ++i)
    for (int m = 0; m < 4; ++m)
      out.stiffness.block<3, 3>(3 * i, 3 * m) =
          (kSign[i] * kSign[m]) * k.block<3, 3>(3 * kFrom[i], 3 * kFrom[m]);
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

namespace ancf::detail {

void evaluate_cable_stiffness_invariant(const CableSection& section,
                                        const CableElementReference& ref, const Vec12& e,
                                        CableTangent tangent, CableElementResult& out) {
  evaluate_stiffness(section, ref, e, tangent, out);
}

}  // namespace ancf::detail
