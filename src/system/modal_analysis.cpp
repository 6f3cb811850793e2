#include "ancf/system/modal_analysis.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace ancf {

namespace {

MatX dense_iteration_matrix(const Model& model, const SystemState& state,
                            const IterationWeights& weights, Workspace& ws) {
  const SparsityPattern& p = model.pattern();
  VecX values(p.nonzeros());
  assemble_iteration_matrix(model, state, weights, ws, as_span(values));
  MatX m = MatX::Zero(p.size(), p.size());
  for (Index col = 0; col < p.size(); ++col)
    for (Index k = p.column_start()[col]; k < p.column_start()[col + 1]; ++k)
      m(p.row_index()[k], col) = values[k];
  return m;
}

// Coordinates whose position inside their 3-vector block equals `component` (all if −1).
// Cables and bodies are sequences of 3-vectors starting at their first coordinate.
std::vector<Index> selected_coordinates(const Model& model, int component) {
  std::vector<bool> keep(static_cast<std::size_t>(model.coordinate_count()), component < 0);
  if (component >= 0) {
    auto mark = [&](Index first, Index count) {
      for (Index i = first + component; i < first + count; i += 3)
        keep[static_cast<std::size_t>(i)] = true;
    };
    for (const CableData& c : model.cables()) mark(c.first_coordinate, 6 * c.node_count);
    for (const BodyData& b : model.bodies()) mark(b.first_coordinate, 12);
  }
  std::vector<Index> out;
  for (Index i = 0; i < model.coordinate_count(); ++i)
    if (keep[static_cast<std::size_t>(i)]) out.push_back(i);
  return out;
}

// Largest |entry| of `m` coupling a selected row/column with an unselected one, relative to
// the largest |entry| of m. An empty m (no constraints) couples nothing; Eigen's maxCoeff of an
// empty matrix is undefined, so it is never asked.
void require_decoupled(const MatX& m, const std::vector<bool>& row_kept,
                       const std::vector<bool>& col_kept, double tolerance, const char* what) {
  if (m.size() == 0) return;
  const double scale = m.cwiseAbs().maxCoeff();
  for (Index c = 0; c < m.cols(); ++c)
    for (Index r = 0; r < m.rows(); ++r)
      if (row_kept[static_cast<std::size_t>(r)] != col_kept[static_cast<std::size_t>(c)] &&
          std::abs(m(r, c)) > tolerance * scale)
        throw std::invalid_argument(std::string("natural_modes: the chosen component is coupled "
                                                "to the others in ") +
                                    what);
}

/// A model that cannot be evaluated at the state (sizes near the double range, say) gives
/// non-finite matrices, on which the eigen-solver would fail without saying where.
void require_finite(const Model& model, const MatX& a, const char* what) {
  for (Index j = 0; j < a.cols(); ++j)
    for (Index i = 0; i < a.rows(); ++i)
      if (!std::isfinite(a(i, j)))
        throw std::domain_error(std::string("natural_modes: the ") + what +
                                " matrix at the state is not finite in row " +
                                model.describe_row(i) + ", column " + model.describe_row(j));
}

}  // namespace

double NaturalModes::omega(Index i) const {
  const double w2 = omega_squared[i];
  return w2 >= 0.0 ? std::sqrt(w2) : std::numeric_limits<double>::quiet_NaN();
}

