// Exercise unit of lesson 03 (exercises/03_orientation_convex/convex.cpp is its stub).
#include "illum/geometry/convex.hpp"

#include <stdexcept>

#include "illum/geometry/orientation.hpp"

namespace illum {

namespace {

// The number of sign changes, cyclically, in the non-zero values of `sign(i)`.
template <class Sign>
int cyclic_sign_changes(std::size_t n, Sign sign) {
  int first = 0, previous = 0, changes = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int s = sign(i);
    if (s == 0) continue;
    if (first == 0) first = s;
    if (previous != 0 && s != previous) ++changes;
    previous = s;
  }
  if (previous != 0 && previous != first) ++changes;  // close the loop
  return changes;
}

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

// The common turn direction of a convex loop, or 0 when it is not convex.
int convex_orientation(std::span<const Vec2> loop) {
  const std::size_t n = loop.size();
  int turn = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& a = loop[(i + n - 1) % n];
    const Vec2& b = loop[i];
    const Vec2& c = loop[(i + 1) % n];
    const int s = orient2d_sign(a, b, c);
    if (s == 0) {
      if (dot(b - a, c - b) < 0.0) return 0;  // a U-turn: the loop folds back on itself
      continue;                               // straight on: a vertex in the middle of an edge
    }
    if (turn == 0) turn = s;
    if (s != turn) return 0;  // turns both ways: concave
  }
  // Going round once: each edge-direction component changes sign at most twice.
  const auto du = [&](std::size_t i) { return sign_of(loop[(i + 1) % n].x - loop[i].x); };
  const auto dv = [&](std::size_t i) { return sign_of(loop[(i + 1) % n].y - loop[i].y); };
  if (cyclic_sign_changes(n, du) > 2 || cyclic_sign_changes(n, dv) > 2) return 0;
  return turn;
}

}  // namespace

bool is_convex(const Polygon& polygon) {
  return polygon.loop_count() == 1 && convex_orientation(polygon.loop_2d(0)) != 0;
}

ConvexPolygon::ConvexPolygon(Polygon polygon) : polygon_(std::move(polygon)) {
  if (polygon_.loop_count() != 1)
    throw std::invalid_argument("ConvexPolygon: a polygon with holes is not convex");
  orientation_ = convex_orientation(polygon_.loop_2d(0));
  if (orientation_ == 0)
    throw std::invalid_argument(
        "ConvexPolygon: the polygon is not convex (it turns both ways, folds back, or winds more than once)");
}

bool inside_convex(const ConvexPolygon& convex, const Vec2& q) {
  const std::span<const Vec2> loop = convex.polygon().loop_2d(0);
  const std::size_t n = loop.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    // Inside means on the same side of every edge as the polygon turns.
    if (orient2d_sign_perturbed(loop[j], loop[i], q) != convex.orientation()) return false;
  }
  return true;
}

}  // namespace illum
