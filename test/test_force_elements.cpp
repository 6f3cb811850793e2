// Force elements (force_elements.hpp, DESIGN §4 loads): every analytic ∂Q/∂q and ∂Q/∂v is checked
// against central differences with the error-estimated tolerance of fd_check.hpp, at seeded random
// configurations in a global q of three entities (a 6-coordinate cable node at 0, body 1 at 6,
// body 2 at 18), so the scatter through the BlockList is exercised. Derivative checks use
// non-orthonormal (perturbed) body coordinates: the formulas must hold for any q. The physical
// properties (virtual work of the torque, drive angle, rate and torque law) are checked at exactly
// rigid configurations.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "ancf/physics/force_elements.hpp"
#include "ancf/physics/rigid_body.hpp"
#include "fd_check.hpp"
#include "random_geometry.hpp"

// ---- Allocation counter -------------------------------------------------------------------------
// evaluate() must not touch the heap. Eigen allocates with std::malloc and operator new ends in
// malloc, so counting malloc calls (forwarded to glibc's) catches both. Only with glibc and
// without AddressSanitizer, which intercepts malloc itself.
#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#if defined(__has_feature)
#if !__has_feature(address_sanitizer)
#define ANCF_COUNT_MALLOC 1
#endif
#else
#define ANCF_COUNT_MALLOC 1
#endif
#endif

#ifdef ANCF_COUNT_MALLOC
namespace {
bool g_count_malloc = false;
long g_malloc_calls = 0;
}  // namespace
extern "C" void* __libc_malloc(std::size_t size);  // NOLINT: glibc's allocator entry point
extern "C" void* malloc(std::size_t size) {        // NOLINT: interposes glibc's malloc
  if (g_count_malloc) ++g_malloc_calls;
  return __libc_malloc(size);
}
#endif

