#include "ancf/physics/rigid_body.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

void RigidBodyInertia::validate(const std::string& body) const {
  auto fail = [&](const std::string& what) { throw ModelError("body '" + body + "': " + what); };
  if (!(mass > 0.0) || !std::isfinite(mass)) fail("mass must be > 0 kg, got " + std::to_string(mass));
  if (!centre_of_mass.allFinite()) fail("centre of mass is not finite");
  if (!inertia.allFinite() || (inertia - inertia.transpose()).norm() > 1e-12 * inertia.norm())
    fail("inertia tensor must be finite and symmetric");
  const Vec3 p = Eigen::SelfAdjointEigenSolver<Mat3>(inertia).eigenvalues();
  // Computed eigenvalues carry round-off ~eps·‖I‖: a semi-definite I (ideal thin rod) must not pass
  // or fail depending on its orientation, so positive means above the same relative tolerance.
  const double tol = 1e-12 * std::abs(p.sum());
  if (!(p.minCoeff() > tol)) fail("inertia tensor must be positive definite");
  // J̄_c = ½tr(I)1 − I must be positive semi-definite: each principal moment ≤ sum of the others.
  if (p[2] > p[0] + p[1] + tol)
    fail("principal moments violate the triangle inequality I3 <= I1 + I2");
}

Mat4 natural_mass_matrix(const RigidBodyInertia& in) {
  const double m = in.mass;
  const Vec3& c = in.centre_of_mass;
  const Mat3 j_c = 0.5 * in.inertia.trace() * Mat3::Identity() - in.inertia;
  Mat4 m4;
  m4(0, 0) = m;
  m4.block<1, 3>(0, 1) = m * c.transpose();
  m4.block<3, 1>(1, 0) = m * c;
  // c̄c̄ᵀ evaluated on its own (Eigen rewrites m·(c̄c̄ᵀ) as (m c̄)c̄ᵀ, which is not exactly
  // symmetric): c_i c_j = c_j c_i, so M is exactly symmetric for a symmetric I_c.
  const Mat3 cc = c * c.transpose();
  m4.block<3, 3>(1, 1) = m * cc + j_c;
  return m4;
}

BodyCoordinates body_coordinates(const Vec3& position, const Mat3& rotation) {
  BodyCoordinates q;
  q << position, rotation.col(0), rotation.col(1), rotation.col(2);
  return q;
}

BodyCoordinates body_velocities(const Mat3& rotation, const Vec3& v, const Vec3& w) {
  BodyCoordinates qd;
  qd << v, w.cross(rotation.col(0)), w.cross(rotation.col(1)), w.cross(rotation.col(2));
  return qd;
}

Vec3 angular_velocity(const BodyCoordinates& q, const BodyCoordinates& v) {
  Vec3 w = Vec3::Zero();
  for (int k = 1; k <= 3; ++k) w += q.segment<3>(3 * k).cross(v.segment<3>(3 * k));
  return 0.5 * w;
}

Mat3 rotation_of(const BodyCoordinates& q) {
  Mat3 a;
  a << q.segment<3>(3), q.segment<3>(6), q.segment<3>(9);
  return a;
}

}  // namespace ancf
