// The model's own sparsity pattern of the iteration matrix and the scatter slot of every
// contribution, computed once in finalize(). Contact coupling blocks are not in it: they follow
// the pairs that are near (ContactPattern, DESIGN §5).
#include "ancf/system/model_builder.hpp"

namespace ancf {
namespace {

// Calls visit(row, col) for every entry a model contributes, in a fixed order; used twice: once
// to declare the pattern, once (in the same order) to collect the slots.
template <class Visit>
void visit_cable_block(Index base, Visit&& visit) {
  for (Index col = 0; col < 12; ++col)
    for (Index r = 0; r < 12; ++r) visit(base + r, base + col);
}

// The n×n block of rod element j (centreline block, the two twist angles and, quadratic, the
// interior twist), column-major.
template <class Visit>
void visit_rod_block(const CableData& c, Index j, Visit&& visit) {
  const int n = c.rod->element_coordinates();
  for (int col = 0; col < n; ++col)
    for (int r = 0; r < n; ++r) visit(c.rod_coordinate(j, r), c.rod_coordinate(j, col));
}

template <class Visit>
void visit_moment_block(const RodMomentData& d, Visit&& visit) {
  for (int col = 0; col < 4; ++col)
    for (int r = 0; r < 4; ++r) visit(d.coordinates[r], d.coordinates[col]);
}

template <class VisitPhiQ, class VisitGeometric>
void visit_row(Index row, const DotConstraintRow& c, VisitPhiQ&& visit_phi_q,
               VisitGeometric&& visit_geometric) {
  for (const AffineVector* a : {&c.u, &c.w})
    for (int k = 0; k < a->term_count; ++k) {
      for (int d = 0; d < 3; ++d) visit_phi_q(row, a->terms[k].block + d);
      for (int d = 0; d < 3; ++d) visit_phi_q(a->terms[k].block + d, row);
    }
  for (int k = 0; k < c.u.term_count; ++k)
    for (int m = 0; m < c.w.term_count; ++m) {
      const Index bk = c.u.terms[k].block, bm = c.w.terms[m].block;
      for (int d = 0; d < 3; ++d) visit_geometric(bk + d, bm + d);
      for (int d = 0; d < 3; ++d) visit_geometric(bm + d, bk + d);
    }
}

// A twist row (rod_twist_constraint.hpp): Φ_q at (row, c) and Φ_qᵀ at (c, row) per column, then
// the Hessian over all column pairs, column-major.
template <class VisitPhiQ, class VisitHessian>
void visit_twist_row(Index row, const RodTwistRowData& t, VisitPhiQ&& visit_phi_q,
                     VisitHessian&& visit_hessian) {
  std::array<Index, RodTwistRow::kMaxColumns> cols{};
  const int n = rod_twist_columns(t.row, cols);
  for (int k = 0; k < n; ++k) {
    visit_phi_q(row, cols[k]);
    visit_phi_q(cols[k], row);
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) visit_hessian(cols[i], cols[j]);
}

template <class Visit>
void visit_blocks(const BlockList& blocks, Visit&& visit) {
  for (int cb = 0; cb < blocks.count; ++cb)
    for (int cd = 0; cd < 3; ++cd)
      for (int rb = 0; rb < blocks.count; ++rb)
        for (int rd = 0; rd < 3; ++rd) visit(blocks.blocks[rb] + rd, blocks.blocks[cb] + cd);
}

template <class Elements>
void declare_forces(const Elements& elements, SparsityPattern& p) {
  for (const auto& e : elements) visit_blocks(e.blocks, [&](Index r, Index c) { p.add(r, c); });
}

template <class Elements>
void collect_forces(Elements& elements, const SparsityPattern& p) {
  for (auto& e : elements) {
    e.slots.clear();
    visit_blocks(e.blocks, [&](Index r, Index c) { e.slots.push_back(p.slot(r, c)); });
  }
}

}  // namespace

void ModelBuilder::build_pattern_and_slots(Model& m) {
  SparsityPattern& p = m.pattern_;
  p = SparsityPattern(m.system_size());
  auto add = [&](Index r, Index c) { p.add(r, c); };
  for (const CableData& c : m.cables_)
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j)
      if (c.rod)
        visit_rod_block(c, j, add);
      else
        visit_cable_block(c.first_coordinate + 6 * j, add);
  for (const RodMomentData& d : m.rod_moments_) visit_moment_block(d, add);
  for (const BodyData& b : m.bodies_) visit_cable_block(b.first_coordinate, add);  // 12×12 as well
  const Index dot_rows = static_cast<Index>(m.rows_.size());
  for (Index r = 0; r < dot_rows; ++r) visit_row(m.n_coordinates_ + r, m.rows_[r], add, add);
  for (std::size_t k = 0; k < m.twist_rows_.size(); ++k)
    visit_twist_row(m.n_coordinates_ + dot_rows + static_cast<Index>(k), m.twist_rows_[k], add,
                    add);
  declare_forces(m.springs_, p);
  // Point forces do not depend on q or v: no matrix entries.
  declare_forces(m.torques_, p);
  declare_forces(m.drives_, p);
  // Contact coupling blocks are not reserved here: ContactPattern adds those of the pairs that
  // are near (DESIGN §5).
  p.freeze();

