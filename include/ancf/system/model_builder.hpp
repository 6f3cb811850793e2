// Collects cables, bodies, driven frames, constraints, force elements and loads; finalize()
// numbers the unknowns, checks the constraints for redundancy, builds the fixed sparsity pattern
// and the scatter slots and returns the immutable Model.
//
// Attachments are placed by the initial configuration: e.g. attach_node_to_body() fixes the node
// at the body point where it starts, revolute() takes a global point and axis and derives the
// body-frame data, so a scene is consistent by construction.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "ancf/physics/contact_law.hpp"
#include "ancf/physics/contact_shapes.hpp"
#include "ancf/physics/joints.hpp"
#include "ancf/system/contact_data.hpp"
#include "ancf/system/model.hpp"

namespace ancf {

/// A node of a cable: cable index as returned by add_cable, node index (< 0 counts from the end).
struct NodeRef {
  Index cable = 0;
  Index node = 0;
};

/// Where a force element attaches: ground point (global), cable node position, body point
/// (body frame), or driven-frame point (frame coordinates).
struct GroundPoint {
  Vec3 position;
};
struct BodyPoint {
  Index body = 0;
  Vec3 position;
};
struct FramePoint {
  int frame = 0;
  Vec3 position;
};
using AttachmentPoint = std::variant<GroundPoint, NodeRef, BodyPoint, FramePoint>;

class ModelBuilder {
 public:
  // --- components ---------------------------------------------------------------------------
  /// Add a cable whose stress-free reference is `reference` (its nodal coordinates define J₀ and
  /// κ₀). The initial configuration is the reference unless set_initial_configuration() is called.
  Index add_cable(std::string name, const CableGeometry& reference, const CableSection& section);
  /// Add a Kirchhoff rod (kirchhoff_rod_element.hpp, docs/rod.md): a cable whose elements carry
  /// a material frame and twist. `section` supplies ρA, the radius (contact), mass-proportional
  /// damping; its EA and EI are ignored (the rod's own are used). `frames` has one material triad
  /// per reference node, first column the unit reference tangent (rod_reference_frames()).
  /// The twist angles start at 0 with zero rate.
  Index add_rod(std::string name, const CableGeometry& reference, CableSection section,
                const RodSection& rod, const std::vector<Mat3>& frames);
  /// Start cable `cable` from other nodal coordinates (same node count) and velocities (optional).
  void set_initial_configuration(Index cable, const CableGeometry& current,
                                 const std::vector<NodeCoordinates>* velocities = nullptr);
  /// Add a rigid body with origin at `position`, rotation `rotation` (orthonormal, det +1),
  /// origin velocity and angular velocity (global frame). Its six orthonormality rows are added
  /// at finalize(). Returns the body index.
  Index add_body(std::string name, const RigidBodyInertia& inertia, const Vec3& position,
                 const Mat3& rotation = Mat3::Identity(), const Vec3& velocity = Vec3::Zero(),
                 const Vec3& angular_velocity = Vec3::Zero());
  /// Add a frame with prescribed motion; returns its index.
  int add_driven_frame(DrivenFrame frame);

  // --- loads --------------------------------------------------------------------------------
  /// Uniform gravitational acceleration [m/s²] on all cables and bodies (consistent loads).
  void set_gravity(const Vec3& g) { gravity_ = g; }
  /// Dead force [N] at a node.
  void add_node_force(NodeRef node, const Vec3& force);
  /// Dead force per unit reference length [N/m], fixed in space, on the elements `range` of the
  /// cable or rod `cable` (acting on its centreline), as consistent nodal loads ∫ Sᵀ w dx like
  /// gravity's ρA g. `name` is for messages. Throws ModelError on a bad cable or range.
  void add_distributed_force(const std::string& name, Index cable, const Vec3& force_per_length,
                             ElementRange range = {});
  /// Moment per unit reference length [N m/m] fixed in space on the material triads of the
  /// elements `range` of the rod `cable` (scaled by the load factor; its load stiffness enters
  /// the iteration matrix: rod_distributed_moment). Throws ModelError on a cable that is no rod.
  void add_distributed_moment(const std::string& name, Index cable, const Vec3& moment_per_length,
                              ElementRange range = {});
  /// Moment [N m] fixed in space on a rod node's material triad (scaled by the load factor); its
  /// load stiffness enters the iteration matrix (rod_end_moment).
  void add_node_moment(NodeRef node, const Vec3& moment);
  /// Force [N] at a point, constant or F(t).
  void add_point_force(std::string name, const AttachmentPoint& point, const Vec3& force,
                       std::function<Vec3(double)> time_function = {});
  /// Torque [N m] on a body, constant or τ(t).
  void add_body_torque(std::string name, Index body, const Vec3& torque,
                       std::function<Vec3(double)> time_function = {});
  /// Spring-damper between two points; rest_length < 0 means "the initial distance".
  void add_spring_damper(std::string name, const AttachmentPoint& a, const AttachmentPoint& b,
                         double stiffness, double damping, double rest_length = -1.0);
  /// Torque-limited PD drive on the revolute joint `joint` (added before with revolute() or
  /// revolute_to_ground()); θ = 0 at the initial configuration, positive about the joint axis.
  void add_revolute_drive(std::string name, const std::string& joint, AngleLaw reference, double kp,
                          double kd, double torque_max);

