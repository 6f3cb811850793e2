// Seeded random rotations and vectors shared by the tests.
#pragma once

#include <Eigen/Geometry>
#include <random>

#include "ancf/core/types.hpp"

namespace ancf::random_geometry {

/// Uniformly distributed rotation: a normalised Gaussian quaternion.
inline Mat3 random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

/// Vector with independent N(0, scale²) components.
inline Vec3 random_vec3(std::mt19937& rng, double scale) {
  std::normal_distribution<double> n(0.0, scale);
  return {n(rng), n(rng), n(rng)};
}

}  // namespace ancf::random_geometry
