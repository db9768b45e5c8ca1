// Lesson 03 exercise: the winding number (oriented crossings).
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/winding.hpp.
#include "illum/geometry/winding.hpp"

#include "illum/geometry/orientation.hpp"

namespace illum {

// Task 1. +1 for an upward edge with q on its left, −1 for a downward edge
// with q on its right; the half-open rule of lesson 02, §4, for vertices on the
// test ray, and orient2d_sign_perturbed for the side.
int winding_number(std::span<const Vec2> loop, const Vec2& q) {
  throw NotImplemented("winding_number(loop)",
                       "upward edge and q left: +1; downward edge and q right: −1 (lesson 03, §3)");
}

// Task 2. The sum over the polygon's loops.
int winding_number(const Polygon& polygon, const Vec2& q) {
  throw NotImplemented("winding_number(Polygon)",
                       "add winding_number over polygon.loop_2d(l) (lesson 03, §3)");
}

// Task 3. The nonzero rule.
bool inside_nonzero(const Polygon& polygon, const Vec2& q) {
  throw NotImplemented("inside_nonzero", "inside when the winding number is not zero (lesson 03, §3)");
}

}  // namespace illum
