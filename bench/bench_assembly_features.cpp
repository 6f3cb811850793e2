// "A scene pays only for what it has": assemble_residual and assemble_iteration_matrix of one
// 200-element cable (pinned at node 0, deformed, moving) with one model feature switched on at a
// time, so the cost of each feature shows as the difference to the bare cable.
//
// Variants (each is variant 1 plus one thing):
//   1 axial           the paper's element: Green strain, EI = 0, no damping, no gravity, no
//                     bodies, no force elements;
//   2 bending         + EI > 0 (Gerstmayr–Shabana curvature at every Gauss point);
//   3 damping         + Kelvin–Voigt axial damping c_a > 0 (c_b = 0, so still no bending path);
//   4 gravity         + gravity: a constant load folded into Model::constant_load() at finalize();
//   5 remote_body     + one rigid body far from the cable, spherical joint to ground, and one
//                     spring-damper body–ground: features present, but not on the cable;
//   6 hanging_bodies  + 50 rigid bodies, each hung from ground on a spring-damper (features scale);
//   7 second_cable    + a second 200-element cable and a free rigid drum, both 50 m away;
//   8 far_contact     variant 7 + contact pairs that cannot touch: cable–cable (the two cables),
//                     cable–drum (capped cylinder on the body), both cables against a ground plane
//                     100 m below (friction and Hunt–Crossley damping on);
//   9 far_contact_local  variant 8 with the cable–cable pair restricted to 20 candidate elements of
//                     each cable (ElementRange), as a scene would declare a local contact zone.
//
// Expected outcome (what the table must show for the claim to hold):
//   * variant 1 ≈ 200 × the element kernel (BM_ElementForce/green_axial for the residual,
//     BM_ElementForceTangent/green_axial for the matrix) + a small scatter overhead; the
//     BM_FeaturesKernelSweep cases time exactly those 200 kernel calls without any scatter, so
//     assembly − sweep is the whole overhead;
//   * variants 4 and 5 cost the same as 1 within noise: they add O(1) work (4 adds nothing at all
//     — the constant load is subtracted in both cases —, 5 adds 9 constraint rows, one 12×12 mass
//     block and one spring);
//   * 2 and 3 cost more, and exactly because their kernels run: their extra time over 1 matches
//     the extra time of their kernel sweep over the axial sweep (×200), the scatter is unchanged;
//   * the residual of 8 and 9 costs about the same as 7 (the broad phase: element boxes refreshed
//     per call, whole-cable boxes cull every pair, no sample reaches a narrow-phase kernel);
//   * the matrix of 8 costs more than 7 by the zeroing of the reserved coupling blocks: the full
//     200 × 200 element cable–cable pair reserves 2·144·200² ≈ 2.9M entries (the price of a fixed
//     pattern, paid also by KLU); 9 reserves 2·144·20² and costs about the same as 7.
//   * 6 costs more in proportion to the 50 bodies (6 orthonormality rows + 1 spring + 1 mass block
//     each); the per-body cost is (t6 − t1)/50 and is independent of the cable.
// The benchmarks report s_per_element = time / 200 cable elements (also for 5 and 6, where it then
// includes the non-cable work). The deterministic part of the claim (velocities and the w_v
// weight are never read for an undamped cable, curvature is never evaluated for EI = 0, loads do
// not touch the matrix) is checked exactly in test/test_assembly_cost.cpp.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ancf/system/assembly.hpp"
#include "ancf/system/model_builder.hpp"

