#include "ancf/system/assembly.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "ancf/core/stopwatch.hpp"
#include "ancf/system/contact_pattern.hpp"
#include "contact_sampling.hpp"

namespace ancf {
namespace {

using BlockVec = std::array<Vec3, AffineVector::kMaxTerms>;

// The rod history twist coordinates refer to: the state's (outputs) or the workspace's.
const RodHistory& history_of(const SystemState& state, const Workspace& ws) {
  return state.rod_history ? *state.rod_history : ws.rods;
}

// Twist row k (rod_twist_constraint.hpp) at the state's q (and v if `with_velocity`).
void evaluate_twist(const Model& model, std::size_t k, const SystemState& state, Workspace& ws,
                    bool with_velocity, RodTwistRowValues& out) {
  const RodTwistRowData& t = model.twist_rows()[k];
  evaluate(t.row, history_of(state, ws).frames[t.cable][t.node], as_span(state.q),
           with_velocity ? as_span(state.v) : std::span<const double>{},
           ws.frames_at(model, state.t), out);
}

// Visit every cable element with its 12 coordinates/velocities taken from the global vectors.
template <class Visitor>
void for_each_element(const Model& model, const VecX& q, const VecX& v, Visitor&& visit) {
  for (Index ci = 0; ci < static_cast<Index>(model.cables().size()); ++ci) {
    const CableData& c = model.cables()[ci];
    if (c.rod) continue;  // rods: rod_assembly.hpp
    const bool damping = c.section.has_damping();
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      const Index base = c.first_coordinate + 6 * j;
      const Vec12 e = q.segment<12>(base);
      const Vec12 e_dot = damping ? Vec12(v.segment<12>(base)) : Vec12::Zero();
      visit(ci, j, c, base, e, e_dot);
    }
  }
}

// r[base + 3p : +3] += Σ_s m4(p, s) x[base + 3s : +3] — a (4×4 ⊗ I₃) product on one block.
// As 3×4 matrices of the four nodal 3-vectors: R += X m4ᵀ, one fixed-size (vectorized) product
// instead of 16 scalar-times-3-vector updates.
inline void add_mass_times(const Mat4& m4, Index base, const VecX& x, Eigen::Map<VecX>& r) {
  using Mat34 = Eigen::Matrix<double, 3, 4>;
  Eigen::Map<Mat34>(r.data() + base).noalias() +=
      Eigen::Map<const Mat34>(x.data() + base) * m4.transpose();
}

// Where the iteration-matrix entries land. Entry s of model.pattern() has a position part
// (∂/∂q terms and the constraint blocks) and a velocity part (∂/∂v, ∂/∂a terms). In the model's
// own matrix both are the same entry; in a larger matrix (the GGL Jacobian of ggl_problem.cpp)
// they are separate blocks. One template serves both, so the loops over elements, bodies, force
// elements and constraint rows exist once.
struct OwnPattern {
  static constexpr bool kSharedBlocks = true;  // position and velocity terms share one slot
  std::span<double> values;
  double& position(Index s) const { return values[s]; }
  double& velocity(Index s) const { return values[s]; }
};
// The model's slots mapped into a larger pattern with shared position and velocity blocks (the
// contact pattern, contact_pattern.hpp): one indirection per write.
struct Mapped {
  static constexpr bool kSharedBlocks = true;
  std::span<double> values;
  std::span<const Index> map;
  double& position(Index s) const { return values[map[s]]; }
  double& velocity(Index s) const { return values[map[s]]; }
};
struct Scattered {
  static constexpr bool kSharedBlocks = false;
  std::span<double> values;
  const MatrixScatter& map;
  double& position(Index s) const { return values[map.position[s]]; }
  double& velocity(Index s) const { return values[map.velocity[s]]; }
};

}  // namespace
}  // namespace ancf

#include "rod_assembly.hpp"

