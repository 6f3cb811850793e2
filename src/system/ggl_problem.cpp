#include "ancf/system/ggl_problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/core/klu_solver.hpp"

namespace ancf {
namespace {

using BlockVec = std::array<Vec3, AffineVector::kMaxTerms>;

// True if coordinate i is a position (metres): a cable node's r or a body's r_O. Slopes, body
// axes and rod twist angles are dimensionless.
bool is_length(const Model& model, Index i) {
  for (const CableData& c : model.cables()) {
    const Index local = i - c.first_coordinate;
    if (local >= 0 && local < 6 * c.node_count) return local % 6 < 3;
    if (c.is_twist_coordinate(i)) return false;  // a twist angle [rad]
  }
  for (const BodyData& b : model.bodies()) {
    const Index local = i - b.first_coordinate;
    if (local >= 0 && local < 12) return local < 3;
  }
  return true;
}

}  // namespace

GglProblem::GglProblem(const Model& model, GglScales scales, ContactPatternOptions contact)
    : model_(model),
      n_(model.coordinate_count()),
      m_(model.multiplier_count()),
      state_(SystemState::initial(model)),
      workspace_(model),
      contact_(model, contact) {
  build_pattern();
  compute_scales(scales);
}

bool GglProblem::update_jacobian_pattern(double t, std::span<const double> y, double horizon) {
  state_.t = t;
  state_.q = Eigen::Map<const VecX>(y.data(), n_);
  state_.v = Eigen::Map<const VecX>(y.data() + n_, n_);
  if (!contact_.update(state_, horizon, workspace_)) return false;
  build_pattern();
  return true;
}

// Every assembly slot of the contact pattern (the model's pattern entries, then the near
// coupling entries) is copied to the GGL blocks it feeds (see the header's block matrix); the
// slots are looked up once here, so jacobian() only adds through index arrays.
void GglProblem::build_pattern() {
  const Index nnz = contact_.slot_count(), n = n_, v0 = n_, l0 = 2 * n_, u0 = 2 * n_ + m_;
  const std::span<const Index> row = contact_.slot_rows(), col = contact_.slot_columns();
  std::vector<char> geometric(nnz, 0);
  for (Index i = 0; i < static_cast<Index>(model_.rows().size()); ++i)
    for (const Index s : model_.geometric_slots(i)) geometric[s] = 1;
  for (const RodTwistRowData& t : model_.twist_rows()) {
    std::array<Index, RodTwistRow::kMaxColumns> cols{};
    const int count = rod_twist_columns(t.row, cols);
    for (int j = 0; j < count; ++j)
      for (int i = 0; i < count; ++i) geometric[t.hessian_slots[RodTwistRowData::kN * j + i]] = 1;
  }

  // Positions in the GGL matrix of the parts of model entry s (−1: that part does not exist).
  enum Part { kPosition, kVelocity, kPsiQ, kPsiV, kMu, kMuGeometric, kParts };
  auto target = [&](Index s, int part) -> std::pair<Index, Index> {
    const Index r = row[s], c = col[s];
    const bool dyn_row = r < n, dyn_col = c < n;
    switch (part) {
      case kPosition:
        return {dyn_row ? v0 + r : l0 + (r - n), dyn_col ? c : l0 + (c - n)};
      case kVelocity:
        return dyn_row && dyn_col ? std::pair{v0 + r, v0 + c} : std::pair{Index{-1}, Index{-1}};
      case kPsiQ:
        return !dyn_row && dyn_col ? std::pair{u0 + (r - n), c} : std::pair{Index{-1}, Index{-1}};
      case kPsiV:
        return !dyn_row && dyn_col ? std::pair{u0 + (r - n), v0 + c}
                                   : std::pair{Index{-1}, Index{-1}};
      case kMu:
        return dyn_row && !dyn_col ? std::pair{r, u0 + (c - n)} : std::pair{Index{-1}, Index{-1}};
      case kMuGeometric:
        return geometric[s] ? std::pair{r, c} : std::pair{Index{-1}, Index{-1}};
      default:
        return {-1, -1};
    }
  };
  pattern_ = SparsityPattern(size());
  for (Index s = 0; s < nnz; ++s)
    for (int part = 0; part < kParts; ++part)
      if (const auto [r, c] = target(s, part); r >= 0) pattern_.add(r, c);
  for (Index i = 0; i < n; ++i) {
    pattern_.add(i, i);
    pattern_.add(i, v0 + i);
  }
  pattern_.freeze();

  std::vector<Index>* maps[kParts] = {&position_slot_, &velocity_slot_, &psi_q_slot_,
                                      &psi_v_slot_,    &mu_slot_,       &mu_geometric_slot_};
  for (int part = 0; part < kParts; ++part) {
    maps[part]->assign(nnz, -1);
    for (Index s = 0; s < nnz; ++s)
      if (const auto [r, c] = target(s, part); r >= 0) (*maps[part])[s] = pattern_.slot(r, c);
  }
  identity_q_slot_.resize(n);
  identity_v_slot_.resize(n);
  for (Index i = 0; i < n; ++i) {
    identity_q_slot_[i] = pattern_.slot(i, i);
    identity_v_slot_[i] = pattern_.slot(i, v0 + i);
  }
}

void GglProblem::compute_scales(GglScales given) {
  const VecX& q0 = model_.initial_coordinates();
  // Length: extent of the initial configuration (cable nodes, body origins) or the size of a body
  // (|c̄| plus the radius of gyration), whichever is larger.
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::max()), hi = -lo;
  double length = 0.0, mass = 0.0;
  auto extend = [&](const Vec3& x) { lo = lo.cwiseMin(x), hi = hi.cwiseMax(x); };
  for (const CableData& c : model_.cables()) {
    for (Index k = 0; k < c.node_count; ++k) extend(q0.segment<3>(c.first_coordinate + 6 * k));
    for (const Mat4& m4 : c.mass) mass += Vec4(1, 0, 1, 0).dot(m4 * Vec4(1, 0, 1, 0));
  }
  for (const BodyData& b : model_.bodies()) {
    extend(q0.segment<3>(b.first_coordinate));
    const RigidBodyInertia& in = b.inertia;
    length = std::max(length,
                      2.0 * (in.centre_of_mass.norm() + std::sqrt(in.inertia.trace() / in.mass)));
    mass += in.mass;
  }
  if (lo.x() <= hi.x()) length = std::max(length, (hi - lo).norm());
  scales_.length = given.length > 0.0 ? given.length : std::max(length, 1e-6);
  const double big_l = scales_.length;

