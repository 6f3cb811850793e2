// ancf.Scene: a scene file or string loaded, checked and built by the C++ loader (one set of
// scene rules: docs/scenes.md), with KEY=VALUE overrides applied before it is built.
#include "ancf/io/run_limits.hpp"
#include "bindings.hpp"

namespace ancf::python {

namespace {

using Overrides = std::vector<std::pair<std::string, std::string>>;

std::vector<SceneOverride> to_overrides(const Overrides& pairs) {
  std::vector<SceneOverride> o;
  for (const auto& [key, value] : pairs) o.push_back({key, value});
  return o;
}

SceneHandle load_text(const std::string& text, const std::string& path,
                      std::vector<SceneOverride> overrides, bool from_file) {
  SceneHandle h;
  h.text = text;
  h.overrides = std::move(overrides);
  h.from_file = from_file;
  h.scene = std::make_shared<const Scene>(load_scene_from_string(h.text, path, h.overrides));
  return h;
}

py::dict integrator_dict(const IntegratorSettings& s) {
  py::dict d;
  d["method"] = s.kind == IntegratorKind::ida ? "ida" : "genalpha";
  d["t_end"] = s.t_end;
  d["rtol"] = s.rtol;
  d["contact_pattern"] = s.contact_pattern == ContactPatternPolicy::all ? "all" : "near";
  d["ida"] = py::dict(py::arg("max_step") = s.max_step, py::arg("max_order") = s.max_order,
                      py::arg("atol_position") = s.ida_atol_position,
                      py::arg("atol_velocity") = s.ida_atol_velocity,
                      py::arg("atol_multiplier") = s.ida_atol_multiplier,
                      py::arg("linear_solver") = s.ida_sundials_klu ? "sundials_klu" : "ancf_klu",
                      py::arg("slope_scale") = ida_scale_name(s.ida_slope_position_scale),
                      py::arg("twist_scale") = ida_scale_name(s.ida_twist_position_scale));
  d["genalpha"] = py::dict(
      py::arg("step") = s.step, py::arg("rho_infinity") = s.rho_infinity,
      py::arg("formulation") = s.stabilized_index2 ? "stabilized_index2" : "index3",
      py::arg("start") = s.perturbed_start ? "perturbed" : "consistent",
      py::arg("stepping") = s.ga_error_controlled ? "error_controlled" : "fixed",
      py::arg("error_rtol") = s.ga_controller.rtol, py::arg("error_atol") = s.ga_controller.atol,
      py::arg("h_min") = s.ga_controller.h_min, py::arg("h_max") = s.ga_controller.h_max,
      py::arg("atol_position") = s.ga_atol_position, py::arg("atol_velocity") = s.ga_atol_velocity,
      py::arg("atol_multiplier") = s.ga_atol_multiplier,
      py::arg("newton_damping") = s.ga_max_damping_halvings,
      py::arg("error_filter") = s.ga_filter_error_estimate,
      py::arg("refresh_on_contact_change") = s.ga_refresh_on_contact_change);
  return d;
}

py::dict info(const Scene& scene) {
  const Model& m = scene.model;
  py::dict d;
  d["coordinates"] = m.coordinate_count();
  d["multipliers"] = m.multiplier_count();
  d["system_size"] = m.system_size();
  d["ggl_size"] = 2 * m.coordinate_count() + 2 * m.multiplier_count();
  d["nonzeros"] = m.pattern().nonzeros();
  d["cables"] = m.cables().size();
  d["bodies"] = m.bodies().size();
  d["frames"] = m.frames().size();
  d["constraints"] = m.constraints().size();
  d["contact_pairs"] = m.contact_pair_count();
  return d;
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<SceneHandle>(m, "Scene", R"(A scene loaded, validated and built into a Model.

Made by ancf.load(path) or ancf.loads(text) (or ancf.SceneBuilder.build()); immutable: a
changed value is a new scene, scene.with_overrides({...}). Every check of the scene format
(docs/scenes.md) is the C++ loader's, with the same messages, raised as ancf.SceneError.)")
      .def_property_readonly(
          "name", [](const SceneHandle& h) { return h.scene->name; }, "[scene] name")
      .def_property_readonly(
          "path", [](const SceneHandle& h) { return h.scene->path; },
          "the file, or the name given to loads()")
      .def_property_readonly(
          "text", [](const SceneHandle& h) { return h.text; }, "the text as loaded (no overrides)")
      .def_property_readonly(
          "overrides",
          [](const SceneHandle& h) {
            Overrides o;
            for (const SceneOverride& s : h.overrides) o.emplace_back(s.key, s.value);
            return o;
          },
          "the overrides applied, in order, as (key, TOML value text) pairs")
      .def(
          "toml",
          [](const SceneHandle& h) {
            return h.overrides.empty() ? h.text
                                       : apply_scene_overrides(h.text, h.scene->path, h.overrides);
          },
          "The TOML that was built: the text with the overrides applied (comments dropped then).")
      .def(
          "info", [](const SceneHandle& h) { return info(*h.scene); },
          "Sizes as `ancf info` prints them: coordinates, multipliers, system and GGL sizes, "
          "pattern non-zeros, cables, bodies, frames, constraints, contact pairs.")
      .def_property_readonly(
          "names",
          [](const SceneHandle& h) {
            const SceneNames& n = h.scene->names;
            return py::dict(py::arg("cables") = n.cables, py::arg("bodies") = n.bodies,
                            py::arg("frames") = n.frames, py::arg("shapes") = n.shapes,
                            py::arg("contacts") = n.contacts, py::arg("drives") = n.drives);
          },
          "names of the scene's entities → their indices, per kind")
      .def_property_readonly(
          "integrator", [](const SceneHandle& h) { return integrator_dict(h.scene->integrator); },
          "the [integrator] settings in effect (defaults filled in), as a dict")
      .def_property_readonly(
          "output_interval", [](const SceneHandle& h) { return h.scene->output.interval; },
          "[output] interval [s]")
      .def(
          "output_times",
          [](const SceneHandle& h) {
            const std::vector<double> t =
                output_times(h.scene->output.interval, h.scene->integrator.t_end);
            return copy(Eigen::Map<const VecX>(t.data(), static_cast<Index>(t.size())));
          },
          "The output times after t = 0 (interval, 2·interval, …, t_end) [s].")
      .def_property_readonly(
          "q0", [](const SceneHandle& h) { return copy(h.scene->model.initial_coordinates()); },
          "initial coordinates q(0) as given (before the integrator makes them consistent)")
      .def_property_readonly(
          "v0", [](const SceneHandle& h) { return copy(h.scene->model.initial_velocities()); },
          "initial velocities v(0) as given")
      .def(
          "describe_coordinate",
          [](const SceneHandle& h, Index i) {
            if (i < 0 || i >= h.scene->model.system_size()) throw py::index_error();
            return h.scene->model.describe_row(i);
          },
          py::arg("index"), "What unknown `index` of [q; λ] is, e.g. \"cable 'rope' node 3 r_x\".")
      .def(
          "check",
          [](const SceneHandle& h, double max_steps) {
            require_runnable(h.scene->integrator, h.scene->output.interval, max_steps);
          },
          py::arg("max_steps") = kDefaultMaxSteps,
          "The checks a run makes before it starts (those of `ancf check` and `ancf run`): a "
          "generalized-α step ≤ t_end, h_max ≥ h_min, at most max_steps steps. Raises "
          "ancf.ModelError.")
      .def(
          "_with_overrides",
          [](const SceneHandle& h, const Overrides& more) {
            std::vector<SceneOverride> all = h.overrides;
            for (const SceneOverride& o : to_overrides(more)) all.push_back(o);
            return load_text(h.text, h.scene->path, std::move(all), h.from_file);
          },
          py::arg("overrides"))
      .def("__repr__", [](const SceneHandle& h) {
        return "<ancf.Scene '" + h.scene->name + "' from " + h.scene->path + ", " +
               std::to_string(h.scene->model.coordinate_count()) + " coordinates, " +
               std::to_string(h.scene->model.multiplier_count()) + " multipliers>";
      });

  m.def(
      "_load",
      [](const std::string& path, const Overrides& overrides) {
        return load_text(read_scene_text(path), path, to_overrides(overrides), true);
      },
      py::arg("path"), py::arg("overrides"));
  m.def(
      "_loads",
      [](const std::string& text, const std::string& path, const Overrides& overrides) {
        return load_text(text, path, to_overrides(overrides), false);
      },
      py::arg("text"), py::arg("path"), py::arg("overrides"));
}

}  // namespace ancf::python
