// What progressive refinement shows on screen (lesson 11, §7). Provided code,
// not part of the exercise unit: it only combines the student's ambient_term
// with the current radiosities, so the stub need not repeat it.
#include "illum/radiosity/radiosity_solvers.hpp"

namespace illum {

std::vector<Color> display_radiosity(const std::vector<Patch>& patches, const ProgressiveState& state) {
  const Color ambient = ambient_term(patches, state.unshot);
  std::vector<Color> shown(state.radiosity.size());
  for (std::size_t i = 0; i < shown.size(); ++i)
    shown[i] = state.radiosity[i] + patches[i].reflectance * ambient;
  return shown;
}

}  // namespace illum
