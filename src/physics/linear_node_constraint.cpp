#include "ancf/physics/linear_node_constraint.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "ancf/core/error.hpp"

namespace ancf {

LinearNodeConstraint pin_to_ground(const Vec3& target) {
  LinearNodeConstraint k;
  k.rows = 3;
  k.g.leftCols<3>().setIdentity();
  k.c = target;
  return k;
}

LinearNodeConstraint slope_direction_to_ground(const Vec3& direction) {
  const double n = direction.norm();
  if (!(n > 0.0) || !std::isfinite(n)) throw ModelError("clamp direction must be a non-zero finite vector");
  const Vec3 d = direction / n;
  // Any vector not parallel to d gives a basis of the orthogonal plane.
  const Vec3 helper = std::abs(d.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 t1 = d.cross(helper).normalized();
  const Vec3 t2 = d.cross(t1);
  LinearNodeConstraint k;
  k.rows = 2;
  k.g.block<1, 3>(0, 3) = t1.transpose();
  k.g.block<1, 3>(1, 3) = t2.transpose();
  return k;
}

}  // namespace ancf
