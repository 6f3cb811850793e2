// Detection of redundant constraints at finalize(): rows of Φ_q (at the initial configuration and
// t = 0) that are linear combinations of earlier rows. A redundant set makes the iteration matrix
// singular, so it must be reported by name before any solve (DESIGN §2).
#include <Eigen/Dense>
#include <map>
#include <set>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/system/model_builder.hpp"

namespace ancf {
namespace {

// Rows are normalised to unit length; a row whose component orthogonal to the span of the
// accepted rows is below this is dependent. Independent rows of a well-posed scene are O(1) apart
// (angles between joint axes, unit directions), while a true dependency leaves round-off
// (≈ 1e-15); √ε separates the two with a wide margin on either side.
constexpr double kDependencyTolerance = 1.5e-8;

}  // namespace

void ModelBuilder::check_redundancy(const Model& m) {
  const Index rows = m.multiplier_count();
  if (rows == 0) return;
  std::vector<FrameKinematics> frames;
  for (const DrivenFrame& f : m.frames_) frames.push_back(f.at(0.0));
  const VecX& q = m.q0_;
  // Columns each row touches (3 per block of each affine term).
  // Twist rows (after the dot rows) at the reference history: their values per column.
  const Index dot_rows = static_cast<Index>(m.rows_.size());
  std::vector<RodTwistRowValues> twist(m.twist_rows_.size());
  for (std::size_t k = 0; k < twist.size(); ++k) {
    const RodTwistRowData& t = m.twist_rows_[k];
    evaluate(t.row, m.cables_[t.cable].rod->reference_frames[t.node], as_span(q), {}, frames,
             twist[k]);
  }
  std::vector<std::vector<Index>> row_columns(rows);
  for (Index i = 0; i < dot_rows; ++i) {
    const DotConstraintRow& r = m.rows_[i];
    for (const AffineVector* a : {&r.u, &r.w})
      for (int k = 0; k < a->term_count; ++k)
        for (int d = 0; d < 3; ++d) row_columns[i].push_back(a->terms[k].block + d);
  }
  for (std::size_t k = 0; k < twist.size(); ++k)
    for (int c = 0; c < twist[k].column_count; ++c)
      row_columns[dot_rows + static_cast<Index>(k)].push_back(twist[k].columns[c]);

  // Rows in groups that share no column (connected components of the row–column incidence,
  // union–find over columns): Φ_q is block diagonal over the groups, so a row is a combination
  // of earlier rows iff it is one of the earlier rows of its own group, and each group is checked
  // on its own. Without the split the dense Gram–Schmidt below costs O(rows² × columns) for the
  // whole model: K independent pinned cables took O(K³) (1000 cables: minutes).
  std::map<Index, Index> parent;  // column → parent column
  auto find = [&](Index c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  for (const auto& cols : row_columns)
    for (const Index c : cols) parent.emplace(c, c);
  for (const auto& cols : row_columns)
    for (std::size_t k = 1; k < cols.size(); ++k) parent[find(cols[k])] = find(cols[0]);
  std::map<Index, std::vector<Index>> groups;  // root column → rows in order (zero rows: own group)
  for (Index i = 0; i < rows; ++i)
    groups[row_columns[i].empty() ? -1 - i : find(row_columns[i][0])].push_back(i);

  auto owner = [&](Index row) -> const ConstraintData& {
    for (const ConstraintData& c : m.constraints_)
      if (m.n_coordinates_ + row >= c.first_row &&
          m.n_coordinates_ + row < c.first_row + c.row_count)
        return c;
    return m.constraints_.front();
  };

  std::map<Index, std::string> findings;  // row → report line, so the report is in row order
  for (const auto& [root, group] : groups) {
    // Dense Φ_q of the group over the columns it touches.
    std::map<Index, Index> column;
    for (const Index i : group)
      for (const Index c : row_columns[i]) column.emplace(c, 0);
    Index next = 0;
    for (auto& [global, local] : column) local = next++;
    const Index count = static_cast<Index>(group.size());
    MatX jac = MatX::Zero(count, next);
    for (Index g = 0; g < count; ++g) {
      if (group[g] >= dot_rows) {
        const RodTwistRowValues& t = twist[group[g] - dot_rows];
        for (int c = 0; c < t.column_count; ++c) jac(g, column[t.columns[c]]) += t.phi_q[c];
        continue;
      }
      const DotConstraintRow& r = m.rows_[group[g]];
      const AffineVectorState u = evaluate(r.u, as_span(q), {}, frames);
      const AffineVectorState w = evaluate(r.w, as_span(q), {}, frames);
      std::array<Vec3, AffineVector::kMaxTerms> gu, gw;
      gradient_blocks(r, u, w, false, gu, gw);
      for (int k = 0; k < r.u.term_count; ++k)
        for (int d = 0; d < 3; ++d) jac(g, column[r.u.terms[k].block + d]) += gu[k][d];
      for (int k = 0; k < r.w.term_count; ++k)
        for (int d = 0; d < 3; ++d) jac(g, column[r.w.terms[k].block + d]) += gw[k][d];
    }

    // Gram–Schmidt (twice, for stability) over the rows in order; accepted rows form the basis.
    std::vector<Index> accepted;
    MatX basis(next, 0);
    for (Index g = 0; g < count; ++g) {
      const double norm = jac.row(g).norm();
      VecX r = jac.row(g).transpose() / (norm > 0.0 ? norm : 1.0);
      for (int pass = 0; pass < 2; ++pass)
        if (basis.cols() > 0) r -= basis * (basis.transpose() * r);
      if (norm > 0.0 && r.norm() > kDependencyTolerance) {
        basis.conservativeResize(Eigen::NoChange, basis.cols() + 1);
        basis.col(basis.cols() - 1) = r / r.norm();
        accepted.push_back(g);
        continue;
      }
      // Which accepted rows does it depend on? Least squares on the accepted rows.
      std::set<std::string> partners;
      if (!accepted.empty()) {
        MatX a(next, static_cast<Index>(accepted.size()));
        for (std::size_t k = 0; k < accepted.size(); ++k)
          a.col(k) = jac.row(accepted[k]).transpose();
        const VecX coef = a.colPivHouseholderQr().solve(jac.row(g).transpose());
        for (std::size_t k = 0; k < accepted.size(); ++k)
          if (std::abs(coef[k]) > 1e-8 * coef.cwiseAbs().maxCoeff())
            partners.insert(owner(group[accepted[k]]).name);
      }
      const Index i = group[g];
      const ConstraintData& c = owner(i);
      std::string line =
          "\n  constraint '" + c.name + "' row " +
          std::to_string(m.n_coordinates_ + i - c.first_row) +
          (norm == 0.0 ? " has a zero Jacobian row" : " is a combination of rows of:");
      for (const std::string& p : partners) line += " '" + p + "'";
      findings[i] = line;
    }
  }
  std::string report;
  for (const auto& [row, line] : findings) report += line;
  if (!report.empty())
    throw ModelError(
        "redundant constraints at the initial configuration (remove or replace them):" + report);
}

}  // namespace ancf