  // --- contact (DESIGN §5; contact_law.hpp, contact_shapes.hpp, cable_contact.hpp) -------------
  /// Add a named shape fixed to ground (shape data in global coordinates), to a driven frame or
  /// to a rigid body (shape data in that frame / body frame). Returns the shape index.
  Index add_ground_shape(std::string name, const ContactShape& shape);
  Index add_frame_shape(std::string name, int frame, const ContactShape& shape);
  Index add_body_shape(std::string name, Index body, const ContactShape& shape);
  /// Candidate contact pair between cable `cable` (its CableSection::radius must be > 0) and the
  /// shape `shape`: `samples_per_element` ≥ 1 points per element at ξ = (k + ½)/N, each weighing
  /// l/N, on the elements of `range` (default: all). The pattern reserves the cable–body blocks
  /// of every candidate element, so KLU analyses once.
  void add_cable_shape_contact(std::string name, Index cable, Index shape, const ContactLaw& law,
                               int samples_per_element, ElementRange range = {});
  /// Candidate contact pair between two different cables (both radii > 0): samples of cable a
  /// against the closest point of cable b. Reserves every candidate element-pair block
  /// (2·144·count_a·count_b entries: restrict the ranges where contact can only happen locally).
  /// Crossing contact is seen through the samples: space them ≲ the radii (docs/contact.md).
  void add_cable_cable_contact(std::string name, Index cable_a, Index cable_b,
                               const ContactLaw& law, int samples_per_element,
                               ElementRange range_a = {}, ElementRange range_b = {});

  // --- constraints on cable nodes -------------------------------------------------------------
  /// Node position fixed at `target` [m] (3 rows).
  void pin(std::string name, NodeRef node, const Vec3& target);
  /// Node slope kept parallel to `direction` (2 rows). Pin + align_slope = clamp.
  void align_slope(std::string name, NodeRef node, const Vec3& direction);
  /// Node position fixed to the body point where the node starts (3 rows).
  void attach_node_to_body(std::string name, NodeRef node, Index body);
  /// Node slope kept parallel to the body-fixed direction of its initial slope (2 rows).
  void align_slope_to_body(std::string name, NodeRef node, Index body);
  /// Node position fixed to the driven-frame point where the node starts at t = 0 (3 rows).
  void attach_node_to_frame(std::string name, NodeRef node, int frame);
  /// Node slope parallel to the frame-fixed direction of its initial slope (2 rows).
  void align_slope_to_frame(std::string name, NodeRef node, int frame);
  /// Rod node twist angle fixed at its initial value (1 row). With the node's slope fixed in
  /// direction (align_slope) the material triad is fixed: pin + align_slope + fix_twist = clamp.
  void fix_twist(std::string name, NodeRef node);
  /// Two rod nodes share their twist angle (1 row); with join_nodes(…, slopes = true) the two
  /// material triads coincide, provided their reference triads do (checked at finalize).
  void join_twist(std::string name, NodeRef a, NodeRef b);
  /// Rod node's twist tied to a body (1 row, rod_twist_constraint.hpp): d₂·b = 0 with b the
  /// body-fixed vector that is the node's material d₃ at the initial configuration. With
  /// attach_node_to_body + align_slope_to_body the node's material triad is fixed in the body
  /// (a clamp into the body including twist). Multipliers follow all dot rows.
  void tie_twist_to_body(std::string name, NodeRef node, Index body);
  /// The same with b fixed in a driven frame (rheonomic).
  void tie_twist_to_frame(std::string name, NodeRef node, int frame);
  /// Two nodes share their position (3 rows) and, with `slopes`, their slope (3 more rows).
  void join_nodes(std::string name, NodeRef a, NodeRef b, bool slopes = false);

