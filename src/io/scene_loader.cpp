// load_scene: parse the TOML text, read every section into a ModelBuilder, finalize, and turn any
// problem into a located SceneError before anything can run.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene_parts.hpp"

namespace ancf {

namespace {

/// The name after the first occurrence of `kind '` in a builder message: the constraint a
/// redundancy report names first ("constraint 'NAME' row …"), the rod an element error names
/// ("rod 'NAME' element j: …"); empty if there is none.
std::string first_named(const std::string& message, const std::string& kind) {
  const std::string tag = kind + " '";
  const auto a = message.find(tag);
  if (a == std::string::npos) return {};
  const auto b = message.find('\'', a + tag.size());
  return b == std::string::npos ? std::string()
                                : message.substr(a + tag.size(), b - a - tag.size());
}

}  // namespace

namespace io {

Scene build_scene(const toml::table& root_table, const std::string& path,
                  const SceneLimits& limits) {
  io::SceneBuild b(path, limits);
  io::TableReader root(path, root_table, "");
  Scene scene;
  scene.path = path;
  scene.name = std::filesystem::path(path).stem().string();
  if (auto meta = root.optional_table("scene")) {
    scene.name = meta->string_or("name", scene.name);
    (void)meta->optional_string("description");
    if (auto g = meta->optional_vec3("gravity")) b.builder.set_gravity(*g);
    meta->finish();
  }
  io::read_cables(root, b);
  io::read_rods(root, b);
  io::read_bodies(root, b);
  io::read_frames(root, b);
  io::read_shapes(root, b);
  io::read_joints(root, b);
  io::read_drives(root, b);
  io::read_loads(root, b);
  io::read_contacts(root, b);
  scene.integrator = io::read_integrator(root);
  scene.output = io::read_output(root, b);
  root.finish();
  if (b.cable_names.empty() && b.names.bodies.empty())
    throw SceneError(path, 0, 0, "",
                     "nothing to simulate: the scene has no [[cable]] and no [[body]]");
  try {
    scene.model = b.builder.finalize();
  } catch (const ModelError& e) {
    // Point at the declaration of the first constraint the builder names (redundancy report),
    // else at the rod or cable it names (a reference the element cannot be built on).
    if (const auto it = b.origins.find(first_named(e.what(), "constraint")); it != b.origins.end())
      throw SceneError(path, it->second.line, 0, it->second.path, e.what());
    for (const char* kind : {"rod", "cable"})
      if (const auto it = b.cable_origins.find(first_named(e.what(), kind));
          it != b.cable_origins.end())
        throw SceneError(path, it->second.line, 0, it->second.path, e.what());
    throw SceneError(path, 0, 0, "", e.what());
  }
  // Reaction probes: the constraints of their joint (NAME, and NAME.slope, NAME.twist where they
  // exist).
  for (Probe& p : scene.output.probes)
    if (p.kind == Probe::Kind::reaction)
      for (Index c = 0; c < static_cast<Index>(scene.model.constraints().size()); ++c) {
        const std::string& name = scene.model.constraints()[c].name;
        if (name == p.joint || name == p.joint + ".slope" || name == p.joint + ".twist")
          p.constraints.push_back(c);
      }
  scene.names = std::move(b.names);
  return scene;
}

toml::table parse_scene_text(const std::string& text, const std::string& path) {
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw SceneError(path, static_cast<int>(e.source().begin.line),
                     static_cast<int>(e.source().begin.column), "",
                     "TOML syntax error: " + std::string(e.description()));
  }
}

std::string read_scene_file(const std::string& path) {
  // A directory opens as an empty stream on Linux and would read as an empty scene.
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (!std::filesystem::exists(status))
    throw SceneError(path, 0, 0, "", "cannot open the scene file (no such file)");
  if (!std::filesystem::is_regular_file(status))
    throw SceneError(path, 0, 0, "",
                     std::filesystem::is_directory(status)
                         ? "is a directory, not a scene file"
                         : "is not a regular file (expected a TOML scene file)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, 0, 0, "", "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace io

Scene load_scene_from_string(const std::string& text, const std::string& path,
                             const SceneLimits& limits) {
  return io::build_scene(io::parse_scene_text(text, path), path, limits);
}

Scene load_scene(const std::string& path, const SceneLimits& limits) {
  return load_scene_from_string(io::read_scene_file(path), path, limits);
}

}  // namespace ancf
