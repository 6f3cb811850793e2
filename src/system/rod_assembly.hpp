// The Kirchhoff rod contributions to the residual and iteration matrix (private to assembly.cpp,
// which includes it after its scatter targets and history_of): element forces and matrices under
// the committed history (the state's if it names one, e.g. a static solution's; else the
// workspace's), centreline and twist inertia, mass-proportional damping of the
// centreline and the end and distributed moments with their load stiffness.
#pragma once

#include "ancf/system/assembly.hpp"
#include "ancf/system/rod_history.hpp"

namespace ancf::detail {

// Visit every rod element with its 15 coordinates and velocities (β = 0 for a linear twist).
template <class Visitor>
void for_each_rod_element(const Model& model, const VecX& q, const VecX& v, Visitor&& visit) {
  for (Index ci = 0; ci < static_cast<Index>(model.cables().size()); ++ci) {
    const CableData& c = model.cables()[ci];
    if (!c.rod) continue;
    const bool damping = c.rod->section.has_damping();
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      const Vec15 e = rod_element_coordinates(c, j, as_span(q));
      const Vec15 e_dot = damping && v.size() == q.size()
                              ? rod_element_coordinates(c, j, as_span(v))
                              : Vec15(Vec15::Zero());
      visit(ci, j, c, e, e_dot);
    }
  }
}

// Evaluate every element under a distributed moment into ws.rod_moment (its Jacobian if asked)
// and visit it.
template <class Visitor>
void for_each_distributed_moment(const Model& model, const VecX& q, const RodHistory& history,
                                 Workspace& ws, bool jacobian, Visitor&& visit) {
  for (const RodDistributedMomentData& d : model.rod_distributed_moments()) {
    const CableData& c = model.cables()[d.cable];
    for (Index j = d.first; j < d.first + d.count; ++j) {
      rod_distributed_moment(c.rod->elements[j], history.element(d.cable, j),
                             rod_element_coordinates(c, j, as_span(q)), d.moment_per_length,
                             jacobian, ws.rod_moment);
      visit(c, j);
    }
  }
}

// rows += f (rod elements), M a and α M v of the centreline and the twist inertia; −s Q of the
// moments. `inertia`: a holds accelerations.
inline void add_rod_residual(const Model& model, const SystemState& state, double load_factor,
                             bool inertia, Workspace& ws, Eigen::Map<VecX>& r) {
  const RodHistory& history = history_of(state, ws);
  for_each_rod_element(
      model, state.q, state.v,
      [&](Index ci, Index j, const CableData& c, const Vec15& e, const Vec15& ed) {
        evaluate_rod_element(c.rod->section, c.rod->elements[j], history.element(ci, j), e, ed, {},
                             ws.rod);
        const int n = c.rod->element_coordinates();
        for (int i = 0; i < n; ++i) r[c.rod_coordinate(j, i)] += ws.rod.force[i];
        const Index base = c.first_coordinate + 6 * j;
        const Mat4& m4 = c.mass[j];
        const Mat3& mt = c.rod->twist_mass[j];
        auto add_m = [&](const VecX& x, double s) {
          for (int p = 0; p < 4; ++p)
            for (int k = 0; k < 4; ++k)
              r.segment<3>(base + 3 * p) += s * m4(p, k) * x.segment<3>(base + 3 * k);
          for (int p = 12; p < n; ++p)
            for (int k = 12; k < n; ++k)
              r[c.rod_coordinate(j, p)] += s * mt(p - 12, k - 12) * x[c.rod_coordinate(j, k)];
        };
        if (inertia) add_m(state.a, 1.0);
        if (c.section.mass_damping > 0.0) add_m(state.v, c.section.mass_damping);
      });
  for (const RodMomentData& d : model.rod_moments()) {
    const Index t = d.coordinates[0];
    const RodMomentLoad load =
        rod_end_moment(history.frames[d.cable][d.node],
                       Vec3(state.q[t], state.q[t + 1], state.q[t + 2]), d.moment);
    for (int k = 0; k < 4; ++k) r[d.coordinates[k]] -= load_factor * load.force[k];
  }
  for_each_distributed_moment(model, state.q, history, ws, false, [&](const CableData& c, Index j) {
    for (int i = 0; i < c.rod->element_coordinates(); ++i)
      r[c.rod_coordinate(j, i)] -= load_factor * ws.rod_moment.force[i];
  });
}

