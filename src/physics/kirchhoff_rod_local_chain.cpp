// The Kirchhoff rod's force, tangent and damping matrix by a two-level chain rule
// (RodKernel::local_chain). The strains at a Gauss point depend on the 14 element coordinates
// only through 11 local variables
//   y = (a = r_x, b = r_xx, t₁, α₁, ζ) ∈ R¹¹,
// all linear in e except ζ = α₂ + ω(t₁, t₂). So with B = ∂y/∂e (the point's Hermite
// derivatives, identities, and ∇ζ as last row) and H_ζ = ∂²ζ/∂e² (on t₁, t₂ only):
//   ∇ₑs = Bᵀ∇_y s,   ∇ₑ²s = Bᵀ(∇_y² s)B + (∂s/∂ζ) H_ζ.
// Jets run in the 11 local variables per point and in (t₁, t₂) once per element for ω, instead
// of in all 14 coordinates through every operation (RodKernel::element_jets). The values use the
// same operations as that kernel (kirchhoff_rod_strains.hpp), so energy and strains are bitwise
// equal and the derivatives agree to round-off (test_kirchhoff_rod_element).
#include "kirchhoff_rod_local_chain.hpp"

#include <array>

#include "ancf/physics/jet.hpp"
#include "kirchhoff_rod_strains.hpp"

