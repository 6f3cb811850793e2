#include "ancf/system/assembly.hpp"

#include <algorithm>

namespace ancf {
namespace {

// Visit every element with its 12 coordinates/velocities mapped from the global vectors.
template <class Visitor>
void for_each_element(const Model& model, const VecX& q, const VecX& v, Visitor&& visit) {
  for (Index ci = 0; ci < static_cast<Index>(model.cables().size()); ++ci) {
    const CableData& c = model.cables()[ci];
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      const Index base = c.first_coordinate + 6 * j;
      const Vec12 e = q.segment<12>(base);
      const Vec12 e_dot = c.section.has_damping() ? Vec12(v.segment<12>(base)) : Vec12::Zero();
      visit(ci, j, c, base, e, e_dot);
    }
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

void assemble_residual(const Model& model, const SystemState& state, double load_factor,
                       std::span<double> r) {
  const Index n = model.coordinate_count();
  Eigen::Map<VecX> rq(r.data(), n);
  rq.noalias() = -load_factor * model.constant_load();
  CableElementResult res;
  const CableEvalRequest request{};
  const bool has_inertia = state.a.size() == n && state.a.squaredNorm() > 0.0;
  for_each_element(model, state.q, state.v,
                   [&](Index, Index j, const CableData& c, Index base, const Vec12& e,
                       const Vec12& e_dot) {
                     evaluate_cable_element(c.section, c.elements[j], e, e_dot, request, res);
                     rq.segment<12>(base) += res.force;
                     if (has_inertia) {
                       const Mat4& m4 = c.mass[j];
                       for (int p = 0; p < 4; ++p)
                         for (int s = 0; s < 4; ++s)
                           rq.segment<3>(base + 3 * p) += m4(p, s) * state.a.segment<3>(base + 3 * s);
                     }
                   });
  for (const NodeConstraintData& d : model.constraints()) {
    const Eigen::Matrix<double, 6, 1> x = state.q.segment<6>(d.node_coordinate);
    for (int k = 0; k < d.law.rows; ++k) {
      const double lam = state.lambda[d.first_row - n + k];
      rq.segment<6>(d.node_coordinate) += d.law.g.row(k).transpose() * lam;
      r[d.first_row + k] = d.law.residual(k, x);
    }
  }
}

void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& w, std::span<double> values) {
  std::fill(values.begin(), values.end(), 0.0);
  CableElementResult res;
  const CableEvalRequest request{.stiffness = w.w_q != 0.0, .damping_matrix = w.w_v != 0.0};
  for_each_element(model, state.q, state.v,
                   [&](Index ci, Index j, const CableData& c, Index, const Vec12& e,
                       const Vec12& e_dot) {
                     const auto& slots = model.element_slots(ci, j);
                     const bool damping = request.damping_matrix && c.section.has_damping();
                     if (request.stiffness || damping) {
                       evaluate_cable_element(c.section, c.elements[j], e, e_dot, request, res);
                       for (int k = 0; k < 144; ++k) {
                         double value = w.w_q * res.stiffness.data()[k];
                         if (damping) value += w.w_v * res.damping.data()[k];
                         values[slots[k]] += value;
                       }
                     }
                     if (w.w_a != 0.0) {
                       // M = m4 ⊗ I₃: only the diagonal of each 3×3 block is non-zero.
                       const Mat4& m4 = c.mass[j];
                       for (int s = 0; s < 4; ++s)
                         for (int p = 0; p < 4; ++p)
                           for (int d = 0; d < 3; ++d)
                             values[slots[12 * (3 * s + d) + 3 * p + d]] += w.w_a * m4(p, s);
                     }
                   });
  for (const NodeConstraintData& d : model.constraints()) {
    for (int r = 0; r < d.law.rows; ++r)
      for (int k = 0; k < 6; ++k)
        if (d.slot_phi_q[r][k] >= 0) {
          values[d.slot_phi_q[r][k]] += d.law.g(r, k);
          values[d.slot_phi_qt[r][k]] += d.law.g(r, k);
        }
  }
}

double strain_energy(const Model& model, const VecX& q) {
  double u = 0.0;
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

double load_potential(const Model& model, const VecX& q) { return -model.constant_load().dot(q); }

double kinetic_energy(const Model& model, const VecX& v) {
  double t = 0.0;
  for (const CableData& c : model.cables()) {
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      const Index base = c.first_coordinate + 6 * j;
      for (int p = 0; p < 4; ++p)
        for (int s = 0; s < 4; ++s)
          t += 0.5 * c.mass[j](p, s) * v.segment<3>(base + 3 * p).dot(v.segment<3>(base + 3 * s));
    }
  }
  return t;
}

}  // namespace ancf
