// Constraint kinds of joints.hpp (DESIGN §4) on the dot-product kernel (dot_constraint.hpp).
//
// Every kind is checked at seeded random configurations of a 36-coordinate model (cable nodes at 0
// and 6, bodies at 12 and 24, two driven frames: constant rate and smooth ramp, tilted axes, non-
// trivial initial rotations): the configurations include the one the kind was built to satisfy
// (orthonormal bodies) and generic perturbations of it (non-orthonormal bodies), at several times.
//   * Φ_q, Φ_t, Φ_q v + Φ_t (total derivative), (Φ_q v)_q, the acceleration right-hand side γ and
//     the geometric stiffness ∂(Φ_qᵀλ)/∂q against central differences with error-estimated
//     tolerances (fd_check.hpp); γ also against a second difference of Φ along q0 + v t + ½ a t²;
//   * Φ = 0 to round-off at the configuration the kind was built for;
//   * with the orthonormality rows of its bodies every kind has full row rank (rows independent,
//     e.g. revolute to ground: rank 11 = 12 − 1 dof), and the motions the joint allows (rotation
//     about the hinge axis, rigid motion of the whole assembly, motion with a driven frame) satisfy
//     Φ_q v + Φ_t = 0.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <Eigen/SVD>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "ancf/core/error.hpp"
#include "ancf/physics/angle_law.hpp"
#include "ancf/physics/dot_constraint.hpp"
#include "ancf/physics/driven_frame.hpp"
#include "ancf/physics/joints.hpp"
#include "ancf/physics/rigid_body.hpp"
#include "fd_check.hpp"
#include "random_geometry.hpp"

namespace {
using namespace ancf;
constexpr double kEps = std::numeric_limits<double>::epsilon();

// ---- Model layout -------------------------------------------------------------------------------

constexpr Index kNodeA = 0, kNodeB = 6, kBody1 = 12, kBody2 = 24, kSize = 36;
using Frames = std::vector<FrameKinematics>;

using random_geometry::random_rotation;
using random_geometry::random_vec3;

VecX random_vector(std::mt19937& rng, Index size, double scale) {
  std::normal_distribution<double> n(0.0, scale);
  VecX x(size);
  for (Index i = 0; i < size; ++i) x[i] = n(rng);
  return x;
}

// Frame 0 spins at a constant rate, frame 1 is inside its smooth ramp for t < 1.5 s (θ̈ ≠ 0).
std::vector<DrivenFrame> make_frames() {
  DrivenFrame spin;
  spin.name = "spin";
  spin.origin = Vec3(0.3, -0.2, 0.5);
  spin.initial_rotation = Eigen::AngleAxisd(0.8, Vec3(1, 1, 0).normalized()).toRotationMatrix();
  spin.axis = Vec3(1.0, 2.0, -0.5).normalized();
  spin.law = AngleLaw::constant_rate(1.3, 0.4);
  DrivenFrame ramp;
  ramp.name = "ramp";
  ramp.origin = Vec3(-0.4, 0.1, 0.2);
  ramp.initial_rotation =
      Eigen::AngleAxisd(-1.1, Vec3(0.2, -1, 0.5).normalized()).toRotationMatrix();
  ramp.axis = Vec3(0.3, -0.4, 0.866).normalized();
  ramp.law = AngleLaw::smooth_ramp(2.5, 1.5, -0.3);
  return {spin, ramp};
}

Frames frames_at(const std::vector<DrivenFrame>& frames, double t) {
  Frames k;
  for (const DrivenFrame& f : frames) k.push_back(f.at(t));
  return k;
}

Vec3 frame_angular_velocity(const DrivenFrame& f, double t) {
  return f.law.at(t).rate * f.axis.normalized();
}

Mat3 rotation_at(const VecX& q, Index body) {
  return rotation_of(q.segment<12>(body));
}

// ---- Constraint kinds ---------------------------------------------------------------------------

struct Kind {
  std::string name;
  ConstraintRows rows;
  bool rheonomic = false;
  bool satisfied = true;      ///< the scenario's q_sat satisfies it at t_sat
  std::vector<Index> bodies;  ///< bodies whose orthonormality rows go with it (rank test)
  bool relative = false;      ///< invariant under a rigid motion of the whole assembly
  int frame = -1;             ///< the driven frame it is attached to
};

// A random orthonormal configuration q_sat (nodes A and B coincide) and, for every kind, joint data
// computed from it so that q_sat satisfies the joint at t_sat.
struct Scenario {
  std::vector<DrivenFrame> frames = make_frames();
  double t_sat = 0.7;
  VecX q_sat;
  std::vector<Kind> kinds;

