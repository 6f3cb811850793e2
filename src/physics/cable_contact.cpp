// Contact kernels of one cable sample (cable_contact.hpp, DESIGN §5).
//
// Both kernels reduce the geometry to the same few intermediates over the position unknowns P
// (N = 12 for a shape on ground or a driven frame, 24 for a body or a second cable):
//   g, ∂g/∂P            gap,
//   n, ∂n/∂P            contact normal (the curvature terms live here),
//   v_rel, ∂v_rel/∂P    relative velocity of the two material points (moves with P through the
//                       material point of the other side, y or ξ_b),
//   G = ∂v_rel/∂V       the 3×N map of the velocities,
// and one law routine turns them into the force F per unit length and its Jacobians ∂F/∂P, ∂F/∂V.
// The generalised force is Q = w Gᵀ F; besides Gᵀ ∂F/∂P its P-Jacobian has the term (∂Gᵀ/∂P) F
// because G depends on the material point of the other side (y for a body, ξ_b for a cable).
//
// Everything is fixed-size (3×N Jacobians); no heap allocation.
//
// References: Hunt & Crossley (1975), J. Appl. Mech. 42:440 (damping proportional to the
// penetration); Wriggers, Computational Contact Mechanics (2nd ed. 2006), ch. 4 and 9
// (closest-point projection, its linearisation and the curvature terms in beam-to-beam contact);
// Gerstmayr & Shabana (2006), Nonlinear Dyn. 45:109 (the gradient-deficient ANCF cable element).
#include "ancf/physics/cable_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "ancf/physics/hermite_shape.hpp"