  scale_.assign(size(), 1.0);
  for (Index i = 0; i < n_; ++i) scale_[i] = is_length(model_, i) ? big_l : 1.0;
  if (given.slope == SlopeScale::position_equivalent) {
    // A nodal slope enters the element's positions through S2, S4 with max|S2| = max|S4| = 4l/27
    // (ξ = 1/3, 2/3): a slope error δ moves centreline points by at most (4l/27)δ, so the slope
    // whose error moves them by L has the scale L/(4l/27), l the shorter adjacent element.
    for (const CableData& c : model_.cables())
      for (Index k = 0; k < c.node_count; ++k) {
        const Index last = static_cast<Index>(c.elements.size()) - 1;
        double l = c.elements[std::min(k, last)].length;
        if (k > 0) l = std::min(l, c.elements[k - 1].length);
        for (int d = 3; d < 6; ++d)
          scale_[c.first_coordinate + 6 * k + d] = big_l / (4.0 * l / 27.0);
      }
  }
  if (given.twist == TwistScale::position_equivalent) {
    // A twist error δα turns the section about the centreline: its points move by r_g δα in the
    // RMS over the section (r_g² = J_p/A = ρJ_p/ρA), so the twist whose error moves them by L
    // has the scale L/r_g. Node angles and interior twists alike.
    for (const CableData& c : model_.cables()) {
      if (!c.rod) continue;
      const RodSection& s = c.rod->section;
      const double r_g = std::sqrt(s.polar_inertia / s.mass_per_length);
      if (!(r_g > 0.0 && std::isfinite(r_g))) continue;
      const Index count = c.rod->twist_block_size(c.node_count);
      for (Index k = 0; k < count; ++k) scale_[c.rod->twist_first + k] = big_l / r_g;
    }
  }

