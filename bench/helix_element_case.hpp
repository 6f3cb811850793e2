// The element both rod-cost tools measure (bench_rod_element.cpp for times, rod_element_calls.cpp
// for callgrind instruction counts): element 1 of a 4-element helix (radius 0.1 m, pitch 0.3 m),
// perturbed off its reference, with a cable section and a rod section of the same EA and EI.
#pragma once

#include "ancf/physics/cable_element.hpp"
#include "ancf/physics/kirchhoff_rod_element.hpp"
#include "ancf/system/cable_geometry.hpp"

namespace ancf::bench {

struct HelixElementCase {
  CableGeometry g = helix_cable(Vec3::Zero(), Vec3::UnitZ(), Vec3::UnitX(), 0.1, 0.3, 2.0, 0.15, 4);
  Vec12 e0 = g.element_coordinates(1);                ///< reference coordinates [m, –]
  Vec12 e = e0 + 0.01 * Vec12::LinSpaced(-1.0, 1.0);  ///< evaluated coordinates
  double twist1 = 0.05, twist2 = -0.03;               ///< nodal twist angles of the rod [rad]
  double interior_twist = 0.02;  ///< interior twist β of the rod element [rad]

  [[nodiscard]] static CableSection cable_section() {
    CableSection section;
    section.strain = StrainMeasure::elastic_line;
    section.axial_stiffness = 3e5;
    section.bending_stiffness = 0.5;
    section.mass_per_length = 0.02;
    return section;
  }
  [[nodiscard]] CableElementReference cable_reference() const {
    return CableElementReference::from_reference(e0, g.element_lengths[1], cable_section().strain,
                                                 {.axial = 4, .bending = 4});
  }

  [[nodiscard]] static RodSection rod_section() {
    RodSection section;
    section.axial_stiffness = 3e5;
    section.torsional_stiffness = 0.4;
    section.bending_stiffness_2 = section.bending_stiffness_3 = 0.5;
    section.mass_per_length = 0.02;
    section.polar_inertia = 1e-7;
    return section;
  }
  /// Committed nodal triads of the element (material frames toward the helix axis).
  [[nodiscard]] RodElementHistory rod_history() const {
    const auto frames = rod_frames_toward_axis(g, Vec3::Zero(), Vec3::UnitZ());
    return RodElementHistory{frames[1], frames[2], 0.0};
  }
  /// The reference of the element; sets the committed values of `h`
  /// (RodElementReference::from_reference).
  [[nodiscard]] RodElementReference rod_reference(RodElementHistory& h) const {
    return RodElementReference::from_reference(e0, g.element_lengths[1], h);
  }
  /// The rod element coordinates (r, t, twist angles and an interior twist).
  [[nodiscard]] Vec15 rod_coordinates() const {
    Vec15 r;
    r << e, twist1, twist2, interior_twist;
    return r;
  }
};

}  // namespace ancf::bench
