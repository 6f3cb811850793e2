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
  static const char* const kNode[6] = {"r.x", "r.y", "r.z", "r_x.x", "r_x.y", "r_x.z"};
  static const char* const kBody[12] = {"r_O.x", "r_O.y", "r_O.z", "a1.x", "a1.y", "a1.z",
                                        "a2.x",  "a2.y",  "a2.z",  "a3.x", "a3.y", "a3.z"};
  if (row >= 0 && row < n_coordinates_) {
    for (const CableData& c : cables_) {
      const Index local = row - c.first_coordinate;
      if (local >= 0 && local < 6 * c.node_count)
        return "cable '" + c.name + "' node " + std::to_string(local / 6) + " " + kNode[local % 6];
      if (c.rod && row >= c.rod->twist_first && row < c.rod->twist_first + c.node_count)
        return "rod '" + c.name + "' node " + std::to_string(row - c.rod->twist_first) + " twist";
      if (c.rod && c.rod->interior_first >= 0 && row >= c.rod->interior_first &&
          row < c.rod->interior_first + c.node_count - 1)
        return "rod '" + c.name + "' element " + std::to_string(row - c.rod->interior_first) +
               " interior twist";
    }
    for (const BodyData& b : bodies_) {
      const Index local = row - b.first_coordinate;
      if (local >= 0 && local < 12) return "body '" + b.name + "' " + kBody[local];
    }
  }
  for (const ConstraintData& c : constraints_) {
    const Index local = row - c.first_row;
    if (local >= 0 && local < c.row_count)
      return "constraint '" + c.name + "' row " + std::to_string(local);
  }
  return "row " + std::to_string(row) + " (outside the system)";
}

const std::string& Model::contact_pair_name(Index pair) const {
  const auto n_shape = static_cast<Index>(cable_shape_contacts_.size());
  if (pair < 0 || pair >= contact_pair_count())
    throw ModelError("no contact pair with index " + std::to_string(pair));
  return pair < n_shape ? cable_shape_contacts_[pair].name
                        : cable_cable_contacts_[pair - n_shape].name;
}

Index Model::find_constraint(const std::string& name) const {
  for (std::size_t k = 0; k < constraints_.size(); ++k)
    if (constraints_[k].name == name) return static_cast<Index>(k);
  return -1;
}

}  // namespace ancf
