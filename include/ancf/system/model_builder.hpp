// Collects cables, boundary conditions and loads; finalize() numbers the unknowns, builds the
// fixed sparsity pattern and the scatter slots and returns the immutable Model.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "ancf/system/model.hpp"

namespace ancf {

/// A node of a cable: cable index as returned by add_cable, node index (< 0 counts from the end).
struct NodeRef {
  Index cable = 0;
  Index node = 0;
};

class ModelBuilder {
 public:
  /// Add a cable whose stress-free reference is `reference` (its nodal coordinates define J₀ and
  /// κ₀). The initial configuration is the reference unless set_initial_configuration() is called.
  /// Returns the cable index. Throws ModelError on a non-physical section or geometry.
  Index add_cable(std::string name, const CableGeometry& reference, const CableSection& section);
  /// Start cable `cable` from other nodal coordinates (same node count) and velocities (optional).
  void set_initial_configuration(Index cable, const CableGeometry& current,
                                 const std::vector<NodeCoordinates>* velocities = nullptr);

  /// Uniform gravitational acceleration [m/s²] acting on all cables (consistent nodal loads).
  void set_gravity(const Vec3& g) { gravity_ = g; }
  /// Dead force [N] at a node.
  void add_node_force(NodeRef node, const Vec3& force);

  /// Pin the node position to `target` [m] (3 constraint rows).
  void pin(std::string name, NodeRef node, const Vec3& target);
  /// Keep the node slope parallel to `direction` (2 rows). Pin + align = clamp.
  void align_slope(std::string name, NodeRef node, const Vec3& direction);

  /// Number, build the pattern and slots. The builder is left empty.
  [[nodiscard]] Model finalize();

 private:
  struct PendingCable {
    std::string name;
    CableSection section;
    CableGeometry reference;
    CableGeometry initial;
    std::vector<NodeCoordinates> velocities;
  };
  struct PendingConstraint {
    std::string name;
    NodeRef node;
    LinearNodeConstraint law;
  };
  struct PendingForce {
    NodeRef node;
    Vec3 force;
  };
  const PendingCable& cable_at(Index cable, const char* what) const;
  Index resolve_node(NodeRef node, const char* what) const;

  std::vector<PendingCable> cables_;
  std::vector<PendingConstraint> constraints_;
  std::vector<PendingForce> forces_;
  Vec3 gravity_ = Vec3::Zero();
};

}  // namespace ancf
