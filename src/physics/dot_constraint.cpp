#include "ancf/physics/dot_constraint.hpp"

#include <stdexcept>

namespace ancf {

AffineVector& AffineVector::add(Index block, double coefficient) {
  if (term_count >= kMaxTerms) throw std::length_error("AffineVector: more than 8 block terms");
  terms[term_count++] = {block, coefficient};
  return *this;
}

AffineVector& AffineVector::add_body(Index body, const Vec4& weights, double coefficient) {
  for (int k = 0; k < 4; ++k)
    if (weights[k] != 0.0) add(body + 3 * k, coefficient * weights[k]);
  return *this;
}

AffineVector AffineVector::constant(const Vec3& value) {
  AffineVector a;
  a.offset = value;
  return a;
}

AffineVectorState evaluate(const AffineVector& u, std::span<const double> q,
                           std::span<const double> v, std::span<const FrameKinematics> frames) {
  AffineVectorState s;
  s.value = u.offset;
  s.velocity.setZero();
  s.time_rate.setZero();
  s.time_accel.setZero();
  for (int k = 0; k < u.term_count; ++k) {
    const BlockTerm& t = u.terms[k];
    s.value += t.coefficient * Eigen::Map<const Vec3>(q.data() + t.block);
    if (!v.empty()) s.velocity += t.coefficient * Eigen::Map<const Vec3>(v.data() + t.block);
  }
  if (u.frame >= 0) {
    const FrameKinematics& f = frames[u.frame];
    s.value += u.frame_position_scale * f.r + f.a * u.frame_vector;
    s.time_rate = u.frame_position_scale * f.r_dot + f.a_dot * u.frame_vector;
    s.time_accel = u.frame_position_scale * f.r_ddot + f.a_ddot * u.frame_vector;
  }
  return s;
}

DotConstraintValues evaluate(const DotConstraintRow& row, std::span<const double> q,
                             std::span<const double> v, std::span<const FrameKinematics> frames) {
  const AffineVectorState u = evaluate(row.u, q, v, frames);
  const AffineVectorState w = evaluate(row.w, q, v, frames);
  DotConstraintValues r;
  r.phi = u.value.dot(w.value) + row.c;
  r.phi_t = u.time_rate.dot(w.value) + u.value.dot(w.time_rate);
  r.phi_q_v = u.velocity.dot(w.value) + u.value.dot(w.velocity);
  const double phi_tt = u.time_accel.dot(w.value) + 2.0 * u.time_rate.dot(w.time_rate) +
                        u.value.dot(w.time_accel);
  const double phi_qv_q_v = 2.0 * u.velocity.dot(w.velocity);
  const double phi_qt_v = u.velocity.dot(w.time_rate) + u.time_rate.dot(w.velocity);
  r.gamma = -(phi_qv_q_v + 2.0 * phi_qt_v + phi_tt);
  return r;
}

void gradient_blocks(const DotConstraintRow& row, const AffineVectorState& u,
                     const AffineVectorState& w, RowGradient which, std::span<Vec3> out_u,
                     std::span<Vec3> out_w) {
  // Φ = u·w: u-blocks pair with (a derivative of) w, w-blocks with (a derivative of) u. For
  // Φ_q v + Φ_t = U·w + u·W + u̇·w + u·ẇ only u and w depend on q.
  const bool time = which == RowGradient::velocity_and_time;
  const Vec3 wu = which == RowGradient::phi ? w.value
                  : time                    ? Vec3(w.velocity + w.time_rate)
                                            : w.velocity;
  const Vec3 uw = which == RowGradient::phi ? u.value
                  : time                    ? Vec3(u.velocity + u.time_rate)
                                            : u.velocity;
  for (int k = 0; k < row.u.term_count; ++k) out_u[k] = row.u.terms[k].coefficient * wu;
  for (int k = 0; k < row.w.term_count; ++k) out_w[k] = row.w.terms[k].coefficient * uw;
}

void gradient_blocks(const DotConstraintRow& row, const AffineVectorState& u,
                     const AffineVectorState& w, bool velocity, std::span<Vec3> out_u,
                     std::span<Vec3> out_w) {
  gradient_blocks(row, u, w, velocity ? RowGradient::velocity : RowGradient::phi, out_u, out_w);
}

}  // namespace ancf
