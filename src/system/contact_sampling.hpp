// Internal to the system layer: the broad and narrow phase over every declared contact pair
// (DESIGN §5). One loop serves the residual, the iteration matrix and the outputs; each passes a
// ContactSink that consumes the samples.
#pragma once

#include "ancf/physics/cable_contact.hpp"
#include "ancf/system/assembly.hpp"

namespace ancf::detail {

/// Where a sample's Q and Jacobian go: the 12 coordinates of the cable element (side a) and the
/// 12 of the body or cable-b element (side b; first_b = −1 when the other side is ground or a
/// driven frame), and the value slots of the four 12×12 blocks (column-major; side-b blocks are
/// nullptr when first_b = −1; the coupling blocks ab, ba are nullptr also when the current
/// contact pattern does not hold them, ContactPattern).
struct ContactSampleBlocks {
  Index pair = 0;
  Index cable = 0;  ///< cable of side a
  Index first_a = 0, first_b = -1;
  const BlockSlots* aa = nullptr;
  const BlockSlots* ab = nullptr;
  const BlockSlots* ba = nullptr;
  const BlockSlots* bb = nullptr;
};

class ContactSink {
 public:
  virtual void add(const ContactSampleResult& sample, const ContactSampleBlocks& blocks) = 0;

 protected:
  ~ContactSink() = default;
};

struct ContactVisit {
  bool jacobians = false;  ///< evaluate ∂Q/∂P and ∂Q/∂V
  /// false: broad phase on, only active samples reach the sink (residual, matrix).
  /// true: no broad phase, every sample reaches the sink, active or not (outputs: exact min gap).
  bool all_samples = false;
};

/// Pose of a shape's owner at `state`: ground (identity), driven frame (prescribed) or rigid body
/// (read from its natural coordinates).
ShapeOwnerPose owner_pose(const ContactShapeData& s, const SystemState& state,
                          std::span<const FrameKinematics> frames);

/// Broad-phase test of a (radius-inflated) element box against a placed shape.
struct ShapeBroadPhase {
  const ContactShape& shape;
  const ShapeOwnerPose& pose;
  Aabb box;  ///< global box of a sphere or cylinder (unused for a plane)
  ShapeBroadPhase(const ContactShape& s, const ShapeOwnerPose& p);
  [[nodiscard]] bool may_touch(const Aabb& element_box) const;
};

/// Refresh the whole-cable boxes and the element boxes of the cables in contact pairs (one pass).
void refresh_cable_boxes(const Model& model, const SystemState& state, Workspace& ws);
/// Element boxes of cable c: those of the last refresh_cable_boxes, which must have been at `state`
/// (computed here only if no refresh has run yet).
const std::vector<Aabb>& element_boxes_of(const Model& model, const SystemState& state,
                                          Workspace& ws, Index c);

/// Contact sample k of `samples` (midpoint rule) on element `element` of `cable` at `state`.
CableSample sample_of(const CableData& cable, Index element, int k, int samples,
                      const SystemState& state);

/// Centreline point Σ_n shape_n r_n of element coordinates `e` (shape = hermite::values); one
/// summation order for the kernels and the outputs, so that their projections agree bit for bit.
inline Vec3 centreline_point(const Vec4& shape, const Vec12& e) {
  Vec3 x = Vec3::Zero();
  for (int n = 0; n < 4; ++n) x += shape[n] * e.segment<3>(3 * n);
  return x;
}

inline Aabb inflated(Aabb box, double margin) {
  box.inflate(margin);
  return box;
}

/// Run the contact detection and kernels of every pair at `state`, feeding `sink`.
void visit_contact_samples(const Model& model, const SystemState& state, Workspace& ws,
                           ContactVisit how, ContactSink& sink);

}  // namespace ancf::detail