  // Energy: work of the constant loads over one scale of motion, initial kinetic and strain energy.
  double energy = kinetic_energy(model_, model_.initial_velocities()) + strain_energy(model_, q0);
  double load_work = 0.0;
  for (Index i = 0; i < n_; ++i) load_work += std::abs(model_.constant_load()[i]) * scale_[i];
  energy = std::max(energy, load_work);
  // Nothing moves (no loads, at rest, stress-free; motion comes from drives, frames or contact
  // later): a 1 s time scale. "Nothing" includes the round-off strain energy of a curved
  // stress-free reference (~1e-25 J), which would otherwise set T ~ 1e12 s and velocity
  // tolerances no Newton iteration can meet: energies below √ε of ½mL² count as zero.
  const double resting = 0.5 * mass * big_l * big_l;
  if (!(energy > std::sqrt(std::numeric_limits<double>::epsilon()) * resting)) energy = resting;
  scales_.energy = given.energy > 0.0 ? given.energy : energy;
  scales_.time = given.time > 0.0
                     ? given.time
                     : big_l / std::sqrt(2.0 * scales_.energy / std::max(mass, 1e-300));

  for (Index i = 0; i < n_; ++i) scale_[n_ + i] = scale_[i] / scales_.time;

  // Multipliers: g_i = ‖Φ_q,i S‖ at the initial configuration (repeated blocks accumulated).
  row_gradient_.assign(m_, 0.0);
  const auto frames = workspace_.frames_at(model_, 0.0);
  VecX dense = VecX::Zero(n_);
  BlockVec gu, gw;
  const Index dot_rows = static_cast<Index>(model_.rows().size());
  for (Index i = 0; i < dot_rows; ++i) {
    const DotConstraintRow& row = model_.rows()[i];
    const AffineVectorState u = evaluate(row.u, as_span(q0), {}, frames);
    const AffineVectorState w = evaluate(row.w, as_span(q0), {}, frames);
    gradient_blocks(row, u, w, RowGradient::phi, gu, gw);
    double largest_scale = 0.0;
    auto add = [&](const BlockTerm& term, const Vec3& g) {
      dense.segment<3>(term.block) += g;
      largest_scale = std::max(largest_scale, scale_[term.block]);
    };
    for (int k = 0; k < row.u.term_count; ++k) add(row.u.terms[k], gu[k]);
    for (int k = 0; k < row.w.term_count; ++k) add(row.w.terms[k], gw[k]);
    double g2 = 0.0;
    for (const AffineVector* a : {&row.u, &row.w})
      for (int k = 0; k < a->term_count; ++k) {
        const Index b = a->terms[k].block;
        g2 += dense.segment<3>(b).squaredNorm() * scale_[b] * scale_[b];
        dense.segment<3>(b).setZero();  // counted once
      }
    const double g = std::max(std::sqrt(g2), 1e-300);
    row_gradient_[i] = g;
    scale_[2 * n_ + i] = scales_.energy / g;
    scale_[2 * n_ + m_ + i] = largest_scale * largest_scale / (scales_.time * g);
  }
  // Twist rows the same way, at the reference history (their columns do not repeat).
  const RodHistory reference = RodHistory::initial(model_);
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model_.twist_rows().size(); ++k) {
    const RodTwistRowData& tr = model_.twist_rows()[k];
    evaluate(tr.row, reference.frames[tr.cable][tr.node], as_span(q0), {}, frames, tv);
    double largest_scale = 0.0, g2 = 0.0;
    for (int c = 0; c < tv.column_count; ++c) {
      const double sc = scale_[tv.columns[c]];
      largest_scale = std::max(largest_scale, sc);
      g2 += tv.phi_q[c] * tv.phi_q[c] * sc * sc;
    }
    const Index i = dot_rows + static_cast<Index>(k);
    const double g = std::max(std::sqrt(g2), 1e-300);
    row_gradient_[i] = g;
    scale_[2 * n_ + i] = scales_.energy / g;
    scale_[2 * n_ + m_ + i] = largest_scale * largest_scale / (scales_.time * g);
  }
}