  for (CableData& c : m.cables_) {
    m.element_slot_offset_.push_back(static_cast<Index>(m.element_slots_.size()));
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      std::array<Index, 144> s{};
      int k = 0;
      visit_cable_block(c.first_coordinate + 6 * j,
                        [&](Index r, Index col) { s[k++] = p.slot(r, col); });
      m.element_slots_.push_back(s);
    }
    if (!c.rod) continue;
    c.rod->slots.resize(c.elements.size());
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      int k = 0;
      visit_rod_block(c, j, [&](Index r, Index col) { c.rod->slots[j][k++] = p.slot(r, col); });
    }
  }
  for (RodMomentData& d : m.rod_moments_) {
    int k = 0;
    visit_moment_block(d, [&](Index r, Index col) { d.slots[k++] = p.slot(r, col); });
  }
  for (const BodyData& b : m.bodies_) {
    std::array<Index, 144> s{};
    int k = 0;
    visit_cable_block(b.first_coordinate, [&](Index r, Index col) { s[k++] = p.slot(r, col); });
    m.body_slots_.push_back(s);
  }
  m.row_slot_offset_.assign(1, 0);
  m.geometric_slot_offset_.assign(1, 0);
  for (Index r = 0; r < dot_rows; ++r) {
    visit_row(
        m.n_coordinates_ + r, m.rows_[r],
        [&](Index i, Index j) { m.row_slots_.push_back(p.slot(i, j)); },
        [&](Index i, Index j) { m.geometric_slots_.push_back(p.slot(i, j)); });
    m.row_slot_offset_.push_back(static_cast<Index>(m.row_slots_.size()));
    m.geometric_slot_offset_.push_back(static_cast<Index>(m.geometric_slots_.size()));
  }
  for (std::size_t k = 0; k < m.twist_rows_.size(); ++k) {
    RodTwistRowData& t = m.twist_rows_[k];
    std::array<Index, RodTwistRow::kMaxColumns> cols{};
    const int n = rod_twist_columns(t.row, cols);
    int a = 0, h = 0;
    visit_twist_row(
        m.n_coordinates_ + dot_rows + static_cast<Index>(k), t,
        [&](Index i, Index j) { t.phi_slots[a++] = p.slot(i, j); },
        [&](Index i, Index j) {
          t.hessian_slots[RodTwistRowData::kN * (h / n) + h % n] = p.slot(i, j);
          ++h;
        });
  }
  collect_forces(m.springs_, p);
  collect_forces(m.torques_, p);
  collect_forces(m.drives_, p);
}

}  // namespace ancf
