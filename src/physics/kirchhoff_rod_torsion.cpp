// Projected torsion against the twist locking of torsion-stiff curved rods (docs/rod.md,
// "Projected torsion"). Out of its plane a curved element must bend while keeping K₁ = K₁⁰; with
// K₁ taken at four Gauss points those are four conditions per element against its two twist
// freedoms (β and one nodal angle), and the smallest-rotation part −(t̂₁·κ)/(1 + t̂₁·g) of K₁ is
// rational in the tangent, so the centreline is constrained too and the element stiffens
// (measured: the quarter circle at GJ/EI = 10⁶ converges as h² only). Replacing K₁ by its
// projection onto linear functions leaves two conditions — an assumed strain, as the collocated
// axial strain is for ε (kirchhoff_rod_axial.cpp).
//
// With ŵ_q = w_q/Σw, ξ̄ = Σ ŵ_q ξ_q, v = Σ ŵ_q (ξ_q − ξ̄)²: P_pq = ŵ_q [1 + (ξ_p − ξ̄)(ξ_q − ξ̄)/v],
// the w-orthogonal projection. Then K̃_p = Σ_q P_pq K₁_q, G̃_p = Σ_q P_pq ∇K₁_q and
//   σ̃_p = GJ (K̃_p − K̃⁰_p) + c_t G̃_p·ė,  f = Σ_p w_p σ̃_p G̃_p,
//   K = Σ_p w_p GJ G̃_p G̃_pᵀ + Σ_q τ_q ∇²K₁_q + Σ_p w_p c_t G̃_p (Σ_q P_pq ∇²K₁_q ė)ᵀ,
//   τ_q = Σ_p w_p σ̃_p P_pq,  D = Σ_p w_p c_t G̃_p G̃_pᵀ.
#include "kirchhoff_rod_torsion.hpp"

namespace ancf::rod_detail {

std::array<double, kRodGaussPoints> linear_projection_row(
    const std::array<double, kRodGaussPoints>& xi,
    const std::array<double, kRodGaussPoints>& weight, double at) {
  double total = 0.0, mean = 0.0, variance = 0.0;
  for (int q = 0; q < kRodGaussPoints; ++q) total += weight[q];
  for (int q = 0; q < kRodGaussPoints; ++q) mean += weight[q] / total * xi[q];
  for (int q = 0; q < kRodGaussPoints; ++q)
    variance += weight[q] / total * (xi[q] - mean) * (xi[q] - mean);
  std::array<double, kRodGaussPoints> row{};
  for (int q = 0; q < kRodGaussPoints; ++q)
    row[q] = weight[q] / total * (1.0 + (at - mean) * (xi[q] - mean) / variance);
  return row;
}

Eigen::Matrix<double, kRodGaussPoints, kRodGaussPoints> linear_projection(
    const std::array<double, kRodGaussPoints>& xi,
    const std::array<double, kRodGaussPoints>& weight) {
  Eigen::Matrix<double, kRodGaussPoints, kRodGaussPoints> p;
  for (int i = 0; i < kRodGaussPoints; ++i) {
    const auto row = linear_projection_row(xi, weight, xi[i]);
    for (int q = 0; q < kRodGaussPoints; ++q) p(i, q) = row[q];
  }
  return p;
}

void add_projected_torsion(const RodSection& section, const RodElementReference& ref,
                           const TorsionPoints& k1, const Vec15& e_dot,
                           const RodEvalRequest& request, RodElementResult& out) {
  const double gj = section.torsional_stiffness, ct = section.torsional_damping;
  const bool damped = ct > 0.0;
  const auto& p = ref.torsion_projection;
  std::array<Vec15, kRodGaussPoints> hess_edot;  // ∇²K₁_q ė (damped stiffness only)
  if (damped && request.stiffness)
    for (int q = 0; q < kRodGaussPoints; ++q) hess_edot[q].noalias() = k1[q].hessian * e_dot;
  std::array<double, kRodGaussPoints> tau{};  // τ_q
  for (int i = 0; i < kRodGaussPoints; ++i) {
    double value = 0.0;
    Vec15 g = Vec15::Zero();
    for (int q = 0; q < kRodGaussPoints; ++q) {
      value += p(i, q) * k1[q].value;
      g.noalias() += p(i, q) * k1[q].gradient;
    }
    const double w = ref.weight[i], d = value - ref.projected_k10[i];
    const double sigma = gj * d + (damped ? ct * g.dot(e_dot) : 0.0);  // σ̃_p
    out.energy += 0.5 * w * gj * d * d;
    out.force.noalias() += (w * sigma) * g;
    for (int q = 0; q < kRodGaussPoints; ++q) tau[q] += w * sigma * p(i, q);
    if (request.stiffness) {
      out.stiffness.noalias() += (w * gj) * g * g.transpose();
      if (damped) {
        Vec15 h = Vec15::Zero();
        for (int q = 0; q < kRodGaussPoints; ++q) h.noalias() += p(i, q) * hess_edot[q];
        out.stiffness.noalias() += (w * ct) * g * h.transpose();
      }
    }
    if (request.damping_matrix && damped) out.damping.noalias() += (w * ct) * g * g.transpose();
  }
  if (request.stiffness)
    for (int q = 0; q < kRodGaussPoints; ++q) out.stiffness.noalias() += tau[q] * k1[q].hessian;
}

}  // namespace ancf::rod_detail
