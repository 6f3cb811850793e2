#include "ancf/system/contact_output.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "contact_min_gap.hpp"
#include "contact_sampling.hpp"

namespace ancf {
namespace {

class StateSink final : public detail::ContactSink {
 public:
  explicit StateSink(std::span<ContactPairState> out) : out_(out), weights_(out.size(), 0.0) {}
  /// Σ |w f_n| of the active samples of pair k (normalises ContactPairState::centre).
  [[nodiscard]] double weight(std::size_t k) const { return weights_[k]; }
  void add(const ContactSampleResult& s, const detail::ContactSampleBlocks& b) override {
    ContactPairState& p = out_[b.pair];
    p.min_gap = std::min(p.min_gap, s.gap);
    if (!s.active) return;
    p.active = true;
    ++p.active_samples;
    p.normal_force += s.normal_force;
    p.friction_force += s.friction_force;
    p.peak_sample_force = std::max(p.peak_sample_force, s.normal_force.norm());
    p.centre += s.normal_force.norm() * s.point;  // normalised in contact_states()
    weights_[static_cast<std::size_t>(b.pair)] += s.normal_force.norm();
  }

 private:
  std::span<ContactPairState> out_;
  std::vector<double> weights_;
};

}  // namespace

void contact_states(const Model& model, const SystemState& state, Workspace& ws,
                    std::span<ContactPairState> out, ContactSearch search) {
  std::fill(out.begin(), out.end(), ContactPairState{});
  StateSink sink(out);
  // Exhaustive: every sample reaches the sink (its gaps give min_gap). Pruned: the broad phase
  // lets through every active sample, in the same order (the resultants are the same sums), and
  // refreshes the element boxes that the branch and bound of the minimum gaps needs.
  const bool exhaustive = search == ContactSearch::exhaustive;
  detail::visit_contact_samples(model, state, ws, {.jacobians = false, .all_samples = exhaustive},
                                sink);
  if (!exhaustive && model.contact_pair_count() > 0)
    for (Index p = 0; p < model.contact_pair_count(); ++p)
      out[static_cast<std::size_t>(p)].min_gap =
          detail::sample_min_gap(model, state, ws, p, search);
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k].centre = sink.weight(k) > 0.0 ? Vec3(out[k].centre / sink.weight(k)) : Vec3::Zero();
  for (Index p = 0; p < static_cast<Index>(model.cable_shape_contacts().size()); ++p)
    out[static_cast<std::size_t>(p)].min_centreline_gap =
        detail::centreline_min_gap(model, state, ws, p, search);
}

ContactMonitor::ContactMonitor(const Model& model)
    : states_(model.contact_pair_count()),
      pair_first_(model.contact_pair_count(), std::nan("")),
      cable_first_(model.cables().size(), std::nan("")) {
  for (const auto& c : model.cable_shape_contacts())
    pair_cables_a_.push_back(c.cable), pair_cables_b_.push_back(-1);
  for (const auto& c : model.cable_cable_contacts())
    pair_cables_a_.push_back(c.cable_a), pair_cables_b_.push_back(c.cable_b);
}

std::span<const ContactPairState> ContactMonitor::update(const Model& model,
                                                         const SystemState& state, Workspace& ws) {
  contact_states(model, state, ws, states_);
  for (std::size_t p = 0; p < states_.size(); ++p) {
    if (!states_[p].active) continue;
    auto record = [&](double& first) {
      if (std::isnan(first)) first = state.t;
    };
    record(pair_first_[p]);
    record(cable_first_[pair_cables_a_[p]]);
    if (pair_cables_b_[p] >= 0) record(cable_first_[pair_cables_b_[p]]);
  }
  return states_;
}

}  // namespace ancf