namespace {

using ancf::Index;
using ancf::Mat3;
using ancf::Vec3;
using ancf::VecX;

enum class Variant {
  axial,
  bending,
  damping,
  gravity,
  remote_body,
  hanging_bodies,
  second_cable,
  far_contact,
  far_contact_local
};

constexpr Index kElements = 200;
constexpr double kElementLength = 0.1;  // [m], as in bench_cable_element.cpp
constexpr int kHangingBodies = 50;

// The section of bench_cable_element.cpp (steel-like thin rope), with the variant's feature.
ancf::CableSection section_for(Variant v) {
  ancf::CableSection s;
  s.axial_stiffness = 4e6;  // EA [N]
  s.mass_per_length = 0.15;
  if (v == Variant::bending) s.bending_stiffness = 6.0;  // EI [N m²]
  if (v == Variant::damping) s.axial_damping = 40.0;     // c_a [N s]
  s.radius = 0.005;                                      // only read by contact pairs [m]
  return s;
}

ancf::RigidBodyInertia box(double m, const Vec3& size) {
  ancf::RigidBodyInertia in;
  in.mass = m;
  const double x2 = size.x() * size.x(), y2 = size.y() * size.y(), z2 = size.z() * size.z();
  in.inertia = (m / 12.0 * Vec3(y2 + z2, x2 + z2, x2 + y2)).asDiagonal();
  return in;
}

// Reference: straight along +x from the origin, 200 elements of 0.1 m. Initial configuration: the
// reference stretched by 1 %, given a helical wave (amplitude 5 cm, wavelength 5 m: curvature
// ~0.08 /m everywhere, so no κ = 0 shortcut is taken) and rotated by 0.2 rad about an oblique axis
// through node 0, which the pin holds at the origin. Small random nodal velocities (fixed seed),
// so the Kelvin–Voigt terms of the damped variant are really evaluated.
ancf::Model features_scene(Variant v) {
  ancf::ModelBuilder b;
  const ancf::CableGeometry reference =
      ancf::straight_cable(Vec3::Zero(), Vec3(kElements * kElementLength, 0.0, 0.0), kElements);
  const Index cable = b.add_cable("cable", reference, section_for(v));

  const Mat3 rot = Eigen::AngleAxisd(0.2, Vec3(0.3, 1.0, 0.2).normalized()).toRotationMatrix();
  const double amp = 0.05, k = 2.0 * std::numbers::pi / 5.0;
  ancf::CableGeometry current = reference;
  std::vector<ancf::NodeCoordinates> velocities(current.nodes.size());
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  for (std::size_t n = 0; n < current.nodes.size(); ++n) {
    const double s = static_cast<double>(n) * kElementLength;
    const Vec3 r(1.01 * s, amp * std::sin(k * s), amp * (1.0 - std::cos(k * s)));
    const Vec3 r_x(1.01, amp * k * std::cos(k * s), amp * k * std::sin(k * s));
    current.nodes[n] << rot * r, rot * r_x;
    for (int i = 0; i < 6; ++i) velocities[n][i] = u(rng);
  }
  velocities[0].head<3>().setZero();  // consistent with the pin
  b.set_initial_configuration(cable, current, &velocities);
  b.pin("pin", {cable, 0}, Vec3::Zero());

  if (v == Variant::gravity) b.set_gravity(Vec3(0.0, 0.0, -9.81));
  if (v == Variant::remote_body) {
    const Vec3 at(50.0, 50.0, 50.0);
    const Index body = b.add_body("remote", box(2.0, Vec3(0.2, 0.1, 0.1)), at, Mat3::Identity(),
                                  Vec3(0.1, -0.2, 0.0), Vec3(0.3, 0.1, -0.5));
    b.spherical_to_ground("remote ball", body, at + Vec3(0.1, 0.0, 0.0));
    b.add_spring_damper("remote spring", ancf::BodyPoint{body, Vec3(-0.1, 0.05, 0.0)},
                        ancf::GroundPoint{at + Vec3(-0.1, 0.05, 1.0)}, 300.0, 2.0);
  }
  if (v == Variant::hanging_bodies) {
    for (int i = 0; i < kHangingBodies; ++i) {
      const std::string name = "hanging " + std::to_string(i);
      const Vec3 at(0.5 * i, 5.0, -3.0);
      const Index body = b.add_body(name, box(1.0, Vec3(0.1, 0.1, 0.2)), at, Mat3::Identity(),
                                    Vec3(0.01 * i, 0.0, -0.1), Vec3(0.0, 0.2, 0.01 * i));
      b.add_spring_damper(name + " spring", ancf::BodyPoint{body, Vec3(0.0, 0.0, 0.1)},
                          ancf::GroundPoint{at + Vec3(0.0, 0.0, 1.1)}, 500.0, 5.0);
    }
  }
  if (v == Variant::second_cable || v == Variant::far_contact || v == Variant::far_contact_local) {
    const Index other = b.add_cable(
        "far cable", ancf::straight_cable(Vec3(0.0, 50.0, 0.0), Vec3(20.0, 50.0, 0.0), kElements),
        section_for(v));
    const Index drum = b.add_body("far drum", box(5.0, Vec3(0.3, 0.3, 1.0)), Vec3(10.0, -50.0, 0.0),
                                  Mat3::Identity(), Vec3(0.0, 0.1, 0.0), Vec3(0.0, 0.0, 0.5));
    if (v == Variant::far_contact || v == Variant::far_contact_local) {
      ancf::ContactLaw law;
      law.stiffness = 1e6;
      law.onset_depth = 1e-4;
      law.damping = 1.0;
      law.friction = 0.3;
      const Index cylinder = b.add_body_shape(
          "drum surface", drum, ancf::CappedCylinderShape{Vec3::Zero(), Vec3::UnitZ(), 0.15, 0.5});
      const Index floor =
          b.add_ground_shape("floor", ancf::PlaneShape{Vec3(0.0, 0.0, -100.0), Vec3::UnitZ()});
      if (v == Variant::far_contact)
        b.add_cable_cable_contact("cables", cable, other, law, 3);
      else
        b.add_cable_cable_contact("cables", cable, other, law, 3, {180, 20}, {0, 20});
      b.add_cable_shape_contact("cable-drum", cable, cylinder, law, 3);
      b.add_cable_shape_contact("cable-floor", cable, floor, law, 3);
      b.add_cable_shape_contact("far cable-floor", other, floor, law, 3);
    }
  }
  return b.finalize();
}

// The model, the state (initial q, v; random accelerations and multipliers, so the mass products
// and the multiplier terms do their work) and a workspace, all built outside the timed loop.
struct Setup {
  ancf::Model model;
  ancf::SystemState state;
  ancf::Workspace ws;

