// The immutable model: numbering, element and body data, constraint rows, force elements, loads
// and the fixed sparse pattern with precomputed scatter slots. Built only by
// ModelBuilder::finalize(); read by the assembly functions (assembly.hpp).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "ancf/core/sparsity_pattern.hpp"
#include "ancf/physics/cable_element.hpp"
#include "ancf/physics/dot_constraint.hpp"
#include "ancf/physics/driven_frame.hpp"
#include "ancf/physics/force_elements.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"
#include "ancf/physics/rigid_body.hpp"
#include "ancf/physics/rod_twist_constraint.hpp"
#include "ancf/system/cable_geometry.hpp"
#include "ancf/system/contact_data.hpp"

namespace ancf {

/// Coordinates of a rod's twist block: N node angles and, with the quadratic twist, N − 1
/// interior ones.
[[nodiscard]] inline Index rod_twist_block_size(RodTwist twist, Index node_count) {
  return twist == RodTwist::quadratic ? 2 * node_count - 1 : node_count;
}

/// The twist part of a cable of the Kirchhoff rod kind (kirchhoff_rod_element.hpp, docs/rod.md).
/// Node k's twist angle α_k is coordinate twist_first + k; with the quadratic twist, element j's
/// interior twist β_j is interior_first + j = twist_first + N + j. The twist block
/// [twist_first, … + N (+ N − 1)) lies directly in front of the cable's centreline block.
struct RodData {
  RodSection section;
  Index twist_first = 0;
  Index interior_first = -1;  ///< −1: linear twist (RodTwist::linear), no β coordinates
  std::vector<RodElementReference> elements;
  std::vector<Mat3> twist_mass;         ///< per element, on (α_j, α_j+1, β_j)
  std::vector<Mat3> reference_frames;   ///< per node: material triad of the reference (α = 0)
  std::vector<double> reference_omega;  ///< per element: ω of the reference
  /// Per element, column-major over n×n, n = element_coordinates() (the first n² entries).
  std::vector<std::array<Index, kRodElementCoordinates * kRodElementCoordinates>> slots;
  /// Coordinates an element has in the model: 15, or 14 without β (linear twist).
  [[nodiscard]] int element_coordinates() const { return interior_first >= 0 ? 15 : 14; }
  [[nodiscard]] Index twist_block_size(Index node_count) const {
    return rod_twist_block_size(section.twist, node_count);
  }
};

/// One cable. Node k owns coordinates [first_coordinate + 6k, … + 6); element j owns the
/// contiguous block [first_coordinate + 6j, … + 12). A rod (rod present) is evaluated by the rod
/// kernel instead of the cable kernel; `elements` then serve only contact, loads and outputs.
struct CableData {
  std::string name;
  CableSection section;
  Index first_coordinate = 0;
  Index node_count = 0;
  std::vector<CableElementReference> elements;
  std::vector<Mat4> mass;  ///< scalar 4×4 consistent mass per element (⊗ I₃)
  std::optional<RodData> rod;