  explicit Scenario(unsigned seed) {
    std::mt19937 rng(seed);
    const Vec3 r1 = random_vec3(rng, 1.0), r2 = random_vec3(rng, 1.0);
    const Mat3 a1 = random_rotation(rng), a2 = random_rotation(rng);
    const Vec3 r = random_vec3(rng, 1.0), rx = 1.3 * random_rotation(rng).col(0);
    q_sat = VecX::Zero(kSize);
    q_sat.segment<3>(kNodeA) = r;
    q_sat.segment<3>(kNodeA + 3) = rx;
    q_sat.segment<6>(kNodeB) = q_sat.segment<6>(kNodeA);
    q_sat.segment<12>(kBody1) = body_coordinates(r1, a1);
    q_sat.segment<12>(kBody2) = body_coordinates(r2, a2);
    const Frames fk = frames_at(frames, t_sat);

    auto add = [&](std::string name, ConstraintRows rows, std::vector<Index> bodies = {}) {
      Kind k;
      k.name = std::move(name);
      k.rows = rows;
      k.bodies = std::move(bodies);
      kinds.push_back(k);
      return &kinds.back();
    };
    // Cable node attachments.
    add("node_position_to_ground", node_position_to_ground(kNodeA, r));
    add("node_slope_to_ground", node_slope_to_ground(kNodeA, 2.0 * rx));
    add("node_position_to_body", node_position_to_body(kNodeA, kBody1, a1.transpose() * (r - r1)),
        {kBody1})
        ->relative = true;
    add("node_slope_to_body", node_slope_to_body(kNodeA, kBody1, 0.7 * a1.transpose() * rx),
        {kBody1})
        ->relative = true;
    for (int f = 0; f < 2; ++f) {
      const std::string suffix = "(" + frames[f].name + ")";
      Kind* k = add("node_position_to_frame" + suffix,
                    node_position_to_frame(kNodeA, f, fk[f].a.transpose() * (r - fk[f].r)));
      k->rheonomic = true;
      k->frame = f;
      k = add("node_slope_to_frame" + suffix,
              node_slope_to_frame(kNodeA, f, 0.5 * fk[f].a.transpose() * rx));
      k->rheonomic = true;
      k->frame = f;
    }
    add("node_to_node", node_to_node(kNodeA, kNodeB))->relative = true;
    add("node_slope_to_node_slope", node_slope_to_node_slope(kNodeA, kNodeB))->relative = true;
    // Directions along coordinate axes: perpendicular_pair returns axis-aligned t_i and add_body
    // drops zero weights. Only for the derivative checks (q_sat does not satisfy them).
    add("node_slope_to_ground(axis)", node_slope_to_ground(kNodeA, Vec3::UnitZ()))->satisfied =
        false;
    add("node_slope_to_body(axis)", node_slope_to_body(kNodeA, kBody2, Vec3::UnitY()), {kBody2})
        ->satisfied = false;

    // Rigid-body joints; body points with all components non-zero (body-body: 8 block terms).
    const Vec3 p1 = random_vec3(rng, 0.5), p1b = random_vec3(rng, 0.5);
    const Vec3 axis1 = random_vec3(rng, 1.0);
    const Vec3 g1 = r1 + a1 * p1;  // body-1 point p̄₁ in the global frame
    add("body_spherical_to_ground", body_spherical_to_ground(kBody1, p1, g1), {kBody1});
    add("body_revolute_to_ground",
        body_revolute_to_ground(kBody1, p1, axis1, g1, 3.0 * a1 * axis1.normalized()), {kBody1});
    add("body_fixed_to_ground", body_fixed_to_ground(kBody1, p1b, r1 + a1 * p1b, a1), {kBody1});
    const Vec3 p2 = a2.transpose() * (g1 - r2);
    add("body_spherical", body_spherical(kBody1, p1, kBody2, p2), {kBody1, kBody2})->relative =
        true;
    add("body_revolute",
        body_revolute(kBody1, p1, axis1, kBody2, p2, 0.5 * a2.transpose() * a1 * axis1),
        {kBody1, kBody2})
        ->relative = true;
    add("body_fixed", body_fixed(kBody1, p1, kBody2, p2, a1.transpose() * a2), {kBody1, kBody2})
        ->relative = true;
    add("body_orthonormality(1)", body_orthonormality(kBody1), {kBody1})->relative = true;
    add("body_orthonormality(2)", body_orthonormality(kBody2), {kBody2})->relative = true;
  }
};

// ---- Evaluation through the kernel --------------------------------------------------------------

std::span<const double> span_of(const VecX& x) {
  return as_span(x);
}

std::vector<DotConstraintValues> values(const ConstraintRows& c, const VecX& q, const VecX& v,
                                        const Frames& f) {
  std::vector<DotConstraintValues> out;
  for (int r = 0; r < c.count; ++r) out.push_back(evaluate(c.rows[r], span_of(q), span_of(v), f));
  return out;
}

VecX phi(const ConstraintRows& c, const VecX& q, const Frames& f) {
  VecX out(c.count);
  for (int r = 0; r < c.count; ++r) out[r] = evaluate(c.rows[r], span_of(q), {}, f).phi;
  return out;
}

template <class Field>
VecX field(const ConstraintRows& c, const VecX& q, const VecX& v, const Frames& f, Field get) {
  const auto vals = values(c, q, v, f);
  VecX out(c.count);
  for (int r = 0; r < c.count; ++r) out[r] = get(vals[r]);
  return out;
}

/// Dense Φ_q (velocity = false) or (Φ_q v)_q (velocity = true) from gradient_blocks, accumulating
/// repeated blocks (a_i·a_i, or a block in both u and w).
MatX jacobian(const ConstraintRows& c, const VecX& q, const VecX& v, const Frames& f,
              bool velocity) {
  MatX j = MatX::Zero(c.count, q.size());
  for (int r = 0; r < c.count; ++r) {
    const DotConstraintRow& row = c.rows[r];
    const AffineVectorState us = evaluate(row.u, span_of(q), span_of(v), f);
    const AffineVectorState ws = evaluate(row.w, span_of(q), span_of(v), f);
    std::array<Vec3, AffineVector::kMaxTerms> gu, gw;
    gradient_blocks(row, us, ws, velocity, std::span(gu).first(row.u.term_count),
                    std::span(gw).first(row.w.term_count));
    for (int k = 0; k < row.u.term_count; ++k)
      j.block<1, 3>(r, row.u.terms[k].block) += gu[k].transpose();
    for (int k = 0; k < row.w.term_count; ++k)
      j.block<1, 3>(r, row.w.terms[k].block) += gw[k].transpose();
  }
  return j;
}

/// Dense Σ_r λ_r ∂(Φ_r,qᵀ)/∂q from the kernel's block visitor.
MatX geometric_stiffness(const ConstraintRows& c, const VecX& lambda, Index n) {
  MatX k = MatX::Zero(n, n);
  for (int r = 0; r < c.count; ++r)
    add_geometric_stiffness(c.rows[r], lambda[r], [&](Index i, Index j, double coefficient) {
      k.block<3, 3>(i, j).diagonal().array() += coefficient;
    });
  return k;
}

// ---- Magnitudes of the terms (rounding scale of the finite differences) -------------------------
// Φ = u·w + c is a sum of products of block terms; where Φ is small next to them (a satisfied
// constraint, a_i·a_i − 1) max |Φ| would underestimate its rounding error, so fd_check's f_scale is
// the magnitude of the terms: ‖u‖~ = Σ|α_k| ‖q_b‖ + ‖o‖ + |s| ‖r_F‖ + ‖A_F f‖ and so on.

struct Magnitude {
  double value = 0.0, velocity = 0.0, rate = 0.0, accel = 0.0;
  double max_coefficient = 0.0;
};

Magnitude magnitude(const AffineVector& u, const VecX& q, const VecX& v, const Frames& f) {
  Magnitude m;
  m.value = u.offset.norm();
  for (int k = 0; k < u.term_count; ++k) {
    const BlockTerm& t = u.terms[k];
    m.value += std::abs(t.coefficient) * q.segment<3>(t.block).norm();
    if (v.size() > 0) m.velocity += std::abs(t.coefficient) * v.segment<3>(t.block).norm();
    m.max_coefficient = std::max(m.max_coefficient, std::abs(t.coefficient));
  }
  if (u.frame >= 0) {
    const FrameKinematics& k = f[u.frame];
    const double s = std::abs(u.frame_position_scale);
    m.value += s * k.r.norm() + (k.a * u.frame_vector).norm();
    m.rate = s * k.r_dot.norm() + (k.a_dot * u.frame_vector).norm();
    m.accel = s * k.r_ddot.norm() + (k.a_ddot * u.frame_vector).norm();
  }
  return m;
}

struct RowScales {
  double phi = 0.0;         ///< of Φ
  double derivative = 0.0;  ///< of Φ_q v + Φ_t
  double gradient = 0.0;    ///< of Φ_qᵀλ (with the λ of the point)
};

RowScales scales(const ConstraintRows& c, const VecX& q, const VecX& v, const VecX& lambda,
                 const Frames& f) {
  RowScales s;
  for (int r = 0; r < c.count; ++r) {
    const Magnitude u = magnitude(c.rows[r].u, q, v, f), w = magnitude(c.rows[r].w, q, v, f);
    s.phi = std::max(s.phi, u.value * w.value + std::abs(c.rows[r].c));
    s.derivative = std::max(s.derivative, u.velocity * w.value + u.value * w.velocity +
                                              u.rate * w.value + u.value * w.rate);
    if (lambda.size() > 0)
      s.gradient +=
          std::abs(lambda[r]) * (u.max_coefficient * w.value + w.max_coefficient * u.value);
  }
  return s;
}

// ---- Second difference with a Richardson error estimate -----------------------------------------
// D(h) = (f(h) − 2 f(0) + f(−h)) / h² has truncation error c h² + O(h⁴), so |D(h) − D(2h)| / 3
// estimates it; rounding ≈ 4 eps f_scale / h², balanced at h = eps^¼. Same tolerance form as
// fd_check.hpp.
fdcheck::Result check_second_derivative(const std::function<VecX(double)>& f, const VecX& d2,
                                        double f_scale, double safety = 10.0) {
  const double h = std::pow(kEps, 0.25);
  auto difference = [&](double step) {
    return VecX((f(step) - 2.0 * f(0.0) + f(-step)) / (step * step));
  };
  const VecX e1 = difference(h), e2 = difference(2.0 * h);
  const double rounding = 4.0 * kEps * f_scale / (h * h);
  const double floor = 4.0 * kEps * d2.norm();
  const double d_max = std::max(d2.cwiseAbs().maxCoeff(), std::numeric_limits<double>::min());
  fdcheck::Result r;
  for (Index i = 0; i < d2.size(); ++i) {
    const double tol = safety * (std::abs(e1[i] - e2[i]) / 3.0 + rounding) + floor;
    const double err = std::abs(e1[i] - d2[i]);
    const double ratio = err == 0.0 ? 0.0 : err / tol;
    r.max_rel = std::max(r.max_rel, err / d_max);
    r.max_tol_rel = std::max(r.max_tol_rel, tol / d_max);
    if (r.row < 0 || ratio > r.max_ratio) {
      r.max_ratio = ratio;
      r.row = i;
      r.col = 0;
      r.analytic = d2[i];
      r.fd = e1[i];
      r.tol = tol;
    }
  }
  return r;
}

// ---- The derivative checks: every kind × seeds × configurations ---------------------------------

struct Point {
  VecX q, v, a, lambda;
  double t = 0.0;
  std::string label;
};

// Configuration 0: q_sat at t_sat (orthonormal, satisfied); 1-3: generic (non-orthonormal)
// perturbations at times inside the ramp (θ̈ ≠ 0) and after it.
std::vector<Point> points(const Scenario& sc, unsigned seed) {
  std::mt19937 rng(1000 + seed);
  const double times[] = {sc.t_sat, 0.3, 1.1, 2.4};
  std::vector<Point> out;
  for (int k = 0; k < 4; ++k) {
    Point p;
    p.q = k == 0 ? sc.q_sat : VecX(sc.q_sat + random_vector(rng, kSize, 0.3));
    p.v = random_vector(rng, kSize, 1.0);
    p.a = random_vector(rng, kSize, 1.0);
    p.lambda = random_vector(rng, 6, 1.0);
    p.t = times[k];
    p.label = "seed " + std::to_string(seed) + (k == 0 ? " q_sat" : " generic") +
              " t=" + std::to_string(p.t);
    out.push_back(p);
  }
  return out;
}

using Check = std::function<fdcheck::Result(const Scenario&, const Kind&, const Point&)>;

// Runs `check` for every kind, seed and point; prints the worst ratio, |FD − analytic| / max|J| and
// tolerance / max|J| per kind, and expects ratio < 1 everywhere.
void run_check(const char* title, const Check& check, bool rheonomic_only = false) {
  std::map<std::string, fdcheck::Result> worst;
  std::map<std::string, std::string> where;
  std::vector<std::string> order;
  fdcheck::Result total;
  for (unsigned seed : {1u, 2u, 3u}) {
    const Scenario sc(seed);
    for (const Point& p : points(sc, seed))
      for (const Kind& k : sc.kinds) {
        if (rheonomic_only && !k.rheonomic) continue;
        const fdcheck::Result r = check(sc, k, p);
        if (!worst.contains(k.name)) {
          order.push_back(k.name);
          worst[k.name] = r;
          where[k.name] = p.label;
        } else {
          if (r.max_ratio > worst[k.name].max_ratio) where[k.name] = p.label;
          worst[k.name].merge(r);
        }
        total.merge(r);
        EXPECT_LT(r.max_ratio, 1.0)
            << title << ", " << k.name << ", " << p.label << ": entry (" << r.row << ", " << r.col
            << ") analytic " << r.analytic << " fd " << r.fd << " tolerance " << r.tol;
      }
  }
  // err/max, tol/max: relative to max |analytic|; where the analytic matrix is exactly zero (a
  // constant Φ_q) fd_check divides by DBL_MIN, so those kinds print "exact" (the FD is then zero
  // too: err/tol = 0).
  std::printf("\n%s\n  %-36s %10s %10s %10s  %s\n", title, "kind", "err/tol", "err/max", "tol/max",
              "worst at");
  double tol_rel = 0.0, err_rel = 0.0;
  for (const std::string& name : order) {
    const fdcheck::Result& r = worst[name];
    if (r.max_tol_rel > 1e100) {
      std::printf("  %-36s %10.2e %21s  (analytic = 0 exactly)\n", name.c_str(), r.max_ratio, "");
      continue;
    }
    tol_rel = std::max(tol_rel, r.max_tol_rel);
    err_rel = std::max(err_rel, r.max_rel);
    std::printf("  %-36s %10.2e %10.2e %10.2e  %s\n", name.c_str(), r.max_ratio, r.max_rel,
                r.max_tol_rel, where[name].c_str());
  }
  std::printf("  %-36s %10.2e %10.2e %10.2e\n", "ALL", total.max_ratio, err_rel, tol_rel);
}

// ---- Tests ------------------------------------------------------------------------------------

TEST(PerpendicularPair, OrthonormalRightHanded) {
  std::mt19937 rng(7);
  std::vector<Vec3> dirs = {Vec3::UnitX(),       Vec3::UnitY(),        Vec3::UnitZ(),
                            -Vec3::UnitZ(),      Vec3(1, 1e-12, 0),    Vec3(1, 1, 1),
                            Vec3(-3, 0, 1e-300), Vec3(1e-20, 2e-20, 0)};
  for (int i = 0; i < 100; ++i) dirs.push_back(random_vec3(rng, 10.0));
  double worst = 0.0;
  for (const Vec3& d : dirs) {
    Vec3 t1, t2;
    perpendicular_pair(d, t1, t2);
    const Vec3 n = d.normalized();
    Mat3 b;
    b << t1, t2, n;
    const double err =
        std::max((b.transpose() * b - Mat3::Identity()).norm(), (t1.cross(t2) - n).norm());
    worst = std::max(worst, err);
    EXPECT_LT(err, 8 * kEps) << "d = " << d.transpose();
  }
  std::printf(
      "perpendicular_pair: worst |[t1 t2 n]^T[t1 t2 n] - I|, |t1 x t2 - n| = %.2e (tol %.2e)\n",
      worst, 8 * kEps);
}

TEST(Joints, RowCountsAndTermLimit) {
  const Scenario sc(1);
  const std::map<std::string, int> expected_rows = {{"node_position_to_ground", 3},
                                                    {"node_slope_to_ground", 2},
                                                    {"node_position_to_body", 3},
                                                    {"node_slope_to_body", 2},
                                                    {"node_to_node", 3},
                                                    {"node_slope_to_node_slope", 3},
                                                    {"body_spherical_to_ground", 3},
                                                    {"body_revolute_to_ground", 5},
                                                    {"body_fixed_to_ground", 6},
                                                    {"body_spherical", 3},
                                                    {"body_revolute", 5},
                                                    {"body_fixed", 6},
                                                    {"body_orthonormality(1)", 6}};
  for (const Kind& k : sc.kinds)
    if (expected_rows.contains(k.name)) {
      EXPECT_EQ(k.rows.count, expected_rows.at(k.name)) << k.name;
    }
  // Body-body spherical with a generic point: r_O1 + Σ p̄₁ a₁ − r_O2 − Σ p̄₂ a₂, 8 block terms.
  const ConstraintRows s =
      body_spherical(kBody1, Vec3(0.1, 0.2, 0.3), kBody2, Vec3(-0.4, 0.5, -0.6));
  for (int r = 0; r < s.count; ++r) EXPECT_EQ(s.rows[r].w.term_count, 8);
  AffineVector full = s.rows[0].w;
  EXPECT_THROW(full.add(0, 1.0), std::length_error);
  // Zero body-frame components are dropped.
  const ConstraintRows p = node_position_to_body(kNodeA, kBody1, Vec3(0.0, 0.5, 0.0));
  EXPECT_EQ(p.rows[0].w.term_count, 3);
}

TEST(Joints, InvalidInput) {
  EXPECT_THROW((void)node_slope_to_ground(kNodeA, Vec3::Zero()), ModelError);
  EXPECT_THROW((void)node_slope_to_body(kNodeA, kBody1, Vec3(NAN, 0, 1)), ModelError);
  EXPECT_THROW((void)node_position_to_ground(kNodeA, Vec3(INFINITY, 0, 0)), ModelError);
  EXPECT_THROW((void)body_revolute_to_ground(kBody1, Vec3::Zero(), Vec3::Zero(), Vec3::Zero(),
                                             Vec3::UnitZ()),
               ModelError);
  EXPECT_THROW(
      (void)body_fixed_to_ground(kBody1, Vec3::Zero(), Vec3::Zero(), 2.0 * Mat3::Identity()),
      ModelError);
  EXPECT_THROW((void)body_fixed(kBody1, Vec3::Zero(), kBody2, Vec3::Zero(), -Mat3::Identity()),
               ModelError);
  EXPECT_THROW((void)node_position_to_frame(kNodeA, -1, Vec3::Zero()), ModelError);
}

TEST(Joints, JacobianMatchesFiniteDifferences) {
  run_check("Phi_q vs FD of Phi over q", [](const Scenario& sc, const Kind& k, const Point& p) {
    const Frames f = frames_at(sc.frames, p.t);
    const MatX j = jacobian(k.rows, p.q, p.v, f, false);
    // Φ_q v from the kernel's scalar path agrees with the assembled Φ_q to round-off.
    const VecX qv =
        field(k.rows, p.q, p.v, f, [](const DotConstraintValues& x) { return x.phi_q_v; });
    const double s = scales(k.rows, p.q, p.v, VecX(), f).derivative;
    EXPECT_LE((qv - j * p.v).cwiseAbs().maxCoeff(), 16 * kEps * s) << k.name;
    fdcheck::Options opt;
    opt.f_scale = scales(k.rows, p.q, VecX(), VecX(), f).phi;
    return fdcheck::check_jacobian([&](const VecX& x) { return phi(k.rows, x, f); }, p.q, j, opt);
  });
}

TEST(Joints, TimeDerivativeMatchesFiniteDifferences) {
  run_check(
      "Phi_t vs FD of Phi over t (rheonomic kinds)",
      [](const Scenario& sc, const Kind& k, const Point& p) {
        const Frames f = frames_at(sc.frames, p.t);
        const VecX pt =
            field(k.rows, p.q, p.v, f, [](const DotConstraintValues& x) { return x.phi_t; });
        EXPECT_GT(pt.norm(), 0.0) << k.name;
        fdcheck::Options opt;
        opt.f_scale = scales(k.rows, p.q, VecX(), VecX(), f).phi;
        return fdcheck::check_jacobian(
            [&](const VecX& t) { return phi(k.rows, p.q, frames_at(sc.frames, t[0])); },
            VecX::Constant(1, p.t), MatX(pt), opt);
      },
      true);
  // Scleronomic kinds: Φ_t = 0 exactly.
  const Scenario sc(1);
  for (const Kind& k : sc.kinds) {
    if (k.rheonomic) continue;
    for (const DotConstraintValues& x :
         values(k.rows, sc.q_sat, sc.q_sat, frames_at(sc.frames, 0.7)))
      EXPECT_EQ(x.phi_t, 0.0) << k.name;
  }
}

TEST(Joints, TotalDerivativeMatchesFiniteDifferences) {
  run_check("Phi_q v + Phi_t vs FD of Phi(q + s v, t + s) over s",
            [](const Scenario& sc, const Kind& k, const Point& p) {
              const Frames f = frames_at(sc.frames, p.t);
              const VecX d = field(k.rows, p.q, p.v, f, [](const DotConstraintValues& x) {
                return x.phi_q_v + x.phi_t;
              });
              fdcheck::Options opt;
              opt.f_scale = scales(k.rows, p.q, VecX(), VecX(), f).phi;
              return fdcheck::check_jacobian(
                  [&](const VecX& s) {
                    return phi(k.rows, p.q + s[0] * p.v, frames_at(sc.frames, p.t + s[0]));
                  },
                  VecX::Zero(1), MatX(d), opt);
            });
}

TEST(Joints, VelocityJacobianMatchesFiniteDifferences) {
  run_check("(Phi_q v)_q vs FD of Phi_q v over q", [](const Scenario& sc, const Kind& k,
                                                      const Point& p) {
    const Frames f = frames_at(sc.frames, p.t);
    const MatX jv = jacobian(k.rows, p.q, p.v, f, true);
    fdcheck::Options opt;
    opt.f_scale = scales(k.rows, p.q, p.v, VecX(), f).derivative;
    return fdcheck::check_jacobian(
        [&](const VecX& x) {
          return field(k.rows, x, p.v, f, [](const DotConstraintValues& y) { return y.phi_q_v; });
        },
        p.q, jv, opt);
  });
}

// Along q(s) = q + v s + ½ a s², t + s: d²Φ/ds² = Φ_q a + (Φ_q v)_q v + 2 Φ_qt v + Φ_tt = Φ_q a −
// γ.
VecX second_total_derivative(const Kind& k, const Frames& f, const Point& p) {
  const MatX j = jacobian(k.rows, p.q, p.v, f, false);
  const VecX gamma =
      field(k.rows, p.q, p.v, f, [](const DotConstraintValues& x) { return x.gamma; });
  return j * p.a - gamma;
}

TEST(Joints, GammaMatchesDerivativeOfTotalDerivative) {
  run_check("Phi_q a - gamma vs FD over s of (Phi_q q' + Phi_t)(q(s), q'(s), t + s)",
            [](const Scenario& sc, const Kind& k, const Point& p) {
              const Frames f = frames_at(sc.frames, p.t);
              fdcheck::Options opt;
              opt.f_scale = scales(k.rows, p.q, p.v, VecX(), f).derivative;
              return fdcheck::check_jacobian(
                  [&](const VecX& s) {
                    const VecX q = p.q + s[0] * p.v + 0.5 * s[0] * s[0] * p.a;
                    const VecX v = p.v + s[0] * p.a;
                    return field(k.rows, q, v, frames_at(sc.frames, p.t + s[0]),
                                 [](const DotConstraintValues& x) { return x.phi_q_v + x.phi_t; });
                  },
                  VecX::Zero(1), MatX(second_total_derivative(k, f, p)), opt);
            });
}

TEST(Joints, GammaMatchesSecondDifference) {
  run_check("Phi_q a - gamma vs second difference of Phi(q + v s + a s^2/2, t + s)",
            [](const Scenario& sc, const Kind& k, const Point& p) {
              const Frames f = frames_at(sc.frames, p.t);
              return check_second_derivative(
                  [&](double s) {
                    return phi(k.rows, p.q + s * p.v + 0.5 * s * s * p.a,
                               frames_at(sc.frames, p.t + s));
                  },
                  second_total_derivative(k, f, p), scales(k.rows, p.q, VecX(), VecX(), f).phi);
            });
}

TEST(Joints, GeometricStiffnessMatchesFiniteDifferences) {
  run_check("d(Phi_q^T lambda)/dq vs FD of Phi_q^T lambda over q",
            [](const Scenario& sc, const Kind& k, const Point& p) {
              const Frames f = frames_at(sc.frames, p.t);
              const VecX lambda = p.lambda.head(k.rows.count);
              const MatX kg = geometric_stiffness(k.rows, lambda, kSize);
              EXPECT_EQ((kg - kg.transpose()).norm(), 0.0) << k.name;
              fdcheck::Options opt;
              opt.f_scale = scales(k.rows, p.q, VecX(), lambda, f).gradient;
              return fdcheck::check_jacobian(
                  [&](const VecX& x) {
                    return VecX(jacobian(k.rows, x, p.v, f, false).transpose() * lambda);
                  },
                  p.q, kg, opt);
            });
}

TEST(Joints, ResidualVanishesAtSatisfiedConfiguration) {
  double worst = 0.0;
  for (unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    const Scenario sc(seed);
    const Frames f = frames_at(sc.frames, sc.t_sat);
    for (const Kind& k : sc.kinds) {
      if (!k.satisfied) continue;
      const VecX r = phi(k.rows, sc.q_sat, f);
      const double s = scales(k.rows, sc.q_sat, VecX(), VecX(), f).phi;
      const double ratio = r.cwiseAbs().maxCoeff() / (kEps * s);
      worst = std::max(worst, ratio);
      EXPECT_LE(ratio, 16.0) << k.name << " seed " << seed << ": Phi = " << r.transpose();
    }
  }
  std::printf(
      "\nPhi at the satisfied configuration: worst |Phi| / (eps * term scale) = %.2f (tol 16)\n",
      worst);
}

// Jacobian of a kind together with the orthonormality rows of its bodies, at q_sat.
MatX jacobian_with_orthonormality(const Scenario& sc, const Kind& k) {
  const Frames f = frames_at(sc.frames, sc.t_sat);
  const VecX zero = VecX::Zero(kSize);
  MatX j = jacobian(k.rows, sc.q_sat, zero, f, false);
  for (Index b : k.bodies) {
    const MatX o = jacobian(body_orthonormality(b), sc.q_sat, zero, f, false);
    MatX stacked(j.rows() + o.rows(), kSize);
    stacked << j, o;
    j = stacked;
  }
  return j;
}

TEST(Joints, RowsIndependentWithOrthonormality) {
  std::printf("\nrank of [Phi_q; orthonormality rows of its bodies] at q_sat (seed 1..3):\n");
  const std::map<std::string, int> expected = {
      {"body_spherical_to_ground", 9}, {"body_revolute_to_ground", 11},
      {"body_fixed_to_ground", 12},    {"body_spherical", 15},
      {"body_revolute", 17},           {"body_fixed", 18}};
  for (unsigned seed : {1u, 2u, 3u}) {
    const Scenario sc(seed);
    for (const Kind& k : sc.kinds) {
      if (!k.satisfied || k.name.starts_with("body_orthonormality")) continue;
      const MatX j = jacobian_with_orthonormality(sc, k);
      const Eigen::ColPivHouseholderQR<MatX> qr(j);
      const Eigen::JacobiSVD<MatX> svd(j);
      const auto& sv = svd.singularValues();
      const double cond = sv[0] / sv[sv.size() - 1];
      EXPECT_EQ(qr.rank(), j.rows()) << k.name << " seed " << seed;
      EXPECT_LT(cond, 1e3) << k.name << " seed " << seed;  // well separated from dependence
      if (expected.contains(k.name)) {
        EXPECT_EQ(qr.rank(), expected.at(k.name)) << k.name;
      }
      if (seed == 1)
        std::printf("  %-36s rows %2d rank %2d  sigma_max/sigma_min = %.2f\n", k.name.c_str(),
                    static_cast<int>(j.rows()), static_cast<int>(qr.rank()), cond);
    }
  }
}

// Velocities of nodes and bodies for a rigid motion of everything with angular velocity ω about
// the point c (plus translation `vc` of c).
VecX rigid_motion(const VecX& q, const Vec3& c, const Vec3& vc, const Vec3& w) {
  VecX v = VecX::Zero(kSize);
  for (Index node : {kNodeA, kNodeB}) {
    v.segment<3>(node) = vc + w.cross(q.segment<3>(node) - c);
    v.segment<3>(node + 3) = w.cross(q.segment<3>(node + 3));
  }
  for (Index body : {kBody1, kBody2})
    v.segment<12>(body) =
        body_velocities(rotation_at(q, body), vc + w.cross(q.segment<3>(body) - c), w);
  return v;
}

TEST(Joints, AllowedMotionsSatisfyVelocityConstraint) {
  std::mt19937 rng(99);
  double worst = 0.0;
  auto expect_zero = [&](const Kind& k, const VecX& d, double scale, const std::string& what) {
    const double ratio = d.cwiseAbs().maxCoeff() / (kEps * scale);
    worst = std::max(worst, ratio);
    EXPECT_LE(ratio, 64.0) << k.name << ": " << what << ": " << d.transpose();
  };
  for (unsigned seed : {1u, 2u, 3u}) {
    const Scenario sc(seed);
    const Frames f = frames_at(sc.frames, sc.t_sat);
    const VecX& q = sc.q_sat;
    auto total = [&](const Kind& k, const VecX& v) {
      return field(k.rows, q, v, f,
                   [](const DotConstraintValues& x) { return x.phi_q_v + x.phi_t; });
    };
    for (const Kind& k : sc.kinds) {
      if (!k.satisfied) continue;
      // Relative joints: any rigid motion of the whole assembly.
      if (k.relative) {
        const VecX v =
            rigid_motion(q, random_vec3(rng, 1.0), random_vec3(rng, 1.0), random_vec3(rng, 1.0));
        expect_zero(k, total(k, v), scales(k.rows, q, v, VecX(), f).derivative, "rigid motion");
      }
      // Attachments to a driven frame: node moving with the frame.
      if (k.frame >= 0) {
        const DrivenFrame& df = sc.frames[k.frame];
        const VecX v =
            rigid_motion(q, df.origin, Vec3::Zero(), frame_angular_velocity(df, sc.t_sat));
        expect_zero(k, total(k, v), scales(k.rows, q, v, VecX(), f).derivative,
                    "motion with frame");
      }
    }
    // Body joints to ground: rotations about the ground point (spherical), about the hinge axis
    // (revolute); a rotation off the hinge axis violates the revolute.
    const Scenario& s = sc;
    for (const Kind& k : s.kinds) {
      if (k.name != "body_spherical_to_ground" && k.name != "body_revolute_to_ground") continue;
      const DotConstraintRow& row0 = k.rows.rows[0];  // ē_0·(r_P − p): offset is −p
      const Vec3 p = -row0.w.offset;
      Vec3 w = random_vec3(rng, 1.0);
      if (k.name == "body_revolute_to_ground") {
        // Hinge axis n: the ground axis is ⊥ to the two perpendiculars t_i (rows 3 and 4).
        const Vec3 n = k.rows.rows[3].u.offset.cross(k.rows.rows[4].u.offset);
        const VecX off = rigid_motion(q, p, Vec3::Zero(), n.cross(w));
        EXPECT_GT(total(k, off).cwiseAbs().maxCoeff(), 1e-3) << "rotation off the hinge axis";
        w = 1.7 * n;
      }
      const VecX v = rigid_motion(q, p, Vec3::Zero(), w);
      expect_zero(k, total(k, v), scales(k.rows, q, v, VecX(), f).derivative,
                  "rotation about joint");
    }
  }
  std::printf("\nallowed motions: worst |Phi_q v + Phi_t| / (eps * term scale) = %.2f (tol 64)\n",
              worst);
}

}  // namespace
