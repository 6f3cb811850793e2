// Force elements (force_elements.hpp): spring-damper, point force, body torque and the
// torque-limited PD drive of a revolute joint, each with its exact ∂Q/∂q and ∂Q/∂v.
//
// Every point or direction is an AffineVector u = Σ_k α_k q[b_k : b_k+3] + ū(t)
// (dot_constraint.hpp), so ∂u/∂q[b_k] = α_k I₃. The results are assembled over the element's
// BlockList: the 3-block with global first index b sits at local rows/columns 3·pos .. 3·pos+2, pos
// = blocks.find(b). Terms of one expression (or of two expressions) that share a block simply
// accumulate.
//
// No heap allocation during evaluation: LocalVector/LocalMatrix have a fixed capacity of 24
// (8 blocks); only the error paths build std::string messages.
#include "ancf/physics/force_elements.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace ancf {

int BlockList::insert(Index block) {
  const int at = find(block);
  if (at >= 0) return at;
  if (count >= kMaxBlocks)
    throw std::length_error("force element: touches more than " + std::to_string(kMaxBlocks) +
                            " distinct 3-blocks");
  blocks[count] = block;
  return count++;
}

int BlockList::find(Index block) const {
  for (int i = 0; i < count; ++i)
    if (blocks[i] == block) return i;
  return -1;
}

void ForceResult::resize(int blocks) {
  if (blocks < 0 || blocks > BlockList::kMaxBlocks)
    throw std::length_error("ForceResult: " + std::to_string(blocks) + " blocks, capacity is " +
                            std::to_string(BlockList::kMaxBlocks));
  const int n = 3 * blocks;  // ≤ 24: within the fixed capacity, so setZero never allocates
  force.setZero(n);
  d_force_dq.setZero(n, n);
  d_force_dv.setZero(n, n);
}

namespace {

void insert_terms(BlockList& list, const AffineVector& u) {
  for (int k = 0; k < u.term_count; ++k) list.insert(u.terms[k].block);
}

/// evaluate(AffineVector, ...) with the frame index checked against the frames supplied.
AffineVectorState state_of(const AffineVector& u, std::span<const double> q,
                           std::span<const double> v, std::span<const FrameKinematics> frames,
                           const char* element) {
  if (u.frame >= 0 && static_cast<std::size_t>(u.frame) >= frames.size())
    throw std::out_of_range(std::string(element) + ": driven frame " + std::to_string(u.frame) +
                            " requested, " + std::to_string(frames.size()) + " supplied");
  return evaluate(u, q, v, frames);
}

/// The 3-vector segment / 3×3 block of local block positions.
auto segment(LocalVector& x, int pos) {
  return x.segment<3>(3 * pos);
}
auto block(LocalMatrix& m, int row, int col) {
  return m.block<3, 3>(3 * row, 3 * col);
}

/// [a]×: [a]× b = a × b.
Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

/// Angle in (−π, π] equal to `a` modulo 2π: a − 2π·ceil((a − π)/2π).
double wrap(double a) {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  return a - two_pi * std::ceil((a - std::numbers::pi) / two_pi);
}

// ---- Spring-damper ------------------------------------------------------------------------------

/// Δ = p2 − p1 = Σ_j γ_j q[b_j] + Δ̄(t): the terms of p1 with γ = −α, then those of p2 with γ = +β,
/// each with the local position of its block.
struct SignedTerm {
  int pos = 0;
  double gamma = 0.0;
};
struct SignedTerms {
  std::array<SignedTerm, 2 * AffineVector::kMaxTerms> terms{};
  int count = 0;
};

SignedTerms difference_terms(const SpringDamper& e, const BlockList& blocks) {
  SignedTerms d;
  for (int k = 0; k < e.p1.term_count; ++k)
    d.terms[d.count++] = {blocks.find(e.p1.terms[k].block), -e.p1.terms[k].coefficient};
  for (int k = 0; k < e.p2.term_count; ++k)
    d.terms[d.count++] = {blocks.find(e.p2.terms[k].block), e.p2.terms[k].coefficient};
  return d;
}

double checked_length(const Vec3& delta) {
  const double length = delta.norm();
  if (!(length > 0.0) || !std::isfinite(length))
    throw std::domain_error("spring-damper: length between its points is " +
                            std::to_string(length) +
                            "; the direction of the force needs a finite length > 0");
  return length;
}

// ---- Revolute drive -----------------------------------------------------------------------------

void reject_frames(const AffineVector& u, const char* which) {
  if (u.frame >= 0)
    throw std::invalid_argument(std::string("revolute drive: direction ") + which +
                                " refers to a driven frame; drive directions must be body "
                                "directions or constants (evaluate() takes no frames)");
}

}  // namespace

