// Name resolution and the small value types shared by several scene sections.
#include <Eigen/Geometry>

#include "scene_parts.hpp"

namespace ancf::io {

namespace {

template <class Map>
std::string known(const Map& m) {
  std::string s;
  for (const auto& [name, index] : m) s += (s.empty() ? "" : ", ") + ("'" + name + "'");
  return s.empty() ? "none defined" : "defined: " + s;
}

}  // namespace

void SceneBuild::declare(TableReader& t, std::string_view key, const std::string& name) {
  if (auto it = origins.find(name); it != origins.end())
    t.fail(key, "the name '" + name + "' is already used by " + it->second.path + " (line " +
                    std::to_string(it->second.line) + ")");
  origins[name] = {t.path(), t.line()};
}

Index SceneBuild::cable(TableReader& t, std::string_view key) {
  const std::string name = t.string(key);
  auto it = names.cables.find(name);
  if (it == names.cables.end())
    t.fail(key, "no cable named '" + name + "' (" + known(names.cables) + ")");
  return it->second;
}

ElementRange SceneBuild::element_range(TableReader& t, std::string_view key, Index cable) {
  ElementRange r;
  const auto pair = t.optional_pair(key);
  if (!pair) return r;
  const long n = static_cast<long>(cable_initial[cable].element_count());
  if (pair->first < 0 || pair->second < 1 || pair->first + pair->second > n)
    t.fail(key, "expected [first, count] with 0 <= first, count >= 1, first + count <= " +
                    std::to_string(n) + " (elements of cable '" + cable_names[cable] + "')");
  r.first = pair->first;
  r.count = pair->second;
  return r;
}

Index SceneBuild::body(TableReader& t, std::string_view key) {
  const std::string name = t.string(key);
  auto it = names.bodies.find(name);
  if (it == names.bodies.end())
    t.fail(key, "no body named '" + name + "' (" + known(names.bodies) + ")");
  return it->second;
}

int SceneBuild::frame(TableReader& t, std::string_view key) {
  const std::string name = t.string(key);
  auto it = names.frames.find(name);
  if (it == names.frames.end())
    t.fail(key, "no frame named '" + name + "' (" + known(names.frames) + ")");
  return static_cast<int>(it->second);
}

Index SceneBuild::body_or_ground(TableReader& t, std::string_view key) {
  if (!t.has(key) || t.string(key) == "ground") return -1;
  return body(t, key);
}

NodeRef SceneBuild::node(TableReader& t, std::string_view key) {
  TableReader r = t.table(key);
  NodeRef n;
  n.cable = cable(r, "cable");
  const toml::node* k = r.get("node");
  if (!k) r.fail_here("missing required key 'node' (node index, < 0 counts from the end)");
  if (!k->is_integer()) r.fail("node", "expected an integer node index, got " + type_name(*k));
  const long i = static_cast<long>(*k->value<int64_t>());
  const long count = static_cast<long>(cable_initial[n.cable].node_count());
  if (i >= count || i < -count)
    r.fail("node", "cable '" + cable_names[n.cable] + "' has nodes 0 … " +
                       std::to_string(count - 1) + " (or −1 … −" + std::to_string(count) +
                       " from the end), got " + std::to_string(i));
  n.node = i < 0 ? count + i : i;
  r.finish();
  return n;
}

AttachmentPoint SceneBuild::attachment(TableReader& t, std::string_view key) {
  TableReader r = t.table(key);
  const int kinds = r.has("cable") + r.has("body") + r.has("frame") + r.has("ground");
  if (kinds != 1)
    r.fail_here(
        "expected exactly one of { cable, node }, { body, point }, { frame, point }, { ground = "
        "[x, y, z] }");
  if (r.has("cable")) return node(t, key);
  if (r.has("ground")) {
    const Vec3 p = r.vec3("ground");
    r.finish();
    return GroundPoint{p};
  }
  if (r.has("body")) {
    BodyPoint p{body(r, "body"), r.vec3_or("point", Vec3::Zero())};
    r.finish();
    return p;
  }
  FramePoint p{frame(r, "frame"), r.vec3_or("point", Vec3::Zero())};
  r.finish();
  return p;
}

Mat3 read_rotation(TableReader& t, std::string_view key) {
  const toml::node* n = t.get(key);
  if (!n) return Mat3::Identity();
  if (n->is_table()) {
    TableReader r = t.table(key);
    const Vec3 axis = r.direction("axis");
    const double angle = r.number("angle");
    r.finish();
    return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  }
  const toml::array* a = n->as_array();
  if (!a || a->size() != 3)
    t.fail(key,
           "expected { axis = [x, y, z], angle = rad } or a 3×3 matrix [[..], [..], [..]] (rows)");
  Mat3 m;
  for (int i = 0; i < 3; ++i) {
    const toml::array* row = a->get(static_cast<std::size_t>(i))->as_array();
    if (!row || row->size() != 3) t.fail(key, "expected a 3×3 matrix: 3 rows of 3 numbers");
    for (int j = 0; j < 3; ++j) {
      const toml::node* x = row->get(static_cast<std::size_t>(j));
      if (!x->is_number()) t.fail(key, "expected a 3×3 matrix of numbers, got " + type_name(*x));
      m(i, j) = *x->value<double>();
    }
  }
  if ((m.transpose() * m - Mat3::Identity()).norm() > 1e-9 || m.determinant() < 0.0)
    t.fail(key, "expected a proper rotation matrix (orthonormal rows, determinant +1)");
  return m;
}

AngleLaw read_angle_law(TableReader& t, std::string_view key) {
  if (!t.has(key)) return AngleLaw::fixed();
  TableReader r = t.table(key);
  const std::string kind = r.choice("kind", {"fixed", "constant_rate", "smooth_ramp"});
  const double angle0 = r.number_or("angle0", 0.0);
  AngleLaw law = AngleLaw::fixed(angle0);
  if (kind == "constant_rate") law = AngleLaw::constant_rate(r.number("rate"), angle0);
  if (kind == "smooth_ramp")
    law =
        AngleLaw::smooth_ramp(r.number("max_rate"), r.number("ramp_time", Range::positive), angle0);
  r.finish();
  return law;
}

}  // namespace ancf::io