NaturalModes natural_modes(const Model& model, const SystemState& equilibrium,
                           const ModalAnalysisOptions& options) {
  SystemState s = equilibrium;
  s.v.setZero();
  s.a.setZero();
  Workspace ws(model);
  const Index n = model.coordinate_count(), m = model.multiplier_count();
  const MatX k_matrix = dense_iteration_matrix(model, s, {1.0, 0.0, 0.0}, ws);
  const MatX m_matrix = dense_iteration_matrix(model, s, {0.0, 0.0, 1.0}, ws);
  require_finite(model, k_matrix, "stiffness");
  require_finite(model, m_matrix, "mass");
  const MatX k_full = k_matrix.topLeftCorner(n, n), m_full = m_matrix.topLeftCorner(n, n);
  const MatX phi_q = k_matrix.bottomLeftCorner(m, n);

  const std::vector<Index> dofs = selected_coordinates(model, options.component);
  std::vector<bool> kept(static_cast<std::size_t>(n), false);
  for (const Index i : dofs) kept[static_cast<std::size_t>(i)] = true;
  // Constraint rows acting on the selected coordinates; such a row must not also act on others.
  std::vector<Index> rows;
  std::vector<bool> row_kept(static_cast<std::size_t>(m), false);
  for (Index r = 0; r < m; ++r) {
    bool touches = false;
    for (const Index i : dofs) touches = touches || phi_q(r, i) != 0.0;
    if (touches) rows.push_back(r), row_kept[static_cast<std::size_t>(r)] = true;
  }
  if (options.component >= 0) {
    require_decoupled(k_full, kept, kept, options.coupling_tolerance, "K");
    require_decoupled(m_full, kept, kept, options.coupling_tolerance, "M");
    require_decoupled(phi_q, row_kept, kept, options.coupling_tolerance, "the constraint Jacobian");
  }

  const Index d = static_cast<Index>(dofs.size()), r_count = static_cast<Index>(rows.size());
  MatX k(d, d), mass(d, d), g(r_count, d);
  for (Index a = 0; a < d; ++a) {
    for (Index b = 0; b < d; ++b)
      k(a, b) = k_full(dofs[a], dofs[b]), mass(a, b) = m_full(dofs[a], dofs[b]);
    for (Index r = 0; r < r_count; ++r) g(r, a) = phi_q(rows[r], dofs[a]);
  }
  NaturalModes out;
  out.selected_coordinates = d;
  const double k_scale = k.size() > 0 ? k.cwiseAbs().maxCoeff() : 0.0;
  out.asymmetry = k_scale > 0.0 ? (k - k.transpose()).cwiseAbs().maxCoeff() / k_scale : 0.0;

  // Orthonormal null-space basis: the last d − rank columns of Q in Φ_qᵀ P = Q R.
  MatX z = MatX::Identity(d, d);
  if (r_count > 0) {
    Eigen::ColPivHouseholderQR<MatX> qr(g.transpose());
    out.constraint_rank = qr.rank();
    const MatX q = qr.householderQ() * MatX::Identity(d, d);
    z = q.rightCols(d - out.constraint_rank);
  }
  const MatX k_reduced = z.transpose() * (0.5 * (k + k.transpose())) * z;
  const MatX m_reduced = z.transpose() * mass * z;
  const MatX k_sym = 0.5 * (k_reduced + k_reduced.transpose());
  const MatX m_sym = 0.5 * (m_reduced + m_reduced.transpose());
  MatX local;  // d × modes, M-orthonormal
  // The lowest frequencies are wanted. Solved as K φ = ω² M φ (Cholesky of M), their absolute
  // error is ~ ε‖K‖, i.e. a relative error ~ ε·ω²_max/ω²₁ ∝ N⁴ for bending. When K is positive
  // definite the inverted pencil M φ = μ K φ, μ = 1/ω², is solved instead, whose largest μ are
  // the lowest modes. Measured on the clamped beam (mesh-convergence study): the round-off floor
  // of ω₁ at 64 elements fell from 1e-8 to 7e-10 relative; a floor growing with N remains
  // (6e-9 at 128 elements).
  const Eigen::LLT<MatX> k_cholesky(k_sym);
  if (k_cholesky.info() == Eigen::Success) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> eig(m_sym, k_sym);
    if (eig.info() != Eigen::Success)
      throw std::runtime_error("natural_modes: eigen-solver failed");
    const Index count = eig.eigenvalues().size();
    out.omega_squared.resize(count);
    local.resize(k_sym.rows(), count);   // reduced coordinates (d − rank), mapped back by z below
    for (Index i = 0; i < count; ++i) {  // ascending ω² = descending μ; φ = x/√μ (xᵀKx = 1)
      const double mu = eig.eigenvalues()[count - 1 - i];
      out.omega_squared[i] = 1.0 / mu;
      local.col(i) = eig.eigenvectors().col(count - 1 - i) / std::sqrt(mu);
    }
  } else {
    const Eigen::GeneralizedSelfAdjointEigenSolver<MatX> eig(k_sym, m_sym);
    if (eig.info() != Eigen::Success)
      throw std::runtime_error("natural_modes: eigen-solver failed");
    out.omega_squared = eig.eigenvalues();
    local = eig.eigenvectors();
  }
  local = z * local;
  out.shapes = MatX::Zero(n, local.cols());
  for (Index a = 0; a < d; ++a) out.shapes.row(dofs[a]) = local.row(a);
  return out;
}

NaturalModes natural_modes_at_initial_equilibrium(const Model& model,
                                                  const ModalAnalysisOptions& options,
                                                  double equilibrium_tolerance) {
  SystemState s = SystemState::initial(model);
  s.v.setZero();
  s.a.setZero();
  s.lambda.setZero();
  Workspace ws(model);
  const Index n = model.coordinate_count(), m = model.multiplier_count();
  VecX r(model.system_size());
  assemble_residual(model, s, 1.0, ws, as_span(r));
  const VecX force = r.head(n);  // F − Q at λ = 0
  const MatX k_matrix = dense_iteration_matrix(model, s, {1.0, 0.0, 0.0}, ws);
  // Force scale: the larger of the load and the force of a deformation of the size of q (so a
  // stress-free state, F − Q at round-off, counts as balanced).
  const double scale =
      std::max(force.lpNorm<Eigen::Infinity>(), k_matrix.topLeftCorner(n, n).cwiseAbs().maxCoeff() *
                                                    std::max(1.0, s.q.lpNorm<Eigen::Infinity>()));
  VecX remaining = force;
  if (m > 0) {
    const MatX phi_q_t = k_matrix.topRightCorner(n, m);  // Φ_qᵀ
    s.lambda = phi_q_t.colPivHouseholderQr().solve(-force);
    remaining += phi_q_t * s.lambda;
  }
  if (remaining.lpNorm<Eigen::Infinity>() > equilibrium_tolerance * scale)
    throw std::invalid_argument(
        "natural_modes_at_initial_equilibrium: the initial configuration is not an equilibrium "
        "(unbalanced force " +
        std::to_string(remaining.lpNorm<Eigen::Infinity>()) + ")");
  return natural_modes(model, s, options);
}

}  // namespace ancf
