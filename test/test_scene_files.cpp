// Scene files: every malformed scene under test/scenes/malformed fails with its expected message
// (file, line, fragment given in its "# expect:" and "# line:" comments); valid scenes build the
// model they describe; every scene under studies/scenes loads.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "ancf/io/scene.hpp"
#include "ancf/scenes/pendulums.hpp"
#include "ancf/system/assembly.hpp"

namespace fs = std::filesystem;
using namespace ancf;

namespace {

const fs::path kSource = ANCF_SOURCE_DIR;

std::vector<fs::path> scenes_in(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".toml") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

/// Value of the first comment line "# KEY: value" of a file.
std::string directive(const fs::path& file, const std::string& key) {
  std::ifstream in(file);
  const std::string tag = "# " + key + ": ";
  for (std::string line; std::getline(in, line);)
    if (line.rfind(tag, 0) == 0) return line.substr(tag.size());
  return {};
}

}  // namespace

TEST(SceneFiles, MalformedCorpusHasAtLeastTwentyFiles) {
  EXPECT_GE(scenes_in(kSource / "test/scenes/malformed").size(), 20u);
}

// The fuzz target's malformed corpus (test/fuzz/malformed: hand-made edge cases and every
// regression case of a fuzzer finding, docs/fuzzing.md) through the normal loader: each must be
// refused with a SceneError, never load, crash or throw anything else.
TEST(SceneFiles, FuzzMalformedCorpusGivesSceneErrors) {
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(kSource / "test/fuzz/malformed")) {
    SCOPED_TRACE(e.path().filename().string());
    ++files;
    try {
      (void)load_scene(e.path().string());
      ADD_FAILURE() << "loaded without error";
    } catch (const SceneError& error) {
      EXPECT_NE(std::string(error.what()).find(e.path().string()), std::string::npos)
          << error.what();
    }
  }
  EXPECT_GE(files, 10u);
}

// The fuzz target's seed corpus (test/fuzz/corpus) starts from valid scenes so that mutations reach
// the model builder; those seeds are copies, and a format change must not leave them refused. Each
// seed not named malformed_* loads and builds a model with unknowns.
TEST(SceneFiles, FuzzSeedCorpusLoads) {
  std::size_t seeds = 0, rods = 0;
  for (const fs::path& file : scenes_in(kSource / "test/fuzz/corpus")) {
    if (file.filename().string().rfind("malformed_", 0) == 0) continue;
    SCOPED_TRACE(file.filename().string());
    ++seeds;
    try {
      const Scene scene = load_scene(file.string());
      EXPECT_GT(scene.model.coordinate_count(), 0);
      if (std::ifstream in(file);
          std::string(std::istreambuf_iterator<char>(in), {}).find("[[rod]]") != std::string::npos)
        ++rods;
    } catch (const SceneError& e) {
      ADD_FAILURE() << e.what();
    }
  }
  EXPECT_GE(seeds, 10u);
  EXPECT_GE(rods, 5u);  // the rod loader (issue 16) is seeded too
}

TEST(SceneFiles, EachMalformedSceneGivesItsLocatedMessage) {
  for (const fs::path& file : scenes_in(kSource / "test/scenes/malformed")) {
    SCOPED_TRACE(file.filename().string());
    const std::string expect = directive(file, "expect"), line = directive(file, "line");
    ASSERT_FALSE(expect.empty()) << "no '# expect:' comment";
    ASSERT_FALSE(line.empty()) << "no '# line:' comment";
    try {
      (void)load_scene(file.string());
      ADD_FAILURE() << "loaded without error";
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file.string() + ":" + line + ":"), std::string::npos) << what;
      EXPECT_EQ(std::to_string(e.line()), line) << what;
      EXPECT_NE(what.find(expect), std::string::npos) << what;
    }
  }
}

TEST(SceneFiles, MissingFileIsASceneError) {
  EXPECT_THROW((void)load_scene("/nonexistent/scene.toml"), SceneError);
}

// Issue 17 item 8: a directory read as an empty stream and an empty scene answered OK.
TEST(SceneFiles, DirectoryIsNotASceneFile) {
  try {
    (void)load_scene(fs::temp_directory_path().string());
    ADD_FAILURE() << "a directory loaded";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("is a directory, not a scene file"), std::string::npos)
        << e.what();
  }
}

TEST(SceneFiles, SceneWithNothingToSimulateIsRefused) {
  for (const std::string text :
       {"", "# only a comment\n", "[scene]\nname = \"x\"\n", "[[frame]]\nname = \"f\"\n"}) {
    try {
      (void)load_scene_from_string(text, "empty.toml");
      ADD_FAILURE() << "loaded: '" << text << "'";
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("nothing to simulate"), std::string::npos) << e.what();
    }
  }
}