// ---- Block lists --------------------------------------------------------------------------------

BlockList blocks_of(const SpringDamper& e) {  // p1's blocks, then p2's
  BlockList list;
  insert_terms(list, e.p1);
  insert_terms(list, e.p2);
  return list;
}

BlockList blocks_of(const PointForce& e) {
  BlockList list;
  insert_terms(list, e.point);
  return list;
}

BlockList blocks_of(const BodyTorque& e) {  // a₁, a₂, a₃; the torque does no work on r_O
  BlockList list;
  for (int k = 1; k <= 3; ++k) list.insert(e.body + 3 * k);
  return list;
}

BlockList blocks_of(const RevoluteDrive& e) {  // d's blocks, then e₁'s, then e₂'s
  BlockList list;
  insert_terms(list, e.d);
  insert_terms(list, e.e1);
  insert_terms(list, e.e2);
  return list;
}

// ---- Spring-damper ------------------------------------------------------------------------------
//
// Δ = p2 − p1 = Σ_j γ_j q_j + Δ̄(t), ℓ = |Δ|, n = Δ/ℓ, Δ̇ = Σ_j γ_j v_j + dΔ̄/dt, ℓ̇ = n·Δ̇,
// f = k(ℓ − ℓ₀) + c ℓ̇. The force on p1 is +f n and on p2 −f n; by virtual work (δp1 = Σ α δq,
// δp2 = Σ β δq) the generalised force of term j is
//   Q_j = −γ_j f n.
// With ∂n/∂q_j = γ_j (I − nnᵀ)/ℓ, ∂ℓ/∂q_j = γ_j nᵀ and ∂ℓ̇/∂q_j = γ_j Δ̇ᵀ(I − nnᵀ)/ℓ (n varies,
// Δ̇ does not depend on q):
//   ∂f/∂q_j = γ_j gᵀ,  g = k n + (c/ℓ)(I − nnᵀ)Δ̇,
//   ∂Q_i/∂q_j = −γ_i γ_j [n gᵀ + (f/ℓ)(I − nnᵀ)],
//   ∂Q_i/∂v_j = −γ_i γ_j c n nᵀ                       (∂ℓ̇/∂v_j = γ_j nᵀ).
// n gᵀ is not symmetric when c ≠ 0 (the damping-rate term); with c = 0 the stiffness is the
// symmetric Hessian of V = ½k(ℓ − ℓ₀)².