// w_q K + w_v D + w_a M of the rods and −w_q s ∂Q/∂q of the moments into the target t.
template <class Target>
void add_rod_matrix(const Model& model, const SystemState& state, const IterationWeights& w,
                    Workspace& ws, const Target& t) {
  const RodEvalRequest request{.stiffness = w.w_q != 0.0, .damping_matrix = w.w_v != 0.0};
  const RodHistory& history = history_of(state, ws);
  for_each_rod_element(
      model, state.q, state.v,
      [&](Index ci, Index j, const CableData& c, const Vec15& e, const Vec15& ed) {
        const auto& slots = c.rod->slots[j];
        const int n = c.rod->element_coordinates();
        const bool damping = request.damping_matrix && c.rod->section.has_damping();
        if (request.stiffness || damping) {
          evaluate_rod_element(c.rod->section, c.rod->elements[j], history.element(ci, j), e, ed,
                               request, ws.rod);
          for (int col = 0; col < n; ++col)
            for (int row = 0; row < n; ++row) {
              const Index slot = slots[n * col + row];
              if (request.stiffness) t.position(slot) += w.w_q * ws.rod.stiffness(row, col);
              if (damping) t.velocity(slot) += w.w_v * ws.rod.damping(row, col);
            }
        }
        const double wm = w.w_a + w.w_v * c.section.mass_damping;
        if (wm == 0.0) return;
        const Mat4& m4 = c.mass[j];
        for (int s = 0; s < 4; ++s)
          for (int p = 0; p < 4; ++p)
            for (int d = 0; d < 3; ++d)
              t.velocity(slots[n * (3 * s + d) + 3 * p + d]) += wm * m4(p, s);
        for (int s = 12; s < n; ++s)
          for (int p = 12; p < n; ++p)
            t.velocity(slots[n * s + p]) += wm * c.rod->twist_mass[j](p - 12, s - 12);
      });
  if (w.w_q == 0.0) return;
  for (const RodMomentData& d : model.rod_moments()) {
    const Index q = d.coordinates[0];
    const RodMomentLoad load =
        rod_end_moment(history.frames[d.cable][d.node],
                       Vec3(state.q[q], state.q[q + 1], state.q[q + 2]), d.moment);
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row)
        t.position(d.slots[4 * col + row]) -= w.w_q * w.load_factor * load.jacobian(row, col);
  }
  for_each_distributed_moment(model, state.q, history, ws, true, [&](const CableData& c, Index j) {
    const int n = c.rod->element_coordinates();
    for (int col = 0; col < n; ++col)
      for (int row = 0; row < n; ++row)
        t.position(c.rod->slots[j][n * col + row]) -=
            w.w_q * w.load_factor * ws.rod_moment.jacobian(row, col);
  });
}

// Strain energy of the rods under `history` [J].
inline double rod_strain_energy(const Model& model, const VecX& q, const RodHistory& history) {
  double u = 0.0;
  RodElementResult res;
  for_each_rod_element(
      model, q, q, [&](Index ci, Index j, const CableData& c, const Vec15& e, const Vec15&) {
        RodSection elastic = c.rod->section;
        elastic.axial_damping = elastic.torsional_damping = elastic.bending_damping = 0.0;
        evaluate_rod_element(elastic, c.rod->elements[j], history.element(ci, j), e, Vec15::Zero(),
                             {}, res);
        u += res.energy;
      });
  return u;
}

}  // namespace ancf::detail
