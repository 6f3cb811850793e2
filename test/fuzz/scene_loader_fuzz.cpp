// libFuzzer target for the scene loader (docs/fuzzing.md): any byte string is parsed as a scene
// file. The loader's contract (scene.hpp) is that bad input raises SceneError; every other
// exception, a crash, a leak or a sanitizer report is a finding. The memory bound of the loader is
// lowered so that a large `elements` value is refused instead of building a mesh that would make
// the fuzzer report an out-of-memory or a timeout that says nothing about the loader.
#include <cstddef>
#include <cstdint>
#include <string>

#include "ancf/io/run_limits.hpp"
#include "ancf/io/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // 64 MB: 2 700 cable elements at kRunBytesPerCableElement, enough for every feature.
  const ancf::SceneLimits limits{.memory_bytes = 64e6};
  ancf::Scene scene;
  try {
    scene = ancf::load_scene_from_string(text, "fuzz.toml", limits);
  } catch (const ancf::SceneError&) {
    return 0;  // the documented outcome for bad input; any other exception escapes: a finding
  }
  try {
    // What `ancf check` does next with a loaded scene: the step-count bound.
    ancf::require_bounded_steps(scene.integrator, scene.output.interval, ancf::kDefaultMaxSteps);
  } catch (const ancf::ModelError&) {
    // Its refusal (not located in the file, so a ModelError).
  }
  return 0;
}
