// `ancf static` and `ancf modes` from scene files (test/scenes/statics, test/scenes/modes)
// against closed forms (REFERENCES §1, §3, §4), and reaction probes against statics worked out by
// hand. Run through the executable, as a user would; values read back from probes.csv and
// modes.csv (17 significant digits).
#include <gtest/gtest.h>

#include "ancf_command.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

using ancf::testing::kSource;

int run(const std::string& args) {
  return ancf::testing::run_ancf(args);
}

std::string text(const fs::path& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Rows of a CSV file as column name → values.
std::map<std::string, std::vector<double>> csv(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::vector<std::string> names;
  std::map<std::string, std::vector<double>> out;
  for (bool header = true; std::getline(in, line); header = false) {
    std::stringstream s(line);
    std::string cell;
    for (std::size_t k = 0; std::getline(s, cell, ','); ++k)
      if (header)
        names.push_back(cell);
      else
        out[names.at(k)].push_back(std::strtod(cell.c_str(), nullptr));
  }
  return out;
}

fs::path solve_static(const std::string& scene) {
  const fs::path out = fs::temp_directory_path() / ("ancf_static_" + scene);
  fs::remove_all(out);
  EXPECT_EQ(run("static " + (kSource / "test/scenes/statics" / (scene + ".toml")).string() +
                " --quiet --out " + out.string()),
            0);
  return out;
}

fs::path modes(const std::string& scene, const std::string& options) {
  const fs::path out = fs::temp_directory_path() / ("ancf_modes_" + scene);
  fs::remove_all(out);
  EXPECT_EQ(run("modes " + (kSource / "test/scenes/modes" / (scene + ".toml")).string() + " " +
                options + " --quiet --out " + out.string()),
            0);
  return out;
}

}  // namespace

// Mattiasson k = 2 (REFERENCES §1), 64 elements: the library's own test (test_statics_reference)
// puts every k within 1e-5 at 64 elements; here u/L and w/L within 1e-5 (measured 4.9e-7,
// 3.3e-7). The clamp's reaction balances the tip load: force (0, P, 0) and, by moment balance
// about the root node, mz = P x_tip. Both hold to the static residual (rigid-motion invariance of
// the element's internal forces), so 1e-9.
TEST(AncfStatic, MattiassonCantileverAndClampReaction) {
  const fs::path out = solve_static("mattiasson_k2");
  auto p = csv(out / "probes.csv");
  ASSERT_EQ(p["t"].size(), 1u);
  const double x = p["tip.x"][0], y = p["tip.y"][0];
  EXPECT_NEAR((1.0 - x) / 0.16064172, 1.0, 1e-5);
  EXPECT_NEAR(-y / 0.49345748, 1.0, 1e-5);
  EXPECT_NEAR(p["root.fx"][0], 0.0, 1e-9);
  EXPECT_NEAR(p["root.fy"][0], 2.0, 1e-9);
  EXPECT_NEAR(p["root.mz"][0], 2.0 * x, 1e-9);
  EXPECT_NEAR(p["root.mx"][0], 0.0, 1e-12);
  const std::string json = text(out / "run.json");
  EXPECT_NE(json.find("\"command\": \"static\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"status\": \"completed\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"Newton iterations\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"residual_norm\""), std::string::npos) << json;
  EXPECT_TRUE(fs::exists(out / "mattiasson_k2.pvd"));
  EXPECT_TRUE(fs::exists(out / "frames/frame_000000.vtp"));
}

// Elastic catenary (REFERENCES §3, EA = 1e3 N), 16 elements: sag and support tension within 1e-4
// (the bound of test_statics_reference at 16 elements; measured 1.3e-5 and 2.5e-6 in H). The pins
// carry the weight: fz left + right = ρA L₀ g and each = V = ρA L₀ g / 2 by symmetry, to the
// residual (1e-12 N); fx = ∓H.
TEST(AncfStatic, CatenaryAndPinReactionsCarryTheWeight) {
  const fs::path out = solve_static("catenary");
  auto p = csv(out / "probes.csv");
  const double weight = 0.1 * 1.0 * 9.81, h = 0.3313180182;
  EXPECT_NEAR(-p["middle.z"][0] / 0.2657655657, 1.0, 1e-4);
  EXPECT_NEAR(p["left.fz"][0] + p["right.fz"][0], weight, 1e-12);
  EXPECT_NEAR(p["left.fz"][0], weight / 2.0, 1e-12);
  EXPECT_NEAR(-p["left.fx"][0] / h, 1.0, 1e-4);
  EXPECT_NEAR(p["left.fx"][0] + p["right.fx"][0], 0.0, 1e-12);
  EXPECT_NEAR(std::hypot(p["left.fx"][0], p["left.fz"][0]) / 0.5919137430, 1.0, 1e-4);
  EXPECT_EQ(p["left.mx"][0], 0.0);  // a pin transmits no moment
}

