// run.json (run_record.hpp): one writer for `ancf run` and the Python module.
#include "ancf/io/run_record.hpp"

#include "ancf/io/run_outputs.hpp"

#ifndef ANCF_VERSION
#define ANCF_VERSION "unknown"
#endif

namespace ancf {

const char* ancf_version() {
  return ANCF_VERSION;
}

JsonObject run_json(const Scene& scene, const RunRecord& record, const RunOutputs* out) {
  const IntegratorSettings& s = scene.integrator;
  const bool ida = s.kind == IntegratorKind::ida;
  JsonObject opts, counts, results, times;
  opts.set("integrator", ida ? "ida" : "genalpha").set("rtol", s.rtol).set("t_end", s.t_end);
  opts.set("contact_pattern", s.contact_pattern == ContactPatternPolicy::all ? "all" : "near");
  opts.set("rod_frame_turn", s.rod_frame_turn);
  opts.set("cable_tangent",
           s.cable_tangent == CableTangent::tension_only ? "tension_only" : "exact");
  if (ida)
    opts.set("max_step", s.max_step)
        .set("max_order", static_cast<long>(s.max_order))
        .set("slope_scale", ida_scale_name(s.ida_slope_position_scale))
        .set("twist_scale", ida_scale_name(s.ida_twist_position_scale));
  else
    opts.set("step", s.step)
        .set("rho_infinity", s.rho_infinity)
        .set("formulation", s.stabilized_index2 ? "stabilized_index2" : "index3")
        .set("stepping", s.ga_error_controlled ? "error_controlled" : "fixed");
  if (!ida && s.ga_error_controlled)
    opts.set("error_rtol", s.ga_controller.rtol)
        .set("error_atol", s.ga_controller.atol)
        .set("h_min", s.ga_controller.h_min)
        .set("h_max", s.ga_controller.h_max);
  opts.set("output_interval", scene.output.interval).set("out", record.out_dir);
  for (const auto& [name, value] : record.counters) counts.set(name, value);
  for (const auto& [name, value] : record.timings) times.set(name, value);
  if (out)
    results.set("frames", out->frames())
        .set("t_reached", out->last_time())
        .set("initial_energy", out->initial_energy())
        .set("final_energy", out->final_energy())
        .set("max_energy_change", out->max_energy_change())
        .set("max_position_violation", out->max_position_violation())
        .set("max_velocity_violation", out->max_velocity_violation());
  JsonObject meta = run_json_header(scene, record.scene_text, "run", record.status, record.message,
                                    record.wall_seconds);
  meta.set("options", opts).set("counters", counts).set("time_s", times).set("results", results);
  return meta;
}

}  // namespace ancf
