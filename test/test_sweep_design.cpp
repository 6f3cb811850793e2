// Sweep files → cases (sweep_design.hpp): grid order and count, list pairing, the value
// template and scale, seeded random reproducibility, Latin-hypercube stratification, and
// located errors for bad sweep files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "ancf/io/scene.hpp"
#include "ancf/io/scene_error.hpp"
#include "ancf/io/sweep_design.hpp"

namespace fs = std::filesystem;
using namespace ancf;

namespace {

const fs::path kSweeps = fs::path(ANCF_SOURCE_DIR) / "test" / "scenes" / "sweep";

/// A sweep file next to the tiny scene (scene paths are relative to the sweep file).
std::string write_sweep(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / "ancf_sweep_design";
  fs::create_directories(dir);
  fs::copy_file(kSweeps / "tiny_pendulum.toml", dir / "tiny_pendulum.toml",
                fs::copy_options::overwrite_existing);
  const fs::path file = dir / name;
  std::ofstream(file) << text;
  return file.string();
}

const std::string kHead = "[sweep]\nscene = \"tiny_pendulum.toml\"\n";

}  // namespace

TEST(SweepDesign, GridIsNestedLoopsLastParameterFastest) {
  const SweepSpec s = load_sweep((kSweeps / "grid.toml").string());
  ASSERT_EQ(s.cases.size(), 6u);
  EXPECT_EQ(s.cases[1].shown, (std::vector<std::string>{"-9.81", "1"}));
  EXPECT_EQ(s.cases[3].shown, (std::vector<std::string>{"-5", "0.5"}));
  // Value template and scale: g into the gravity vector, E in GPa to Pa (a TOML float).
  ASSERT_EQ(s.cases[3].overrides.size(), 2u);
  EXPECT_EQ(s.cases[3].overrides[0].key, "scene.gravity");
  EXPECT_EQ(s.cases[3].overrides[0].value, "[0.0, 0.0, -5.0]");
  EXPECT_EQ(s.cases[3].overrides[1].value, "500000000.0");
}

TEST(SweepDesign, ListPairsValuesAndTextValuesAreInsertedAsWritten) {
  const SweepSpec s = load_sweep((kSweeps / "failing.toml").string());
  ASSERT_EQ(s.cases.size(), 6u);  // good, error, timeout, crash, solver failure, good
  EXPECT_EQ(s.cases[2].shown, (std::vector<std::string>{"1", "10000", "too long", "\"fixed\""}));
  // The sweep-wide `set` entries come first (three), then one override per parameter.
  ASSERT_EQ(s.cases[3].overrides.size(), 7u);
  EXPECT_EQ(s.cases[3].overrides[2].value, "2e-3");
  EXPECT_EQ(s.cases[3].overrides[5].value, "\"crash me\"");
  EXPECT_EQ(s.time_limit, 1.5);
}

TEST(SweepDesign, LatinHypercubeHasOneSampleInEveryStratumAndIsSeeded) {
  const std::string text =
      kHead +
      "design = \"lhs\"\nsamples = 10\nseed = 3\n"
      "[[parameter]]\nname = \"a\"\nkeys = [\"integrator.t_end\"]\nmin = 1.0\nmax = 2.0\n"
      "[[parameter]]\nname = \"b\"\nkeys = [\"cable[0].section.E\"]\nmin = -5.0\nmax = 5.0\n";
  const SweepSpec s = load_sweep(write_sweep("lhs.toml", text));
  ASSERT_EQ(s.cases.size(), 10u);
  for (std::size_t p = 0; p < 2; ++p) {
    const double lo = p == 0 ? 1.0 : -5.0, width = p == 0 ? 1.0 : 10.0;
    std::set<int> strata;
    for (const SweepCase& c : s.cases) {
      const double u = (std::stod(c.shown[p]) - lo) / width;
      ASSERT_GE(u, 0.0);
      ASSERT_LT(u, 1.0);
      strata.insert(static_cast<int>(u * 10.0));
    }
    EXPECT_EQ(strata.size(), 10u) << "parameter " << p;
  }
  // The same seed gives the same cases; another seed others.
  EXPECT_EQ(load_sweep(write_sweep("lhs.toml", text)).cases[4].shown, s.cases[4].shown);
  std::string other = text;
  other.replace(other.find("seed = 3"), 8, "seed = 4");
  EXPECT_NE(load_sweep(write_sweep("lhs4.toml", other)).cases[4].shown, s.cases[4].shown);
}

TEST(SweepDesign, RandomStaysInItsRange) {
  const std::string text =
      kHead +
      "design = \"random\"\nsamples = 50\n"
      "[[parameter]]\nname = \"a\"\nkeys = [\"integrator.t_end\"]\nmin = 0.1\nmax = 0.2\n";
  const SweepSpec s = load_sweep(write_sweep("random.toml", text));
  ASSERT_EQ(s.cases.size(), 50u);
  double lo = 1.0, hi = 0.0;
  for (const SweepCase& c : s.cases)
    lo = std::min(lo, std::stod(c.shown[0])), hi = std::max(hi, std::stod(c.shown[0]));
  EXPECT_GE(lo, 0.1);
  EXPECT_LT(hi, 0.2);
  EXPECT_GT(hi - lo, 0.05);  // 50 uniform samples span more than half the range (p ≈ 1 − 1e-13)
}

TEST(SweepDesign, BadFilesAreLocatedErrors) {
  const auto error_of = [](const std::string& name, const std::string& text) {
    try {
      (void)load_sweep(write_sweep(name, text));
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      error_of("unknown.toml",
               kHead + "colour = 1\n[[parameter]]\nname = \"a\"\nkeys = [\"x\"]\nvalues = [1]\n")
          .find("colour"),
      std::string::npos);
  EXPECT_NE(
      error_of("unequal.toml",
               kHead +
                   "design = \"list\"\n[[parameter]]\nname = \"a\"\nkeys = [\"x\"]\n"
                   "values = [1, 2]\n[[parameter]]\nname = \"b\"\nkeys = [\"y\"]\nvalues = [1]\n")
          .find("has 1 values"),
      std::string::npos);
  EXPECT_NE(error_of("none.toml", kHead).find("[[parameter]]"), std::string::npos);
  EXPECT_NE(
      error_of("range.toml", kHead + "design = \"lhs\"\nsamples = 3\n[[parameter]]\nname = \"a\"\n"
                                     "keys = [\"x\"]\nmin = 2.0\nmax = 1.0\n")
          .find("max > min"),
      std::string::npos);
}

// The capture envelope for rod ropes (studies/sweeps/capture_envelope_rod.toml) addresses
// studies/scenes/capture_rod.toml: every case builds, with the ropes as rods clamped into both
// rings including twist (three twist rows tied to the ring).
TEST(SweepDesign, CaptureEnvelopeRodCasesBuild) {
  const SweepSpec spec = load_sweep(
      (fs::path(ANCF_SOURCE_DIR) / "studies" / "sweeps" / "capture_envelope_rod.toml").string());
  ASSERT_EQ(spec.cases.size(), 18u);
  const std::string base = read_scene_text(spec.scene);
  for (const SweepCase& c : spec.cases) {
    const Scene scene = load_scene_from_string(base, spec.scene, c.overrides);
    EXPECT_EQ(scene.model.cables().size(), 3u);
    for (const CableData& rope : scene.model.cables()) EXPECT_TRUE(rope.rod.has_value());
    EXPECT_EQ(scene.model.twist_rows().size(), 3u);
  }
}