// A plate on a hinge about z with 10 N along −z at (0.5, 0, 0): force (0, 0, 10) N and moment
// (0, −5, 0) N m about the hinge (the body origin), to round-off.
TEST(AncfStatic, HingeReactionOfAnOffsetLoad) {
  const fs::path out = solve_static("hinge_offset_load");
  auto p = csv(out / "probes.csv");
  EXPECT_NEAR(p["hinge.fx"][0], 0.0, 1e-12);
  EXPECT_NEAR(p["hinge.fy"][0], 0.0, 1e-12);
  EXPECT_NEAR(p["hinge.fz"][0], 10.0, 1e-12);
  EXPECT_NEAR(p["hinge.mx"][0], 0.0, 1e-12);
  EXPECT_NEAR(p["hinge.my"][0], -5.0, 1e-12);
  EXPECT_NEAR(p["hinge.mz"][0], 0.0, 1e-12);
}

// A rod turned into a two-turn helix by an inclined end moment (test/scenes/statics/
// rod_helix_moment.toml, 32 elements, 40 load steps): the probes and the energy are evaluated under
// the frame history the static solver committed (until 2026-12-06 under the reference frames:
// torque 89.35 N m, d₂ (0, −0.88, 0.48), energy 579 J). The twisting moment is the end moment's
// tangential part to round-off (moment balance); d₂ and the energy carry the 32-element
// discretisation (tip slope 5.8e-4 off, energy 8.1e-5:
// KirchhoffRodStatics.HelixByInclinedEndMoment, StaticSolutionIsEvaluatedUnderItsHistory).
TEST(AncfStatic, RodProbesAreEvaluatedUnderTheCommittedFrames) {
  const fs::path out = fs::temp_directory_path() / "ancf_static_rod_helix_moment";
  fs::remove_all(out);
  ASSERT_EQ(run("static " + (kSource / "test/scenes/statics/rod_helix_moment.toml").string() +
                " --load-steps 40 --quiet --out " + out.string()),
            0);
  auto p = csv(out / "probes.csv");
  EXPECT_NEAR(p["tipframe.torque"][0] / 88.857659, 1.0, 1e-12);
  EXPECT_NEAR(p["tipframe.d2x"][0], 0.0, 1e-3);
  EXPECT_NEAR(p["tipframe.d2y"][0], 1.0, 1e-3);
  EXPECT_NEAR(p["tipframe.d2z"][0], 0.0, 1e-3);
  const double exact_energy = 0.5 * std::pow(40.0 * std::numbers::pi, 2) * 10.0 / 100.0;
  EXPECT_NEAR(p["energy.strain"][0] / exact_energy, 1.0, 1e-3);
}

// Cantilever bending (REFERENCES §4), 8 elements: modes 1–3 within 1e-5, 1e-4, 1e-3 (h⁴
// convergence; measured 2.1e-6 for mode 1, as in test_modal_analysis), from above (Rayleigh–Ritz).
// The mode-shape series: one .pvd per mode with 24 frames.
TEST(AncfModes, CantileverBendingFrequencies) {
  const fs::path out = modes("cantilever", "--component y --count 3");
  auto m = csv(out / "modes.csv");
  ASSERT_EQ(m["omega"].size(), 3u);
  const double beta[] = {1.8751040687, 4.6940911330, 7.8547574382}, bound[] = {1e-5, 1e-4, 1e-3};
  for (int k = 0; k < 3; ++k) {
    const double exact = beta[k] * beta[k];
    EXPECT_GT(m["omega"][k], exact);
    EXPECT_LT(m["omega"][k] / exact - 1.0, bound[k]) << "mode " << k + 1;
    EXPECT_NEAR(m["frequency"][k], m["omega"][k] / (2.0 * std::numbers::pi), 1e-12 * exact);
  }
  EXPECT_TRUE(fs::exists(out / "modes/mode_003.pvd"));
  EXPECT_TRUE(fs::exists(out / "modes/mode_001/frame_023.vtp"));
  EXPECT_FALSE(fs::exists(out / "modes/mode_001/frame_024.vtp"));
  EXPECT_NE(text(out / "run.json").find("\"constraint_rank\": 2"), std::string::npos);
}

