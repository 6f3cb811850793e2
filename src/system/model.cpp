#include "ancf/system/model.hpp"

#include <string>

#include "ancf/core/error.hpp"

namespace ancf {

Index Model::node_coordinate(Index cable, Index node) const {
  if (cable < 0 || cable >= static_cast<Index>(cables_.size()))
    throw ModelError("no cable with index " + std::to_string(cable));
  const CableData& c = cables_[cable];
  const Index k = node < 0 ? c.node_count + node : node;
  if (k < 0 || k >= c.node_count)
    throw ModelError("cable '" + c.name + "' has no node " + std::to_string(node));
  return c.first_coordinate + 6 * k;
}

std::string Model::describe_row(Index row) const {
  static const char* const kComponent[6] = {"r.x", "r.y", "r.z", "r_x.x", "r_x.y", "r_x.z"};
  if (row >= 0 && row < n_coordinates_) {
    for (const CableData& c : cables_) {
      const Index local = row - c.first_coordinate;
      if (local >= 0 && local < 6 * c.node_count)
        return "cable '" + c.name + "' node " + std::to_string(local / 6) + " " + kComponent[local % 6];
    }
  }
  for (const NodeConstraintData& d : constraints_) {
    const Index local = row - d.first_row;
    if (local >= 0 && local < d.law.rows)
      return "constraint '" + d.name + "' row " + std::to_string(local);
  }
  return "row " + std::to_string(row) + " (outside the system)";
}

}  // namespace ancf