namespace ancf {
namespace {

// velocity part += w (m4 ⊗ I₃): only the diagonal of each 3×3 block is non-zero (w = w_a for
// the inertia, w_v α for mass-proportional damping).
template <class Target>
void add_mass_matrix(const Mat4& m4, const std::array<Index, 144>& slots, double w,
                     const Target& t) {
  for (int s = 0; s < 4; ++s)
    for (int p = 0; p < 4; ++p)
      for (int d = 0; d < 3; ++d) t.velocity(slots[12 * (3 * s + d) + 3 * p + d]) += w * m4(p, s);
}

// Scatter −scale·Q of a force element into the dynamic residual rows.
inline void subtract_force(const BlockList& blocks, const ForceResult& f, double scale,
                           Eigen::Map<VecX>& r) {
  for (int b = 0; b < blocks.count; ++b)
    r.segment<3>(blocks.blocks[b]) -= scale * f.force.segment<3>(3 * b);
}

// position part −= w_q ∂Q/∂q, velocity part −= w_v ∂Q/∂v, through the element's column-major slots.
template <class Target>
void subtract_force_jacobian(const std::vector<Index>& slots, const ForceResult& f, double w_q,
                             double w_v, const Target& t) {
  const Eigen::Index n = f.d_force_dq.rows();
  for (Eigen::Index c = 0; c < n; ++c)
    for (Eigen::Index r = 0; r < n; ++r) {
      const Index s = slots[c * n + r];
      if (w_q != 0.0) t.position(s) -= w_q * f.d_force_dq(r, c);
      if (w_v != 0.0) t.velocity(s) -= w_v * f.d_force_dv(r, c);
    }
}

// Contact samples: −Q into the dynamic rows of both sides.
// Also hashes the active samples (FNV-1a over pair and element indices, in visiting order) into
// a signature of the active set, which the integrators compare across Newton iterations.
class ResidualContactSink final : public detail::ContactSink {
 public:
  ResidualContactSink(Eigen::Map<VecX>& r, std::uint64_t& signature) : r_(r), hash_(signature) {
    hash_ = 0;
  }
  void add(const ContactSampleResult& s, const detail::ContactSampleBlocks& b) override {
    r_.segment<12>(b.first_a) -= s.force.head<12>();
    if (b.first_b >= 0) r_.segment<12>(b.first_b) -= s.force.tail<12>();
    if (hash_ == 0) hash_ = 14695981039346656037ull;
    for (const Index x : {b.pair, b.first_a, b.first_b})
      hash_ = (hash_ ^ static_cast<std::uint64_t>(x)) * 1099511628211ull;
  }

 private:
  Eigen::Map<VecX>& r_;
  std::uint64_t& hash_;
};

// Contact samples: −w_q ∂Q/∂q and −w_v ∂Q/∂v into the four 12×12 blocks of each sample.
// A coupling block the pattern does not hold (ab == nullptr) is left out and counted: it means
// the contact pattern was not updated at this state (ContactPattern::update).
template <class Target>
class MatrixContactSink final : public detail::ContactSink {
 public:
  MatrixContactSink(const Target& t, double w_q, double w_v) : t_(t), w_q_(w_q), w_v_(w_v) {}
  void add(const ContactSampleResult& s, const detail::ContactSampleBlocks& b) override {
    scatter(s, *b.aa, 0, 0);
    if (b.first_b < 0) return;
    scatter(s, *b.bb, 12, 12);
    if (!b.ab) {
      ++missing;
      return;
    }
    scatter(s, *b.ab, 0, 12);
    scatter(s, *b.ba, 12, 0);
  }
  long missing = 0;

