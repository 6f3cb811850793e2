// Graded meshes along a cable or rod: element lengths that shrink towards the ends, for the
// bending boundary layer of a clamped end under tension, and optionally in a band inside, e.g.
// where a rope wraps an obstacle (docs/scenes.md "grading", docs/capture.md "A clamped end has a
// bending boundary layer").
#pragma once

#include <vector>

#include "ancf/core/types.hpp"

namespace ancf {

/// A fixed mapping from uniform element indices to arc length, so that refining `elements`
/// refines every element by the same factor (a mesh convergence study stays a study of h).
/// The element density per unit length is
///   ρ(s) = 1 + (1/end_ratio − 1)(a e^{−s/ℓ} + b e^{−(L−s)/ℓ})
///            + (1/band_ratio − 1) e^{−((s − s_b)/μ)²},  ℓ = end_length, μ = band_width,
/// with a = at_start, b = at_end (0 or 1), s_b = band_centre·L: elements at a graded end are
/// about end_ratio times as long as those far from it and the refinement decays over ℓ from that
/// end; elements at the band's centre about band_ratio times (where both overlap, less).
struct MeshGrading {
  double end_ratio = 1.0;    ///< element length at a graded end over that far from it, (0, 1]
  double end_length = 0.0;   ///< ℓ [m], > 0 when end_ratio < 1
  bool at_start = true;      ///< grade towards node 0
  bool at_end = true;        ///< grade towards the last node
  double band_ratio = 1.0;   ///< element length at the band centre over that far from it, (0, 1]
  double band_width = 0.0;   ///< μ [m] (Gaussian half-width), > 0 when band_ratio < 1
  double band_centre = 0.5;  ///< s_b/L, in [0, 1]

  [[nodiscard]] bool graded_ends() const { return end_ratio != 1.0 && (at_start || at_end); }
  [[nodiscard]] bool graded_band() const { return band_ratio != 1.0; }
  [[nodiscard]] bool uniform() const { return !graded_ends() && !graded_band(); }
};

/// Arc-length fractions 0 = f₀ < f₁ < … < f_n = 1 of the nodes of `elements` ≥ 1 elements on a
/// curve of length `length` > 0 [m]: f_k = s_k/L with N(s_k) = (k/n) N(L), N = ∫ρ (closed form),
/// solved by safeguarded Newton to round-off. Uniform grading gives f_k = k/n exactly.
/// Throws ModelError on a ratio outside (0, 1], a non-positive end_length or band_width (where
/// used), a band centre outside [0, 1], or length scales so far below `length` that the fractions
/// do not increase in double precision.
[[nodiscard]] std::vector<double> node_fractions(Index elements, double length,
                                                 const MeshGrading& grading);

}  // namespace ancf
