// A Model's equations of motion as the Gear–Gupta–Leimkuhler stabilized index-2 DAE (DESIGN §6),
// the abstract DaeProblem the IDA adapter integrates.
//
// Unknowns y = [q; v; λ; μ] (n, n, m, m) and residual rows
//   F_q = q' − v + Φ_qᵀμ                      (kinematics, stabilized by μ)
//   F_v = M v' + F(q, v) − Q(q, v, t) + Φ_qᵀλ (dynamics)
//   F_Φ = Φ(q, t)                              (position constraints)
//   F_Ψ = Φ_q v + Φ_t                          (velocity constraints)
// On exact solutions μ = 0: the μ-term only projects q' onto the velocity manifold, so μ is a
// round-off-level check of the integration. Jacobian J = ∂F/∂y + c_j ∂F/∂y' by blocks (rows F_q,
// F_v, F_Φ, F_Ψ; columns q, v, λ, μ):
//   [c_j I + ∂(Φ_qᵀμ)/∂q   −I          0      Φ_qᵀ]
//   [K (with ∂(Φ_qᵀλ)/∂q)  D + c_j M   Φ_qᵀ   0   ]
//   [Φ_q                   0           0      0   ]
//   [∂(Φ_q v + Φ_t)/∂q     Φ_q         0      0   ]
// with K = ∂(F − Q)/∂q, D = ∂(F − Q)/∂v; the K, D, M, Φ_q terms come from the same assembly code
// as the model's iteration matrix (add_iteration_matrix), scattered into this larger pattern.
#pragma once

#include <functional>
#include <vector>

#include "ancf/core/dae_problem.hpp"
#include "ancf/system/assembly.hpp"
#include "ancf/system/contact_pattern.hpp"

namespace ancf {

/// Physical scales that set the absolute tolerances (DaeProblem::variable_scale). Zero entries
/// are derived from the model: length L from the extent of the initial configuration, energy E
/// from the constant loads over L, the initial kinetic and strain energy, velocity √(2E/m_total),
/// time T = L/velocity. Coordinates get L (positions) or 1 (slopes, body axes, rod twist angles;
/// see SlopeScale and TwistScale),
/// velocities those over T, a multiplier λ_i the force E/g_i and μ_i the rate s_i²/(T g_i), with
/// g_i = ‖Φ_q,i S‖ the gradient of row i in scaled coordinates and s_i the largest coordinate scale
/// in the row. Scale of a cable's nodal slope r' (and of its rate, over T).
enum class SlopeScale {
  unit,  ///< 1 (dimensionless): a slope error of rtol is allowed, whatever the element length
  /// L/(4l/27): the slope error that moves centreline points as much as a position error of the
  /// scale L (a slope enters positions through S2, S4, max |S2| = 4l/27). On slack ropes with
  /// EI = 0 the end slopes carry no stiffness and wander; unit scales made their rates limit every
  /// IDA step of the capture scene (ancf-study-ida-capture).
  position_equivalent,
};

/// Scale of a rod's twist angles α, β (and of their rates, over T).
enum class TwistScale {
  unit,  ///< 1 rad: a twist error of rtol rad is allowed, whatever the section
  /// L/r_g, r_g = √(ρJ_p/ρA) the section's polar radius of gyration: the twist error that moves
  /// the section's material points (RMS over the section, r_g δα) as much as a position error of
  /// the scale L. On thin ropes (r_g ≪ L) the twist modes are light and fast; with unit scales
  /// their contact-excited rates set every IDA step of the rod capture (ancf-study-ida-capture).
  /// A section without mass or polar inertia keeps 1.
  position_equivalent,
};

struct GglScales {
  double length = 0.0;  ///< L [m]
  double energy = 0.0;  ///< E [J]
  double time = 0.0;    ///< T [s]
  SlopeScale slope = SlopeScale::unit;
  TwistScale twist = TwistScale::unit;
};

/// Ownership: keeps a reference to `model`, which must outlive the problem.
class GglProblem final : public DaeProblem {
 public:
  /// Event functions g(state) (roots located by the integrator): the state has t, q, v, a = v', λ.
  using EventFunction = std::function<void(const SystemState& state, std::span<double> g)>;

  explicit GglProblem(const Model& model, GglScales scales = {},
                      ContactPatternOptions contact = {});

