#include "ancf/physics/rod_twist_constraint.hpp"

#include <stdexcept>
#include <string>

#include "ancf/physics/jet.hpp"

namespace ancf {
namespace {

using J = Jet<4>;  // variables (r_x, α)

struct V3J {
  J x, y, z;
};
J dot(const V3J& a, const Vec3& b) {
  return a.x * b.x() + a.y * b.y() + a.z * b.z();
}

// d₂ = cos α s₂ + sin α s₃ with s_k = R_k − (R_k·t̂)/(1 + R₁·t̂) (t̂ + R₁) (the smallest
// rotation of R onto t̂, as in kirchhoff_rod_element.cpp's sr_column).
V3J material_d2(const Mat3& reference, const Vec3& slope, double alpha) {
  const J tx = J::variable(slope.x(), 0), ty = J::variable(slope.y(), 1),
          tz = J::variable(slope.z(), 2), a = J::variable(alpha, 3);
  const double norm = slope.norm();
  if (!(norm > 0.0)) throw std::invalid_argument("rod twist condition: the node slope is zero");
  const J inv = 1.0 / sqrt(tx * tx + ty * ty + tz * tz);
  const V3J g{tx * inv, ty * inv, tz * inv};
  const Vec3 r1 = reference.col(0);
  const J denominator = 1.0 + dot(g, r1);
  if (!(denominator.v > 1e-8))
    throw std::domain_error(
        "Kirchhoff rod twist condition: the node tangent turned against its smallest-rotation "
        "source (1 + t·t_ref = " +
        std::to_string(denominator.v) + ")");
  const J ic = 1.0 / denominator;
  auto sr = [&](int k) {
    const Vec3 rk = reference.col(k);
    const J f = dot(g, rk) * ic;
    return V3J{rk.x() - f * (g.x + r1.x()), rk.y() - f * (g.y + r1.y()),
               rk.z() - f * (g.z + r1.z())};
  };
  const V3J s2 = sr(1), s3 = sr(2);
  const J c = cos(a), s = sin(a);
  return {c * s2.x + s * s3.x, c * s2.y + s * s3.y, c * s2.z + s * s3.z};
}

}  // namespace

RodTwistLocal rod_twist_condition(const Mat3& reference, const Vec3& slope, double alpha,
                                  const Vec3& b) {
  const V3J d2 = material_d2(reference, slope, alpha);
  const J* d[3] = {&d2.x, &d2.y, &d2.z};
  RodTwistLocal out;
  out.phi = 0.0;
  out.gradient.setZero();
  out.hessian.setZero();
  for (int i = 0; i < 3; ++i) {
    out.phi += d[i]->v * b[i];
    out.gradient.head<4>() += b[i] * d[i]->g;
    out.gradient[4 + i] = d[i]->v;
    out.hessian.topLeftCorner<4, 4>() += b[i] * d[i]->h;
    out.hessian.block<4, 1>(0, 4 + i) = d[i]->g;  // ∂²φ/∂x∂b_i = ∂d₂,i/∂x
    out.hessian.block<1, 4>(4 + i, 0) = d[i]->g.transpose();
  }
  return out;
}

int rod_twist_columns(const RodTwistRow& row, std::array<Index, RodTwistRow::kMaxColumns>& out) {
  if (row.b.term_count > RodTwistRow::kMaxBodyTerms)
    throw std::invalid_argument("rod twist row: b has more than 3 block terms");
  for (int d = 0; d < 3; ++d) out[d] = row.slope + d;
  out[3] = row.twist;
  int n = 4;
  for (int k = 0; k < row.b.term_count; ++k)
    for (int d = 0; d < 3; ++d) out[n++] = row.b.terms[k].block + d;
  return n;
}

void evaluate(const RodTwistRow& row, const Mat3& reference, std::span<const double> q,
              std::span<const double> v, std::span<const FrameKinematics> frames,
              RodTwistRowValues& out) {
  const int n = out.column_count = rod_twist_columns(row, out.columns);
  const AffineVectorState b = evaluate(row.b, q, v, frames);
  const Vec3 slope(q[row.slope], q[row.slope + 1], q[row.slope + 2]);
  const RodTwistLocal local = rod_twist_condition(reference, slope, q[row.twist], b.value);

  // ż = (v_x, U + ḃ_F) and z̈'s explicit part (0, b̈_F).
  Vec7 z_dot = Vec7::Zero();
  if (!v.empty()) {
    for (int d = 0; d < 3; ++d) z_dot[d] = v[row.slope + d];
    z_dot[3] = v[row.twist];
    z_dot.tail<3>() = b.velocity;
  }
  z_dot.tail<3>() += b.time_rate;
  const Vec3 phi_b = local.gradient.tail<3>();
  out.phi = local.phi;
  out.phi_t = phi_b.dot(b.time_rate);
  out.phi_q_v = local.gradient.dot(z_dot) - out.phi_t;
  const Vec7 h_z = local.hessian * z_dot;
  out.gamma = -(z_dot.dot(h_z) + phi_b.dot(b.time_accel));

  // Chain through J = ∂z/∂q: column c < 4 is z_c; column 4 + 3k + d is b̄_k e_d.
  auto jacobian_row = [&](int c, int i) {  // J(i, c)
    if (c < 4) return c == i ? 1.0 : 0.0;
    const int k = (c - 4) / 3, d = (c - 4) % 3;
    return i == 4 + d ? row.b.terms[k].coefficient : 0.0;
  };
  Eigen::Matrix<double, RodTwistRowValues::kN, 7> jac;
  jac.setZero();
  for (int c = 0; c < n; ++c)
    for (int i = 0; i < 7; ++i) jac(c, i) = jacobian_row(c, i);
  // Fixed-size products (rows ≥ n of jac are zero): no heap allocation.
  out.phi_q.noalias() = jac * local.gradient;
  out.psi_q.noalias() = jac * h_z;
  const Eigen::Matrix<double, RodTwistRowValues::kN, 7> jh = jac * local.hessian;
  out.phi_qq.noalias() = jh * jac.transpose();
}

}  // namespace ancf