namespace {
using namespace ancf;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = std::numbers::pi;

// Global layout: node (r, r_x) at 0, body 1 at 6, body 2 at 18.
constexpr Index kNode = 0, kBody1 = 6, kBody2 = 18, kDofs = 30;
constexpr int kSeeds = 20;

using random_geometry::random_rotation;
using random_geometry::random_vec3;

Vec3 random_unit(std::mt19937& rng) {
  return random_vec3(rng, 1.0).normalized();
}

Vec3 random_perpendicular_unit(std::mt19937& rng, const Vec3& axis) {
  const Vec3 r = random_vec3(rng, 1.0);
  return (r - r.dot(axis) * axis).normalized();
}

double uniform(std::mt19937& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// A rigid configuration of the three entities, and one perturbed off the rigid manifold.
VecX rigid_q(std::mt19937& rng, const Mat3& r1, const Mat3& r2) {
  VecX q(kDofs);
  q.segment<3>(kNode) = random_vec3(rng, 0.5);
  q.segment<3>(kNode + 3) = random_unit(rng);
  q.segment<12>(kBody1) = body_coordinates(random_vec3(rng, 0.5), r1);
  q.segment<12>(kBody2) = body_coordinates(random_vec3(rng, 0.5), r2);
  return q;
}
VecX perturbed(std::mt19937& rng, const VecX& x, double scale) {
  std::normal_distribution<double> n(0.0, scale);
  VecX y = x;
  for (Index i = 0; i < y.size(); ++i) y[i] += n(rng);
  return y;
}
VecX random_v(std::mt19937& rng, double scale) {
  return perturbed(rng, VecX::Zero(kDofs), scale);
}

std::span<const double> span_of(const VecX& x) {
  return as_span(x);
}

// ---- Global scatter of element results ----------------------------------------------------------

struct Global {
  VecX force;
  MatX dq, dv;
};

Global scatter(const BlockList& blocks, const ForceResult& r) {
  Global g{VecX::Zero(kDofs), MatX::Zero(kDofs, kDofs), MatX::Zero(kDofs, kDofs)};
  EXPECT_EQ(r.force.size(), 3 * blocks.count);
  for (int i = 0; i < blocks.count; ++i) {
    g.force.segment<3>(blocks.blocks[i]) += r.force.segment<3>(3 * i);
    for (int j = 0; j < blocks.count; ++j) {
      g.dq.block<3, 3>(blocks.blocks[i], blocks.blocks[j]) +=
          r.d_force_dq.block<3, 3>(3 * i, 3 * j);
      g.dv.block<3, 3>(blocks.blocks[i], blocks.blocks[j]) +=
          r.d_force_dv.block<3, 3>(3 * i, 3 * j);
    }
  }
  return g;
}

using GlobalFunction = std::function<Global(const VecX& q, const VecX& v)>;

fdcheck::Result check_dq(const GlobalFunction& fn, const VecX& q, const VecX& v) {
  const fdcheck::Function f = [&](const VecX& x) { return VecX(fn(x, v).force); };
  return fdcheck::check_jacobian(f, q, fn(q, v).dq);
}
fdcheck::Result check_dv(const GlobalFunction& fn, const VecX& q, const VecX& v) {
  const fdcheck::Function f = [&](const VecX& x) { return VecX(fn(q, x).force); };
  return fdcheck::check_jacobian(f, v, fn(q, v).dv);
}

std::string describe(const fdcheck::Result& r) {
  char buf[200];
  std::snprintf(
      buf, sizeof buf, "worst entry (%ld,%ld): analytic %.9g, fd %.9g, tol %.3g, ratio %.3g",
      static_cast<long>(r.row), static_cast<long>(r.col), r.analytic, r.fd, r.tol, r.max_ratio);
  return buf;
}

void print_table(const char* what, const std::map<std::string, fdcheck::Result>& worst) {
  std::printf("%s: max |fd-analytic|/tol, max |fd-analytic|/max|J|, max tol/max|J|\n", what);
  for (const auto& [label, r] : worst)
    std::printf("  %-44s %8.2e %8.2e %8.2e\n", label.c_str(), r.max_ratio, r.max_rel,
                r.max_tol_rel);
}

/// Worst ratio of a plain error/tolerance check, printed like the FD tables.
struct Worst {
  std::map<std::string, double> ratio;
  void add(const std::string& label, double error, double tolerance) {
    EXPECT_LE(error, tolerance) << label;
    ratio[label] = std::max(ratio[label], error / tolerance);
  }
  void print(const char* what) const {
    std::printf("%s: max error/tolerance\n", what);
    for (const auto& [label, r] : ratio) std::printf("  %-44s %8.2e\n", label.c_str(), r);
  }
};

// ---- Spring-damper ------------------------------------------------------------------------------

struct SpringCase {
  std::string label;
  SpringDamper spring;
  DrivenFrame frame;
  bool has_frame = false;
  VecX q, v;
  double t = 0.0;
  [[nodiscard]] std::vector<FrameKinematics> frames_at(double time) const {
    if (!has_frame) return {};
    return {frame.at(time)};
  }
};

Vec3 point_of(const AffineVector& p, const VecX& q, const std::vector<FrameKinematics>& frames) {
  return evaluate(p, span_of(q), {}, frames).value;
}

// Three springs: cable node – body-1 point, body-2 point – point of a rotating driven frame, and
// two points of body 1 (the two ends share blocks). Positions are laid out ~0.6 m apart.
std::vector<SpringCase> spring_cases() {
  std::vector<SpringCase> cases;
  std::mt19937 rng(20240611);
  for (int seed = 0; seed < kSeeds; ++seed) {
    const double k = uniform(rng, 1e3, 5e3), c = uniform(rng, 5.0, 50.0);
    {  // node – body 1
      SpringCase s;
      s.label = "node - body point";
      const Vec3 pb(0.2, -0.1, 0.15);
      s.spring.p1.add(kNode, 1.0);
      s.spring.p2.add_body(kBody1, point_weights(pb));
      s.q = perturbed(rng, rigid_q(rng, random_rotation(rng), random_rotation(rng)), 0.05);
      s.q.segment<3>(kNode) = point_of(s.spring.p2, s.q, {}) + 0.6 * random_unit(rng);
      s.v = random_v(rng, 1.0);
      s.spring.stiffness = k;
      s.spring.damping = c;
      s.spring.rest_length = uniform(rng, 0.4, 0.8);
      cases.push_back(s);
    }
    {  // body 2 – rotating frame
      SpringCase s;
      s.label = "body point - rotating frame point";
      s.has_frame = true;
      s.frame.origin = Vec3(0.1, -0.2, 0.3);
      s.frame.initial_rotation = random_rotation(rng);
      s.frame.axis = random_unit(rng);
      s.frame.law = AngleLaw::constant_rate(uniform(rng, 0.5, 2.0), uniform(rng, -1.0, 1.0));
      s.t = uniform(rng, 0.0, 3.0);
      const Vec3 pb(0.1, -0.05, 0.2);
      s.spring.p1.add_body(kBody2, point_weights(pb));
      s.spring.p2.frame = 0;
      s.spring.p2.frame_position_scale = 1.0;
      s.spring.p2.frame_vector = Vec3(0.4, 0.0, 0.1);
      s.spring.p2.offset = Vec3(0.0, 0.0, 0.01);  // exercise the constant part too
      s.q = perturbed(rng, rigid_q(rng, random_rotation(rng), random_rotation(rng)), 0.05);
      const Vec3 target = point_of(s.spring.p2, s.q, s.frames_at(s.t)) + 0.6 * random_unit(rng);
      s.q.segment<3>(kBody2) += target - point_of(s.spring.p1, s.q, {});
      s.v = random_v(rng, 1.0);
      s.spring.stiffness = k;
      s.spring.damping = c;
      s.spring.rest_length = uniform(rng, 0.4, 0.8);
      cases.push_back(s);
    }
    {  // two points of body 1
      SpringCase s;
      s.label = "two points of one body";
      s.spring.p1.add_body(kBody1, point_weights(Vec3(0.3, 0.1, -0.2)));
      s.spring.p2.add_body(kBody1, point_weights(Vec3(-0.2, 0.25, 0.1)), 1.5);
      s.q = perturbed(rng, rigid_q(rng, random_rotation(rng), random_rotation(rng)), 0.05);
      s.v = random_v(rng, 1.0);
      s.spring.stiffness = k;
      s.spring.damping = c;
      s.spring.rest_length = uniform(rng, 0.4, 0.8);
      cases.push_back(s);
    }
  }
  return cases;
}

Global spring_global(const SpringCase& s, const SpringDamper& spring, const VecX& q,
                     const VecX& v) {
  const std::vector<FrameKinematics> frames = s.frames_at(s.t);
  ForceResult r;
  evaluate(spring, span_of(q), span_of(v), frames, r);
  return scatter(blocks_of(spring), r);
}

TEST(SpringDamper, BlocksAreP1ThenP2Deduplicated) {
  SpringDamper s;
  s.p1.add(kNode, 1.0);
  s.p2.add_body(kBody1, point_weights(Vec3(0.1, 0.0, 0.3)));  // r_O, a₁, a₃ (a₂ weight 0)
  s.p2.add(kNode, 0.5);                                       // repeated block
  const BlockList b = blocks_of(s);
  ASSERT_EQ(b.count, 4);
  EXPECT_EQ(b.blocks[0], kNode);
  EXPECT_EQ(b.blocks[1], kBody1);
  EXPECT_EQ(b.blocks[2], kBody1 + 3);
  EXPECT_EQ(b.blocks[3], kBody1 + 9);
  EXPECT_EQ(b.find(kBody1 + 6), -1);
}

TEST(SpringDamper, JacobiansMatchFiniteDifferences) {
  std::map<std::string, fdcheck::Result> worst_q, worst_v;
  for (const SpringCase& s : spring_cases()) {
    const GlobalFunction fn = [&](const VecX& q, const VecX& v) {
      return spring_global(s, s.spring, q, v);
    };
    const fdcheck::Result rq = check_dq(fn, s.q, s.v);
    EXPECT_TRUE(rq.ok()) << s.label << " dQ/dq: " << describe(rq);
    worst_q[s.label].merge(rq);
    const fdcheck::Result rv = check_dv(fn, s.q, s.v);
    EXPECT_TRUE(rv.ok()) << s.label << " dQ/dv: " << describe(rv);
    worst_v[s.label].merge(rv);
  }
  print_table("spring-damper dQ/dq", worst_q);
  print_table("spring-damper dQ/dv", worst_v);
}

// Undamped: Q = −∂V/∂q, V = ½k(ℓ − ℓ₀)²; and its stiffness is symmetric.
TEST(SpringDamper, ForceIsMinusPotentialGradient) {
  std::map<std::string, fdcheck::Result> worst;
  double max_asym = 0.0;
  for (const SpringCase& s : spring_cases()) {
    SpringDamper spring = s.spring;
    spring.damping = 0.0;
    const std::vector<FrameKinematics> frames = s.frames_at(s.t);
    const auto energy = [&](const VecX& q) { return potential_energy(spring, span_of(q), frames); };
    const Global g = spring_global(s, spring, s.q, s.v);
    const fdcheck::Result r = fdcheck::check_gradient(energy, s.q, -g.force);
    EXPECT_TRUE(r.ok()) << s.label << ": " << describe(r);
    worst[s.label].merge(r);
    const double asym = (g.dq - g.dq.transpose()).norm() / g.dq.norm();
    EXPECT_LE(asym, 8 * kEps) << s.label;
    max_asym = std::max(max_asym, asym);
  }
  print_table("spring Q vs -dV/dq (undamped)", worst);
  std::printf("max ||K - K^T|| / ||K|| (undamped spring): %.2e\n", max_asym);
}

// The damping force uses ℓ̇ = dℓ/dt along q(t) = q + (t − t₀)v with the frames at t: the driven
// frame's motion counts. Tension from Q (k = 0, c = 1: f = ℓ̇) on p1's first term, whose block no
// other term shares (coefficient 1): Q = f n.
TEST(SpringDamper, LengthRateIncludesFrameMotion) {
  std::map<std::string, fdcheck::Result> worst;
  for (const SpringCase& s : spring_cases()) {
    if (s.label == "two points of one body") continue;  // p1's blocks shared with p2
    SpringDamper spring = s.spring;
    spring.stiffness = 0.0;
    spring.damping = 1.0;
    ASSERT_EQ(spring.p1.terms[0].coefficient, 1.0);
    const auto length = [&](const VecX& time) {
      const double dt = time[0] - s.t;
      const VecX q = s.q + dt * s.v;
      const std::vector<FrameKinematics> frames = s.frames_at(time[0]);
      return VecX::Constant(
          1, (point_of(spring.p2, q, frames) - point_of(spring.p1, q, frames)).norm());
    };
    const std::vector<FrameKinematics> frames = s.frames_at(s.t);
    const Vec3 n =
        (point_of(spring.p2, s.q, frames) - point_of(spring.p1, s.q, frames)).normalized();
    ForceResult r;
    evaluate(spring, span_of(s.q), span_of(s.v), frames, r);
    const double rate = n.dot(r.force.segment<3>(0));
    const fdcheck::Result res =
        fdcheck::check_jacobian(length, VecX::Constant(1, s.t), MatX::Constant(1, 1, rate));
    EXPECT_TRUE(res.ok()) << s.label << ": " << describe(res);
    worst[s.label].merge(res);
  }
  print_table("spring tension (k=0, c=1) vs d(length)/dt", worst);
}

TEST(SpringDamper, DirectionAndSign) {
  // p1 at the origin, p2 at (2, 0, 0), ℓ₀ = 1.5, k = 10: tension 5 N pulls p1 toward +x.
  SpringDamper s;
  s.p1.add(kNode, 1.0);
  s.p2 = AffineVector::constant(Vec3(2.0, 0.0, 0.0));
  s.stiffness = 10.0;
  s.rest_length = 1.5;
  const VecX q = VecX::Zero(kDofs);
  ForceResult r;
  evaluate(s, span_of(q), {}, {}, r);
  ASSERT_EQ(r.force.size(), 3);
  EXPECT_EQ(r.force, Vec3(5.0, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(potential_energy(s, span_of(q), {}), 0.5 * 10.0 * 0.25);
}

TEST(SpringDamper, ZeroOrNonFiniteLengthThrows) {
  SpringDamper s;
  s.p1.add(kNode, 1.0);
  s.p2 = AffineVector::constant(Vec3(0.1, 0.2, 0.3));
  s.stiffness = 1.0;
  VecX q = VecX::Zero(kDofs);
  q.segment<3>(kNode) = Vec3(0.1, 0.2, 0.3);
  ForceResult r;
  EXPECT_THROW(evaluate(s, span_of(q), {}, {}, r), std::domain_error);
  q[kNode] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(evaluate(s, span_of(q), {}, {}, r), std::domain_error);
  q[kNode] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(evaluate(s, span_of(q), {}, {}, r), std::domain_error);
  s.p2.frame = 0;  // a frame index without frames
  q[kNode] = 0.0;
  EXPECT_THROW(evaluate(s, span_of(q), {}, {}, r), std::out_of_range);
}

// ---- Point force --------------------------------------------------------------------------------

TEST(PointForce, BlocksAreCoefficientTimesForce) {
  PointForce p;
  const Vec3 pb(0.3, -0.2, 0.5);
  p.point.add(kNode, 0.25).add_body(kBody1, point_weights(pb)).add(kNode, 0.5);
  p.time_function = [](double t) { return Vec3(std::sin(2.0 * t), std::cos(t), t * t); };
  const BlockList b = blocks_of(p);
  ASSERT_EQ(b.count, 5);  // node (twice), r_O, a₁, a₂, a₃
  const std::array<Index, 5> blocks{kNode, kBody1, kBody1 + 3, kBody1 + 6, kBody1 + 9};
  const std::array<double, 5> coefficient{0.75, 1.0, pb.x(), pb.y(), pb.z()};
  for (const double t : {0.0, 0.7, 2.3}) {
    ForceResult r;
    evaluate(p, t, r);
    ASSERT_EQ(r.force.size(), 15);
    const Vec3 f = p.time_function(t);
    for (int i = 0; i < 5; ++i) {
      EXPECT_EQ(b.blocks[i], blocks[i]);
      EXPECT_LE((r.force.segment<3>(3 * i) - coefficient[i] * f).norm(), 2 * kEps * f.norm());
    }
    EXPECT_TRUE(r.d_force_dq.isZero(0.0));
    EXPECT_TRUE(r.d_force_dv.isZero(0.0));
  }
  // Without a time function the constant force applies; a point on ground touches no block.
  p.time_function = nullptr;
  p.force = Vec3(1.0, -2.0, 3.0);
  ForceResult r;
  evaluate(p, 5.0, r);
  EXPECT_EQ(Vec3(r.force.segment<3>(3)), p.force);
  PointForce ground;
  ground.point = AffineVector::constant(Vec3::Ones());
  ground.force = Vec3::Ones();
  evaluate(ground, 0.0, r);
  EXPECT_EQ(blocks_of(ground).count, 0);
  EXPECT_EQ(r.force.size(), 0);
}

// ---- Body torque --------------------------------------------------------------------------------

BodyTorque make_torque() {
  BodyTorque b;
  b.body = kBody1;
  b.time_function = [](double t) { return Vec3(1.0 + std::sin(t), -2.0 * std::cos(t), 0.5 * t); };
  return b;
}

TEST(BodyTorque, Blocks) {
  const BlockList b = blocks_of(make_torque());
  ASSERT_EQ(b.count, 3);
  EXPECT_EQ(b.blocks[0], kBody1 + 3);
  EXPECT_EQ(b.blocks[1], kBody1 + 6);
  EXPECT_EQ(b.blocks[2], kBody1 + 9);
}

TEST(BodyTorque, JacobianMatchesFiniteDifferences) {
  std::map<std::string, fdcheck::Result> worst;
  std::mt19937 rng(7);
  const BodyTorque e = make_torque();
  for (int seed = 0; seed < kSeeds; ++seed) {
    const double t = uniform(rng, 0.0, 5.0);
    const VecX q = perturbed(rng, rigid_q(rng, random_rotation(rng), random_rotation(rng)), 0.05);
    const GlobalFunction fn = [&](const VecX& x, const VecX&) {
      ForceResult r;
      evaluate(e, span_of(x), t, r);
      return scatter(blocks_of(e), r);
    };
    const fdcheck::Result r = check_dq(fn, q, VecX::Zero(kDofs));
    EXPECT_TRUE(r.ok()) << describe(r);
    worst["body torque"].merge(r);
  }
  print_table("body torque dQ/dq", worst);
}

// Orthonormal a_k, δa_k = δθ × a_k, δr_O arbitrary: Q·δq = τ·δθ.
TEST(BodyTorque, VirtualWorkIsTorqueTimesRotation) {
  Worst worst;
  std::mt19937 rng(8);
  const BodyTorque e = make_torque();
  for (int seed = 0; seed < kSeeds; ++seed) {
    const double t = uniform(rng, 0.0, 5.0);
    const Mat3 rot = random_rotation(rng);
    const VecX q = rigid_q(rng, rot, random_rotation(rng));
    const Vec3 dtheta = random_vec3(rng, 1.0);
    VecX dq = random_v(rng, 1.0);  // other coordinates: must not matter
    for (int k = 0; k < 3; ++k) dq.segment<3>(kBody1 + 3 * (k + 1)) = dtheta.cross(rot.col(k));
    ForceResult r;
    evaluate(e, span_of(q), t, r);
    const double work = scatter(blocks_of(e), r).force.dot(dq);
    const Vec3 tau = e.time_function(t);
    worst.add("body torque", std::abs(work - tau.dot(dtheta)),
              8 * kEps * tau.norm() * dtheta.norm());
  }
  worst.print("body torque: |Q.dq - tau.dtheta| / (8 eps |tau||dtheta|)");
}

// ---- Revolute drive -----------------------------------------------------------------------------

constexpr double kKp = 100.0, kKd = 2.83;  // CAPTURE.md's gains

// A drive between body 1 (base, e₁ and e₂ ⊥ the joint axis) and body 2 (d), or between ground
// (constant e₁, e₂) and body 2. Body 2 is body 1 (or the ground frame) rotated by `angle` about the
// joint axis n and by a random constant S: R₂ = R(n, angle) R₁ S, d̄ = Sᵀ ē₁, so that θ = angle.
// Angular velocities ω₁ (0 on ground) and ω₂ = ω₁ + rate·n: θ̇ = rate. The reference is
// θ_ref(t) = angle + angle_error + 2π turns, ω_ref = rate + rate_error, hence
// u = K_p angle_error + K_d rate_error.
struct DriveCase {
  std::string label, regime;
  RevoluteDrive drive;
  VecX q, v;
  double t = 0.9;
  double angle = 0.0, rate = 0.0, turns = 0.0, u = 0.0;
  Vec3 axis;        // n
  Vec3 axis_point;  // a point on the joint axis
  Vec3 w1;          // ω₁ (zero on ground)
  bool ground = false;
};

DriveCase make_drive(std::mt19937& rng, const std::string& label, bool ground, double angle,
                     double angle_error, double rate_error, double torque_max, double turns = 0) {
  DriveCase c;
  c.label = label;
  const std::size_t slash = label.rfind("/ ");
  c.regime = slash == std::string::npos ? "" : label.substr(slash + 2);
  c.ground = ground;
  c.angle = angle;
  c.turns = turns;
  c.rate = uniform(rng, -2.0, 2.0);
  const Mat3 r1 = random_rotation(rng), s = random_rotation(rng);
  const Vec3 axis_body = random_unit(rng);
  const Vec3 e1_body = random_perpendicular_unit(rng, axis_body);
  const Vec3 e2_body = axis_body.cross(e1_body);  // (e₁, e₂, axis) right-handed
  c.axis = r1 * axis_body;
  const Mat3 r2 = Eigen::AngleAxisd(angle, c.axis).toRotationMatrix() * r1 * s;
  c.q = rigid_q(rng, r1, r2);
  c.axis_point = c.q.segment<3>(kBody1);
  c.q.segment<3>(kBody2) = c.axis_point + 0.2 * c.axis;  // body 2 origin on the axis

  RevoluteDrive& d = c.drive;
  d.d.add_body(kBody2, direction_weights(s.transpose() * e1_body));
  if (ground) {
    d.e1 = AffineVector::constant(r1 * e1_body);
    d.e2 = AffineVector::constant(r1 * e2_body);
  } else {
    d.e1.add_body(kBody1, direction_weights(e1_body));
    d.e2.add_body(kBody1, direction_weights(e2_body));
  }
  d.kp = kKp;
  d.kd = kKd;
  d.torque_max = torque_max;
  const double ref_rate = c.rate + rate_error;
  const double ref_angle = angle + angle_error + 2.0 * kPi * turns;
  d.reference = AngleLaw::constant_rate(ref_rate, ref_angle - ref_rate * c.t);
  c.u = kKp * angle_error + kKd * rate_error;

  c.v = random_v(rng, 1.0);
  c.w1 = ground ? Vec3::Zero() : random_vec3(rng, 0.5);
  const Vec3 w2 = c.w1 + c.rate * c.axis;
  c.v.segment<12>(kBody1) = body_velocities(r1, random_vec3(rng, 0.3), c.w1);
  c.v.segment<12>(kBody2) = body_velocities(r2, random_vec3(rng, 0.3), w2);
  return c;
}

double sign_of(std::mt19937& rng) {
  return uniform(rng, -1.0, 1.0) < 0.0 ? -1.0 : 1.0;
}

// Unsaturated: τ_max = 1e4 N m, |u| ≲ 3 N m. Saturated: τ_max = 6 N m (CAPTURE.md), |u| ≈ 20..31,
// u/τ_max ≈ 3..5. Angles uniform, plus the atan2 branch cut: θ = ±π exactly and just across.
std::vector<DriveCase> drive_cases() {
  std::vector<DriveCase> cases;
  std::mt19937 rng(31337);
  for (const bool ground : {false, true}) {
    const std::string where = ground ? "ground - body" : "body - body";
    for (int seed = 0; seed < kSeeds; ++seed) {
      const double angle = uniform(rng, -kPi, kPi);
      cases.push_back(make_drive(rng, where + " / unsaturated", ground, angle,
                                 uniform(rng, -0.02, 0.02), uniform(rng, -0.1, 0.1), 1e4));
      const double sg = sign_of(rng);
      cases.push_back(make_drive(rng, where + " / saturated", ground, angle,
                                 sg * uniform(rng, 0.2, 0.3), sg * uniform(rng, 0.0, 0.5), 6.0));
    }
    for (const double angle : {kPi, -kPi, kPi + 0.005, -kPi - 0.005}) {
      const double sg = sign_of(rng);
      cases.push_back(make_drive(rng, where + " / across +-pi", ground, angle, sg * 0.015,
                                 uniform(rng, -0.1, 0.1), 6.0, sign_of(rng) * 2.0));
    }
  }
  return cases;
}

Global drive_global(const RevoluteDrive& d, double t, const VecX& q, const VecX& v,
                    DriveState* state = nullptr) {
  ForceResult r;
  const DriveState s = evaluate(d, span_of(q), span_of(v), t, r);
  if (state) *state = s;
  return scatter(blocks_of(d), r);
}

TEST(RevoluteDrive, Blocks) {
  std::mt19937 rng(1);
  const DriveCase body = make_drive(rng, "", false, 0.3, 0.0, 0.0, 1.0);
  const BlockList b = blocks_of(body.drive);  // d: a₁..a₃ of body 2, then e₁/e₂: of body 1
  ASSERT_EQ(b.count, 6);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(b.blocks[k], kBody2 + 3 * (k + 1));
    EXPECT_EQ(b.blocks[3 + k], kBody1 + 3 * (k + 1));
  }
  const DriveCase ground = make_drive(rng, "", true, 0.3, 0.0, 0.0, 1.0);
  EXPECT_EQ(blocks_of(ground.drive).count, 3);
}

// ∂Q/∂q of the drive against central differences at (q, v), `dq` the analytic matrix.
// Q = τ θ_q with u = K_p(θ_ref − θ) + K_d(ω_ref − θ̇) a small difference of large terms: θ is
// accurate to ~ε absolutely (atan2 of O(1) dot products), so u carries a round-off of
// ~ε K_p(|θ_ref| + π) + ε K_d(|ω_ref| + |θ̇|), passed on to τ by τ_u = sech²(u/τ_max) — much more
// than ε|Q| when |θ_ref − θ| ≪ 1. That magnitude of the terms of Q is the helper's f_scale.
fdcheck::Result drive_dq_check(const DriveCase& c, const VecX& q, const VecX& v, const MatX& dq) {
  DriveState state;
  const VecX force = drive_global(c.drive, c.t, q, v, &state).force;
  EXPECT_GT(std::abs(state.torque), 1e-3) << c.label;
  const double theta_q_max = force.cwiseAbs().maxCoeff() / std::abs(state.torque);
  const double tanh_s = state.torque / c.drive.torque_max;
  const AngleState ref = c.drive.reference.at(c.t);
  fdcheck::Options opt;
  opt.f_scale =
      theta_q_max * (std::abs(state.torque) +
                     (1.0 - tanh_s * tanh_s) * (kKp * (std::abs(ref.angle) + kPi) +
                                                kKd * (std::abs(ref.rate) + std::abs(state.rate))));
  const fdcheck::Function f = [&](const VecX& x) {
    return VecX(drive_global(c.drive, c.t, x, v).force);
  };
  return fdcheck::check_jacobian(f, q, dq, opt);
}

TEST(RevoluteDrive, JacobiansMatchFiniteDifferences) {
  std::map<std::string, fdcheck::Result> worst_q, worst_v;
  std::mt19937 rng(99);
  double min_s = 1e300, max_s = 0.0;
  for (const DriveCase& c : drive_cases()) {
    // Off the rigid manifold: non-orthonormal directions, velocities not rigid.
    const VecX q = perturbed(rng, c.q, 0.02), v = perturbed(rng, c.v, 0.2);
    DriveState state;
    const Global g = drive_global(c.drive, c.t, q, v, &state);
    const double s = std::abs(std::atanh(state.torque / c.drive.torque_max));  // |u|/τ_max
    if (c.regime == "saturated") {
      min_s = std::min(min_s, s);
      EXPECT_GT(s, 1.5) << c.label;  // past the knee of tanh
    } else if (c.regime == "unsaturated") {
      max_s = std::max(max_s, s);
      EXPECT_LT(s, 1e-3) << c.label;
    }
    const fdcheck::Result rq = drive_dq_check(c, q, v, g.dq);
    EXPECT_TRUE(rq.ok()) << c.label << " dQ/dq: " << describe(rq);
    worst_q[c.label].merge(rq);
    const GlobalFunction fn = [&](const VecX& x, const VecX& y) {
      return drive_global(c.drive, c.t, x, y);
    };
    const fdcheck::Result rv = check_dv(fn, q, v);
    EXPECT_TRUE(rv.ok()) << c.label << " dQ/dv: " << describe(rv);
    worst_v[c.label].merge(rv);
  }
  print_table("revolute drive dQ/dq", worst_q);
  print_table("revolute drive dQ/dv", worst_v);
  std::printf("|u|/tau_max: unsaturated max %.2e, saturated min %.2f\n", max_s, min_s);
}

// The f_scale above leaves the check its teeth: an error of 1e-6 · max|∂Q/∂q| in one entry, or
// leaving out the τ θ_qq term (the curvature of atan2 and of the bilinear forms), is reported.
TEST(RevoluteDrive, FdCheckDetectsSmallJacobianError) {
  std::mt19937 rng(4);
  for (const DriveCase& c : drive_cases()) {
    if (c.regime != "unsaturated") continue;
    const VecX q = perturbed(rng, c.q, 0.02), v = perturbed(rng, c.v, 0.2);
    DriveState state;
    MatX dq = drive_global(c.drive, c.t, q, v, &state).dq;
    ASSERT_TRUE(drive_dq_check(c, q, v, dq).ok()) << c.label;
    MatX wrong = dq;
    wrong(kBody2 + 4, kBody2 + 7) += 1e-6 * dq.cwiseAbs().maxCoeff();
    EXPECT_FALSE(drive_dq_check(c, q, v, wrong).ok()) << c.label;
    // τ θ_qq from a linear P drive with the same τ: K_p = τ, K_d = 0, θ_ref = θ + 1 rad, no limit
    // to speak of, so τ' = τ and ∂Q'/∂q = −τ θ_q θ_qᵀ + τ θ_qq.
    RevoluteDrive linear = c.drive;
    linear.kp = state.torque;
    linear.kd = 0.0;
    linear.torque_max = 1e12;
    linear.reference = AngleLaw::fixed(state.angle + 1.0);
    const Global lin = drive_global(linear, c.t, q, v);
    const VecX theta_q = lin.force / state.torque;
    const MatX tau_theta_qq = lin.dq + state.torque * theta_q * theta_q.transpose();
    EXPECT_FALSE(drive_dq_check(c, q, v, dq - tau_theta_qq).ok()) << c.label;
  }
}

// At the rigid configuration: θ (on the branch of the reference, so = angle + 2π turns), θ̇ and τ
// are those used to build it; a rotation of body 2 alone about the axis by δθ does work τ δθ; a
// rigid rotation of both bodies together does none.
TEST(RevoluteDrive, AngleRateTorqueAndVirtualWork) {
  Worst worst;
  std::mt19937 rng(5);
  for (const DriveCase& c : drive_cases()) {
    DriveState s;
    const Global g = drive_global(c.drive, c.t, c.q, c.v, &s);
    const double angle = c.angle + 2.0 * kPi * c.turns;
    const double angle_tol = 16 * kEps * (1.0 + std::abs(angle));
    worst.add(c.label + " / angle", std::abs(s.angle - angle), angle_tol);
    const double rate_tol = 16 * kEps * (1.0 + c.w1.norm() + std::abs(c.rate));
    worst.add(c.label + " / rate", std::abs(s.rate - c.rate), rate_tol);
    // τ(u) with u from the construction; |∂τ/∂u| ≤ 1 carries the angle and rate round-off.
    const double tau = c.drive.torque_max * std::tanh(c.u / c.drive.torque_max);
    worst.add(c.label + " / torque", std::abs(s.torque - tau),
              kKp * angle_tol + kKd * rate_tol + 4 * kEps * std::abs(tau));

    // δq: body 2 rotated about the joint axis by a unit angle.
    VecX dq = VecX::Zero(kDofs);
    dq.segment<3>(kBody2) = c.axis.cross(Vec3(c.q.segment<3>(kBody2) - c.axis_point));
    for (int k = 1; k <= 3; ++k)
      dq.segment<3>(kBody2 + 3 * k) = c.axis.cross(Vec3(c.q.segment<3>(kBody2 + 3 * k)));
    worst.add(c.label + " / work of body-2 rotation", std::abs(g.force.dot(dq) - s.torque),
              16 * kEps * std::abs(s.torque));
    if (!c.ground) {  // both bodies rotated rigidly about any axis through any point
      const Vec3 w = random_vec3(rng, 1.0), p = random_vec3(rng, 1.0);
      VecX both = VecX::Zero(kDofs);
      for (const Index b : {kBody1, kBody2}) {
        both.segment<3>(b) = w.cross(Vec3(c.q.segment<3>(b) - p));
        for (int k = 1; k <= 3; ++k)
          both.segment<3>(b + 3 * k) = w.cross(Vec3(c.q.segment<3>(b + 3 * k)));
      }
      worst.add(c.label + " / work of rigid rotation", std::abs(g.force.dot(both)),
                16 * kEps * std::abs(s.torque) * w.norm());
    }
  }
  worst.print("revolute drive at rigid configurations");
}

// wrap(): the error θ_ref − θ is taken in (−π, π], so a reference just past +π drives a body just
// short of it forward, and vice versa; multiples of 2π in the reference do not matter.
TEST(RevoluteDrive, TrackingErrorWrapsAcrossPi) {
  std::mt19937 rng(11);
  struct Wrap {
    double angle, reference;
  };
  for (const Wrap w : {Wrap{kPi - 0.01, -kPi + 0.01}, Wrap{-kPi + 0.01, kPi - 0.01},
                       Wrap{kPi + 0.01, 5 * kPi - 0.01}, Wrap{0.2, 0.2 - 6 * kPi + 0.01}}) {
    DriveCase c = make_drive(rng, "", false, w.angle, 0.0, 0.0, 1e4);
    c.drive.kd = 0.0;
    c.drive.reference = AngleLaw::fixed(w.reference);
    DriveState s;
    drive_global(c.drive, c.t, c.q, c.v, &s);
    const double error =
        std::remainder(w.reference - w.angle, 2.0 * kPi);  // |error| = 0.02 or 0.01
    const double tau = 1e4 * std::tanh(kKp * error / 1e4);
    EXPECT_NEAR(s.torque, tau, 1e-10) << w.angle << " -> " << w.reference;
    EXPECT_NEAR(s.angle, w.reference - error, 1e-12);
  }
}

TEST(RevoluteDrive, InvalidParametersThrow) {
  std::mt19937 rng(2);
  DriveCase c = make_drive(rng, "", false, 0.3, 0.0, 0.0, 1.0);
  ForceResult r;
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity()}) {
    RevoluteDrive d = c.drive;
    d.torque_max = bad;
    EXPECT_THROW(evaluate(d, span_of(c.q), span_of(c.v), c.t, r), std::invalid_argument) << bad;
  }
  RevoluteDrive framed = c.drive;
  framed.e1.frame = 0;
  EXPECT_THROW(evaluate(framed, span_of(c.q), span_of(c.v), c.t, r), std::invalid_argument);
  RevoluteDrive degenerate = c.drive;  // d along the axis: no angle
  degenerate.d = AffineVector::constant(c.axis);
  EXPECT_THROW(evaluate(degenerate, span_of(c.q), span_of(c.v), c.t, r), std::domain_error);
}

// ---- Containers and allocation ------------------------------------------------------------------

TEST(BlockList, InsertFindAndCapacity) {
  BlockList b;
  EXPECT_EQ(b.insert(12), 0);
  EXPECT_EQ(b.insert(3), 1);
  EXPECT_EQ(b.insert(12), 0);
  EXPECT_EQ(b.count, 2);
  EXPECT_EQ(b.find(3), 1);
  EXPECT_EQ(b.find(4), -1);
  for (Index k = 0; k < 6; ++k) b.insert(100 + 3 * k);
  EXPECT_EQ(b.count, 8);
  EXPECT_EQ(b.insert(3), 1);  // existing: fine at capacity
  EXPECT_THROW(b.insert(999), std::length_error);
  ForceResult r;
  r.resize(8);
  EXPECT_EQ(r.force.size(), 24);
  EXPECT_EQ(r.d_force_dq.rows(), 24);
  EXPECT_TRUE(r.d_force_dv.isZero(0.0));
  EXPECT_THROW(r.resize(9), std::length_error);
}

TEST(ForceElements, EvaluateDoesNotAllocate) {
#ifdef ANCF_COUNT_MALLOC
  std::mt19937 rng(3);
  const std::vector<SpringCase> springs = spring_cases();
  const SpringCase& s = springs[1];  // with a driven frame
  const std::vector<FrameKinematics> frames = s.frames_at(s.t);
  const DriveCase d = make_drive(rng, "", false, 0.3, 0.1, 0.1, 6.0);
  PointForce p;
  p.point.add_body(kBody1, point_weights(Vec3(0.1, 0.2, 0.3)));
  p.time_function = [](double t) { return Vec3(t, 0.0, 1.0); };
  const BodyTorque torque = make_torque();
  ForceResult r;
  g_malloc_calls = 0;
  g_count_malloc = true;
  evaluate(s.spring, span_of(s.q), span_of(s.v), frames, r);
  evaluate(d.drive, span_of(d.q), span_of(d.v), d.t, r);
  evaluate(p, 0.5, r);
  evaluate(torque, span_of(d.q), 0.5, r);
  g_count_malloc = false;
  EXPECT_EQ(g_malloc_calls, 0);
  // The counter works: an Eigen dynamic vector allocates.
  g_count_malloc = true;
  const VecX probe = VecX::Zero(kDofs);
  g_count_malloc = false;
  EXPECT_GE(g_malloc_calls, 1);
  EXPECT_EQ(probe.size(), kDofs);
#else
  GTEST_SKIP() << "malloc counting needs glibc without AddressSanitizer";
#endif
}

}  // namespace
