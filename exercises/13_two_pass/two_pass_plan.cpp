// Lesson 13 exercise: the plan of two-pass global illumination.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/radiosity/two_pass_plan.hpp.
// contribution_threshold (1/1024) is in illum/trace/effects_plan.hpp.
#include "illum/radiosity/two_pass_plan.hpp"

#include <algorithm>
#include <cmath>

#include "illum/core/error.hpp"
#include "illum/trace/effects_plan.hpp"

namespace illum {

// Task 1. Decide the passes and the rays of pass two from the inventory.
TwoPassPlan plan_two_pass(const SceneInventory& scene, const TwoPassRequest& request) {
  throw NotImplemented(
      "plan_two_pass",
      "pass one needs an emitter and a facing pair (or the caustic pass); specular rays need a "
      "mirror or glass; shadow rays only for light that B does not hold (lesson 13, §2)");
}

}  // namespace illum
