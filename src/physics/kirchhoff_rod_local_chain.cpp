// The Kirchhoff rod's force, tangent and damping matrix by a two-level chain rule
// (RodKernel::local_chain; docs/rod.md, "Derivatives"). The strains at a Gauss point depend on
// the 15 element coordinates only through 12 local variables
//   y = (b = r_xx, a = r_x, t₁, α₁, ζ, β) ∈ R¹²,
// all linear in e except ζ = α₂ + ω(t₁, t₂). So with B = ∂y/∂e (the point's Hermite
// derivatives, identities, and ∇ζ as a row) and H_ζ = ∂²ζ/∂e² (on t₁, t₂ only):
//   ∇ₑs = Bᵀ∇_y s,   ∇ₑ²s = Bᵀ(∇_y² s)B + (∂s/∂ζ) H_ζ.
// Inside a point each intermediate is a jet in only the variables it depends on (3, 6 or 9 of
// y; the twist ψ by hand), and ω is a jet in (t₁, t₂) once per element, instead of jets in all
// 15 coordinates through every operation (RodKernel::element_jets). The values use the same
// operations as that kernel (kirchhoff_rod_strains.hpp), so energy and strains are bitwise equal
// and the derivatives agree to round-off (test_kirchhoff_rod_element).
#include "kirchhoff_rod_local_chain.hpp"

#include <array>
#include <utility>

#include "ancf/physics/jet.hpp"
#include "kirchhoff_rod_staged_frame.hpp"
#include "kirchhoff_rod_strains.hpp"