VariableClass GglProblem::variable_class(Index i) const {
  return i < n_       ? VariableClass::position
         : i < 2 * n_ ? VariableClass::velocity
                      : VariableClass::algebraic;
}

void GglProblem::unpack(double t, std::span<const double> y, std::span<const double> yp,
                        SystemState& s) const {
  s.t = t;
  s.q = Eigen::Map<const VecX>(y.data(), n_);
  s.v = Eigen::Map<const VecX>(y.data() + n_, n_);
  s.a = Eigen::Map<const VecX>(yp.data() + n_, n_);
  s.lambda = Eigen::Map<const VecX>(y.data() + 2 * n_, m_);
}

void GglProblem::residual(double t, std::span<const double> y, std::span<const double> yp,
                          std::span<double> r) {
  unpack(t, y, yp, state_);
  // F_v and F_Φ are the model's residual with a = v' (rows n … 2n + m are contiguous).
  assemble_residual(model_, state_, 1.0, workspace_, r.subspan(n_, n_ + m_));
  for (Index i = 0; i < n_; ++i) r[i] = yp[i] - y[n_ + i];
  const auto frames = workspace_.frames_at(model_, t);
  const auto q = as_span(state_.q), v = as_span(state_.v);
  const double* mu = y.data() + 2 * n_ + m_;
  BlockVec gu, gw;
  const Index dot_rows = static_cast<Index>(model_.rows().size());
  for (Index i = 0; i < dot_rows; ++i) {
    const DotConstraintRow& row = model_.rows()[i];
    const DotConstraintValues c = evaluate(row, q, v, frames);
    r[2 * n_ + m_ + i] = c.phi_q_v + c.phi_t;
    if (mu[i] == 0.0) continue;
    const AffineVectorState u = evaluate(row.u, q, {}, frames);
    const AffineVectorState w = evaluate(row.w, q, {}, frames);
    gradient_blocks(row, u, w, RowGradient::phi, gu, gw);
    for (int k = 0; k < row.u.term_count; ++k)
      for (int d = 0; d < 3; ++d) r[row.u.terms[k].block + d] += mu[i] * gu[k][d];
    for (int k = 0; k < row.w.term_count; ++k)
      for (int d = 0; d < 3; ++d) r[row.w.terms[k].block + d] += mu[i] * gw[k][d];
  }
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model_.twist_rows().size(); ++k) {
    const RodTwistRowData& tr = model_.twist_rows()[k];
    const Index i = dot_rows + static_cast<Index>(k);
    evaluate(tr.row, workspace_.rods.frames[tr.cable][tr.node], q, v, frames, tv);
    r[2 * n_ + m_ + i] = tv.phi_q_v + tv.phi_t;
    if (mu[i] == 0.0) continue;
    for (int c = 0; c < tv.column_count; ++c) r[tv.columns[c]] += mu[i] * tv.phi_q[c];
  }
}