 private:
  void scatter(const ContactSampleResult& s, const BlockSlots& slots, int r0, int c0) const {
    for (int c = 0; c < 12; ++c)
      for (int r = 0; r < 12; ++r) {
        const Index slot = slots[12 * c + r];
        if (w_q_ != 0.0) t_.position(slot) -= w_q_ * s.d_force_dq(r0 + r, c0 + c);
        if (w_v_ != 0.0) t_.velocity(slot) -= w_v_ * s.d_force_dv(r0 + r, c0 + c);
      }
  }
  const Target& t_;
  double w_q_, w_v_;
};

// The iteration matrix w_q K + w_v D + w_a M with the constraint blocks, added into `t`.
// Each cable element kernel runs once, returning K and D together.
template <class Target>
void add_iteration_matrix_to(const Model& model, const SystemState& state,
                             const IterationWeights& w, Workspace& ws, const Target& t) {
  const CableEvalRequest request{.stiffness = w.w_q != 0.0,
                                 .damping_matrix = w.w_v != 0.0,
                                 .tangent = ws.cable_tangent,
                                 .stiffness_kernel = ws.cable_stiffness_kernel};
  const auto frames = ws.frames_at(model, state.t);
  const auto q = as_span(state.q), v = as_span(state.v);

  const auto element_start = TickClock::now();
  for_each_element(
      model, state.q, state.v,
      [&](Index ci, Index j, const CableData& c, Index, const Vec12& e, const Vec12& e_dot) {
        const auto& slots = model.element_slots(ci, j);
        const bool damping = request.damping_matrix && c.section.has_damping();
        if (request.stiffness || damping) {
          evaluate_cable_element(c.section, c.elements[j], e, e_dot, request, ws.element);
          const double* k_e = ws.element.stiffness.data();
          const double* d_e = ws.element.damping.data();
          if constexpr (Target::kSharedBlocks) {
            // One pass writes w_q K + w_v D (the two blocks share slots in the model's pattern).
            if (request.stiffness && damping)
              for (int k = 0; k < 144; ++k) t.position(slots[k]) += w.w_q * k_e[k] + w.w_v * d_e[k];
            else if (request.stiffness)
              for (int k = 0; k < 144; ++k) t.position(slots[k]) += w.w_q * k_e[k];
            else
              for (int k = 0; k < 144; ++k) t.velocity(slots[k]) += w.w_v * d_e[k];
          } else {
            if (request.stiffness)
              for (int k = 0; k < 144; ++k) t.position(slots[k]) += w.w_q * k_e[k];
            if (damping)
              for (int k = 0; k < 144; ++k) t.velocity(slots[k]) += w.w_v * d_e[k];
          }
        }
        if (w.w_a != 0.0) add_mass_matrix(c.mass[j], slots, w.w_a, t);
        if (w.w_v != 0.0 && c.section.mass_damping > 0.0)  // ∂(α M v)/∂v = α M
          add_mass_matrix(c.mass[j], slots, w.w_v * c.section.mass_damping, t);
      });
  detail::add_rod_matrix(model, state, w, ws, t);
  ws.element_seconds += TickClock::seconds_since(element_start);
  if (w.w_a != 0.0)
    for (Index b = 0; b < static_cast<Index>(model.bodies().size()); ++b)
      add_mass_matrix(model.bodies()[b].mass, model.body_slots(b), w.w_a, t);

  if (w.w_q != 0.0)
    for (const auto& f : model.body_torques()) {
      evaluate(f.element, q, state.t, ws.force);
      subtract_force_jacobian(f.slots, ws.force, w.w_q * w.load_factor, 0.0, t);
    }
  for (const auto& f : model.spring_dampers()) {
    evaluate(f.element, q, v, frames, ws.force);
    subtract_force_jacobian(f.slots, ws.force, w.w_q, w.w_v, t);
  }
  for (const auto& f : model.drives()) {
    evaluate(f.element, q, v, state.t, ws.force);
    subtract_force_jacobian(f.slots, ws.force, w.w_q, w.w_v, t);
  }
  if (model.contact_pair_count() > 0 && (w.w_q != 0.0 || w.w_v != 0.0)) {
    const auto contact_start = TickClock::now();
    MatrixContactSink<Target> sink(t, w.w_q, w.w_v);
    detail::visit_contact_samples(model, state, ws, {.jacobians = true, .all_samples = false},
                                  sink);
    ws.missing_coupling_samples += sink.missing;
    ws.contact_seconds += TickClock::seconds_since(contact_start);
  }

  // Constraint blocks Φ_q, Φ_qᵀ and the geometric stiffness w_q ∂(Φ_qᵀλ)/∂q = w_q λ α_k β_m I₃.
  BlockVec gu, gw;
  for (Index i = 0; i < static_cast<Index>(model.rows().size()); ++i) {
    const DotConstraintRow& row = model.rows()[i];
    const AffineVectorState u = evaluate(row.u, q, {}, frames);
    const AffineVectorState wv = evaluate(row.w, q, {}, frames);
    gradient_blocks(row, u, wv, RowGradient::phi, gu, gw);
    const auto slots = model.row_slots(i);
    std::size_t s = 0;
    for (int k = 0; k < row.u.term_count; ++k) {
      for (int d = 0; d < 3; ++d) t.position(slots[s++]) += gu[k][d];
      for (int d = 0; d < 3; ++d) t.position(slots[s++]) += gu[k][d];
    }
    for (int k = 0; k < row.w.term_count; ++k) {
      for (int d = 0; d < 3; ++d) t.position(slots[s++]) += gw[k][d];
      for (int d = 0; d < 3; ++d) t.position(slots[s++]) += gw[k][d];
    }
    const double g = w.w_q * state.lambda[i];
    if (g == 0.0) continue;
    // add_geometric_stiffness visits the (u-term, w-term) pairs in the order the slots were made.
    const auto geo = model.geometric_slots(i);
    std::size_t k = 0;
    add_geometric_stiffness(row, g, [&](Index, Index, double c) {
      for (int d = 0; d < 3; ++d) t.position(geo[k++]) += c;
    });
  }
  // Twist rows: Φ_q, Φ_qᵀ and w_q λ Φ_qq.
  const Index dot_rows = static_cast<Index>(model.rows().size());
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model.twist_rows().size(); ++k) {
    const RodTwistRowData& d = model.twist_rows()[k];
    evaluate_twist(model, k, state, ws, false, tv);
    for (int c = 0; c < tv.column_count; ++c) {
      t.position(d.phi_slots[2 * c]) += tv.phi_q[c];
      t.position(d.phi_slots[2 * c + 1]) += tv.phi_q[c];
    }
    const double g = w.w_q * state.lambda[dot_rows + static_cast<Index>(k)];
    if (g == 0.0) continue;
    for (int j = 0; j < tv.column_count; ++j)
      for (int i = 0; i < tv.column_count; ++i)
        t.position(d.hessian_slots[RodTwistRowData::kN * j + i]) += g * tv.phi_qq(i, j);
  }
}

}  // namespace