namespace ancf::rod_detail {
namespace {

constexpr int kLocal = 12;
constexpr int kB = 0, kA = 3, kT1 = 6, kAlpha1 = 9, kZeta = 10, kBeta = 11;  // offsets in y
using LocalVec = Eigen::Matrix<double, kLocal, 1>;
using LocalMat = Eigen::Matrix<double, kLocal, kLocal>;
using LocalMap = Eigen::Matrix<double, kLocal, 15>;  // B = ∂y/∂e

// x·y for x a jet in NX variables placed at [ox, ox + NX) of M and y one in NY at [oy, oy + NY),
// as a jet in M, by the product rule without first promoting both to M variables. The value takes
// dot()'s operations (x_k y_k = y_k x_k exactly).
template <int M, int ox, int oy, int NX, int NY, bool S>
Jet<M, S> mixed_dot(const V3<Jet<NX, S>>& x, const V3<Jet<NY, S>>& y) {
  const std::array<const Jet<NX, S>*, 3> xs{&x.x, &x.y, &x.z};
  const std::array<const Jet<NY, S>*, 3> ys{&y.x, &y.y, &y.z};
  Jet<M, S> c(x.x.v * y.x.v + x.y.v * y.y.v + x.z.v * y.z.v);
  Eigen::Matrix<double, NX, 3> xg;
  Eigen::Matrix<double, NY, 3> yg;
  for (int k = 0; k < 3; ++k) {
    xg.col(k) = xs[k]->g;
    yg.col(k) = ys[k]->g;
  }
  const Eigen::Vector3d xv(x.x.v, x.y.v, x.z.v), yv(y.x.v, y.y.v, y.z.v);
  c.g.template segment<NX>(ox) += xg * yv;
  c.g.template segment<NY>(oy) += yg * xv;
  if constexpr (S) {
    for (int k = 0; k < 3; ++k) {
      c.h.template block<NX, NX>(ox, ox) += yv[k] * xs[k]->h;
      c.h.template block<NY, NY>(oy, oy) += xv[k] * ys[k]->h;
    }
    const Eigen::Matrix<double, NX, NY> p = xg.lazyProduct(yg.transpose());  // Σ x_k′ y_k′ᵀ
    c.h.template block<NX, NY>(ox, oy) += p;
    c.h.template block<NY, NX>(oy, ox) += p.transpose();
  }
  return c;
}

// a × b for a, b the independent variables at [3, 6) and [0, 3) of a jet in (b, a): bilinear, so
// its derivatives are written out. The value takes cross()'s operations.
template <bool S>
V3<Jet<6, S>> cross_of_variables(const V3<double>& a, const V3<double>& b) {
  constexpr int ob = 0, oa = 3;
  const std::array<double, 3> av{a.x, a.y, a.z}, bv{b.x, b.y, b.z};
  std::array<Jet<6, S>, 3> c;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;  // c_i = a_j b_k − a_k b_j
    c[i] = Jet<6, S>(av[j] * bv[k] - av[k] * bv[j]);
    c[i].g[oa + j] = bv[k];
    c[i].g[oa + k] = -bv[j];
    c[i].g[ob + k] = av[j];
    c[i].g[ob + j] = -av[k];
    if constexpr (S) {
      c[i].h(oa + j, ob + k) = c[i].h(ob + k, oa + j) = 1.0;
      c[i].h(oa + k, ob + j) = c[i].h(ob + j, oa + k) = -1.0;
    }
  }
  return {c[0], c[1], c[2]};
}

// The strains (ε, K₁, K₂, K₃) at a point as jets in y = (b, a, t₁, α₁, ζ, β). The operations and
// their order are those of point_strains (kirchhoff_rod_strains.hpp), so the values are bitwise
// equal; each intermediate is carried as a jet in only the variables it depends on:
//   |a|, g = a/|a|: a (3);  κ = a × b/|a|²: (b, a) (6);  1/(1 + t̂₁·g), SR columns: (a, t₁) (6);
//   κ·d₂, κ·d₃, (t̂₁·κ)/(1 + t̂₁·g): (b, a, t₁) (9).
// The twist ψ = (1 − ξ)α₁ + ξζ + 4ξ(1 − ξ)β enters through cos ψ, sin ψ, by hand:
//   K₂ = (c k₂ + s k₃)/J₀, ∂K₂/∂ψ = K₃;  K₃ = (c k₃ − s k₂)/J₀, ∂K₃/∂ψ = −K₂.
template <bool S>
std::array<Jet<kLocal, S>, 4> staged_point_strains(const PointData& pd, const NodeFrame<S>& f,
                                                   const V3<double>& ad, const V3<double>& bd,
                                                   double alpha1, double zeta, double beta) {
  using std::sqrt;
  using J3 = Jet<3, S>;
  using J6 = Jet<6, S>;
  using J9 = Jet<9, S>;
  using JL = Jet<kLocal, S>;
  const double ij = pd.inv_j0, xi = pd.xi;
  // a alone
  const V3<J3> a = variables<J3>(ad, 0);
  const J3 saa = dot(a, a);
  const J3 na = sqrt(saa);
  const V3<J3> g = scale(1.0 / na, a);
  // (b, a)
  const V3<J6> kappa = scale(promote<6>(1.0 / saa, 3), cross_of_variables<S>(ad, bd));
  // (a, t₁): the SR columns sr_column(t̂₁, n, g, ic) = n − ((n·g) ic)(g + t̂₁)
  const V3<J6> t1_at = promote<6>(f.t1, 3);
  const J6 ic =
      checked_inverse_denominator(1.0 + mixed_dot<6, 3, 0>(f.t1, g), "centreline tangent");
  const V3<J6> g_plus_t1 = promote<6>(g, 0) + t1_at;
  const V3<J6> g2 = promote<6>(f.n2, 3) - scale(mixed_dot<6, 3, 0>(f.n2, g) * ic, g_plus_t1),
               g3 = promote<6>(f.n3, 3) - scale(mixed_dot<6, 3, 0>(f.n3, g) * ic, g_plus_t1);
  // (b, a, t₁)
  const J9 k2 = mixed_dot<9, 0, 3>(kappa, g2), k3 = mixed_dot<9, 0, 3>(kappa, g3);
  const J9 sr_twist = mixed_dot<9, 3, 0>(t1_at, kappa) * promote<9>(ic, 3);
  // the twist, by hand
  const double psi = twist_angle(xi, alpha1, zeta, beta);
  const double c = std::cos(psi), s = std::sin(psi);
  const double k1 = twist_increment(xi, alpha1, zeta, beta) * (1.0 / pd.length) - sr_twist.v;
  std::array<JL, 4> out;
  out[0].v = na.v * ij - 1.0;
  out[0].g.template segment<3>(kA) = ij * na.g;
  out[1].v = k1 * ij;
  out[1].g.template head<9>() = -ij * sr_twist.g;
  out[1].g[kAlpha1] = -ij / pd.length;
  out[1].g[kZeta] = ij / pd.length;
  out[1].g[kBeta] = ij * bubble_slope(xi) / pd.length;
  const double kk2 = (c * k2.v + s * k3.v) * ij, kk3 = (c * k3.v - s * k2.v) * ij;
  out[2].v = kk2;
  out[3].v = kk3;
  const Eigen::Matrix<double, 9, 1> q2 = ij * (c * k3.g - s * k2.g),  // ∂²K₂/∂ψ∂(b, a, t₁)
      q3 = -ij * (s * k3.g + c * k2.g);  // ∂²K₃/∂ψ∂(b, a, t₁)
  out[2].g.template head<9>() = ij * (c * k2.g + s * k3.g);
  out[3].g.template head<9>() = ij * (c * k3.g - s * k2.g);
  // ∂ψ/∂(α₁, ζ, β)
  const std::array<std::pair<int, double>, 3> twist{
      {{kAlpha1, 1.0 - xi}, {kZeta, xi}, {kBeta, bubble(xi)}}};
  for (const auto& [index, p] : twist) {
    out[2].g[index] = p * kk3;
    out[3].g[index] = -p * kk2;
  }
  if constexpr (S) {
    out[0].h.template block<3, 3>(kA, kA) = ij * na.h;
    out[1].h.template topLeftCorner<9, 9>() = -ij * sr_twist.h;
    out[2].h.template topLeftCorner<9, 9>() = ij * (c * k2.h + s * k3.h);
    out[3].h.template topLeftCorner<9, 9>() = ij * (c * k3.h - s * k2.h);
    for (int m = 2; m < 4; ++m) {
      const Eigen::Matrix<double, 9, 1>& q = m == 2 ? q2 : q3;
      const double second = m == 2 ? -kk2 : -kk3;  // ∂²K/∂ψ²
      auto& h = out[m].h;
      for (const auto& [i, pi] : twist) {
        h.template block<9, 1>(0, i) = pi * q;
        h.template block<1, 9>(i, 0) = pi * q.transpose();
        for (const auto& [j, pj] : twist) h(i, j) = second * pi * pj;
      }
    }
  }
  return out;
}

// B = ∂y/∂e is sparse: column j (centreline coordinate j = 3k + i) holds S_k′ at a_i, S_k″ at
// b_i and, for k = 1, 1 at t₁ᵢ; column 12 holds 1 at α₁, column 14 1 at β; ∂ζ/∂e_j at ζ. Calls
// f(row, B(row, j)).
template <class F>
void for_map_column(const PointData& pd, const Vec15& zeta_gradient, int j, F&& f) {
  if (j < 12) {
    const int k = j / 3, i = j % 3;
    f(kA + i, pd.d1[k]);
    f(kB + i, pd.d2[k]);
    if (k == 1) f(kT1 + i, 1.0);
  } else if (j == 12) {
    f(kAlpha1, 1.0);
  } else if (j == 14) {
    f(kBeta, 1.0);
  }
  if (zeta_gradient[j] != 0.0) f(kZeta, zeta_gradient[j]);
}

// Bᵀ v
Vec15 map_transpose_times(const PointData& pd, const Vec15& zg, const LocalVec& v) {
  Vec15 out;
  for (int j = 0; j < 15; ++j) {
    double sum = 0.0;
    for_map_column(pd, zg, j, [&](int r, double beta) { sum += beta * v[r]; });
    out[j] = sum;
  }
  return out;
}

// B u
LocalVec map_times(const PointData& pd, const Vec15& zg, const Vec15& u) {
  LocalVec out = LocalVec::Zero();
  for (int j = 0; j < 15; ++j)
    for_map_column(pd, zg, j, [&](int r, double beta) { out[r] += beta * u[j]; });
  return out;
}

// out += Bᵀ m B
void add_congruence(const PointData& pd, const Vec15& zg, const LocalMat& m, Mat15& out) {
  LocalMap mb;  // m B
  for (int j = 0; j < 15; ++j) {
    mb.col(j).setZero();
    for_map_column(pd, zg, j, [&](int r, double beta) { mb.col(j) += beta * m.col(r); });
  }
  for (int i = 0; i < 15; ++i)
    for_map_column(pd, zg, i, [&](int r, double beta) { out.row(i) += beta * mb.row(r); });
}

template <bool kSecond>
void evaluate(const RodSection& section, const RodElementReference& ref,
              const RodElementHistory& history, const Vec15& e, const Vec15& e_dot,
              const RodEvalRequest& request, RodElementResult& out, TorsionPoints* torsion) {
  const std::array<double, 4> stiff{section.axial_stiffness, section.torsional_stiffness,
                                    section.bending_stiffness_2, section.bending_stiffness_3};
  const std::array<double, 4> damp{section.axial_damping, section.torsional_damping,
                                   section.bending_damping, section.bending_damping};
  const bool damping = section.has_damping();
  const bool stiffness = kSecond && request.stiffness;

  // Element frame: node 1's triad in t₁, ζ = α₂ + ω in (t₁, t₂) (α₂ enters linearly).
  const NodeFrame<kSecond> frame = staged_element_frame<kSecond>(history, e);
  const Jet<6, kSecond>& zeta = frame.zeta;
  Vec15 zeta_gradient = Vec15::Zero();
  for (int i = 0; i < 6; ++i) zeta_gradient[kTangents[i]] = zeta.g[i];
  zeta_gradient[13] = 1.0;

  std::array<double, 15> x;
  for (int i = 0; i < 15; ++i) x[i] = e[i];
  double zeta_stress = 0.0;            // Σ w σ_k ∂s_k/∂ζ, multiplies H_ζ
  Vec15 zeta_damping = Vec15::Zero();  // Σ w c_k (∂s_k/∂ζ) ∇ₑs_k, times (H_ζ ė)ᵀ
  for (int p = 0; p < kRodGaussPoints; ++p) {
    const PointData pd = point_data(ref, p);
    V3<double> a, b;
    centreline_derivatives(pd, x, a, b);
    const auto s = staged_point_strains(pd, frame, a, b, e[12], zeta.v, e[14]);
    const LocalVec y_dot = damping ? map_times(pd, zeta_gradient, e_dot) : LocalVec::Zero();
    const double w = ref.weight[p];
    if (p == kRodGaussPoints / 2) out.strain_mid = Vec3(s[1].v, s[2].v, s[3].v);
    LocalVec f = LocalVec::Zero();
    LocalMat k_local = LocalMat::Zero(), d_local = LocalMat::Zero();
    LocalVec z_local = LocalVec::Zero();
    if (torsion) {  // K₁ in the element coordinates, for add_projected_torsion
      TorsionAtPoint& t = (*torsion)[p];
      t.value = s[1].v;
      t.gradient = map_transpose_times(pd, zeta_gradient, s[1].g);
      if constexpr (kSecond) {
        if (stiffness) {  // Bᵀ H B + (∂K₁/∂ζ) H_ζ
          t.hessian.setZero();
          add_congruence(pd, zeta_gradient, s[1].h, t.hessian);
          for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 6; ++i)
              t.hessian(kTangents[i], kTangents[j]) += s[1].g[kZeta] * zeta.h(i, j);
        }
      }
    }
    for (int k = 0; k < 4; ++k) {
      if (!strain_at_gauss_points(section, k)) continue;
      const double d = s[k].v - (k == 0 ? 0.0 : ref.k0[p][k - 1]);
      out.energy += 0.5 * w * stiff[k] * d * d;
      const bool damped = damping && damp[k] > 0.0;
      const double rate = damped ? s[k].g.dot(y_dot) : 0.0;
      const double sigma = stiff[k] * d + damp[k] * rate;  // stress resultant of strain k
      f.noalias() += (w * sigma) * s[k].g;
      if constexpr (kSecond) {
        if (stiffness) {
          const LocalVec wg = (w * stiff[k]) * s[k].g;
          for (int j = 0; j < kLocal; ++j) k_local.col(j) += s[k].g[j] * wg;  // w EA_k ∇s ∇sᵀ
          k_local.noalias() += (w * sigma) * s[k].h;
          zeta_stress += w * sigma * s[k].g[kZeta];
          if (damped) {
            const LocalVec hy = s[k].h * y_dot;  // ∂(c ṡ)/∂y = c (H ẏ)ᵀ
            k_local.noalias() += (w * damp[k]) * s[k].g * hy.transpose();
            z_local.noalias() += (w * damp[k] * s[k].g[kZeta]) * s[k].g;
          }
        }
      }
      if (request.damping_matrix && damped)
        d_local.noalias() += (w * damp[k]) * s[k].g * s[k].g.transpose();
    }
    out.force += map_transpose_times(pd, zeta_gradient, f);
    if (stiffness) {
      add_congruence(pd, zeta_gradient, k_local, out.stiffness);
      if (damping) zeta_damping += map_transpose_times(pd, zeta_gradient, z_local);
    }
    if (request.damping_matrix && damping) add_congruence(pd, zeta_gradient, d_local, out.damping);
  }
  if constexpr (kSecond) {
    if (stiffness) {
      Eigen::Matrix<double, 6, 1> hz_edot = Eigen::Matrix<double, 6, 1>::Zero();
      if (damping) {
        Eigen::Matrix<double, 6, 1> et;
        for (int i = 0; i < 6; ++i) et[i] = e_dot[kTangents[i]];
        hz_edot = zeta.h * et;
      }
      for (int j = 0; j < 6; ++j) {
        const int cj = kTangents[j];
        for (int i = 0; i < 6; ++i) out.stiffness(kTangents[i], cj) += zeta_stress * zeta.h(i, j);
        if (damping) out.stiffness.col(cj).noalias() += hz_edot[j] * zeta_damping;
      }
    }
  }
}

}  // namespace

void evaluate_with_local_chain(const RodSection& section, const RodElementReference& ref,
                               const RodElementHistory& history, const Vec15& e, const Vec15& e_dot,
                               const RodEvalRequest& request, RodElementResult& out,
                               TorsionPoints* torsion) {
  if (request.stiffness)
    evaluate<true>(section, ref, history, e, e_dot, request, out, torsion);
  else
    evaluate<false>(section, ref, history, e, e_dot, request, out, torsion);
}

}  // namespace ancf::rod_detail
