// Global residual, iteration matrix, energies, momenta and constraint violations of a Model,
// written into preallocated storage (no heap allocation per call once a Workspace exists).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "ancf/physics/cable_contact.hpp"
#include "ancf/physics/kirchhoff_rod_distributed_moment.hpp"
#include "ancf/system/model.hpp"
#include "ancf/system/rod_history.hpp"

namespace ancf {

struct ContactCoupling;
class ContactPattern;

/// State at time t: coordinates q, velocities v = q', accelerations a = q'' and multipliers λ.
/// Sizes: q, v, a: model.coordinate_count(); λ: model.multiplier_count().
struct SystemState {
  double t = 0.0;
  VecX q, v, a, lambda;
  /// The rod history the twist coordinates of q refer to (rod_history.hpp), for evaluations
  /// outside the integrator (outputs); nullptr: the Workspace's own.
  const RodHistory* rod_history = nullptr;

  /// State at t = 0 with q, v from the model's initial values, a = 0, λ = 0.
  static SystemState initial(const Model& model);
};

/// Scratch storage of the assembly functions; create once per model and reuse.
struct Workspace {
  std::vector<FrameKinematics> frames;  ///< driven-frame kinematics at `frames_time`
  double frames_time = 0.0;
  bool frames_valid = false;
  CableElementResult element;
  ForceResult force;
  /// Committed rod history (rod_history.hpp): the state the rod kernels are evaluated under.
  /// Changed only by commit_rod_history() on accepted states.
  RodHistory rods;
  RodElementResult rod;
  RodDistributedMomentLoad rod_moment;  ///< scratch of distributed moments
  // Contact scratch, sized here so that a time step allocates nothing: element and cable boxes
  // of the cables in contact pairs (empty for the others), candidate elements, one sample result.
  std::vector<std::vector<Aabb>> element_boxes;
  /// Per element of those cables: largest distance of its inner control points from its chord
  /// (the hull bound of the broad phase, contact_bounds.hpp); reset with element_boxes, computed
  /// on demand (< 0: not yet).
  std::vector<std::vector<double>> element_deviations;
  std::vector<Aabb> cable_boxes;
  std::vector<char> element_boxes_current;  ///< per cable: element_boxes valid for this call
  std::vector<Index> candidates;
  ContactSampleResult contact;
  long narrow_phase_samples = 0;  ///< contact samples that reached a kernel (cumulative counter)
  /// Broad phase, second level: skip cable elements (and cable–cable element pairs) whose
  /// Bézier hulls provably keep them out of contact (contact_bounds.hpp; same residual and
  /// matrix, fewer kernel calls). false: element boxes only (the first design).
  bool hull_broad_phase = true;
  /// Hash of the active contact samples (pair and elements of each, in visiting order) of the
  /// last assemble_residual; 0 when none is active.
  std::uint64_t active_contact_signature = 0;
  /// Coupling-block slots of the current contact pattern (set by assembly into a ContactPattern;
  /// nullptr: the model's own pattern, which holds no coupling blocks).
  const ContactCoupling* coupling = nullptr;
  /// Active samples whose coupling blocks the pattern did not hold (cumulative): their ∂Q/∂P
  /// coupling terms were left out of a matrix. Zero when the pattern was updated at the state the
  /// matrix is assembled at (ContactPattern::update).
  long missing_coupling_samples = 0;
  /// Wall time [s] in the cable element kernels (forces and matrices) and in the contact
  /// detection and kernels, cumulative: the time shares of a run.
  double element_seconds = 0.0, contact_seconds = 0.0;
  /// Tangent of the cable kernels in iteration matrices (CableTangent; residuals are exact).
  CableTangent cable_tangent = CableTangent::exact;
  /// The turn [rad] of a rod node's tangent after which the time integrators' commit updates its
  /// frame (commit_rod_history's min_turn; rod_history.hpp).
  double rod_frame_turn = kRodCommitTurn;
  /// Force-only kernel of the cable elements in residuals (CableKernel; same force).
  CableKernel cable_force_kernel = CableKernel::invariant;
  /// Stiffness kernel of undamped cable elements in iteration matrices (same matrix).
  CableKernel cable_stiffness_kernel = CableKernel::invariant;
  explicit Workspace(const Model& model);
  /// Frame kinematics at t (recomputed only when t changes).
  std::span<const FrameKinematics> frames_at(const Model& model, double t);
};

/// Weights of the iteration matrix w_q ∂R/∂q + w_v ∂R/∂v + w_a ∂R/∂a of the dynamic rows.
/// Statics: (1, 0, 0). Generalized-α: (1, γ/(βh), 1/(βh²)). IDA: the q-block uses (1, 0, 0), the
/// v-block (0, 1, c_j).
struct IterationWeights {
  double w_q = 1.0;
  double w_v = 0.0;
  double w_a = 0.0;
  double load_factor = 1.0;  ///< s of assemble_residual (scales ∂Q_loads/∂q of body torques)
};

/// Residual of the equations of motion and constraints (DESIGN §1, S6):
///   rows [0, n):   M a + F(q, v) − s·Q_loads(t) − Q_elements(q, v, t) + Φ_qᵀ λ
///   rows [n, n+m): Φ(q, t)
/// Q_loads are gravity, dead nodal loads, point forces and body torques (scaled by the load
/// factor s, 1 in dynamics); Q_elements are spring-dampers and drives. `r` has system_size().
void assemble_residual(const Model& model, const SystemState& state, double load_factor,
                       Workspace& ws, std::span<double> r);

/// Values of [w_q K + w_v D + w_a M, Φ_qᵀ; Φ_q, 0] in model.pattern() with
/// K = ∂(F − sQ + Φ_qᵀλ)/∂q and D = ∂(F − Q)/∂v. `values` has pattern().nonzeros() entries.
void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& weights, Workspace& ws,
                               std::span<double> values);