SystemState SystemState::initial(const Model& model) {
  SystemState s;
  s.q = model.initial_coordinates();
  s.v = model.initial_velocities();
  s.a = VecX::Zero(model.coordinate_count());
  s.lambda = VecX::Zero(model.multiplier_count());
  return s;
}

Workspace::Workspace(const Model& model)
    : frames(model.frames().size()),
      rods(RodHistory::initial(model)),
      element_boxes(model.cables().size()),
      element_deviations(model.cables().size()),
      cable_boxes(model.cables().size()),
      element_boxes_current(model.cables().size(), 0) {
  auto reserve = [&](Index cable) {
    element_boxes[cable].resize(model.cables()[cable].elements.size());
    element_deviations[cable].resize(model.cables()[cable].elements.size());
  };
  std::size_t most = 0;
  for (const auto& c : model.cable_shape_contacts()) reserve(c.cable);
  for (const auto& c : model.cable_cable_contacts()) {
    reserve(c.cable_a);
    reserve(c.cable_b);
    most = std::max(most, static_cast<std::size_t>(c.count_b));
  }
  candidates.reserve(most);
}

std::span<const FrameKinematics> Workspace::frames_at(const Model& model, double t) {
  if (!frames_valid || t != frames_time) {
    for (std::size_t k = 0; k < frames.size(); ++k) frames[k] = model.frames()[k].at(t);
    frames_time = t;
    frames_valid = true;
  }
  return frames;
}

