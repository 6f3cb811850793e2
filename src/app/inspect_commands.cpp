// `ancf check` and `ancf info`: everything short of running a scene.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

#include "ancf/io/scene.hpp"
#include "ancf/system/contact_pattern.hpp"
#include "commands.hpp"

namespace ancf::app {

int check_command(const std::string& scene_path, double max_steps) {
  try {
    const Scene scene = load_scene(scene_path);
    require_bounded_steps(scene.integrator, scene.output.interval, max_steps);
    fmt::print("OK {}: {} unknowns, {} constraint rows\n", scene_path,
               scene.model.coordinate_count(), scene.model.multiplier_count());
    return 0;
  } catch (const ModelError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
}

int info_command(const std::string& scene_path) {
  try {
    const Scene scene = load_scene(scene_path);
    const Model& m = scene.model;
    fmt::print("scene        {} ({})\n", scene.name, scene.path);
    fmt::print("coordinates  {}\n", m.coordinate_count());
    fmt::print("multipliers  {} (constraint rows)\n", m.multiplier_count());
    fmt::print("system size  {} (IDA/GGL: {})\n", m.system_size(),
               2 * m.coordinate_count() + 2 * m.multiplier_count());
    const ContactPattern every(m, {.policy = ContactPatternPolicy::all});
    const double dense =
        static_cast<double>(m.system_size()) * static_cast<double>(m.system_size());
    fmt::print(
        "nonzeros     {} in the iteration-matrix pattern without contact coupling ({:.2g} %)\n",
        m.pattern().nonzeros(), 100.0 * static_cast<double>(m.pattern().nonzeros()) / dense);
    if (every.pattern().nonzeros() > m.pattern().nonzeros())
      fmt::print(
          "             {} with every candidate contact block ({:.2g} %; contact_pattern = "
          "\"all\"); the default holds only the pairs that are near\n",
          every.pattern().nonzeros(),
          100.0 * static_cast<double>(every.pattern().nonzeros()) / dense);
    fmt::print("cables       {}\n", m.cables().size());
    for (const CableData& c : m.cables()) {
      // A graded mesh (scene key `grading`) shows its shortest and longest element.
      double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
      for (const CableElementReference& e : c.elements) {
        shortest = std::min(shortest, e.length);
        longest = std::max(longest, e.length);
      }
      const std::string graded =
          longest > shortest * (1.0 + 1e-9)
              ? fmt::format("  graded: elements {:.3g} to {:.3g} mm", 1e3 * shortest, 1e3 * longest)
              : std::string();
      if (c.rod) {
        const RodSection& r = c.rod->section;
        fmt::print(
            "  {:<18} {:>4} elements {:>4} nodes  Kirchhoff rod ({} twist, coordinates {}..{}): EA "
            "{:.4g} N  GJ {:.4g} N m^2  EI2 {:.4g}  EI3 {:.4g} N m^2  rhoA {:.4g} kg/m  rhoJ "
            "{:.4g} kg m  Gauss {}  axial strain {}  torsion {}{}\n",
            c.name, c.elements.size(), c.node_count,
            r.twist == RodTwist::quadratic ? "quadratic" : "linear", c.rod->twist_first,
            c.rod->twist_first + c.rod->twist_block_size(c.node_count) - 1, r.axial_stiffness,
            r.torsional_stiffness, r.bending_stiffness_2, r.bending_stiffness_3, r.mass_per_length,
            r.polar_inertia, kRodGaussPoints,
            r.axial_strain == RodAxialStrain::collocated ? "collocated" : "at Gauss points",
            r.torsion_strain == RodTorsionStrain::projected ? "projected" : "at Gauss points",
            graded);
        continue;
      }
      fmt::print(
          "  {:<18} {:>4} elements {:>4} nodes  EA {:.4g} N  EI {:.4g} N m^2  rhoA {:.4g} kg/m  "
          "Gauss {}/{}{}\n",
          c.name, c.elements.size(), c.node_count, c.section.axial_stiffness,
          c.section.bending_stiffness, c.section.mass_per_length, c.section.quadrature.axial,
          c.section.quadrature.bending, graded);
    }
    fmt::print("bodies       {}\n", m.bodies().size());
    for (const BodyData& b : m.bodies())
      fmt::print("  {:<18} mass {:.4g} kg\n", b.name, b.inertia.mass);
    fmt::print("frames       {}\n", m.frames().size());
    fmt::print("constraints  {}\n", m.constraints().size());
    const Index twist_rows_start = m.coordinate_count() + static_cast<Index>(m.rows().size());
    for (const ConstraintData& c : m.constraints())
      fmt::print(
          "  {:<30} {} rows{}\n", c.name, c.row_count,
          c.first_row >= twist_rows_start ? " (rod twist tied to a body/frame: d2.b = 0)" : "");
    fmt::print(
        "forces       {} spring-dampers, {} point forces, {} dead nodal forces, {} torques, {} "
        "drives\n",
        m.spring_dampers().size(), m.point_forces().size(), m.node_forces().size(),
        m.body_torques().size(), m.drives().size());
    if (!m.rod_moments().empty()) fmt::print("rod moments  {}\n", m.rod_moments().size());
    for (const NodeForceData& f : m.node_forces())
      fmt::print("  force on '{}' node {}: [{:.4g}, {:.4g}, {:.4g}] N\n", m.cables()[f.cable].name,
                 f.node, f.force.x(), f.force.y(), f.force.z());
    for (const DistributedForceData& d : m.distributed_forces())
      fmt::print("  distributed force on '{}', elements {}..{}: [{:.4g}, {:.4g}, {:.4g}] N/m\n",
                 m.cables()[d.cable].name, d.first, d.first + d.count - 1, d.force_per_length.x(),
                 d.force_per_length.y(), d.force_per_length.z());
    for (const RodDistributedMomentData& d : m.rod_distributed_moments())
      fmt::print(
          "  distributed moment on rod '{}', elements {}..{}: [{:.4g}, {:.4g}, {:.4g}] N m/m\n",
          m.cables()[d.cable].name, d.first, d.first + d.count - 1, d.moment_per_length.x(),
          d.moment_per_length.y(), d.moment_per_length.z());
    fmt::print("contact      {} pairs, {} shapes\n", m.contact_pair_count(), m.shapes().size());
    for (const CableShapeContactData& p : m.cable_shape_contacts())
      fmt::print("  {:<18} cable '{}' - shape '{}', elements {}..{}, {} samples/element\n", p.name,
                 m.cables()[p.cable].name, m.shapes()[p.shape].name, p.first, p.first + p.count - 1,
                 p.samples);
    for (const CableCableContactData& p : m.cable_cable_contacts())
      fmt::print("  {:<18} cable '{}' - cable '{}', {} x {} elements, {} samples/element\n", p.name,
                 m.cables()[p.cable_a].name, m.cables()[p.cable_b].name, p.count_a, p.count_b,
                 p.samples);
    const IntegratorSettings& s = scene.integrator;
    if (s.kind == IntegratorKind::ida)
      fmt::print("integrator   ida, rtol {:g}, t_end {:g} s\n", s.rtol, s.t_end);
    else
      fmt::print("integrator   genalpha ({}), h {:g} s, rho_inf {:g}, t_end {:g} s\n",
                 s.stabilized_index2 ? "stabilized index 2" : "index 3", s.step, s.rho_infinity,
                 s.t_end);
    fmt::print("output       every {:g} s, {} probes, vtk {}\n", scene.output.interval,
               scene.output.probes.size(), scene.output.vtk ? "on" : "off");
    return 0;
  } catch (const ModelError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 1;
  }
}

}  // namespace ancf::app
