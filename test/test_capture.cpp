// Smoke run of the capture example (studies/scenes/capture.toml, shared/CAPTURE.md): its first
// 0.5 s with both integrators through the same driver as `ancf run` and ancf-capture, with the
// event observer. In that time the ring spins up on the smooth ramp and the slack ropes follow
// without reaching the pole, so the checks are: both runs complete; the ring tracks the drive's
// reference θ_ref(t) = ω_max (t/2 − t_a/(2π) sin(πt/t_a)) (the PD error stays small against it);
// the pole has not moved; constraints hold; IDA and generalized-α agree. And the rope-as-rod
// variant (studies/scenes/capture_rod.toml) at 12 elements up to the first two ropes' contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "ancf/io/scene.hpp"
#include "ancf/io/scene_overrides.hpp"
#include "ancf/io/simulation.hpp"
#include "ancf/scenes/capture_events.hpp"

namespace ancf {
namespace {

struct SmokeRun {
  std::vector<CaptureSample> samples;
  double max_violation = 0.0;
  SimulationCounters counters;
};

// Runs `scene` to t_end with output every `interval`, recording the capture observer's samples.
SmokeRun run_scene(Scene& scene, IntegratorKind kind, double t_end, double interval,
                   bool error_controlled = false) {
  scene.integrator.kind = kind;
  scene.integrator.ga_error_controlled = error_controlled;
  scene.integrator.t_end = t_end;
  CaptureObserver observer(scene.model);
  Workspace ws(scene.model);
  SmokeRun r;
  SimulationHooks hooks;
  hooks.output = [&](const SystemState& s) {
    observer.record(s);
    r.max_violation = std::max(r.max_violation, constraint_violation(scene.model, s, ws).position);
  };
  simulate(scene.model, scene.integrator, output_times(interval, t_end), hooks, r.counters);
  r.samples = observer.samples();
  return r;
}

SmokeRun run(IntegratorKind kind, bool error_controlled = false) {
  Scene scene = load_scene(std::string(ANCF_SOURCE_DIR) + "/studies/scenes/capture.toml");
  return run_scene(scene, kind, 0.5, 0.05, error_controlled);
}

double reference_angle(double t) {
  const double omega = 12.0 * std::numbers::pi / 180.0, ta = 1.0;  // capture.toml
  return omega * (0.5 * t - ta / (2.0 * std::numbers::pi) * std::sin(std::numbers::pi * t / ta));
}

TEST(CaptureSmoke, FirstHalfSecondWithBothIntegrators) {
  const SmokeRun ga = run(IntegratorKind::genalpha), ida = run(IntegratorKind::ida);
  ASSERT_EQ(ga.samples.size(), 11u);
  ASSERT_EQ(ida.samples.size(), 11u);
  double tracking = 0.0, agreement = 0.0, tilt_change = 0.0;
  for (std::size_t k = 0; k < ga.samples.size(); ++k) {
    const CaptureSample &g = ga.samples[k], &i = ida.samples[k];
    EXPECT_EQ(g.t, i.t);
    tracking = std::max({tracking, std::abs(g.ring_angle - reference_angle(g.t)),
                         std::abs(i.ring_angle - reference_angle(i.t))});
    agreement = std::max(agreement, std::abs(g.ring_angle - i.ring_angle));
    tilt_change = std::max({tilt_change, std::abs(g.tilt - ga.samples[0].tilt),
                            std::abs(i.tilt - ida.samples[0].tilt)});
    for (int r = 0; r < 3; ++r)
      EXPECT_FALSE(g.rope_on_pole[r] || i.rope_on_pole[r]) << "t = " << g.t;
  }
  const double final_angle = ga.samples.back().ring_angle;
  std::printf("  ring angle at 0.5 s: genalpha %.6e rad, IDA %.6e rad, reference %.6e rad\n",
              final_angle, ida.samples.back().ring_angle, reference_angle(0.5));
  std::printf(
      "  max |theta - theta_ref| %.3e rad, max |theta_GA - theta_IDA| %.3e rad, max tilt change "
      "%.3e rad\n",
      tracking, agreement, tilt_change);
  std::printf("  max |Phi|: genalpha %.3e, IDA %.3e\n", ga.max_violation, ida.max_violation);
  for (const auto* c : {&ga.counters, &ida.counters})
    for (const auto& [name, value] : *c) std::printf("    %s %ld\n", name.c_str(), value);
  // The PD drive (K_p = 100 N m/rad) holds the ring on its reference to a small fraction of the
  // angle turned; the two integrators agree to well within that.
  EXPECT_LT(tracking, 0.01 * reference_angle(0.5));
  EXPECT_LT(agreement, 0.1 * tracking + 1e-6);
  EXPECT_LT(tilt_change, 1e-6);  // nothing touches the pole yet
  EXPECT_LT(ga.max_violation, 1e-8);
  EXPECT_LT(ida.max_violation, 1e-8);
}

// Error-controlled generalized-α (docs/time_step_control.md) over the same half second: it lands
// on the same output times, tracks the drive as the fixed step does, holds the constraints, and
// takes fewer steps than the fixed h = 1e-3 (the error allows larger ones in the slack phase).
TEST(CaptureSmoke, ErrorControlledGeneralizedAlphaAgreesWithFixedStep) {
  const SmokeRun fixed = run(IntegratorKind::genalpha), ec = run(IntegratorKind::genalpha, true);
  ASSERT_EQ(ec.samples.size(), fixed.samples.size());
  double tracking = 0.0, agreement = 0.0;
  for (std::size_t k = 0; k < ec.samples.size(); ++k) {
    EXPECT_EQ(ec.samples[k].t, fixed.samples[k].t);
    tracking = std::max(
        tracking, std::abs(fixed.samples[k].ring_angle - reference_angle(fixed.samples[k].t)));
    agreement =
        std::max(agreement, std::abs(ec.samples[k].ring_angle - fixed.samples[k].ring_angle));
  }
  auto counter = [](const SmokeRun& r, const std::string& name) {
    for (const auto& [n, v] : r.counters)
      if (n == name) return v;
    return -1L;
  };
  std::printf(
      "  error-controlled: %ld steps (fixed %ld), %ld rejected; max |theta_ec - theta_fixed| %.3e "
      "rad\n",
      counter(ec, "steps"), counter(fixed, "steps"), counter(ec, "rejected steps"), agreement);
  EXPECT_LT(agreement, 0.1 * tracking + 1e-6);
  EXPECT_LT(ec.max_violation, 1e-8);
  EXPECT_LT(counter(ec, "steps"), counter(fixed, "steps"));
}

// The rod capture (studies/scenes/capture_rod.toml: Kirchhoff-rod ropes clamped into both rings
// including twist, IDA with position-equivalent slope and twist tolerances) at 12 elements per
// rope up to 4.98 s: ropes 2 and 3 reach the shaft (at ≈ 4.81 and 4.93 s), rope 1 not yet. Both
// integrators must see the same first contacts within issue 16's 0.05 s, and the rope–pole gaps
// and the pole's tilt within a tenth of its mesh checks (0.5 mm, 0.1°): the integrators must agree
// far better than the meshes (measured: 0.002 mm, events identical or one 0.01 s output apart).
TEST(CaptureSmoke, RodRopesReachThePoleAlikeWithBothIntegrators) {
  std::vector<SceneOverride> twelve;
  for (int r = 0; r < 3; ++r) twelve.push_back({"rod[" + std::to_string(r) + "].elements", "12"});
  for (int c = 6; c < 9; ++c)  // the rope–rope pairs: the middle halves of 12-element ropes
    for (const char* key : {"elements", "other_elements"})
      twelve.push_back({"contact[" + std::to_string(c) + "]." + key, "[3, 6]"});
  const std::string path = std::string(ANCF_SOURCE_DIR) + "/studies/scenes/capture_rod.toml";
  Scene for_ga = load_scene(path, twelve), for_ida = load_scene(path, twelve);
  const SmokeRun ga = run_scene(for_ga, IntegratorKind::genalpha, 4.98, 0.01);
  const SmokeRun ida = run_scene(for_ida, IntegratorKind::ida, 4.98, 0.01);
  ASSERT_EQ(ga.samples.size(), ida.samples.size());
  double gap = 0.0, tilt = 0.0;
  std::array<double, 3> first_ga{-1, -1, -1}, first_ida{-1, -1, -1};
  for (std::size_t k = 0; k < ga.samples.size(); ++k) {
    const CaptureSample &g = ga.samples[k], &i = ida.samples[k];
    EXPECT_EQ(g.t, i.t);
    tilt = std::max(tilt, std::abs(g.tilt - i.tilt));
    for (int r = 0; r < 3; ++r) {
      gap = std::max(gap, std::abs(g.rope_pole_gap[r] - i.rope_pole_gap[r]));
      if (first_ga[r] < 0 && g.rope_on_pole[r]) first_ga[r] = g.t;
      if (first_ida[r] < 0 && i.rope_on_pole[r]) first_ida[r] = i.t;
    }
  }
  std::printf("  first contacts (genalpha / IDA): rope 2 %.2f / %.2f s, rope 3 %.2f / %.2f s\n",
              first_ga[1], first_ida[1], first_ga[2], first_ida[2]);
  std::printf("  max |gap_GA - gap_IDA| %.3e m, max |tilt_GA - tilt_IDA| %.3e rad\n", gap, tilt);
  std::printf("  max |Phi|: genalpha %.3e, IDA %.3e\n", ga.max_violation, ida.max_violation);
  for (const auto* c : {&ga.counters, &ida.counters})
    for (const auto& [name, value] : *c)
      if (name == "steps") std::printf("    steps %ld\n", value);
  EXPECT_LT(first_ga[0], 0.0);  // rope 1 arrives at ≈ 5.97 s
  EXPECT_LT(first_ida[0], 0.0);
  for (int r = 1; r < 3; ++r) {
    ASSERT_GT(first_ga[r], 4.5) << "rope " << r + 1;
    ASSERT_GT(first_ida[r], 4.5) << "rope " << r + 1;
    EXPECT_LE(std::abs(first_ga[r] - first_ida[r]), 0.05 + 1e-9) << "rope " << r + 1;
  }
  EXPECT_LT(gap, 0.05e-3);                           // 0.05 mm
  EXPECT_LT(tilt, 0.01 * std::numbers::pi / 180.0);  // 0.01°
  EXPECT_LT(ga.max_violation, 1e-8);
  // IDA (GGL, index 2) holds Φ = 0 to its Newton tolerance, rtol on the scene's 0.3 m extent
  // (measured 1.1e-8 m, with unit twist tolerances too).
  EXPECT_LT(ida.max_violation, for_ida.integrator.rtol * 0.3);
}

}  // namespace
}  // namespace ancf