/// The same matrix in contact.pattern() (the model's pattern plus the near contact coupling
/// blocks; `values` has contact.pattern().nonzeros() entries). Call contact.update() at (or
/// shortly before) `state` first, so that the pattern holds every block in contact.
void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& weights, const ContactPattern& contact,
                               Workspace& ws, std::span<double> values);

/// Destination of the iteration-matrix entries inside a larger matrix whose ∂/∂q and ∂/∂v blocks
/// are separate (the GGL Jacobian, ggl_problem.hpp). Assembly slot s (model.pattern() entries,
/// then the coupling entries of `coupling`, see contact_pattern.hpp) adds its position part (w_q K
/// with the geometric stiffness, and the unweighted Φ_q, Φ_qᵀ) to values[position[s]] and its
/// velocity part (w_v D + w_a M) to values[velocity[s]]. Both spans have one entry per assembly
/// slot; velocity[s] is read only for entries of the n×n dynamic block. `coupling` (nullptr: none)
/// gives the coupling blocks' slots.
struct MatrixScatter {
  std::span<const Index> position;
  std::span<const Index> velocity;
};

/// Adds (does not zero) the terms of assemble_iteration_matrix into `values` through `scatter`;
/// the same code path, so both matrices agree term by term. Each cable element kernel runs once.
void add_iteration_matrix(const Model& model, const SystemState& state,
                          const IterationWeights& weights, const MatrixScatter& scatter,
                          const ContactCoupling* coupling, Workspace& ws, std::span<double> values);

/// Φ_q v + Φ_t (size m): the velocity-level constraint.
void assemble_velocity_constraint(const Model& model, const SystemState& state, Workspace& ws,
                                  std::span<double> out);
/// γ = −[(Φ_q v)_q v + 2Φ_qt v + Φ_tt] (size m): Φ_q a = γ on the constraint manifold.
void assemble_acceleration_rhs(const Model& model, const SystemState& state, Workspace& ws,
                               std::span<double> out);

/// Energies [J]. potential = strain + springs + constant-load potential (−Q_constᵀq).
struct Energies {
  double kinetic = 0.0, strain = 0.0, spring = 0.0, load = 0.0;
  [[nodiscard]] double potential() const { return strain + spring + load; }
  [[nodiscard]] double total() const { return kinetic + potential(); }
};
[[nodiscard]] Energies energies(const Model& model, const SystemState& state, Workspace& ws);

/// Linear momentum [kg m/s] and angular momentum about the origin [kg m²/s] of cables and bodies
/// (∫ρ ṙ dV, ∫ρ r × ṙ dV, exact through the consistent mass matrices).
struct Momentum {
  Vec3 linear = Vec3::Zero(), angular = Vec3::Zero();
};
[[nodiscard]] Momentum momentum(const Model& model, const VecX& q, const VecX& v);

/// Largest |Φ| and |Φ_q v + Φ_t| with the rows they occur in (model.describe_row).
struct ConstraintViolation {
  double position = 0.0, velocity = 0.0;
  Index position_row = -1, velocity_row = -1;
};
[[nodiscard]] ConstraintViolation constraint_violation(const Model& model, const SystemState& state,
                                                       Workspace& ws);

/// Angle θ [rad], rate [rad/s] and applied torque τ [N m] of drive `drive` (Model::drives()
/// order) at `state` (the same evaluation the residual uses).
[[nodiscard]] DriveState drive_state(const Model& model, const SystemState& state, Index drive,
                                     Workspace& ws);

// Convenience overloads that allocate a workspace (not for time-stepping loops).
void assemble_iteration_matrix(const Model& model, const SystemState& state,
                               const IterationWeights& weights, std::span<double> values);
[[nodiscard]] double strain_energy(const Model& model, const VecX& q);
/// The same with the rods evaluated under `rods` (the one above uses the reference history).
[[nodiscard]] double strain_energy(const Model& model, const VecX& q, const RodHistory& rods);
[[nodiscard]] double kinetic_energy(const Model& model, const VecX& v);

}  // namespace ancf
