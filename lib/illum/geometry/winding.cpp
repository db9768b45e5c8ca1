// Exercise unit of lesson 03 (exercises/03_orientation_convex/winding.cpp is its stub).
#include "illum/geometry/winding.hpp"

#include "illum/geometry/orientation.hpp"

namespace illum {

int winding_number(std::span<const Vec2> loop, const Vec2& q) {
  int winding = 0;
  const std::size_t n = loop.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = loop[j];
    const Vec2& b = loop[i];
    // The half-open rule of lesson 02: a vertex on the test ray counts as below.
    const bool a_above = a.y > q.y;
    const bool b_above = b.y > q.y;
    if (!a_above && b_above) {
      // Upward edge: crossed by the ray to +u when q is left of a→b.
      if (orient2d_sign_perturbed(a, b, q) > 0) ++winding;
    } else if (a_above && !b_above) {
      // Downward edge: crossed when q is right of a→b (left of b→a).
      if (orient2d_sign_perturbed(a, b, q) < 0) --winding;
    }
  }
  return winding;
}

int winding_number(const Polygon& polygon, const Vec2& q) {
  int winding = 0;
  for (std::size_t l = 0; l < polygon.loop_count(); ++l) winding += winding_number(polygon.loop_2d(l), q);
  return winding;
}

bool inside_nonzero(const Polygon& polygon, const Vec2& q) { return winding_number(polygon, q) != 0; }

}  // namespace illum