  /// Global index of local coordinate i of rod element j: 0…11 the centreline block, 12 and 13
  /// the twist angles of its nodes, 14 its interior twist β. Precondition: rod present, and
  /// i < rod->element_coordinates().
  [[nodiscard]] Index rod_coordinate(Index j, int i) const {
    if (i < 12) return first_coordinate + 6 * j + i;
    return i < 14 ? rod->twist_first + j + (i - 12) : rod->interior_first + j;
  }
  /// True if model coordinate i is one of this rod's twist coordinates (node angles α and
  /// interior twists β, dimensionless); false for a cable without twist.
  [[nodiscard]] bool is_twist_coordinate(Index i) const {
    return rod && i >= rod->twist_first && i < rod->twist_first + rod->twist_block_size(node_count);
  }
};

/// A moment fixed in space [N m] at a rod node (scaled by the load factor), with the slots of its
/// load stiffness on the node's (r_x, α) coordinates (4×4, column-major).
struct RodMomentData {
  Index cable = 0, node = 0;
  Vec3 moment;
  std::array<Index, 4> coordinates{};
  std::array<Index, 16> slots{};
};

/// A distributed moment per unit reference length [N m/m], fixed in space, on the elements
/// [first, first + count) of rod `cable` (kirchhoff_rod_distributed_moment.hpp), scaled by the
/// load factor. Its load stiffness uses the rod elements' blocks (no pattern entries of its own).
struct RodDistributedMomentData {
  Index cable = 0, first = 0, count = 0;
  Vec3 moment_per_length = Vec3::Zero();
};

/// A distributed dead force per unit reference length [N/m] on the elements [first, first + count)
/// of cable `cable`. Its consistent nodal loads are in constant_load(); kept for reports.
struct DistributedForceData {
  Index cable = 0, first = 0, count = 0;
  Vec3 force_per_length = Vec3::Zero();
};

/// A dead force [N] on node `node` of cable `cable`. Its load is in constant_load(); kept for
/// reports.
struct NodeForceData {
  Index cable = 0, node = 0;
  Vec3 force = Vec3::Zero();
};

/// A twist row of a rod node tied to a body, frame or space (rod_twist_constraint.hpp). The k-th
/// is multiplier rows().size() + k (after all dot rows). It is evaluated under the committed
/// reference triad of node `node` of cable `cable` (RodHistory).
struct RodTwistRowData {
  static constexpr int kN = RodTwistRow::kMaxColumns;
  RodTwistRow row;
  Index cable = 0, node = 0;
  std::array<Index, 2 * kN> phi_slots{};  ///< per column c: Φ_q at (row, c), then Φ_qᵀ at (c, row)
  std::array<Index, kN * kN> hessian_slots{};  ///< (c_i, c_j) at [kN j + i] for i, j < count
};

/// One rigid body: coordinates [first_coordinate, … + 12) = [r_O, a₁, a₂, a₃].
struct BodyData {
  std::string name;
  RigidBodyInertia inertia;
  Index first_coordinate = 0;
  Mat4 mass;  ///< natural_mass_matrix (⊗ I₃)
};

/// A named constraint: rows [first_row, first_row + row_count) of the system (multiplier indices),
/// row r of the model being rows()[r − coordinate_count()] or, past the dot rows, a twist row.
struct ConstraintData {
  std::string name;
  Index first_row = 0;
  int row_count = 0;
};

/// A force element with its blocks and value slots ((3·blocks)² entries, column-major; −1 = none).
template <class Element>
struct ForceElementData {
  std::string name;
  Element element;
  BlockList blocks;
  std::vector<Index> slots;
};

class ModelBuilder;

/// Unknowns y = [q; λ]: n coordinates followed by m multipliers.
class Model {
 public:
  [[nodiscard]] Index coordinate_count() const { return n_coordinates_; }
  [[nodiscard]] Index multiplier_count() const {
    return static_cast<Index>(rows_.size() + twist_rows_.size());
  }
  [[nodiscard]] Index system_size() const { return n_coordinates_ + multiplier_count(); }

  [[nodiscard]] const std::vector<CableData>& cables() const { return cables_; }
  [[nodiscard]] const std::vector<BodyData>& bodies() const { return bodies_; }
  [[nodiscard]] const std::vector<DrivenFrame>& frames() const { return frames_; }
  [[nodiscard]] const std::vector<ConstraintData>& constraints() const { return constraints_; }
  /// The bilinear rows: multipliers [0, rows().size()).
  [[nodiscard]] const std::vector<DotConstraintRow>& rows() const { return rows_; }
  /// The rod twist rows: multipliers [rows().size(), multiplier_count()).
  [[nodiscard]] const std::vector<RodTwistRowData>& twist_rows() const { return twist_rows_; }
  [[nodiscard]] const std::vector<ForceElementData<SpringDamper>>& spring_dampers() const {
    return springs_;
  }
  [[nodiscard]] const std::vector<ForceElementData<PointForce>>& point_forces() const {
    return point_forces_;
  }
  [[nodiscard]] const std::vector<ForceElementData<BodyTorque>>& body_torques() const {
    return torques_;
  }
  [[nodiscard]] const std::vector<ForceElementData<RevoluteDrive>>& drives() const {
    return drives_;
  }

  [[nodiscard]] const std::vector<RodMomentData>& rod_moments() const { return rod_moments_; }
  [[nodiscard]] const std::vector<RodDistributedMomentData>& rod_distributed_moments() const {
    return rod_distributed_moments_;
  }
  [[nodiscard]] const std::vector<NodeForceData>& node_forces() const { return node_forces_; }
  [[nodiscard]] const std::vector<DistributedForceData>& distributed_forces() const {
    return distributed_forces_;
  }
  /// True if some cable is a rod: the model keeps history (RodHistory, committed per step).
  [[nodiscard]] bool has_rods() const {
    for (const CableData& c : cables_)
      if (c.rod) return true;
    return false;
  }

