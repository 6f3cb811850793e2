// Initial velocities of a scene's cables and bodies (docs/scenes.md "Initial velocities"): a
// rigid motion v(x) = v_c + ω × (x − c) and, for cables, per-node velocities and slope rates.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "ancf/system/cable_geometry.hpp"
#include "toml_reader.hpp"

namespace ancf::io {

/// `velocity` v_c [m/s] of the point `rotation_centre` c [m] and `angular_velocity` ω [rad/s]
/// (global frame) of a [[cable]] or [[body]] table.
struct RigidVelocity {
  Vec3 velocity = Vec3::Zero(), omega = Vec3::Zero(), centre = Vec3::Zero();
  [[nodiscard]] Vec3 at(const Vec3& x) const { return velocity + omega.cross(x - centre); }
};

/// Reads the three keys. `default_centre`: the centre when `rotation_centre` is absent; without
/// one, `rotation_centre` is required as soon as `angular_velocity` is given.
[[nodiscard]] RigidVelocity read_rigid_velocity(TableReader& t,
                                                const std::optional<Vec3>& default_centre);

/// Nodal velocities of a cable table: the rigid field at every node (position rate v(r), slope
/// rate ω × r_x), then the [[cable.node_velocity]] entries { node, velocity, slope_rate }, each
/// replacing what it gives at its node. nullopt when the table gives no velocity at all.
[[nodiscard]] std::optional<std::vector<NodeCoordinates>> read_cable_velocities(
    TableReader& t, const CableGeometry& initial);

}  // namespace ancf::io
