// Micro-benchmarks of the contact kernels (physics/contact_law.hpp, contact_shapes.hpp,
// cable_contact.hpp): the penalty law, one cable sample against a sphere, a plane and a capped
// cylinder (on ground, and the cylinder also on a rigid body, whose 12 coordinates are unknowns),
// the closest-point projection onto an element and one cable–cable sample (projection + kernel).
// Each kernel is timed with the force only (what the residual needs) and with ∂Q/∂P, ∂Q/∂V (what
// the iteration matrix needs).
//
// Geometry: one element of length 0.1 m along +x, slightly bent (so the projection and the normal
// are not trivial), cross-section radius 5 mm, sample at ξ = 0.4 (x ≈ (0.04, 0, 0)); every shape
// is placed so that the sample penetrates by 1 mm, on the linear branch of the law (δ > δ_s), and
// the sample slides tangentially, so the Hunt–Crossley and friction terms are evaluated too. A
// benchmark whose sample is not in contact stops with an error instead of timing the inactive
// path.
#include <benchmark/benchmark.h>

#include "ancf/physics/cable_contact.hpp"
#include "ancf/physics/hermite_shape.hpp"

namespace {

using ancf::ContactLaw;
using ancf::ContactSampleResult;
using ancf::ContactShape;
using ancf::Vec12;
using ancf::Vec3;

constexpr double kLength = 0.1, kRadius = 0.005, kXi = 0.4;
constexpr double kPenetration = 1e-3;  // [m], > onset depth: linear branch

ContactLaw law() {
  ContactLaw l;
  l.stiffness = 1e6;  // [N/m²]
  l.onset_depth = 1e-4;
  l.damping = 1.0;  // c_HC [s/m]
  l.friction = 0.3;
  return l;
}

// Element a: from the origin along +x with slopes tilted ±0.05 rad in z (a shallow arc).
Vec12 element_a() {
  Vec12 e;
  e << 0, 0, 0, 1, 0, 0.05, kLength, 0, 0, 1, 0, -0.05;
  return e;
}

// Sliding along +x (tangential) and moving into the shapes below it (−z).
Vec12 velocity_a() {
  Vec12 v;
  v << 0.2, 0.01, -0.05, 0, 0, 0.01, 0.2, 0.01, -0.05, 0, 0, -0.01;
  return v;
}

ancf::CableSample sample() {
  ancf::CableSample s;
  s.e = element_a();
  s.e_dot = velocity_a();
  s.length = kLength;
  s.xi = kXi;
  s.radius = kRadius;
  s.weight = kLength / 3.0;  // three samples per element
  return s;
}

// Centreline point of element a at ξ: r = Σ_k S_k(ξ) e_k.
Vec3 sample_point() {
  const ancf::Vec4 shape = ancf::hermite::values(kXi, kLength);
  const Vec12 e = element_a();
  Vec3 r = Vec3::Zero();
  for (int k = 0; k < 4; ++k) r += shape[k] * e.segment<3>(3 * k);
  return r;
}

// Shapes below the sample point p whose surface lies kRadius − kPenetration below p.
ContactShape shape(int kind) {
  const Vec3 p = sample_point();
  const double surface = kRadius - kPenetration;  // distance from p to the surface
  switch (kind) {
    case 0:  // sphere of radius 0.5 m
      return ancf::SphereShape{p - Vec3(0, 0, 0.5 + surface), 0.5};
    case 1:  // plane
      return ancf::PlaneShape{p - Vec3(0, 0, surface), Vec3::UnitZ()};
    default:  // capped cylinder, axis along y, radius 0.2 m, half-length 0.5 m: side contact
      return ancf::CappedCylinderShape{p - Vec3(0, 0, 0.2 + surface), Vec3::UnitY(), 0.2, 0.5};
  }
}

// Owner pose: ground (no unknowns) or a rigid body at the origin with the identity rotation,
// translating and spinning slowly (its 12 coordinates are unknowns: P = [e; q_b]).
ancf::ShapeOwnerPose owner(bool body) {
  ancf::ShapeOwnerPose pose;
  if (body) {
    pose.is_body = true;
    pose.origin_velocity = Vec3(0.0, 0.02, 0.01);
    const Vec3 w(0.0, 0.0, 0.3);  // Ȧ = [ω]× A
    pose.rotation_rate << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  }
  return pose;
}

// ContactLaw::pressure at three penetrations (none, onset, linear): the branchy scalar kernel.
void BM_ContactLawPressure(benchmark::State& state) {
  const ContactLaw l = law();
  double depth[3] = {-1e-3, 0.5 * l.onset_depth, kPenetration};
  for (auto _ : state) {
    benchmark::DoNotOptimize(depth);
    for (const double d : depth) benchmark::DoNotOptimize(l.pressure(d));
  }
  state.SetItemsProcessed(3 * state.iterations());
}

// One sample against a shape: `kind` 0 sphere, 1 plane, 2 capped cylinder.
void BM_CableShapeContact(benchmark::State& state, int kind, bool body, bool jacobians) {
  const ContactLaw l = law();
  const ContactShape s = shape(kind);
  const ancf::ShapeOwnerPose pose = owner(body);
  ancf::CableSample smp = sample();
  ContactSampleResult out;
  if (!ancf::evaluate_cable_shape_contact(l, s, pose, smp, jacobians, out)) {
    state.SkipWithError("sample not in contact: the benchmark would time the inactive path");
    return;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(smp);
    benchmark::DoNotOptimize(ancf::evaluate_cable_shape_contact(l, s, pose, smp, jacobians, out));
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["gap_mm"] = 1e3 * out.gap;
}

// Element b: crossing over element a along +y at x = sample point's x, its centreline
// 2 kRadius − kPenetration above the sample point (so the two cross-sections overlap by 1 mm).
Vec12 element_b() {
  const Vec3 p = sample_point() + Vec3(0.0, 0.0, 2 * kRadius - kPenetration);
  Vec12 e;
  e << p - Vec3(0, 0.05, 0), Vec3(0, 1, 0), p + Vec3(0, 0.05, 0), Vec3(0, 1, 0);
  return e;
}

// Closest point of element b to the sample point (coarse sampling + safeguarded Newton).
void BM_ProjectOntoElement(benchmark::State& state) {
  Vec12 e = element_b();
  Vec3 x = sample_point();
  ancf::ElementProjection p;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e);
    benchmark::DoNotOptimize(x);
    p = ancf::project_onto_element(e, kLength, x);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["xi"] = p.xi;
}

// One cable–cable sample as the assembly does it: projection of the sample point onto element b,
// then the kernel at that ξ_b.
void BM_CableCableContact(benchmark::State& state, bool jacobians) {
  const ContactLaw l = law();
  ancf::CableSample smp = sample();
  Vec12 e_b = element_b();
  const Vec12 e_b_dot = Vec12::Zero();
  Vec3 x = sample_point();
  ContactSampleResult out;
  {
    const double xi_b = ancf::project_onto_element(e_b, kLength, x).xi;
    if (!ancf::evaluate_cable_cable_contact(l, smp, e_b, e_b_dot, kLength, kRadius, xi_b, jacobians,
                                            out)) {
      state.SkipWithError("samples not in contact: the benchmark would time the inactive path");
      return;
    }
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(smp);
    benchmark::DoNotOptimize(e_b);
    benchmark::DoNotOptimize(x);
    const double xi_b = ancf::project_onto_element(e_b, kLength, x).xi;
    benchmark::DoNotOptimize(ancf::evaluate_cable_cable_contact(l, smp, e_b, e_b_dot, kLength,
                                                                kRadius, xi_b, jacobians, out));
    benchmark::DoNotOptimize(out);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["gap_mm"] = 1e3 * out.gap;
}

}  // namespace

BENCHMARK(BM_ContactLawPressure);
BENCHMARK_CAPTURE(BM_CableShapeContact, sphere_force, 0, false, false);
BENCHMARK_CAPTURE(BM_CableShapeContact, sphere_jacobians, 0, false, true);
BENCHMARK_CAPTURE(BM_CableShapeContact, plane_force, 1, false, false);
BENCHMARK_CAPTURE(BM_CableShapeContact, plane_jacobians, 1, false, true);
BENCHMARK_CAPTURE(BM_CableShapeContact, cylinder_force, 2, false, false);
BENCHMARK_CAPTURE(BM_CableShapeContact, cylinder_jacobians, 2, false, true);
BENCHMARK_CAPTURE(BM_CableShapeContact, cylinder_on_body_force, 2, true, false);
BENCHMARK_CAPTURE(BM_CableShapeContact, cylinder_on_body_jacobians, 2, true, true);
BENCHMARK(BM_ProjectOntoElement);
BENCHMARK_CAPTURE(BM_CableCableContact, force, false);
BENCHMARK_CAPTURE(BM_CableCableContact, jacobians, true);