// The memory estimate is checked against the given budget before the cable is built: 1 000
// elements need 24 MB, refused under a 10 MB budget, accepted under 100 MB.
TEST(SceneFiles, ElementCountBeyondTheMemoryBudgetIsRefused) {
  const std::string text =
      "[[cable]]\nname = \"c\"\nelements = 1000\n"
      "geometry = { kind = \"straight\", start = [0, 0, 0], end = [1, 0, 0] }\n"
      "section = { EA = 1e5, mass_per_length = 0.1, bending = false }\n";
  EXPECT_NO_THROW((void)load_scene_from_string(text, "c.toml", {.memory_bytes = 100e6}));
  try {
    (void)load_scene_from_string(text, "c.toml", {.memory_bytes = 10e6});
    ADD_FAILURE() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.key(), "cable[0].elements");
    EXPECT_NE(e.message().find("more than the 0.01 GB allowed"), std::string::npos) << e.what();
  }
}

TEST(SceneFiles, GaussRulesPerTermReachTheElements) {
  const Scene s = load_scene_from_string(
      "[[cable]]\nname = \"c\"\nelements = 2\n"
      "geometry = { kind = \"straight\", start = [0, 0, 0], end = [1, 0, 0] }\n"
      "section = { EA = 1e5, EI = 1.0, mass_per_length = 0.1, axial_gauss_points = 4, "
      "bending_gauss_points = 2 }\n",
      "rules.toml");
  const CableData& c = s.model.cables()[0];
  EXPECT_EQ(c.section.quadrature, (CableQuadrature{4, 2}));
  EXPECT_EQ(c.elements[1].axial.count, 4);
  EXPECT_EQ(c.elements[1].bending.count, 2);
  EXPECT_FALSE(c.elements[1].shared_points);
}

// Issue 17 item 2: a rigid rotation about a point for cables and bodies, per-node velocities.
TEST(SceneFiles, InitialVelocitiesRigidRotationAndPerNode) {
  const Scene s = load_scene_from_string(R"(
[[cable]]
name = "c"
elements = 4
velocity = [0.1, 0.0, 0.0]
angular_velocity = [0.0, 4.0, 1.0]
rotation_centre = [0.5, 0.0, 0.0]
geometry = { kind = "arc", u = [1, 0, 0], w = [0, 1, 0], radius = 1.0, angle = 1.0 }
section = { EA = 1e5, EI = 1.0, mass_per_length = 0.1 }
[[cable.node_velocity]]
node = -1
slope_rate = [1.0, 2.0, 3.0]
[[cable.node_velocity]]
node = 1
velocity = [7.0, 8.0, 9.0]
[[body]]
name = "b"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
position = [1.0, 2.0, 3.0]
velocity = [0.0, 0.0, 1.0]
angular_velocity = [0.0, 0.0, 2.0]
rotation_centre = [0.0, 2.0, 3.0]
[[body]]
name = "plain"
mass = 1.0
inertia = [1.0, 1.0, 1.0]
position = [1.0, 2.0, 3.0]
velocity = [0.0, 0.0, 1.0]
angular_velocity = [0.0, 0.0, 2.0]
)",
                                         "velocities.toml");
  const Model& m = s.model;
  const VecX& q = m.initial_coordinates();
  const VecX& v = m.initial_velocities();
  const Vec3 omega(0.0, 4.0, 1.0), centre(0.5, 0.0, 0.0), v0(0.1, 0.0, 0.0);
  for (Index k = 0; k < 5; ++k) {
    const Index i = m.node_coordinate(0, k);
    const Vec3 r = q.segment<3>(i), rx = q.segment<3>(i + 3);
    const Vec3 rdot = k == 1 ? Vec3(7.0, 8.0, 9.0) : Vec3(v0 + omega.cross(r - centre));
    const Vec3 rxdot = k == 4 ? Vec3(1.0, 2.0, 3.0) : Vec3(omega.cross(rx));
    EXPECT_LT((v.segment<3>(i) - rdot).norm(), 1e-15) << "node " << k;
    EXPECT_LT((v.segment<3>(i + 3) - rxdot).norm(), 1e-15) << "node " << k;
  }
  // Body: velocity is that of rotation_centre; without it, that of the origin (as before).
  const Index b = m.bodies()[0].first_coordinate, plain = m.bodies()[1].first_coordinate;
  EXPECT_LT(
      (v.segment<3>(b) - Vec3(0.0, 0.0, 1.0) - Vec3(0.0, 0.0, 2.0).cross(Vec3(1, 0, 0))).norm(),
      1e-15);
  EXPECT_LT((v.segment<3>(plain) - Vec3(0.0, 0.0, 1.0)).norm(), 1e-15);
  EXPECT_LT((v.segment<3>(b + 3) - v.segment<3>(plain + 3)).norm(), 1e-15);  // same ω
}

