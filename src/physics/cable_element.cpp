#include "ancf/physics/cable_element.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "ancf/core/error.hpp"
#include "ancf/physics/hermite_shape.hpp"
#include "cable_force_invariant.hpp"

namespace ancf {
namespace {

using Mat34 = Eigen::Matrix<double, 3, 4>;

// Reference curvatures below this angle per element (κ₀ l) are round-off of a straight
// reference and are set to zero, which selects the smooth κ² branch of the bending energy.
constexpr double kStraightReferenceAngle = 1e-10;
using detail::kVanishingCurvatureRatio;

/// Axial strain and its first two derivatives with respect to a = r_x at one Gauss point.
struct AxialStrain {
  double eps;
  Vec3 eps_a;
  Mat3 eps_aa;
};

inline AxialStrain axial_strain(StrainMeasure measure, const Vec3& a, double inv_j0) {
  AxialStrain s;
  if (measure == StrainMeasure::green_lagrange) {
    const double ij2 = inv_j0 * inv_j0;
    s.eps = 0.5 * (a.squaredNorm() * ij2 - 1.0);
    s.eps_a = ij2 * a;
    s.eps_aa = ij2 * Mat3::Identity();
  } else {
    const double na = a.norm();
    const double c = inv_j0 / na;
    s.eps = na * inv_j0 - 1.0;
    s.eps_a = c * a;
    s.eps_aa = c * (Mat3::Identity() - (a / na) * (a / na).transpose());
  }
  return s;
}

/// K² = |a × b|² / |a|^(2p) (p = 3 Gerstmayr–Shabana, p = 2 elastic line) and its gradient and
/// Hessian in x = (a, b), via φ = (a·a)(b·b) − (a·b)² = |a × b|² and ψ = (a·a)^(−p).
struct CurvatureSquared {
  double k2;
  Eigen::Matrix<double, 6, 1> grad;
  Eigen::Matrix<double, 6, 6> hess;
};

inline int curvature_power(StrainMeasure m) {
  return m == StrainMeasure::green_lagrange ? 3 : 2;
}

// (a·a)^(−p) for p ∈ {2, 3} without std::pow, which costs ~25% of the bending force.
inline double inverse_power(double saa, int p) {
  const double inv = 1.0 / saa;
  return p == 3 ? inv * inv * inv : inv * inv;
}

inline double curvature_squared_value(const Vec3& a, const Vec3& b, int p) {
  const double saa = a.squaredNorm(), sbb = b.squaredNorm(), sab = a.dot(b);
  return std::max(saa * sbb - sab * sab, 0.0) * inverse_power(saa, p);
}

// kHessian = false (residual assembly): value and gradient only; the Hessian is ~3/4 of the
// work and is not needed for the force.
template <bool kHessian>
inline CurvatureSquared curvature_squared(const Vec3& a, const Vec3& b, int p) {
  const double saa = a.squaredNorm(), sbb = b.squaredNorm(), sab = a.dot(b);
  const double phi = std::max(saa * sbb - sab * sab, 0.0);
  const double psi = inverse_power(saa, p);
  const double psi1 = -2.0 * p * psi / saa;                     // ψ_a = psi1 · a
  const double psi2 = 4.0 * p * (p + 1.0) * psi / (saa * saa);  // ψ_aa = psi1 I + psi2 a aᵀ
  const Vec3 phi_a = 2.0 * sbb * a - 2.0 * sab * b;
  const Vec3 phi_b = 2.0 * saa * b - 2.0 * sab * a;
  const Vec3 psi_a = psi1 * a;
  CurvatureSquared c;
  c.k2 = phi * psi;
  c.grad.head<3>() = phi_a * psi + phi * psi_a;
  c.grad.tail<3>() = phi_b * psi;
  if constexpr (!kHessian) return c;
  const Mat3 id = Mat3::Identity();
  const Mat3 phi_aa = 2.0 * sbb * id - 2.0 * b * b.transpose();
  const Mat3 phi_bb = 2.0 * saa * id - 2.0 * a * a.transpose();
  const Mat3 phi_ab = 4.0 * a * b.transpose() - 2.0 * b * a.transpose() - 2.0 * sab * id;
  c.hess.topLeftCorner<3, 3>() = phi_aa * psi + phi_a * psi_a.transpose() +
                                 psi_a * phi_a.transpose() +
                                 phi * (psi1 * id + psi2 * a * a.transpose());
  c.hess.topRightCorner<3, 3>() = phi_ab * psi + psi_a * phi_b.transpose();
  c.hess.bottomLeftCorner<3, 3>() = c.hess.topRightCorner<3, 3>().transpose();
  c.hess.bottomRightCorner<3, 3>() = phi_bb * psi;
  return c;
}

// Scatter a gradient (g_a, g_b) and a Hessian in (a, b) through a = E d1, b = E d2:
// f_k += d1_k g_a + d2_k g_b;  K_km += Σ_{p,q} dp_k dq_m H_pq.
inline void scatter_force(const Vec4& d1, const Vec3& ga, Vec12& f) {
  for (int k = 0; k < 4; ++k) f.segment<3>(3 * k) += d1[k] * ga;
}

inline void scatter_matrix(const Vec4& d1, const Mat3& haa, Mat12& k) {
  for (int m = 0; m < 4; ++m)
    for (int n = 0; n < 4; ++n) k.block<3, 3>(3 * m, 3 * n) += (d1[m] * d1[n]) * haa;
}

inline void scatter_matrix(const Vec4& d1, const Vec4& d2, const Eigen::Matrix<double, 6, 6>& h,
                           Mat12& k) {
  const Mat3 haa = h.topLeftCorner<3, 3>(), hab = h.topRightCorner<3, 3>();
  const Mat3 hba = h.bottomLeftCorner<3, 3>(), hbb = h.bottomRightCorner<3, 3>();
  for (int m = 0; m < 4; ++m)
    for (int n = 0; n < 4; ++n)
      k.block<3, 3>(3 * m, 3 * n) += (d1[m] * d1[n]) * haa + (d1[m] * d2[n]) * hab +
                                     (d2[m] * d1[n]) * hba + (d2[m] * d2[n]) * hbb;
}

// The same for a symmetric h (Hessians: haa, hbb symmetric, hba = habᵀ): the blocks m ≤ n are
// formed and mirrored, half the work of the general scatter.
inline void scatter_symmetric_matrix(const Vec4& d1, const Vec4& d2,
                                     const Eigen::Matrix<double, 6, 6>& h, Mat12& k) {
  const Mat3 haa = h.topLeftCorner<3, 3>(), hab = h.topRightCorner<3, 3>();
  const Mat3 hba = h.bottomLeftCorner<3, 3>(), hbb = h.bottomRightCorner<3, 3>();
  for (int m = 0; m < 4; ++m)
    for (int n = m; n < 4; ++n) {
      const Mat3 block = (d1[m] * d1[n]) * haa + (d1[m] * d2[n]) * hab + (d2[m] * d1[n]) * hba +
                         (d2[m] * d2[n]) * hbb;
      k.block<3, 3>(3 * m, 3 * n) += block;
      if (n != m) k.block<3, 3>(3 * n, 3 * m) += block.transpose();
    }
}

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

/// Axial terms at one Gauss point: gradient and Hessian in a = r_x (elastic + damping) and the
/// damping matrix block in ȧ.
struct AxialPoint {
  Vec3 ga;
  Mat3 haa, daa;
};

template <bool kDamping, bool kStiffness>
inline AxialPoint axial_point(const CableSection& sec, const Vec3& a, const Vec3& a_dot, double w,
                              double inv_j0, const CableEvalRequest& req, double& energy) {
  const double ea = sec.axial_stiffness, ca = sec.axial_damping;
  const AxialStrain s = axial_strain(sec.strain, a, inv_j0);
  const double n_axial = ea * (s.eps + sec.prestrain);  // axial force conjugate to ε
  energy += 0.5 * w * n_axial * (s.eps + sec.prestrain);
  AxialPoint p;
  p.ga = (w * n_axial) * s.eps_a;
  if constexpr (kStiffness) {
    // CableTangent::tension_only: no geometric stiffness from compression (N < 0).
    const bool drop = req.tangent == CableTangent::tension_only && n_axial < 0.0;
    p.haa = (w * ea) * s.eps_a * s.eps_a.transpose();
    if (!drop) p.haa += (w * n_axial) * s.eps_aa;
  }
  if constexpr (kDamping) {
    if (ca > 0.0) {
      const double eps_dot = s.eps_a.dot(a_dot);
      p.ga += (w * ca * eps_dot) * s.eps_a;
      if (kStiffness)
        p.haa += (w * ca) * (s.eps_a * (s.eps_aa * a_dot).transpose() + eps_dot * s.eps_aa);
      if (req.damping_matrix) p.daa = (w * ca) * s.eps_a * s.eps_a.transpose();
    }
  }
  return p;
}

/// Bending terms at one Gauss point: gradient and Hessian in x = (a, b) = (r_x, r_xx) and the
/// damping matrix block in ẋ.
struct BendingPoint {
  Vec6 gx;
  Mat6 hx, dx;
  bool has_damping_matrix = false;
};

template <bool kDamping, bool kStiffness>
inline BendingPoint bending_point(const CableSection& sec, const Vec3& a, const Vec3& b,
                                  const Vec6& x_dot, double w, double kappa_ref,
                                  const CableEvalRequest& req, double& energy) {
  const double ei = sec.bending_stiffness, cb = sec.bending_damping;
  const CurvatureSquared c = curvature_squared<kStiffness>(a, b, curvature_power(sec.strain));
  // A straight reference (κ₀ = 0) needs no √: U_b = ½ EI K² and h' = ½, h'' = 0 below.
  const double kappa = kappa_ref > 0.0 ? std::sqrt(c.k2) : 0.0;
  energy += kappa_ref > 0.0 ? 0.5 * w * ei * (kappa - kappa_ref) * (kappa - kappa_ref)
                            : 0.5 * w * ei * c.k2;
  const double kappa0 = kappa > kVanishingCurvatureRatio * kappa_ref ? kappa_ref : 0.0;
  // U_b = EI h(K²) with h = ½K² − κ₀√K² + ½κ₀²: h' = ½ − κ₀/(2κ), h'' = κ₀/(4κ³).
  const double h1 = kappa0 > 0.0 ? 0.5 - 0.5 * kappa0 / kappa : 0.5;
  const double h2 = kappa0 > 0.0 ? 0.25 * kappa0 / (kappa * kappa * kappa) : 0.0;
  BendingPoint p;
  p.gx = (w * ei * h1) * c.grad;
  if (kStiffness) p.hx = (w * ei) * (h1 * c.hess + h2 * c.grad * c.grad.transpose());
  if constexpr (kDamping) {
    if (cb > 0.0) {
      // Kelvin–Voigt on κ̃ = √(K² + κ_s²) (docs/formulation.md): f = c_b κ̃̇ ∇κ̃ = c_b φ χ̇ ∇χ
      // with χ = K², χ̇ = ∇χ·ẋ, φ = 1/(4(χ + κ_s²)); ∂f/∂ẋ = c_b φ ∇χ∇χᵀ and
      // ∂f/∂x = c_b [φ(χ̇ ∇²χ + ∇χ (∇²χ ẋ)ᵀ) − 4φ² χ̇ ∇χ∇χᵀ]. Smooth: φ ≤ 1/(4κ_s²).
      const double ks = sec.bending_damping_curvature;
      const double phi = 0.25 / (c.k2 + ks * ks);
      const double chi_dot = c.grad.dot(x_dot);
      p.gx += (w * cb * phi * chi_dot) * c.grad;
      if (kStiffness)
        p.hx += (w * cb) * (phi * (chi_dot * c.hess + c.grad * (c.hess * x_dot).transpose()) -
                            4.0 * phi * phi * chi_dot * c.grad * c.grad.transpose());
      if (req.damping_matrix) {
        p.dx = (w * cb * phi) * c.grad * c.grad.transpose();
        p.has_damping_matrix = true;
      }
    }
  }
  return p;
}

// kStiffness mirrors req.stiffness at compile time: the force-only instantiation (residual
// assembly) carries no Hessian code.
template <bool kBending, bool kDamping, bool kStiffness>
void evaluate(const CableSection& sec, const CableElementReference& ref, const Vec12& e,
              const Vec12& e_dot, const CableEvalRequest& req, CableElementResult& out) {
  const Eigen::Map<const Mat34> E(e.data());
  const Eigen::Map<const Mat34> Edot(e_dot.data());
  const bool axial_damping = kDamping && sec.axial_damping > 0.0;

  out.energy = 0.0;
  out.force.setZero();
  if (kStiffness) out.stiffness.setZero();
  if (kDamping && req.damping_matrix) out.damping.setZero();

  // Bending terms at point g of ref.bending, with the axial gradient/Hessian `axial` of the same
  // point added (one scatter of the 6-vector instead of two) when the rules coincide.
  auto bending = [&](int g, const AxialPoint* axial) {
    const CableElementReference::Points& pts = ref.bending;
    const Vec4& d1 = pts.d1[g];
    const Vec4& d2 = pts.d2[g];
    const Vec3 a = E * d1, b = E * d2;
    Vec6 x_dot = Vec6::Zero();
    if constexpr (kDamping) x_dot << Edot * d1, Edot * d2;
    BendingPoint p = bending_point<kDamping, kStiffness>(sec, a, b, x_dot, pts.weight[g],
                                                         pts.kappa0[g], req, out.energy);
    if (axial) {
      p.gx.template head<3>() += axial->ga;
      if (kStiffness) p.hx.template topLeftCorner<3, 3>() += axial->haa;
    }
    scatter_force(d1, p.gx.template head<3>(), out.force);
    scatter_force(d2, p.gx.template tail<3>(), out.force);
    if (kStiffness) {
      // Without damping p.hx is the Hessian of the energy (symmetric); the damping terms'
      // ∂f/∂e is not.
      if constexpr (kDamping)
        scatter_matrix(d1, d2, p.hx, out.stiffness);
      else
        scatter_symmetric_matrix(d1, d2, p.hx, out.stiffness);
    }
    if (kDamping && p.has_damping_matrix) scatter_matrix(d1, d2, p.dx, out.damping);
  };

  const bool fused = kBending && ref.shared_points;
  for (int g = 0; g < ref.axial.count; ++g) {
    const Vec4& d1 = ref.axial.d1[g];
    Vec3 a_dot = Vec3::Zero();
    if (axial_damping) a_dot = Edot * d1;
    const AxialPoint p = axial_point<kDamping, kStiffness>(sec, E * d1, a_dot, ref.axial.weight[g],
                                                           ref.axial.inv_j0[g], req, out.energy);
    if (axial_damping && req.damping_matrix) scatter_matrix(d1, p.daa, out.damping);
    if (fused) {
      bending(g, &p);
    } else {
      scatter_force(d1, p.ga, out.force);
      if (kStiffness) scatter_matrix(d1, p.haa, out.stiffness);
    }
  }
  if constexpr (kBending)
    if (!fused)
      for (int g = 0; g < ref.bending.count; ++g) bending(g, nullptr);
}

}  // namespace

CableElementReference CableElementReference::from_reference(const Vec12& e0, double length,
                                                            StrainMeasure strain,
                                                            const CableQuadrature& quadrature) {
  if (!(length > 0.0)) {
    throw ModelError("cable element length must be > 0 m, got " + std::to_string(length));
  }
  CableElementReference ref;
  ref.length = length;
  ref.shared_points = quadrature.axial == quadrature.bending;
  const Eigen::Map<const Mat34> E0(e0.data());
  for (auto [points, count] :
       {std::pair{&ref.axial, quadrature.axial}, std::pair{&ref.bending, quadrature.bending}}) {
    if (count < 1 || count > kMaxCableGaussPoints)
      throw ModelError("cable Gauss rule: expected 1 … " + std::to_string(kMaxCableGaussPoints) +
                       " points per element, got " + std::to_string(count));
    const GaussRule rule = gauss_legendre_unit(count);
    points->count = count;
    for (int g = 0; g < count; ++g) {
      const double xi = rule.points[g];
      points->d1[g] = hermite::first_derivative(xi, length);
      points->d2[g] = hermite::second_derivative(xi, length);
      const Vec3 a0 = E0 * points->d1[g];
      const Vec3 b0 = E0 * points->d2[g];
      const double j0 = a0.norm();
      if (!(j0 > 1e-12)) {
        throw ModelError("cable element reference has a vanishing slope |r_x| = " +
                         std::to_string(j0) + " at xi = " + std::to_string(xi));
      }
      points->inv_j0[g] = 1.0 / j0;
      points->weight[g] = rule.weights[g] * length * j0;
      double kappa0 = std::sqrt(curvature_squared_value(a0, b0, curvature_power(strain)));
      if (kappa0 * length <= kStraightReferenceAngle) kappa0 = 0.0;
      points->kappa0[g] = kappa0;
    }
    for (int g = 0; g < kMaxCableGaussPoints; ++g) {
      const int src = std::min(g, count - 1);
      points->lane_d1.col(g) = points->d1[src].tail<3>();
      points->lane_d2.col(g) = points->d2[src].tail<3>();
      points->lane_weight[g] = g < count ? points->weight[g] : 0.0;
      points->lane_inv_j0[g] = points->inv_j0[src];
      points->lane_kappa0[g] = points->kappa0[src];
    }
    points->straight = (points->lane_kappa0 == 0.0).all();
  }
  return ref;
}

void evaluate_cable_element(const CableSection& section, const CableElementReference& ref,
                            const Vec12& e, const Vec12& e_dot, const CableEvalRequest& request,
                            CableElementResult& out) {
  const bool bending = section.has_bending();
  const bool damping = section.has_damping();
  auto run = [&]<bool kStiffness>() {
    if (bending) {
      if (damping)
        evaluate<true, true, kStiffness>(section, ref, e, e_dot, request, out);
      else
        evaluate<true, false, kStiffness>(section, ref, e, e_dot, request, out);
    } else {
      if (damping)
        evaluate<false, true, kStiffness>(section, ref, e, e_dot, request, out);
      else
        evaluate<false, false, kStiffness>(section, ref, e, e_dot, request, out);
    }
  };
  if (request.stiffness)
    run.template operator()<true>();
  else if (!request.damping_matrix && request.force_kernel == CableForceKernel::invariant)
    detail::evaluate_cable_force_invariant(section, ref, e, e_dot, out);
  else
    run.template operator()<false>();
}

double cable_axial_strain(StrainMeasure strain, const Vec12& e, double xi, double length,
                          double j0) {
  const Eigen::Map<const Mat34> E(e.data());
  const Vec3 a = E * hermite::first_derivative(xi, length);
  return axial_strain(strain, a, 1.0 / j0).eps;
}

}  // namespace ancf
