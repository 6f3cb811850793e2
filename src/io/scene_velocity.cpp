// Initial velocities of cables and bodies (scene_velocity.hpp).
#include "scene_velocity.hpp"

#include <set>
#include <string>

namespace ancf::io {

RigidVelocity read_rigid_velocity(TableReader& t, const std::optional<Vec3>& default_centre) {
  RigidVelocity v;
  v.velocity = t.vec3_or("velocity", Vec3::Zero());
  v.omega = t.vec3_or("angular_velocity", Vec3::Zero());
  const auto centre = t.optional_vec3("rotation_centre");
  if (t.has("angular_velocity") && !centre && !default_centre)
    t.fail("angular_velocity",
           "a rigid rotation needs its centre: give rotation_centre = [x, y, z] [m]");
  if (centre && !t.has("angular_velocity"))
    t.fail("rotation_centre", "rotation_centre without angular_velocity has no effect");
  v.centre = centre ? *centre : default_centre.value_or(Vec3::Zero());
  return v;
}

std::optional<std::vector<NodeCoordinates>> read_cable_velocities(TableReader& t,
                                                                  const CableGeometry& initial) {
  const bool rigid = t.has("velocity") || t.has("angular_velocity") || t.has("rotation_centre");
  const RigidVelocity field = read_rigid_velocity(t, std::nullopt);
  std::vector<TableReader> entries = t.tables("node_velocity");
  if (!rigid && entries.empty()) return std::nullopt;
  std::vector<NodeCoordinates> v(initial.nodes.size());
  for (std::size_t k = 0; k < v.size(); ++k) {
    const NodeCoordinates& x = initial.nodes[k];
    v[k] << field.at(x.head<3>()), field.omega.cross(x.tail<3>());
  }
  const Index n = static_cast<Index>(v.size());
  std::set<Index> seen;
  for (TableReader& e : entries) {
    const long given = e.integer("node", -n);
    if (given >= n)
      e.fail("node", "the cable has nodes 0 … " + std::to_string(n - 1) + " (or -1 … -" +
                         std::to_string(n) + " from the end), got " + std::to_string(given));
    const Index k = given < 0 ? n + given : given;
    if (!seen.insert(k).second)
      e.fail("node", "node " + std::to_string(k) + " has two node_velocity entries");
    if (!e.has("velocity") && !e.has("slope_rate"))
      e.fail_here("expected velocity = [..] [m/s] and/or slope_rate = [..] [1/s]");
    if (auto u = e.optional_vec3("velocity")) v[static_cast<std::size_t>(k)].head<3>() = *u;
    if (auto s = e.optional_vec3("slope_rate")) v[static_cast<std::size_t>(k)].tail<3>() = *s;
    e.finish();
  }
  return v;
}

}  // namespace ancf::io
