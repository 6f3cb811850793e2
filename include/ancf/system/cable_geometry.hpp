// Nodal coordinates of a cable: generators for common stress-free reference shapes.
#pragma once

#include <span>
#include <vector>

#include "ancf/core/types.hpp"

namespace ancf {

using NodeCoordinates = Eigen::Matrix<double, 6, 1>;  ///< [r (m), r_x (-)] of one node

/// Nodes (position and slope) and element lengths of one cable, in order along the cable.
/// Slopes are derivatives with respect to the reference arc length, so for a reference shape
/// they are unit tangents. Invariant: nodes.size() == element_lengths.size() + 1.
struct CableGeometry {
  std::vector<NodeCoordinates> nodes;
  std::vector<double> element_lengths;  ///< [m], each > 0

  [[nodiscard]] Index element_count() const { return static_cast<Index>(element_lengths.size()); }
  [[nodiscard]] Index node_count() const { return static_cast<Index>(nodes.size()); }
  /// The 12 coordinates of element j: [node j, node j + 1].
  [[nodiscard]] Vec12 element_coordinates(Index j) const;
};

// The generators below place node k at arc-length fraction `fractions[k]` (n + 1 increasing
// values from 0 to 1, e.g. from node_fractions() in mesh_grading.hpp); empty: equal elements.

/// Straight cable from `start` to `end` with n ≥ 1 elements, slopes = unit direction.
[[nodiscard]] CableGeometry straight_cable(const Vec3& start, const Vec3& end, Index elements,
                                           std::span<const double> fractions = {});

/// Circular arc of radius R > 0 about `centre` in the plane spanned by unit vectors u (towards the
/// start point) and w (direction of travel at the start), from angle 0 to `angle` [rad].
[[nodiscard]] CableGeometry arc_cable(const Vec3& centre, const Vec3& u, const Vec3& w,
                                      double radius, double angle, Index elements,
                                      std::span<const double> fractions = {});

/// Helix about the axis through `base` along unit `axis`, radius R, starting at polar angle phi0
/// (measured from unit `u` ⊥ axis towards axis × u), turning by `twist` [rad] while rising `rise`
/// [m].
[[nodiscard]] CableGeometry helix_cable(const Vec3& base, const Vec3& axis, const Vec3& u,
                                        double radius, double phi0, double twist, double rise,
                                        Index elements, std::span<const double> fractions = {});

/// Reference material triads of a rod (kirchhoff_rod_element.hpp), one per node:
/// [t̂, d₂, d₃] with d₂ the unit part of `normal` orthogonal to the node's tangent t̂ and
/// d₃ = t̂ × d₂. For straight and polyline references. Throws ModelError where `normal` is
/// (nearly) parallel to a tangent.
[[nodiscard]] std::vector<Mat3> rod_frames_with_normal(const CableGeometry& g, const Vec3& normal);
/// The same with d₂ pointing from each node towards the axis through `point` along `axis`: the
/// principal normal of an arc (axis through its centre, normal to its plane) or of a helix.
[[nodiscard]] std::vector<Mat3> rod_frames_toward_axis(const CableGeometry& g, const Vec3& point,
                                                       const Vec3& axis);

}  // namespace ancf
