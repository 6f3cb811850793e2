// A scene file (TOML, docs/scenes.md) turned into a finalized Model plus the settings a run needs:
// integrator, output interval, probes, and the names the file used for its entities.
//
// load_scene() validates everything before anything runs: unknown keys at every table level,
// wrong types, missing required keys, non-physical values, undefined names and redundant
// constraints all raise SceneError with file, line, key path and what was expected.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "ancf/io/scene_error.hpp"
#include "ancf/solvers/generalized_alpha.hpp"
#include "ancf/system/contact_pattern.hpp"
#include "ancf/system/model.hpp"
#include "ancf/system/rod_history.hpp"

namespace ancf {

enum class IntegratorKind { ida, genalpha };

/// [integrator] of a scene file. IDA uses rtol, the ida_* tolerances and max_step; generalized-α
/// uses rtol, step, rho_infinity, the formulation and its absolute tolerances.
struct IntegratorSettings {
  IntegratorKind kind = IntegratorKind::ida;
  double t_end = 1.0;  ///< [s] > 0, end of the run (starts at t = 0)
  double rtol = 1e-6;  ///< relative tolerance (> 0), both integrators
  /// IDA: absolute tolerances as multiples of the physical scale of each variable class
  /// (IdaOptions::atol_*); negative: equal to rtol.
  double ida_atol_position = -1.0, ida_atol_velocity = -1.0, ida_atol_multiplier = -1.0;
  double max_step = 0.0;                  ///< IDA step limit [s]; 0: none
  int max_order = 5;                      ///< IDA BDF order limit, 1 … 5
  bool ida_sundials_vector_ops = false;   ///< IDA: SUNDIALS' own vector operations (IdaOptions)
  bool ida_sundials_klu = false;          ///< IDA: SUNDIALS' SUNLinSol_KLU instead of the project's
  bool ida_slope_position_scale = false;  ///< IDA: SlopeScale::position_equivalent tolerances
  bool ida_twist_position_scale = false;  ///< IDA: TwistScale::position_equivalent tolerances
  double step = 1e-3;                     ///< generalized-α step size h [s] > 0
  double rho_infinity = 0.8;              ///< generalized-α spectral radius at infinity, [0, 1]
  bool stabilized_index2 = false;  ///< generalized-α formulation (false: index 3, needs ρ∞ < 1)
  bool perturbed_start = false;    ///< generalized-α starting procedure (ABC 2015)
  /// Generalized-α absolute Newton tolerances [m], [m/s], [N].
  double ga_atol_position = 1e-8, ga_atol_velocity = 1e-6, ga_atol_multiplier = 1e-6;
  /// Generalized-α error-controlled stepping (false: fixed step `step`), its controller (local
  /// error tolerances [m], h_min, h_max [s]), what a change of h does, and the fresh matrix when
  /// the active contact set changes.
  bool ga_error_controlled = false;
  StepControllerOptions ga_controller;
  GeneralizedAlphaStepChange ga_step_change = GeneralizedAlphaStepChange::automatic;
  bool ga_refresh_on_contact_change = false;
  int ga_max_damping_halvings = 0;  ///< damped Newton (GeneralizedAlphaOptions), 0: off
  bool ga_recovery_backoff = true;  ///< fixed stepping: wait doubling after failed climbs
  bool ga_klu_refactor = false;     ///< klu_l_refactor instead of the LU on the runs (KluRefactor)
  bool ga_filter_error_estimate = true;  ///< filtered local error estimate
  double ga_max_reuse_rate = 0.1;  ///< modified Newton's reuse threshold (GeneralizedAlphaOptions)
  /// Contact coupling blocks in the iteration matrix: those of the pairs that are near (default)
  /// or every candidate's (the first design, kept to measure against).
  ContactPatternPolicy contact_pattern = ContactPatternPolicy::near;
  /// Tangent of the cable elements in both integrators' iteration matrices (CableTangent).
  CableTangent cable_tangent = CableTangent::exact;
  /// Turn [rad] of a rod node's tangent after which the time integrators update its frame
  /// (0 … kRodMaxFrameTurn; rod_history.hpp, docs/rod.md "Frame updates").
  double rod_frame_turn = kRodCommitTurn;
};

/// The scene's word for an IDA tolerance-scale choice ([integrator.ida] slope_scale and
/// twist_scale): "position_equivalent" or "unit". For records (run.json, Python, events.json).
[[nodiscard]] inline const char* ida_scale_name(bool position_equivalent) {
  return position_equivalent ? "position_equivalent" : "unit";
}

/// One probe of the output time series (probes.csv columns, docs/scenes.md).
struct Probe {
  enum class Kind { node, body, energy, constraint_violation, contact, drive, reaction, rod };
  Kind kind = Kind::energy;
  std::string label;  ///< column prefix
  Index target = -1;  ///< cable (node), body, contact pair or drive index; unused otherwise
  Index node = 0;  ///< node index (≥ 0, resolved) for Kind::node, Kind::rod and a node's reaction
  /// Kind::reaction: the joint's name; it acts on node `node` of cable `target`, or on body
  /// `target` (on_body); its constraints (Model::constraints() indices: the joint's own and,
  /// for clamp / slope options, NAME.slope), resolved when the model is finalized.
  std::string joint;
  bool on_body = false;
  std::vector<Index> constraints;
};

struct OutputSettings {
  double interval = 0.01;           ///< [s] > 0 between output frames (probes and VTK)
  bool vtk = true;                  ///< write .vtp frames and a .pvd series
  int vtk_samples_per_element = 4;  ///< polyline points per cable element (≥ 1)
  std::vector<Probe> probes;
};

/// Names used in the scene file → indices in the Model.
struct SceneNames {
  std::map<std::string, Index> cables, bodies, frames, shapes, contacts, drives;
};

struct Scene {
  std::string path;  ///< the file as given to load_scene
  std::string name;  ///< [scene] name (default: file stem)
  Model model;
  IntegratorSettings integrator;
  OutputSettings output;
  SceneNames names;
};

/// Bounds load_scene applies before it builds anything (runaway work refused, run_limits.hpp).
struct SceneLimits {
  /// Memory the scene's cable elements may need to run [bytes]; ≤ 0: this machine's physical
  /// memory.
  double memory_bytes = 0.0;
};

/// Parse, validate and build the scene in `path`, which must be a regular file. Throws
/// SceneError (any problem with the file or the model it describes, a scene with nothing to
/// simulate, a mesh whose memory estimate exceeds limits.memory_bytes).
[[nodiscard]] Scene load_scene(const std::string& path, const SceneLimits& limits = {});

/// Same from text already in memory; `path` is used in messages and as Scene::path.
[[nodiscard]] Scene load_scene_from_string(const std::string& text, const std::string& path,
                                           const SceneLimits& limits = {});

}  // namespace ancf