namespace ancf {

namespace {

template <int N>
using Row = Eigen::Matrix<double, 1, N>;
template <int N>
using Jac = Eigen::Matrix<double, 3, N>;

/// S(ξ) e = Σ_k s_k e_k for shape-function values (or derivatives) s.
Vec3 combine(const Vec4& s, const Vec12& e) {
  return s[0] * e.segment<3>(0) + s[1] * e.segment<3>(3) + s[2] * e.segment<3>(6) +
         s[3] * e.segment<3>(9);
}

/// Writes scale · (sᵀ ⊗ I₃) into the 3×12 block of m starting at column `col`.
template <int N>
void put_shape(Jac<N>& m, int col, const Vec4& s, double scale) {
  for (int k = 0; k < 4; ++k)
    m.template block<3, 3>(0, col + 3 * k) = (scale * s[k]) * Mat3::Identity();
}

/// The geometric intermediates of a sample (see the file comment). The P-Jacobians are filled only
/// when Jacobians are requested.
template <int N>
struct Kinematics {
  double gap = 0.0;
  Vec3 normal, v_rel;
  Row<N> gap_p;
  Jac<N> normal_p, v_rel_p, v_rel_v;
};

/// Force per unit length on the cable, F = f_n n + f_t, and its Jacobians.
template <int N>
struct LawForce {
  Vec3 normal, friction;
  Jac<N> total_p, total_v;
};

// The contact law (contact_law.hpp) on the intermediates, with the chain rule
//   f_n = p(δ) h⁺,  δ = −g,  h = 1 + c_HC δ̇,  δ̇ = −n·v_rel   (Hunt & Crossley 1975),
//   v_t = v_rel − (n·v_rel) n,  f_t = −μ f_n v_t / s,  s = √(|v_t|² + v_ε²).
// n is used as computed (it is of unit length only for an orthonormal owner rotation), so every
// derivative below is the exact derivative of what is evaluated.
template <int N>
void apply_law(const ContactLaw& law, const Kinematics<N>& k, bool jacobians, LawForce<N>& out) {
  const Vec3& n = k.normal;
  const ContactLaw::Pressure p = law.pressure(-k.gap);
  const double v_n = n.dot(k.v_rel);  // = −δ̇
  double factor = 1.0;
  bool damped = false;  // damping present and not clipped: h⁺ depends on the state
  if (law.damping > 0.0) {
    const double h = 1.0 - law.damping * v_n;
    factor = std::max(0.0, h);
    damped = h > 0.0;
  }
  const double f_n = p.value * factor;
  out.normal = f_n * n;

  Row<N> fn_p, fn_v;
  if (jacobians) {
    fn_p = (-p.derivative * factor) * k.gap_p;  // ∂p/∂P = p'(δ) ∂δ/∂P = −p' ∂g/∂P
    if (damped) {
      // ∂h/∂P = −c ∂(n·v_rel)/∂P = −c (v_relᵀ ∂n/∂P + nᵀ ∂v_rel/∂P), ∂h/∂V = −c nᵀ G.
      const Row<N> vn_p = k.v_rel.transpose() * k.normal_p + n.transpose() * k.v_rel_p;
      fn_p -= (p.value * law.damping) * vn_p;
      fn_v = (-p.value * law.damping) * (n.transpose() * k.v_rel_v);
    } else {
      fn_v.setZero();
    }
    out.total_p = n * fn_p + f_n * k.normal_p;
    out.total_v = n * fn_v;
  }

  if (!(law.friction > 0.0)) {
    out.friction.setZero();
    return;
  }
  const Vec3 v_t = k.v_rel - v_n * n;
  const double s =
      std::sqrt(v_t.squaredNorm() + law.regularization_speed * law.regularization_speed);
  const Vec3 dir = v_t / s;  // |dir| < 1: the regularised sliding direction
  out.friction = (-law.friction * f_n) * dir;
  if (!jacobians) return;
  // ∂v_t = (I − n nᵀ) ∂v_rel − (n v_relᵀ + (n·v_rel) I) ∂n;  ∂(v_t/s) = (I − dir dirᵀ)/s ∂v_t.
  const Mat3 across = Mat3::Identity() - n * n.transpose();
  const Mat3 turn = n * k.v_rel.transpose() + v_n * Mat3::Identity();
  const Mat3 dir_vt = (Mat3::Identity() - dir * dir.transpose()) / s;
  const Jac<N> vt_p = across * k.v_rel_p - turn * k.normal_p;
  const Jac<N> vt_v = across * k.v_rel_v;
  out.total_p -= law.friction * (dir * fn_p + (f_n * dir_vt) * vt_p);
  out.total_v -= law.friction * (dir * fn_v + (f_n * dir_vt) * vt_v);
}

/// Q = w Gᵀ F and the parts Gᵀ ∂F/∂P, Gᵀ ∂F/∂V of its Jacobians (the (∂Gᵀ/∂P) F part is the
/// caller's, as it depends on what G depends on).
template <int N>
void assemble(const Jac<N>& g_mat, const LawForce<N>& f, double w, bool jacobians,
              ContactSampleResult& out) {
  out.normal_force = w * f.normal;
  out.friction_force = w * f.friction;
  const Vec3 force = f.normal + f.friction;
  out.force.template head<N>() = w * (g_mat.transpose() * force);
  if (!jacobians) return;
  out.d_force_dq.template topLeftCorner<N, N>() = w * (g_mat.transpose() * f.total_p);
  out.d_force_dv.template topLeftCorner<N, N>() = w * (g_mat.transpose() * f.total_v);
}

// Sample against a shape; N = 24 when the owner is a body (P = [e; r_O; a₁; a₂; a₃]), 12 otherwise.
//   y = Aᵀ(x − r_O):   ∂y/∂e = Aᵀ(S ⊗ I),  ∂y/∂r_O = −Aᵀ,  ∂y_k/∂a_k = (x − r_O)ᵀ;
//   g = d(y) − r:      ∂g/∂P = ∇dᵀ ∂y/∂P;
//   n = A ∇d(y):       ∂n/∂P = A ∇²d ∂y/∂P (curvature) + ∂_{a_k}: (∇d)_k I;
//   v_rel = ẋ − ṙ_O − Ȧ y:  ∂v_rel/∂P = −Ȧ ∂y/∂P (the material point y moves with P);
//   G = [S ⊗ I, −I, −y₁ I, −y₂ I, −y₃ I]:  ∂(Gᵀ F)/∂P adds −F ∂y_k/∂P in the rows of a_k.
template <int N>
void shape_kernel(const ContactLaw& law, const ShapeOwnerPose& owner, const CableSample& c,
                  const Vec4& s, const Vec3& rel, const Vec3& y, const SignedDistance& sd,
                  bool jacobians, ContactSampleResult& out) {
  constexpr bool body = N == 24;
  const Mat3& a = owner.rotation;
  const Mat3& a_dot = owner.rotation_rate;

  Jac<N> g_mat = Jac<N>::Zero();
  put_shape(g_mat, 0, s, 1.0);
  if constexpr (body) {
    g_mat.template block<3, 3>(0, 12) = -Mat3::Identity();
    for (int k = 0; k < 3; ++k)
      g_mat.template block<3, 3>(0, 15 + 3 * k) = -y[k] * Mat3::Identity();
  }

  Kinematics<N> kin;
  kin.gap = out.gap;
  kin.normal = out.normal;
  kin.v_rel = combine(s, c.e_dot) - owner.origin_velocity - a_dot * y;
  Jac<N> y_p;
  if (jacobians) {
    y_p.setZero();
    for (int k = 0; k < 4; ++k) y_p.template block<3, 3>(0, 3 * k) = s[k] * a.transpose();
    if constexpr (body) {
      y_p.template block<3, 3>(0, 12) = -a.transpose();
      for (int k = 0; k < 3; ++k) y_p.template block<1, 3>(k, 15 + 3 * k) = rel.transpose();
    }
    kin.gap_p = sd.gradient.transpose() * y_p;
    kin.normal_p = (a * sd.hessian) * y_p;
    if constexpr (body)
      for (int k = 0; k < 3; ++k)
        kin.normal_p.template block<3, 3>(0, 15 + 3 * k).diagonal().array() += sd.gradient[k];
    kin.v_rel_p = -a_dot * y_p;
    kin.v_rel_v = g_mat;
  }

  LawForce<N> f;
  apply_law(law, kin, jacobians, f);
  assemble(g_mat, f, c.weight, jacobians, out);
  if constexpr (body) {
    if (jacobians) {
      const Vec3 force = c.weight * (f.normal + f.friction);
      for (int k = 0; k < 3; ++k)
        out.d_force_dq.template block<3, N>(15 + 3 * k, 0) -= force * y_p.row(k);
    }
  }
}

/// Newton on f(ξ) = (r(ξ) − x)·r_ξ(ξ) inside a bracket with f(lo) < 0 ≤ f(hi), falling back to
/// bisection whenever the Newton step would leave the bracket (or f' ≤ 0), to round-off.
template <class Residual>
double refine_root(const Residual& residual, double lo, double hi) {
  constexpr double eps = std::numeric_limits<double>::epsilon();
  double xi = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200; ++iteration) {
    double slope = 0.0;
    const double f = residual(xi, slope);
    if (f == 0.0) return xi;
    (f < 0.0 ? lo : hi) = xi;
    double next = slope > 0.0 ? xi - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    const bool converged = std::abs(next - xi) <= 4.0 * eps || hi - lo <= 4.0 * eps;
    xi = next;
    if (converged) break;
  }
  return xi;
}

}  // namespace

