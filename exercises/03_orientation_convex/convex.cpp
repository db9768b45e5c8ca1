// Lesson 03 exercise: convexity check and the convex containment test.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/convex.hpp.
#include "illum/geometry/convex.hpp"

#include <stdexcept>

#include "illum/geometry/orientation.hpp"

namespace illum {

// Task 4. One loop; every turn orient2d_sign(prev, this, next) the same way
// (zero allowed for a straight vertex, but not a U-turn); the edges' u and v
// components change sign at most twice each going round (cyclically, zero
// components skipped).
bool is_convex(const Polygon& polygon) {
  throw NotImplemented("is_convex",
                       "same turn sign at every vertex, and one revolution only (lesson 03, §4)");
}

// Task 5. Refuse polygons with holes and non-convex ones with
// std::invalid_argument; remember the turn direction (+1 or −1).
ConvexPolygon::ConvexPolygon(Polygon polygon) : polygon_(std::move(polygon)) {
  throw NotImplemented(
      "ConvexPolygon::ConvexPolygon",
      "check convexity, throw std::invalid_argument if it fails, store the orientation (lesson 03, §4)");
}

// Task 6. Inside when orient2d_sign_perturbed(edge start, edge end, q) equals
// the polygon's orientation for every edge; stop at the first that does not.
bool inside_convex(const ConvexPolygon& convex, const Vec2& q) {
  throw NotImplemented("inside_convex", "one orientation sign per edge, early exit (lesson 03, eq. 3.3)");
}

}  // namespace illum