  explicit Setup(Variant v)
      : model(features_scene(v)), state(ancf::SystemState::initial(model)), ws(model) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (Index i = 0; i < model.coordinate_count(); ++i) state.a[i] = u(rng);
    for (Index i = 0; i < model.multiplier_count(); ++i) state.lambda[i] = 10.0 * u(rng);
  }
};

// Generalized-α-like weights (1, γ/(βh), 1/(βh²)) for h = 1 ms, γ = 0.6, β = (γ + ½)²/4.
ancf::IterationWeights dynamic_weights() {
  const double h = 1e-3, gamma = 0.6, beta = 0.25 * (gamma + 0.5) * (gamma + 0.5);
  return {.w_q = 1.0, .w_v = gamma / (beta * h), .w_a = 1.0 / (beta * h * h), .load_factor = 1.0};
}

void set_counters(benchmark::State& state, const ancf::Model& model) {
  state.SetItemsProcessed(state.iterations() * kElements);
  state.counters["s_per_element"] = benchmark::Counter(
      static_cast<double>(kElements),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["bodies"] = static_cast<double>(model.bodies().size());
  state.counters["unknowns"] = static_cast<double>(model.system_size());
}

// M a + F(q, v) − Q_loads − Q_elements + Φ_qᵀλ and Φ(q, t).
void BM_FeaturesResidual(benchmark::State& state, Variant v) {
  Setup s(v);
  VecX r(s.model.system_size());
  for (auto _ : state) {
    ancf::assemble_residual(s.model, s.state, 1.0, s.ws, ancf::as_span(r));
    benchmark::DoNotOptimize(r.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, s.model);
}

// [w_q K + w_v D + w_a M, Φ_qᵀ; Φ_q, 0] with the generalized-α weights.
void BM_FeaturesMatrix(benchmark::State& state, Variant v) {
  Setup s(v);
  const ancf::IterationWeights w = dynamic_weights();
  VecX values(s.model.pattern().nonzeros());
  for (auto _ : state) {
    ancf::assemble_iteration_matrix(s.model, s.state, w, s.ws, ancf::as_span(values));
    benchmark::DoNotOptimize(values.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, s.model);
  state.counters["nonzeros"] = static_cast<double>(values.size());
}

// The 200 evaluate_cable_element calls the assembly makes (same section, coordinates,
// velocities and request), without any scatter: the pure kernel share of the two cases above.
// `matrix` selects the iteration-matrix request (stiffness + damping matrix) over force only.
void BM_FeaturesKernelSweep(benchmark::State& state, Variant v, bool matrix) {
  Setup s(v);
  const ancf::CableData& c = s.model.cables()[0];
  std::vector<ancf::Vec12> e(c.elements.size()), e_dot(c.elements.size());
  for (std::size_t j = 0; j < c.elements.size(); ++j) {
    const Index base = c.first_coordinate + 6 * static_cast<Index>(j);
    e[j] = s.state.q.segment<12>(base);
    // The assembly passes zero velocities to an undamped section (they are not read then).
    e_dot[j] =
        c.section.has_damping() ? ancf::Vec12(s.state.v.segment<12>(base)) : ancf::Vec12::Zero();
  }
  const ancf::CableEvalRequest request{.stiffness = matrix, .damping_matrix = matrix};
  ancf::CableElementResult out;
  for (auto _ : state) {
    for (std::size_t j = 0; j < e.size(); ++j) {
      ancf::evaluate_cable_element(c.section, c.elements[j], e[j], e_dot[j], request, out);
      benchmark::DoNotOptimize(out);
    }
    benchmark::ClobberMemory();
  }
  set_counters(state, s.model);
}

}  // namespace

BENCHMARK_CAPTURE(BM_FeaturesResidual, 1_axial, Variant::axial)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 2_bending, Variant::bending)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 3_damping, Variant::damping)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 4_gravity, Variant::gravity)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 5_remote_body, Variant::remote_body)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 6_hanging_bodies, Variant::hanging_bodies)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 7_second_cable, Variant::second_cable)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 8_far_contact, Variant::far_contact)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesResidual, 9_far_contact_local, Variant::far_contact_local)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK_CAPTURE(BM_FeaturesMatrix, 1_axial, Variant::axial)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 2_bending, Variant::bending)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 3_damping, Variant::damping)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 4_gravity, Variant::gravity)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 5_remote_body, Variant::remote_body)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 6_hanging_bodies, Variant::hanging_bodies)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 7_second_cable, Variant::second_cable)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 8_far_contact, Variant::far_contact)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesMatrix, 9_far_contact_local, Variant::far_contact_local)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK_CAPTURE(BM_FeaturesKernelSweep, residual_1_axial, Variant::axial, false)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesKernelSweep, residual_2_bending, Variant::bending, false)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesKernelSweep, residual_3_damping, Variant::damping, false)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesKernelSweep, matrix_1_axial, Variant::axial, true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesKernelSweep, matrix_2_bending, Variant::bending, true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_FeaturesKernelSweep, matrix_3_damping, Variant::damping, true)
    ->Unit(benchmark::kMicrosecond);