void evaluate(const SpringDamper& e, std::span<const double> q, std::span<const double> v,
              std::span<const FrameKinematics> frames, ForceResult& out) {
  const BlockList blocks = blocks_of(e);
  out.resize(blocks.count);
  const AffineVectorState s1 = state_of(e.p1, q, v, frames, "spring-damper");
  const AffineVectorState s2 = state_of(e.p2, q, v, frames, "spring-damper");

  const Vec3 delta = s2.value - s1.value;
  const double length = checked_length(delta);
  const Vec3 n = delta / length;
  // Driven-frame parts move the points explicitly in time: they enter ℓ̇ like velocities.
  const Vec3 delta_rate = (s2.velocity + s2.time_rate) - (s1.velocity + s1.time_rate);
  const double length_rate = n.dot(delta_rate);
  const double tension = e.stiffness * (length - e.rest_length) + e.damping * length_rate;

  const Mat3 transverse = Mat3::Identity() - n * n.transpose();  // I − nnᵀ
  const Vec3 g = e.stiffness * n + (e.damping / length) * (transverse * delta_rate);
  const Mat3 k_block = n * g.transpose() + (tension / length) * transverse;
  const Mat3 c_block = e.damping * n * n.transpose();

  const SignedTerms d = difference_terms(e, blocks);
  for (int i = 0; i < d.count; ++i) {
    const SignedTerm& ti = d.terms[i];
    segment(out.force, ti.pos) -= ti.gamma * tension * n;
    for (int j = 0; j < d.count; ++j) {
      const SignedTerm& tj = d.terms[j];
      block(out.d_force_dq, ti.pos, tj.pos) -= ti.gamma * tj.gamma * k_block;
      block(out.d_force_dv, ti.pos, tj.pos) -= ti.gamma * tj.gamma * c_block;
    }
  }
}

double potential_energy(const SpringDamper& e, std::span<const double> q,
                        std::span<const FrameKinematics> frames) {
  const AffineVectorState s1 = state_of(e.p1, q, {}, frames, "spring-damper");
  const AffineVectorState s2 = state_of(e.p2, q, {}, frames, "spring-damper");
  const double stretch = (s2.value - s1.value).norm() - e.rest_length;
  return 0.5 * e.stiffness * stretch * stretch;
}

// ---- Point force --------------------------------------------------------------------------------
// Work F·δp with δp = Σ_k α_k δq_k: Q_k = α_k F(t). Independent of q and v.

void evaluate(const PointForce& e, double t, ForceResult& out) {
  const BlockList blocks = blocks_of(e);
  out.resize(blocks.count);
  const Vec3 f = e.time_function ? e.time_function(t) : e.force;
  for (int k = 0; k < e.point.term_count; ++k)
    segment(out.force, blocks.find(e.point.terms[k].block)) += e.point.terms[k].coefficient * f;
}

// ---- Body torque --------------------------------------------------------------------------------
// Q_{a_k} = ½ τ × a_k = ½[τ]× a_k. For orthonormal a_k and δa_k = δθ × a_k,
//   Σ_k ½(τ × a_k)·(δθ × a_k) = ½ Σ_k [(τ·δθ)|a_k|² − (τ·a_k)(a_k·δθ)] = ½(3 − 1) τ·δθ = τ·δθ.
// ∂Q_{a_k}/∂a_k = ½[τ]×, no coupling between different a_k, no dependence on v.

void evaluate(const BodyTorque& e, std::span<const double> q, double t, ForceResult& out) {
  out.resize(3);  // blocks_of(e): a₁, a₂, a₃ at positions 0, 1, 2
  const Vec3 tau = e.time_function ? e.time_function(t) : e.torque;
  const Mat3 half_skew = 0.5 * skew(tau);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Map<const Vec3> a(q.data() + e.body + 3 * (k + 1));
    segment(out.force, k) = half_skew * a;
    block(out.d_force_dq, k, k) = half_skew;
  }
}

