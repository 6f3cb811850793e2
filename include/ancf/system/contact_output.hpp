// Contact outputs (issue: per pair active flag, minimum gap, force resultants; per cable first
// contact time). Computed on demand at output times; the minimum gaps are exact over all samples
// (and the whole centreline) even for pairs that are far apart.
#pragma once

#include <limits>
#include <span>
#include <vector>

#include "ancf/system/assembly.hpp"

namespace ancf {

struct ContactPairState {
  bool active = false;  ///< at least one sample penetrates (g < 0)
  int active_samples = 0;
  double min_gap = std::numeric_limits<double>::infinity();  ///< min over all samples [m]
  /// Cable–shape pairs: min of the gap over every point of the candidate elements' centrelines,
  /// samples or not [m] (< 0: the cable touches the shape somewhere, even where no sample
  /// penetrates yet, so no force acts there). NaN for cable–cable pairs.
  double min_centreline_gap = std::numeric_limits<double>::quiet_NaN();
  Vec3 normal_force = Vec3::Zero();    ///< Σ w f_n n on the pair's (first) cable [N]
  Vec3 friction_force = Vec3::Zero();  ///< Σ w f_t on the pair's (first) cable [N]
  double peak_sample_force = 0.0;      ///< max over samples of |w f_n| [N]
  /// Where the resultant acts: mean of the active samples' centreline points weighted by |w f_n|
  /// [m] (zero when inactive). Used to draw the contact force (VTK output).
  Vec3 centre = Vec3::Zero();
};

/// How contact_states finds the minimum gaps; both give the same numbers, bit for bit.
enum class ContactSearch {
  /// Active samples through the broad phase (those the residual sees); the minimum gaps by branch
  /// and bound on the element boxes: elements that provably cannot hold a smaller gap than one
  /// found are skipped (contact_min_gap.cpp). Default.
  pruned,
  /// Every sample of every pair and every element's centreline evaluated (the first design).
  exhaustive,
};

/// States of every contact pair (model.contact_pair_count() entries, numbered as in Model).
void contact_states(const Model& model, const SystemState& state, Workspace& ws,
                    std::span<ContactPairState> out, ContactSearch search = ContactSearch::pruned);

/// Records the first time each pair and each cable is in contact, from the states at the times
/// it is updated with (so the resolution is the caller's step or output interval).
class ContactMonitor {
 public:
  explicit ContactMonitor(const Model& model);
  /// Evaluate the pair states at `state` and record first-contact times.
  std::span<const ContactPairState> update(const Model& model, const SystemState& state,
                                           Workspace& ws);
  [[nodiscard]] std::span<const ContactPairState> states() const { return states_; }
  /// First time the pair / any pair involving the cable was active; NaN if never.
  [[nodiscard]] double first_contact_of_pair(Index pair) const { return pair_first_[pair]; }
  [[nodiscard]] double first_contact_of_cable(Index cable) const { return cable_first_[cable]; }

 private:
  std::vector<ContactPairState> states_;
  std::vector<double> pair_first_, cable_first_;
  std::vector<Index> pair_cables_a_, pair_cables_b_;  // −1 for shape pairs
};

}  // namespace ancf