  [[nodiscard]] Index size() const override { return 2 * n_ + 2 * m_; }
  [[nodiscard]] const SparsityPattern& jacobian_pattern() const override { return pattern_; }
  /// ContactPattern::update at (t, q, v) of y; rebuilds the GGL pattern when it changed.
  bool update_jacobian_pattern(double t, std::span<const double> y, double horizon) override;
  /// Rods keep history: IDA returns after every step so that it is committed (rod_history.hpp).
  [[nodiscard]] bool keeps_history() const override { return model_.has_rods(); }
  void commit_step(double, std::span<const double> y) override {
    commit_rod_history(model_, y, workspace_.rods, workspace_.rod_frame_turn);
  }
  void residual(double t, std::span<const double> y, std::span<const double> yp,
                std::span<double> r) override;
  void jacobian(double t, std::span<const double> y, std::span<const double> yp, double c_j,
                std::span<double> values) override;
  [[nodiscard]] VariableClass variable_class(Index i) const override;
  [[nodiscard]] double variable_scale(Index i) const override { return scale_[i]; }
  [[nodiscard]] double time_scale() const override { return scales_.time; }
  void initial_state(std::span<double> y) const override;
  /// Projects q onto Φ(q, t) = 0 and v onto Φ_q v + Φ_t = 0 (minimum change in the metric of M),
  /// then solves [M Φ_qᵀ; Φ_q 0][v'; λ] = [Q − F; γ], γ = −(Φ_q v)_q v − 2Φ_qt v − Φ_tt, and sets
  /// μ = 0, μ' = λ' = 0. The multiplier scales are raised to |λ| found here.
  void consistent_values(double t, std::span<double> y, std::span<double> yp) override;
  [[nodiscard]] std::string describe_row(Index i) const override;
  [[nodiscard]] int root_count() const override { return event_count_; }
  void roots(double t, std::span<const double> y, std::span<const double> yp,
             std::span<double> g) override;

  /// Install `count` event functions (replaces any earlier ones; count 0 removes them).
  void set_events(int count, EventFunction events);

  /// (t, y, y') as a model state: q, v, a = v' and λ (μ is y[2n + m, 2n + 2m)).
  void unpack(double t, std::span<const double> y, std::span<const double> yp,
              SystemState& state) const;
  [[nodiscard]] const Model& model() const { return model_; }
  [[nodiscard]] const GglScales& scales() const { return scales_; }
  [[nodiscard]] const ContactPattern& contact_pattern() const { return contact_; }
  /// The scratch workspace, for its counters (contact samples, kernel times).
  [[nodiscard]] const Workspace& workspace() const { return workspace_; }
  /// Tangent of the cable elements in the iteration matrix (CableTangent; default exact). The
  /// residual does not depend on it.
  void set_cable_tangent(CableTangent tangent) { workspace_.cable_tangent = tangent; }
  /// Turn [rad] ≥ 0 of a rod node's tangent after which a commit updates the node's frame
  /// (default kRodCommitTurn; 0: every step). See rod_history.hpp and docs/rod.md, "Frame updates".
  void set_rod_frame_turn(double turn) { workspace_.rod_frame_turn = turn; }
  /// First index of each part of y.
  [[nodiscard]] Index velocity_offset() const { return n_; }
  [[nodiscard]] Index lambda_offset() const { return 2 * n_; }
  [[nodiscard]] Index mu_offset() const { return 2 * n_ + m_; }

 private:
  void build_pattern();
  void compute_scales(GglScales given);

  const Model& model_;
  Index n_, m_;
  GglScales scales_;
  SparsityPattern pattern_;
  // Slot maps from assembly slots (contact_pattern.hpp) into pattern_ (−1: none): the
  // iteration-matrix parts (MatrixScatter), and the GGL-only copies of Φ_q (rows F_Ψ), Φ_qᵀ (rows
  // F_q) and of the geometric-stiffness positions (μ term in rows F_q).
  std::vector<Index> position_slot_, velocity_slot_;
  std::vector<Index> psi_q_slot_, psi_v_slot_, mu_slot_, mu_geometric_slot_;
  std::vector<Index> identity_q_slot_, identity_v_slot_;  // (F_q, q) and (F_q, v) diagonals
  std::vector<double> scale_;
  std::vector<double> row_gradient_;  // g_i of the scale definition
  SystemState state_;
  Workspace workspace_;
  ContactPattern contact_;
  int event_count_ = 0;
  EventFunction events_;
};

}  // namespace ancf
