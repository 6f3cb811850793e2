// Collocated axial strain against membrane locking (docs/rod.md, "Membrane locking"). A cubic
// Hermite element bent into a curve cannot keep |r_x| constant along it, so with the strain taken
// at every Gauss point a slender (EA ≫ EI/l²) curved element pays axial energy for bending and is
// too stiff. Taking ε only at ξ = 0, ½, 1 and interpolating it quadratically (Meier, Popp & Wall,
// CMAME 290 (2015) 314–341, "minimally constrained strains"; 4C BEAM3K `epsilon_cp`) leaves three
// axial conditions per element instead of four.
//
// With ε_c = |a_c|/J₀,c − 1, a_c = r_x(ξ_c) = Σ_k S_k′(ξ_c) x_k linear in e, and L_pc = L_c(ξ_p):
//   ∇ε_c = (S′(ξ_c) ⊗ g_c)/J₀,c,  ∇²ε_c = (S′ S′ᵀ) ⊗ (I − g_c g_cᵀ)/(|a_c| J₀,c),  g_c = a_c/|a_c|,
//   ε̃_p = Σ_c L_pc ε_c,  N_p = EA ε̃_p + c_a ε̃̇_p,
//   f = Σ_p w_p N_p ∇ε̃_p,
//   K = Σ_p w_p EA ∇ε̃_p ∇ε̃_pᵀ + Σ_c n_c ∇²ε_c + Σ_p w_p c_a ∇ε̃_p (Σ_c L_pc ∇²ε_c ė)ᵀ,
//   n_c = Σ_p w_p N_p L_pc,  D = Σ_p w_p c_a ∇ε̃_p ∇ε̃_pᵀ.
#include "kirchhoff_rod_axial.hpp"

#include "kirchhoff_rod_strains.hpp"

namespace ancf::rod_detail {

std::array<double, 3> collocation_lagrange(double xi) {
  return {(2.0 * xi - 1.0) * (xi - 1.0), 4.0 * xi * (1.0 - xi), xi * (2.0 * xi - 1.0)};
}

namespace {

// ε_c and its derivatives in a_c (the Hessian is symmetric; only a 3×3 block per point).
struct CollocationStrain {
  double eps;
  Vec3 grad;  // ∂ε_c/∂a_c
  Mat3 hess;  // ∂²ε_c/∂a_c²
};

CollocationStrain collocation_strain(const Vec4& d1, double inv_j0, const Vec15& e) {
  const Vec3 a = centreline_slope(d1, e.data());
  const double n = a.norm();
  const Vec3 g = a / n;
  return {n * inv_j0 - 1.0, inv_j0 * g, (inv_j0 / n) * (Mat3::Identity() - g * g.transpose())};
}

// ∇ₑ of a function of a_c with gradient v: (S′(ξ_c) ⊗ v) on the 12 centreline coordinates.
Vec12 centreline_gradient(const Vec4& d1, const Vec3& v) {
  Vec12 out;
  for (int k = 0; k < 4; ++k) out.segment<3>(3 * k) = d1[k] * v;
  return out;
}

}  // namespace

void add_collocated_axial(const RodSection& section, const RodElementReference& ref, const Vec15& e,
                          const Vec15& e_dot, const RodEvalRequest& request,
                          RodElementResult& out) {
  const double ea = section.axial_stiffness, ca = section.axial_damping;
  const bool damped = ca > 0.0;
  std::array<CollocationStrain, 3> cs;
  std::array<Vec12, 3> grad;
  std::array<Vec12, 3> hess_edot;  // ∇²ε_c ė (damped stiffness only)
  for (int c = 0; c < 3; ++c) {
    cs[c] = collocation_strain(ref.collocation_d1[c], ref.collocation_inv_j0[c], e);
    grad[c] = centreline_gradient(ref.collocation_d1[c], cs[c].grad);
    if (damped && request.stiffness) {
      const Vec3 a_dot = centreline_slope(ref.collocation_d1[c], e_dot.data());  // ȧ_c
      hess_edot[c] = centreline_gradient(ref.collocation_d1[c], cs[c].hess * a_dot);
    }
  }
  std::array<double, 3> n{};  // n_c
  for (int p = 0; p < kRodGaussPoints; ++p) {
    const auto& l = ref.collocation_weight[p];
    const double w = ref.weight[p];
    const double eps = l[0] * cs[0].eps + l[1] * cs[1].eps + l[2] * cs[2].eps;
    const Vec12 g = l[0] * grad[0] + l[1] * grad[1] + l[2] * grad[2];
    const double rate = damped ? g.dot(e_dot.head<12>()) : 0.0;
    const double force = ea * eps + ca * rate;  // N_p
    out.energy += 0.5 * w * ea * eps * eps;
    out.force.head<12>() += (w * force) * g;
    for (int c = 0; c < 3; ++c) n[c] += w * force * l[c];
    if (request.stiffness) {
      out.stiffness.topLeftCorner<12, 12>().noalias() += (w * ea) * g * g.transpose();
      if (damped) {
        const Vec12 h = l[0] * hess_edot[0] + l[1] * hess_edot[1] + l[2] * hess_edot[2];
        out.stiffness.topLeftCorner<12, 12>().noalias() += (w * ca) * g * h.transpose();
      }
    }
    if (request.damping_matrix && damped)
      out.damping.topLeftCorner<12, 12>().noalias() += (w * ca) * g * g.transpose();
  }
  if (request.stiffness) {
    for (int c = 0; c < 3; ++c) {
      const Vec4& d1 = ref.collocation_d1[c];
      const Mat3 h = n[c] * cs[c].hess;
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) out.stiffness.block<3, 3>(3 * i, 3 * j) += (d1[i] * d1[j]) * h;
    }
  }
}

}  // namespace ancf::rod_detail
