#include "ancf/io/probe_recorder.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>

#include "ancf/physics/dot_constraint.hpp"
#include "ancf/physics/rigid_body.hpp"

namespace ancf {

namespace {

std::vector<std::string> suffixes(Probe::Kind kind) {
  switch (kind) {
    case Probe::Kind::node:
      return {"x", "y", "z"};
    case Probe::Kind::body:
      return {"x", "y", "z", "rx", "ry", "rz"};
    case Probe::Kind::energy:
      return {"kinetic", "strain", "spring", "load", "total"};
    case Probe::Kind::constraint_violation:
      return {"position", "velocity"};
    case Probe::Kind::contact:
      return {"active", "samples", "min_gap", "centreline_gap", "normal", "friction", "peak"};
    case Probe::Kind::drive:
      return {"angle", "rate", "torque"};
    case Probe::Kind::reaction:
      return {"fx", "fy", "fz", "mx", "my", "mz"};
    case Probe::Kind::rod:
      return {"twist", "torque", "K2", "K3", "d2x", "d2y", "d2z"};
  }
  return {};
}

/// Rotation vector (axis × angle) of the body axes, orthonormalized first (Newton iterates and
/// index-2 drift leave them orthonormal only to the tolerance).
Vec3 rotation_vector(const Mat3& a) {
  const Eigen::AngleAxisd aa(Eigen::Quaterniond(a).normalized());
  return aa.angle() * aa.axis();
}

/// Force [N] and moment [N m] that the constraints `p.constraints` exert on the probe's node or
/// body: the generalized constraint force −Φ_qᵀλ of their rows (residual M a + … + Φ_qᵀλ),
/// restricted to the entity's coordinates, read as a rigid motion's virtual work. Force: the block
/// of the node position / body origin. Moment: δr_x = δθ × r_x (node slope) and δa_i = δθ × a_i
/// (body axes) give M = r_x × Q_{r_x} and M = Σ a_i × Q_{a_i}, about the node and the body
/// origin respectively (a force f at body point p̄ gives Q_{a_i} = p̄_i f, M = (r_P − r_O) × f).
/// A rod node also turns its twist angle: δα = t̂·δθ + (R₁ × t̂)·(δθ × t̂)/(1 + R₁·t̂) (docs/rod.md,
/// end moments), which adds Q_α [t̂ + t̂ × (R₁ × t̂)/(1 + R₁·t̂)] to M.
void reaction(const Model& model, const Probe& p, const SystemState& state, Workspace& ws,
              Vec3& force, Vec3& moment) {
  const Index first = p.on_body ? model.bodies()[p.target].first_coordinate
                                : model.node_coordinate(p.target, p.node);
  const int blocks = p.on_body ? 4 : 2;
  const CableData* rod =
      !p.on_body && model.cables()[p.target].rod ? &model.cables()[p.target] : nullptr;
  const Index node = rod ? (first - rod->first_coordinate) / 6 : 0;
  const Index twist = rod ? rod->rod->twist_first + node : -1;
  std::array<Vec3, 4> g;
  for (Vec3& x : g) x.setZero();
  double g_twist = 0.0;
  const auto frames = ws.frames_at(model, state.t);
  const RodHistory& history = state.rod_history ? *state.rod_history : ws.rods;
  const Index dot_rows = static_cast<Index>(model.rows().size());
  std::array<Vec3, AffineVector::kMaxTerms> gu, gw;
  RodTwistRowValues tv;
  auto add_column = [&](Index column, double value) {
    if (column == twist) g_twist += value;
    const Index offset = column - first;
    if (offset >= 0 && offset < 3 * blocks) g[offset / 3][offset % 3] += value;
  };
  for (const Index c : p.constraints) {
    const ConstraintData& data = model.constraints()[c];
    // first_row counts system rows (y = [q; λ]): multiplier r is system row n + r.
    const Index begin = data.first_row - model.coordinate_count();
    for (Index r = begin; r < begin + data.row_count; ++r) {
      const double lambda = state.lambda[r];
      if (r >= dot_rows) {
        const RodTwistRowData& t = model.twist_rows()[r - dot_rows];
        evaluate(t.row, history.frames[t.cable][t.node], as_span(state.q), {}, frames, tv);
        for (int k = 0; k < tv.column_count; ++k) add_column(tv.columns[k], lambda * tv.phi_q[k]);
        continue;
      }
      const DotConstraintRow& row = model.rows()[r];
      const AffineVectorState u = evaluate(row.u, as_span(state.q), as_span(state.v), frames);
      const AffineVectorState w = evaluate(row.w, as_span(state.q), as_span(state.v), frames);
      gradient_blocks(row, u, w, RowGradient::phi, std::span(gu.data(), row.u.term_count),
                      std::span(gw.data(), row.w.term_count));
      auto add = [&](const BlockTerm& term, const Vec3& gradient) {
        for (int d = 0; d < 3; ++d) add_column(term.block + d, lambda * gradient[d]);
      };
      for (int j = 0; j < row.u.term_count; ++j) add(row.u.terms[j], gu[j]);
      for (int j = 0; j < row.w.term_count; ++j) add(row.w.terms[j], gw[j]);
    }
  }
  force = -g[0];
  moment.setZero();
  for (int k = 1; k < blocks; ++k) moment += state.q.segment<3>(first + 3 * k).cross(-g[k]);
  if (rod && g_twist != 0.0) {
    const Vec3 t = state.q.segment<3>(first + 3).normalized();
    const Vec3 r1 = history.frames[p.target][node].col(0);
    moment -= g_twist * (t + t.cross(r1.cross(t)) / (1.0 + r1.dot(t)));
  }
}

}  // namespace

ProbeRecorder::ProbeRecorder(const Model& model, const std::vector<Probe>& probes)
    : model_(model), probes_(probes), monitor_(model) {
  columns_.push_back("t");
  for (const Probe& p : probes)
    for (const std::string& s : suffixes(p.kind)) columns_.push_back(p.label + "." + s);
  row_.resize(columns_.size());
}

const std::vector<double>& ProbeRecorder::evaluate(const SystemState& state, Workspace& ws) {
  std::size_t k = 0;
  row_[k++] = state.t;
  bool contacts_done = false;
  for (const Probe& p : probes_) {
    switch (p.kind) {
      case Probe::Kind::node: {
        const Index i = model_.node_coordinate(p.target, p.node);
        for (int d = 0; d < 3; ++d) row_[k++] = state.q[i + d];
        break;
      }
      case Probe::Kind::body: {
        const BodyData& b = model_.bodies()[p.target];
        const BodyCoordinates qb = state.q.segment<12>(b.first_coordinate);
        const Vec3 r = rotation_vector(rotation_of(qb));
        for (int d = 0; d < 3; ++d) row_[k++] = qb[d];
        for (int d = 0; d < 3; ++d) row_[k++] = r[d];
        break;
      }
      case Probe::Kind::energy: {
        const Energies e = energies(model_, state, ws);
        for (double x : {e.kinetic, e.strain, e.spring, e.load, e.total()}) row_[k++] = x;
        break;
      }
      case Probe::Kind::constraint_violation: {
        const ConstraintViolation c = constraint_violation(model_, state, ws);
        row_[k++] = c.position;
        row_[k++] = c.velocity;
        break;
      }
      case Probe::Kind::contact: {
        if (!contacts_done) monitor_.update(model_, state, ws);
        contacts_done = true;
        const ContactPairState& c = monitor_.states()[p.target];
        for (double x : {c.active ? 1.0 : 0.0, static_cast<double>(c.active_samples), c.min_gap,
                         c.min_centreline_gap, c.normal_force.norm(), c.friction_force.norm(),
                         c.peak_sample_force})
          row_[k++] = x;
        break;
      }
      case Probe::Kind::rod: {
        // Twist angle α of the node (relative to its committed frame); the torque GJ(K₁ − K₁⁰) the
        // energy sees (projected over the element by default) and the curvatures K₂, K₃ at the
        // middle of the element starting at the node (the last node: the element ending there).
        const CableData& c = model_.cables()[p.target];
        const RodHistory& h = state.rod_history ? *state.rod_history : ws.rods;
        const Index j = std::min<Index>(p.node, c.node_count - 2);
        const RodElementReference& ref = c.rod->elements[j];
        const RodElementHistory now_history = h.element(p.target, j);
        const Vec15 e = rod_element_coordinates(c, j, as_span(state.q));
        const RodPointState now = rod_point_state(ref, now_history, e, 0.5);
        const RodElementHistory ref_history{
            c.rod->reference_frames[j], c.rod->reference_frames[j + 1], c.rod->reference_omega[j]};
        row_[k++] = state.q[c.rod->twist_first + p.node];
        row_[k++] = c.rod->section.torsional_stiffness *
                    rod_torsion_strain(c.rod->section, ref, ref_history, now_history, e, 0.5);
        row_[k++] = now.curvature[1];
        row_[k++] = now.curvature[2];
        // The node's material axis d₂: unlike α it does not depend on the frame history.
        const Vec3 d2 = rod_node_triad(model_, p.target, p.node, as_span(state.q), h).col(1);
        for (int d = 0; d < 3; ++d) row_[k++] = d2[d];
        break;
      }
      case Probe::Kind::drive: {
        const DriveState d = ancf::evaluate(model_.drives()[p.target].element, as_span(state.q),
                                            as_span(state.v), state.t, ws.force);
        row_[k++] = d.angle;
        row_[k++] = d.rate;
        row_[k++] = d.torque;
        break;
      }
      case Probe::Kind::reaction: {
        Vec3 force, moment;
        reaction(model_, p, state, ws, force, moment);
        for (int d = 0; d < 3; ++d) row_[k++] = force[d];
        for (int d = 0; d < 3; ++d) row_[k++] = moment[d];
        break;
      }
    }
  }
  return row_;
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& columns)
    : out_(path) {
  if (!out_) throw ModelError("cannot create " + path);
  for (std::size_t i = 0; i < columns.size(); ++i) out_ << (i ? "," : "") << columns[i];
  out_ << '\n' << std::flush;
}

void CsvWriter::write(const std::vector<double>& row) {
  for (std::size_t i = 0; i < row.size(); ++i)
    // "{}" is the shortest decimal that reads back to the same double (≤ 17 significant
    // digits): full precision, round-trip exact, and short for short values (0.05, not
    // 0.050000000000000003).
    out_ << (i ? "," : "") << fmt::format("{}", row[i]);
  out_ << '\n' << std::flush;
  ++rows_;
}

}  // namespace ancf