namespace ancf::rod_detail {
namespace {

constexpr int kLocal = 11;
constexpr int kA = 0, kB = 3, kT1 = 6, kAlpha1 = 9, kZeta = 10;  // offsets in y
using LocalVec = Eigen::Matrix<double, kLocal, 1>;
using LocalMat = Eigen::Matrix<double, kLocal, kLocal>;
using LocalMap = Eigen::Matrix<double, kLocal, 14>;  // B = ∂y/∂e
// Element coordinates of (t₁, t₂), the variables of ω's jets.
constexpr std::array<int, 6> kTangents{3, 4, 5, 9, 10, 11};

// A jet in (t₁, t₂) that depends on t₁ only, as a jet in y.
template <bool S>
Jet<kLocal, S> embed_t1(const Jet<6, S>& x) {
  Jet<kLocal, S> y(x.v);
  y.g.template segment<3>(kT1) = x.g.template head<3>();
  if constexpr (S) y.h.template block<3, 3>(kT1, kT1) = x.h.template topLeftCorner<3, 3>();
  return y;
}
template <bool S>
V3<Jet<kLocal, S>> embed_t1(const V3<Jet<6, S>>& v) {
  return {embed_t1(v.x), embed_t1(v.y), embed_t1(v.z)};
}

template <class J>
V3<J> variables(const V3<double>& v, int first) {
  return {J::variable(v.x, first), J::variable(v.y, first + 1), J::variable(v.z, first + 2)};
}

// B = ∂y/∂e is sparse: column j (centreline coordinate j = 3k + i) holds S_k′ at a_i, S_k″ at
// b_i and, for k = 1, 1 at t₁ᵢ; column 12 holds 1 at α₁; ∂ζ/∂e_j at ζ. Calls f(row, B(row, j)).
template <class F>
void for_map_column(const PointData& pd, const Vec14& zeta_gradient, int j, F&& f) {
  if (j < 12) {
    const int k = j / 3, i = j % 3;
    f(kA + i, pd.d1[k]);
    f(kB + i, pd.d2[k]);
    if (k == 1) f(kT1 + i, 1.0);
  } else if (j == 12) {
    f(kAlpha1, 1.0);
  }
  if (zeta_gradient[j] != 0.0) f(kZeta, zeta_gradient[j]);
}

// Bᵀ v
Vec14 map_transpose_times(const PointData& pd, const Vec14& zg, const LocalVec& v) {
  Vec14 out;
  for (int j = 0; j < 14; ++j) {
    double sum = 0.0;
    for_map_column(pd, zg, j, [&](int r, double beta) { sum += beta * v[r]; });
    out[j] = sum;
  }
  return out;
}

// B u
LocalVec map_times(const PointData& pd, const Vec14& zg, const Vec14& u) {
  LocalVec out = LocalVec::Zero();
  for (int j = 0; j < 14; ++j)
    for_map_column(pd, zg, j, [&](int r, double beta) { out[r] += beta * u[j]; });
  return out;
}

// out += Bᵀ m B
void add_congruence(const PointData& pd, const Vec14& zg, const LocalMat& m, Mat14& out) {
  LocalMap mb;  // m B
  for (int j = 0; j < 14; ++j) {
    mb.col(j).setZero();
    for_map_column(pd, zg, j, [&](int r, double beta) { mb.col(j) += beta * m.col(r); });
  }
  for (int i = 0; i < 14; ++i)
    for_map_column(pd, zg, i, [&](int r, double beta) { out.row(i) += beta * mb.row(r); });
}

template <bool kSecond>
void evaluate(const RodSection& section, const RodElementReference& ref,
              const RodElementHistory& history, const Vec14& e, const Vec14& e_dot,
              const RodEvalRequest& request, RodElementResult& out) {
  using FrameJet = Jet<6, kSecond>;
  using LocalJet = Jet<kLocal, kSecond>;
  const std::array<double, 4> stiff{section.axial_stiffness, section.torsional_stiffness,
                                    section.bending_stiffness_2, section.bending_stiffness_3};
  const std::array<double, 4> damp{section.axial_damping, section.torsional_damping,
                                   section.bending_damping, section.bending_damping};
  const bool damping = section.has_damping();
  const bool stiffness = kSecond && request.stiffness;

  // Element frame with jets in (t₁, t₂); α₂ enters ζ linearly.
  const ElementFrame<FrameJet> f6 =
      element_frame(history, variables<FrameJet>({e[3], e[4], e[5]}, 0),
                    variables<FrameJet>({e[9], e[10], e[11]}, 3), FrameJet(e[13]));
  Vec14 zeta_gradient = Vec14::Zero();
  for (int i = 0; i < 6; ++i) zeta_gradient[kTangents[i]] = f6.zeta.g[i];
  zeta_gradient[13] = 1.0;
  const ElementFrame<LocalJet> frame{embed_t1(f6.t1), embed_t1(f6.n2), embed_t1(f6.n3),
                                     LocalJet::variable(f6.zeta.v, kZeta), LocalJet(f6.omega.v)};
  const LocalJet alpha1 = LocalJet::variable(e[12], kAlpha1);

  std::array<double, 14> x;
  for (int i = 0; i < 14; ++i) x[i] = e[i];
  double zeta_stress = 0.0;            // Σ w σ_k ∂s_k/∂ζ, multiplies H_ζ
  Vec14 zeta_damping = Vec14::Zero();  // Σ w c_k (∂s_k/∂ζ) ∇ₑs_k, times (H_ζ ė)ᵀ
  for (int p = 0; p < kRodGaussPoints; ++p) {
    const PointData pd = point_data(ref, p);
    V3<double> a, b;
    centreline_derivatives(pd, x, a, b);
    const auto s =
        point_strains(pd, frame, variables<LocalJet>(a, kA), variables<LocalJet>(b, kB), alpha1);
    const LocalVec y_dot = damping ? map_times(pd, zeta_gradient, e_dot) : LocalVec::Zero();
    const double w = ref.weight[p];
    if (p == kRodGaussPoints / 2) out.strain_mid = Vec3(s[1].v, s[2].v, s[3].v);
    LocalVec f = LocalVec::Zero();
    LocalMat k_local = LocalMat::Zero(), d_local = LocalMat::Zero();
    LocalVec z_local = LocalVec::Zero();
    for (int k = 0; k < 4; ++k) {
      const double d = s[k].v - (k == 0 ? 0.0 : ref.k0[p][k - 1]);
      out.energy += 0.5 * w * stiff[k] * d * d;
      const bool damped = damping && damp[k] > 0.0;
      const double rate = damped ? s[k].g.dot(y_dot) : 0.0;
      const double sigma = stiff[k] * d + damp[k] * rate;  // stress resultant of strain k
      f.noalias() += (w * sigma) * s[k].g;
      if constexpr (kSecond) {
        if (stiffness) {
          k_local.noalias() += (w * stiff[k]) * s[k].g * s[k].g.transpose();
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
        hz_edot = f6.zeta.h * et;
      }
      for (int j = 0; j < 6; ++j) {
        const int cj = kTangents[j];
        for (int i = 0; i < 6; ++i)
          out.stiffness(kTangents[i], cj) += zeta_stress * f6.zeta.h(i, j);
        if (damping) out.stiffness.col(cj).noalias() += hz_edot[j] * zeta_damping;
      }
    }
  }
}

}  // namespace

void evaluate_with_local_chain(const RodSection& section, const RodElementReference& ref,
                               const RodElementHistory& history, const Vec14& e, const Vec14& e_dot,
                               const RodEvalRequest& request, RodElementResult& out) {
  out.energy = 0.0;
  out.force.setZero();
  if (request.stiffness) out.stiffness.setZero();
  if (request.damping_matrix) out.damping.setZero();
  if (request.stiffness)
    evaluate<true>(section, ref, history, e, e_dot, request, out);
  else
    evaluate<false>(section, ref, history, e, e_dot, request, out);
}

}  // namespace ancf::rod_detail