  // --- joints of rigid bodies (points and axes global, at the initial configuration) ----------
  void spherical_to_ground(std::string name, Index body, const Vec3& point);
  void revolute_to_ground(std::string name, Index body, const Vec3& point, const Vec3& axis);
  void fixed_to_ground(std::string name, Index body);
  void spherical(std::string name, Index body1, Index body2, const Vec3& point);
  void revolute(std::string name, Index body1, Index body2, const Vec3& point, const Vec3& axis);
  void fixed(std::string name, Index body1, Index body2);

  /// Number, check for redundant constraints (ModelError naming them), build pattern and slots.
  /// The builder is left empty.
  [[nodiscard]] Model finalize();

 private:
  struct PendingCable {
    std::string name;
    CableSection section;
    CableGeometry reference;
    CableGeometry initial;
    std::vector<NodeCoordinates> velocities;
    std::optional<RodSection> rod;
    std::vector<Mat3> frames;  // rods: reference material triads per node
  };
  struct PendingBody {
    std::string name;
    RigidBodyInertia inertia;
    Vec3 position;
    Mat3 rotation;
    Vec3 velocity, angular_velocity;
  };
  // Constraints and forces refer to entities by kind and index until numbering is known; they are
  // stored as functions of the final coordinate offsets.
  struct Offsets {
    std::vector<Index> cable_first, body_first;
    std::vector<Index> twist_first;  // −1 for cables that are not rods
    [[nodiscard]] Index twist(NodeRef n) const { return twist_first[n.cable] + n.node; }
    [[nodiscard]] Index node(NodeRef n) const { return cable_first[n.cable] + 6 * n.node; }
    [[nodiscard]] Index body(Index b) const { return body_first[b]; }
  };
  struct PendingConstraint {
    std::string name;
    std::function<ConstraintRows(const Offsets&)> rows;
  };
  struct PendingTwist {
    std::string name;
    NodeRef node;
    std::function<AffineVector(const Offsets&)> b;
  };
  struct RevoluteInfo {
    std::string name;
    Index base_body;  // −1: ground
    Index body;
    Vec3 axis;  // global, at the initial configuration
  };
  struct PendingForce {
    std::string name;
    std::function<void(const Offsets&, Model&)> add;
  };

  const PendingCable& cable_at(Index cable, const char* what) const;
  const PendingBody& body_at(Index body, const char* what) const;
  NodeRef resolve(NodeRef node, const char* what) const;
  const NodeCoordinates& initial_node(NodeRef node) const;
  /// Material triad of a rod node at the initial configuration (α = 0, reference history).
  Mat3 initial_rod_triad(NodeRef node, const char* what) const;
  void require_new_name(const std::string& name, const char* what) const;
  static AffineVector point_expression(const AttachmentPoint& p, const Offsets& o);
  Vec3 point_position(const AttachmentPoint& p) const;
  void add_constraint(std::string name, std::function<ConstraintRows(const Offsets&)> rows);
  Index add_shape(ContactShapeData shape);
  /// Rod data of cable `c` from its pending data (model_builder_rods.cpp).
  static RodData make_rod_data(const PendingCable& pc, const CableData& c, Index twist_first);
  /// Contact data of the model (owner coordinates) at finalize() (contact_builder.cpp).
  void finalize_contacts(const Offsets& o, Model& m) const;
  /// ModelError naming each constraint whose rows are linearly dependent on earlier rows at the
  /// initial configuration (constraint_redundancy.cpp).
  static void check_redundancy(const Model& m);
  /// Fixed pattern and scatter slots of every block (model_pattern.cpp).
  static void build_pattern_and_slots(Model& m);

  std::vector<PendingCable> cables_;
  std::vector<PendingBody> bodies_;
  std::vector<DrivenFrame> frames_;
  std::vector<PendingConstraint> constraints_;
  std::vector<PendingTwist> twists_;
  std::vector<RevoluteInfo> revolutes_;
  std::vector<PendingForce> forces_;
  std::vector<std::pair<NodeRef, Vec3>> node_forces_;
  std::vector<DistributedForceData> distributed_forces_;
  std::vector<RodDistributedMomentData> distributed_moments_;
  std::vector<std::pair<NodeRef, Vec3>> node_moments_;
  std::vector<ContactShapeData> shapes_;
  std::vector<CableShapeContactData> cable_shape_contacts_;
  std::vector<CableCableContactData> cable_cable_contacts_;
  Vec3 gravity_ = Vec3::Zero();
};

}  // namespace ancf
