// Contact kernels in isolation (DESIGN §5, docs/contact.md): the smooth penalty law, the signed
// distance functions of the rigid shapes (gradient and Hessian = the curvature terms), the
// closest-point projection onto an element, and the generalised contact force of one sample with
// its analytic Jacobians ∂Q/∂P and ∂Q/∂V against central finite differences, for cable–sphere,
// cable–cylinder (side, cap, rim, inside), cable–plane and cable–cable (interior and clamped
// projection), with shapes on ground, on a moving driven frame and on a rigid body, each with the
// normal law alone, with Hunt–Crossley damping, with friction and with both, at penetrations in
// the quadratic onset (0.3 δ_s, 0.8 δ_s) and on the linear branch (3 δ_s).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ancf/physics/cable_contact.hpp"
#include "ancf/physics/contact_law.hpp"
#include "ancf/physics/contact_shapes.hpp"
#include "ancf/physics/hermite_shape.hpp"
#include "fd_check.hpp"
#include "random_geometry.hpp"

namespace ancf {
namespace {

using random_geometry::random_rotation;
using random_geometry::random_vec3;
constexpr double kEps = std::numeric_limits<double>::epsilon();

Vec3 unit(const Vec3& v) {
  return v.normalized();
}

Mat3 skew(const Vec3& w) {
  Mat3 m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

// ---- Law -------------------------------------------------------------------------------------

TEST(ContactLaw, PressureIsC1AndItsDerivativeIsExact) {
  ContactLaw law;
  law.stiffness = 3e5;
  law.onset_depth = 2e-3;
  // Value and slope continuous at δ = 0 and δ = δ_s (compare both sides a relative 1e-12 apart).
  for (const double at : {0.0, law.onset_depth}) {
    const double below = at * (1.0 - 1e-12) - (at == 0.0 ? 1e-15 : 0.0),
                 above = at * (1.0 + 1e-12) + 1e-15;
    const auto lo = law.pressure(below), hi = law.pressure(above);
    EXPECT_LE(std::abs(hi.value - lo.value), 1e-9 * law.stiffness * law.onset_depth) << at;
    EXPECT_LE(std::abs(hi.derivative - lo.derivative), 1e-9 * law.stiffness) << at;
  }
  // Derivative against central differences inside each branch; the inverse gives back δ.
  fdcheck::Result worst;
  for (const double d : {0.1, 0.5, 0.9, 1.5, 4.0}) {
    const double delta = d * law.onset_depth;
    const fdcheck::Vec x = fdcheck::Vec::Constant(1, delta);
    worst.merge(
        fdcheck::check_gradient([&](const fdcheck::Vec& y) { return law.pressure(y[0]).value; }, x,
                                fdcheck::Vec::Constant(1, law.pressure(delta).derivative)));
    EXPECT_NEAR(law.static_penetration(law.pressure(delta).value), delta, 8 * kEps * delta);
  }
  std::printf("  dp/ddelta: worst error/tolerance %.3f\n", worst.max_ratio);
  EXPECT_TRUE(worst.ok());
  EXPECT_EQ(law.pressure(-1e-3).value, 0.0);
  EXPECT_EQ(law.pressure(-1e-3).derivative, 0.0);
}

TEST(ContactLaw, ValidationNamesTheParameter) {
  ContactLaw law;
  law.stiffness = -1.0;
  try {
    law.validate("rope-pole");
    FAIL() << "negative stiffness accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("rope-pole"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("stiffness"), std::string::npos) << e.what();
  }
  law.stiffness = 1.0;
  law.friction = 0.2;
  law.regularization_speed = 0.0;
  EXPECT_THROW(law.validate("x"), std::exception);
}

// ---- Signed distance -------------------------------------------------------------------------

struct DistanceCase {
  std::string name;
  ContactShape shape;
  Vec3 point;
  double expected;  // signed distance known by construction
};

std::vector<DistanceCase> distance_cases(std::mt19937& rng) {
  const Mat3 r = random_rotation(rng);
  const Vec3 c = random_vec3(rng, 0.2), u = r.col(2), e1 = r.col(0), e2 = r.col(1);
  const SphereShape sphere{c, 0.05};
  const CappedCylinderShape cyl{c, u, 0.04, 0.1};
  const PlaneShape plane{c, u};
  const Vec3 er = unit(0.6 * e1 + 0.8 * e2);
  return {
      {"sphere outside", sphere, c + 0.07 * er, 0.02},
      {"sphere inside", sphere, c + 0.03 * er, -0.02},
      {"plane above", plane, c + 0.3 * e1 + 0.01 * u, 0.01},
      {"plane below", plane, c - 0.2 * e2 - 0.02 * u, -0.02},
      {"cylinder side", cyl, c + 0.03 * u + 0.05 * er, 0.01},
      {"cylinder cap", cyl, c - 0.115 * u + 0.02 * er, 0.015},
      {"cylinder rim", cyl, c + (0.1 + 0.006) * u + (0.04 + 0.008) * er, 0.01},
      {"cylinder inside near side", cyl, c + 0.02 * u + 0.035 * er, -0.005},
      {"cylinder inside near cap", cyl, c + 0.095 * u + 0.01 * er, -0.005},
  };
}

// ∇d against differences of d, ∇²d against differences of ∇d, |∇d| = 1, d as constructed.
TEST(SignedDistance, GradientAndHessianMatchFiniteDifferences) {
  std::mt19937 rng(11);
  fdcheck::Result worst_g, worst_h;
  for (int seed = 0; seed < 3; ++seed)
    for (const DistanceCase& c : distance_cases(rng)) {
      const SignedDistance sd = signed_distance(c.shape, c.point);
      EXPECT_NEAR(sd.distance, c.expected, 64 * kEps) << c.name;
      EXPECT_NEAR(sd.gradient.norm(), 1.0, 8 * kEps) << c.name;
      EXPECT_LE((sd.hessian - sd.hessian.transpose()).norm(), 8 * kEps * (1.0 + sd.hessian.norm()))
          << c.name;
      const fdcheck::Result g = fdcheck::check_gradient(
          [&](const fdcheck::Vec& y) { return signed_distance(c.shape, y).distance; }, c.point,
          sd.gradient);
      const fdcheck::Result h = fdcheck::check_jacobian(
          [&](const fdcheck::Vec& y) { return fdcheck::Vec(signed_distance(c.shape, y).gradient); },
          c.point, sd.hessian);
      EXPECT_TRUE(g.ok()) << c.name << ": gradient error/tolerance " << g.max_ratio;
      EXPECT_TRUE(h.ok()) << c.name << ": Hessian error/tolerance " << h.max_ratio;
      worst_g.merge(g);
      worst_h.merge(h);
    }
  std::printf("  signed distance: gradient worst error/tolerance %.3f, Hessian %.3f\n",
              worst_g.max_ratio, worst_h.max_ratio);
}

// The broad phase must never cull a point of the shape or of the element.
TEST(BoundingBoxes, ContainTheShapeAndTheElement) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 a = random_rotation(rng);
    const Vec3 origin = random_vec3(rng, 1.0);
    const CappedCylinderShape cyl{random_vec3(rng, 0.1), unit(random_vec3(rng, 1.0)), 0.05, 0.2};
    const SphereShape sphere{random_vec3(rng, 0.1), 0.07};
    const Aabb bc = shape_bounding_box(cyl, origin, a), bs = shape_bounding_box(sphere, origin, a);
    Aabb tight_c, tight_s;
    const Mat3 frame = [&] {
      Mat3 f;
      f.col(2) = cyl.axis;
      f.col(0) = unit(cyl.axis.cross(Vec3(0.3, 0.5, 0.7)));
      f.col(1) = f.col(2).cross(f.col(0));
      return f;
    }();
    for (int k = 0; k < 2000; ++k) {
      const double phi = 2.0 * M_PI * k / 2000.0;
      // Rim circles (the extreme points of a capped cylinder) and sphere great circles.
      for (const double end : {-1.0, 1.0}) {
        const Vec3 p = cyl.centre + end * cyl.half_length * cyl.axis +
                       cyl.radius * (std::cos(phi) * frame.col(0) + std::sin(phi) * frame.col(1));
        const Vec3 x = origin + a * p;
        EXPECT_TRUE((x.array() >= bc.lower.array() - 1e-14).all() &&
                    (x.array() <= bc.upper.array() + 1e-14).all());
        tight_c.extend(x);
      }
      const Vec3 dir = unit(random_vec3(rng, 1.0));
      const Vec3 xs = origin + a * (sphere.centre + sphere.radius * dir);
      EXPECT_TRUE((xs.array() >= bs.lower.array() - 1e-14).all() &&
                  (xs.array() <= bs.upper.array() + 1e-14).all());
    }
    // Not grossly conservative: the rotated-disk box is the exact extent of the rims.
    EXPECT_LE((bc.upper - tight_c.upper).cwiseAbs().maxCoeff(), 1e-4);
    Vec12 e;
    e << random_vec3(rng, 0.3), unit(random_vec3(rng, 1.0)) * 1.5, random_vec3(rng, 0.3),
        unit(random_vec3(rng, 1.0)) * 1.5;
    const double l = 0.4;
    const Aabb be = element_bounding_box(e, l);
    for (int k = 0; k <= 400; ++k) {
      const Vec4 s = hermite::values(k / 400.0, l);
      const Vec3 x = s[0] * e.segment<3>(0) + s[1] * e.segment<3>(3) + s[2] * e.segment<3>(6) +
                     s[3] * e.segment<3>(9);
      EXPECT_TRUE((x.array() >= be.lower.array() - 1e-14).all() &&
                  (x.array() <= be.upper.array() + 1e-14).all());
    }
  }
}

// ---- Sample geometry shared by the kernel checks ---------------------------------------------

Vec3 centreline(const Vec12& e, double l, double xi) {
  const Vec4 s = hermite::values(xi, l);
  return s[0] * e.segment<3>(0) + s[1] * e.segment<3>(3) + s[2] * e.segment<3>(6) +
         s[3] * e.segment<3>(9);
}
Vec3 tangent(const Vec12& e, double l, double xi) {
  const Vec4 s = hermite::first_derivative(xi, l);
  return s[0] * e.segment<3>(0) + s[1] * e.segment<3>(3) + s[2] * e.segment<3>(6) +
         s[3] * e.segment<3>(9);
}

// A curved, slightly stretched element of length l whose sample at ξ sits at `target`.
Vec12 element_through(std::mt19937& rng, double l, double xi, const Vec3& target) {
  const Vec3 d = unit(random_vec3(rng, 1.0));
  Vec12 e;
  e << Vec3::Zero(), unit(d + random_vec3(rng, 0.3)) * 1.02, l * d + random_vec3(rng, 0.03),
      unit(d + random_vec3(rng, 0.3)) * 0.98;
  const Vec3 shift = target - centreline(e, l, xi);  // S1 + S3 = 1: a rigid shift moves x by it
  e.segment<3>(0) += shift;
  e.segment<3>(6) += shift;
  return e;
}

Vec12 random_velocity(std::mt19937& rng, double scale) {
  Vec12 v;
  for (int k = 0; k < 4; ++k) v.segment<3>(3 * k) = random_vec3(rng, scale);
  return v;
}

struct LawCase {
  const char* name;
  double damping, friction;
};
constexpr LawCase kLaws[] = {
    {"normal", 0.0, 0.0}, {"damped", 0.6, 0.0}, {"friction", 0.0, 0.4}, {"all", 0.6, 0.4}};
constexpr double kOnset = 2e-3;
constexpr double kPenetrations[] = {0.3 * kOnset, 0.8 * kOnset, 3.0 * kOnset};

ContactLaw make_law(const LawCase& c) {
  ContactLaw law;
  law.stiffness = 2e5;
  law.onset_depth = kOnset;
  law.damping = c.damping;
  law.friction = c.friction;
  law.regularization_speed = 0.1;  // of the order of the sliding speeds below: the smooth part
  return law;
}

// Shapes in their owner's frame and a point whose signed distance is `d` by construction.
struct ShapeCase {
  const char* name;
  ContactShape shape;
  std::function<Vec3(double d)> point;
  bool inside = false;  ///< the centreline is inside the shape (deep penetration, fixed depth)
};

std::vector<ShapeCase> shape_cases() {
  const Vec3 c(0.02, -0.01, 0.03), u = unit(Vec3(0.2, 0.3, 1.0));
  const Vec3 e1 = unit(u.cross(Vec3::UnitX())), e2 = u.cross(e1);
  const Vec3 er = unit(0.8 * e1 - 0.6 * e2);
  const SphereShape sphere{c, 0.05};
  const CappedCylinderShape cyl{c, u, 0.04, 0.1};
  const PlaneShape plane{c, u};
  return {
      {"sphere", sphere, [=](double d) { return Vec3(c + (0.05 + d) * er); }},
      {"plane", plane, [=](double d) { return Vec3(c + 0.1 * e1 - 0.05 * e2 + d * u); }},
      {"cylinder side", cyl, [=](double d) { return Vec3(c + 0.03 * u + (0.04 + d) * er); }},
      {"cylinder cap", cyl, [=](double d) { return Vec3(c - (0.1 + d) * u + 0.015 * er); }},
      {"cylinder rim", cyl,
       [=](double d) {
         return Vec3(c + (0.1 + d * std::sin(0.6)) * u + (0.04 + d * std::cos(0.6)) * er);
       }},
      {"sphere, centreline inside", sphere, [=](double) { return Vec3(c + 0.045 * er); }, true},
      {"cylinder side, centreline inside", cyl,
       [=](double) { return Vec3(c - 0.02 * u + 0.035 * er); }, true},
  };
}

enum class Owner { ground, frame, body };
const char* owner_name(Owner o) {
  return o == Owner::ground ? "ground" : o == Owner::frame ? "frame" : "body";
}

ShapeOwnerPose body_pose(const Vec12& qb, const Vec12& vb) {
  ShapeOwnerPose p;
  p.origin = qb.head<3>();
  p.origin_velocity = vb.head<3>();
  for (int k = 0; k < 3; ++k) {
    p.rotation.col(k) = qb.segment<3>(3 + 3 * k);
    p.rotation_rate.col(k) = vb.segment<3>(3 + 3 * k);
  }
  p.is_body = true;
  return p;
}

struct KernelWorst {
  fdcheck::Result dq, dv;
  int cases = 0;
  void merge(const fdcheck::Result& q, const fdcheck::Result& v) {
    dq.merge(q);
    dv.merge(v);
    ++cases;
  }
};

// Q(P, V) and its analytic Jacobians from one kernel evaluation; `active` must hold at every FD
// point (the configurations keep the penetration far from 0 compared with the FD steps).
using Kernel =
    std::function<bool(const VecX& p, const VecX& v, bool jacobians, ContactSampleResult& out)>;

void check_kernel(const Kernel& kernel, const VecX& p, const VecX& v, const std::string& what,
                  KernelWorst& worst) {
  const Index n = p.size();
  ContactSampleResult r;
  ASSERT_TRUE(kernel(p, v, true, r)) << what << ": not in contact";
  const MatX dq = r.d_force_dq.topLeftCorner(n, n), dv = r.d_force_dv.topLeftCorner(n, n);
  const auto force = [&](const VecX& pp, const VecX& vv) {
    ContactSampleResult s;
    if (!kernel(pp, vv, false, s)) ADD_FAILURE() << what << ": contact lost at an FD point";
    return VecX(s.force.head(n));
  };
  // Rounding of Q is not only ε|Q|: the gap is a small difference of coordinates of size |P|, so
  // its rounding ε|P| reaches Q amplified by ∂Q/∂P (and likewise for V). That is the f_scale of
  // the FD error estimate (fd_check.hpp).
  const double q_max = r.force.head(n).cwiseAbs().maxCoeff();
  fdcheck::Options op, ov;
  op.f_scale = q_max + dq.cwiseAbs().maxCoeff() * p.cwiseAbs().maxCoeff();
  ov.f_scale = q_max + dv.cwiseAbs().maxCoeff() * v.cwiseAbs().maxCoeff() +
               dq.cwiseAbs().maxCoeff() * p.cwiseAbs().maxCoeff();
  const fdcheck::Result q =
      fdcheck::check_jacobian([&](const VecX& x) { return force(x, v); }, p, dq, op);
  const fdcheck::Result w =
      fdcheck::check_jacobian([&](const VecX& x) { return force(p, x); }, v, dv, ov);
  EXPECT_TRUE(q.ok()) << what << " dQ/dP(" << q.row << ", " << q.col << "): analytic " << q.analytic
                      << ", FD " << q.fd << ", tolerance " << q.tol;
  EXPECT_TRUE(w.ok()) << what << " dQ/dV(" << w.row << ", " << w.col << "): analytic " << w.analytic
                      << ", FD " << w.fd << ", tolerance " << w.tol;
  // The kernel with and without Jacobians gives the same force (one code path).
  ContactSampleResult plain;
  kernel(p, v, false, plain);
  EXPECT_EQ(plain.force.head(n), r.force.head(n)) << what;
  worst.merge(q, w);
}

TEST(CableShapeContact, ForceJacobiansMatchFiniteDifferences) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> uni(0.15, 0.85);
  const double radius = 0.01, length = 0.3;
  KernelWorst worst;
  for (const ShapeCase& sc : shape_cases())
    for (const Owner owner : {Owner::ground, Owner::frame, Owner::body})
      for (const LawCase& lc : kLaws)
        for (const double delta : kPenetrations) {
          if (sc.inside && delta != kPenetrations[0]) continue;  // fixed depth: one case per law
          const ContactLaw law = make_law(lc);
          const double xi = uni(rng);
          // Owner pose: identity (ground); a rotating, translating frame; a body with a slightly
          // non-orthonormal A (as during Newton iterations: the derivatives are exact for any A).
          ShapeOwnerPose pose;
          Vec12 qb = Vec12::Zero(), vb = Vec12::Zero();
          if (owner != Owner::ground) {
            const Mat3 a = random_rotation(rng);
            const Vec3 w = random_vec3(rng, 1.0);
            pose.origin = random_vec3(rng, 0.5);
            pose.origin_velocity = random_vec3(rng, 0.2);
            pose.rotation = a;
            pose.rotation_rate = skew(w) * a;
            if (owner == Owner::body) {
              qb.head<3>() = pose.origin;
              vb.head<3>() = pose.origin_velocity;
              for (int k = 0; k < 3; ++k) {
                qb.segment<3>(3 + 3 * k) = a.col(k) + random_vec3(rng, 1e-3);
                vb.segment<3>(3 + 3 * k) = pose.rotation_rate.col(k);
              }
              pose = body_pose(qb, vb);
            }
          }
          const Vec3 y = sc.point(radius - delta);  // owner frame: gap = d − r = −δ
          const Vec3 x = pose.origin + pose.rotation * y;
          const Vec12 e = element_through(rng, length, xi, x);
          const Vec12 e_dot = random_velocity(rng, 0.15);
          const bool body = owner == Owner::body;
          VecX p(body ? 24 : 12), v(body ? 24 : 12);
          p.head<12>() = e;
          v.head<12>() = e_dot;
          if (body) p.tail<12>() = qb, v.tail<12>() = vb;
          const Kernel kernel = [&](const VecX& pp, const VecX& vv, bool jac,
                                    ContactSampleResult& out) {
            CableSample s;
            s.e = pp.head<12>();
            s.e_dot = vv.head<12>();
            s.length = length;
            s.xi = xi;
            s.radius = radius;
            s.weight = length / 4.0;
            const ShapeOwnerPose po = body ? body_pose(pp.tail<12>(), vv.tail<12>()) : pose;
            return evaluate_cable_shape_contact(law, sc.shape, po, s, jac, out);
          };
          const std::string what = std::string(sc.name) + " on " + owner_name(owner) + ", " +
                                   lc.name + ", delta/delta_s " +
                                   std::to_string(sc.inside ? -1.0 : delta / kOnset);
          ContactSampleResult r;
          kernel(p, v, false, r);
          if (!sc.inside && owner != Owner::body) {  // body: A is not orthonormal here
            EXPECT_NEAR(r.gap, -delta, 1e-14) << what;
          }
          check_kernel(kernel, p, v, what, worst);
        }
  std::printf(
      "  cable-shape: %d cases; worst error/tolerance dQ/dP %.3f (error/max|J| %.1e), dQ/dV %.3f "
      "(%.1e)\n",
      worst.cases, worst.dq.max_ratio, worst.dq.max_rel, worst.dv.max_ratio, worst.dv.max_rel);
}