void assemble_residual(const Model& model, const SystemState& state, double load_factor,
                       Workspace& ws, std::span<double> r) {
  const Index n = model.coordinate_count();
  Eigen::Map<VecX> rq(r.data(), n);
  rq.noalias() = -load_factor * model.constant_load();
  const bool inertia = state.a.size() == n;
  const auto frames = ws.frames_at(model, state.t);
  const auto q = as_span(state.q), v = as_span(state.v);

  const auto element_start = TickClock::now();
  for_each_element(
      model, state.q, state.v,
      [&](Index, Index j, const CableData& c, Index base, const Vec12& e, const Vec12& e_dot) {
        evaluate_cable_element(c.section, c.elements[j], e, e_dot,
                               {.force_kernel = ws.cable_force_kernel}, ws.element);
        rq.segment<12>(base) += ws.element.force;
        if (inertia) add_mass_times(c.mass[j], base, state.a, rq);
        if (c.section.mass_damping > 0.0)
          add_mass_times(c.section.mass_damping * c.mass[j], base, state.v, rq);
      });
  detail::add_rod_residual(model, state, load_factor, inertia, ws, rq);
  ws.element_seconds += TickClock::seconds_since(element_start);
  if (inertia)
    for (const BodyData& b : model.bodies())
      add_mass_times(b.mass, b.first_coordinate, state.a, rq);

  for (const auto& f : model.point_forces()) {
    evaluate(f.element, state.t, ws.force);
    subtract_force(f.blocks, ws.force, load_factor, rq);
  }
  for (const auto& f : model.body_torques()) {
    evaluate(f.element, q, state.t, ws.force);
    subtract_force(f.blocks, ws.force, load_factor, rq);
  }
  for (const auto& f : model.spring_dampers()) {
    evaluate(f.element, q, v, frames, ws.force);
    subtract_force(f.blocks, ws.force, 1.0, rq);
  }
  for (const auto& f : model.drives()) {
    evaluate(f.element, q, v, state.t, ws.force);
    subtract_force(f.blocks, ws.force, 1.0, rq);
  }
  if (model.contact_pair_count() > 0) {
    const auto contact_start = TickClock::now();
    ResidualContactSink sink(rq, ws.active_contact_signature);
    detail::visit_contact_samples(model, state, ws, {.jacobians = false, .all_samples = false},
                                  sink);
    ws.contact_seconds += TickClock::seconds_since(contact_start);
  }

  BlockVec gu, gw;
  for (Index i = 0; i < static_cast<Index>(model.rows().size()); ++i) {
    const DotConstraintRow& row = model.rows()[i];
    const AffineVectorState u = evaluate(row.u, q, {}, frames);
    const AffineVectorState w = evaluate(row.w, q, {}, frames);
    r[n + i] = u.value.dot(w.value) + row.c;
    const double lambda = state.lambda[i];
    if (lambda == 0.0) continue;
    gradient_blocks(row, u, w, false, gu, gw);
    for (int k = 0; k < row.u.term_count; ++k)
      rq.segment<3>(row.u.terms[k].block) += lambda * gu[k];
    for (int k = 0; k < row.w.term_count; ++k)
      rq.segment<3>(row.w.terms[k].block) += lambda * gw[k];
  }
  const Index dot_rows = static_cast<Index>(model.rows().size());
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model.twist_rows().size(); ++k) {
    const Index i = dot_rows + static_cast<Index>(k);
    evaluate_twist(model, k, state, ws, false, tv);
    r[n + i] = tv.phi;
    const double lambda = state.lambda[i];
    if (lambda == 0.0) continue;
    for (int c = 0; c < tv.column_count; ++c) rq[tv.columns[c]] += lambda * tv.phi_q[c];
  }
}

