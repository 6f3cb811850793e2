#include "ancf/io/vtk_writer.hpp"

#include <fmt/format.h>

#include <fstream>

#include "ancf/core/error.hpp"
#include "ancf/physics/hermite_shape.hpp"
#include "ancf/system/contact_output.hpp"

namespace ancf {

namespace {

struct PolyData {
  std::vector<Vec3> points, velocities, contact_forces;
  std::vector<std::vector<Index>> verts, lines;
  std::vector<int> vert_object, line_object;
};

void append_cells(std::ofstream& out, const char* tag,
                  const std::vector<std::vector<Index>>& cells) {
  out << "<" << tag << ">\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  for (const auto& c : cells)
    for (Index i : c) out << i << ' ';
  out << "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  Index offset = 0;
  for (const auto& c : cells) out << (offset += static_cast<Index>(c.size())) << ' ';
  out << "\n</DataArray>\n</" << tag << ">\n";
}

void append_vectors(std::ofstream& out, const char* name, const std::vector<Vec3>& v) {
  out << "<DataArray type=\"Float64\" Name=\"" << name
      << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec3& p : v) out << fmt::format("{:.9g} {:.9g} {:.9g}\n", p.x(), p.y(), p.z());
  out << "</DataArray>\n";
}

}  // namespace

void write_vtp(const std::string& path, const Model& model, const SystemState& state,
               int samples_per_element, double axis_length, Workspace& ws) {
  PolyData d;
  int object = 0;
  for (const CableData& c : model.cables()) {
    std::vector<Index> line;
    for (std::size_t j = 0; j < c.elements.size(); ++j) {
      const Index first = c.first_coordinate + 6 * static_cast<Index>(j);
      const double l = c.elements[j].length;
      for (int k = (j == 0 ? 0 : 1); k <= samples_per_element; ++k) {
        // r(ξ) = S(ξ) e with the 4 scalar Hermite weights applied to r_i, r_i,x, r_j, r_j,x.
        const Vec4 s = hermite::values(static_cast<double>(k) / samples_per_element, l);
        Vec3 r = Vec3::Zero(), v = Vec3::Zero();
        for (int b = 0; b < 4; ++b) {
          r += s[b] * state.q.segment<3>(first + 3 * b);
          v += s[b] * state.v.segment<3>(first + 3 * b);
        }
        line.push_back(static_cast<Index>(d.points.size()));
        d.points.push_back(r);
        d.velocities.push_back(v);
      }
    }
    d.lines.push_back(std::move(line));
    d.line_object.push_back(object++);
  }
  for (const BodyData& b : model.bodies()) {
    const Index o = static_cast<Index>(d.points.size());
    const Vec3 r = state.q.segment<3>(b.first_coordinate),
               v = state.v.segment<3>(b.first_coordinate);
    d.points.push_back(r);
    d.velocities.push_back(v);
    d.verts.push_back({o});
    d.vert_object.push_back(object);
    for (int k = 1; k <= 3; ++k) {
      d.points.push_back(r + axis_length * state.q.segment<3>(b.first_coordinate + 3 * k));
      d.velocities.push_back(v + axis_length * state.v.segment<3>(b.first_coordinate + 3 * k));
      d.lines.push_back({o, static_cast<Index>(d.points.size() - 1)});
      d.line_object.push_back(object);
    }
    ++object;
  }
  d.contact_forces.assign(d.points.size(), Vec3::Zero());
  // Contact: one vertex per pair in contact, where its resultant acts, carrying the resultant
  // (normal + friction, on the pair's first cable) as point data "contact_force" [N].
  if (model.contact_pair_count() > 0) {
    std::vector<ContactPairState> pairs(static_cast<std::size_t>(model.contact_pair_count()));
    contact_states(model, state, ws, pairs);
    for (const ContactPairState& p : pairs) {
      ++object;
      if (!p.active) continue;
      d.verts.push_back({static_cast<Index>(d.points.size())});
      d.vert_object.push_back(object - 1);
      d.points.push_back(p.centre);
      d.velocities.push_back(Vec3::Zero());
      d.contact_forces.push_back(p.normal_force + p.friction_force);
    }
  }
  std::ofstream out(path);
  if (!out) throw ModelError("cannot create " + path);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" "
         "byte_order=\"LittleEndian\">\n"
      << "<PolyData>\n"
      << fmt::format(
             "<Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" "
             "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
             d.points.size(), d.verts.size(), d.lines.size())
      << "<Points>\n";
  append_vectors(out, "Points", d.points);
  out << "</Points>\n<PointData Vectors=\"velocity\">\n";
  append_vectors(out, "velocity", d.velocities);
  append_vectors(out, "contact_force", d.contact_forces);
  out << "</PointData>\n";
  append_cells(out, "Verts", d.verts);
  append_cells(out, "Lines", d.lines);
  // Cell data follow VTK's cell order: verts, then lines.
  out << "<CellData Scalars=\"object\">\n<DataArray type=\"Int32\" Name=\"object\" "
         "format=\"ascii\">\n";
  for (int o : d.vert_object) out << o << ' ';
  for (int o : d.line_object) out << o << ' ';
  out << "\n</DataArray>\n</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  if (!out) throw ModelError("error writing " + path);
}

void PvdSeries::add(double t, const std::string& relative_file) {
  frames_.emplace_back(t, relative_file);
  std::ofstream out(path_);
  if (!out) throw ModelError("cannot create " + path_);
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (const auto& [time, file] : frames_)
    out << fmt::format("<DataSet timestep=\"{:.10g}\" part=\"0\" file=\"{}\"/>\n", time, file);
  out << "</Collection>\n</VTKFile>\n";
}

}  // namespace ancf
