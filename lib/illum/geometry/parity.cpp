// Exercise unit of lesson 02 (exercises/02_polygon_parity/parity.cpp is its stub).
#include "illum/geometry/parity.hpp"

namespace illum {

int count_crossings(std::span<const Vec2> loop, const Vec2& q) {
  int crossings = 0;
  const std::size_t n = loop.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = loop[j];
    const Vec2& b = loop[i];
    // Half-open in v: a vertex on the test ray counts as below it.
    const bool a_above = a.y > q.y;
    const bool b_above = b.y > q.y;
    if (a_above == b_above) continue;  // both ends on one side: no crossing
    // The edge lower end first, so that every polygon sharing it computes
    // the same determinant and the same decision.
    const Vec2& lo = a_above ? b : a;
    const Vec2& hi = a_above ? a : b;
    const double side = (hi.x - lo.x) * (q.y - lo.y) - (hi.y - lo.y) * (q.x - lo.x);
    if (side > 0.0) ++crossings;  // q strictly left of the upward edge: the ray to +u crosses it
  }
  return crossings;
}

bool inside_parity(const Polygon& polygon, const Vec2& q) {
  int crossings = 0;
  for (std::size_t l = 0; l < polygon.loop_count(); ++l) crossings += count_crossings(polygon.loop_2d(l), q);
  return (crossings & 1) != 0;
}

std::optional<PolygonHit> intersect(const Ray& ray, const Polygon& polygon) {
  const std::optional<double> s = intersect(ray, polygon.plane());
  if (!s) return std::nullopt;
  const Point3 p = ray.at(*s);
  const Vec2 q = polygon.project(p);
  // The bounding rectangle rejects most misses before the O(n) parity loop.
  if (q.x < polygon.min_2d().x || q.y < polygon.min_2d().y || q.x > polygon.max_2d().x ||
      q.y > polygon.max_2d().y)
    return std::nullopt;
  if (!inside_parity(polygon, q)) return std::nullopt;
  return PolygonHit{*s, p, polygon.plane().normal};
}

}  // namespace illum
