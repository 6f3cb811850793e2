// Internal to the system layer: the exact minimum gaps of a contact pair that the outputs report
// (contact_output.hpp): over all samples of the pair, and over every point of the centreline of
// a cable–shape pair's elements. Both are the same numbers whichever way they are searched;
// ContactSearch::pruned skips elements whose bounding boxes prove that they cannot hold a smaller
// gap than one already found (branch and bound), ContactSearch::exhaustive evaluates every one.
#pragma once

#include "ancf/system/contact_output.hpp"
#include "contact_sampling.hpp"

namespace ancf::detail {

/// Smallest gap g over all samples of pair `pair` (Model numbering: cable–shape pairs first) [m],
/// each sample's gap computed by its contact kernel exactly as for the residual. Pruned: needs
/// refresh_cable_boxes at `state` first. Counts the kernel calls in ws.narrow_phase_samples.
double sample_min_gap(const Model& model, const SystemState& state, Workspace& ws, Index pair,
                      ContactSearch search);

/// Smallest gap d − r over every point of the centreline of cable–shape pair `pair`'s candidate
/// elements (not only at its samples) [m]: a scan of 17 points per element refined by
/// golden-section search. Pruned: needs refresh_cable_boxes at `state` first.
double centreline_min_gap(const Model& model, const SystemState& state, Workspace& ws, Index pair,
                          ContactSearch search);

}  // namespace ancf::detail