void GglProblem::jacobian(double t, std::span<const double> y, std::span<const double> yp,
                          double c_j, std::span<double> values) {
  unpack(t, y, yp, state_);
  std::fill(values.begin(), values.end(), 0.0);
  // Rows F_v (K, D + c_j M, Φ_qᵀ) and F_Φ (Φ_q): the model's iteration matrix, one pass.
  add_iteration_matrix(model_, state_, IterationWeights{1.0, 1.0, c_j, 1.0},
                       MatrixScatter{position_slot_, velocity_slot_}, &contact_.coupling(),
                       workspace_, values);
  for (Index i = 0; i < n_; ++i) {
    values[identity_q_slot_[i]] += c_j;
    values[identity_v_slot_[i]] -= 1.0;
  }
  // Rows F_q (Φ_qᵀ in column μ, μ-geometric stiffness) and F_Ψ (∂(Φ_q v + Φ_t)/∂q, Φ_q). The row
  // slots list, per term of u then w, 3 Φ_q entries followed by 3 Φ_qᵀ entries.
  const auto frames = workspace_.frames_at(model_, t);
  const auto q = as_span(state_.q), v = as_span(state_.v);
  const double* mu = y.data() + 2 * n_ + m_;
  BlockVec gu, gw, hu, hw;
  const Index dot_rows = static_cast<Index>(model_.rows().size());
  for (Index i = 0; i < dot_rows; ++i) {
    const DotConstraintRow& row = model_.rows()[i];
    const AffineVectorState u = evaluate(row.u, q, v, frames);
    const AffineVectorState w = evaluate(row.w, q, v, frames);
    gradient_blocks(row, u, w, RowGradient::phi, gu, gw);
    gradient_blocks(row, u, w, RowGradient::velocity_and_time, hu, hw);
    const auto slots = model_.row_slots(i);
    std::size_t s = 0;
    auto add_term = [&](const Vec3& g, const Vec3& h) {
      for (int d = 0; d < 3; ++d, ++s) {
        values[psi_v_slot_[slots[s]]] += g[d];
        values[psi_q_slot_[slots[s]]] += h[d];
      }
      for (int d = 0; d < 3; ++d, ++s) values[mu_slot_[slots[s]]] += g[d];
    };
    for (int k = 0; k < row.u.term_count; ++k) add_term(gu[k], hu[k]);
    for (int k = 0; k < row.w.term_count; ++k) add_term(gw[k], hw[k]);
    if (mu[i] == 0.0) continue;
    const auto geo = model_.geometric_slots(i);
    std::size_t k = 0;
    add_geometric_stiffness(row, mu[i], [&](Index, Index, double c) {
      for (int d = 0; d < 3; ++d) values[mu_geometric_slot_[geo[k++]]] += c;
    });
  }
  // Twist rows: per column the Φ_q slot (row, c) feeds Ψ_v = Φ_q and Ψ_q; the Φ_qᵀ slot (c, row)
  // the μ column; the Hessian slots μ Φ_qq.
  RodTwistRowValues tv;
  for (std::size_t k = 0; k < model_.twist_rows().size(); ++k) {
    const RodTwistRowData& tr = model_.twist_rows()[k];
    evaluate(tr.row, workspace_.rods.frames[tr.cable][tr.node], q, v, frames, tv);
    for (int c = 0; c < tv.column_count; ++c) {
      values[psi_v_slot_[tr.phi_slots[2 * c]]] += tv.phi_q[c];
      values[psi_q_slot_[tr.phi_slots[2 * c]]] += tv.psi_q[c];
      values[mu_slot_[tr.phi_slots[2 * c + 1]]] += tv.phi_q[c];
    }
    const double mu_k = mu[dot_rows + static_cast<Index>(k)];
    if (mu_k == 0.0) continue;
    for (int j = 0; j < tv.column_count; ++j)
      for (int i = 0; i < tv.column_count; ++i)
        values[mu_geometric_slot_[tr.hessian_slots[RodTwistRowData::kN * j + i]]] +=
            mu_k * tv.phi_qq(i, j);
  }
}

void GglProblem::initial_state(std::span<double> y) const {
  std::fill(y.begin(), y.end(), 0.0);
  Eigen::Map<VecX>(y.data(), n_) = model_.initial_coordinates();
  Eigen::Map<VecX>(y.data() + n_, n_) = model_.initial_velocities();
}

