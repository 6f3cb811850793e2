// The immutable model: numbering, element data, constraints, loads and the fixed sparse pattern.
// Built only by ModelBuilder::finalize(); read by the assembly functions.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/physics/cable_element.hpp"
#include "ancf/physics/linear_node_constraint.hpp"
#include "ancf/system/cable_geometry.hpp"

namespace ancf {

/// One cable: its section, its first global coordinate and its elements' reference data.
/// Node k of the cable owns coordinates [first_coordinate + 6k, first_coordinate + 6k + 6);
/// element j therefore owns the contiguous block [first_coordinate + 6j, … + 12).
struct CableData {
  std::string name;
  CableSection section;
  Index first_coordinate = 0;
  Index node_count = 0;
  std::vector<CableElementReference> elements;
  std::vector<Mat4> mass;  ///< scalar 4×4 consistent mass per element (⊗ I₃)
};

/// A constraint on one node, with its multiplier rows and precomputed matrix slots.
struct NodeConstraintData {
  std::string name;
  LinearNodeConstraint law;
  Index node_coordinate = 0;  ///< global index of the node's first coordinate
  Index first_row = 0;        ///< global index of its first multiplier (≥ coordinate count)
  std::array<std::array<Index, 6>, 3> slot_phi_q{};   ///< (row, coord) → value slot of Φ_q
  std::array<std::array<Index, 6>, 3> slot_phi_qt{};  ///< (coord, row) → value slot of Φ_qᵀ
};

class ModelBuilder;

/// Unknowns y = [q; λ]: n coordinates followed by m multipliers.
class Model {
 public:
  [[nodiscard]] Index coordinate_count() const { return n_coordinates_; }
  [[nodiscard]] Index multiplier_count() const { return n_multipliers_; }
  [[nodiscard]] Index system_size() const { return n_coordinates_ + n_multipliers_; }

  [[nodiscard]] const std::vector<CableData>& cables() const { return cables_; }
  [[nodiscard]] const std::vector<NodeConstraintData>& constraints() const { return constraints_; }
  /// Constant generalised external force (gravity and dead nodal loads) [N].
  [[nodiscard]] const VecX& constant_load() const { return constant_load_; }
  [[nodiscard]] const VecX& initial_coordinates() const { return q0_; }
  [[nodiscard]] const VecX& initial_velocities() const { return v0_; }

  /// Pattern of the (n + m)² matrix [w_q K + w_v D + w_a M, Φ_qᵀ; Φ_q, 0].
  [[nodiscard]] const SparsityPattern& pattern() const { return pattern_; }
  /// Value slots of element j of cable c, column-major over the 12×12 block.
  [[nodiscard]] const std::array<Index, 144>& element_slots(Index cable, Index element) const {
    return element_slots_[element_slot_offset_[cable] + element];
  }

  /// Global coordinate index of a node of a cable (node < 0 counts from the end: −1 = last).
  [[nodiscard]] Index node_coordinate(Index cable, Index node) const;
  /// "cable 'rope' node 3 r_x.y" or "constraint 'clamp' row 1" for a row of the system.
  [[nodiscard]] std::string describe_row(Index row) const;

 private:
  friend class ModelBuilder;
  Index n_coordinates_ = 0;
  Index n_multipliers_ = 0;
  std::vector<CableData> cables_;
  std::vector<NodeConstraintData> constraints_;
  VecX constant_load_;
  VecX q0_, v0_;
  SparsityPattern pattern_;
  std::vector<Index> element_slot_offset_;
  std::vector<std::array<Index, 144>> element_slots_;
};

}  // namespace ancf
