// Lesson 08 exercise: the slab test.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declaration and its contract are in lib/illum/accel/slab_test.hpp.
#include "illum/accel/slab_test.hpp"

#include <cmath>
#include <utility>

#include "illum/core/error.hpp"

namespace illum {

// Task 1. Clip `range` to the closed box, one slab (axis) at a time, with the
// products (lo[a] − P0[a])·inverse[a] and (hi[a] − P0[a])·inverse[a]. Where
// inverse[a] is not finite the ray is parallel to the slab: keep the range if
// lo[a] ≤ P0[a] ≤ hi[a], else return Interval::nothing(). Widen each slab's
// exit by far_slack·|exit|. An empty box (lo[a] > hi[a] on an axis, as the
// default Aabb{}) gives Interval::nothing().
Interval slab_clip(const SlabRay& ray, const Aabb& box, Interval range, double far_slack) {
  throw NotImplemented("slab_clip",
                       "intersect the ray's range with the three slab intervals; branch on a parallel axis "
                       "instead of computing 0·∞ (lesson 08, §2 \"the slab test\")");
}

}  // namespace illum
