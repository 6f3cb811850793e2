// Distributed moment on a rod element (kirchhoff_rod_distributed_moment.hpp). The triad at a
// Gauss point depends on the element coordinates only through nine local variables
//   y = (a = r_x, t₁, α₁, ζ, β),
// linear in e except ζ = α₂ + ω(t₁, t₂) (as for the element's local-chain kernel,
// kirchhoff_rod_local_chain.cpp). With B_p = ∂y/∂e at point p (Hermite S′ for a, identities, ∇ζ)
// and H_ζ = ∂²ζ/∂e²: Q = Σ_p B_pᵀ q_p and ∂Q/∂e = Σ_p [B_pᵀ (∂q_p/∂y) B_p + q_p,ζ H_ζ], where q_p
// and ∂q_p/∂y come from the triad in jets over y. RodKernel::element_jets keeps jets in all 15
// coordinates through the triad instead (the first version, for comparison).
#include "ancf/physics/kirchhoff_rod_distributed_moment.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "ancf/physics/jet.hpp"
#include "kirchhoff_rod_staged_frame.hpp"
#include "kirchhoff_rod_strains.hpp"

namespace ancf {
namespace {
using namespace rod_detail;

constexpr int kA = 0, kT1 = 3, kAlpha1 = 6, kZeta = 7, kBeta = 8, kLocal = 9;  // offsets in y

// Adds ½ w Σ_k [Gᵀ(m × g_k)] to q and, for second-order jets, ½ w Σ_k [Gᵀ[m]×G + (m × g_k)·∇²g_k]
// to h, for the triad's columns g_k as jets in N variables (G = ∂g_k/∂vars).
template <int N, bool S>
void add_point(const PointTriad<Jet<N, S>>& t, const Vec3& m, const Mat3& skew_m, double half_w,
               Eigen::Matrix<double, N, 1>& q, Eigen::Matrix<double, N, N>& h) {
  for (const V3<Jet<N, S>>* g : {&t.g1, &t.g2, &t.g3}) {
    const Vec3 a = m.cross(Vec3(g->x.v, g->y.v, g->z.v));  // m × g_k
    Eigen::Matrix<double, 3, N> dg;
    dg.row(0) = g->x.g.transpose();
    dg.row(1) = g->y.g.transpose();
    dg.row(2) = g->z.g.transpose();
    q.noalias() += half_w * dg.transpose() * a;
    if constexpr (S) {
      h.noalias() += half_w * dg.transpose() * skew_m * dg;
      h.noalias() +=
          (half_w * a.x()) * g->x.h + (half_w * a.y()) * g->y.h + (half_w * a.z()) * g->z.h;
    }
  }
}

Mat3 skew(const Vec3& m) {
  Mat3 s;
  s << 0.0, -m.z(), m.y(), m.z(), 0.0, -m.x(), -m.y(), m.x(), 0.0;
  return s;
}

template <bool S>
void element_jets(const RodElementReference& ref, const RodElementHistory& history, const Vec15& e,
                  const Vec3& m, RodDistributedMomentLoad& out) {
  using J = Jet<15, S>;
  const auto x = to_array<J>(e);
  const ElementFrame<J> f = element_frame(history, x);
  for (int p = 0; p < kRodGaussPoints; ++p) {
    PointTriad<J> t;
    point_strains(point_data(ref, p), f, x, &t);
    add_point<15, S>(t, m, skew(m), 0.5 * ref.weight[p], out.force, out.jacobian);
  }
}

template <bool S>
void local_chain(const RodElementReference& ref, const RodElementHistory& history, const Vec15& e,
                 const Vec3& m, RodDistributedMomentLoad& out) {
  using J = Jet<kLocal, S>;
  // Node 1's untwisted frame as jets in t₁ (y[3, 6)) and ζ = α₂ + ω in (t₁, t₂), once per element.
  const NodeFrame<S> staged = staged_element_frame<S>(history, e);
  const ElementFrame<J> f{promote<kLocal>(staged.t1, kT1), promote<kLocal>(staged.n2, kT1),
                          promote<kLocal>(staged.n3, kT1), J::variable(staged.zeta.v, kZeta),
                          J(0.0)};
  const J alpha1 = J::variable(e[12], kAlpha1), beta = J::variable(e[14], kBeta);
  const Mat3 skew_m = skew(m);
  Eigen::Matrix<double, kLocal, 15> b = Eigen::Matrix<double, kLocal, 15>::Zero();  // B_p
  b.block<3, 3>(kT1, 3).setIdentity();
  b(kAlpha1, 12) = 1.0;
  for (int i = 0; i < 6; ++i) b(kZeta, kTangents[i]) = staged.zeta.g[i];
  b(kZeta, 13) = 1.0;
  b(kBeta, 14) = 1.0;
  for (int p = 0; p < kRodGaussPoints; ++p) {
    const PointData pd = point_data(ref, p);
    const Vec3 a = centreline_slope(pd.d1, e.data());
    const PointFrame<J> frame = point_frame(
        f, V3<J>{J::variable(a.x(), kA), J::variable(a.y(), kA + 1), J::variable(a.z(), kA + 2)});
    using std::cos;
    using std::sin;
    const J psi = twist_angle(pd.xi, alpha1, f.zeta, beta);
    const PointTriad<J> t = material_triad(frame, cos(psi), sin(psi));
    Eigen::Matrix<double, kLocal, 1> q = Eigen::Matrix<double, kLocal, 1>::Zero();
    Eigen::Matrix<double, kLocal, kLocal> h;
    if constexpr (S) h.setZero();
    add_point<kLocal, S>(t, m, skew_m, 0.5 * ref.weight[p], q, h);
    for (int k = 0; k < 4; ++k) b.block<3, 3>(kA, 3 * k) = pd.d1[k] * Mat3::Identity();
    out.force.noalias() += b.transpose() * q;
    if constexpr (S) {
      out.jacobian.noalias() += b.transpose() * h * b;
      for (int j = 0; j < 6; ++j)
        for (int i = 0; i < 6; ++i)
          out.jacobian(kTangents[i], kTangents[j]) += q[kZeta] * staged.zeta.h(i, j);
    }
  }
}

}  // namespace

void rod_distributed_moment(const RodElementReference& ref, const RodElementHistory& history,
                            const Vec15& e, const Vec3& moment_per_length, bool jacobian,
                            RodDistributedMomentLoad& out, RodKernel kernel) {
  out.force.setZero();
  if (jacobian) out.jacobian.setZero();
  if (kernel == RodKernel::element_jets) {
    if (jacobian)
      element_jets<true>(ref, history, e, moment_per_length, out);
    else
      element_jets<false>(ref, history, e, moment_per_length, out);
  } else {
    if (jacobian)
      local_chain<true>(ref, history, e, moment_per_length, out);
    else
      local_chain<false>(ref, history, e, moment_per_length, out);
  }
}

}  // namespace ancf
