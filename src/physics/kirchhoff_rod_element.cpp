#include "ancf/physics/kirchhoff_rod_element.hpp"

#include <Eigen/LU>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/core/gauss_legendre.hpp"
#include "ancf/physics/hermite_shape.hpp"
#include "ancf/physics/jet.hpp"
#include "kirchhoff_rod_axial.hpp"
#include "kirchhoff_rod_local_chain.hpp"
#include "kirchhoff_rod_strains.hpp"
#include "kirchhoff_rod_torsion.hpp"

namespace ancf {
namespace {
using namespace rod_detail;

Vec3 to_vec3(const V3<double>& v) {
  return {v.x, v.y, v.z};
}

}  // namespace

Mat3 smallest_rotation(const Mat3& frame, const Vec3& t) {
  const Vec3 g = t.normalized();
  const Vec3 s1 = frame.col(0);
  const double inv = 1.0 / (1.0 + s1.dot(g));
  Mat3 out;
  out.col(0) = g;
  for (int k = 1; k < 3; ++k) out.col(k) = frame.col(k) - (frame.col(k).dot(g) * inv) * (g + s1);
  return out;
}

Mat3 rod_material_triad(const Mat3& reference, const Vec3& t, double alpha) {
  const Mat3 sr = smallest_rotation(reference, t);
  const double c = std::cos(alpha), s = std::sin(alpha);
  Mat3 out = sr;
  out.col(1) = c * sr.col(1) + s * sr.col(2);
  out.col(2) = c * sr.col(2) - s * sr.col(1);
  return out;
}

Mat3 rod_twist_mass(double polar_inertia, double length) {
  Mat3 m;
  m << 10.0, 5.0, 10.0, 5.0, 10.0, 10.0, 10.0, 10.0, 16.0;  // 30 ∫ N Nᵀ dξ
  return (polar_inertia * length / 30.0) * m;
}

RodElementReference RodElementReference::from_reference(const Vec12& e0, double length,
                                                        RodElementHistory& history) {
  if (!(length > 0.0)) throw ModelError("Kirchhoff rod element: length must be > 0");
  for (int node = 0; node < 2; ++node) {
    const Mat3& r = node == 0 ? history.frame1 : history.frame2;
    const Vec3 t = e0.segment<3>(6 * node + 3);
    if (!(t.norm() > 0.0) || (r.transpose() * r - Mat3::Identity()).norm() > 1e-10 ||
        r.determinant() < 0.0 || (r.col(0) - t.normalized()).norm() > 1e-10)
      throw ModelError("Kirchhoff rod element: the reference triad of node " +
                       std::to_string(node + 1) +
                       " is not a right-handed orthonormal triad with the unit reference tangent "
                       "as first column");
  }
  RodElementReference ref;
  ref.length = length;
  ref.e0 = e0;
  const GaussRule rule = gauss_legendre_unit(kRodGaussPoints);
  for (int p = 0; p < kRodGaussPoints; ++p) {
    const double xi = rule.points[p];
    ref.xi[p] = xi;
    ref.d1[p] = hermite::first_derivative(xi, length);
    ref.d2[p] = hermite::second_derivative(xi, length);
    const double j0 = centreline_slope(ref.d1[p], e0.data()).norm();
    if (!(j0 > 0.0)) throw ModelError("Kirchhoff rod element: vanishing reference slope");
    ref.inv_j0[p] = 1.0 / j0;
    ref.weight[p] = rule.weights[p] * length * j0;
    ref.collocation_weight[p] = collocation_lagrange(xi);
  }
  for (int c = 0; c < 3; ++c) {
    const double xi = 0.5 * c;
    ref.collocation_d1[c] = hermite::first_derivative(xi, length);
    const Vec3 a = centreline_slope(ref.collocation_d1[c], e0.data());
    if (!(a.norm() > 0.0)) throw ModelError("Kirchhoff rod element: vanishing reference slope");
    ref.collocation_inv_j0[c] = 1.0 / a.norm();
  }
  Vec15 e = Vec15::Zero();
  e.head<12>() = e0;
  history.omega = 0.0;
  const auto x = to_array<double>(e);
  const ElementFrame<double> f = element_frame(history, x);
  history.omega = f.omega;
  for (int p = 0; p < kRodGaussPoints; ++p) {
    const auto s = point_strains(point_data(ref, p), f, x);
    ref.k0[p] = Vec3(s[1], s[2], s[3]);
  }
  ref.torsion_projection = linear_projection(ref.xi, ref.weight);
  for (int p = 0; p < kRodGaussPoints; ++p) {
    ref.projected_k10[p] = 0.0;
    for (int q = 0; q < kRodGaussPoints; ++q)
      ref.projected_k10[p] += ref.torsion_projection(p, q) * ref.k0[q][0];
  }
  return ref;
}

RodPointState rod_point_state(const RodElementReference& ref, const RodElementHistory& history,
                              const Vec15& e, double xi) {
  const Vec4 d1 = hermite::first_derivative(xi, ref.length);
  const PointData pd{d1, hermite::second_derivative(xi, ref.length),
                     1.0 / centreline_slope(d1, ref.e0.data()).norm(), xi, ref.length};
  const auto x = to_array<double>(e);
  const ElementFrame<double> f = element_frame(history, x);
  PointTriad<double> t;
  const auto s = point_strains(pd, f, x, &t);
  RodPointState out;
  out.triad.col(0) = to_vec3(t.g1);
  out.triad.col(1) = to_vec3(t.g2);
  out.triad.col(2) = to_vec3(t.g3);
  out.axial_strain = s[0];
  out.curvature = Vec3(s[1], s[2], s[3]);
  return out;
}

double rod_torsion_strain(const RodSection& section, const RodElementReference& ref,
                          const RodElementHistory& reference_history,
                          const RodElementHistory& history, const Vec15& e, double xi) {
  if (section.torsion_strain == RodTorsionStrain::projected) {
    // The values the energy squares at the Gauss points lie on this line
    // (kirchhoff_rod_torsion.cpp); K₁ there as the kernels take it, one element frame for all.
    const auto row = rod_detail::linear_projection_row(ref.xi, ref.weight, xi);
    const auto x = to_array<double>(e);
    const ElementFrame<double> f = element_frame(history, x);
    double s = 0.0;
    for (int q = 0; q < kRodGaussPoints; ++q)
      s += row[q] * (point_strains(point_data(ref, q), f, x)[1] - ref.k0[q][0]);
    return s;
  }
  Vec15 e0 = Vec15::Zero();
  e0.head<12>() = ref.e0;
  return rod_point_state(ref, history, e, xi).curvature[0] -
         rod_point_state(ref, reference_history, e0, xi).curvature[0];
}

RodMomentLoad rod_end_moment(const Mat3& reference, const Vec3& t, const Vec3& moment) {
  using J = Jet<3, false>;
  const V3<J> tv{J::variable(t.x(), 0), J::variable(t.y(), 1), J::variable(t.z(), 2)};
  const J inv = 1.0 / sqrt(dot(tv, tv));
  const V3<J> u = scale(inv, tv);
  const V3<J> e = constant<J>(reference.col(0)), m = constant<J>(moment);
  const J ic = checked_inverse_denominator(1.0 + dot(e, u), "loaded node tangent");
  const J mt = dot(m, u);
  const V3<J> q = scale(inv, cross(m, u) - scale(mt * ic, cross(e, u)));
  RodMomentLoad out;
  out.force = Vec4(q.x.v, q.y.v, q.z.v, mt.v);
  out.jacobian.setZero();
  out.jacobian.block<1, 3>(0, 0) = q.x.g.transpose();
  out.jacobian.block<1, 3>(1, 0) = q.y.g.transpose();
  out.jacobian.block<1, 3>(2, 0) = q.z.g.transpose();
  out.jacobian.block<1, 3>(3, 0) = mt.g.transpose();
  return out;
}

double rod_element_omega(const RodElementHistory& history, const Vec15& e) {
  return element_frame(history, to_array<double>(e)).omega;
}

namespace {

// The original kernel: jets in all 15 element coordinates through every operation. Adds and fills
// as evaluate_with_local_chain does.
void evaluate_with_element_jets(const RodSection& section, const RodElementReference& ref,
                                const RodElementHistory& history, const Vec15& e,
                                const Vec15& e_dot, const RodEvalRequest& request,
                                RodElementResult& out, TorsionPoints* torsion) {
  const std::array<double, 4> stiff{section.axial_stiffness, section.torsional_stiffness,
                                    section.bending_stiffness_2, section.bending_stiffness_3};
  const std::array<double, 4> damp{section.axial_damping, section.torsional_damping,
                                   section.bending_damping, section.bending_damping};
  const bool damping = section.has_damping();

  // One pass per Gauss point over the four strains of a jet type J (with or without Hessians).
  auto run = [&](auto tag) {
    using J = decltype(tag);
    const auto x = to_array<J>(e);
    const ElementFrame<J> f = element_frame(history, x);
    for (int p = 0; p < kRodGaussPoints; ++p) {
      const auto s = point_strains(point_data(ref, p), f, x);
      const double w = ref.weight[p];
      if (p == kRodGaussPoints / 2) out.strain_mid = Vec3(s[1].v, s[2].v, s[3].v);
      if (torsion) {
        (*torsion)[p].value = s[1].v;
        (*torsion)[p].gradient = s[1].g;
        if constexpr (std::is_same_v<J, Jet<15, true>>) {
          if (request.stiffness) (*torsion)[p].hessian = s[1].h;
        }
      }
      for (int k = 0; k < 4; ++k) {
        if (!strain_at_gauss_points(section, k)) continue;
        const double d = s[k].v - (k == 0 ? 0.0 : ref.k0[p][k - 1]);
        out.energy += 0.5 * w * stiff[k] * d * d;
        double rate = 0.0;
        if (damping && damp[k] > 0.0) rate = s[k].g.dot(e_dot);
        const double sigma = stiff[k] * d + damp[k] * rate;  // stress resultant of strain k
        out.force.noalias() += (w * sigma) * s[k].g;
        if constexpr (std::is_same_v<J, Jet<15, true>>) {
          if (request.stiffness) {
            out.stiffness.noalias() += (w * stiff[k]) * s[k].g * s[k].g.transpose();
            out.stiffness.noalias() += (w * sigma) * s[k].h;
            if (damping && damp[k] > 0.0) {
              const Vec15 he = s[k].h * e_dot;  // ∂(c ṡ)/∂e = c (H ė)ᵀ
              out.stiffness.noalias() += (w * damp[k]) * s[k].g * he.transpose();
            }
          }
        }
        if (request.damping_matrix && damp[k] > 0.0)
          out.damping.noalias() += (w * damp[k]) * s[k].g * s[k].g.transpose();
      }
    }
  };
  if (request.stiffness)
    run(Jet<15, true>{});
  else
    run(Jet<15, false>{});
}

}  // namespace

void evaluate_rod_element(const RodSection& section, const RodElementReference& ref,
                          const RodElementHistory& history, const Vec15& e, const Vec15& e_dot,
                          const RodEvalRequest& request, RodElementResult& out) {
  out.energy = 0.0;
  out.force.setZero();
  if (request.stiffness) out.stiffness.setZero();
  if (request.damping_matrix) out.damping.setZero();
  // The kernels take the strains at the Gauss points (strain_at_gauss_points); the projected
  // torsion and the collocated axial strain are element-wide and added here.
  TorsionPoints torsion;
  TorsionPoints* const k1 =
      section.torsion_strain == RodTorsionStrain::projected ? &torsion : nullptr;
  if (request.kernel == RodKernel::element_jets)
    evaluate_with_element_jets(section, ref, history, e, e_dot, request, out, k1);
  else
    rod_detail::evaluate_with_local_chain(section, ref, history, e, e_dot, request, out, k1);
  if (k1) rod_detail::add_projected_torsion(section, ref, torsion, e_dot, request, out);
  if (section.axial_strain == RodAxialStrain::collocated)
    rod_detail::add_collocated_axial(section, ref, e, e_dot, request, out);
}

}  // namespace ancf