TEST(CableCableContact, ForceJacobiansMatchFiniteDifferences) {
  std::mt19937 rng(77);
  const double ra = 0.01, rb = 0.008, la = 0.25, lb = 0.3;
  KernelWorst worst_interior, worst_end;
  for (const bool at_end : {false, true})
    for (const LawCase& lc : kLaws)
      for (const double delta : kPenetrations)
        for (int seed = 0; seed < 2; ++seed) {
          const ContactLaw law = make_law(lc);
          Vec12 eb;
          const Vec3 db = unit(random_vec3(rng, 1.0));
          eb << random_vec3(rng, 0.1), unit(db + random_vec3(rng, 0.4)),
              lb * db + random_vec3(rng, 0.04), unit(db + random_vec3(rng, 0.4));
          const double xi_b = at_end ? 1.0 : 0.45, dist = ra + rb - delta;
          const Vec3 xb = centreline(eb, lb, xi_b), tb = unit(tangent(eb, lb, xi_b));
          Vec3 dir;
          if (at_end) {  // beyond the end: the closest point is clamped at ξ_b = 1
            const Vec3 m = unit(tb.cross(random_vec3(rng, 1.0)));
            dir = std::cos(0.7) * tb + std::sin(0.7) * m;
          } else {
            dir = unit(tb.cross(random_vec3(rng, 1.0)));
          }
          const double xi_a = 0.3 + 0.2 * seed;
          const Vec12 ea = element_through(rng, la, xi_a, xb + dist * dir);
          VecX p(24), v(24);
          p << ea, eb;
          v << random_velocity(rng, 0.15), random_velocity(rng, 0.15);
          const Kernel kernel = [&](const VecX& pp, const VecX& vv, bool jac,
                                    ContactSampleResult& out) {
            CableSample s;
            s.e = pp.head<12>();
            s.e_dot = vv.head<12>();
            s.length = la;
            s.xi = xi_a;
            s.radius = ra;
            s.weight = la / 3.0;
            const Vec12 e_b = pp.tail<12>();
            const ElementProjection proj = project_onto_element(e_b, lb, centreline(s.e, la, xi_a));
            return evaluate_cable_cable_contact(law, s, e_b, vv.tail<12>(), lb, rb, proj.xi, jac,
                                                out);
          };
          const ElementProjection proj = project_onto_element(eb, lb, centreline(ea, la, xi_a));
          const std::string what = std::string(at_end ? "clamped" : "interior") + ", " + lc.name +
                                   ", delta/delta_s " + std::to_string(delta / kOnset);
          EXPECT_NEAR(proj.xi, xi_b, 1e-10) << what;
          EXPECT_NEAR(proj.distance, dist, 1e-14) << what;
          check_kernel(kernel, p, v, what, at_end ? worst_end : worst_interior);
        }
  for (const auto& [name, w] :
       {std::pair{"interior", &worst_interior}, std::pair{"clamped", &worst_end}})
    std::printf(
        "  cable-cable %s: %d cases; worst error/tolerance dQ/dP %.3f (error/max|J| %.1e), dQ/dV "
        "%.3f\n",
        name, w->cases, w->dq.max_ratio, w->dq.max_rel, w->dv.max_ratio);
}

