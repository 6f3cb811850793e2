#include "ancf/system/model_builder.hpp"

#include <cmath>
#include <string>

#include "ancf/core/error.hpp"
#include "ancf/physics/hermite_shape.hpp"

namespace ancf {
namespace {

void validate_section(const std::string& cable, const CableSection& s) {
  auto fail = [&](const std::string& what) { throw ModelError("cable '" + cable + "': " + what); };
  if (!(s.axial_stiffness > 0.0) || !std::isfinite(s.axial_stiffness))
    fail("axial stiffness EA must be > 0 N, got " + std::to_string(s.axial_stiffness));
  if (!(s.bending_stiffness >= 0.0) || !std::isfinite(s.bending_stiffness))
    fail("bending stiffness EI must be >= 0 N m^2, got " + std::to_string(s.bending_stiffness));
  if (!(s.mass_per_length > 0.0) || !std::isfinite(s.mass_per_length))
    fail("mass per length rhoA must be > 0 kg/m, got " + std::to_string(s.mass_per_length));
  if (!(s.axial_damping >= 0.0) || !(s.bending_damping >= 0.0))
    fail("damping coefficients must be >= 0");
  if (!std::isfinite(s.prestrain) || s.prestrain <= -1.0)
    fail("prestrain must be finite and > -1, got " + std::to_string(s.prestrain));
}

void validate_geometry(const std::string& cable, const CableGeometry& g) {
  if (g.element_count() < 1 || g.node_count() != g.element_count() + 1)
    throw ModelError("cable '" + cable + "': needs >= 1 element and one more node than elements");
  for (Index j = 0; j < g.element_count(); ++j) {
    if (!(g.element_lengths[j] > 0.0))
      throw ModelError("cable '" + cable + "': element " + std::to_string(j) +
                       " has non-positive length " + std::to_string(g.element_lengths[j]));
  }
  for (Index k = 0; k < g.node_count(); ++k) {
    if (!g.nodes[k].allFinite())
      throw ModelError("cable '" + cable + "': node " + std::to_string(k) + " has non-finite coordinates");
  }
}

}  // namespace

Index ModelBuilder::add_cable(std::string name, const CableGeometry& reference,
                              const CableSection& section) {
  for (const auto& c : cables_)
    if (c.name == name) throw ModelError("cable name '" + name + "' is used twice");
  validate_section(name, section);
  validate_geometry(name, reference);
  cables_.push_back({std::move(name), section, reference, reference,
                     std::vector<NodeCoordinates>(reference.nodes.size(), NodeCoordinates::Zero())});
  return static_cast<Index>(cables_.size()) - 1;
}

const ModelBuilder::PendingCable& ModelBuilder::cable_at(Index cable, const char* what) const {
  if (cable < 0 || cable >= static_cast<Index>(cables_.size()))
    throw ModelError(std::string(what) + ": no cable with index " + std::to_string(cable));
  return cables_[cable];
}

void ModelBuilder::set_initial_configuration(Index cable, const CableGeometry& current,
                                             const std::vector<NodeCoordinates>* velocities) {
  cable_at(cable, "set_initial_configuration");  // validates the index
  PendingCable& c = cables_[cable];
  if (current.node_count() != c.reference.node_count())
    throw ModelError("cable '" + c.name + "': initial configuration has " +
                     std::to_string(current.node_count()) + " nodes, reference has " +
                     std::to_string(c.reference.node_count()));
  validate_geometry(c.name, current);
  c.initial = current;
  if (velocities) {
    if (velocities->size() != current.nodes.size())
      throw ModelError("cable '" + c.name + "': initial velocity count differs from node count");
    c.velocities = *velocities;
  }
}

Index ModelBuilder::resolve_node(NodeRef node, const char* what) const {
  const PendingCable& c = cable_at(node.cable, what);
  const Index n = c.reference.node_count();
  const Index k = node.node < 0 ? n + node.node : node.node;
  if (k < 0 || k >= n)
    throw ModelError(std::string(what) + ": cable '" + c.name + "' has no node " +
                     std::to_string(node.node) + " (it has " + std::to_string(n) + ")");
  return k;
}

void ModelBuilder::add_node_force(NodeRef node, const Vec3& force) {
  node.node = resolve_node(node, "add_node_force");
  if (!force.allFinite()) throw ModelError("add_node_force: non-finite force");
  forces_.push_back({node, force});
}

void ModelBuilder::pin(std::string name, NodeRef node, const Vec3& target) {
  node.node = resolve_node(node, "pin");
  constraints_.push_back({std::move(name), node, pin_to_ground(target)});
}

void ModelBuilder::align_slope(std::string name, NodeRef node, const Vec3& direction) {
  node.node = resolve_node(node, "align_slope");
  constraints_.push_back({std::move(name), node, slope_direction_to_ground(direction)});
}

Model ModelBuilder::finalize() {
  Model m;
  // Numbering: cables one after another, 6 coordinates per node.
  Index next = 0;
  for (const PendingCable& pc : cables_) {
    CableData c;
    c.name = pc.name;
    c.section = pc.section;
    c.first_coordinate = next;
    c.node_count = pc.reference.node_count();
    for (Index j = 0; j < pc.reference.element_count(); ++j) {
      const double l = pc.reference.element_lengths[j];
      c.elements.push_back(CableElementReference::from_reference(
          pc.reference.element_coordinates(j), l, pc.section.strain));
      c.mass.push_back(hermite::mass_matrix(pc.section.mass_per_length, l));
    }
    next += 6 * c.node_count;
    m.cables_.push_back(std::move(c));
  }
  m.n_coordinates_ = next;

  m.q0_ = VecX::Zero(next);
  m.v0_ = VecX::Zero(next);
  m.constant_load_ = VecX::Zero(next);
  for (std::size_t ci = 0; ci < cables_.size(); ++ci) {
    const PendingCable& pc = cables_[ci];
    const CableData& c = m.cables_[ci];
    for (Index k = 0; k < c.node_count; ++k) {
      m.q0_.segment<6>(c.first_coordinate + 6 * k) = pc.initial.nodes[k];
      m.v0_.segment<6>(c.first_coordinate + 6 * k) = pc.velocities[k];
    }
    // Consistent gravity load ρA ∫ Sᵀ g dx per element.
    if (gravity_.squaredNorm() > 0.0) {
      for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
        const Vec4 wts = hermite::load_weights(c.elements[j].length);
        for (int s = 0; s < 4; ++s)
          m.constant_load_.segment<3>(c.first_coordinate + 6 * j + 3 * s) +=
              c.section.mass_per_length * wts[s] * gravity_;
      }
    }
  }
  for (const PendingForce& f : forces_)
    m.constant_load_.segment<3>(m.cables_[f.node.cable].first_coordinate + 6 * f.node.node) += f.force;