// ---- Revolute drive -----------------------------------------------------------------------------
//
// x = d·e₁, y = d·e₂ are bilinear in q; θ = atan2(y, x), r² = x² + y²:
//   θ_x = −y/r², θ_y = x/r², θ_xx = 2xy/r⁴ = −θ_yy, θ_xy = (y² − x²)/r⁴.
// Gradients (local vectors over the blocks): x_q has δ_k e₁ at d's terms and ε_m d at e₁'s terms
// (likewise y_q with e₂); x_qq is constant: δ_k ε_m I₃ at (b_k, b_m) and (b_m, b_k).
//   θ_q  = θ_x x_q + θ_y y_q,
//   θ_qq = θ_xx x_q x_qᵀ + θ_xy (x_q y_qᵀ + y_q x_qᵀ) + θ_yy y_q y_qᵀ + θ_x x_qq + θ_y y_qq.
// The drive directions carry no driven-frame parts (the interface takes no frames; checked), so
// θ̇ = θ_q·v = θ_x ẋ + θ_y ẏ with ẋ = ḋ·e₁ + d·ė₁, and
//   ∂θ̇/∂q = θ_qq v = (θ_xx ẋ + θ_xy ẏ) x_q + (θ_xy ẋ + θ_yy ẏ) y_q + θ_x ẋ_q + θ_y ẏ_q,
// ẋ_q = x_qq v being x_q with the vectors replaced by their velocities.  ∂θ̇/∂v = θ_q.
// Drive law τ = τ_max tanh(u/τ_max), u = K_p wrap(θ_ref − θ) + K_d(ω_ref − θ̇) (wrap' = 1), so with
// τ_u = sech²(u/τ_max): τ_θ = −K_p τ_u, τ_θ̇ = −K_d τ_u, and Q = τ θ_q gives
//   ∂Q/∂q = τ_θ θ_q θ_qᵀ + τ_θ̇ θ_q (θ_qq v)ᵀ + τ θ_qq,   ∂Q/∂v = τ_θ̇ θ_q θ_qᵀ.

