// The history a model with Kirchhoff rods keeps: per rod node the committed untwisted reference
// triad R_i, per rod element the committed angle ω (kirchhoff_rod_element.hpp, docs/rod.md).
//
// Why history: the nodal triad is the smallest rotation of R_i onto the current tangent, which is
// singular only for a tangent opposite R_i's; moving R_i along with each accepted state keeps it
// far from that, for any rotation of the rod over the run (Meier, Popp & Wall 2014, §4; 4C's
// qrefconv_). It changes only in commit_rod_history(), called on accepted states (a converged
// load step, an accepted time step): a rejected step or Newton iterate never touches it, so there
// is nothing to roll back. At the committed state the commit leaves every triad and strain
// unchanged, and the forces on the positions and twists; it changes how nearby states are
// parametrised, and with it the slope forces by −f_α c (f_α the node's twist force, c the twist
// the old smallest rotation gave a slope change; test
// FrameUpdateChangesTheSlopeForcesByTheTwistForce): nothing in a twist equilibrium, the twist
// inertia force ρJ α̈ times c in dynamics.
#pragma once

#include <span>
#include <vector>

#include "ancf/system/model.hpp"

namespace ancf {

struct RodHistory {
  std::vector<std::vector<Mat3>> frames;   ///< per cable (empty unless a rod), per node
  std::vector<std::vector<double>> omega;  ///< per cable, per element
  long frame_updates = 0;  ///< commit_rod_history calls that updated some node's frame

  /// The history of the reference configuration (the model's reference frames, α = 0).
  [[nodiscard]] static RodHistory initial(const Model& model);
  /// The two node triads and ω of element j of cable c.
  [[nodiscard]] RodElementHistory element(Index cable, Index j) const {
    return {frames[cable][j], frames[cable][j + 1], omega[cable][j]};
  }
};

/// The 15 coordinates [r_j, r_j,x, r_j+1, r_j+1,x, α_j, α_j+1, β_j] of rod element j from q
/// (β_j = 0 for a linear twist).
[[nodiscard]] Vec15 rod_element_coordinates(const CableData& cable, Index j,
                                            std::span<const double> q);

/// Commit the accepted coordinates q (the model's n coordinates; longer spans are read up to n):
/// ω_e ← ω_e(q) (only the seed of ω's 2π branch: no effect on any evaluation near q), and
/// R_i ← SR(R_i → t_i(q)) for the nodes whose unit tangent has turned by more than `min_turn`
/// [rad] from R_i's. No heap allocation.
///
/// Why a threshold: the strain energy is a function of the physical state (centreline and
/// material triads) and does not see a commit, but the constant twist inertia ρJ α̇² (see
/// rod_twist_mass) measures the spin relative to R_i, so every frame update changes the
/// equations of motion slightly (the slope rows by ρJ α̈ c, see above; and the twist kinematics,
/// which sets the first-order convergence of the triad, docs/rod.md). Updating only after a
/// finite turn keeps them smooth between rare updates, still far (min_turn ≪ π) from the
/// smallest-rotation singularity.
void commit_rod_history(const Model& model, std::span<const double> q, RodHistory& history,
                        double min_turn = 0.0);

/// The turn [rad] after which the problems (static, generalized-α, IDA) update a node's frame by
/// default ([integrator] rod_frame_turn sets it for the time integrators). Each update changes
/// how α parametrises the spin, so the constant twist inertia sees a slightly different equation
/// at a time quantised to the step grid (docs/rod.md, "Frame updates").
inline constexpr double kRodCommitTurn = 0.1;
/// Largest [integrator] rod_frame_turn: keeps a step's further turn well away from the smallest
/// rotation's singularity at π.
inline constexpr double kRodMaxFrameTurn = 2.0;

/// Material triad [t̂, d₂, d₃] of rod node k at q under `history`.
[[nodiscard]] Mat3 rod_node_triad(const Model& model, Index cable, Index node,
                                  std::span<const double> q, const RodHistory& history);

}  // namespace ancf
