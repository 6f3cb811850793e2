#include "ancf/system/rod_history.hpp"

#include <cmath>

namespace ancf {

RodHistory RodHistory::initial(const Model& model) {
  RodHistory h;
  for (const CableData& c : model.cables()) {
    h.frames.emplace_back(c.rod ? c.rod->reference_frames : std::vector<Mat3>{});
    h.omega.emplace_back(c.rod ? c.rod->reference_omega : std::vector<double>{});
  }
  return h;
}

Vec15 rod_element_coordinates(const CableData& cable, Index j, std::span<const double> q) {
  Vec15 e;
  const int n = cable.rod->element_coordinates();
  for (int i = 0; i < n; ++i) e[i] = q[cable.rod_coordinate(j, i)];
  if (n < 15) e[14] = 0.0;  // linear twist: β ≡ 0
  return e;
}

void commit_rod_history(const Model& model, std::span<const double> q, RodHistory& history,
                        double min_turn) {
  const double min_cos = std::cos(min_turn);
  bool any = false;
  for (Index ci = 0; ci < static_cast<Index>(model.cables().size()); ++ci) {
    const CableData& c = model.cables()[ci];
    if (!c.rod) continue;
    // ω first, under the old triads (at q the result is the same either way,
    // kirchhoff_rod_element).
    for (Index j = 0; j + 1 < c.node_count; ++j)
      history.omega[ci][j] =
          rod_element_omega(history.element(ci, j), rod_element_coordinates(c, j, q));
    for (Index k = 0; k < c.node_count; ++k) {
      const Index t = c.first_coordinate + 6 * k + 3;
      const Vec3 tk(q[t], q[t + 1], q[t + 2]);
      if (min_turn > 0.0 && history.frames[ci][k].col(0).dot(tk) >= min_cos * tk.norm()) continue;
      history.frames[ci][k] = smallest_rotation(history.frames[ci][k], tk);
      any = true;
    }
  }
  if (any) ++history.frame_updates;
}

Mat3 rod_node_triad(const Model& model, Index cable, Index node, std::span<const double> q,
                    const RodHistory& history) {
  const CableData& c = model.cables().at(static_cast<std::size_t>(cable));
  if (node < 0) node += c.node_count;
  const Index t = c.first_coordinate + 6 * node + 3;
  return rod_material_triad(history.frames[cable][node], Vec3(q[t], q[t + 1], q[t + 2]),
                            q[c.rod->twist_first + node]);
}

}  // namespace ancf