DriveState evaluate(const RevoluteDrive& e, std::span<const double> q, std::span<const double> v,
                    double t, ForceResult& out) {
  if (!(e.torque_max > 0.0) || !std::isfinite(e.torque_max))
    throw std::invalid_argument("revolute drive: torque limit must be finite and > 0 N m, got " +
                                std::to_string(e.torque_max));
  reject_frames(e.d, "d");
  reject_frames(e.e1, "e1");
  reject_frames(e.e2, "e2");

  const BlockList blocks = blocks_of(e);
  const int n = 3 * blocks.count;
  out.resize(blocks.count);
  const AffineVectorState d = evaluate(e.d, q, v, {});
  const AffineVectorState e1 = evaluate(e.e1, q, v, {});
  const AffineVectorState e2 = evaluate(e.e2, q, v, {});

  const double x = d.value.dot(e1.value), y = d.value.dot(e2.value);
  const double r2 = x * x + y * y;
  // x, y carry round-off ~ε|d||e|: below ~16ε of that, d is along the axis to working precision
  // and θ (and its derivatives ~1/r, 1/r²) would be noise.
  constexpr double tiny = 16.0 * std::numeric_limits<double>::epsilon();
  const double scale2 = d.value.squaredNorm() * (e1.value.squaredNorm() + e2.value.squaredNorm());
  if (!(r2 > tiny * tiny * scale2) || !std::isfinite(r2))
    throw std::domain_error("revolute drive: d is along the joint axis (x^2 + y^2 = " +
                            std::to_string(r2) + "); the angle is undefined");
  const double angle = std::atan2(y, x);
  const double x_rate = d.velocity.dot(e1.value) + d.value.dot(e1.velocity);
  const double y_rate = d.velocity.dot(e2.value) + d.value.dot(e2.velocity);

  // x_q, y_q and their velocity counterparts ẋ_q, ẏ_q.
  LocalVector x_q = LocalVector::Zero(n), y_q = LocalVector::Zero(n);
  LocalVector x_rate_q = LocalVector::Zero(n), y_rate_q = LocalVector::Zero(n);
  for (int k = 0; k < e.d.term_count; ++k) {
    const int p = blocks.find(e.d.terms[k].block);
    const double a = e.d.terms[k].coefficient;
    segment(x_q, p) += a * e1.value;
    segment(y_q, p) += a * e2.value;
    segment(x_rate_q, p) += a * e1.velocity;
    segment(y_rate_q, p) += a * e2.velocity;
  }
  for (int m = 0; m < e.e1.term_count; ++m) {
    const int p = blocks.find(e.e1.terms[m].block);
    segment(x_q, p) += e.e1.terms[m].coefficient * d.value;
    segment(x_rate_q, p) += e.e1.terms[m].coefficient * d.velocity;
  }
  for (int m = 0; m < e.e2.term_count; ++m) {
    const int p = blocks.find(e.e2.terms[m].block);
    segment(y_q, p) += e.e2.terms[m].coefficient * d.value;
    segment(y_rate_q, p) += e.e2.terms[m].coefficient * d.velocity;
  }

  const double r4 = r2 * r2;
  const double th_x = -y / r2, th_y = x / r2;
  const double th_xx = 2.0 * x * y / r4, th_yy = -th_xx, th_xy = (y * y - x * x) / r4;

  LocalVector th_q = th_x * x_q + th_y * y_q;
  const double rate = th_x * x_rate + th_y * y_rate;  // = θ_q·v
  LocalVector rate_q = (th_xx * x_rate + th_xy * y_rate) * x_q +
                       (th_xy * x_rate + th_yy * y_rate) * y_q + th_x * x_rate_q + th_y * y_rate_q;

  // Drive law. The tracking error is wrapped to (−π, π], so the drive is continuous across the
  // atan2 branch cut and for multi-turn references.
  const AngleState ref = e.reference.at(t);
  const double error = wrap(ref.angle - angle);
  const double u = e.kp * error + e.kd * (ref.rate - rate);
  const double s = u / e.torque_max;
  const double tau = e.torque_max * std::tanh(s);
  const double cosh_s = std::cosh(s);
  const double tau_u = 1.0 / (cosh_s * cosh_s);  // sech²: accurate also when saturated (→ 0)
  const double tau_th = -e.kp * tau_u, tau_rate = -e.kd * tau_u;

  out.force = tau * th_q;
  // τ θ_qq, outer-product part.
  out.d_force_dq.noalias() += (tau * th_xx) * x_q * x_q.transpose();
  out.d_force_dq.noalias() += (tau * th_xy) * x_q * y_q.transpose();
  out.d_force_dq.noalias() += (tau * th_xy) * y_q * x_q.transpose();
  out.d_force_dq.noalias() += (tau * th_yy) * y_q * y_q.transpose();
  // τ θ_qq, constant cross-block Hessians of the bilinear forms: τ θ_x x_qq + τ θ_y y_qq.
  for (int k = 0; k < e.d.term_count; ++k) {
    const int pk = blocks.find(e.d.terms[k].block);
    const double a = e.d.terms[k].coefficient;
    for (int m = 0; m < e.e1.term_count; ++m) {
      const int pm = blocks.find(e.e1.terms[m].block);
      const double h = tau * th_x * a * e.e1.terms[m].coefficient;
      block(out.d_force_dq, pk, pm).diagonal().array() += h;
      block(out.d_force_dq, pm, pk).diagonal().array() += h;
    }
    for (int m = 0; m < e.e2.term_count; ++m) {
      const int pm = blocks.find(e.e2.terms[m].block);
      const double h = tau * th_y * a * e.e2.terms[m].coefficient;
      block(out.d_force_dq, pk, pm).diagonal().array() += h;
      block(out.d_force_dq, pm, pk).diagonal().array() += h;
    }
  }
  // Drive-law parts: θ_q (τ_θ θ_q + τ_θ̇ ∂θ̇/∂q)ᵀ and ∂Q/∂v.
  out.d_force_dq.noalias() += th_q * (tau_th * th_q + tau_rate * rate_q).transpose();
  out.d_force_dv.noalias() += tau_rate * th_q * th_q.transpose();

  // Report the branch of θ nearest the reference (θ_ref − wrapped error): continuous over several
  // turns as long as the tracking error stays below π, unlike atan2's principal value.
  return {ref.angle - error, rate, tau};
}

}  // namespace ancf
