// Natural frequencies and mode shapes of a Model linearised at an equilibrium: the dense
// generalized symmetric eigenproblem K φ = ω² M φ on the null space of the constraint Jacobian
// (small models only: dense O(n³)). Shared by the vibration tests and the mesh-convergence study.
#pragma once

#include "ancf/system/assembly.hpp"
#include "ancf/system/model.hpp"

namespace ancf {

struct ModalAnalysisOptions {
  /// −1: every coordinate. 0, 1, 2: only the x, y or z components of every 3-vector coordinate
  /// block (cable positions and slopes, body origins and axes). Valid when that component is
  /// decoupled from the others in K, M and Φ_q (e.g. a straight cable along x linearised about a
  /// straight state: axial in x, bending in y and z); natural_modes checks this and throws
  /// std::invalid_argument otherwise. It separates modes that would be degenerate (y and z
  /// bending pairs), whose eigenvectors the solver could mix.
  int component = -1;
  /// Relative threshold on |entries| counted as coupling (of the largest |K|, |M|, |Φ_q| entry).
  double coupling_tolerance = 1e-12;
};

struct NaturalModes {
  VecX omega_squared;  ///< ascending eigenvalues ω² [rad²/s²] (negative: unstable equilibrium)
  /// Mode shapes, one column per eigenvalue, as full coordinate vectors (model.coordinate_count()
  /// rows; zero outside the selected component), M-orthonormal: φᵢᵀ M φⱼ = δᵢⱼ.
  MatX shapes;
  Index selected_coordinates = 0;  ///< coordinates of the chosen component
  Index constraint_rank = 0;       ///< rank of Φ_q on them
  double asymmetry = 0.0;          ///< ‖K − Kᵀ‖_max / ‖K‖_max before symmetrisation

  /// ω_i = √(ω²_i) [rad/s]; NaN for a negative eigenvalue.
  [[nodiscard]] double omega(Index i) const;
};

/// Modes at `equilibrium` (q and λ; v is taken as zero). K = ∂(F − Q + Φ_qᵀλ)/∂q and M come from
/// assemble_iteration_matrix with weights (1, 0, 0) and (0, 0, 1), so the geometric stiffness of
/// prestress and of non-linear constraints is included. The eigenproblem is reduced to an
/// orthonormal null-space basis Z of Φ_q (QR of Φ_qᵀ): (Zᵀ K Z) y = ω² (Zᵀ M Z) y, φ = Z y.
/// Throws std::domain_error if K, Φ_q or M is not finite at the state (naming the row and
/// column), std::runtime_error if the eigen-solver fails.
[[nodiscard]] NaturalModes natural_modes(const Model& model, const SystemState& equilibrium,
                                         const ModalAnalysisOptions& options = {});

/// Modes at the model's initial configuration, which must be an equilibrium (e.g. a stress-free
/// or uniformly prestressed cable without loads; a loaded one: solve the statics, then call
/// natural_modes). λ is the least-squares solution of Φ_qᵀλ = −(F − Q) (QR); throws
/// std::invalid_argument if the remaining force exceeds `equilibrium_tolerance` times
/// max(‖F − Q‖∞, max|K|·max(1, ‖q‖∞)).
[[nodiscard]] NaturalModes natural_modes_at_initial_equilibrium(
    const Model& model, const ModalAnalysisOptions& options = {},
    double equilibrium_tolerance = 1e-9);

}  // namespace ancf
