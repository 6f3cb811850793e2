// The assembled iteration matrix against central differences of the assembled residual: one
// check for every test that verifies a model's whole matrix (elements, constraints, loads).
#pragma once

#include "ancf/system/assembly.hpp"
#include "dense_matrix.hpp"
#include "fd_check.hpp"

namespace ancf::testing {

/// R(q + x, v + (w_v/w_q) x, a + (w_a/w_q) x, λ + x_λ) differentiated in x at x = 0 is
/// w_q K + w_v D + w_a M with the constraint blocks: compared entry by entry with the matrix
/// assemble_iteration_matrix gives at `s` (tolerances from fd_check's error estimate).
inline fdcheck::Result check_iteration_matrix(const Model& m, const SystemState& s,
                                              const IterationWeights& w, Workspace& ws) {
  VecX values(m.pattern().nonzeros());
  assemble_iteration_matrix(m, s, w, ws, as_span(values));
  const MatX jac = dense(m.pattern(), values);
  const Index n = m.coordinate_count(), nn = m.system_size();
  const auto residual = [&](const fdcheck::Vec& x) {
    SystemState t = s;
    t.q += x.head(n);
    t.v += (w.w_v / w.w_q) * x.head(n);
    t.a += (w.w_a / w.w_q) * x.head(n);
    t.lambda += x.tail(nn - n);
    VecX r(nn);
    assemble_residual(m, t, w.load_factor, ws, as_span(r));
    return fdcheck::Vec(r);
  };
  return fdcheck::check_jacobian(residual, fdcheck::Vec::Zero(nn), jac);
}

}  // namespace ancf::testing