bool evaluate_cable_shape_contact(const ContactLaw& law, const ContactShape& shape,
                                  const ShapeOwnerPose& owner, const CableSample& sample,
                                  bool jacobians, ContactSampleResult& out) {
  const Vec4 s = hermite::values(sample.xi, sample.length);
  const Vec3 x = combine(s, sample.e);
  const Vec3 rel = x - owner.origin;
  const Vec3 y = owner.rotation.transpose() * rel;  // y_k = a_k·(x − r_O)
  const SignedDistance sd = signed_distance(shape, y);
  out.point = x;
  out.normal = owner.rotation * sd.gradient;  // not re-normalised: exact derivatives for any A
  out.gap = sd.distance - sample.radius;
  out.active = out.gap < 0.0;
  if (!out.active) return false;
  if (owner.is_body)
    shape_kernel<24>(law, owner, sample, s, rel, y, sd, jacobians, out);
  else
    shape_kernel<12>(law, owner, sample, s, rel, y, sd, jacobians, out);
  return true;
}

// Cable a against element b, P = [e_a; e_b]:
//   d = x_a − x_b(ξ_b),  g = |d| − r_a − r_b,  n = d/|d|,  G = [S(ξ_a) ⊗ I, −S(ξ_b) ⊗ I].
// For an interior ξ_b the projection is stationary, f(ξ_b, P) = (x_b − x_a)·x_b,ξ = 0, so by the
// implicit function theorem ∂ξ_b/∂P = −f_P/f_ξ with
//   f_ξ = |x_b,ξ|² − d·x_b,ξξ,   f_{e_a} = −x_b,ξᵀ (S(ξ_a) ⊗ I),
//   f_{e_b} = x_b,ξᵀ (S(ξ_b) ⊗ I) − dᵀ (S_ξ(ξ_b) ⊗ I)
// (Wriggers 2006, closest-point projection of beam contact). Sliding of ξ_b gives
//   ∂d/∂P = G − x_b,ξ ∂ξ_b/∂P,  ∂v_rel/∂P = −(S_ξ(ξ_b) ė_b) ∂ξ_b/∂P,
// and ∂(Gᵀ F)/∂P gains −S_ξ,k(ξ_b) F ∂ξ_b/∂P in the rows of node block k of e_b. The tangential
// part of ∂d/∂P turns n (the curvature terms); for a clamped ξ_b ∈ {0, 1} all ∂ξ_b/∂P terms vanish.
bool evaluate_cable_cable_contact(const ContactLaw& law, const CableSample& a, const Vec12& e_b,
                                  const Vec12& e_b_dot, double length_b, double radius_b,
                                  double xi_b, bool jacobians, ContactSampleResult& out) {
  const Vec4 sa = hermite::values(a.xi, a.length);
  const Vec4 sb = hermite::values(xi_b, length_b);
  const Vec3 x_a = combine(sa, a.e);
  const Vec3 d = x_a - combine(sb, e_b);
  const double dist = d.norm();
  out.point = x_a;
  out.xi_other = xi_b;
  out.gap = dist - a.radius - radius_b;
  // Coincident centrelines (measure zero) have no normal: reported inactive, with a zero normal.
  out.normal = dist > 0.0 ? Vec3(d / dist) : Vec3::Zero();
  out.active = out.gap < 0.0 && dist > 0.0;
  if (!out.active) return false;
  const Vec3& n = out.normal;

  Jac<24> g_mat = Jac<24>::Zero();
  put_shape(g_mat, 0, sa, 1.0);
  put_shape(g_mat, 12, sb, -1.0);

  Kinematics<24> kin;
  kin.gap = out.gap;
  kin.normal = n;
  kin.v_rel = combine(sa, a.e_dot) - combine(sb, e_b_dot);

  bool sliding = false;  // ξ_b interior with a regular stationary point: ∂ξ_b/∂P ≠ 0
  Row<24> xi_p;
  Vec4 sb_xi;
  if (jacobians) {
    Jac<24> d_p = g_mat;
    kin.v_rel_p.setZero();
    if (xi_b > 0.0 && xi_b < 1.0) {
      sb_xi = length_b * hermite::first_derivative(xi_b, length_b);  // dS/dξ
      const Vec4 sb_xixi = (length_b * length_b) * hermite::second_derivative(xi_b, length_b);
      const Vec3 tangent = combine(sb_xi, e_b), tangent_xi = combine(sb_xixi, e_b);
      const double f_xi = tangent.squaredNorm() - d.dot(tangent_xi);
      // f_ξ > 0 at a strict minimum; f_ξ ≤ 0 (degenerate projection) is treated as clamped.
      if (f_xi > 0.0) {
        sliding = true;
        Row<24> f_p;
        for (int k = 0; k < 4; ++k) {
          f_p.segment<3>(3 * k) = -sa[k] * tangent.transpose();
          f_p.segment<3>(12 + 3 * k) = sb[k] * tangent.transpose() - sb_xi[k] * d.transpose();
        }
        xi_p = -f_p / f_xi;
        d_p -= tangent * xi_p;
        kin.v_rel_p = -combine(sb_xi, e_b_dot) * xi_p;
      }
    }
    kin.gap_p = n.transpose() * d_p;
    kin.normal_p = ((Mat3::Identity() - n * n.transpose()) / dist) * d_p;
    kin.v_rel_v = g_mat;
  }

  LawForce<24> f;
  apply_law(law, kin, jacobians, f);
  assemble(g_mat, f, a.weight, jacobians, out);
  if (sliding) {
    const Vec3 force = a.weight * (f.normal + f.friction);
    for (int k = 0; k < 4; ++k)
      out.d_force_dq.block<3, 24>(12 + 3 * k, 0) -= (sb_xi[k] * force) * xi_p;
  }
  return true;
}

