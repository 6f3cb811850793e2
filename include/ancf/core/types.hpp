// Basic scalar, index and vector types shared by every layer.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>

namespace ancf {

/// Index type of unknowns and sparse-matrix entries. 64-bit to match SUNDIALS' sunindextype
/// (Debian's build uses 64-bit indices) and KLU's klu_l_* interface.
using Index = std::int64_t;

using Vec3 = Eigen::Vector3d;
using Vec4 = Eigen::Vector4d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;
using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using VecX = Eigen::VectorXd;
using MatX = Eigen::MatrixXd;

/// Views of an Eigen vector as a span, for the span-based solver interfaces.
inline std::span<double> as_span(VecX& v) { return {v.data(), static_cast<std::size_t>(v.size())}; }
inline std::span<const double> as_span(const VecX& v) {
  return {v.data(), static_cast<std::size_t>(v.size())};
}

}  // namespace ancf