void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& w, Workspace& ws, std::span<double> values) {
  std::fill(values.begin(), values.end(), 0.0);
  ws.coupling = nullptr;
  const long missing = ws.missing_coupling_samples;
  add_iteration_matrix_to(model, state, w, ws, OwnPattern{values});
  // The model's own pattern has no coupling blocks: a contact touching a body or another cable
  // needs the ContactPattern overload (a silently partial matrix would only slow Newton down).
  if (ws.missing_coupling_samples != missing)
    throw std::logic_error(
        "assemble_iteration_matrix: a contact couples two components, whose blocks the model's "
        "own pattern does not hold; assemble into a ContactPattern");
}

void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& w, const ContactPattern& contact,
                               Workspace& ws, std::span<double> values) {
  std::fill(values.begin(), values.end(), 0.0);
  ws.coupling = &contact.coupling();
  if (contact.identity())
    add_iteration_matrix_to(model, state, w, ws, OwnPattern{values});
  else
    add_iteration_matrix_to(model, state, w, ws, Mapped{values, contact.position_of_slot()});
  ws.coupling = nullptr;
}

void add_iteration_matrix(const Model& model, const SystemState& state, const IterationWeights& w,
                          const MatrixScatter& scatter, const ContactCoupling* coupling,
                          Workspace& ws, std::span<double> values) {
  ws.coupling = coupling;
  add_iteration_matrix_to(model, state, w, ws, Scattered{values, scatter});
  ws.coupling = nullptr;
}

void assemble_velocity_constraint(const Model& model, const SystemState& state, Workspace& ws,
                                  std::span<double> out) {
  const auto frames = ws.frames_at(model, state.t);
  const Index dot_rows = static_cast<Index>(model.rows().size());
  for (Index i = 0; i < dot_rows; ++i) {
    const DotConstraintValues c =
        evaluate(model.rows()[i], as_span(state.q), as_span(state.v), frames);
    out[i] = c.phi_q_v + c.phi_t;
  }
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model.twist_rows().size(); ++k) {
    evaluate_twist(model, k, state, ws, true, tv);
    out[dot_rows + static_cast<Index>(k)] = tv.phi_q_v + tv.phi_t;
  }
}

void assemble_acceleration_rhs(const Model& model, const SystemState& state, Workspace& ws,
                               std::span<double> out) {
  const auto frames = ws.frames_at(model, state.t);
  const Index dot_rows = static_cast<Index>(model.rows().size());
  for (Index i = 0; i < dot_rows; ++i)
    out[i] = evaluate(model.rows()[i], as_span(state.q), as_span(state.v), frames).gamma;
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model.twist_rows().size(); ++k) {
    evaluate_twist(model, k, state, ws, true, tv);
    out[dot_rows + static_cast<Index>(k)] = tv.gamma;
  }
}

Energies energies(const Model& model, const SystemState& state, Workspace& ws) {
  Energies e;
  e.kinetic = kinetic_energy(model, state.v);
  e.strain = strain_energy(model, state.q, state.rod_history ? *state.rod_history : ws.rods);
  const auto frames = ws.frames_at(model, state.t);
  for (const auto& f : model.spring_dampers())
    e.spring += potential_energy(f.element, as_span(state.q), frames);
  e.load = -model.constant_load().dot(state.q);
  return e;
}