// A planted error in a curvature term must be visible: drop the sliding of the closest point
// (∂ξ_b/∂P) by evaluating with a fixed ξ_b in the FD function — the analytic Jacobian (which has
// it) then disagrees with FD, so the check above can tell the terms apart.
TEST(CableCableContact, SlidingProjectionTermIsDetectable) {
  std::mt19937 rng(3);
  const ContactLaw law = make_law(kLaws[0]);
  Vec12 eb;
  eb << Vec3::Zero(), Vec3::UnitX(), Vec3(0.3, 0.02, 0.0), unit(Vec3(1.0, 0.2, 0.0));
  const Vec3 xb = centreline(eb, 0.3, 0.5), tb = unit(tangent(eb, 0.3, 0.5));
  const Vec12 ea =
      element_through(rng, 0.25, 0.5, xb + 0.015 * unit(tb.cross(Vec3::UnitZ() + 0.3 * tb)));
  VecX p(24), v = VecX::Zero(24);
  p << ea, eb;
  const double xi_b = project_onto_element(eb, 0.3, centreline(ea, 0.25, 0.5)).xi;
  const auto eval = [&](const VecX& pp, bool jac, ContactSampleResult& out) {
    CableSample s;
    s.e = pp.head<12>();
    s.length = 0.25;
    s.xi = 0.5;
    s.radius = 0.01;
    s.weight = 0.1;
    return evaluate_cable_cable_contact(law, s, pp.tail<12>(), Vec12::Zero(), 0.3, 0.008, xi_b, jac,
                                        out);
  };
  ContactSampleResult r;
  ASSERT_TRUE(eval(p, true, r));
  const fdcheck::Result frozen = fdcheck::check_jacobian(
      [&](const VecX& x) {
        ContactSampleResult s;
        eval(x, false, s);
        return VecX(s.force);
      },
      p, r.d_force_dq);
  std::printf("  frozen projection vs analytic: error/tolerance %.3g (must be > 1)\n",
              frozen.max_ratio);
  EXPECT_FALSE(frozen.ok());
}

// The projection finds the global minimum of the distance over the element (dense search).
TEST(ProjectOntoElement, FindsTheGlobalMinimum) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 200; ++trial) {
    Vec12 e;
    e << random_vec3(rng, 0.1), unit(random_vec3(rng, 1.0)) * 1.3, random_vec3(rng, 0.3),
        unit(random_vec3(rng, 1.0)) * 1.3;
    const double l = 0.3;
    const Vec3 x = random_vec3(rng, 0.3);
    const ElementProjection p = project_onto_element(e, l, x);
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 20000; ++k)
      best = std::min(best, (centreline(e, l, k / 20000.0) - x).norm());
    EXPECT_LE(p.distance, best + 1e-12) << trial;
    EXPECT_NEAR(p.distance, (centreline(e, l, p.xi) - x).norm(), 4 * kEps);
  }
}

}  // namespace
}  // namespace ancf