ElementProjection project_onto_element(const Vec12& e, double length, const Vec3& x) {
  // φ(ξ) = ½|r(ξ) − x|² is a polynomial of degree 6; its stationary points solve
  // f(ξ) = φ' = (r − x)·r_ξ = 0, with f' = |r_ξ|² + (r − x)·r_ξξ. Minima of φ are where f
  // changes sign from − to +: bracket them on a coarse grid, refine each, and keep the global
  // minimum together with the two end points (clamped candidates).
  const auto residual = [&](double xi, double& slope) {
    const Vec3 r = combine(hermite::values(xi, length), e) - x;
    const Vec3 t = combine(length * hermite::first_derivative(xi, length), e);
    const Vec3 t_xi = combine((length * length) * hermite::second_derivative(xi, length), e);
    slope = t.squaredNorm() + r.dot(t_xi);
    return r.dot(t);
  };
  const auto distance = [&](double xi) {
    return (combine(hermite::values(xi, length), e) - x).norm();
  };

  ElementProjection best{0.0, distance(0.0)};
  const auto consider = [&](double xi) {
    const double dist = distance(xi);
    if (dist < best.distance) best = {xi, dist};
  };
  consider(1.0);

  constexpr int kSamples = 8;  // including both ends
  std::array<double, kSamples> f{};
  for (int i = 0; i < kSamples; ++i) {
    double slope = 0.0;
    f[i] = residual(static_cast<double>(i) / (kSamples - 1), slope);
  }
  for (int i = 0; i + 1 < kSamples; ++i)
    if (f[i] < 0.0 && f[i + 1] >= 0.0)
      consider(refine_root(residual, static_cast<double>(i) / (kSamples - 1),
                           static_cast<double>(i + 1) / (kSamples - 1)));
  return best;
}

Aabb element_bounding_box(const Vec12& e, double length) {
  // Bézier control points of the cubic: the curve lies in their convex hull.
  const Vec3 ri = e.segment<3>(0), rj = e.segment<3>(6);
  Aabb box;
  box.extend(ri);
  box.extend(ri + (length / 3.0) * e.segment<3>(3));
  box.extend(rj - (length / 3.0) * e.segment<3>(9));
  box.extend(rj);
  return box;
}

}  // namespace ancf