Momentum momentum(const Model& model, const VecX& q, const VecX& v) {
  Momentum p;
  // ∫ρ ṙ = Σ_s (Σ_p t_p m4(p, s)) v_s with t the translation field; ∫ρ r × ṙ = Σ m4(p, s) x_p ×
  // v_s.
  auto add = [&](const Mat4& m4, Index base, const Vec4& translation) {
    for (int a = 0; a < 4; ++a)
      for (int s = 0; s < 4; ++s) {
        const Vec3 vs = v.segment<3>(base + 3 * s);
        p.linear += translation[a] * m4(a, s) * vs;
        p.angular += m4(a, s) * q.segment<3>(base + 3 * a).cross(vs);
      }
  };
  for (const CableData& c : model.cables())
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j)
      add(c.mass[j], c.first_coordinate + 6 * j, Vec4(1, 0, 1, 0));
  for (const BodyData& b : model.bodies()) add(b.mass, b.first_coordinate, Vec4(1, 0, 0, 0));
  return p;
}

DriveState drive_state(const Model& model, const SystemState& state, Index drive, Workspace& ws) {
  const auto& d = model.drives().at(static_cast<std::size_t>(drive));
  return evaluate(d.element, as_span(state.q), as_span(state.v), state.t, ws.force);
}

ConstraintViolation constraint_violation(const Model& model, const SystemState& state,
                                         Workspace& ws) {
  ConstraintViolation cv;
  const auto frames = ws.frames_at(model, state.t);
  auto take = [&](Index i, double phi, double vel) {
    if (std::abs(phi) > cv.position)
      cv.position = std::abs(phi), cv.position_row = model.coordinate_count() + i;
    if (std::abs(vel) > cv.velocity)
      cv.velocity = std::abs(vel), cv.velocity_row = model.coordinate_count() + i;
  };
  const Index dot_rows = static_cast<Index>(model.rows().size());
  for (Index i = 0; i < dot_rows; ++i) {
    const DotConstraintValues c =
        evaluate(model.rows()[i], as_span(state.q), as_span(state.v), frames);
    take(i, c.phi, c.phi_q_v + c.phi_t);
  }
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model.twist_rows().size(); ++k) {
    evaluate_twist(model, k, state, ws, true, tv);
    take(dot_rows + static_cast<Index>(k), tv.phi, tv.phi_q_v + tv.phi_t);
  }
  return cv;
}

void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& weights, std::span<double> values) {
  Workspace ws(model);
  assemble_iteration_matrix(model, state, weights, ws, values);
}

double strain_energy(const Model& model, const VecX& q) {
  return strain_energy(model, q, RodHistory::initial(model));
}

double strain_energy(const Model& model, const VecX& q, const RodHistory& rods) {
  double u = detail::rod_strain_energy(model, q, rods);
  CableElementResult res;
  for_each_element(model, q, q,
                   [&](Index, Index j, const CableData& c, Index, const Vec12& e, const Vec12&) {
                     CableSection elastic = c.section;
                     elastic.axial_damping = elastic.bending_damping = 0.0;
                     evaluate_cable_element(elastic, c.elements[j], e, Vec12::Zero(), {}, res);
                     u += res.energy;
                   });
  return u;
}

double kinetic_energy(const Model& model, const VecX& v) {
  double t = 0.0;
  auto add = [&](const Mat4& m4, Index base) {
    for (int p = 0; p < 4; ++p)
      for (int s = 0; s < 4; ++s)
        t += 0.5 * m4(p, s) * v.segment<3>(base + 3 * p).dot(v.segment<3>(base + 3 * s));
  };
  for (const CableData& c : model.cables())
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j)
      add(c.mass[j], c.first_coordinate + 6 * j);
  for (const BodyData& b : model.bodies()) add(b.mass, b.first_coordinate);
  for (const CableData& c : model.cables())  // twist inertia ½ ẇᵀ M_α ẇ, w = (α_j, α_j+1, β_j)
    if (c.rod)
      for (Index j = 0; j + 1 < c.node_count; ++j) {
        const int n = c.rod->element_coordinates() - 12;
        Vec3 w = Vec3::Zero();
        for (int k = 0; k < n; ++k) w[k] = v[c.rod_coordinate(j, 12 + k)];
        t += 0.5 * w.dot(c.rod->twist_mass[j] * w);
      }
  return t;
}

}  // namespace ancf
