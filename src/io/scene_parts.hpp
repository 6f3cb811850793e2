// Internal to the scene loader: the state shared by the readers of each section of a scene file
// (builder, names seen so far, where each constraint was declared) and the section readers.
#pragma once

#include <map>
#include <span>
#include <string>

#include "ancf/io/scene.hpp"
#include "ancf/physics/angle_law.hpp"
#include "ancf/system/model_builder.hpp"
#include "toml_reader.hpp"

namespace ancf::io {

struct SceneBuild {
  SceneBuild(const std::string& f, const SceneLimits& l) : file(f), limits(l) {}
  const std::string& file;
  const SceneLimits& limits;
  double elements = 0.0;  // cable elements read so far (memory estimate, run_limits.hpp)
  ModelBuilder builder;
  SceneNames names;
  std::vector<CableGeometry> cable_initial;  // initial configuration per cable (defaults of pins)
  std::vector<double> cable_radius;          // section radius per cable [m]
  std::vector<std::string> cable_names;
  std::vector<char> cable_is_rod;  // per cable: a [[rod]] (twist coordinates) or a [[cable]]
  /// Where each named constraint / force / pair was declared (key path and line), so that
  /// errors found later (redundancy at finalize) point back into the file.
  struct Origin {
    std::string path;
    int line = 0;
  };
  std::map<std::string, Origin> origins;
  /// Where each [[cable]] / [[rod]] was declared, for errors the builder finds at finalize that
  /// name the cable ("rod 'NAME' element j: …").
  std::map<std::string, Origin> cable_origins;
  std::map<std::string, std::string> revolute_joints;  // name → path (drives refer to them)
  /// What each [[joint]] acts on (its `at` node or its `body`): the entity of its reaction probe.
  struct JointTarget {
    bool on_body = false;
    Index index = 0;  // cable (node joints) or body
    Index node = 0;
  };
  std::map<std::string, JointTarget> joint_targets;

  /// Record `name` (constraint, force element, contact pair or drive) as declared by `t`; fails
  /// if the name is already used by another of them.
  void declare(TableReader& t, std::string_view key, const std::string& name);

  /// Run a builder call; a ModelError it throws becomes a SceneError at table `t`.
  template <class F>
  void build(const TableReader& t, F&& f) {
    try {
      f();
    } catch (const SceneError&) {
      throw;
    } catch (const ModelError& e) {
      t.fail_here(e.what());
    }
  }

  Index cable(TableReader& t, std::string_view key);
  Index body(TableReader& t, std::string_view key);
  int frame(TableReader& t, std::string_view key);
  /// Inline table { cable = "name", node = k } (k < 0 counts from the end), validated.
  NodeRef node(TableReader& t, std::string_view key);
  /// { cable, node } | { body, point } | { frame, point } | { ground = [x, y, z] }.
  AttachmentPoint attachment(TableReader& t, std::string_view key);
  /// "ground" → −1, otherwise a body index.
  Index body_or_ground(TableReader& t, std::string_view key);
  /// Optional `key = [first, count]` of elements of `cable` (absent: all of them), validated.
  ElementRange element_range(TableReader& t, std::string_view key, Index cable);
};

/// A rotation: { axis = [..], angle = rad } or a 3×3 matrix given by rows (orthonormal, det +1).
Mat3 read_rotation(TableReader& t, std::string_view key);
/// { kind = "fixed" | "constant_rate" | "smooth_ramp", angle0, rate, max_rate, ramp_time }.
AngleLaw read_angle_law(TableReader& t, std::string_view key);

/// The axis of a helix or arc geometry (through `point` along `direction`), for rod frames.
struct GeometryAxis {
  bool valid = false;
  Vec3 point = Vec3::Zero(), direction = Vec3::UnitZ();
};
/// A `geometry`/`reference` table (docs/scenes.md) with `elements` elements at the arc-length
/// node fractions `fractions` (empty: equal elements); `axis` (optional) receives the axis of a
/// helix or arc.
CableGeometry read_geometry(TableReader g, Index elements, GeometryAxis* axis = nullptr,
                            std::span<const double> fractions = {});
/// The mesh of a [[cable]] or [[rod]] table: `geometry`, the optional `reference` (else the
/// geometry) and the optional `grading` (mesh_grading.hpp), whose node fractions are taken along
/// the geometry and used for both, so that a graded reference and its initial shape share nodes.
struct CableMesh {
  CableGeometry initial, reference;
  GeometryAxis axis, reference_axis;  ///< of the geometry and of the reference (helix, arc)
};
CableMesh read_cable_mesh(TableReader& t, Index elements);
void read_cables(TableReader& root, SceneBuild& b);
/// [[rod]]: Kirchhoff rods (scene_rods.cpp).
void read_rods(TableReader& root, SceneBuild& b);
void read_bodies(TableReader& root, SceneBuild& b);
void read_frames(TableReader& root, SceneBuild& b);
void read_joints(TableReader& root, SceneBuild& b);
void read_drives(TableReader& root, SceneBuild& b);
void read_loads(TableReader& root, SceneBuild& b);
void read_shapes(TableReader& root, SceneBuild& b);
void read_contacts(TableReader& root, SceneBuild& b);
IntegratorSettings read_integrator(TableReader& root);
/// Needs the finalized model to resolve probe targets' node indices.
OutputSettings read_output(TableReader& root, SceneBuild& b);

/// The loader's stages (scene_loader.cpp), shared with the overrides (scene_overrides.cpp):
/// the file's text (regular files only), its TOML (syntax errors located), the Scene built from it.
std::string read_scene_file(const std::string& path);
toml::table parse_scene_text(const std::string& text, const std::string& path);
Scene build_scene(const toml::table& root, const std::string& path, const SceneLimits& limits);

}  // namespace ancf::io
