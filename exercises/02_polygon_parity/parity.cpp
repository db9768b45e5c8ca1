// Lesson 02 exercise: point in polygon by crossing parity.
// Replace each `throw NotImplemented(...)` with your code. The tasks, hints
// and the tests that grade them are in README.md beside this file; the
// declarations and their contracts are in lib/illum/geometry/parity.hpp.
#include "illum/geometry/parity.hpp"

namespace illum {

// Task 3. Count the edges crossed by the test ray from q towards +u, with
// the half-open rule: an end with v == q.v counts as below; the side test is
// the determinant (hi − lo) × (q − lo) with the edge taken lower end first,
// and only a strictly positive value counts.
int count_crossings(std::span<const Vec2> loop, const Vec2& q) {
  throw NotImplemented(
      "count_crossings",
      "one end strictly above q.v, the other not; then q strictly left of the edge (lesson 02, §4)");
}

// Task 4. Sum the crossings over every loop (holes included); odd = inside.
bool inside_parity(const Polygon& polygon, const Vec2& q) {
  throw NotImplemented("inside_parity",
                       "add count_crossings over polygon.loop_2d(l) for every loop (lesson 02, §5)");
}

// Task 5. The plane hit, then parity on the projected hit point.
std::optional<PolygonHit> intersect(const Ray& ray, const Polygon& polygon) {
  throw NotImplemented(
      "intersect(Ray, Polygon)",
      "hit polygon.plane(), project the point with polygon.project, test parity (lesson 02, §6)");
}

}  // namespace illum
