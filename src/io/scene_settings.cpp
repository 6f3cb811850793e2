// [integrator] and [output] (with its [[output.probe]] entries).
#include <fmt/format.h>

#include "scene_parts.hpp"

namespace ancf::io {

IntegratorSettings read_integrator(TableReader& root) {
  IntegratorSettings s;
  auto table = root.optional_table("integrator");
  if (!table) return s;
  TableReader& t = *table;
  s.kind = t.choice("method", {"ida", "genalpha"}, "ida") == "ida" ? IntegratorKind::ida
                                                                   : IntegratorKind::genalpha;
  s.t_end = t.number_or("t_end", s.t_end, Range::positive);
  s.rtol = t.number_or("rtol", s.rtol, Range::positive);
  s.contact_pattern = t.choice("contact_pattern", {"near", "all"}, "near") == "all"
                          ? ContactPatternPolicy::all
                          : ContactPatternPolicy::near;
  s.cable_tangent = t.choice("cable_tangent", {"exact", "tension_only"}, "exact") == "tension_only"
                        ? CableTangent::tension_only
                        : CableTangent::exact;
  s.rod_frame_turn = t.number_or("rod_frame_turn", s.rod_frame_turn, Range::non_negative);
  if (s.rod_frame_turn > kRodMaxFrameTurn)
    t.fail("rod_frame_turn", fmt::format("expected a turn in [0, {:g}] rad (the smallest rotation "
                                         "is singular at π)",
                                         kRodMaxFrameTurn));
  if (auto ida = t.optional_table("ida")) {
    s.ida_atol_position = ida->number_or("atol_position", s.ida_atol_position, Range::positive);
    s.ida_atol_velocity = ida->number_or("atol_velocity", s.ida_atol_velocity, Range::positive);
    s.ida_atol_multiplier =
        ida->number_or("atol_multiplier", s.ida_atol_multiplier, Range::positive);
    s.max_step = ida->number_or("max_step", s.max_step, Range::non_negative);
    s.max_order = static_cast<int>(ida->integer_or("max_order", s.max_order, 1));
    if (s.max_order > 5) ida->fail("max_order", "expected a BDF order 1 … 5");
    s.ida_sundials_vector_ops =
        ida->choice("vector_ops", {"compiled", "sundials"}, "compiled") == "sundials";
    s.ida_slope_position_scale = ida->choice("slope_scale", {"unit", "position_equivalent"},
                                             "unit") == "position_equivalent";
    s.ida_twist_position_scale = ida->choice("twist_scale", {"unit", "position_equivalent"},
                                             "unit") == "position_equivalent";
    s.ida_sundials_klu =
        ida->choice("linear_solver", {"ancf_klu", "sundials_klu"}, "ancf_klu") == "sundials_klu";
    ida->finish();
  }
  if (auto ga = t.optional_table("genalpha")) {
    s.step = ga->number_or("step", s.step, Range::positive);
    s.rho_infinity = ga->number_or("rho_infinity", s.rho_infinity, Range::unit_interval);
    s.stabilized_index2 =
        ga->choice("formulation", {"index3", "stabilized_index2"}, "index3") == "stabilized_index2";
    s.perturbed_start =
        ga->choice("start", {"consistent", "perturbed"}, "consistent") == "perturbed";
    s.ga_atol_position = ga->number_or("atol_position", s.ga_atol_position, Range::positive);
    s.ga_atol_velocity = ga->number_or("atol_velocity", s.ga_atol_velocity, Range::positive);
    s.ga_atol_multiplier = ga->number_or("atol_multiplier", s.ga_atol_multiplier, Range::positive);
    s.ga_error_controlled =
        ga->choice("stepping", {"fixed", "error_controlled"}, "fixed") == "error_controlled";
    StepControllerOptions& c = s.ga_controller;
    c.rtol = ga->number_or("error_rtol", c.rtol, Range::positive);
    c.atol = ga->number_or("error_atol", c.atol, Range::positive);
    c.h_min = ga->number_or("h_min", c.h_min, Range::positive);
    c.h_max = ga->number_or("h_max", c.h_max, Range::non_negative);
    if (c.h_max > 0.0 && c.h_max < c.h_min) ga->fail("h_max", "expected h_max >= h_min (0: none)");
    c.easy_rate = ga->number_or("ceiling_rate", c.easy_rate, Range::positive);
    if (c.easy_rate >= 1.0) ga->fail("ceiling_rate", "expected a contraction rate in (0, 1)");
    c.ceiling_growth = ga->number_or("ceiling_growth", c.ceiling_growth, Range::positive);
    if (c.ceiling_growth < 1.0) ga->fail("ceiling_growth", "expected a factor >= 1");
    s.ga_max_reuse_rate = ga->number_or("max_reuse_rate", s.ga_max_reuse_rate, Range::positive);
    if (s.ga_max_reuse_rate >= 1.0)
      ga->fail("max_reuse_rate", "expected a contraction rate in (0, 1)");
    const std::string change =
        ga->choice("step_change",
                   {"automatic", "restart", "rescale", "rescale_with_velocity", "rescale_climbs"},
                   "automatic");
    s.ga_step_change = change == "restart"   ? GeneralizedAlphaStepChange::restart
                       : change == "rescale" ? GeneralizedAlphaStepChange::rescale
                       : change == "rescale_with_velocity"
                           ? GeneralizedAlphaStepChange::rescale_with_velocity
                       : change == "rescale_climbs" ? GeneralizedAlphaStepChange::rescale_climbs
                                                    : GeneralizedAlphaStepChange::automatic;
    s.ga_refresh_on_contact_change =
        ga->boolean_or("refresh_on_contact_change", s.ga_refresh_on_contact_change);
    s.ga_filter_error_estimate = ga->boolean_or("error_filter", s.ga_filter_error_estimate);
    s.ga_max_damping_halvings =
        static_cast<int>(ga->integer_or("newton_damping", s.ga_max_damping_halvings, 0));
    s.ga_klu_refactor = ga->choice("refactor", {"runs", "klu"}, "runs") == "klu";
    s.ga_recovery_backoff = ga->boolean_or("recovery_backoff", s.ga_recovery_backoff);
    if (!s.stabilized_index2 && s.rho_infinity >= 1.0)
      ga->fail("rho_infinity",
               "index 3 with rho_infinity = 1 is unstable: use rho_infinity < 1 or "
               "formulation = \"stabilized_index2\"");
    ga->finish();
  }
  if (s.step > s.t_end) t.fail("t_end", "expected t_end >= the generalized-alpha step");
  t.finish();
  return s;
}

OutputSettings read_output(TableReader& root, SceneBuild& b) {
  OutputSettings s;
  auto table = root.optional_table("output");
  if (!table) return s;
  TableReader& t = *table;
  s.interval = t.number_or("interval", s.interval, Range::positive);
  s.vtk = t.boolean_or("vtk", s.vtk);
  s.vtk_samples_per_element = static_cast<int>(t.integer_or("vtk_samples_per_element", 4, 1));
  auto lookup = [&](TableReader& p, std::string_view key, const std::map<std::string, Index>& m,
                    const char* what) {
    const std::string name = p.string(key);
    auto it = m.find(name);
    if (it == m.end()) p.fail(key, std::string("no ") + what + " named '" + name + "'");
    return std::pair<std::string, Index>(name, it->second);
  };
  for (TableReader& p : t.tables("probe")) {
    Probe probe;
    const std::string kind = p.choice("kind", {"node", "body", "energy", "constraint_violation",
                                               "contact", "drive", "reaction", "rod"});
    std::string label = kind;
    if (kind == "node") {
      probe.kind = Probe::Kind::node;
      const NodeRef n = b.node(p, "at");
      probe.target = n.cable;
      probe.node = n.node;
      label = b.cable_names[n.cable] + "[" + std::to_string(n.node) + "]";
    } else if (kind == "rod") {
      probe.kind = Probe::Kind::rod;
      const NodeRef n = b.node(p, "at");
      if (!b.cable_is_rod[n.cable]) p.fail("at", "a rod probe needs a node of a [[rod]]");
      probe.target = n.cable;
      probe.node = n.node;
      label = b.cable_names[n.cable] + "[" + std::to_string(n.node) + "].rod";
    } else if (kind == "body") {
      probe.kind = Probe::Kind::body;
      std::tie(label, probe.target) = lookup(p, "body", b.names.bodies, "body");
    } else if (kind == "energy") {
      probe.kind = Probe::Kind::energy;
    } else if (kind == "constraint_violation") {
      probe.kind = Probe::Kind::constraint_violation;
      label = "violation";
    } else if (kind == "contact") {
      probe.kind = Probe::Kind::contact;
      std::tie(label, probe.target) = lookup(p, "pair", b.names.contacts, "contact pair");
    } else if (kind == "reaction") {
      probe.kind = Probe::Kind::reaction;
      probe.joint = p.string("joint");
      const auto it = b.joint_targets.find(probe.joint);
      if (it == b.joint_targets.end()) p.fail("joint", "no [[joint]] named '" + probe.joint + "'");
      probe.on_body = it->second.on_body;
      probe.target = it->second.index;
      probe.node = it->second.node;
      label = probe.joint;
    } else {
      probe.kind = Probe::Kind::drive;
      std::tie(label, probe.target) = lookup(p, "drive", b.names.drives, "drive");
    }
    probe.label = p.string_or("label", label);
    for (const Probe& q : s.probes)
      if (q.label == probe.label)
        p.fail("label", "two probes with the label '" + probe.label + "' (set label = \"...\")");
    p.finish();
    s.probes.push_back(probe);
  }
  t.finish();
  return s;
}

}  // namespace ancf::io