// Free–free beam (REFERENCES §4), no constraints, 16 elements: two rigid modes at ω² ≈ 0, then
// β₁L, β₂L within 1e-5 and 1e-4 (as test_modal_analysis; measured 5.2e-6, 3.9e-5).
TEST(AncfModes, FreeFreeBendingFrequencies) {
  const fs::path out = modes("free_free", "--component y --count 4 --no-vtk");
  auto m = csv(out / "modes.csv");
  ASSERT_EQ(m["omega_squared"].size(), 4u);
  EXPECT_LT(std::abs(m["omega_squared"][0]), 1e-9 * m["omega_squared"][2]);
  EXPECT_LT(std::abs(m["omega_squared"][1]), 1e-9 * m["omega_squared"][2]);
  const double beta[] = {4.730040744862704, 7.853204624095838};
  EXPECT_NEAR(m["omega"][2] / (beta[0] * beta[0]), 1.0, 1e-5);
  EXPECT_NEAR(m["omega"][3] / (beta[1] * beta[1]), 1.0, 1e-4);
  EXPECT_FALSE(fs::exists(out / "modes"));
}

// Taut string (REFERENCES §4), T = 100 N, 16 elements: modes 1–3 within 1e-6 (h⁶; measured
// 9.3e-10, 5.7e-8, 6.1e-7). About the static equilibrium (--static; the initial state is one, so
// the solve stays there) the same frequencies to 1e-9.
TEST(AncfModes, TautStringFrequenciesAboutInitialAndStaticState) {
  const fs::path initial = modes("taut_string", "--component y --count 3 --no-vtk");
  auto a = csv(initial / "modes.csv");
  ASSERT_EQ(a["omega"].size(), 3u);
  for (int n = 1; n <= 3; ++n)
    EXPECT_NEAR(a["omega"][n - 1] / (n * std::numbers::pi * std::sqrt(100.0 / 0.1)), 1.0, 1e-6);
  const fs::path about_static = modes("taut_string", "--static --component y --count 3 --no-vtk");
  auto b = csv(about_static / "modes.csv");
  ASSERT_EQ(b["omega"].size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(b["omega"][k] / a["omega"][k], 1.0, 1e-9);
  EXPECT_NE(text(about_static / "run.json").find("\"about\": \"static\""), std::string::npos);
}

// A loaded scene is not in equilibrium initially: `modes` without --static fails (exit 2, the
// reason in run.json), with --static it runs.
TEST(AncfModes, LoadedSceneNeedsTheStaticOption) {
  const fs::path out = fs::temp_directory_path() / "ancf_modes_loaded";
  fs::remove_all(out);
  const std::string scene = (kSource / "test/scenes/statics/catenary.toml").string();
  EXPECT_EQ(run("modes " + scene + " --no-vtk --out " + out.string()), 2);
  EXPECT_NE(text(out / "run.json").find("--static"), std::string::npos);
  EXPECT_EQ(run("modes " + scene + " --static --count 2 --no-vtk --out " + out.string()), 0);
  EXPECT_EQ(csv(out / "modes.csv")["omega"].size(), 2u);
}

// Reaction probes in `ancf run`: the hinge scene stays at rest, so each integrator's multipliers
// give the static reaction to its Newton tolerance on λ (generalized-α atol 1e-6 N; IDA rtol 1e-6).
TEST(AncfRun, HingeReactionProbeDuringARun) {
  for (const std::string integrator : {"ida", "genalpha"}) {
    const fs::path out = fs::temp_directory_path() / ("ancf_run_reaction_" + integrator);
    fs::remove_all(out);
    ASSERT_EQ(run("run " + (kSource / "test/scenes/statics/hinge_offset_load.toml").string() +
                  " --integrator " + integrator + " --t-end 0.02 --quiet --out " + out.string()),
              0);
    auto p = csv(out / "probes.csv");
    ASSERT_GE(p["t"].size(), 2u);
    EXPECT_NEAR(p["hinge.fz"].back(), 10.0, 1e-6) << integrator;
    EXPECT_NEAR(p["hinge.my"].back(), -5.0, 1e-6) << integrator;
  }
}
