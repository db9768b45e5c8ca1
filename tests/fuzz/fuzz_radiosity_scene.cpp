// Fuzz target: the loader of radiosity scenes (lessons 09–11, --scene).
// Any bytes give either a meshed scene whose patches are valid or an
// illum::InputError; never a crash, a hang, another exception (a
// std::invalid_argument from meshing would mean the loader let through a
// polygon a later step refuses) or undefined behaviour.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "illum/core/error.hpp"
#include "illum/io/scene_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    // A coarse meshing (Cornell box: one patch per wall) keeps each run short; the
    // count limit still applies to walls far larger than the scene's.
    const illum::RadiosityScene scene = illum::parse_radiosity_scene(text, "fuzz.json", 1000.0);
    for (const illum::Patch& p : scene.patches)
      if (!(p.area > 0 && std::isfinite(p.area))) std::abort();  // the loader let a degenerate patch through
  } catch (const illum::InputError&) {
    // the expected refusal
  }
  return 0;
}