  [[nodiscard]] const std::vector<ContactShapeData>& shapes() const { return shapes_; }
  [[nodiscard]] const std::vector<CableShapeContactData>& cable_shape_contacts() const {
    return cable_shape_contacts_;
  }
  [[nodiscard]] const std::vector<CableCableContactData>& cable_cable_contacts() const {
    return cable_cable_contacts_;
  }
  /// Contact pairs are numbered cable–shape pairs first, then cable–cable pairs.
  [[nodiscard]] Index contact_pair_count() const {
    return static_cast<Index>(cable_shape_contacts_.size() + cable_cable_contacts_.size());
  }
  [[nodiscard]] const std::string& contact_pair_name(Index pair) const;

  /// Constant generalised external force (gravity on cables and bodies, dead nodal loads) [N].
  [[nodiscard]] const VecX& constant_load() const { return constant_load_; }
  [[nodiscard]] const VecX& initial_coordinates() const { return q0_; }
  [[nodiscard]] const VecX& initial_velocities() const { return v0_; }

  /// Pattern of the (n + m)² matrix [w_q K + w_v D + w_a M, Φ_qᵀ; Φ_q, 0].
  [[nodiscard]] const SparsityPattern& pattern() const { return pattern_; }
  /// Value slots of element j of cable c, column-major over the 12×12 block.
  [[nodiscard]] const std::array<Index, 144>& element_slots(Index cable, Index element) const {
    return element_slots_[element_slot_offset_[cable] + element];
  }
  /// Value slots of body b's 12×12 block, column-major.
  [[nodiscard]] const std::array<Index, 144>& body_slots(Index body) const {
    return body_slots_[body];
  }

  /// Slots of row r (0-based among the multipliers): for each term of u then of w, 3 slots of
  /// Φ_q followed by 3 slots of Φ_qᵀ, starting at row_slot_offset(r).
  [[nodiscard]] std::span<const Index> row_slots(Index r) const {
    return {row_slots_.data() + row_slot_offset_[r], row_slots_.data() + row_slot_offset_[r + 1]};
  }
  /// Slots of ∂(Φ_qᵀλ)/∂q of row r: for each (k in u, m in w) pair, 3 slots (b_k+d, b_m+d) then 3
  /// slots (b_m+d, b_k+d), d = 0, 1, 2.
  [[nodiscard]] std::span<const Index> geometric_slots(Index r) const {
    return {geometric_slots_.data() + geometric_slot_offset_[r],
            geometric_slots_.data() + geometric_slot_offset_[r + 1]};
  }

  /// Global coordinate index of a node of a cable (node < 0 counts from the end: −1 = last).
  [[nodiscard]] Index node_coordinate(Index cable, Index node) const;
  /// "cable 'rope' node 3 r_x.y", "body 'pole' a2.z" or "constraint 'clamp' row 1".
  [[nodiscard]] std::string describe_row(Index row) const;
  /// Index of a constraint by name, or −1.
  [[nodiscard]] Index find_constraint(const std::string& name) const;

 private:
  friend class ModelBuilder;
  Index n_coordinates_ = 0;
  std::vector<CableData> cables_;
  std::vector<BodyData> bodies_;
  std::vector<DrivenFrame> frames_;
  std::vector<ConstraintData> constraints_;
  std::vector<DotConstraintRow> rows_;
  std::vector<RodTwistRowData> twist_rows_;
  std::vector<ForceElementData<SpringDamper>> springs_;
  std::vector<ForceElementData<PointForce>> point_forces_;
  std::vector<ForceElementData<BodyTorque>> torques_;
  std::vector<ForceElementData<RevoluteDrive>> drives_;
  std::vector<RodMomentData> rod_moments_;
  std::vector<RodDistributedMomentData> rod_distributed_moments_;
  std::vector<NodeForceData> node_forces_;
  std::vector<DistributedForceData> distributed_forces_;
  std::vector<ContactShapeData> shapes_;
  std::vector<CableShapeContactData> cable_shape_contacts_;
  std::vector<CableCableContactData> cable_cable_contacts_;
  VecX constant_load_;
  VecX q0_, v0_;
  SparsityPattern pattern_;
  std::vector<Index> element_slot_offset_;
  std::vector<std::array<Index, 144>> element_slots_;
  std::vector<std::array<Index, 144>> body_slots_;
  std::vector<Index> row_slots_, row_slot_offset_;
  std::vector<Index> geometric_slots_, geometric_slot_offset_;
};

}  // namespace ancf