void GglProblem::consistent_values(double t, std::span<double> y, std::span<double> yp) {
  const Index n = n_, m = m_;
  SystemState s = SystemState::initial(model_);
  s.t = t;
  s.q = Eigen::Map<const VecX>(y.data(), n);
  s.v = Eigen::Map<const VecX>(y.data() + n, n);
  s.lambda.setZero();
  KluSolver klu(model_.pattern());
  VecX kkt(model_.pattern().nonzeros()), rhs(n + m), r(n + m);
  // [M Φ_qᵀ; Φ_q 0] at the current q: every projection and the acceleration solve use it.
  auto factor = [&] {
    assemble_iteration_matrix(model_, s, IterationWeights{0.0, 0.0, 1.0, 1.0}, workspace_,
                              as_span(kkt));
    klu.factor(as_span(kkt));
  };
  const auto frames = [&] { return workspace_.frames_at(model_, t); };

  // 1. Positions: Newton on Φ(q, t) = 0 with the minimum-M-norm step
  //    [M Φ_qᵀ; Φ_q 0][Δq; κ] = [0; −Φ]; converged when the step is round-off in scaled units.
  double step = 0.0;
  for (int it = 0; it < 30; ++it) {
    factor();
    rhs.setZero();
    const Index dot_rows = static_cast<Index>(model_.rows().size());
    for (Index i = 0; i < dot_rows; ++i)
      rhs[n + i] = -evaluate(model_.rows()[i], as_span(s.q), {}, frames()).phi;
    RodTwistRowValues tv;
    for (std::size_t k = 0; k < model_.twist_rows().size(); ++k) {
      const RodTwistRowData& tr = model_.twist_rows()[k];
      evaluate(tr.row, workspace_.rods.frames[tr.cable][tr.node], as_span(s.q), {}, frames(), tv);
      rhs[n + dot_rows + static_cast<Index>(k)] = -tv.phi;
    }
    klu.solve(as_span(rhs));
    s.q += rhs.head(n);
    step = 0.0;
    for (Index i = 0; i < n; ++i) step = std::max(step, std::abs(rhs[i]) / scale_[i]);
    if (step <= 1e-14) break;
  }
  if (step > 1e-10) {
    const ConstraintViolation cv = constraint_violation(model_, s, workspace_);
    throw SolverError("consistent initial values at t = " + std::to_string(t) +
                      ": the position projection did not converge; largest |Φ| = " +
                      std::to_string(cv.position) + " in " + model_.describe_row(cv.position_row));
  }
  // 2. Velocities (linear): [M Φ_qᵀ; Φ_q 0][Δv; κ] = [0; −(Φ_q v + Φ_t)].
  factor();
  rhs.setZero();
  assemble_velocity_constraint(model_, s, workspace_, std::span(rhs.data() + n, m));
  rhs.tail(m) *= -1.0;
  klu.solve(as_span(rhs));
  s.v += rhs.head(n);
  // 3. Accelerations and multipliers: [M Φ_qᵀ; Φ_q 0][a; λ] = [Q − F; γ] (same matrix).
  s.a.setZero();
  assemble_residual(model_, s, 1.0, workspace_, as_span(r));  // rows [0, n): F − Q at a = 0, λ = 0
  rhs.head(n) = -r.head(n);
  assemble_acceleration_rhs(model_, s, workspace_, std::span(rhs.data() + n, m));
  klu.solve(as_span(rhs));

  std::fill(y.begin(), y.end(), 0.0);
  std::fill(yp.begin(), yp.end(), 0.0);
  Eigen::Map<VecX>(y.data(), n) = s.q;
  Eigen::Map<VecX>(y.data() + n, n) = s.v;
  Eigen::Map<VecX>(y.data() + 2 * n, m) = rhs.tail(m);
  Eigen::Map<VecX>(yp.data(), n) = s.v;
  Eigen::Map<VecX>(yp.data() + n, n) = rhs.head(n);
  for (Index i = 0; i < m; ++i)
    scale_[2 * n + i] = std::max(scale_[2 * n + i], std::abs(rhs[n + i]));
}

std::string GglProblem::describe_row(Index i) const {
  if (i < 0 || i >= size()) return "unknown " + std::to_string(i) + " (outside the system)";
  if (i < n_) return "q of " + model_.describe_row(i);
  if (i < 2 * n_) return "v of " + model_.describe_row(i - n_);
  if (i < 2 * n_ + m_) return "λ of " + model_.describe_row(n_ + i - 2 * n_);
  return "μ of " + model_.describe_row(n_ + i - 2 * n_ - m_);
}

void GglProblem::set_events(int count, EventFunction events) {
  if (count < 0 || (count > 0 && !events))
    throw ModelError("GglProblem::set_events: need count ≥ 0 and a function");
  event_count_ = count;
  events_ = std::move(events);
}

void GglProblem::roots(double t, std::span<const double> y, std::span<const double> yp,
                       std::span<double> g) {
  unpack(t, y, yp, state_);
  events_(state_, g);
}

}  // namespace ancf