  Index row = next;
  for (const PendingConstraint& pc : constraints_) {
    NodeConstraintData d;
    d.name = pc.name;
    d.law = pc.law;
    d.node_coordinate = m.cables_[pc.node.cable].first_coordinate + 6 * pc.node.node;
    d.first_row = row;
    row += pc.law.rows;
    m.constraints_.push_back(std::move(d));
  }
  m.n_multipliers_ = row - next;

  // Pattern: element blocks, then Φ_q and Φ_qᵀ entries of every non-zero of G.
  m.pattern_ = SparsityPattern(row);
  for (const CableData& c : m.cables_) {
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      const Index base = c.first_coordinate + 6 * j;
      for (Index col = 0; col < 12; ++col)
        for (Index r = 0; r < 12; ++r) m.pattern_.add(base + r, base + col);
    }
  }
  for (const NodeConstraintData& d : m.constraints_) {
    for (int r = 0; r < d.law.rows; ++r)
      for (int k = 0; k < 6; ++k)
        if (d.law.g(r, k) != 0.0) {
          m.pattern_.add(d.first_row + r, d.node_coordinate + k);
          m.pattern_.add(d.node_coordinate + k, d.first_row + r);
        }
  }
  m.pattern_.freeze();

  for (const CableData& c : m.cables_) {
    m.element_slot_offset_.push_back(static_cast<Index>(m.element_slots_.size()));
    for (Index j = 0; j < static_cast<Index>(c.elements.size()); ++j) {
      const Index base = c.first_coordinate + 6 * j;
      std::array<Index, 144> s{};
      for (Index col = 0; col < 12; ++col)
        for (Index r = 0; r < 12; ++r) s[12 * col + r] = m.pattern_.slot(base + r, base + col);
      m.element_slots_.push_back(s);
    }
  }
  for (NodeConstraintData& d : m.constraints_) {
    for (int r = 0; r < d.law.rows; ++r)
      for (int k = 0; k < 6; ++k) {
        d.slot_phi_q[r][k] = -1;
        d.slot_phi_qt[r][k] = -1;
        if (d.law.g(r, k) != 0.0) {
          d.slot_phi_q[r][k] = m.pattern_.slot(d.first_row + r, d.node_coordinate + k);
          d.slot_phi_qt[r][k] = m.pattern_.slot(d.node_coordinate + k, d.first_row + r);
        }
      }
  }
  *this = ModelBuilder{};
  return m;
}

}  // namespace ancf