TEST(SceneFiles, PendulumSceneMatchesTheReferenceScene) {
  const Scene s = load_scene((kSource / "studies/scenes/cable_pendulum.toml").string());
  const Model reference = cable_pendulum_model(benchmark_cable_pendulum(20));
  const Model& m = s.model;
  ASSERT_EQ(m.cables().size(), 1u);
  EXPECT_EQ(m.coordinate_count(), reference.coordinate_count());
  EXPECT_EQ(m.multiplier_count(), reference.multiplier_count());
  EXPECT_EQ(m.pattern().nonzeros(), reference.pattern().nonzeros());
  const CableSection& a = m.cables()[0].section;
  const CableSection& b = reference.cables()[0].section;
  // E·πd²/4 etc.: the same formulas, so equal to round-off.
  EXPECT_NEAR(a.axial_stiffness, b.axial_stiffness, 1e-12 * b.axial_stiffness);
  EXPECT_NEAR(a.bending_stiffness, b.bending_stiffness, 1e-12 * b.bending_stiffness);
  EXPECT_NEAR(a.mass_per_length, b.mass_per_length, 1e-12 * b.mass_per_length);
  EXPECT_NEAR(a.radius, 0.005, 1e-15);
  EXPECT_EQ((m.constant_load() - reference.constant_load()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(s.integrator.kind, IntegratorKind::ida);
  ASSERT_EQ(s.output.probes.size(), 3u);
  EXPECT_EQ(s.output.probes[0].label, "tip");
  EXPECT_EQ(s.output.probes[0].node, 20);
}

TEST(SceneFiles, MechanismSceneBuildsEveryComponent) {
  const Scene s = load_scene((kSource / "test/scenes/valid/mechanism.toml").string());
  const Model& m = s.model;
  // Nodes 7 + 5 + 6 (polyline: 5 elements over 2 equal segments → 3 + 2), two bodies.
  EXPECT_EQ(m.coordinate_count(), 6 * 18 + 2 * 12);
  // 2×6 orthonormality, spherical 3, revolute 5, pins 3 + 3, frame attach 3, body attach 3 + 2,
  // clamp 3 + 2.
  EXPECT_EQ(m.multiplier_count(), 39);
  EXPECT_EQ(m.constraints().size(), 11u);
  EXPECT_GE(m.find_constraint("rotor_end.slope"), 0);
  EXPECT_GE(m.find_constraint("poly_end.slope"), 0);
  EXPECT_EQ(m.frames().size(), 1u);
  EXPECT_EQ(m.drives().size(), 1u);
  EXPECT_EQ(m.spring_dampers().size(), 1u);
  EXPECT_EQ(m.body_torques().size(), 1u);
  EXPECT_EQ(m.shapes().size(), 2u);
  EXPECT_EQ(m.contact_pair_count(), 3);
  EXPECT_EQ(s.names.contacts.at("helix_arc"), 2);  // cable–cable pairs are numbered last
  EXPECT_EQ(m.contact_pair_name(s.names.contacts.at("helix_knob")), "helix_knob");
  const CableShapeContactData& knob = m.cable_shape_contacts()[1];
  EXPECT_EQ(knob.first, 3);
  EXPECT_EQ(knob.count, 3);
  EXPECT_EQ(knob.samples, 4);
  EXPECT_DOUBLE_EQ(m.cable_shape_contacts()[0].law.friction, 0.05);
  // Helix rope: EA = E πd²/4 with d = 2 mm, ρA = 7800 πd²/4, no bending.
  const CableSection& helix = m.cables()[0].section;
  EXPECT_NEAR(helix.axial_stiffness, 1e11 * std::numbers::pi * 1e-6, 1e-6);
  EXPECT_EQ(helix.bending_stiffness, 0.0);
  EXPECT_NEAR(helix.radius, 0.001, 1e-15);
  // Arc rope starts curved over a straight reference of length 0.3 m: its nodes sit on the arc.
  const Index last = m.node_coordinate(1, -1);
  const Vec3 tip(m.initial_coordinates()[last], m.initial_coordinates()[last + 1],
                 m.initial_coordinates()[last + 2]);
  EXPECT_NEAR((tip - Vec3(0.3 * std::cos(1.0), 0.3 * std::sin(1.0), -1.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(m.cables()[1].elements[0].length, 0.3 / 4, 1e-15);
  EXPECT_EQ(m.cables()[1].section.strain, StrainMeasure::elastic_line);
  // Polyline: the corner node (index 3) has the bisector slope.
  const Index corner = m.node_coordinate(2, 3);
  EXPECT_NEAR(m.initial_coordinates()[corner + 3], std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(m.initial_coordinates()[corner + 4], std::sqrt(0.5), 1e-12);
  EXPECT_EQ(s.integrator.kind, IntegratorKind::genalpha);
  EXPECT_TRUE(s.integrator.stabilized_index2);
  ASSERT_EQ(s.output.probes.size(), 4u);
  EXPECT_EQ(s.output.probes[2].label, "knob");
  EXPECT_EQ(s.output.probes[3].node, 5);
}

TEST(SceneFiles, EveryStudySceneLoads) {
  const auto files = scenes_in(kSource / "studies/scenes");
  EXPECT_FALSE(files.empty());
  for (const fs::path& file : files) {
    SCOPED_TRACE(file.string());
    EXPECT_NO_THROW((void)load_scene(file.string()));
  }
}

TEST(SceneFiles, DocumentedExampleLoads) {
  // The "Complete example" of docs/scenes.md must stay a valid scene.
  std::ifstream in(kSource / "docs/scenes.md");
  std::string text, line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line == "```toml")
      inside = true;
    else if (inside && line == "```")
      break;
    else if (inside)
      text += line + "\n";
  }
  ASSERT_FALSE(text.empty());
  const Scene s = load_scene_from_string(text, "docs/scenes.md");
  EXPECT_EQ(s.model.contact_pair_count(), 1);
  EXPECT_EQ(s.model.drives().size(), 1u);
}

// docs/rod.md: a rod is exactly stress-free in any reference shape with its material frame. The
// element tests check that on element data; here the whole path from a scene: each geometry kind
// (straight and a non-planar polyline with a given frame normal, arc and helix with the derived
// frame) gives a model whose assembled residual at the reference (no loads, at rest) is zero to
// round-off and whose strain energy is zero. Bound: the element test's 64 ε EA per element, two
// elements per node.
TEST(SceneFiles, RodReferencesOfEveryGeometryAreStressFree) {
  const std::string section = R"(
[rod.section]
EA = 1.0e5
GJ = 0.7
EI2 = 1.0
EI3 = 1.4
mass_per_length = 0.2
radius = 0.01
)";
  const std::vector<std::pair<std::string, std::string>> rods = {
      {"straight",
       R"(geometry = { kind = "straight", start = [0.0, 0.0, 0.0], end = [0.4, 0.3, 0.2] }
frame = { normal = [0.0, 0.0, 1.0] })"},
      {"polyline",
       R"(geometry = { kind = "polyline", points = [[0.0, 0.0, 0.0], [0.3, 0.0, 0.0], [0.5, 0.2, 0.1], [0.6, 0.4, 0.35]] }
frame = { normal = [0.2, -0.3, 0.9] })"},
      {"arc",
       R"(geometry = { kind = "arc", centre = [0.0, 0.0, 0.0], u = [1.0, 0.0, 0.0], w = [0.0, 0.6, 0.8], radius = 0.25, angle = 2.5 })"},
      {"helix",
       R"(geometry = { kind = "helix", axis = [0.0, 0.0, 1.0], radius = 0.1, twist = 7.0, rise = 0.3 })"}};
  const double bound = 2.0 * 64.0 * std::numeric_limits<double>::epsilon() * 1.0e5;
  for (const auto& [kind, geometry] : rods) {
    SCOPED_TRACE(kind);
    const Scene s = load_scene_from_string(
        "[[rod]]\nname = \"r\"\nelements = 9\n" + geometry + "\n" + section, kind + ".toml");
    const Model& m = s.model;
    ASSERT_TRUE(m.has_rods());
    const SystemState state = SystemState::initial(m);
    Workspace ws(m);
    VecX residual(m.system_size());
    assemble_residual(m, state, 1.0, ws, as_span(residual));
    const double largest = residual.lpNorm<Eigen::Infinity>();
    const double energy = strain_energy(m, state.q, ws.rods);
    std::printf("%s reference: largest residual %.2e (bound %.2e), strain energy %.2e J\n",
                kind.c_str(), largest, bound, energy);
    EXPECT_LE(largest, bound);
    EXPECT_LE(std::abs(energy), 1e-20);
  }
}
